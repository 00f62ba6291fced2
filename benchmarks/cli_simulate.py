"""``drivefem simulate`` end to end (issue 25): events per second of the command line on seed 000 with
k* = 2 (examples/discrete_seed000_stick_slip.toml as shipped: output_step = 0.02 s), writing its outputs
-- the JSON summary with the named outputs (element loads, reactions, their peak/rms/DLF) and the time
history with the loads in the HDF5 container (--h5) -- against the command line of release 890424e
(writing its JSON), in the same run.

Timing: long minus short.  Each program runs the model at two end times (``--short``, ``--long``; the
release at its own, shorter pair: it is ~100x slower) as separate processes, all four interleaved round
by round; the rate of one round is (events_long - events_short) / (wall_long - wall_short), so the
start-up (interpreter, imports, numba's cached kernel, building the model) cancels.  Medians and spread
over ``--runs`` rounds; process CPU time (the children's rusage) alongside.  Target: >= 25x the
release's rate (issue 25).

    python benchmarks/cli_simulate.py [--runs 5] [--short 300] [--long 6000] [--old-short 150]
                                      [--old-long 900] [--commit 890424e]
"""
from __future__ import annotations

import argparse
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import common

ROOT = common.ROOT
MODEL = ROOT / "examples" / "discrete_seed000_stick_slip.toml"
PRE_ISSUE = "890424e"


def model_at(t_end: float, directory: Path) -> Path:
    """The example with ``t_end`` replaced (everything else as shipped)."""
    text = MODEL.read_text()
    new, n = re.subn(r"(?m)^t_end = .*$", f"t_end = {t_end!r}", text)
    if n != 1:
        raise RuntimeError(f"{MODEL}: expected one 't_end = ..' line, found {n}")
    p = directory / f"seed000_{t_end:g}.toml"
    p.write_text(new)
    return p


def runner(label: str, cmd: list[str], env: dict, cwd: Path, json_path: Path):
    """A candidate of common.interleaved: one process; its wall time, the children's CPU time, and the
    number of events its JSON reports."""
    def run() -> common.Measured:
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        p = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=3600)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if p.returncode != 0:
            raise RuntimeError(f"{label}: exit {p.returncode}\n{p.stderr[-2000:]}")
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        d = json.loads(json_path.read_text())
        return common.Measured(wall, cpu, int(d.get("n_events", len(d.get("events", [])))))
    return run


def rates(tm: dict, short: str, long: str, attr: str) -> list[float]:
    """(events_long - events_short) / (time_long - time_short) of each round."""
    n = tm[long].result - tm[short].result
    a, b = getattr(tm[short], attr), getattr(tm[long], attr)
    return [n / (tl - ts) if tl > ts else float("nan") for ts, tl in zip(a, b)]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--short", type=float, default=300.0, help="short end time of the package, s")
    ap.add_argument("--long", type=float, default=6000.0, help="long end time of the package, s")
    ap.add_argument("--old-short", type=float, default=150.0, help="short end time of the release, s")
    ap.add_argument("--old-long", type=float, default=900.0, help="long end time of the release, s")
    ap.add_argument("--commit", default=PRE_ISSUE, help="the release compared with")
    a = ap.parse_args(argv)
    common.header(__file__, "drivefem simulate end to end (JSON + --h5 with the loads), seed 000 k* = 2")
    work = Path(tempfile.mkdtemp(prefix="drivefem-cli-bench-"))
    env = dict(os.environ, PYTHONPATH=str(ROOT), OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    cands = {}
    for tag, t_end in (("package short", a.short), ("package long", a.long)):
        m = model_at(t_end, work)
        j, h = work / f"{tag.replace(' ', '_')}.json", work / f"{tag.replace(' ', '_')}.h5"
        cands[tag] = runner(tag, [sys.executable, "-m", "fem.app.cli", "simulate", str(m), "--json", str(j),
                                  "--h5", str(h)], env, ROOT, j)
    old = None
    try:
        old = common.old_release(a.commit)
    except RuntimeError as e:
        print(f"release {a.commit} NOT available: {e}")
    if old is not None:
        env_old = dict(env, PYTHONPATH=str(old))
        for tag, t_end in (("release short", a.old_short), ("release long", a.old_long)):
            m = model_at(t_end, work)
            j = work / f"{tag.replace(' ', '_')}.json"
            cands[tag] = runner(tag, [sys.executable, "-m", "fem.cli", "simulate", str(m), "--json", str(j)], env_old,
                                old, j)
    tm = common.interleaved(cands, runs=a.runs, warmup=1)
    print(f"\n{'run':<16} {'t_end [s]':>9} {'events':>7} {'wall [s] median [min-max]':>30} {'cpu [s] median [min-max]':>28}")
    ends = {"package short": a.short, "package long": a.long, "release short": a.old_short,
            "release long": a.old_long}
    for name, t in tm.items():
        print(f"{name:<16} {ends[name]:9g} {t.result:7d} {t.wall_stats.fmt():>30} {t.cpu_stats.fmt():>28}")
    pkg_w, pkg_c = rates(tm, "package short", "package long", "wall"), rates(tm, "package short", "package long", "cpu")
    pw, pc = statistics.median(pkg_w), statistics.median(pkg_c)
    print(f"\npackage: {pw:,.0f} events/s wall [{min(pkg_w):,.0f}-{max(pkg_w):,.0f}], {pc:,.0f} events/s cpu "
          f"(long minus short, {len(pkg_w)} rounds)")
    recs = [common.record(__file__, "drivefem simulate end to end, seed 000 k* = 2 (JSON + --h5 with loads), "
                          "long minus short", "drivefem simulate (CLI)", None, pw, None, metric="events/s",
                          unit="events/s", ratio_cpu=pc, runs=len(pkg_w),
                          spread={"package": {"wall": [pw, min(pkg_w), max(pkg_w)], "cpu": [pc, min(pkg_c), max(pkg_c)]}})]
    if old is not None:
        old_w, old_c = rates(tm, "release short", "release long", "wall"), rates(tm, "release short", "release long", "cpu")
        ow, oc = statistics.median(old_w), statistics.median(old_c)
        print(f"release {a.commit}: {ow:,.0f} events/s wall [{min(old_w):,.0f}-{max(old_w):,.0f}], {oc:,.0f} events/s "
              f"cpu\nratio: {pw / ow:.1f}x wall, {pc / oc:.1f}x cpu (target >= 25x)")
        recs.append(common.record(
            __file__, f"drivefem simulate end to end vs release {a.commit}, seed 000 k* = 2, events/s long minus short",
            "drivefem simulate (JSON + --h5, loads)", f"release {a.commit} (JSON)", pw / ow, (">=", 25),
            ratio_cpu=pc / oc, runs=min(len(pkg_w), len(old_w)),
            spread={"package": {"wall": [pw, min(pkg_w), max(pkg_w)]},
                    "baseline": {"wall": [ow, min(old_w), max(old_w)]}}))
    else:
        recs.append(common.record(__file__, f"drivefem simulate end to end vs release {a.commit} (NOT available)",
                                  "drivefem simulate", f"release {a.commit}", None, (">=", 25)))
    print()
    return common.finish(recs)


if __name__ == "__main__":
    sys.exit(main())
