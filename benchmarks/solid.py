"""3D solid shaft: lowest 10 modes of a cantilever with >= 100 000 DOFs (27-node hexahedra).

Compares, each in its own subprocess (so the peak memory is that method's own):
  * the package's sparse shift-invert Lanczos (discrete.linear.modal.modal_analysis: sparse LU of K,
    ARPACK), and
  * LOBPCG preconditioned by smoothed-aggregation AMG (pyamg, with the six rigid-body
    modes as near-null space; block of modes + 4 vectors; the preconditioner applies one
    V-cycle per column), relative residual 1e-8 or ``--maxiter`` iterations,
and prints time, peak resident memory, the frequencies' agreement, and the faster one.

    python benchmarks/solid.py [--axial 80] [--n-quarter 3] [--modes 10]
"""
from __future__ import annotations

import argparse
import multiprocessing as mp
import resource
import sys
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))


def _build(axial, n_quarter):
    from fem.solid import ShaftMeshSpec, build_solid
    from validation.builders import uniform

    return build_solid(uniform("bending", 1.0, axial, d=0.05, supports=[(0.0, "clamped")]),
                       ShaftMeshSpec(n_quarter=n_quarter))


def _shift_invert(axial, n_quarter, k, q):
    t0 = time.perf_counter()
    solid = _build(axial, n_quarter)
    tb = time.perf_counter() - t0
    from discrete.linear.modal import modal_analysis

    t0 = time.perf_counter()
    res = modal_analysis(solid.system, k)
    q.put({"build": tb, "solve": time.perf_counter() - t0, "f": res.frequencies_hz.tolist(),
           "n": solid.system.n_dofs, "rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
           "residual": float(res.residuals.max())})


def _lobpcg_amg(axial, n_quarter, k, lam_ref, maxiter, q):
    import pyamg
    import scipy.sparse.linalg as spla

    solid = _build(axial, n_quarter)
    sysm = solid.system
    t0 = time.perf_counter()
    K, M = sysm.free_block(sysm.K), sysm.free_block(sysm.M)
    B = np.zeros((sysm.n_dofs, 6))
    from fem.solid.model import _rigid_modes

    B = _rigid_modes(np.tile(solid.basis.doflocs, 3), np.repeat(np.arange(3), solid.basis.N), np.zeros(0, int))[sysm.free]
    ml = pyamg.smoothed_aggregation_solver(K.tocsr(), B=B, max_coarse=500)
    prec = ml.aspreconditioner(cycle="V")
    rng = np.random.default_rng(0)
    X = rng.standard_normal((K.shape[0], k + 4))
    # lobpcg's tolerance is on the absolute residual ||K x - lam M x||: scale it by the
    # largest wanted eigenvalue (from the shift-invert run) for a relative 1e-8
    tol = 1e-8 * lam_ref * np.sqrt(M.diagonal().max())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        lam, vec, hist = spla.lobpcg(K, X, B=M, M=prec, largest=False, tol=tol, maxiter=maxiter,
                                     retResidualNormsHistory=True)
    order = np.argsort(lam)[:k]
    lam, vec = lam[order], vec[:, order]
    r = np.linalg.norm(K @ vec - (M @ vec) * lam, axis=0) / (np.linalg.norm(K @ vec, axis=0))
    q.put({"solve": time.perf_counter() - t0, "f": (np.sqrt(lam) / (2 * np.pi)).tolist(), "n": sysm.n_dofs,
           "iterations": len(hist),
           "rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, "residual": float(r.max())})


def _run(target, *args):
    ctx = mp.get_context("spawn")
    q = ctx.Queue()
    p = ctx.Process(target=target, args=args + (q,))
    p.start()
    out = q.get()
    p.join()
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--axial", type=int, default=120, help="elements along the shaft (120: about 105 000 DOFs)")
    ap.add_argument("--n-quarter", type=int, default=3, help="divisions of a quarter circle")
    ap.add_argument("--modes", type=int, default=10)
    ap.add_argument("--maxiter", type=int, default=60, help="LOBPCG iterations (about 50 reach 1e-8 here)")
    args = ap.parse_args(argv)
    a = _run(_shift_invert, args.axial, args.n_quarter, args.modes)
    print(f"3D cantilever L = 1 m, d = 50 mm: {a['n']} DOFs (27-node hexahedra), build {a['build']:.1f} s")
    print(f"shift-invert (sparse LU + ARPACK): {a['solve']:7.1f} s, peak RSS {a['rss_mb']:7.0f} MB, "
          f"max residual {a['residual']:.1e}")
    try:
        import pyamg  # noqa: F401
    except ImportError:
        print("LOBPCG + AMG: skipped (pip install pyamg)")
        return 0
    lam_ref = (2 * np.pi * a["f"][-1]) ** 2
    b = _run(_lobpcg_amg, args.axial, args.n_quarter, args.modes, lam_ref, args.maxiter)
    print(f"LOBPCG + SA-AMG (pyamg):           {b['solve']:7.1f} s, peak RSS {b['rss_mb']:7.0f} MB, "
          f"max residual {b['residual']:.1e}, {b['iterations']} iterations")
    diff = np.max(np.abs(np.array(b["f"]) / np.array(a["f"]) - 1))
    print(f"frequencies agree to {diff:.1e} (lowest {np.array(a['f'][:4]).round(3).tolist()} Hz)")
    fast = "shift-invert" if a["solve"] <= b["solve"] else "LOBPCG + AMG"
    print(f"faster: {fast} (ratio {max(a['solve'], b['solve']) / min(a['solve'], b['solve']):.2f}x)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
