"""A 200-point sweep (seed 002 map, examples/sweep_seed002.toml: 4 cam amplitudes x 50 frequencies, each
point time integration + shooting + Floquet): a local Dask cluster with 2 workers against the serial run
of the same points, in the same process tree (``fem.app.sweep.run_sweep``).  Both write their points to
temporary directories; the results are checked identical, then the ratio serial / Dask is printed
(target >= 1.6x on 2 cores).

Timing (benchmarks/common.py): serial and Dask runs interleaved round by round (the order alternating),
median and spread of ``--runs`` runs after one untimed run of each; the Dask time includes the LocalCluster start-up, unless
``--warm-cluster``: then one LocalCluster (the settings of run_sweep: one single-threaded process per
worker) is started once, its start-up timed and printed apart, and each Dask run connects to it as
``drivefem sweep --scheduler`` does (what ``make bench`` uses with a smaller sweep, to stay within its
time budget: 5 runs of the 200-point sweep take about 5 minutes).  Only wall time
makes sense here: the Dask work runs in worker processes, whose CPU time this process does not see (the
serial run's CPU time is printed for reference).  A parallel speed-up needs idle cores: with a load
average above the core count the ratio says more about the other processes than about the package,
and the script says so.

    python benchmarks/sweep.py [--workers 2] [--periods 100] [--frequencies 50] [--runs 5] [--warm-cluster]
"""
from __future__ import annotations

import argparse
import json
import os
import re
import sys
import tempfile
from pathlib import Path

import common

ROOT = common.ROOT
sys.path.insert(0, str(ROOT))

from fem.app.sweep import run_sweep  # noqa: E402

TARGET = 1.6


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--periods", type=int, default=100, help="integration periods per point before shooting")
    ap.add_argument("--frequencies", type=int, default=50, help="frequencies per cam amplitude (4 amplitudes)")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--warm-cluster", action="store_true", help="start the Dask cluster once, outside the timing")
    args = ap.parse_args(argv)
    common.header(__file__, f"sweep, serial vs a local Dask cluster of {args.workers} workers")
    text = (ROOT / "examples" / "sweep_seed002.toml").read_text()
    text = re.sub(r"^periods = \d+", f"periods = {args.periods}", text, flags=re.M)
    text = re.sub(r"points = 50 \}", f"points = {args.frequencies} }}", text)
    load0 = common.load_average()
    with tempfile.TemporaryDirectory() as tmp, open(os.devnull, "w") as quiet:
        model = Path(tmp) / "sweep.toml"
        model.write_text(text)
        count = {"serial": 0, "dask": 0}

        def runner(kind, workers, scheduler=None):
            def run():
                k = count[kind]
                count[kind] += 1
                js = Path(tmp) / f"{kind}{k}.json"
                code = run_sweep(model, out=Path(tmp) / f"{kind}{k}", workers=workers, json_path=js, progress=False,
                                 stream=quiet, scheduler=scheduler)
                return code, js
            return run

        cluster, startup = None, None
        if args.warm_cluster:
            from dask.distributed import LocalCluster

            one = {k: "1" for k in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")}
            startup, _, cluster = common.timed(lambda: LocalCluster(
                n_workers=args.workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                dashboard_address=None, silence_logs=40, env=one))
            print(f"LocalCluster of {args.workers} workers started once: {startup:.2f} s wall (not in the timed runs)")
        try:
            tm = common.interleaved({"serial": runner("serial", 0),
                                     "dask": runner("dask", args.workers, cluster.scheduler_address if cluster else None)},
                                    runs=args.runs, warmup=1, verbose=True)
        finally:
            if cluster is not None:
                cluster.close()
        (c1, js1), (c2, js2) = tm["serial"].result, tm["dask"].result
        s = json.load(open(js1))["points"]
        d = json.load(open(js2))["points"]
    n = len(s)
    ok = sum(r["status"] == "ok" for r in s)
    same = s == d
    ratio = tm["serial"].wall_stats.median / tm["dask"].wall_stats.median
    load1 = common.load_average()
    cores = os.cpu_count() or 1
    print(f"sweep of {n} points ({ok} ok), {args.periods} periods each; exit codes serial {c1}, dask {c2}")
    print(f"results identical (serial vs {args.workers} Dask workers): {same}")
    print(f"serial      : {tm['serial'].line()}")
    print(f"dask x {args.workers}    : median {tm['dask'].wall_stats.fmt()} wall ("
          + (f"a warm cluster, start-up {startup:.2f} s apart" if startup is not None else "LocalCluster start-up included")
          + "; the workers' CPU time is not visible here)")
    print(f"ratio (serial / dask): {ratio:.2f}x wall (target >= {TARGET:g}x on {cores} cores)")
    if load0 and max(load0[0], (load1 or load0)[0]) > cores:
        print(f"NOTE: load average {load0[0]:.1f} -> {(load1 or load0)[0]:.1f} on {cores} cores: other processes held "
              f"the cores the Dask workers need; this ratio is not the package's parallel efficiency")
    rec = common.record(
        __file__, f"sweep of {n} points (seed 002 map, {args.periods} periods per point), wall time "
        + (f"on a warm cluster (start-up {startup:.1f} s once)" if startup is not None else "incl. cluster start-up"), f"Dask, {args.workers} workers", "serial", ratio, (">=", TARGET),
        accuracy="points ok; results identical to the serial run", accuracy_package=f"{ok}/{n}; {same}",
        accuracy_baseline=f"{ok}/{n}", runs=args.runs,
        spread={"package": tm["dask"].spread_dict(), "baseline": tm["serial"].spread_dict()})
    print()
    common.print_summary(rec)
    common.emit(rec)
    return 0 if rec["met"] and same else 1


if __name__ == "__main__":
    sys.exit(main())
