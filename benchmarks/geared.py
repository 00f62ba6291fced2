"""Geared-train benchmark (issue 26).

1. Modal analysis and Campbell diagram of a geared train of three shafts with >= 600 elements against a dense
   solve of the same matrices (target >= 50x each).  The train: the high-speed pinion shaft of
   examples/geared_compressor_train.toml as a rotor (Timoshenko, 6 DOFs per node, ``--rotor`` elements) meshing
   with a bull-gear shaft and coupled to a motor shaft, both FE torsion shafts (``--torsion`` elements each);
   20 modes at the operating speed, and a 21-speed Campbell diagram (0 .. 2000 rev/min of the motor) with mode
   tracking and critical speeds.  Baseline: scipy.linalg.eig of the dense first-order form of the same
   M, C + Omega G, K on the free DOFs (all eigenvalues; what a dense code does at each speed).  The dense solve
   is timed once per run (``--dense-runs``, it takes minutes); the Campbell diagram's baseline is 21 of them
   (one per speed, stated).  The lowest 20 frequencies of both are compared (accuracy column).
2. Gear rattle: examples/geared_rattle.toml lightly loaded (5 N m mean torque, 14 N m ripple at 16 000 rad/s:
   impacts on both flanks), 0.5 s with the exact event-driven solver; events per second of CPU time
   (target >= 5000).

    python benchmarks/geared.py [--runs 3] [--rotor 150] [--torsion 225] [--dense-runs 1] [--quick]
"""
from __future__ import annotations

import argparse
import math
import sys

import numpy as np

import common

common.limit_blas_threads(1)

ROOT = common.ROOT
sys.path.insert(0, str(ROOT))

from fem.modelfile.source import read_toml  # noqa: E402
from fem.study import Study  # noqa: E402

RPM = math.pi / 30


def train_doc(n_rotor: int, n_torsion: int) -> dict:
    """Three shafts: motor (FE torsion), bull gear (FE torsion), pinion (rotor) with n elements."""
    comp = read_toml(ROOT / "examples" / "geared_compressor_train.toml")
    pin = next(s for s in comp["shaft"] if s["name"] == "pinion")
    segs = pin["rotor"]["segment"]
    base = sum(s["elements"] for s in segs)
    k = max(1, int(round(n_rotor / base)))          # an integer refinement keeps the discs on nodes
    for s in segs:
        s["elements"] *= k
    torsion = lambda name, L, d, pts, pos: {  # noqa: E731
        "name": name, "position": pos,
        "model": {"physics": "torsion", "order": 1},
        "material": {"E": 210e9, "G": 81e9, "rho": 7850.0},
        "segment": [{"length": L, "elements": n_torsion, "section": {"shape": "circle", "d": d}}],
        "point": pts}
    motor = torsion("motor", 1.2, 0.12, [{"x": 0.6, "inertia": 8.2}], [0.0, -1.0])
    bull = torsion("bull gear", 0.7, 0.13, [{"x": 0.45, "inertia": 8.0}], [0.0, 0.0])
    return {"title": "benchmark: geared train (3 shafts)",
            "train": {"reference": "motor", "speed_rpm": 1490.0},
            "shaft": [motor, bull, pin],
            "coupling": [{"name": "coupling", "between": [{"shaft": "motor", "x": 1.2}, {"shaft": "bull gear", "x": 0.0}],
                          "k_torsion": 2.5e5, "c_torsion": 30.0}],
            "mesh": [dict(comp["mesh"][0], between=[{"shaft": "bull gear", "x": 0.45}, {"shaft": "pinion", "x": 0.15}])],
            "analysis": {"speed_rpm": 1490.0, "modes": 20},
            "campbell": {"speeds_rpm": {"start": 0.0, "stop": 2000.0, "points": 21}, "modes": 20, "orders": [1.0]}}


def dense_eigenvalues(ts, speed):
    """All eigenvalues (Im >= 0, by modulus) of the dense first-order form on the free DOFs."""
    import scipy.linalg as sla

    sys_ = ts.system_at(speed)
    f = sys_.free
    M, K = sys_.M.toarray()[np.ix_(f, f)], sys_.K.toarray()[np.ix_(f, f)]
    D = (sys_.C + speed * sys_.G).toarray()[np.ix_(f, f)]
    n = f.size
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -D]])
    B = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), M]])
    lam = sla.eig(A, B, right=False)
    lam = lam[np.isfinite(lam) & (lam.imag >= 0)]
    return lam[np.argsort(np.abs(lam))]


def modal_and_campbell(args) -> list[dict]:
    doc = train_doc(args.rotor, args.torsion)
    study = Study.parse(doc)
    ts = study.train
    n_el = sum(sum(g.elements for g in s.model.segments) for s in ts.train.shafts)
    speed = 1490.0 * RPM
    n_free = ts.n_dofs - ts.constrained.size
    print(f"train: {len(ts.blocks)} shafts, {n_el} elements, {n_free} free DOFs (dense first-order form "
          f"{2 * n_free} x {2 * n_free})", flush=True)

    def package_modal():
        st = Study.parse(doc)           # a fresh train: no workspace reused from another run
        return st.modal(20)

    def package_campbell():
        st = Study.parse(doc)
        return st.campbell(20)

    def dense():
        return dense_eigenvalues(ts, speed)

    t = common.interleaved({"package modal": package_modal, "package Campbell": package_campbell, "dense": dense},
                           runs=args.runs, runs_of={"dense": args.dense_runs}, verbose=True)
    m = t["package modal"].result
    lam_d = t["dense"].result
    lam_d = lam_d[np.abs(lam_d) > 1e-6 * np.abs(lam_d).max()]
    lam_p = m.eigenvalues[~m.rigid]
    k = min(lam_p.size, lam_d.size, 20)
    err = float(np.max(np.abs(lam_p[:k] - lam_d[:k]) / np.abs(lam_d[:k])))
    r_modal = common.speedup(t["dense"], t["package modal"])
    dense21 = common.Timing(wall=[21 * w for w in t["dense"].wall], cpu=[21 * c for c in t["dense"].cpu])
    r_camp = common.speedup(dense21, t["package Campbell"])
    camp = t["package Campbell"].result
    print(f"package modal: {t['package modal'].line()}\npackage Campbell (21 speeds): {t['package Campbell'].line()}\n"
          f"dense eig (one speed): {t['dense'].line()}\nlowest {k} eigenvalues: max relative difference {err:.2e}; "
          f"Campbell: {len(camp.critical_speeds)} critical speeds", flush=True)
    what = f"geared train, {len(ts.blocks)} shafts, {n_el} elements, {n_free} DOFs"
    return [common.record(__file__, f"{what}: 20 complex modes", "fem.train (sparse shift-invert Arnoldi)",
                          "scipy.linalg.eig of the dense first-order form", r_modal[0], (">=", 50.0),
                          ratio_cpu=r_modal[1], accuracy="max rel. difference of the 20 lowest eigenvalues",
                          accuracy_package=err, runs=t["package modal"].runs,
                          spread={"package": t["package modal"].spread_dict(), "dense": t["dense"].spread_dict()}),
            common.record(__file__, f"{what}: Campbell diagram, 21 speeds, 20 modes", "fem.train (tracked, warm starts)",
                          "21 x scipy.linalg.eig (the dense solve timed once, times 21)", r_camp[0], (">=", 50.0),
                          ratio_cpu=r_camp[1], runs=t["package Campbell"].runs,
                          spread={"package": t["package Campbell"].spread_dict(), "dense": t["dense"].spread_dict()})]


def rattle(args) -> list[dict]:
    doc = read_toml(ROOT / "examples" / "geared_rattle.toml")
    doc["force"][0].update(value=5.0, amplitude=14.0, omega=16000.0)
    doc["simulation"] = {"t_end": args.t_end, "energy": False}
    doc.pop("steady", None)

    def run():
        return Study.parse(doc).simulate()

    run()                                           # compiles the numba kernel (untimed)
    t = common.interleaved({"rattle": run}, runs=args.runs)
    n_ev = len(t["rattle"].result.result.events)
    rate_cpu = n_ev / t["rattle"].cpu_stats.median
    rate_wall = n_ev / t["rattle"].wall_stats.median
    print(f"rattle: {n_ev} events in {args.t_end} s, {t['rattle'].line()}: {rate_cpu:.0f} events/s CPU, "
          f"{rate_wall:.0f} events/s wall", flush=True)
    return [common.record(__file__, f"gear rattle (K&S pair, impacts on both flanks, {n_ev} events)",
                          "exact event-driven solver", None, rate_wall, (">=", 5000.0), metric="events per second",
                          unit="events/s", ratio_cpu=rate_cpu, runs=t["rattle"].runs,
                          spread={"package": t["rattle"].spread_dict()})]


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--dense-runs", type=int, default=1)
    p.add_argument("--rotor", type=int, default=150, help="elements of the rotor shaft")
    p.add_argument("--torsion", type=int, default=225, help="elements of each FE torsion shaft")
    p.add_argument("--t-end", type=float, default=0.5)
    p.add_argument("--quick", action="store_true", help="the rattle part only")
    args = p.parse_args(argv)
    print(common.machine_line(), flush=True)
    recs = rattle(args)
    if not args.quick:
        recs = modal_and_campbell(args) + recs
    return common.finish(recs)


if __name__ == "__main__":
    sys.exit(main())
