"""3D solid shaft: lowest 10 modes of a cantilever with >= 100 000 DOFs (27-node hexahedra).

Times the package's sparse shift-invert Lanczos (``discrete.linear.modal.modal_analysis``: one
factorisation of K, ARPACK, and the definiteness checks of M and K) against the release the issue
was filed against, in the same run:

* ``release``: commit 890424e itself (SuperLU's LU of K with its pivot ratio, ARPACK; no
  definiteness checks yet), exported read-only with ``git archive`` and run in its own process,
  which builds the model with that release's code (build not timed);
* ``today``: this checkout forced to SuperLU with the pivot ratio asked at once -- the old
  reconstruction of the release, kept for comparison; it also runs the checks added since
  (issue 16: SuperLU LDL^T counts of M and of K + z M), so it is 2x slower than the release
  and no longer a fair baseline;
* ``superlu``: today's fallback when MKL is not installed (the ratio only where it is used);
* ``auto``: what ``modal_analysis`` chooses by itself (MKL PARDISO from 30 000 DOFs when
  ``pypardiso`` is installed; ``discrete.linalg.sparse_direct``).

The model is built once and handed to a fresh process per run (``spawn``; the release builds its
own), so each timing starts cold like a command-line call and each peak memory is that run's own
(the release's includes its build); the paths alternate run by run so that load from other
processes hits all of them alike.  Printed: median and spread of the
runs, the median of the per-run ratios, the frequencies' agreement, residuals, the factorisation
and Lanczos shares, peak resident memory, and the BLAS/LAPACK libraries in use (threadpoolctl).

``--growth`` instead builds and solves one size per fresh process (auto path, lowest 10 modes),
refining the mesh in all three directions, and prints DOFs, build and solve time and peak memory
up to the largest size under ``--limit-gib`` (each process is also capped by RLIMIT_AS so that a
size that does not fit fails alone instead of exhausting the machine).

``--amg`` adds one run of LOBPCG preconditioned by smoothed-aggregation AMG (pyamg), the
iterative alternative to a factorisation (176 s against 18 s before issue 13).

    python benchmarks/solid.py [--axial 120] [--n-quarter 3] [--modes 10] [--runs 5] [--amg]
                               [--paths release superlu auto] [--commit 890424e]
    python benchmarks/solid.py --growth [--limit-gib 16] [--max-dofs N] [--sizes 240x6 ...]
"""
from __future__ import annotations

import argparse
import multiprocessing as mp
import os
import pickle
import resource
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

PATHS = {"release": "release 890424e (SuperLU)",
         "today": "SuperLU + eager ratio, today's checks",
         "superlu": "fallback without MKL",
         "auto": "automatic choice"}
PRE_ISSUE = "890424e"

# the release's own build and modal solve (its API: fem.solid, fem.modal.modal_analysis)
_RELEASE = '''
import resource
from fem.solid import ShaftMeshSpec, build_solid
from validation.builders import uniform
from fem.modal import modal_analysis
SOLID = build_solid(uniform("bending", 1.0, {axial}, d=0.05, supports=[(0.0, "clamped")]),
                    ShaftMeshSpec(n_quarter={n_quarter}))
def run():
    res = modal_analysis(SOLID.system, {modes})
    return {{"f": res.frequencies_hz.tolist(), "residual": float(res.residuals.max()),
            "reliable": bool(res.reliable.all()), "n": int(SOLID.system.n_free),
            "rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}}
'''


def _release_once(tree, args) -> dict:
    """One modal solve by the release in a fresh process of its own tree (build excluded)."""
    import common

    setup = _RELEASE.format(axial=args.axial, n_quarter=args.n_quarter, modes=args.modes)
    with common.Worker(tree, setup, label=f"release {args.commit}", timeout=3600) as w:
        m = w()
    out = dict(m.value)
    out.update(time=m.wall, factor=float("nan"), solver="SuperLU LU (release)", blas="(release process)")
    return out


def _build(axial, n_quarter):
    from fem.solid import ShaftMeshSpec, build_solid
    from validation.builders import uniform

    return build_solid(uniform("bending", 1.0, axial, d=0.05, supports=[(0.0, "clamped")]),
                       ShaftMeshSpec(n_quarter=n_quarter))


def _peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def blas_in_use() -> str:
    """The BLAS/LAPACK libraries loaded in this process, as threadpoolctl reports them."""
    from threadpoolctl import threadpool_info

    out = []
    for i in threadpool_info():
        if i.get("user_api") == "blas":
            arch = f" {i['architecture']}" if i.get("architecture") else ""
            out.append(f"{i['internal_api']} {i.get('version') or ''}{arch} ({i['num_threads']} threads, "
                       f"{Path(i['filepath']).name})")
    return "; ".join(out) or "none found"


def _solve_once(path, system_file, k, q):
    """One modal solve of the pickled system along ``path``; reports time, phases and memory."""
    import discrete.linear.modal as modal
    from discrete.linalg import sparse_direct as sd

    with open(system_file, "rb") as fh:
        system = pickle.load(fh)
    factor_time = [0.0]
    inner = modal._factor

    def timed_factor(A, **kw):
        t0 = time.perf_counter()
        f = inner(A, **kw)
        if path == "today" and f is not None:
            f.pivot_ratio                       # the old _factor computed it for every matrix
        factor_time[0] += time.perf_counter() - t0
        return f

    modal._factor = timed_factor
    solver = "superlu" if path in ("today", "superlu") else "auto"
    with sd.preferred_solver(solver):
        t0 = time.perf_counter()
        res = modal.modal_analysis(system, k)
        t = time.perf_counter() - t0
    q.put({"time": t, "factor": factor_time[0], "f": res.frequencies_hz.tolist(), "solver": res.linear_solver,
           "residual": float(res.residuals.max()), "reliable": bool(res.reliable.all()),
           "rss_mb": _peak_mb(), "blas": blas_in_use()})


def _spawn(target, *args):
    ctx = mp.get_context("spawn")
    q = ctx.Queue()
    p = ctx.Process(target=target, args=args + (q,))
    p.start()
    try:
        out = q.get()
    except KeyboardInterrupt:
        p.terminate()
        raise
    p.join()
    return out


def compare(args) -> int:
    t0 = time.perf_counter()
    solid = _build(args.axial, args.n_quarter)
    tb = time.perf_counter() - t0
    n = solid.system.n_free
    PATHS["release"] = f"release {args.commit} (SuperLU)"
    print(f"3D cantilever L = 1 m, d = 50 mm: {n} free DOFs (27-node hexahedra, n_quarter = {args.n_quarter}, "
          f"{args.axial} elements along x), lowest {args.modes} modes; build {tb:.1f} s")
    load = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        system_file = os.path.join(tmp, "system.pkl")
        with open(system_file, "wb") as fh:
            pickle.dump(solid.system, fh, protocol=pickle.HIGHEST_PROTOCOL)
        del solid
        runs = {p: [] for p in args.paths}
        tree = None
        if "release" in args.paths:
            import common

            tree = common.old_release(args.commit)
        for r in range(args.runs):
            for p in args.paths:
                runs[p].append(_release_once(tree, args) if p == "release" else
                               _spawn(_solve_once, p, system_file, args.modes))
                if p == "release" and runs[p][-1]["n"] != n:
                    raise RuntimeError(f"the release built {runs[p][-1]['n']} free DOFs, this checkout {n}")
            print(f"  run {r + 1}/{args.runs}: " + ", ".join(f"{p} {runs[p][-1]['time']:.1f} s" for p in args.paths),
                  flush=True)
    base = next((b for b in ("release", "today") if b in runs), args.paths[0])
    f_base = np.array(runs[base][0]["f"])
    for p in args.paths:
        if p != "release":
            print(f"\nBLAS/LAPACK in use ({p} process): {runs[p][0]['blas']}")
    print(f"\n{'path':<36} {'factorisation':<18} {'median':>8} {'min-max':>13} {'factorise':>9} "
          f"{'Lanczos+':>9} {'peak RSS':>9} {'max resid.':>10} {'max |df/f|':>10}")
    for p in args.paths:
        rs = runs[p]
        ts = [x["time"] for x in rs]
        fac = statistics.median(x["factor"] for x in rs)
        med = statistics.median(ts)
        diff = max(np.max(np.abs(np.array(x["f"]) / f_base - 1)) for x in rs)
        parts = f"{'-':>9} {'-':>9}" if np.isnan(fac) else f"{fac:8.2f}s {med - fac:8.2f}s"
        print(f"{p + ': ' + PATHS[p]:<36} {rs[0]['solver']:<18} {med:7.2f}s {min(ts):6.2f}-{max(ts):5.2f}s "
              f"{parts} {max(x['rss_mb'] for x in rs) / 1024:7.2f}GB "
              f"{max(x['residual'] for x in rs):10.1e} {diff:10.1e}")
    print(f"(median and spread of {args.runs} runs; 'Lanczos+' = ARPACK iterations, residuals and mode "
          f"checks; max |df/f| against the first '{base}' run, all {args.modes} modes; load average "
          f"{load[0]:.1f} at the start, {os.getloadavg()[0]:.1f} at the end on {os.cpu_count()} cores)")
    if base in runs:
        for p in args.paths:
            if p == base:
                continue
            ratios = [a["time"] / b["time"] for a, b in zip(runs[base], runs[p])]
            print(f"speed-up {p} vs {base}: {statistics.median(ratios):.2f}x "
                  f"(per-run ratios {min(ratios):.2f}-{max(ratios):.2f})")
    print(f"lowest frequencies [Hz]: {np.round(f_base[:6], 3).tolist()}")
    if args.amg:
        amg(args, f_base)
    bad = [p for p in args.paths if not all(x["reliable"] for x in runs[p])]
    if bad:
        print(f"NOT RELIABLE: {bad}")
        return 1
    return 0


def _lobpcg_amg(axial, n_quarter, k, lam_ref, maxiter, q):
    """LOBPCG preconditioned by smoothed-aggregation AMG (pyamg; the six rigid-body modes as
    near-null space; block of modes + 4 vectors, one V-cycle per column), relative residual
    1e-8 or ``maxiter`` iterations: the iterative alternative to a factorisation."""
    import warnings

    import pyamg
    import scipy.sparse.linalg as spla

    from fem.solid.model import _rigid_modes

    solid = _build(axial, n_quarter)
    sysm = solid.system
    t0 = time.perf_counter()
    K, M = sysm.free_block(sysm.K), sysm.free_block(sysm.M)
    B = _rigid_modes(np.tile(solid.basis.doflocs, 3), np.repeat(np.arange(3), solid.basis.N), np.zeros(0, int))[sysm.free]
    ml = pyamg.smoothed_aggregation_solver(K.tocsr(), B=B, max_coarse=500)
    prec = ml.aspreconditioner(cycle="V")
    X = np.random.default_rng(0).standard_normal((K.shape[0], k + 4))
    # lobpcg's tolerance is on the absolute residual ||K x - lam M x||: scaled for a relative 1e-8
    tol = 1e-8 * lam_ref * np.sqrt(M.diagonal().max())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        lam, vec, hist = spla.lobpcg(K, X, B=M, M=prec, largest=False, tol=tol, maxiter=maxiter,
                                     retResidualNormsHistory=True)
    order = np.argsort(lam)[:k]
    lam, vec = lam[order], vec[:, order]
    r = np.linalg.norm(K @ vec - (M @ vec) * lam, axis=0) / (np.linalg.norm(K @ vec, axis=0))
    q.put({"time": time.perf_counter() - t0, "f": (np.sqrt(lam) / (2 * np.pi)).tolist(), "iterations": len(hist),
           "rss_mb": _peak_mb(), "residual": float(r.max())})


def amg(args, f_ref) -> None:
    try:
        import pyamg  # noqa: F401
    except ImportError:
        print("LOBPCG + AMG: skipped (pip install pyamg)")
        return
    lam_ref = (2 * np.pi * f_ref[-1]) ** 2
    b = _spawn(_lobpcg_amg, args.axial, args.n_quarter, args.modes, lam_ref, 60)
    diff = np.max(np.abs(np.array(b["f"]) / f_ref - 1))
    print(f"LOBPCG + SA-AMG (pyamg), one run: {b['time']:.1f} s, peak RSS {b['rss_mb'] / 1024:.2f} GB, "
          f"max residual {b['residual']:.1e}, {b['iterations']} iterations, max |df/f| {diff:.1e}")


# ---------------------------------------------------------------------------- growth
def _grow_once(axial, n_quarter, k, limit_bytes, q):
    resource.setrlimit(resource.RLIMIT_AS, (limit_bytes, limit_bytes))
    try:
        t0 = time.perf_counter()
        solid = _build(axial, n_quarter)
        tb = time.perf_counter() - t0
        rss_build = _peak_mb()
        from discrete.linear.modal import modal_analysis

        t0 = time.perf_counter()
        res = modal_analysis(solid.system, k)
        ts = time.perf_counter() - t0
        q.put({"n": solid.system.n_free, "build": tb, "solve": ts, "rss_build_mb": rss_build, "rss_mb": _peak_mb(),
               "solver": res.linear_solver, "f1": float(res.frequencies_hz[0]),
               "residual": float(res.residuals.max()), "reliable": bool(res.reliable.all())})
    except MemoryError:
        q.put({"error": "MemoryError", "rss_mb": _peak_mb()})
    except Exception as exc:            # a failed size is reported, not hidden
        q.put({"error": f"{type(exc).__name__}: {exc}", "rss_mb": _peak_mb()})


GROWTH = [(60, 2), (120, 3), (160, 4), (200, 5), (240, 6), (280, 7), (320, 8)]


def growth(args) -> int:
    limit = int(args.limit_gib * 2**30)
    print(f"Growth of the 3D cantilever (L = 1 m, d = 50 mm; mesh refined along x and in the section), "
          f"lowest {args.modes} modes, automatic solver, one fresh process per size, "
          f"virtual memory capped at {args.limit_gib:g} GiB")
    print(f"{'axial':>5} {'n_q':>3} {'DOFs':>9} {'solver':<18} {'build':>7} {'solve':>7} {'peak RSS':>9} "
          f"{'(build)':>8} {'f1 [Hz]':>9} {'max resid.':>10}")
    sizes = [tuple(int(v) for v in x.split("x")) for x in args.sizes] if args.sizes else GROWTH
    for axial, nq in sizes:
        if args.max_dofs and 96 * axial * nq**2 > 1.2 * args.max_dofs:
            break
        r = _spawn(_grow_once, axial, nq, args.modes, limit)
        if "error" in r:
            print(f"{axial:5d} {nq:3d} {'':>9} failed after {r['rss_mb'] / 1024:.1f} GB: {r['error']}")
            break
        print(f"{axial:5d} {nq:3d} {r['n']:9d} {r['solver']:<18} {r['build']:6.1f}s {r['solve']:6.1f}s "
              f"{r['rss_mb'] / 1024:7.2f}GB {r['rss_build_mb'] / 1024:6.2f}GB {r['f1']:9.4f} {r['residual']:10.1e}",
              flush=True)
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--axial", type=int, default=120, help="elements along the shaft (120: about 105 000 DOFs)")
    ap.add_argument("--n-quarter", type=int, default=3, help="divisions of a quarter circle")
    ap.add_argument("--modes", type=int, default=10)
    ap.add_argument("--runs", type=int, default=5, help="runs of each path (median and spread)")
    ap.add_argument("--paths", nargs="+", default=["release", "superlu", "auto"], choices=list(PATHS))
    ap.add_argument("--commit", default=PRE_ISSUE, help="the release to compare against (git commit)")
    ap.add_argument("--amg", action="store_true", help="also one run of LOBPCG + smoothed-aggregation AMG (pyamg)")
    ap.add_argument("--growth", action="store_true", help="growth table instead of the comparison")
    ap.add_argument("--limit-gib", type=float, default=16.0, help="memory limit of the growth table")
    ap.add_argument("--max-dofs", type=int, default=0, help="growth table: stop above this size")
    ap.add_argument("--sizes", nargs="+", help="growth table: these AXIALxNQUARTER meshes only, e.g. 240x6")
    args = ap.parse_args(argv)
    return growth(args) if args.growth else compare(args)


if __name__ == "__main__":
    sys.exit(main())
