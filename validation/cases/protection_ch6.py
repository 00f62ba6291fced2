"""Vibration protection (textbook ch. 6 §6.4-6.7; digest textbook_ch6-9.md V6.4-V6.7, textbook_ch2-5.md V5.12).

The design helpers of discrete.protection are checked against the book's (or the digest's) printed numbers
at half a printed digit AND against an independent computation: the assembled LumpedModel solved by
discrete.linear.harmonic / modal with forces from discrete.linear.reactions, root finding on the full
(damped) transmissibility, dense complex solves in validation/analytic/protection_refs.py.
Misprints followed in their corrected form: "в резонансном режиме" (6.17) means post-resonant;
"xi_1 < xi_1" before (6.25) means xi_1 < xi_1*; first line of (6.37) needs Pi_max^2 c_0; the maximum
of (6.44) with detuning is z_2^2 = (1 - theta^2)/(1 - theta^2 + 4 delta^2).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from discrete.linear.harmonic import harmonic_response
from discrete.linear.modal import modal_analysis
from discrete.linear.reactions import element_forces, lumped_links, reactions_from_result
from discrete.lumped import Body, Driver, Link, LumpedModel
from discrete.motion import dwell_rise_dwell_return
from discrete.protection import (Absorber, MovingMassIsolation, QuasiConstantPlatform, damped_stiffness_limit,
                                 force_transmissibility, harmonic_unloading, isolation_design, kappa, kappa_extrema,
                                 unbalance_response, unloading_spring)
from validation.analytic import protection_refs as ref
from validation.registry import case, check, claim, printed

SRC = "seed 001 ch. 6 (digest textbook_ch6-9.md)"


def _sdof(m: float, c: float, b: float = 0.0):
    mdl = LumpedModel(bodies=[Body("machine", m)], springs=[Link(("ground", "machine"), c)],
                      dampers=[Link(("ground", "machine"), b)] if b > 0 else [])
    return mdl, mdl.linear_system()


def _transmitted(m: float, c: float, b: float, omega: float) -> float:
    """|force on the foundation| / F_0 of the assembled 1-DOF model (harmonic_response + element forces)."""
    mdl, ls = _sdof(m, c, b)
    r = harmonic_response(ls, [omega], force=np.array([1.0]))
    return float(abs(element_forces(lumped_links(mdl), [omega], r.response).foundation[0]))


@case("protection-absorber", group="protection")
def protection_absorber():
    """V6.5-a: m1 = c1 = 1, m2 = c2 = 0.1 (omega* = 1).  (6.30) A_1(omega*) = 0 and A_2 = -F_1/c_2 = -10;
    natural frequencies k = 0.854309, 1.170537 (roots of (1.1 - s)(0.1 - 0.1 s) - 0.01 = 0; the digest prints
    1.170536, a truncation of 1.1705367).  Independent: harmonic_response and modal_analysis of the assembled
    LumpedModel (A_1 to 1e-12 of F_1/c_1; frequencies at half a printed digit), the absorber spring force from
    element_forces equals -F_1 (the reaction cancels the exciting force, §6.5), a dense complex solve for the
    whole AFC (1e-12), and the AFC with a light damper peaks at k_1, k_2 (grid step 1e-4).  Fig. 6.10: a damper
    b = 0.02 between the masses makes A_1(omega*) > 0 and raises A_1 in a band around omega* while lowering
    both resonance peaks."""
    out = []
    a = Absorber(1.0, 1.0, 0.1, 0.1)
    mdl = a.lumped_model()
    ls = mdl.linear_system()
    F = np.array([1.0, 0.0])
    ws = a.antiresonance
    r = harmonic_response(ls, [ws], force=F)
    A1, A2 = a.amplitudes(ws)
    out.append(check("protection-absorber", "seed 001 (6.30)", "omega* = sqrt(c2/m2)", 1.0, ws, 1e-15))
    out.append(check("protection-absorber", "(6.29) helper", "|A_1(omega*)| c_1/F_1", 0.0, abs(complex(A1)), 1e-12, scale=1.0))
    out.append(check("protection-absorber", "harmonic_response of the LumpedModel", "|A_1(omega*)| c_1/F_1", 0.0,
                     abs(r.response[0, 0]), 1e-12, scale=1.0))
    out.append(check("protection-absorber", "digest V6.5-a", "A_2(omega*) = -F_1/c_2", -10.0, r.response[0, 1].real, 1e-12))
    P = element_forces(lumped_links(mdl), [ws], r.response)
    out.append(check("protection-absorber", "seed 001 §6.5 (reaction = -force)", "absorber spring force / F_1", -1.0,
                     P.values[0, 1].real, 1e-12))
    ma = modal_analysis(ls, 2)
    for i, txt in enumerate(("0.854309", "1.170537")):
        v, tol = printed(txt)
        out.append(check("protection-absorber", "digest V6.5-a", f"k_{i + 1} (helper, closed form)", v,
                         a.natural_frequencies()[i], tol))
        out.append(check("protection-absorber", "modal_analysis of the LumpedModel", f"k_{i + 1}", v, ma.omega_rad_s[i], tol))
    w = np.linspace(0.5, 1.6, 111)
    helper = np.array(a.amplitudes(w)).T
    dense = np.array([ref.two_dof_amplitudes(1, 1, 0.1, 0.1, wi) for wi in w])
    out.append(check("protection-absorber", "dense complex solve", "max |A_helper - A_dense| / max|A|", 0.0,
                     float(np.max(np.abs(helper - dense)) / np.max(np.abs(dense))), 1e-12, scale=1.0))
    light = Absorber(1.0, 1.0, 0.1, 0.1, b=1e-4).lumped_model().linear_system()
    for i, kr in enumerate(a.natural_frequencies()):
        c0 = round(kr, 2)                                  # a round grid of step 1e-4 in a +-0.02 window
        wgrid = c0 + 1e-4 * np.arange(-200, 201)
        amp = np.abs(harmonic_response(light, wgrid, force=F).response[:, 0])
        out.append(check("protection-absorber", "AFC sweep (b = 1e-4, step 1e-4)", f"peak {i + 1} of |A_1|", kr,
                         wgrid[np.argmax(amp)], 0.5e-4 / kr * 1.0001))
    damped = Absorber(1.0, 1.0, 0.1, 0.1, b=0.02)
    wb = np.linspace(0.6, 1.5, 901)
    A_und = np.abs(a.amplitudes(wb)[0])
    A_dam = np.abs(damped.amplitudes(wb)[0])
    up = wb[A_dam > A_und]
    out.append(claim("protection-absorber", "Fig. 6.10 curve 3", "with the damper A_1(omega*) > 0",
                     abs(damped.amplitudes(1.0)[0]) > 1e-3))
    out.append(claim("protection-absorber", "Fig. 6.10 hatched band", "damper raises A_1 in one band around omega* only",
                     up.size > 0 and up.min() < 1.0 < up.max() and up.min() > a.natural_frequencies()[0]
                     and up.max() < a.natural_frequencies()[1], note=f"band [{up.min():.3f}, {up.max():.3f}]"))
    return out


@case("protection-isolation", group="protection")
def protection_isolation():
    """V6.4-a/c.  Undamped transmissibility (6.17) 1/|1 - z^2| = 1/3, 1, 0.125 at z = 2, sqrt 2, 3; the viscous
    transmissibility (digest [D]) against the assembled 1-DOF model's foundation force (harmonic_response +
    element_forces, 1e-12) at delta = 0.1.  Design region: m = 100 kg, omega = 300 rad/s, xi* = 0.1 ->
    c < 8.18e5 N/m (6.18); Delta* = 5 mm -> c > 1.962e5 N/m (6.20), feasible; omega = 100 rad/s -> c < 9.09e4:
    infeasible (line 3 above line 1).  Independent: the stiffness limit found by brentq on the transmissibility
    of the assembled model with a vanishing damper (b = 1e-6 c_crit: the line moves by ~1e-12) and with
    delta = 0.05 against the exact damped limit (quadratic in z^2), 1e-9."""
    out = []
    v, tol = printed("0.33333")
    out.append(check("protection-isolation", "digest V6.4-a (6.17)", "xi(z = 2), undamped", v,
                     float(force_transmissibility(2.0)), tol))
    for z, exact in ((math.sqrt(2), 1.0), (3.0, 0.125)):
        out.append(check("protection-isolation", "digest V6.4-a (6.17), exact values", f"xi(z = {z:.4g}), undamped", exact,
                         float(force_transmissibility(z)), 1e-12))
    zs = np.array([0.5, 1.0, math.sqrt(2), 2.0, 3.0])
    pkg = np.array([_transmitted(1.0, 1.0, 0.2, z) for z in zs])
    out.append(check("protection-isolation", "assembled 1-DOF model: foundation force", "max |T_model - T_formula| (delta 0.1)",
                     0.0, float(np.max(np.abs(pkg - force_transmissibility(zs, 0.1)))), 1e-12, scale=1.0))
    out.append(check("protection-isolation", "dense complex solve", "max |T_ref - T_formula| (delta 0.1)", 0.0,
                     float(np.max(np.abs(ref.sdof_transmitted_force(zs, 0.1) - force_transmissibility(zs, 0.1)))),
                     1e-12, scale=1.0))
    out.append(check("protection-isolation", "seed 001 §6.4 (z > sqrt 2)", "T(sqrt 2) = 1 for any damping", 1.0,
                     float(force_transmissibility(math.sqrt(2), 0.3)), 1e-14))
    d = isolation_design(100.0, 300.0, xi_allowed=0.1, settlement_allowed=0.005)
    v, tol = printed("8.18e5")
    out.append(check("protection-isolation", "digest V6.4-c (6.18)", "c_max [N/m]", v, d.c_max, tol))
    v, tol = printed("1.962e5")
    out.append(check("protection-isolation", "digest V6.4-c (6.20)", "c_min [N/m]", v, d.c_min, tol))
    out.append(claim("protection-isolation", "digest V6.4-c", "omega = 300: feasible", d.feasible))
    d2 = isolation_design(100.0, 100.0, xi_allowed=0.1, settlement_allowed=0.005)
    v, tol = printed("9.09e4")
    out.append(check("protection-isolation", "digest V6.4-c (6.18)", "omega = 100: c_max [N/m]", v, d2.c_max, tol))
    out.append(claim("protection-isolation", "seed 001 §6.4 (line 3 above line 1)", "omega = 100: infeasible",
                     not d2.feasible and d2.m_opt is None))
    m, w = 100.0, 300.0
    for delta in (1e-6, 0.05):
        f = lambda c: _transmitted(m, c, 2 * delta * math.sqrt(c * m), w) - 0.1
        root = brentq(f, 1e4, m * w * w / 2.5, xtol=1e-6, rtol=1e-14)
        exact = damped_stiffness_limit(m, w, 0.1, delta)
        out.append(check("protection-isolation", "brentq on the assembled model's transmissibility",
                         f"c limit at delta = {delta:g}", root, exact, 1e-9))
    out.append(check("protection-isolation", "(6.18) = damped limit at delta -> 0", "c_max (6.18) vs damped limit",
                     damped_stiffness_limit(m, w, 0.1, 0.0), d.c_max, 1e-14))
    # settlement (6.20): static deflection of the assembled model under its weight
    mdl, ls = _sdof(m, d.c_min)
    from discrete.linear.static import static_deflection

    out.append(check("protection-isolation", "static_deflection of the assembled model", "settlement at c_min [m]", 0.005,
                     float(static_deflection(ls, np.array([m * 9.81]))[0]), 1e-12))
    # lightest machine with an amplitude limit (line 2 meets line 3)
    dm = isolation_design(100.0, 300.0, xi_allowed=0.1, settlement_allowed=0.005, force_amplitude=1000.0,
                          amplitude_allowed=1e-4)
    m_exp = (1000.0 / 1e-4) / (300.0**2 - 9.81 / 0.005)
    out.append(check("protection-isolation", "lines 2 and 3 of Fig. 6.8a", "lightest feasible mass (point N) [kg]",
                     m_exp, dm.m_opt, 1e-12))
    return out


@case("protection-moving-mass", group="protection")
def protection_moving_mass():
    """V6.4-b (model 2, (6.22)-(6.28)): m0 = 900 kg, M = 100 kg, c = 2.5e6 N/m, omega = 100 rad/s:
    A/y* = 0.13333 and xi_1 = 0.33333 (digest [D]).  Independent: the assembled 1-DOF LumpedModel (mass
    m0 + M on c) under the omega^2 load M y* omega^2 (unbalance_response) with the transmitted force from
    element_forces; the bounds (6.25), (6.27) equal the stiffnesses where xi_1 and A/y* reach their limits
    (brentq on the closed forms, 1e-12)."""
    out = []
    mm = MovingMassIsolation(900.0, 100.0, 2.5e6, 100.0)
    for val, txt, nm in ((mm.amplitude_ratio, "0.13333", "A/y*"), (mm.xi1, "0.33333", "xi_1")):
        v, tol = printed(txt)
        out.append(check("protection-moving-mass", "digest V6.4-b (6.23)-(6.24)", nm, v, val, tol))
    mdl, ls = _sdof(1000.0, 2.5e6)
    ystar = 1.0
    r, spec = unbalance_response(ls, [100.0], 0, 100.0 * ystar)
    A = abs(r.response[0, 0])
    Rf = abs(element_forces(lumped_links(mdl), [100.0], r.response).foundation[0])
    out.append(check("protection-moving-mass", "unbalance_response of the assembled model", "A/y*", mm.amplitude_ratio,
                     A / ystar, 1e-12))
    out.append(check("protection-moving-mass", "foundation force / (M y* omega^2)", "xi_1", mm.xi1,
                     Rf / (100.0 * ystar * 100.0**2), 1e-12))
    b = mm.bounds(xi1_allowed=0.2, xi2_allowed=0.2, settlement_allowed=0.002)
    c25 = brentq(lambda c: MovingMassIsolation(900.0, 100.0, c, 100.0).xi1 - 0.2, 1e3, 9.9e6, xtol=1e-9, rtol=1e-15)
    c27 = brentq(lambda c: MovingMassIsolation(900.0, 100.0, c, 100.0).amplitude_ratio - 0.2, 1e3, 9.9e6, xtol=1e-9,
                 rtol=1e-15)
    out.append(check("protection-moving-mass", "brentq on xi_1(c)", "(6.25) bound [N/m]", c25, b["6.25"], 1e-12))
    out.append(check("protection-moving-mass", "brentq on A/y*(c)", "(6.27) bound [N/m]", c27, b["6.27"], 1e-12))
    out.append(check("protection-moving-mass", "(6.28)", "settlement bound [N/m]", 9.81 * 1000 / 0.002, b["6.28"], 1e-14))
    return out


@case("protection-unbalance", group="protection")
def protection_unbalance():
    """Loads proportional to omega^2 (§5.12, digest V5.12): the whirl radius of the disc's centre of mass,
    r/e = 1/|1 - s^2| (5.66), s = omega/omega*: 1.33333, 1.96078, 5.26316, 4.76190, 1.04167, 0.33333, 0.125,
    0.041667 at s = 0.5, 0.7, 0.9, 1.1, 1.4, 2, 3, 5 (half a printed digit), from unbalance_response of the
    assembled mass-spring model (deflection Delta under m e omega^2, r = |e + Delta|)."""
    out = []
    m, c, e = 2.0, 800.0, 1e-3
    ws = math.sqrt(c / m)
    table = ((0.5, "1.33333"), (0.7, "1.96078"), (0.9, "5.26316"), (1.1, "4.76190"), (1.4, "1.04167"), (2.0, "0.33333"),
             (3.0, "0.125"), (5.0, "0.041667"))
    _, ls = _sdof(m, c)
    r, spec = unbalance_response(ls, [s * ws for s, _ in table], 0, m * e)
    for (s, txt), D in zip(table, r.response[:, 0]):
        v, tol = printed(txt)
        out.append(check("protection-unbalance", "digest V5.12 (5.66)", f"r/e at s = {s:g}", v, abs(e + D) / e,
                         max(tol, 1e-12)))
    out.append(check("protection-unbalance", "unbalance_spectrum", "F(omega) = m e omega^2 at s = 2", m * e * (2 * ws) ** 2,
                     abs(spec[5]), 1e-14))
    return out


@case("protection-unloading", group="protection")
def protection_unloading():
    """Dynamic unloading §6.6.  V6.6-b (6.31)-(6.32): m = 1, c_0 = 100: R0_max/R_max = |1 - omega*^2/omega^2| =
    0 at omega = 10, 1.0 at 7.0711 (break-even omega*/sqrt 2), 0.75 at 20; independent: the reaction of a driver
    with inertia m and an unloading spring c_0 to ground from constraint_reactions (harmonic base motion).
    V6.6-a (6.35)-(6.38): harmonic stroke y = (Pi_max/2)(1 - cos phi), R* = m omega^2 (Pi_max/2 - y), m = 2 kg,
    omega = 50 rad/s, Pi_max = 0.04 m: c_0 = 5000 N/m, u_0 = -100 N, residual reaction 0 (Gauss-Legendre
    quadrature split at the kinks of |Pi'|, 1e-9), from the general normal equations and from the corrected
    (6.38); the printed first line of (6.37) (Pi_max c_0) gives a spring that does not unload.  A cycloidal
    dwell-rise-dwell-return law with R* = -m omega^2 Pi'' (inertia only) against an independent least-squares
    fit on a 2e4-point periodic grid (numpy lstsq, weights |Pi'|; the rectangle rule on a periodic grid converges
    fast here because |Pi'| is C1 at the dwell boundaries: 1e-9 asserted, ~1e-15 observed); the fitted spring lowers
    the functional Phi (6.35) -- though not the peak reaction of this law (0.84x): the dwells, where the spring
    force acts but |dy| = 0, do not enter (6.35)."""
    out = []
    m, c0 = 1.0, 100.0
    for w, exact in ((10.0, 0.0), (10 / math.sqrt(2), 1.0), (20.0, 0.75)):
        h = harmonic_unloading(m, w, 0.01, c0)
        ratio = float(h["R0_max"] / h["R_max"])
        out.append(check("protection-unloading", "digest V6.6-b (6.32)/(6.31), exact values", f"R0/R at omega = {w:.5g}",
                         exact, ratio, 1e-12, scale=1.0))
        drv = LumpedModel(bodies=[], drivers=[Driver("member", amplitude=0.01, omega=w, inertia=m)],
                          springs=[Link(("ground", "member"), c0)])
        ls = drv.linear_system()
        r = harmonic_response(ls, [w], base_motion={0: 0.01})
        R = reactions_from_result(ls, r)
        out.append(check("protection-unloading", "constraint_reactions of a driven member", f"R0_max at omega = {w:g}",
                         float(h["R0_max"]), abs(R.values[0, 0]), 1e-12, scale=max(float(h["R_max"]), 1e-300)))
    out.append(check("protection-unloading", "seed 001 §6.6", "break-even omega*/sqrt 2", 10 / math.sqrt(2),
                     harmonic_unloading(m, 1.0, 0.01, c0)["break_even"], 1e-15))
    law = dwell_rise_dwell_return(0.04, math.pi, 0.0, math.pi, law="harmonic")
    mass, w = 2.0, 50.0
    R = lambda p: mass * w**2 * (0.02 - law(p))
    u = unloading_spring(law, R)
    for val, exp, nm in ((u.c0, 5000.0, "c_0 [N/m]"), (u.u0, -100.0, "u_0 [N]"), (u.book_c0, 5000.0, "c_0 by (6.38)"),
                         (u.book_u0, -100.0, "u_0 by (6.38)")):
        out.append(check("protection-unloading", "digest V6.6-a", nm, exp, val, 1e-9))
    out.append(check("protection-unloading", "digest V6.6-a", "residual peak |R* + U| / peak |R*|", 0.0,
                     u.peak_after / u.peak_before, 1e-9, scale=1.0))
    pm = u.pi_max
    bad = np.linalg.solve([[2 * pm, pm], [pm**2, 2 / 3 * pm**3]], [u.S1, u.S2])
    phi = np.linspace(0, 2 * math.pi, 2001)
    bad_peak = float(np.max(np.abs(R(phi) + bad[0] + bad[1] * law(phi))))
    out.append(claim("protection-unloading", "(6.37) as printed (Pi_max c_0)", "printed system leaves >= 20% of the reaction",
                     bad_peak > 0.2 * u.peak_before, note=f"peak {bad_peak:.4g} N of {u.peak_before:.4g} N"))
    cyc = dwell_rise_dwell_return(0.03, math.radians(120), math.radians(60), math.radians(120), law="cycloidal")
    Rc = lambda p: mass * w**2 * cyc(p, 2)         # R* = m y'' (inertia of the member), as in V6.6-a
    uc = unloading_spring(cyc, Rc)
    u0g, c0g = ref.unloading_least_squares_grid(lambda p: cyc(p), lambda p: cyc(p, 1), Rc)
    out.append(check("protection-unloading", "lstsq on a 2e4-point grid", "cycloidal law: c_0", c0g, uc.c0, 1e-9))
    out.append(check("protection-unloading", "lstsq on a 2e4-point grid", "cycloidal law: u_0", u0g, uc.u0, 1e-9))
    out.append(claim("protection-unloading", "(6.35)", "least squares lowers the functional Phi",
                     uc.functional_after < uc.functional_before,
                     note=f"Phi ratio {uc.functional_after / uc.functional_before:.3f}; peak ratio {uc.peak_ratio:.3f} "
                          "(dwells are not weighted by |dy|, so the peak may rise)"))
    return out


@case("protection-quasi-constant", group="protection")
def protection_quasi_constant():
    """§6.7, (6.41)-(6.44).  theta = 1, delta = 0.05: kappa at z = 0.5, 0.9, 0.95, 0.99, 1, 1.05, 1.1, 1.5, 2, 3 =
    0.99944, 0.91989, 0.73386, 0.19898, 0, 0.68090, 0.86646, 0.98418, 0.99123, 0.99373 (digest, half a printed
    digit).  Detuned theta^2 = 0.9 (V6.7-b): peak at z = 0.95346 with kappa = 1.41421, zero at z = 1.05409;
    kappa(1) = 0.5 |Delta theta^2|/delta = 1.  Independent: bounded maximisation and root finding on kappa;
    the platform (6.40) synthesised by (6.42) (M = 10 kg, c_0 = 2e4, c_1 = 5e4 N/m, r = 0.01 m) solved as a
    complex 1-DOF equation with the book's resistance b = 2 delta M omega (dense solve, 1e-12), and the
    assembled LumpedModel with a viscous damper b = 2 delta sqrt((c_0 + c_1) M) under the load
    c_1 r - omega^2 (m_1 R + m_2 r) (harmonic_response) against the viscous form of kappa (1e-12).  The
    printed z_2 = sqrt((1 - theta^2)(1 - theta^2 - 4 delta^2)) = 0.095 is not the maximum."""
    out = []
    zs = (0.5, 0.9, 0.95, 0.99, 1.0, 1.05, 1.1, 1.5, 2.0, 3.0)
    vals = ("0.99944", "0.91989", "0.73386", "0.19898", "0", "0.68090", "0.86646", "0.98418", "0.99123", "0.99373")
    for z, txt in zip(zs, vals):
        if txt == "0":
            out.append(check("protection-quasi-constant", "seed 001 (6.44)", "kappa(1) = 0, theta = 1", 0.0,
                             float(kappa(z, 0.05)), 1e-15, scale=1.0))
            continue
        v, tol = printed(txt)
        out.append(check("protection-quasi-constant", "digest §6.7 table (6.44)", f"kappa({z:g}), theta = 1", v,
                         float(kappa(z, 0.05)), tol))
    ex = kappa_extrema(0.05, 0.9)
    res = minimize_scalar(lambda z: -float(kappa(z, 0.05, 0.9)), bounds=(0.8, 1.0), method="bounded",
                          options={"xatol": 1e-12})
    zero = brentq(lambda z: 1 - 0.9 * z * z, 1.0, 1.2, xtol=1e-15)
    for nm, val, txt in (("peak z (corrected z_2)", ex["z_peak"], "0.95346"), ("peak z (maximisation)", res.x, "0.95346"),
                         ("kappa_max", ex["kappa_peak"], "1.41421"), ("kappa_max (maximisation)", -res.fun, "1.41421"),
                         ("zero z_1 = 1/theta", ex["z_zero"], "1.05409"), ("zero (root of numerator)", zero, "1.05409")):
        v, tol = printed(txt)
        out.append(check("protection-quasi-constant", "digest V6.7-b", nm, v, val, tol))
    out.append(check("protection-quasi-constant", "seed 001 §6.7", "kappa(1) = 0.5 |Delta theta^2|/delta", 1.0,
                     ex["kappa_at_1"], 1e-12))
    printed_z2 = math.sqrt((1 - 0.9) * (1 - 0.9 - 4 * 0.05**2))
    out.append(claim("protection-quasi-constant", "seed 001 §6.7 z_2 as printed", "printed z_2 is not the maximum",
                     float(kappa(printed_z2, 0.05, 0.9)) < ex["kappa_peak"] - 0.3, note=f"printed z_2 = {printed_z2:.4f}"))
    plat = QuasiConstantPlatform.synthesised(M=10.0, c0=2e4, c1=5e4, r=0.01, delta=0.05)
    out.append(check("protection-quasi-constant", "(6.42)", "theta^2 of the synthesised platform", 1.0, plat.theta2, 1e-14))
    w = plat.p * np.array([0.3, 0.8, 0.97, 1.0, 1.03, 1.5, 2.5])
    direct = np.array([ref.kappa_direct(wi, plat.M, plat.c0, plat.c1, plat.r, plat.unbalance, 2 * 0.05 * plat.M * wi)
                       for wi in w])
    out.append(check("protection-quasi-constant", "dense solve of (6.40), b = 2 delta M omega", "max |kappa - direct|",
                     0.0, float(np.max(np.abs(plat.amplitude(w) / plat.A_star - direct))), 1e-12, scale=1.0))
    bv = 2 * 0.05 * math.sqrt((plat.c0 + plat.c1) * plat.M)
    mdl = LumpedModel(bodies=[Body("platform", plat.M)], springs=[Link(("ground", "platform"), plat.c0 + plat.c1)],
                      dampers=[Link(("ground", "platform"), bv)])
    ls = mdl.linear_system()
    const = harmonic_response(ls, w, force=np.array([plat.c1 * plat.r]))
    unb, _ = unbalance_response(ls, w, 0, -plat.unbalance)
    A = np.abs(const.response[:, 0] + unb.response[:, 0])
    out.append(check("protection-quasi-constant", "assembled LumpedModel, viscous damper", "max |A/A* - kappa_viscous|",
                     0.0, float(np.max(np.abs(A / plat.A_star - kappa(w / plat.p, 0.05, 1.0, "viscous")))), 1e-12,
                     scale=1.0))
    out.append(claim("protection-quasi-constant", "seed 001 (6.43)", "undamped: A = A* at every omega",
                     bool(np.allclose(QuasiConstantPlatform.synthesised(10.0, 2e4, 5e4, 0.01).amplitude(w), plat.A_star,
                                      rtol=1e-12))))
    return out


@case("protection-unbalance-file", group="protection")
def protection_unbalance_file():
    """The same (5.66) through a model file: a [[load]] with scaling = "omega2" and amplitude m e drives the
    mass-spring model; r/e = |e + Delta|/e at the digest's s values (half a printed digit), and the response
    equal to the Python unbalance_response to 1e-13 (the same solve, scaled by omega^2)."""
    from fem.study import Study

    out = []
    m, c, e = 2.0, 800.0, 1e-3
    ws = math.sqrt(c / m)
    table = ((0.5, "1.33333"), (0.9, "5.26316"), (1.1, "4.76190"), (2.0, "0.33333"), (5.0, "0.041667"))
    doc = {"title": "unbalanced disc on a spring", "body": [{"name": "disc", "inertia": m}],
           "spring": [{"between": ["ground", "disc"], "k": c}],
           "load": [{"body": "disc", "amplitude": m * e, "scaling": "omega2"}],
           "analysis": {"type": "forced", "omega_rad_s": [s * ws for s, _ in table]}}
    r = Study.parse(doc).forced()
    _, ls = _sdof(m, c)
    ref, _ = unbalance_response(ls, [s * ws for s, _ in table], 0, m * e)
    for (s, txt), D in zip(table, r.response[:, 0]):
        v, tol = printed(txt)
        out.append(check("protection-unbalance-file", "digest V5.12 (5.66)", f"r/e at s = {s:g} (model file)", v,
                         abs(e + D) / e, max(tol, 1e-12)))
    out.append(check("protection-unbalance-file", "unbalance_response (Python API)", "max |Delta - Delta_API| / |Delta_API|",
                     0.0, float(np.max(np.abs(r.response[:, 0] - ref.response[:, 0]) / np.abs(ref.response[:, 0]))),
                     1e-13, scale=1.0))
    return out
