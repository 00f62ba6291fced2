"""Event-driven solver speed (issue 13, item 1): events per second on seed 000 with k* = 2, against
the pre-issue release and against the same kernel without numba.

Model: seed 000 with k* = 2 velocity reversals per period (eps = M1/M0 = 6, Omega = 1; I = 2,
c = 50, M0 = 3; benchmarks/stick_slip.py's ``model``), ``--periods`` periods after the first
breakaway (200: 801 events).  Three columns, timed interleaved round by round (medians and
spread of ``--runs`` runs, wall and process-CPU time; BLAS threads 1 everywhere):

* package: ``discrete.nonsmooth.simulate`` in this process (numba kernel when numba is installed);
  targets >= 10 000 events/s and >= 25x the pre-issue release; a run of this column is the median
  of ``--block`` consecutive calls after one untimed call (steady state, like timeit; a 30 ms call
  right after the baseline's second-long run meets cold caches); the single cold call per round is
  also timed and shown ("package, single call", no target);
* baseline: the release the issue was filed against (commit 890424e), exported read-only with
  ``git archive`` and run in a subprocess with PYTHONPATH set to its tree
  (``discrete.nonsmooth.build_problem(doc)`` -> ``simulate(problem, t_end, Options())``); the same
  model and t_end; timed inside its process (import and setup excluded);
* the package with ``DRIVEFEM_JIT=0``: the same kernel source run as plain Python (no numba),
  in a subprocess (``--runs-nojit`` runs).

Accuracy, side by side: the period error against the closed form (20) (validation.analytic.seed000;
the solver's period detector, and the mean slip-to-slip interval over all cycles) and the energy
balance error of each run.  The first call in a fresh process compiles the numba kernel or loads it
from numba's on-disk cache: measured separately in fresh subprocesses (cache as found, and an
empty cache: NUMBA_CACHE_DIR set to a new directory) and not part of the timed runs.

When a target is not met (or with ``--profile``) a cProfile of the package's call shows where the
time goes: the compiled kernel's share and the Python around it.

    python benchmarks/event_solver.py [--periods 200] [--runs 5] [--runs-nojit 5] [--commit 890424e]
                                      [--block 5] [--profile]
"""
from __future__ import annotations

import argparse
import json
import sys
import tempfile

import common

common.limit_blas_threads(1)

ROOT = common.ROOT
sys.path.insert(0, str(ROOT))

from stick_slip import model  # noqa: E402

PRE_ISSUE = "890424e"

# one summary of a run, shared by all trees (the result API is the same for these attributes)
_SUMMARY = '''
def summary(r):
    slips = r.event_times("slip")
    return {"events": len(r.events), "period": None if r.period is None else float(r.period),
            "mean_period": float((slips[-1] - slips[0]) / (slips.size - 1)) if slips.size > 1 else None,
            "energy_error": float(r.energy_error)}
'''

_CURRENT = _SUMMARY + '''
import json
from discrete.nonsmooth import Options, simulate
from fem.study import Study
study = Study.parse(json.loads(DOC_JSON))
PROBLEM, T_END = study.problem_spec().problem(), study.simulation_settings()["t_end"]
def run():
    return summary(simulate(PROBLEM, T_END, Options()))
'''

_OLD = _SUMMARY + '''
import json
from discrete.nonsmooth import Options, build_problem, simulate
PROBLEM, SETTINGS = build_problem(json.loads(DOC_JSON))
T_END = SETTINGS["t_end"]
def run():
    return summary(simulate(PROBLEM, T_END, Options()))
'''


def snippet(template: str, doc_json: str) -> str:
    return f"DOC_JSON = {doc_json!r}\n" + template


def package_runner(doc):
    from discrete.nonsmooth import Options, simulate
    from fem.study import Study

    ns = {}
    exec(_SUMMARY, ns)
    study = Study.parse(doc)
    problem, t_end = study.problem_spec().problem(), study.simulation_settings()["t_end"]
    return lambda: ns["summary"](simulate(problem, t_end, Options()))


def first_call(doc_json: str, env: dict) -> tuple[common.Measured, common.Measured]:
    """(first, second) call of simulate in a fresh process of this checkout with ``env``."""
    with common.Worker(ROOT, snippet(_CURRENT, doc_json), env=env, label="fresh process") as w:
        return w(), w()


def profile(run, calls: int = 10, top: int = 12) -> None:
    """Where the package's time goes: cProfile of ``calls`` calls (after they ran warm), the
    functions with the largest own time, and the share of the compiled kernel (``kernel.py``):
    the rest is the Python around it (event rules, projections, recording), the part a faster
    kernel cannot remove.  cProfile inflates Python calls, so the shares are indicative."""
    import cProfile
    import io
    import pstats

    pr = cProfile.Profile()
    pr.enable()
    for _ in range(calls):
        run()
    pr.disable()
    st = pstats.Stats(pr, stream=io.StringIO())
    total = sum(v[2] for v in st.stats.values())
    kern = sum(v[2] for k, v in st.stats.items() if k[0].endswith("kernel.py"))
    out = io.StringIO()
    pstats.Stats(pr, stream=out).sort_stats("tottime").print_stats(top)
    rows = [l for l in out.getvalue().splitlines() if l.strip() and not l.lstrip().startswith(("Ordered", "List"))]
    print(f"\nprofile of the package ({calls} calls, cProfile, own time): {total:.3f} s in all, "
          f"{kern / total:.0%} in the compiled kernel (discrete/nonsmooth/kernel.py), the rest in the Python around it")
    print("\n".join(rows[-(top + 1):]))


def errors(s: dict, T: float) -> dict:
    e = lambda x: None if x is None else abs(x / T - 1)  # noqa: E731
    return {"period": e(s["period"]), "mean_period": e(s["mean_period"]), "energy": abs(s["energy_error"])}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--periods", type=int, default=200)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--runs-nojit", type=int, default=5, help="runs of the plain-Python column")
    ap.add_argument("--commit", default=PRE_ISSUE, help="the pre-issue release (baseline)")
    ap.add_argument("--profile", action="store_true", help="print where the package's time goes (also printed "
                    "whenever a target is not met)")
    ap.add_argument("--block", type=int, default=5,
                    help="the package's run = the median of this many consecutive calls after one untimed call")
    a = ap.parse_args(argv)
    common.header(__file__, f"event-driven solver, seed 000 k* = 2, {a.periods} periods")
    doc, d = model(a.periods)
    T = d["period"]
    doc_json = json.dumps(doc)
    try:
        from discrete.nonsmooth import kernel
        jit = bool(kernel.JIT)
    except (ImportError, AttributeError):
        jit = False
    print(f"numba kernel: {'compiled (numba)' if jit else 'NOT compiled (numba missing, DRIVEFEM_JIT=0, or no kernel)'}")

    # one-off costs of the first call, in fresh processes
    t_load = first_call(doc_json, {})
    with tempfile.TemporaryDirectory() as cache:
        t_compile = first_call(doc_json, {"NUMBA_CACHE_DIR": cache})
    for label, (m1, m2) in (("numba's on-disk cache as found", t_load), ("an empty numba cache", t_compile)):
        print(f"first call in a fresh process with {label}: {m1.wall:.3f} s wall, {m1.cpu:.3f} s cpu; second call "
              f"{m2.wall:.3f} s wall, {m2.cpu:.3f} s cpu: one-off load/compile {m1.wall - m2.wall:.3f} s wall, "
              f"{m1.cpu - m2.cpu:.3f} s cpu (not in the timed runs)")

    run_pkg = package_runner(doc)
    cands = {"package": common.steady(run_pkg, calls=a.block, warm=1), "package, single call": run_pkg}
    workers = []
    try:
        try:
            workers.append(common.release_worker(a.commit, snippet(_OLD, doc_json)))
            cands["pre-issue release"] = workers[-1]
        except RuntimeError as e:
            print(f"pre-issue release {a.commit} NOT available: {e}")
        workers.append(common.Worker(ROOT, snippet(_CURRENT, doc_json), env={"DRIVEFEM_JIT": "0"},
                                     label="DRIVEFEM_JIT=0"))
        cands["plain Python (DRIVEFEM_JIT=0)"] = workers[-1]
        tm = common.interleaved(cands, runs=a.runs, warmup=1, runs_of={"plain Python (DRIVEFEM_JIT=0)": a.runs_nojit})
    finally:
        for w in workers:
            w.close()

    print(f"\nseed 000, eps = 6, Omega = 1: k* = {d['k_star']}, period (20) = {T:.12g} s, {a.periods} periods")
    print(f"{'column':<32} {'events':>6} {'wall [s] median [min-max]':>30} {'cpu [s] median [min-max]':>28} "
          f"{'events/s (wall)':>15} {'(cpu)':>9}  {'period err':>10} {'mean-period err':>15} {'energy err':>10}")
    for name, t in tm.items():
        s = t.result
        e = errors(s, T)
        n = s["events"]
        print(f"{name:<32} {n:6d} {t.wall_stats.fmt(1, 's', 3):>30} {t.cpu_stats.fmt(1, 's', 3):>28} "
              f"{n / t.wall_stats.median:15.0f} {n / t.cpu_stats.median:9.0f}  {e['period']:10.1e} "
              f"{e['mean_period']:15.1e} {e['energy']:10.1e}")
    print(f"package: each run is the median of {a.block} consecutive calls after one untimed call (steady state, "
          f"like timeit; benchmarks/drives.py does the same); 'package, single call': one call per round right after "
          f"the other columns' runs (cold caches), shown for comparison")
    pkg = tm["package"]
    ep = errors(pkg.result, T)
    n = pkg.result["events"]
    acc_name = "period error (detector) / energy error"
    acc = lambda e: f"{e['period']:.1e} / {e['energy']:.1e}"  # noqa: E731
    recs = [common.record(
        __file__, f"events/s, seed 000 k* = 2, {a.periods} periods ({n} events)",
        "event-driven" + (" (numba)" if jit else " (no numba)"), None, n / pkg.wall_stats.median, (">=", 10000),
        metric="events/s", unit="events/s", ratio_cpu=n / pkg.cpu_stats.median, accuracy=acc_name,
        accuracy_package=acc(ep), runs=pkg.runs, spread={"package": pkg.spread_dict()})]
    if "pre-issue release" in tm:
        old = tm["pre-issue release"]
        r, rc = common.speedup(old, pkg)
        same = old.result["events"] == n
        print(f"same events in both: {same} ({n} vs {old.result['events']})")
        recs.append(common.record(
            __file__, f"event-driven vs the pre-issue release {a.commit}, seed 000 k* = 2, {a.periods} periods",
            "event-driven" + (" (numba)" if jit else " (no numba)"), f"release {a.commit}", r, (">=", 25),
            ratio_cpu=rc, accuracy=acc_name, accuracy_package=acc(ep), accuracy_baseline=acc(errors(old.result, T)),
            runs=min(pkg.runs, old.runs), spread={"package": pkg.spread_dict(), "baseline": old.spread_dict()}))
        one = tm["package, single call"]
        r1, rc1 = common.speedup(old, one)
        recs.append(common.record(
            __file__, f"single cold call vs the pre-issue release {a.commit}, seed 000 k* = 2, {a.periods} periods",
            "event-driven" + (" (numba)" if jit else " (no numba)") + ", single call", f"release {a.commit}", r1, None,
            ratio_cpu=rc1, accuracy=acc_name, accuracy_package=acc(errors(one.result, T)),
            accuracy_baseline=acc(errors(old.result, T)), runs=min(one.runs, old.runs),
            spread={"package": one.spread_dict(), "baseline": old.spread_dict()}))
    else:
        print(f"the baseline (release {a.commit}) was NOT run: the ratio against it is not measured")
        recs.append(common.record(__file__, f"event-driven vs the pre-issue release {a.commit} (NOT available)",
                                  "event-driven", f"release {a.commit}", None, (">=", 25)))
    nj = tm["plain Python (DRIVEFEM_JIT=0)"]
    r, rc = common.speedup(nj, pkg)
    recs.append(common.record(
        __file__, f"numba vs the same kernel as plain Python, seed 000 k* = 2, {a.periods} periods",
        "event-driven" + (" (numba)" if jit else " (no numba)"), "DRIVEFEM_JIT=0", r, None, ratio_cpu=rc,
        accuracy=acc_name, accuracy_package=acc(ep), accuracy_baseline=acc(errors(nj.result, T)),
        runs=min(pkg.runs, nj.runs), spread={"package": pkg.spread_dict(), "baseline": nj.spread_dict()}))
    if a.profile or any(rec["met"] is False for rec in recs):
        profile(run_pkg)
    print()
    return common.finish(recs)


if __name__ == "__main__":
    sys.exit(main())
