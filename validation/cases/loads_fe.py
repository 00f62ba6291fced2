"""Internal loads (fem.loads) against closed forms and exact continuous solutions.

* Statics (end moment / end torque / end force, tip force) of stepped clamped-free shafts: the
  structures are statically determinate, so the element end forces are exact for any mesh and any
  element; only the rounding of the static solve remains.  Element end forces are differences of
  terms of size |K_e||q_e| ~ |F| (L/h)^3 (bending, 40 elements: 6e4 |F|), so a relative error of
  eps (L/h)^3 ~ 1e-11 is expected; tolerance 1e-9.
* Harmonic responses (no damping) against the exact solution of the continuous equations per
  segment (analytic/loads.py: wave solution of torsion, expm transfer of Euler-Bernoulli and
  Timoshenko): the section loads converge at the element's order -- 2 for P1 (consistent mass,
  dispersion error (k h)^2/24), 4 for P2, 4 for Hermite cubics (their frequency error order
  h^{2(p+1-m)} = h^4), 2 for Timoshenko P1 and 4 for P2 with reduced shear integration.  The order is
  fitted over four meshes (halving h) and must lie within 0.25 of the expected one: the next error
  term (h^{p+2}) bends a four-point log-log fit by O(h^2) (measured 0.01 ... 0.1 over these meshes).
  The finest mesh's error is held to 4x its measured value (margin for BLAS/platform rounding).
* Equilibrium: at every free node the two elements meeting there give the same section loads, at an
  attachment they differ by exactly its nodal force, and reactions plus applied loads balance the
  inertia forces of the whole structure -- all to round-off (1e-10 relative to the largest load;
  measured 1e-14 ... 1e-12).
"""
from __future__ import annotations

import math

import numpy as np

from discrete.linear import harmonic_response
from discrete.linear.static import static_deflection
from fem import Material, PointAttachment, Section, Segment, ShaftModel, Support, assemble
from fem.loads import rotor_section_loads, section_loads, support_reactions
from validation.analytic.loads import (euler_bernoulli_ss_harmonic, observed_order, stepped_torsion_torque,
                                       timoshenko_cantilever_harmonic)
from validation.builders import STEEL
from validation.registry import case, check

ALU = Material(E=7.0e10, G=2.6e10, rho=2700.0)
SRC = "statics of the determinate shaft (closed form)"
SRC_DYN = "exact solution of the continuous equations per segment (validation/analytic/loads.py)"
ROUNDOFF = 1e-9
BALANCE = 1e-10
ORDER_TOL = 0.25
THEORIES = (("bending", "euler-bernoulli", 2), ("bending", "timoshenko", 1), ("bending", "timoshenko", 2))


def _stepped(physics, theory="euler-bernoulli", order=2, n=8, supports=((0.0, "clamped"),), points=()):
    segs = [Segment(0.6, n, Section.circle(0.05), STEEL), Segment(0.9, max(1, int(1.5 * n)), Section.circle(0.03), ALU)]
    return ShaftModel(physics, segs, [Support(x, t) for x, t in supports], list(points), theory=theory, order=order)


def _static(fe, dof: str, x: float, value: float):
    s = fe.system
    F = np.zeros(s.n_dofs)
    F[s.dof_index(field=dof, x=x)] = value
    return static_deflection(s, F), F


def _stations(fe):
    """Element ends plus three points inside every element."""
    x_ends = section_loads(fe, np.zeros(fe.system.n_dofs)).x
    inner = np.concatenate([fe.mesh.nodes[:-1] + t * np.diff(fe.mesh.nodes) for t in (0.25, 0.5, 0.8)])
    return x_ends, inner


def _label(physics, theory, order):
    return f"{physics} P{order}" if physics != "bending" else (
        "Euler-Bernoulli Hermite" if theory == "euler-bernoulli" else f"Timoshenko P{order}")


@case("loads-fe-end-moment", group="loads")
def end_moment():
    """Clamped-free stepped shaft (steel d 50 mm, 0.6 m; aluminium d 30 mm, 0.9 m) under an end torque,
    end force or end moment: torque, axial force and bending moment are uniform (shear zero) at every
    element end and inside the elements, for P1/P2 rods and every beam element.  Tolerance: rounding
    of the static solve (module notes)."""
    name = "loads-fe-end-moment"
    out = []
    for physics, theory, order, dof, qty, value in (("torsion", "euler-bernoulli", 1, "theta", "torque", 250.0),
                                                    ("torsion", "euler-bernoulli", 2, "theta", "torque", 250.0),
                                                    ("axial", "euler-bernoulli", 1, "u", "axial_force", 4e3),
                                                    ("axial", "euler-bernoulli", 2, "u", "axial_force", 4e3)) + tuple(
            (p, t, o, "w_x" if t == "euler-bernoulli" else "phi", "bending_moment", 120.0) for p, t, o in THEORIES):
        fe = assemble(_stepped(physics, theory, order))
        q, _ = _static(fe, dof, 1.5, value)
        ends, inner = _stations(fe)
        sl = section_loads(fe, q)
        sl_in = section_loads(fe, q, x=inner)
        got = np.concatenate([sl[qty], sl_in[qty]])
        dev = float(np.max(np.abs(got - value)))
        what = _label(physics, theory, order)
        out.append(check(name, SRC, f"max |{qty} - {value:g}| / {value:g} over {got.size} stations ({what})", 0.0, dev,
                         ROUNDOFF, scale=value))
        if qty == "bending_moment":
            V = np.concatenate([sl["shear_force"], sl_in["shear_force"]])
            out.append(check(name, SRC, f"max |shear force| / (M/L) ({what})", 0.0, float(np.max(np.abs(V))), ROUNDOFF,
                             scale=value / 1.5))
    return out


@case("loads-fe-cantilever-tip-force", group="loads")
def cantilever_tip_force():
    """Stepped cantilever (as loads-fe-end-moment) with a tip force F = 1 kN: M(x) = F (L - x), V(x) = F at the
    element ends and inside the elements; the clamp's reactions are -F and -F L.  Every beam element (the
    Timoshenko elements too: the determinate moment does not depend on shear flexibility)."""
    name = "loads-fe-cantilever-tip-force"
    F0, L = 1e3, 1.5
    out = []
    for physics, theory, order in THEORIES:
        fe = assemble(_stepped(physics, theory, order))
        q, F = _static(fe, "w", L, F0)
        ends, inner = _stations(fe)
        xs = np.concatenate([ends, inner])
        sl = section_loads(fe, q)
        sl_in = section_loads(fe, q, x=inner)
        M = np.concatenate([sl["bending_moment"], sl_in["bending_moment"]])
        V = np.concatenate([sl["shear_force"], sl_in["shear_force"]])
        what = _label(physics, theory, order)
        out.append(check(name, SRC, f"max |M - F (L - x)| / (F L) ({what})", 0.0,
                         float(np.max(np.abs(M - F0 * (L - xs)))), ROUNDOFF, scale=F0 * L))
        out.append(check(name, SRC, f"max |V - F| / F ({what})", 0.0, float(np.max(np.abs(V - F0))), ROUNDOFF, scale=F0))
        R = support_reactions(fe, q, force=F)
        rot = "w_x" if theory == "euler-bernoulli" else "phi"
        out.append(check(name, SRC, f"clamp force reaction [N] ({what})", -F0, float(R["w@x=0"]), ROUNDOFF))
        out.append(check(name, SRC, f"clamp moment reaction [N m] ({what})", -F0 * L, float(R[f"{rot}@x=0"]), ROUNDOFF))
    return out


def _converge(name, quantity_name, expected_order, runs, h, finest_tol):
    """Checks of the observed order and the finest mesh's error; ``runs`` (n_mesh,) relative errors."""
    p = observed_order(np.asarray(h), np.asarray(runs))
    return [check(name, SRC_DYN, f"observed order of {quantity_name} (meshes h = {', '.join(f'{v:.4g}' for v in h)} m)",
                  expected_order, p, ORDER_TOL / expected_order),
            check(name, SRC_DYN, f"relative error of {quantity_name} on the finest mesh", 0.0, float(runs[-1]),
                  finest_tol, scale=1.0)]


@case("loads-fe-ss-beam-harmonic", group="loads")
def ss_beam_harmonic():
    """Simply supported steel beam (L = 1 m, d = 40 mm, Euler-Bernoulli Hermite elements) under a harmonic
    point force F = 100 N at x = 0.3 m, omega = 1.7 omega_1 (between the first two resonances, undamped):
    bending moment and shear force at x = 0.1, 0.3 (under the force), 0.5, 0.8 m against the exact
    dynamic-stiffness solution (E I w'''' = rho A omega^2 w on each side, matched at the force).  Order 4
    (module notes); finest mesh (80 elements) measured 1.2e-8."""
    name = "loads-fe-ss-beam-harmonic"
    L, a, F0 = 1.0, 0.3, 100.0
    sec = Section.circle(0.04)
    EI, rhoA = STEEL.E * sec.I, STEEL.rho * sec.A
    omega = 1.7 * math.pi**2 / L**2 * math.sqrt(EI / rhoA)
    xs = np.array([0.1, 0.3, 0.5, 0.8])
    M_ex, V_ex = euler_bernoulli_ss_harmonic(EI, rhoA, L, a, F0, omega, xs)
    errs = {"bending_moment": [], "shear_force": []}
    ns = (10, 20, 40, 80)
    for n in ns:
        fe = assemble(ShaftModel("bending", [Segment(L, n, sec, STEEL)], [Support(0.0, "pinned"), Support(L, "pinned")]))
        s = fe.system
        F = np.zeros(s.n_dofs, complex)
        F[s.dof_index(field="w", x=a)] = F0
        Q = harmonic_response(s, [omega], force=F).full[0]
        sl = section_loads(fe, Q, omega=omega, x=xs)
        errs["bending_moment"].append(np.max(np.abs(sl["bending_moment"] - M_ex)) / np.max(np.abs(M_ex)))
        errs["shear_force"].append(np.max(np.abs(sl["shear_force"] - V_ex)) / np.max(np.abs(V_ex)))
    h = [L / n for n in ns]
    return (_converge(name, "bending moment (Hermite)", 4, errs["bending_moment"], h, 5e-8)
            + _converge(name, "shear force (Hermite)", 4, errs["shear_force"], h, 2.5e-8))


@case("loads-fe-torsion-stepped-disc", group="loads")
def torsion_stepped_disc():
    """Stepped torsion shaft (steel d 50 mm, 0.6 m; aluminium d 30 mm, 0.9 m) clamped at x = 0 with a disc
    J = 0.01 kg m^2 at the step and a harmonic end torque T = 10 N m at omega = 4000 rad/s (between the first
    two natural frequencies, 2716 and 5467 rad/s): torque at x = 0 (the clamp), 0.3, both sides of the disc (the torque jumps by
    -omega^2 J theta there), 1.05 and 1.5 m against the exact wave solution per segment.  P1 (order 2) and P2
    (order 4); static check: omega = 0 gives T = 10 N m everywhere to round-off.  Finest meshes measured:
    P1 (64 + 96 el.) 1.5e-5, P2 (32 + 48 el.) 6.3e-10."""
    name = "loads-fe-torsion-stepped-disc"
    J_disc, T0, omega = 0.01, 10.0, 4000.0
    s1, s2 = Section.circle(0.05), Section.circle(0.03)
    segs = [(0.6, STEEL.G * s1.J, STEEL.rho * s1.Ip), (0.9, ALU.G * s2.J, ALU.rho * s2.Ip)]
    xs = [0.0, 0.3, 0.6, 0.6, 1.05, 1.5]
    sides = ["right", "right", "left", "right", "right", "left"]
    left, right = stepped_torsion_torque(segs, {0.6: J_disc}, T0, omega, xs)
    T_ex = np.where(np.array(sides) == "left", left, right)
    out = []
    for order, ns, p, finest in ((1, (8, 16, 32, 64), 2, 6e-5), (2, (4, 8, 16, 32), 4, 2.5e-9)):
        errs = []
        for n in ns:
            model = _stepped("torsion", order=order, n=n, points=[PointAttachment(0.6, inertia=J_disc)])
            fe = assemble(model)
            s = fe.system
            F = np.zeros(s.n_dofs, complex)
            F[s.dof_index(field="theta", x=1.5)] = T0
            Q = harmonic_response(s, [omega], force=F).full[0]
            T = np.array([section_loads(fe, Q, omega=omega, x=[x], side=sd)["torque"][0] for x, sd in zip(xs, sides)])
            errs.append(np.max(np.abs(T - T_ex)) / np.max(np.abs(T_ex)))
            if n == ns[0]:
                q0, _ = _static(fe, "theta", 1.5, T0)
                dev = float(np.max(np.abs(section_loads(fe, q0)["torque"] - T0)))
                out.append(check(name, SRC, f"static (omega = 0): max |T - T0| / T0 (P{order})", 0.0, dev, ROUNDOFF,
                                 scale=T0))
        out += _converge(name, f"torque (P{order})", p, errs, [0.6 / n for n in ns], finest)
    jump = right[3] - left[2]
    out.append(check(name, SRC_DYN, "exact torque jump at the disc, T(0.6+) - T(0.6-) [N m] (P2, 32 el.)", jump,
                     float((T[3] - T[2]).real), 1e-6))
    return out


@case("loads-fe-timoshenko-cantilever", group="loads")
def timoshenko_cantilever():
    """Thick steel cantilever (L = 0.5 m, d = 0.1 m: L/d = 5, shear and rotary inertia matter) under a
    harmonic tip force F = 1 kN at omega = 5000 rad/s (between the first two resonances, 1779 and 9939 rad/s): bending moment and
    shear force at x = 0, 0.25, 0.4 m against the exact Timoshenko solution (Cowper's kappa).  P1 (order 2)
    and P2 (order 4) with reduced shear integration.  Finest meshes measured: P1 (64 el.) 1.6e-4, P2 (32 el.)
    1.8e-7."""
    name = "loads-fe-timoshenko-cantilever"
    L, F0, omega = 0.5, 1e3, 5000.0
    sec = Section.circle(0.1)
    kappa = sec.shear_coefficient(STEEL.nu)
    EI, kGA, rhoA, rhoI = STEEL.E * sec.I, kappa * STEEL.G * sec.A, STEEL.rho * sec.A, STEEL.rho * sec.I
    xs = np.array([0.0, 0.25, 0.4])
    M_ex, V_ex = timoshenko_cantilever_harmonic(EI, kGA, rhoA, rhoI, L, F0, omega, xs)
    out = []
    for order, ns, p, finest in ((1, (8, 16, 32, 64), 2, 6.5e-4), (2, (4, 8, 16, 32), 4, 7e-7)):
        errs = []
        for n in ns:
            fe = assemble(ShaftModel("bending", [Segment(L, n, sec, STEEL)], [Support(0.0, "clamped")],
                                     theory="timoshenko", order=order))
            s = fe.system
            F = np.zeros(s.n_dofs, complex)
            F[s.dof_index(field="w", x=L)] = F0
            Q = harmonic_response(s, [omega], force=F).full[0]
            sl = section_loads(fe, Q, omega=omega, x=xs)
            errs.append(max(np.max(np.abs(sl["bending_moment"] - M_ex)) / np.max(np.abs(M_ex)),
                            np.max(np.abs(sl["shear_force"] - V_ex)) / np.max(np.abs(V_ex))))
        out += _converge(name, f"bending moment and shear force (Timoshenko P{order})", p, errs,
                         [L / n for n in ns], finest)
    return out


# ------------------------------------------------------------------ equilibrium
def _rigid(system, rotation: bool) -> np.ndarray:
    """Rigid translation (w = 1) or rotation about x = 0 (w = x, slope / rotation = 1) of a plane beam."""
    r = np.zeros(system.n_dofs)
    w = system.dof_field == "w"
    r[w] = system.dof_x[w] if rotation else 1.0
    if rotation:
        r[np.isin(system.dof_field, ("w_x", "phi"))] = 1.0
    return r


def _free_node_jumps(sl, attached_x) -> float:
    """Largest jump between the two elements at a node without attachment, relative to the largest load."""
    worst = 0.0
    for v in sl.quantities.values():
        v = v.reshape(v.shape[0], -1)
        jumps = np.abs(v[2:-1:2] - v[1:-1:2]).max(axis=1)
        xs = sl.x[1:-1:2]
        free = ~np.any(np.isclose(xs[:, None], np.asarray(attached_x)[None, :], atol=1e-9), axis=1)
        worst = max(worst, float(jumps[free].max() / np.abs(v).max()))
    return worst


@case("loads-fe-equilibrium", group="loads")
def equilibrium_fe():
    """Stepped shaft (loads-fe-end-moment's) clamped at 0, on a spring support at 1.5 m (k = 1e5 N/m, k_r = 50 N m/rad),
    with a point mass (3 kg, 0.02 kg m^2) at 0.6 m, material psi = 0.2 in the first segment, Rayleigh damping
    (alpha = 2 1/s, beta = 1e-5 s) and a harmonic force (torque) of 200 at 1.05 m, omega = 900 rad/s; every beam
    element and torsion P1/P2.  Round-off checks: (1) the two elements at every free node agree; (2) at the point
    mass the shear (torque) jumps by (-omega^2 + i omega alpha) m W, at the load by -F, the bending moment by
    (-omega^2 + i omega alpha) I Theta; (3) at the spring the section load equals the spring's reaction; (4) the
    reactions plus the load balance the inertia and mass-proportional damping forces of the whole shaft (force and
    moment about x = 0).  Then a free-vibration time history (three modes superposed exactly): (1) and (4) at every
    sample, the tolerance there 1e-8 (the modes' own residuals, ~1e-11)."""
    from discrete.linear import Damping, modal_analysis

    name = "loads-fe-equilibrium"
    omega, F0, alpha, beta = 900.0, 200.0, 2.0, 1e-5
    damping = Damping(type="rayleigh", alpha=alpha, beta=beta)
    out = []
    for physics, theory, order in THEORIES + (("torsion", "euler-bernoulli", 1), ("torsion", "euler-bernoulli", 2)):
        what = _label(physics, theory, order)
        bending = physics == "bending"
        segs = [Segment(0.6, 8, Section.circle(0.05), STEEL, psi=0.2), Segment(0.9, 12, Section.circle(0.03), ALU)]
        model = ShaftModel(physics, segs, [Support(0.0, "clamped"), Support(1.5, "spring", k=1e5, kr=50.0 if bending else 0.0)],
                           [PointAttachment(0.6, mass=3.0 if bending else 0.0, inertia=0.02)], theory=theory, order=order)
        fe = assemble(model)
        s = fe.system
        prim, rot = model.fields[0], (model.fields[1] if bending else None)
        F = np.zeros(s.n_dofs, complex)
        F[s.dof_index(field=prim, x=1.05)] = F0
        Q = harmonic_response(s, [omega], force=F, damping=damping).full[0]
        sl = section_loads(fe, Q, omega=omega, damping=damping)
        qty = "shear_force" if bending else "torque"
        out.append(check(name, "nodal equilibrium", f"largest jump at free nodes / largest load ({what})", 0.0,
                         _free_node_jumps(sl, [0.6, 1.05]), BALANCE, scale=1.0))
        at = lambda x, side, q=qty: section_loads(fe, Q, omega=omega, damping=damping, x=[x], side=side)[q][0]
        i_m = s.dof_index(field=prim, x=0.6)
        inertia = (-omega**2 + 1j * omega * alpha) * (3.0 if bending else 0.02) * Q[i_m]
        scale = float(np.max(np.abs(sl[qty])))
        out.append(check(name, "nodal equilibrium", f"|jump of {qty} at the point mass - (-w^2 + i w alpha) m W| ({what})",
                         0.0, abs(at(0.6, "right") - at(0.6, "left") - inertia), BALANCE, scale=scale))
        out.append(check(name, "nodal equilibrium", f"|jump of {qty} at the load + F| ({what})", 0.0,
                         abs(at(1.05, "right") - at(1.05, "left") + F0), BALANCE, scale=scale))
        R = support_reactions(fe, Q, omega=omega, force=F, damping=damping)
        out.append(check(name, "nodal equilibrium", f"|{qty} at the spring - its reaction| ({what})", 0.0,
                         abs(at(1.5, "left") - R[f"spring:{prim}@x=1.5"]), BALANCE, scale=scale))
        if bending:
            i_r = s.dof_index(field=rot, x=0.6)
            rot_inertia = (-omega**2 + 1j * omega * alpha) * 0.02 * Q[i_r]
            Ms = float(np.max(np.abs(sl["bending_moment"])))
            out.append(check(name, "nodal equilibrium", f"|jump of bending moment at the point mass - (-w^2 + i w alpha) "
                             f"I Theta| ({what})", 0.0,
                             abs(at(0.6, "right", "bending_moment") - at(0.6, "left", "bending_moment") - rot_inertia),
                             BALANCE, scale=Ms))
        out += _balance(name, fe, Q, F, R, (-omega**2 + 1j * omega * alpha) * Q, what, bending)
        # a free-vibration time history: q = sum phi_r cos(w_r t), exact velocities and accelerations
        modes = modal_analysis(s, 3)
        t = np.linspace(0.0, 0.01, 7)
        c = np.cos(np.outer(modes.omega_rad_s, t))
        sn = np.sin(np.outer(modes.omega_rad_s, t))
        q = modes.shapes @ c
        qd = -modes.shapes @ (modes.omega_rad_s[:, None] * sn)
        qdd = -modes.shapes @ (modes.omega_rad_s[:, None] ** 2 * c)
        tl = section_loads(fe, q, qd=qd, qdd=qdd)
        out.append(check(name, "nodal equilibrium (time history)", f"largest jump at free nodes / largest load ({what})",
                         0.0, _free_node_jumps(tl, [0.6]), 1e-8, scale=1.0))
        Rt = support_reactions(fe, q, qd=qd, qdd=qdd)
        out += _balance(name, fe, q, np.zeros_like(q), Rt, qdd, what + ", time history", bending, tol=1e-8)
    return out


def _balance(name, fe, q, F, R, acc, what, bending, tol=BALANCE):
    """Reactions + applied loads = inertia forces (and mass-proportional damping in ``acc``) of the whole shaft."""
    s = fe.system
    F = np.asarray(F).reshape(s.n_dofs, -1)
    acc = np.asarray(acc).reshape(s.n_dofs, -1)
    Rv = np.zeros_like(acc)
    for label, value in R.items():
        field_name, x = label.split(":")[-1].split("@x=")
        Rv[s.dof_index(field=field_name, x=float(x))] += value
    checks = []
    rigid = [("force", _rigid(s, False)), ("moment about x = 0", _rigid(s, True))] if bending else \
        [("torque", np.ones(s.n_dofs))]
    for label, r in rigid:
        ext = r @ (F + Rv)
        inert = r @ (s.M @ acc)
        scale = max(float(np.max(np.abs(ext))), float(np.max(np.abs(inert))), float(np.max(np.abs(r @ F))))
        checks.append(check(name, "global balance", f"|sum of reactions and loads - inertia| ({label}, {what})", 0.0,
                            float(np.max(np.abs(ext - inert))), tol, scale=scale))
    return checks


@case("loads-fe-rotor-equilibrium", group="loads")
def equilibrium_rotor():
    """Unbalance responses of the shipped rotors (rotor_friswell_damped: discs, two bearings; rotor_compressor:
    discs, bearings on pedestals, a seal), at 5 speeds: the two elements at every node without a disc, bearing
    or unbalance agree, and the bearing, pedestal and support reactions plus the unbalance forces balance the
    inertia and gyroscopic forces of the whole rotor (forces along y and z, moments about y and z at x = 0), to
    round-off (1e-10 of the largest force)."""
    from fem.loads import rotor_reactions
    from fem.rotor.response import unbalance_load, unbalance_response
    from fem.study import Study
    from validation.examples import EXAMPLES

    name = "loads-fe-rotor-equilibrium"
    out = []
    for file in ("rotor_friswell_damped.toml", "rotor_compressor.toml"):
        study = Study.load(EXAMPLES / file)
        rs = study.rotor
        from fem.modelfile.build import rotor as build_rotor

        spec = build_rotor.response_spec(study.doc)
        speeds = np.linspace(spec.speeds[0], spec.speeds[-1], 5)
        res = unbalance_response(rs, spec.unbalances, speeds, find_peaks=False)
        Q = res.response.T
        sl = rotor_section_loads(rs, Q, omega=speeds)
        Fu = unbalance_load(rs, spec.unbalances)
        attached = sorted({d.x for d in rs.rotor.discs} | {b.x for b in rs.rotor.bearings}
                          | {float(rs.dof_x[i]) for i in np.flatnonzero(Fu)})
        out.append(check(name, "nodal equilibrium", f"largest jump at free nodes / largest load ({file})", 0.0,
                         _free_node_jumps(sl, attached), BALANCE, scale=1.0))
        F = Fu[:, None] * speeds[None, :] ** 2
        R = rotor_reactions(rs, Q, omega=speeds, force=F)
        ext = F.copy()
        nd = rs.node_dofs
        ped = {p.name: rs.node_x.size * len(rs.fields) + 2 * i for i, p in enumerate(rs.rotor.pedestals)}
        for b_no, b in enumerate(rs.rotor.bearings, 1):
            key = f"{b.name or f'bearing {b_no}'}@x={b.x:g}"
            if b.pedestal is None:          # a bearing to ground: its force is an external force on the shaft
                node = rs.node(b.x)
                ext[nd["v"][node]] += R[key + ":F_y"]
                ext[nd["w"][node]] += R[key + ":F_z"]
        for p in rs.rotor.pedestals:
            ext[ped[p.name]] += R[f"pedestal {p.name}:F_y"]
            ext[ped[p.name] + 1] += R[f"pedestal {p.name}:F_z"]
        for label, value in R.items():
            if "@x=" in label and ":" not in label:
                field_name, x = label.split("@x=")
                ext[rs.dof(float(x), field_name)] += value
        inertia = rs.M @ (-(speeds**2) * Q) + (rs.G @ (1j * speeds * Q)) * speeds
        for label, direction, rotation in (("force along y", "v", None), ("force along z", "w", None),
                                           ("moment about z at x = 0", "v", "theta_z"),
                                           ("moment about y at x = 0", "w", "theta_y")):
            r = np.zeros(rs.n_dofs)
            mask = np.isin(rs.dof_field, (direction, "pedestal_" + direction))
            r[mask] = rs.dof_x[mask] if rotation else 1.0
            if rotation:
                r[rs.dof_field == rotation] = 1.0 if rotation == "theta_z" else -1.0
            scale = max(float(np.max(np.abs(r @ F))), float(np.max(np.abs(r @ inertia))))
            out.append(check(name, "global balance", f"|reactions + unbalance - inertia| ({label}, {file})", 0.0,
                             float(np.max(np.abs(r @ ext - r @ inertia))), BALANCE, scale=scale))
    return out


@case("loads-fe-rotor-gravity", group="loads")
def rotor_gravity():
    """A uniform steel rotor (L = 1.2 m, d = 60 mm, Timoshenko elements, 12 of them) on rigid supports at both ends
    with a disc (30 kg) at 0.4 m, deflected by its weight (g = 9.81 m/s^2 along -z): the bending moment
    M_y(x) = p x (L - x) / 2 + P x (L - a) / L (x < a; P a (L - x) / L beyond), p = -rho A g, P = -m g, and the
    shear V_z = dM_y/dx (3D convention) at element ends and inside the elements, M_z = V_y = 0; the supports carry
    the weight.  Statically determinate: exact for any mesh, round-off only."""
    from fem.loads import rotor_reactions
    from fem.rotor import Disc, Rotor, ShaftSegment, Support as RotorSupport, assemble_rotor
    from fem.rotor import static_deflection as rotor_static

    name = "loads-fe-rotor-gravity"
    L, d, a, m, g = 1.2, 0.06, 0.4, 30.0, 9.81
    rotor = Rotor([ShaftSegment(L, 12, d, STEEL)], discs=[Disc(a, m, 0.1, 0.2)],
                  supports=[RotorSupport(0.0), RotorSupport(L)])
    rs = assemble_rotor(rotor)
    gvec = (0.0, 0.0, -g)
    q = rotor_static(rs, gravity=gvec).displacement
    p, P = -STEEL.rho * math.pi * d**2 / 4 * g, -m * g
    ends = rotor_section_loads(rs, q, gravity=gvec)
    inner_x = np.linspace(0.03, L - 0.03, 20)            # 0.03 + 0.06 k: none of them a node (h = 0.1 m)
    inner = rotor_section_loads(rs, q, gravity=gvec, x=inner_x)

    def exact(x, side):
        right = (x > a) | ((x == a) & (side == "right"))
        M = p * x * (L - x) / 2 + np.where(right, P * a * (L - x) / L, P * x * (L - a) / L)
        V = p * (L / 2 - x) + np.where(right, -P * a / L, P * (L - a) / L)
        return M, V

    out = []
    for sl, what in ((ends, "element ends"), (inner, "inside elements")):
        M_ex, V_ex = exact(np.round(sl.x, 12), np.asarray(sl.side))
        scale_M, scale_V = abs(p) * L**2 / 8 + abs(P) * L / 4, abs(p) * L / 2 + abs(P)
        out.append(check(name, SRC, f"max |M_y - exact| / M_max ({what})", 0.0,
                         float(np.max(np.abs(sl["bending_moment_y"] - M_ex))), ROUNDOFF, scale=scale_M))
        out.append(check(name, SRC, f"max |V_z - exact| / V_max ({what})", 0.0,
                         float(np.max(np.abs(sl["shear_force_z"] - V_ex))), ROUNDOFF, scale=scale_V))
        out.append(check(name, SRC, f"max |M_z| + |V_y| (no load in the x-y plane, {what})", 0.0,
                         float(np.max(np.abs(sl["bending_moment_z"])) + np.max(np.abs(sl["shear_force_y"]))), ROUNDOFF,
                         scale=scale_M))
    R = rotor_reactions(rs, q, force=rs.gravity_load(gvec))
    out.append(check(name, SRC, "support reaction at x = 0 along z [N]", -(p * L / 2 + P * (L - a) / L),
                     float(R["w@x=0"]), ROUNDOFF))
    out.append(check(name, SRC, "support reaction at x = L along z [N]", -(p * L / 2 + P * a / L),
                     float(R[f"w@x={L:g}"]), ROUNDOFF))
    return out
