"""Seed 002 amplitude-frequency curve for one cam amplitude: continuation vs brute-force time integration.

Baseline (the paper's method): at each of 200 frequencies z = 0.3 .. 2.0 the exact event-driven
integrator runs whole forcing periods until the stroboscopic state repeats to 1e-9 (at most 400
periods), sweeping z downwards and starting each frequency from the previous final state (this catches
the upper branch up to the left fold of the softening resonance); mu = T_max/F0 over the last period.
It is the package's fastest exact path: :class:`~discrete.steady.ShootingModel` keeps one solver per
frequency, so its exact pieces (matrix exponentials etc.) are built once per frequency, not once per
period (``--legacy-baseline`` also times the old per-period rebuild, for comparison with earlier
figures).
Package: HB (15 harmonics, AFT) + pseudo-arc-length continuation over the same range, plus Floquet
stability of every point, folds refined, the unstable branch included (ds_max = 0.1: 144 points).

Accuracy: both peaks are compared with a reference peak mu* -- the maximum of mu over z of the HB upper
branch found by bounded scalar maximisation and confirmed by exact shooting (difference printed).  The
continuation's peak is the one the AFC reports (``AFCResult.peak()``: the maximum located along the
branch by parabolic interpolation in arc length, each trial point a corrected HB orbit), the brute
force's the largest of its frequencies.
"Equal accuracy": the continuation's peak error must not exceed the brute-force one; ``--coarse``
(default 0.5) also times the continuation at a larger step (fewer points: 42) and says whether it
still meets it (a second record).

Timing (benchmarks/common.py): BLAS single-threaded for both sides (threadpoolctl; the BLAS in use is
printed), one untimed warm-up of each side, then --repeat runs of the package side and
--repeat-baseline runs of the baseline (default 3: a run takes ~6 s of CPU), interleaved; medians and
the range (min .. max) of CPU time (process time: what the method costs, robust on a shared machine)
and of wall time are printed, the ratio from both; ``BENCH-RESULT`` records for benchmarks/report.py.
``--profile`` prints where the package side's time goes (stages and the functions' own time).

    python benchmarks/afc.py [--a 4.7e-4] [--repeat 5] [--repeat-baseline 3] [--coarse 0.5]
                             [--profile] [--legacy-baseline] [--figure docs/img/seed002_afc.png]
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE))

import common  # noqa: E402

common.limit_blas_threads(1)

import numpy as np  # noqa: E402

from discrete.steady import HBModel, ShootingModel  # noqa: E402
from fem.study import forced, steady_model  # noqa: E402
from validation.analytic.steady_seed002 import AMPLITUDES, K_NAT, seed002_doc  # noqa: E402


def brute_force(a, zs, reuse=True):
    sm = steady_model(seed002_doc(a, "simple"))
    sh = ShootingModel(sm.factory, steps_per_period=48, reuse=reuse)
    y = np.zeros(2)
    mus = []
    for z in zs[::-1]:
        w = z * K_NAT
        y, _, _ = sh.settle(y, w, periods=400, tol=1e-9, scale=np.array([0.01, 0.5]))
        _, res = sh.run(y, w, dense=True)
        p = sh.problem(w)
        mus.append(sm.measure(res.t, res.x[p.f], res.v[p.f], w))
    return np.array(mus[::-1])


def continuation(a, ds_max, **steady):
    return forced(seed002_doc(a, "simple", z=(0.3, 2.0), ds_max=ds_max, **steady))


def reference_peak(a, r):
    from scipy.optimize import minimize_scalar

    sm = steady_model(seed002_doc(a, "simple"))
    hb = HBModel(sm.system, harmonics=15)
    i = int(np.argmax(r.response))
    state = {"X": r.states[i]}

    def neg_mu(w):
        X, _ = hb.solve(state["X"], w)
        state["X"] = X
        t, q, v = hb.evaluate(X, w, points=8192)
        return -sm.measure(t, q, v, w)

    lo, hi = r.omega[max(i - 2, 0)], r.omega[min(i + 2, r.omega.size - 1)]
    res = minimize_scalar(neg_mu, bounds=(min(lo, hi), max(lo, hi)), method="bounded", options={"xatol": 1e-9})
    w = float(res.x)
    neg_mu(w)
    t, q, v = hb.evaluate(state["X"], w, points=hb.N)
    sh = ShootingModel(sm.factory)
    y, _ = sh.solve(np.array([q[0, 0], v[0, 0]]), w, np.array([0.02, 1.0]))
    _, out = sh.run(y, w, dense=True)
    p = sh.problem(w)
    mu_shoot = sm.measure(out.t, out.x[p.f], out.v[p.f], w)
    return w / K_NAT, -float(res.fun), mu_shoot


def spread(xs):
    """'median s (min .. max, n runs)' (the form benchmarks/report.py reads when no record is printed)."""
    return f"{statistics.median(xs):8.3f} s ({min(xs):.3f} .. {max(xs):.3f}, {len(xs)} run{'s' if len(xs) > 1 else ''})"


def times_line(t: "common.Timing") -> str:
    return f"cpu {spread(t.cpu)}   wall {spread(t.wall)}"


def profile_split(fn, top: int = 12) -> str:
    """Where the package side's time goes: one profiled run (cProfile, process time; it inflates every
    share alike), cumulative shares of the stages and the functions with the largest own time."""
    import cProfile
    import pstats

    pr = cProfile.Profile(time.process_time)
    pr.enable()
    fn()
    pr.disable()
    st = pstats.Stats(pr)
    total = max(st.total_tt, 1e-300)
    parts = {"arclength (predictor/corrector/tangent)": "arclength", "HB residual+Jacobian evaluations": "evaluate_residual",
             "Floquet (batched)": "floquet_hb_batch", "fold refinement": "refine_fold",
             "response measure": "measure_hb", "dense linear solves (numpy)": "solve"}
    cum = {}
    for (file, _, func), (_, nc, _, ct, _) in st.stats.items():
        for label, name in parts.items():
            if func == name and ("linalg" in file if name == "solve" else "steady" in file):
                cum[label] = (cum.get(label, (0, 0.0))[0] + nc, cum.get(label, (0, 0.0))[1] + ct)
    lines = [f"  {label:42s} {cum[label][1] / total:6.1%}  ({cum[label][0]} calls)" for label in parts if label in cum]
    own = sorted(st.stats.items(), key=lambda kv: -kv[1][2])[:top]
    lines.append(f"  own time, top {top} (profiled total {total:.3f} s):")
    for (file, line, func), (_, nc, tt, _, _) in own:
        where = f"{Path(file).parent.name}/{Path(file).name}:{line}" if line else file
        lines.append(f"    {tt / total:6.1%}  {nc:7d} calls  {func}  ({where})")
    return "package-side profile (share of one profiled run):\n" + "\n".join(lines)


def main(argv=None):
    from threadpoolctl import threadpool_limits

    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--a", type=float, default=4.7e-4)
    ap.add_argument("--points", type=int, default=200)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--repeat-baseline", type=int, default=3)
    ap.add_argument("--ds-max", type=float, default=0.1)
    ap.add_argument("--coarse", type=float, default=0.5,
                    help="also time the continuation at this ds_max (0: do not); default 0.5 (42 points)")
    ap.add_argument("--profile", action="store_true", help="print where the package side's time goes")
    ap.add_argument("--legacy-baseline", action="store_true",
                    help="also time the baseline with a fresh solver per period (the cost before the reuse)")
    ap.add_argument("--figure", default=None, help="write the AFC figure of all four amplitudes (both models)")
    args = ap.parse_args(argv)
    zs = np.linspace(0.3, 2.0, args.points)
    common.header(__file__, f"seed 002 AFC, {args.points} frequencies: continuation (HB + Floquet) vs brute-force "
                            "time sweeps (exact event-driven)")
    if args.repeat_baseline < common.MIN_RUNS:
        print(f"note: the brute-force baseline is timed {args.repeat_baseline} time(s) only (about 6 s of CPU per run, "
              f"minutes of wall time on a loaded machine); the package side {args.repeat} times; the runs interleave")
    cands = {"continuation": lambda: continuation(args.a, args.ds_max),
             "brute force": lambda: brute_force(args.a, zs)}
    runs_of = {"brute force": args.repeat_baseline}
    if args.coarse:
        cands["coarse continuation"] = lambda: continuation(args.a, args.coarse)
    if args.legacy_baseline:
        cands["legacy brute force"] = lambda: brute_force(args.a, zs, reuse=False)
        runs_of["legacy brute force"] = 1
    with threadpool_limits(1):
        brute_force(args.a, zs[:1])                        # warm-up (imports, compiled kernels)
        continuation(args.a, args.ds_max, max_steps=2)
        tm = common.interleaved(cands, runs=args.repeat, runs_of=runs_of)
        split = profile_split(cands["continuation"]) if args.profile else None
    r, mus = tm["continuation"].result, tm["brute force"].result
    tc, tb = tm["continuation"], tm["brute force"]
    z_ref, mu_ref, mu_shoot = reference_peak(args.a, r)
    e_b = abs(mus.max() - mu_ref) / mu_ref
    e_c = abs(r.peak()[1] - mu_ref) / mu_ref          # the AFC's reported peak (located along the branch)
    print(f"seed 002 AFC, a = {args.a:g} m, simplified friction, z = 0.3..2.0")
    print(f"reference peak: z* = {z_ref:.5f}, mu* = {mu_ref:.6f} (HB maximisation; exact shooting there: "
          f"{mu_shoot:.6f}, difference {abs(mu_shoot - mu_ref) / mu_ref:.1e})")
    print(f"brute force  : {args.points} frequencies, down-sweep, exact event-driven, peak mu {mus.max():.6f} at "
          f"z = {zs[int(np.argmax(mus))]:.4f}, peak error {e_b:.2e}")
    print(f"               {times_line(tb)}")
    print(f"continuation : {r.omega.size} branch points (ds_max {args.ds_max:g}), {len(r.folds)} folds, Floquet "
          f"stability of every point, peak mu {r.peak()[1]:.6f} (located), peak error {e_c:.2e}")
    print(f"               {times_line(tc)}")
    print(f"equal accuracy: continuation error {'<=' if e_c <= e_b else '>'} brute-force error")
    rw, rc = common.speedup(tb, tc)
    print(f"ratio (brute force / continuation): {rc:.1f}x cpu, {rw:.1f}x wall (target >= 100x)")
    coarse_rec = None
    if args.coarse:
        tcc = tm["coarse continuation"]
        rr = tcc.result
        e_cc = abs(rr.peak()[1] - mu_ref) / mu_ref
        rwc, rcc = common.speedup(tb, tcc)
        print(f"coarse continuation: ds_max {args.coarse:g}, {rr.omega.size} points, peak error {e_cc:.2e} "
              f"({'<=' if e_cc <= e_b else '>'} brute force), {times_line(tcc)}; ratio {rcc:.1f}x cpu, {rwc:.1f}x wall")
        coarse_rec = common.record(__file__, f"seed 002 AFC, a = {args.a:g} m, {args.points} frequencies, "
                                   f"coarse continuation (ds_max {args.coarse:g}, {rr.omega.size} points)",
                                   "continuation (HB + Floquet)", "brute-force time sweeps (exact event-driven)", rwc,
                                   (">=", 100), ratio_cpu=rcc, accuracy="peak error vs the reference peak",
                                   accuracy_package=e_cc, accuracy_baseline=e_b,
                                   runs={"package": tcc.runs, "baseline": tb.runs},
                                   spread={"package": tcc.spread_dict(), "baseline": tb.spread_dict()})
    if args.legacy_baseline:
        tl = tm["legacy brute force"]
        rwl, rcl = common.speedup(tl, tc)
        print(f"legacy baseline (fresh solver per period): {times_line(tl)}, same mu to "
              f"{np.max(np.abs(tl.result - mus) / mus):.1e}; ratio vs continuation {rcl:.1f}x cpu, {rwl:.1f}x wall")
    if split:
        print(split)
    rec = common.record(__file__, f"seed 002 AFC, a = {args.a:g} m, {args.points} frequencies",
                        "continuation (HB + Floquet)", "brute-force time sweeps (exact event-driven)", rw, (">=", 100),
                        ratio_cpu=rc, accuracy="peak error vs the reference peak", accuracy_package=e_c,
                        accuracy_baseline=e_b, runs={"package": tc.runs, "baseline": tb.runs},
                        spread={"package": tc.spread_dict(), "baseline": tb.spread_dict()})
    for x in (rec, coarse_rec):
        if x:
            common.print_summary(x)
            common.emit(x)
    if args.figure:
        figure(args.figure)


def figure(path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from fem.output.figures import plot_afc

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), sharey=True)
    for ax, fr, title in ((axes[0], "simple", "simplified (viscous) friction, Fig. 4"),
                          (axes[1], "combined", "combined power-law friction, Fig. 5")):
        for a in AMPLITUDES:
            r = forced(seed002_doc(a, fr, z=(0.3, 2.0)))
            plot_afc(r, None, ax=ax, label=f"a = {a:g} m")
        if fr == "simple":   # the period-2 zone at a = 8.6e-4: shooting (subharmonic = 2) continued from z = 1.18
            for zr in ((1.18, 1.4), (1.18, 1.0)):
                r2 = forced(seed002_doc(8.6e-4, fr, z=zr, method="shooting", subharmonic=2, ds=0.05,
                                            ds_max=0.1, max_steps=40))
                plot_afc(r2, None, ax=ax, label="a = 0.00086 m, period 2T (shooting)" if zr[1] > 1.18 else "_nolegend_")
        ax.set_title(title)
        ax.set_xlabel("z = omega1 / k")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_ylabel("mu = T_max / F0 (period-1 branch; dashed: unstable)")
    fig.suptitle("Seed 002: HB + arc-length continuation, Floquet stability (dashed = unstable; "
                 "z > 1 dashed: period doubling -> period-2 zone)", fontsize=9)
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"figure written: {path}")


if __name__ == "__main__":
    main()
