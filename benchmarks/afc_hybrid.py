"""Hybrid (FE + lumped) amplitude-frequency curves: HB continuation vs brute-force time sweeps.

The two hybrid AFC examples (``examples/hybrid_afc_friction_rod.toml``: an axial rod with a dry-friction
damper at its tip, Craig-Bampton reduced; ``examples/hybrid_afc_vibro_impact.toml``: a cantilever with an
elastic stop, hardening with two folds), each on its own [steady] settings:

* package: ``drivefem forced`` of the file -- HB (AFT) + pseudo-arc-length continuation over the range,
  Floquet stability of every point, folds refined;
* brute force: 200 frequencies over the same range, swept upwards (the hardening resonance's upper branch
  up to its jump-down fold), each started from the previous final state; the exact event-driven
  integrator (true Coulomb stick-slip, exact contact switching) runs whole periods until the stroboscopic
  state repeats to 1e-9 of the state's scale (at most 400 periods), the response measured over one more
  period exactly as [steady] measures it.  The state scale of that stopping rule (per DOF, position and
  velocity) is the largest amplitude along the HB branch (an input of the baseline, not timed).

Accuracy: both peaks against a reference peak -- the maximum over omega of the *exact* periodic orbit
(shooting with the event-driven integrator, bounded scalar maximisation started at the HB peak).  HB
carries its own model error there (the friction law regularised by tanh(w / eps), AFT sampling of the
contact kink), printed as it is.

Timing as in ``benchmarks/afc.py`` (benchmarks/common.py): BLAS single-threaded (printed), a warm-up of
each side, the two sides' runs interleaved, CPU and wall medians and ranges of --repeat runs (package)
and --repeat-baseline runs (baseline: one by default, it takes minutes); one ``BENCH-RESULT`` record
per example (the vibro-impact one with issue 27's target >= 50x; the rod's ratio is reported).

    python benchmarks/afc_hybrid.py [--repeat 5] [--repeat-baseline 1] [--points 200] [--only rod|beam]
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

import common  # noqa: E402

common.limit_blas_threads(1)

import numpy as np  # noqa: E402

from afc import times_line  # noqa: E402
from discrete.steady import HBModel, ShootingModel  # noqa: E402
from fem.study import Study  # noqa: E402

EXAMPLES = {"rod": "hybrid_afc_friction_rod", "beam": "hybrid_afc_vibro_impact"}
TARGETS = {"beam": (">=", 50)}           # issue 27: the vibro-impact AFC at >= 50x brute force


def load(name):
    return Study.load(ROOT / "examples" / f"{EXAMPLES[name]}.toml")


def continuation(name):
    return load(name).forced()


def _hb(sm):
    c = sm.cfg
    return HBModel(sm.system, harmonics=c.harmonics, nu=c.subharmonic, samples=c.samples)


def state_scale(sm, r):
    """Largest |q_i|, |v_i| along the HB branch (per DOF): the stopping rule's scale."""
    hb = _hb(sm)
    qs, vs = [], []
    for x, w in zip(r.states, r.omega):
        _, q, v = hb.evaluate(x, w)
        qs.append(np.max(np.abs(q), axis=1))
        vs.append(np.max(np.abs(v), axis=1))
    sc = np.concatenate([np.max(qs, axis=0), np.max(vs, axis=0)])
    return np.maximum(sc, 1e-9 * np.max(sc))


def brute_force(name, omegas, scale):
    sm = load(name).steady_model()
    sh = ShootingModel(sm.factory, nu=sm.cfg.subharmonic, steps_per_period=sm.cfg.steps_per_period)
    y = np.zeros(sh.n)
    out, periods = [], 0
    for w in omegas:
        y, k, _ = sh.settle(y, w, periods=400, tol=1e-9, scale=scale)
        periods += k
        _, res = sh.run(y, w, dense=True)
        p = sh.problem(w)
        out.append(sm.measure(res.t, res.x[p.f], res.v[p.f], w))
    return np.array(out), periods


def reference_peak(name, r, scale):
    """(omega*, response*) of the exact periodic orbit's maximum near the HB peak."""
    from scipy.optimize import minimize_scalar

    sm = load(name).steady_model()
    hb = _hb(sm)
    sh = ShootingModel(sm.factory, nu=sm.cfg.subharmonic, steps_per_period=sm.cfg.steps_per_period)
    i = int(np.argmax(r.response))
    _, q, v = hb.evaluate(r.states[i], r.omega[i])
    state = {"y": np.concatenate([q[:, 0], v[:, 0]])}
    state["y"], _ = sh.solve(state["y"], r.omega[i], scale)

    def neg(w):
        y, _ = sh.solve(state["y"], w, scale)
        state["y"] = y
        _, res = sh.run(y, w, dense=True)
        p = sh.problem(w)
        return -sm.measure(res.t, res.x[p.f], res.v[p.f], w)

    lo, hi = r.omega[max(i - 1, 0)], r.omega[min(i + 1, r.omega.size - 1)]
    res = minimize_scalar(neg, bounds=(min(lo, hi), max(lo, hi)), method="bounded",
                          options={"xatol": 1e-7 * r.omega[i]})
    return float(res.x), -float(res.fun)


def main(argv=None):
    from threadpoolctl import threadpool_limits

    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--repeat-baseline", type=int, default=1)
    ap.add_argument("--points", type=int, default=200)
    ap.add_argument("--only", choices=sorted(EXAMPLES), default=None)
    args = ap.parse_args(argv)
    common.header(__file__, f"hybrid AFCs, {args.points} frequencies: continuation (HB + Floquet) vs brute-force "
                            "time sweeps (exact event-driven)")
    if args.repeat_baseline < common.MIN_RUNS:
        print(f"note: the brute-force baseline is timed {args.repeat_baseline} time(s) only (minutes per run); "
              f"the package side {args.repeat} times; the runs interleave")
    for name in ([args.only] if args.only else list(EXAMPLES)):
        with threadpool_limits(1):
            st = load(name)
            sm = st.steady_model()
            r0 = st.forced()                                    # warm-up, and the baseline's state scale
            scale = state_scale(sm, r0)
            omegas = np.linspace(*sm.cfg.range, args.points)
            brute_force(name, omegas[:1], scale)                # warm-up (compiled kernels)
            tm = common.interleaved({"continuation": lambda: continuation(name),
                                     "brute force": lambda: brute_force(name, omegas, scale)},
                                    runs=args.repeat, runs_of={"brute force": args.repeat_baseline})
            tc, tb = tm["continuation"], tm["brute force"]
            r, (mus, periods) = tc.result, tb.result
            w_ref, mu_ref = reference_peak(name, r, scale)
        e_b = abs(mus.max() - mu_ref) / mu_ref
        e_c = abs(r.peak()[1] - mu_ref) / mu_ref        # the AFC's reported peak (located along the branch)
        ref = sm.cfg.omega_ref or 1.0
        print(f"\n{EXAMPLES[name]}: {st.doc.title if hasattr(st.doc, 'title') else name} "
              f"(n = {sm.system.n} DOFs, {len(sm.system.elements)} element(s)); response: {sm.resp_label}")
        print(f"reference peak (exact shooting, maximised): omega* = {w_ref:.6g} rad/s"
              f"{f' (z = {w_ref / ref:.5f})' if sm.cfg.omega_ref else ''}, response {mu_ref:.6g}")
        print(f"brute force  : {args.points} frequencies {omegas[0]:.6g} .. {omegas[-1]:.6g} rad/s, up-sweep, exact "
              f"event-driven, {periods} periods in all; peak {mus.max():.6g} at {omegas[int(np.argmax(mus))]:.6g} "
              f"rad/s, peak error {e_b:.2e}")
        print(f"               {times_line(tb)}")
        print(f"continuation : {r.method}, {r.omega.size} points, {len(r.folds)} folds, "
              f"{int(np.sum(~r.stable))} unstable; peak {r.peak()[1]:.6g} (located), peak error {e_c:.2e}")
        print(f"               {times_line(tc)}")
        print(f"equal accuracy: continuation error {'<=' if e_c <= e_b else '>'} brute-force error")
        rw, rc = common.speedup(tb, tc)
        print(f"ratio (brute force / continuation): {rc:.1f}x cpu, {rw:.1f}x wall")
        rec = common.record(__file__, f"hybrid AFC, {EXAMPLES[name]} ({sm.system.n} DOFs), {args.points} frequencies",
                            "continuation (HB + Floquet)", "brute-force time sweeps (exact event-driven)", rw,
                            TARGETS.get(name),
                            ratio_cpu=rc, accuracy="peak error vs the exact (shooting) peak", accuracy_package=e_c,
                            accuracy_baseline=e_b, runs={"package": tc.runs, "baseline": tb.runs},
                            spread={"package": tc.spread_dict(), "baseline": tb.spread_dict()})
        common.print_summary(rec)
        common.emit(rec)


if __name__ == "__main__":
    main()
