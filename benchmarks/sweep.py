"""A 200-point sweep (seed 002 map, examples/sweep_seed002.toml: 4 cam amplitudes x 50 frequencies, each
point time integration + shooting + Floquet): a local Dask cluster with 2 workers against the serial run
of the same points, in the same process tree.  Both write their points to temporary directories; the
results are checked identical, then the ratio serial / Dask is printed (target >= 1.6x on 2 cores).

    python benchmarks/sweep.py [--workers 2] [--periods 100] [--repeat 1]
"""
from __future__ import annotations

import argparse
import json
import re
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from fem.sweep import run_sweep  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--periods", type=int, default=100)
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args(argv)
    text = (ROOT / "examples" / "sweep_seed002.toml").read_text()
    text = re.sub(r"^periods = \d+", f"periods = {args.periods}", text, flags=re.M)
    with tempfile.TemporaryDirectory() as tmp:
        model = Path(tmp) / "sweep.toml"
        model.write_text(text)
        ts, td = [], []
        for k in range(args.repeat):
            t0 = time.perf_counter()
            c1 = run_sweep(model, out=Path(tmp) / f"serial{k}", workers=0, json_path=Path(tmp) / f"s{k}.json",
                           progress=False)
            ts.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            c2 = run_sweep(model, out=Path(tmp) / f"dask{k}", workers=args.workers, json_path=Path(tmp) / f"d{k}.json",
                           progress=False)
            td.append(time.perf_counter() - t0)
        s = json.load(open(Path(tmp) / "s0.json"))["points"]
        d = json.load(open(Path(tmp) / "d0.json"))["points"]
        n = len(s)
        ok = sum(r["status"] == "ok" for r in s)
    print(f"sweep of {n} points ({ok} ok), exit codes serial {c1}, dask {c2}")
    print(f"results identical (serial vs {args.workers} Dask workers): {s == d}")
    print(f"serial      : median {statistics.median(ts):8.2f} s")
    print(f"dask x {args.workers}    : median {statistics.median(td):8.2f} s (LocalCluster start-up included)")
    print(f"ratio (serial / dask): {statistics.median(ts) / statistics.median(td):.2f}x (target >= 1.6x on 2 cores)")


if __name__ == "__main__":
    main()
