"""Hybrid benchmark (issue 4): reduced vs full FE model at equal accuracy, and events per second.

Case 4 (vibro-impact cantilever, examples/hybrid_vibro_impact_beam.toml): the full FE model is the
reference; the Craig-Bampton model with the fewest modes whose impact-force peak is within 1 % of
the full model's is timed against it (interleaved repetitions, medians; ratios are stable on a
shared machine, absolute times are not).  Events per second: the reduced vibro-impact run and the
drill string (case 1, stick-slip with reversals).

    python benchmarks/hybrid.py [--reps 3] [--elements 4]
"""
from __future__ import annotations

import argparse
import pathlib
import statistics
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from fem.study import simulate  # noqa: E402
from validation.cases.hybrid_drill_string import variant as drill_variant  # noqa: E402
from validation.cases.hybrid_vibro_impact import impact_metrics, variant  # noqa: E402


def timed(doc):
    t0 = time.perf_counter()
    m = impact_metrics(doc)
    return time.perf_counter() - t0, m


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--elements", type=int, default=4, help="elements on the 0..0.45 m segment (+1 tip element)")
    args = ap.parse_args(argv)
    n = args.elements
    t_full, full = timed(variant(None, elements=n))
    print(f"full model ({n + 1} Hermite elements, {full['result'].compiled.system.n_dofs} DOFs): "
          f"impact peak {full['peak']:.6g} N, tip amplitude {full['amp']:.6g} m, {t_full:.2f} s")
    chosen = None
    for modes in range(1, 9):
        t_red, red = timed(variant(modes, elements=n))
        err = abs(red["peak"] / full["peak"] - 1)
        print(f"  {modes} mode(s): peak error {err:.2e}, amplitude error {abs(red['amp'] / full['amp'] - 1):.2e}, "
              f"{t_red:.3f} s")
        if err <= 0.01:
            chosen = modes
            break
    if chosen is None:
        print("no reduced model reached 1 % within 8 modes")
        return 1
    tf, tr = [t_full], []
    for _ in range(args.reps):
        tr.append(timed(variant(chosen, elements=n))[0])
        if len(tf) < args.reps:
            tf.append(timed(variant(None, elements=n))[0])
    mf, mr = statistics.median(tf), statistics.median(tr)
    print(f"equal accuracy (1 % in the impact-force peak): {chosen} mode(s)")
    print(f"wall time full {mf:.3f} s, reduced {mr:.3f} s (medians of {len(tf)}/{len(tr)}): ratio {mf / mr:.1f}x "
          "(target >= 20x)")
    # events per second
    t0 = time.perf_counter()
    r = simulate(variant(chosen, t_end=2.0, elements=n))
    dt = time.perf_counter() - t0
    print(f"vibro-impact, reduced: {len(r.events)} events in {dt:.3f} s = {len(r.events) / dt:.0f} events/s")
    t0 = time.perf_counter()
    r = simulate(drill_variant(0.01, 8, 2, t_end=40.0))
    dt = time.perf_counter() - t0
    print(f"drill string, reduced (2 modes): {len(r.events)} events in {dt:.3f} s = {len(r.events) / dt:.0f} events/s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
