"""Torsion and axial rods against the frequency equations (4.51)-(4.56) and §2.2.

Tolerances follow the leading discretisation-error terms of consistent-mass Lagrange
elements for the wave equation: relative frequency error (sigma h)^2 / 24 for P1 and
(sigma h)^4 / 1440 for P2 (sigma = mode wavenumber, h = element length); the cases allow
twice that (plus 1e-10 for rounding).  The convergence case measures the orders.
"""
from __future__ import annotations


import numpy as np

from fem import assemble, modal_analysis
from fem.modelfile.source import read_toml
from fem.study import Study
from validation.analytic.torsion import (end_disc_roots, reduced_inertia_omega, stepped_fixed_free_omegas,
                                         torsion_omegas, torsion_roots)
from validation.builders import STEEL, uniform
from validation.registry import case, check, claim
from validation.examples import EXAMPLES

L, D, N = 1.2, 0.05, 24
EXAMPLE_DISC = EXAMPLES / "torsion_shaft_disc.toml"
SRC = "seed 001 §4.10 (4.55)-(4.56)"


def _props(model):
    seg = model.segments[0]
    if model.physics == "torsion":
        return seg.material.G * seg.section.J, seg.material.rho * seg.section.Ip + seg.rho_extra
    return seg.material.E * seg.section.A, seg.material.rho * seg.section.A + seg.rho_extra


def _tol(sigma_h: np.ndarray, order: int) -> np.ndarray:
    lead = sigma_h**2 / 24 if order == 1 else sigma_h**4 / 1440
    return 2 * lead + 1e-10


def _compare(name, physics, bc, supports, n_modes=4, order=2, elements=N, rho_extra=0.0):
    model = uniform(physics, L, elements, d=D, supports=supports, order=order, rho_extra=rho_extra)
    res = modal_analysis(assemble(model).system, n_modes + (bc == "free-free"))
    stiff, inert = _props(model)
    exact = torsion_omegas(stiff, inert, L, bc, n_modes)
    got = res.omega_rad_s[1:] if bc == "free-free" else res.omega_rad_s
    tol = _tol(torsion_roots(bc, n_modes) * (L / elements) / L, order)
    checks = [check(name, SRC, f"omega_{r + 1} [rad/s] ({physics}, {bc}, P{order}, {elements} el.)",
                    exact[r], got[r], tol[r]) for r in range(n_modes)]
    if bc == "free-free":
        checks.append(claim(name, SRC, "exactly one rigid-body (zero-frequency) mode", res.rigid_body_modes == 1
                            and res.omega_rad_s[0] == 0.0, note=f"rigid modes found: {res.rigid_body_modes}"))
    return checks


@case("torsion-fixed-free", group="fe-torsion")
def torsion_fixed_free():
    """Shaft clamped at x = 0, free at L: k_r = (2r-1) pi/2 sqrt(G I_p/(J L)) (4.56); P2, 24 elements."""
    return _compare("torsion-fixed-free", "torsion", "fixed-free", [(0.0, "clamped")])


@case("torsion-fixed-fixed", group="fe-torsion")
def torsion_fixed_fixed():
    """Both ends clamped: sigma_r L = r pi; P2, 24 elements."""
    return _compare("torsion-fixed-fixed", "torsion", "fixed-fixed", [(0.0, "clamped"), (L, "clamped")])


@case("torsion-free-free", group="fe-torsion")
def torsion_free_free():
    """Free-free shaft: one zero frequency (rigid rotation), then sigma_r L = r pi."""
    return _compare("torsion-free-free", "torsion", "free-free", [])


@case("torsion-extra-inertia", group="fe-torsion")
def torsion_extra_inertia():
    """(4.56) with J including attached parts: distributed extra inertia rho_extra equal to the
    shaft's own rho I_p halves k_r^2; P1 element, 48 elements."""
    model = uniform("torsion", L, 1, d=D)
    extra = STEEL.rho * model.segments[0].section.Ip
    return _compare("torsion-extra-inertia", "torsion", "fixed-free", [(0.0, "clamped")], order=1,
                    elements=48, rho_extra=extra)


@case("axial-fixed-free", group="fe-torsion")
def axial_fixed_free():
    """Axial rod, same equation with E A and rho A: omega_r = (2r-1) pi/(2L) sqrt(E/rho)."""
    return _compare("axial-fixed-free", "axial", "fixed-free", [(0.0, "clamped")])


@case("torsion-end-disc", group="fe-torsion")
def torsion_end_disc():
    """Shaft clamped at 0 with a disc J2 at L: sigma L tan(sigma L) = J_shaft/J_disc (digest V2.2b).
    Also the book's reduced-inertia estimate k = sqrt(c/(J2 + J1/3)) (§2.2) and its error
    against the exact root, compared with the digest's table (+0.21 %, +0.66 %, +1.72 % for
    J1/J2 = 0.5, 1, 2; printed to 2 digits -> tolerance 0.005 percentage points).  The model is
    examples/torsion_shaft_disc.toml (steel, L = 1.2 m, d = 50 mm, 24 P2 elements) with the disc
    inertia of each ratio."""
    out = []
    model0 = uniform("torsion", L, 1, d=D)
    stiff, inert = _props(model0)
    J_shaft = inert * L
    for ratio, book_err in ((0.5, 0.21), (1.0, 0.66), (2.0, 1.72)):
        J_disc = J_shaft / ratio
        doc = read_toml(EXAMPLE_DISC)
        doc["point"][0]["inertia"] = J_disc
        model = Study.parse(doc).shaft
        res = modal_analysis(assemble(model).system, 3)
        roots = end_disc_roots(ratio, 3)
        exact = roots * np.sqrt(stiff / L / J_shaft)
        tol = _tol(roots / L * (L / N), 2)
        for r in range(3):
            out.append(check("torsion-end-disc", "digest V2.2b (x tan x = J1/J2)",
                             f"omega_{r + 1}, J1/J2 = {ratio}", exact[r], res.omega_rad_s[r], tol[r]))
        est = reduced_inertia_omega(stiff / L, J_shaft, J_disc)
        err_pct = 100 * (est / exact[0] - 1)
        out.append(check("torsion-end-disc", "seed 001 §2.2 J_B = J1/3 + J2", f"estimate error [%], J1/J2 = {ratio}",
                         book_err, err_pct, 0.005 / book_err, note=f"estimate {est:.6g} vs exact {exact[0]:.6g} rad/s"))
    return out


@case("torsion-lumped-chain", group="fe-torsion")
def torsion_lumped_chain():
    """Lumped-mass P1 = the chain of digest V4.10b (segment stiffness N GIp/L, inertia J/N,
    half at the ends): GIp/L = 1, J = 1, N = 5 -> 1.56434, 4.53991, 7.07107; N = 20 ->
    1.57039, 4.70150, 7.80361 (printed to 6 significant digits -> tolerance 5e-6)."""
    from validation.builders import unit_section
    from fem import Segment, ShaftModel, Support

    mat, sec = unit_section()
    out = []
    for n, ref in ((5, (1.56434, 4.53991, 7.07107)), (20, (1.57039, 4.70150, 7.80361))):
        model = ShaftModel("torsion", [Segment(1.0, n, sec, mat)], supports=[Support(0.0)], order=1, mass="lumped")
        res = modal_analysis(assemble(model).system, 3)
        out += [check("torsion-lumped-chain", "digest V4.10b", f"k_{r + 1}, N = {n}", ref[r], res.omega_rad_s[r], 5e-6)
                for r in range(3)]
    out.append(claim("torsion-lumped-chain", "digest V4.10b", "lumped mass converges from below",
                     bool(res.omega_rad_s[0] < np.pi / 2)))
    return out


@case("torsion-convergence", group="fe-torsion")
def torsion_convergence():
    """Observed order of the first-frequency error on h, h/2, h/4, h/8 (4..32 elements):
    P1 ~ h^2, P2 ~ h^4 (tolerance 0.15 on the fitted exponent: the next term of the error
    expansion shifts the slope by O((sigma h)^2))."""
    out = []
    for order, expected in ((1, 2.0), (2, 4.0)):
        errs, hs = [], []
        for n in (4, 8, 16, 32):
            model = uniform("torsion", L, n, d=D, supports=[(0.0, "clamped")], order=order)
            res = modal_analysis(assemble(model).system, 2)
            stiff, inert = _props(model)
            exact = torsion_omegas(stiff, inert, L, "fixed-free", 2)
            errs.append(abs(res.omega_rad_s[1] / exact[1] - 1))
            hs.append(L / n)
        slope = np.polyfit(np.log(hs), np.log(errs), 1)[0]
        out.append(check("torsion-convergence", "FE theory", f"order of omega_2 error, P{order}", expected, slope,
                         0.15 / expected, note=f"errors {['%.2e' % e for e in errs]}"))
    return out


@case("torsion-stepped-shaft", group="fe-torsion")
def torsion_stepped_shaft():
    """Stepped shaft (solid d = 60 mm, tube 80/50 mm, solid d = 40 mm; per-segment material
    override on the last) clamped-free: roots of the transfer relation with angle and torque
    continuous at the steps (independent of the FE), P2 with 12 elements per segment
    (tolerance (sigma_max h)^4 / 720 for the most demanding segment)."""
    from fem import Material, Section, Segment, ShaftModel, Support

    alu = Material(E=7.0e10, G=2.6e10, rho=2700.0)
    segs = [Segment(0.4, 12, Section.circle(0.06), STEEL),
            Segment(0.6, 12, Section.tube(0.08, 0.05), STEEL),
            Segment(0.3, 12, Section.circle(0.04), alu)]
    model = ShaftModel("torsion", segs, supports=[Support(0.0)], order=2)
    res = modal_analysis(assemble(model).system, 4)
    data = [(s.length, s.material.G * s.section.J, s.material.rho * s.section.Ip) for s in segs]
    exact = stepped_fixed_free_omegas(data, 4)
    sig_h = max(np.sqrt(i / k) * (L / 12) for L, k, i in data) * exact
    return [check("torsion-stepped-shaft", "(4.54) with step continuity", f"omega_{r + 1} [rad/s]", exact[r],
                  res.omega_rad_s[r], sig_h[r] ** 4 / 720 + 1e-10) for r in range(4)]
