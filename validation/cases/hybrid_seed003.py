"""Hybrid case 2: seed 003's three examples (rod, shaft, beam on a rough plane, distributed dry
friction, harmonic forcing) by Moreau-Jean time stepping of the FE model against the
equivalent-damping amplitude (6)/(12)."""
from __future__ import annotations

import math

import numpy as np

from fem.modelfile.source import read_toml
from validation.analytic.hybrid_refs import seed003_amplitude, seed003_modes, seed003_printed_factor
from validation.registry import case, check, claim
from validation.examples import EXAMPLES

STEEL = {"E": 2.0e11, "G": 8.0e10, "rho": 8000.0}
D = 0.02
GRAV = 9.81
RATIO = 0.6            # p / omega_1
ROD_EXAMPLE = EXAMPLES / "hybrid_seed003_rod.toml"


def example(kind: str, beta: float, *, elements: int = 20, periods: int = 20, steps: int = 200,
            mu: float = 0.3) -> dict:
    """Model dict for seed 003 example ``kind`` ('rod', 'shaft', 'beam') with the force amplitude set so
    that the friction ratio beta = 4R/(pi F) of (6) takes the given value, and the references."""
    A = math.pi * D ** 2 / 4
    Ip = math.pi * D ** 4 / 32
    I = math.pi * D ** 4 / 64
    rho = STEEL["rho"]
    if kind == "rod":
        md = seed003_modes("rod", 1.0, STEEL["E"] * A, rho * A)
        q = mu * GRAV * rho * A
        physics, dof, xj, sup = "axial", "u", 1.0, [{"x": 0.0, "type": "clamped"}]
        fr = {"name": "plane", "mu": mu}
    elif kind == "shaft":
        md = seed003_modes("shaft", 1.0, STEEL["G"] * Ip, rho * Ip)
        q = mu * GRAV * rho * A * (D / 2)            # friction torque per length on the shaft's surface
        physics, dof, xj, sup = "torsion", "theta", 1.0, [{"x": 0.0, "type": "clamped"}]
        fr = {"name": "plane", "mu": mu, "radius": D / 2}
    elif kind == "beam":
        md = seed003_modes("beam", 1.0, STEEL["E"] * I, rho * A)
        q = mu * GRAV * rho * A
        physics, dof, xj, sup = "bending", "w", 0.5, [{"x": 0.0, "type": "pinned"}, {"x": 1.0, "type": "pinned"}]
        fr = {"name": "plane", "mu": mu}
    else:
        raise ValueError(kind)
    R = q * md["abs_integral"]
    F0 = 4 * R / (math.pi * beta)
    p = RATIO * md["omega"]
    T = 2 * math.pi / p
    sim = {"method": "moreau", "dt": T / steps, "t_end": periods * T, "samples": periods * steps}
    if kind == "rod":          # examples/hybrid_seed003_rod.toml with the force amplitude of beta and the run
        doc = read_toml(ROD_EXAMPLE)
        doc["segment"][0]["elements"] = elements
        doc["distributed_friction"][0]["mu"] = mu
        doc["force"][0].update(amplitude=F0, phase=math.pi / 2)
        doc["simulation"].update(sim)
    else:
        model = {"physics": physics}
        if physics != "bending":
            model.update({"order": 1, "mass": "lumped"})
        doc = {"title": f"seed 003 {kind}, beta = {beta}", "material": dict(STEEL), "model": model,
               "segment": [{"length": 1.0, "elements": elements, "section": {"shape": "circle", "d": D}}],
               "support": sup, "distributed_friction": [fr],
               "force": [{"x": xj, "dof": dof, "amplitude": F0, "omega": p, "phase": math.pi / 2}],
               "initial": {"state": "linear_steady_state"}, "simulation": sim}
    return {"doc": doc, "modes": md, "R": R, "F0": F0, "p": p, "T": T, "xj": xj, "dof": dof,
            "formula": seed003_amplitude(md["m"], md["k"], p, F0 * float(md["X"](xj)), R),
            "printed": seed003_amplitude(md["m"], md["k"], p, F0 * float(md["X"](xj)), R * seed003_printed_factor(kind))}


def first_harmonic(t, y, p, t0, t1) -> float:
    sel = (t >= t0 - 1e-12) & (t <= t1 + 1e-12)
    tt, yy = t[sel], y[sel]
    span = tt[-1] - tt[0]
    a = 2 / span * np.trapezoid(yy * np.cos(p * tt), tt)
    b = 2 / span * np.trapezoid(yy * np.sin(p * tt), tt)
    return float(np.hypot(a, b))


def run_example(kind: str, beta: float, **kw) -> dict:
    """Time-integrate the FE model and return the first-mode steady amplitude (first harmonic of the
    modal coordinate, last 5 periods), the same over the 5 periods before (steadiness), the stuck
    share of the forced DOF's history, and the formula."""
    return run_example_doc(example(kind, beta, **kw))


def run_example_doc(ex: dict) -> dict:
    from fem.study import simulate
    from discrete.linear.modal import modal_analysis

    r = simulate(ex["doc"])
    sys_ = r.fe.system
    phi = modal_analysis(sys_, 1).shapes[:, 0]
    j = sys_.dof_index(field=ex["dof"], x=ex["xj"])
    phi = phi / phi[j] * float(ex["modes"]["X"](ex["xj"]))
    M = sys_.M
    q1 = (r.field_history @ (M @ phi)) / (phi @ (M @ phi))
    t, T = r.t, ex["T"]
    amp = first_harmonic(t, q1, ex["p"], t[-1] - 5 * T, t[-1])
    prev = first_harmonic(t, q1, ex["p"], t[-1] - 10 * T, t[-1] - 5 * T)
    vj = np.gradient(r.field_history[:, j], t)
    late = t >= t[-1] - 5 * T
    stuck = float(np.mean(np.abs(vj[late]) < 1e-3 * np.max(np.abs(vj[late]))))
    return {"amp": amp, "prev": prev, "formula": ex["formula"], "printed": ex["printed"], "stuck": stuck, "energy_error": r.energy_error,
            "linear": ex["F0"] * float(ex["modes"]["X"](ex["xj"])) / abs(ex["modes"]["k"] - ex["modes"]["m"] * ex["p"] ** 2),
            "one_mode_exact": None, "ex": ex, "result": r}


def one_mode_exact(ex: dict) -> float:
    """Second reference: the single-mode model of (6) with exact Coulomb friction R (not its
    equivalent damping), integrated by the event-driven solver; first harmonic of the steady state."""
    from discrete.linear_system import LinearSystem
    from discrete.nonsmooth import ExternalForce, Friction, Options, Problem, simulate

    md = ex["modes"]
    F = ex["F0"] * float(md["X"](ex["xj"]))
    ls = LinearSystem(M=np.array([[md["m"]]]), K=np.array([[md["k"]]]), dof_field=["x"])
    x0 = F / (md["k"] - md["m"] * ex["p"] ** 2)
    prob = Problem(ls, [Friction("f", np.ones(1), kinetic=ex["R"])],
                   forces=[ExternalForce(np.ones(1), amplitude=F, omega=ex["p"], phase=math.pi / 2)], x0=np.array([x0]))
    T = ex["T"]
    r = simulate(prob, 30 * T, Options(max_step=T / 100))
    sel = r.t >= r.t[-1] - 5 * T
    tu = np.linspace(r.t[sel][0], r.t[-1], 4001)
    yu = np.interp(tu, r.t[sel], r.x[0][sel])
    return first_harmonic(tu, yu, ex["p"], tu[0], tu[-1])


@case("hybrid_seed003", group="hybrid")
def hybrid_seed003():
    """Seed 003 examples 1-3: steel rod (cantilever, longitudinal), shaft (cantilever, torsion),
    beam (simply supported, bending), d = 20 mm, l = 1 m, on a rough plane (f = 0.3, intensity
    f P / l at every node with its tributary weight; torsion: times the radius), harmonic force at
    the tip (mid-span for the beam) at p = 0.6 omega_1, started from the frictionless steady state;
    Moreau-Jean (theta = 1/2, 200 steps per period, 20 periods); the first-mode amplitude is the
    first harmonic of the modal coordinate (M-orthogonal projection on the FE mode 1, scaled like the
    seed's X) over the last 5 periods.  Reference: (6)/(12), A = sqrt(F^2 - (4R/pi)^2)/|k - m p^2|,
    re-derived (equal dissipated work per period); the friction ratio beta = 4R/(pi F) sets F.

    Inside the validity region (beta = 0.1: small friction, no stops) the tolerance is 1.5 %: the
    equivalent linearisation itself errs by 0.3 % there (against the exact single-mode Coulomb
    solution, computed here by the event-driven solver), the FE frequency error (20 linear lumped
    elements: (pi h/2l)^2/24 = 2.6e-4, amplified 3x by the resonance factor 2/(1 - 0.36)) and the
    time step ((omega h)^2/12 = 2.5e-4) add < 0.2 %, and the distributed friction (nodes near a
    support move less, stop longer at reversals, and add stiffness while stuck) another ~0.5 %
    (measured 0.75 % rod).  At beta = 0.3 the tolerance is 6 % (the linearisation alone errs by
    4.7 % there).  The steady state is checked (last two 5-period windows agree to 0.5 %), and the
    energy balance of the time stepper closes to 1e-9.  Reduced model (rod, beta = 0.3, 4 free-interface
    modes, friction acting through the modal values T^T g at every node): within 0.5 % of the full
    model (the first omitted mode at 9 omega_1 responds quasi-statically with < 0.3 % of the
    amplitude; measured 2.8e-4).  The breakdown study is the slow case
    hybrid_seed003_breakdown.  The rod is examples/hybrid_seed003_rod.toml (there F0 = 20 N, beta = 0.30,
    25 periods); each run sets F0 of its beta, the phase pi/2 to the last digit and its run length."""
    out = []
    src = "seed 003 (6)/(12) (re-derived)"
    for kind in ("rod", "shaft", "beam"):
        r = run_example(kind, 0.1)
        out.append(check("hybrid_seed003", src, f"{kind}: first-mode amplitude, beta = 0.1", r["formula"], r["amp"],
                         0.015, note=f"linear (no friction) {r['linear']:.4e}"))
        out.append(check("hybrid_seed003", "steady state", f"{kind}: amplitude, last vs previous 5 periods",
                         r["prev"], r["amp"], 0.005))
        out.append(check("hybrid_seed003", "energy balance (Moreau-Jean)", f"{kind}: energy error", 0.0,
                         r["energy_error"], 1e-9, scale=1.0))
        fac = seed003_printed_factor(kind)
        out.append(check("hybrid_seed003", "seed 003 (9) as printed (series coefficient a_1 for q |X_1|)",
                         f"{kind}: R_printed / R (mode 1)", 4 / math.pi, fac, 1e-12))
    r = run_example("rod", 0.3)
    out.append(check("hybrid_seed003", src, "rod: first-mode amplitude, beta = 0.3", r["formula"], r["amp"], 0.06))
    e_cor, e_pr = r["formula"] / r["amp"] - 1, r["printed"] / r["amp"] - 1
    out.append(claim("hybrid_seed003", "seed 003 (6)/(9) as printed vs re-derived",
                     "rod, beta = 0.3: the printed coefficients err more than the re-derived ones (against FE)",
                     abs(e_pr) > abs(e_cor) + 0.02,
                     note=f"re-derived {e_cor:+.3%}, printed {e_pr:+.3%} (printed friction 4/pi larger)"))
    ex3 = example("rod", 0.3)
    ex3["doc"]["reduction"] = {"modes": 4, "static_correction": False}
    red = run_example_doc(ex3)
    out.append(check("hybrid_seed003", "full FE model (rod, beta = 0.3)",
                     "reduced (4 free-interface modes) vs full: first-mode amplitude", r["amp"], red["amp"], 0.005,
                     note=f"{len(red['result'].warnings)} low-restitution warnings near the clamp (expected: "
                          "free-interface modes restore little flexibility where the rod hardly moves)"))
    out.append(claim("hybrid_seed003", "restitution report", "free-interface reduction warns about low restitution",
                     any("restores only" in w for w in red["result"].warnings)))
    ex = example("rod", 0.1)
    exact = one_mode_exact(ex)
    out.append(check("hybrid_seed003", "exact single-mode Coulomb solution (event-driven)",
                     "rod: equivalent linearisation error at beta = 0.1", exact, ex["formula"], 0.005))
    return out


@case("hybrid_seed003_breakdown", group="hybrid", slow=True)
def hybrid_seed003_breakdown():
    """Where formula (6)/(12) breaks down: friction ratio beta = 4R/(pi F) = 0.1, 0.3, 0.6, 0.86 for
    the three examples.  Reported: the formula's error against the FE model, its error against the
    exact single-mode Coulomb solution (the linearisation's own error) and the FE model's departure
    from that single-mode solution.  Measured: the formula underestimates the FE amplitude by 0.8,
    4.1, 16, 30 % (rod, shaft) and 0.7, 5, 20, 44 % (beam); the linearisation alone errs by 0.3, 4.7,
    20, 47 %; the distributed friction of the FE rod departs from the single-mode model by 25 % at
    beta = 0.86 (nodes near the clamp move little and stick).  The formula predicts no
    motion at all for beta >= 1 while the FE model still moves (Den Hartog: the exact non-stop
    response exists beyond the equivalent-damping limit).  Checks: the error grows monotonically
    with beta and exceeds 10 % by beta = 0.6 (the formula is not usable there); the FE model agrees
    with the single-mode exact solution within 1 % at beta = 0.1.  Side by side, the paper's (6) with its
    printed coefficient (9) (first-mode friction 4/pi too large, see seed003_printed_factor): its error
    against the FE model at every beta, larger than the re-derived form's; it predicts no motion from
    beta = pi/4 = 0.785 on, the re-derived form from beta = 1."""
    out = []
    for kind in ("rod", "shaft", "beam"):
        errs, notes, printed_notes, printed_worse = [], [], [], []
        for beta in (0.1, 0.3, 0.6, 0.86):
            r = run_example(kind, beta)
            ex = r["ex"]
            exact = one_mode_exact(ex)
            e = r["formula"] / r["amp"] - 1
            errs.append(e)
            ep = r["printed"] / r["amp"] - 1 if math.isfinite(r["printed"]) else float("nan")
            printed_notes.append(f"beta {beta}: re-derived {e:+.3f}, printed {ep:+.3f}")
            printed_worse.append(not math.isfinite(ep) or abs(ep) > abs(e))
            notes.append(f"beta {beta}: formula/FE - 1 = {e:+.3f}, formula/one-mode exact - 1 = "
                         f"{r['formula'] / exact - 1:+.3f}, FE/one-mode exact - 1 = {r['amp'] / exact - 1:+.3f}")
            if beta == 0.1:
                out.append(check("hybrid_seed003_breakdown", "exact single-mode Coulomb solution",
                                 f"{kind}: FE amplitude, beta = 0.1", exact, r["amp"], 0.01))
        out.append(claim("hybrid_seed003_breakdown", "seed 003 (6)/(12)",
                         f"{kind}: formula error grows with friction and exceeds 10 % at beta = 0.6",
                         all(abs(a) < abs(b) for a, b in zip(errs, errs[1:])) and abs(errs[2]) > 0.1,
                         note="; ".join(notes)))
        out.append(claim("hybrid_seed003_breakdown", "seed 003 (6)/(9) as printed vs re-derived",
                         f"{kind}: printed coefficients err more at every beta and predict no motion from "
                         "beta = pi/4 (re-derived: from beta = 1); the FE model still moves at beta = 0.86",
                         all(printed_worse) and not math.isfinite(r["printed"]) and r["amp"] > 0,
                         note="formula/FE - 1: " + "; ".join(printed_notes)))
    return out
