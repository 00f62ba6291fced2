"""Seed 002 amplitude-frequency curve for one cam amplitude: continuation vs brute-force time integration.

Baseline (the paper's method): at each of 200 frequencies z = 0.3 .. 2.0 the exact event-driven
integrator runs whole forcing periods until the stroboscopic state repeats to 1e-9 (at most 400
periods), sweeping z downwards and starting each frequency from the previous final state (this catches
the upper branch up to the left fold of the softening resonance); mu = T_max/F0 over the last period.
Package: HB (15 harmonics, AFT) + pseudo-arc-length continuation over the same range, plus Floquet
stability, about 200 branch points (ds_max chosen so), folds and the unstable branch included.

Accuracy: both peaks are compared with a reference peak mu* -- the maximum of mu over z of the HB upper
branch found by bounded scalar maximisation and confirmed by exact shooting (difference printed).  The
continuation's step is set so its peak error is not larger than the brute-force one ("equal accuracy").
Prints the medians of --repeat runs (the baseline once unless --repeat-baseline) and the ratio.

    python benchmarks/afc.py [--a 4.7e-4] [--repeat 3] [--figure docs/img/seed002_afc.png]
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from discrete.steady import HBModel, ShootingModel  # noqa: E402
from fem.study import forced, steady_model
from validation.analytic.steady_seed002 import AMPLITUDES, K_NAT, seed002_doc  # noqa: E402


def brute_force(a, zs):
    sm = steady_model(seed002_doc(a, "simple"))
    sh = ShootingModel(sm.factory, steps_per_period=48)
    y = np.zeros(2)
    mus = []
    for z in zs[::-1]:
        w = z * K_NAT
        y, _, _ = sh.settle(y, w, periods=400, tol=1e-9, scale=np.array([0.01, 0.5]))
        _, res = sh.run(y, w, dense=True)
        p = sh.problem(w)
        mus.append(sm.measure(res.t, res.x[p.f], res.v[p.f], w))
    return np.array(mus[::-1])


def continuation(a, ds_max):
    return forced(seed002_doc(a, "simple", z=(0.3, 2.0), ds_max=ds_max))


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


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--a", type=float, default=4.7e-4)
    ap.add_argument("--points", type=int, default=200)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--repeat-baseline", type=int, default=1)
    ap.add_argument("--figure", default=None, help="write the AFC figure of all four amplitudes (both models)")
    args = ap.parse_args(argv)
    zs = np.linspace(0.3, 2.0, args.points)
    tb = []
    for _ in range(args.repeat_baseline):
        t0 = time.perf_counter()
        mus = brute_force(args.a, zs)
        tb.append(time.perf_counter() - t0)
    ds_max = 0.1
    tc = []
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        r = continuation(args.a, ds_max)
        tc.append(time.perf_counter() - t0)
    z_ref, mu_ref, mu_shoot = reference_peak(args.a, r)
    e_b = abs(mus.max() - mu_ref) / mu_ref
    e_c = abs(r.response.max() - mu_ref) / mu_ref
    print(f"seed 002 AFC, a = {args.a:g} m, simplified friction, z = 0.3..2.0")
    print(f"reference peak: z* = {z_ref:.5f}, mu* = {mu_ref:.6f} (HB maximisation; exact shooting there: "
          f"{mu_shoot:.6f}, difference {abs(mu_shoot - mu_ref) / mu_ref:.1e})")
    print(f"brute force  : {args.points} frequencies, down-sweep, median {statistics.median(tb):8.3f} s, "
          f"peak mu {mus.max():.6f} at z = {zs[int(np.argmax(mus))]:.4f}, peak error {e_b:.2e}")
    print(f"continuation : {r.omega.size} branch points, {len(r.folds)} folds, Floquet stability, median "
          f"{statistics.median(tc):8.3f} s, peak mu {r.response.max():.6f}, peak error {e_c:.2e}")
    print(f"equal accuracy: continuation error {'<=' if e_c <= e_b else '>'} brute-force error")
    print(f"ratio (brute force / continuation): {statistics.median(tb) / statistics.median(tc):.1f}x (target >= 20x)")
    if args.figure:
        figure(args.figure)


def figure(path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from discrete.steady import plot_afc

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
