"""Loads of lumped drives as outputs (issue 25; docs/outputs.md): element forces, gear forces and reactions
recovered from the solved motion against independent references -- the balance of every body with the
solver's own accelerations, the constraint forces recomputed from the state, the hand-assembled K and M of
a linearised mesh, statics, and the solver's exact friction work."""
from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from fem.loads.analyses import time_outputs
from fem.study import Study
from validation.examples import example_doc
from validation.registry import case, check, claim

SRC = "issue 25 (docs/outputs.md)"
GEARED = "geared_mesh.toml"


def _balance(study, res) -> float:
    """max over bodies and recorded instants of |I a - sum of the output loads on the body| / scale."""
    loads = study.time_loads
    out = time_outputs(loads.map, res.t, res.x, res.v, res.acceleration, res.element_forces, res.applied)
    names = study.lumped.names
    _, T = study.lumped.transformation()
    acc = T @ res.acceleration
    worst = 0.0
    for b in study.lumped.bodies:
        f = b.inertia * acc[names.index(b.name)]
        terms = [(c.acts_on[b.name], out.values[k]) for k, c in enumerate(out.channels) if b.name in c.acts_on]
        total = sum(w * y for w, y in terms)
        scale = max([np.max(np.abs(f))] + [np.max(np.abs(w * y)) for w, y in terms])
        worst = max(worst, float(np.max(np.abs(f - total)) / scale))
    return worst


@case("loads-lumped-geared-mesh", group="loads")
def geared_mesh():
    """examples/geared_mesh.toml (motor - coupling - pinion - mesh with backlash - wheel - output shaft - drum
    - brake).  (a) Every body balances at every recorded instant: inertia times the solver's acceleration (the
    equations of each exact piece) equals the sum of the output loads on it (coupling and shaft forces from k,
    c and the ratios, the gap's law, the mesh damper, the brake's friction): round-off, tolerance 1e-9 of the
    loads' scale.  (b) The brake's friction work from the sampled force and speed equals the solver's exact
    friction work (its energy balance, integrated in closed form per piece): the trapezoid rule on 1e-4 s
    samples, tolerance 1e-4.  (c) The mean mesh force over the last 0.25 s equals the statics, brake torque /
    wheel radius = 50 / 0.15 N: the lightly damped first mode (49 rad/s) excited while the ripple sets in
    still rings, tolerance 1 %.  (d) drivefem modal's three frequencies with the mesh closed (linearise =
    "closed") equal the roots of det(K - w^2 M) of K, M assembled here by hand from the file's numbers
    (the mesh a spring k along s = 0.15 phi_w - 0.05 phi_p), 1e-10."""
    name = "loads-lumped-geared-mesh"
    out = []
    st = Study.parse(example_doc(GEARED))
    res = st.simulate()
    out.append(check(name, SRC, "body balance: max |I a - sum of loads| / scale", 0.0, _balance(st, res), 1e-9,
                     scale=1.0))
    o = st.outputs(res)
    F = o.column("mesh force")
    sel = res.t >= res.t[-1] - 0.25
    from discrete.loads import time_mean

    out.append(check(name, "statics: brake torque / wheel radius", "mean mesh force over the last 0.25 s [N]",
                     50.0 / 0.15, time_mean(res.t[sel], F[sel]), 1e-2))
    out.append(check(name, "the solver's exact friction work (energy balance)", "friction work of the brake [J]",
                     res.work_parts["friction"], o.elements["brake"]["friction_work"], 1e-4))
    r = st.modal()
    k, kc, ks = 2.0e8, 2.0e4, 5.0e3
    rp, rw = 0.05, 0.15
    K = np.array([[kc + k * rp * rp, -k * rp * rw, 0.0], [-k * rp * rw, k * rw * rw + ks, -ks], [0.0, -ks, ks]])
    w = np.sqrt(sla.eigh(K, np.diag([0.02, 0.5, 2.0]), eigvals_only=True))
    for j in range(3):
        out.append(check(name, "hand-assembled K, M of the closed mesh", f"omega_{j + 1} [rad/s]", w[j],
                         r.omega_rad_s[j], 1e-10))
    out.append(claim(name, SRC, "drivefem modal names the mesh as closed",
                     any(x["element"] == "mesh" and x["state"] == "closed" for x in st.linearisation)))
    return out


@case("loads-lumped-gap-drive-modal", group="loads")
def gap_drive_modal():
    """The issue's repro: driver motor, bodies pinion 0.02 and wheel 0.5, spring motor-pinion 2e4,
    [[gap]] pinion-wheel ratios [0.05, 0.15], k = 2e8, delta = 5e-5.  drivefem modal takes the mesh closed
    (the default), a spring 2e8 along s: both frequencies equal the roots of the hand-assembled
    det(K - w^2 M), 1e-12 (two symmetric 2x2 eigenproblems in double precision).  The preloaded strand of
    examples/discrete_strand_spool.toml is taut at rest: the spool's frequency is the file's k = 54.15 rad/s
    (k_strand r^2 / J), 1e-12."""
    name = "loads-lumped-gap-drive-modal"
    doc = {"driver": [{"name": "motor"}], "body": [{"name": "pinion", "inertia": 0.02}, {"name": "wheel", "inertia": 0.5}],
           "spring": [{"between": ["motor", "pinion"], "k": 2e4}],
           "gap": [{"name": "mesh", "between": ["pinion", "wheel"], "ratios": [0.05, 0.15], "k": 2e8, "delta": 5e-5}],
           "analysis": {"type": "modal"}}
    r = Study.parse(doc).modal()
    K = np.array([[2e4 + 2e8 * 0.05 ** 2, -2e8 * 0.05 * 0.15], [-2e8 * 0.05 * 0.15, 2e8 * 0.15 ** 2]])
    w = np.sqrt(sla.eigh(K, np.diag([0.02, 0.5]), eigvals_only=True))
    out = [check(name, "hand-assembled K, M", f"omega_{j + 1} [rad/s]", w[j], r.omega_rad_s[j], 1e-12) for j in range(2)]
    rs = Study.parse(example_doc("discrete_strand_spool.toml")).modal()
    out.append(check(name, "seed 002: k = 54.15 1/s (the file's header)", "spool on the taut strand [rad/s]", 54.15,
                     rs.omega_rad_s[0], 1e-12))
    return out


@case("loads-lumped-multipliers-and-reactions", group="loads")
def multipliers_and_reactions():
    """Seed 000 (examples/discrete_seed000_stick_slip.toml): in every stick phase the bit's friction output is
    the Lagrange multiplier of the stick constraint, recomputed here from each recorded state by solving the
    constrained equations again (Problem.evaluate in the stick mode), 1e-9 relative (round-off).  A driver of
    inertia J = 0.3 moving A sin(w t) through a spring k to a body with friction: its reaction output equals
    J a_d(t) - k (x_b - x_d) from its law and the recorded positions, 1e-9."""
    name = "loads-lumped-multipliers-and-reactions"
    st = Study.parse(example_doc("discrete_seed000_stick_slip.toml"))
    res = st.simulate()
    o = st.outputs(res)
    p = st.problem_spec().problem()
    ev = [(e.t, e.kind) for e in res.events if e.element == "bit" and e.kind in ("stick", "slip", "reversal")]
    mask = np.zeros(res.t.size, dtype=bool)
    for (t0, k0), (t1, _) in zip(ev, ev[1:]):
        if k0 == "stick":
            mask |= (res.t > t0) & (res.t < t1)
    ks = np.flatnonzero(mask)
    lam = np.array([p.evaluate(res.t[k], res.x[p.f, k][:, None], res.v[p.f, k][:, None],
                               p.basis(res.t[k])[:, None], (0,))["F"][0, 0] for k in ks])
    F = o.column("bit.force")[ks]
    out = [claim(name, SRC, "seed 000 has stick samples", ks.size > 10),
           check(name, "the stick multiplier recomputed from the state", "max |F_out - lambda| / max |F|", 0.0,
                 float(np.max(np.abs(F - lam)) / np.max(np.abs(F))), 1e-9, scale=1.0)]
    J, k, A, w = 0.3, 400.0, 0.02, 7.0
    doc = {"driver": [{"name": "crank", "inertia": J, "amplitude": A, "omega": w}],
           "body": [{"name": "slider", "inertia": 1.5}], "spring": [{"between": ["crank", "slider"], "k": k}],
           "friction": [{"name": "guide", "body": "slider", "kinetic": 0.5, "static": 0.8}],
           "simulation": {"t_end": 3.0, "output_step": 0.01}}
    s2 = Study.parse(doc)
    r2 = s2.simulate()
    R = J * (-A * w * w * np.sin(w * r2.t)) - k * (r2.x[r2.names.index("slider")] - r2.x[r2.names.index("crank")])
    Ro = s2.outputs(r2).column("crank.reaction")
    out.append(check(name, "J a_d - k (x_b - x_d)", "max |R_out - R| / max |R|", 0.0,
                     float(np.max(np.abs(Ro - R)) / np.max(np.abs(R))), 1e-9, scale=1.0))
    return out
