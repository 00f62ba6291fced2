"""Lumped linear systems (§4.4-4.9, §3.2) and beams with two masses (§3.3, §4.5, §4.7).

References are built the book's way (closed forms, the book's relative coordinates,
Table 3.1 influence coefficients) and are independent of the package's assembler.
Exact relations get 1e-10; the digest's printed numbers get half a unit of the last digit.
"""
from __future__ import annotations


import numpy as np

from discrete.dunkerley import dunkerley_bound
from fem import Material, PointAttachment, Section, Segment, ShaftModel, Support, assemble, modal_analysis
from validation.analytic import bending as eb
from validation.analytic.lumped_refs import (geared_drive_314, geared_drive_314_driven, two_discs,
                                             two_mass_three_spring)
from fem.modelfile.source import read_toml
from fem.study import Study
from validation.registry import case, check, claim, printed
from validation.examples import EXAMPLES



def _pr(text: str, computed: float):
    """(expected, computed, tolerance) for a printed reference number."""
    value, tol = printed(text)
    return value, computed, tol


def _omegas(doc: dict, n: int):
    return modal_analysis(Study.parse(doc).lumped.linear_system(), n)


@case("lumped-two-mass-chain", group="lumped")
def lumped_two_mass_chain():
    """Wall-c-m-c-m-c-wall (§4.4, Fig. 4.7): k = sqrt(c/m), sqrt(3c/m); partial frequency
    p = sqrt(2c/m) lies between them; form coefficients +1, -1 (exact).  The model is
    examples/two_mass_chain.toml (m = 1 kg, c = 1000 N/m)."""
    m, c = 1.0, 1000.0
    res = _omegas(read_toml(EXAMPLES / "two_mass_chain.toml"), 2)
    ref = two_mass_three_spring(m, c)
    beta = res.shapes[1] / res.shapes[0]
    p = np.sqrt(2 * c / m)
    return [check("lumped-two-mass-chain", "seed 001 §4.4", f"k_{r + 1} [rad/s]", ref[r], res.omega_rad_s[r], 1e-10)
            for r in range(2)] + \
        [check("lumped-two-mass-chain", "seed 001 §4.4", f"beta_{r + 1}", (1.0, -1.0)[r], beta[r], 1e-10) for r in range(2)] + \
        [claim("lumped-two-mass-chain", "seed 001 §4.4", "k_1 < p < k_2 (partial frequency between)",
               bool(res.omega_rad_s[0] < p < res.omega_rad_s[1]))]


@case("lumped-two-discs", group="lumped")
def lumped_two_discs():
    """Free two-disc shaft (4.41): k = 0 (one rigid-body mode) and sqrt(c (J1+J2)/(J1 J2))."""
    out = []
    for J1, J2 in ((1.0, 1.0), (2.0, 1.0), (1000.0, 1.0)):
        doc = {"body": [{"name": "J1", "inertia": J1}, {"name": "J2", "inertia": J2}],
               "spring": [{"between": ["J1", "J2"], "k": 1.0}]}
        res = _omegas(doc, 2)
        ref = two_discs(J1, J2, 1.0)
        out.append(check("lumped-two-discs", "seed 001 (4.41)", f"k_2, J1 = {J1:g}, J2 = {J2:g}", ref[1],
                         res.omega_rad_s[1], 1e-10))
        out.append(claim("lumped-two-discs", "seed 001 §4.8", f"one rigid-body mode, J1 = {J1:g}",
                         res.rigid_body_modes == 1 and res.omega_rad_s[0] == 0.0))
    return out


GEARED = dict(J1=1.0, J2=0.5, J3=0.2, J4=2.0, u21=0.5, c1=1000.0, c2=500.0)


def _geared_doc(driven: bool) -> dict:
    """examples/geared_drive.toml (motor J1, gear1 J2, gear2 J3, drum J4 of GEARED); ``driven``: the
    motor's angle prescribed (a driver instead of the first body)."""
    doc = read_toml(EXAMPLES / "geared_drive.toml")
    if driven:
        motor = doc["body"].pop(0)
        doc["driver"] = [{"name": motor["name"], "velocity": 1.0}]
    return doc


@case("lumped-geared-drive", group="lumped")
def lumped_geared_drive():
    """Drive of Fig. 2.1g, equations (3.14): the package eliminates the gear from absolute
    angles; the reference builds a_ik, c_ik in the book's relative coordinates (3.9)-(3.11).
    Digest V3.2a: 0, 17.6739, 54.6176 rad/s; V3.2b (input disc driven): 14.7950, 45.5693.
    The model is examples/geared_drive.toml."""
    out = []
    res = _omegas(_geared_doc(False), 3)
    ref = geared_drive_314(**GEARED)
    out += [check("lumped-geared-drive", "seed 001 (3.14)", f"k_{r + 1}", ref[r], res.omega_rad_s[r], 1e-10,
                  scale=ref[-1]) for r in range(3)]
    out += [check("lumped-geared-drive", "digest V3.2a (printed)", f"k_{r + 2}", *_pr(v, res.omega_rad_s[r + 1]))
            for r, v in enumerate(("17.6739", "54.6176"))]
    res_d = _omegas(_geared_doc(True), 2)
    ref_d = geared_drive_314_driven(**GEARED)
    out += [check("lumped-geared-drive", "seed 001 (3.14), q1 prescribed", f"k_{r + 1} driven", ref_d[r],
                  res_d.omega_rad_s[r], 1e-10) for r in range(2)]
    out.append(claim("lumped-geared-drive", "seed 001 §4.8", "one rigid-body mode when free", res.rigid_body_modes == 1))
    return out


def _massless_beam(length, supports, masses, overhang=0.0):
    """Beam with negligible own mass (1e-10 of the point masses) carrying point masses."""
    mat = Material(E=1.0, G=1.0, rho=1e-10)
    sec = Section(A=1.0, I=1.0, J=1.0, Ip=1.0)
    model = ShaftModel("bending", [Segment(length + overhang, 8, sec, mat)], supports=[Support(*s) for s in supports],
                       points=[PointAttachment(x=x, mass=m) for x, m in masses])
    return assemble(model)


@case("beam-two-masses", group="lumped")
def beam_two_masses():
    """Massless beams with two point masses (§4.5): the FE beam (Hermite, nodally exact for
    point loads) against the closed-form roots of (4.31) with Table 3.1 coefficients.
    V4.5a simply supported, masses at L/3, 2L/3: k = 5.69210, 22.0454 sqrt(EI/(m L^3));
    V4.5b cantilever, masses at L/2, L: 1.65134, 10.9864, beta 3.12047, -0.32047.
    Tolerance 1e-8: the beam's own mass (1e-10 of the point masses) and rounding."""
    out = []
    cases = [("simply supported", [(0.0, "pinned"), (1.0, "pinned")], (1 / 3, 2 / 3), 2, ("5.69210", "22.0454")),
             ("cantilever", [(0.0, "clamped")], (0.5, 1.0), 1, ("1.65134", "10.9864"))]
    for name, sups, (a, c), row, printed in cases:
        fe = _massless_beam(1.0, sups, [(a, 1.0), (c, 1.0)])
        res = modal_analysis(fe.system, 2)
        e11, e22, e12 = eb.influence_coefficients(row, 1.0, a, c)
        k, beta = eb.two_mass_frequencies(e11, e22, e12, 1.0, 1.0)
        out += [check("beam-two-masses", "seed 001 (4.31), Table 3.1", f"k_{r + 1}, {name}", k[r], res.omega_rad_s[r], 1e-8)
                for r in range(2)]
        out += [check("beam-two-masses", "digest V4.5 (printed)", f"k_{r + 1}, {name}", *_pr(printed[r], res.omega_rad_s[r]))
                for r in range(2)]
        w1 = fe.system.dof_index(field="w", x=a)
        w2 = fe.system.dof_index(field="w", x=c)
        fe_beta = res.shapes[w2] / res.shapes[w1]
        out += [check("beam-two-masses", "seed 001 (4.32)", f"beta_{r + 1}, {name}", beta[r], fe_beta[r], 1e-7)
                for r in range(2)]
        exact_bound = eb.dunkerley_bound([e11, e22], [1.0, 1.0])
        bound = dunkerley_bound(fe.system)
        out.append(check("beam-two-masses", "seed 001 (4.40) Dunkerley", f"lower bound, {name}", exact_bound, bound, 1e-8))
        out.append(claim("beam-two-masses", "seed 001 (4.39)", f"Dunkerley bound <= k_1, {name}",
                         bool(bound <= res.omega_rad_s[0]), note=f"{bound:.6g} vs {res.omega_rad_s[0]:.6g}"))
    return out


@case("beam-influence-coefficients", group="lumped")
def beam_influence_coefficients():
    """Static flexibility of the FE beam (K^-1 condensed at two points) against Table 3.1,
    rows 1-6 (l = 1, EI = 1, a = 0.3, c = 0.7; row 1 points at 0.3 and 0.8; rows 5-6 with an
    overhang c = 0.4).  Hermite elements are exact for point loads: tolerance 1e-9."""
    import scipy.sparse.linalg as spla

    geoms = {
        1: ([(0.0, "clamped")], 1.0, 0.3, 0.8, 0.0),
        2: ([(0.0, "pinned"), (1.0, "pinned")], 1.0, 0.3, 0.7, 0.0),
        3: ([(0.0, "clamped"), (1.0, "pinned")], 1.0, 0.3, 0.7, 0.0),
        4: ([(0.0, "clamped"), (1.0, "clamped")], 1.0, 0.3, 0.7, 0.0),
        5: ([(0.0, "pinned"), (1.0, "pinned")], 1.0, 0.3, 1.4, 0.4),
        6: ([(0.0, "clamped"), (1.0, "pinned")], 1.0, 0.3, 1.4, 0.4),
    }
    out = []
    for row, (sups, l, xa, xc, over) in geoms.items():
        fe = _massless_beam(l, sups, [(xa, 1.0), (xc, 1.0)], overhang=over)
        sys_ = fe.system
        i, j = sys_.dof_index(field="w", x=xa), sys_.dof_index(field="w", x=xc)
        f = sys_.free
        Kf = sys_.free_block(sys_.K).tocsc()
        pos = {d: k for k, d in enumerate(f)}
        E = np.zeros((f.size, 2))
        E[pos[i], 0] = E[pos[j], 1] = 1.0
        flex = E.T @ spla.spsolve(Kf, E)
        c_arg = over if row in (5, 6) else xc
        ref = eb.influence_coefficients(row, l, xa, c_arg)
        for name, v, r in (("e11", flex[0, 0], ref[0]), ("e22", flex[1, 1], ref[1]), ("e12", flex[0, 1], ref[2])):
            out.append(check("beam-influence-coefficients", f"seed 001 Table 3.1 row {row}", f"{name}, row {row}", r, v, 1e-9))
    return out
