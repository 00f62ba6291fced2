"""Factorise a sparse symmetric matrix with the best available direct solver, and say which.

Shift-invert eigen-solvers spend their time in one factorisation of ``A = K - sigma M`` and a few
dozen solves with it.  SuperLU (scipy's default) is a general LU with a column ordering (COLAMD)
and partial pivoting; on 3D quadratic elements it fills twice as much as a symmetric
factorisation with nested-dissection ordering, and runs on one core.  Measured on the 105k-DOF
solid shaft of ``benchmarks/solid.py`` (27-node hexahedra, 2-core machine; ``docs/solid.md``):

================================  =================  =========  ===========  ==============
library (ordering)                nnz of the factor  factorise  one solve    peak memory
================================  =================  =========  ===========  ==============
SuperLU (COLAMD), LU              112 M              6.8 s      0.09 s       2.7 GB
CHOLMOD 3.0 (METIS), LL^T         53 M               6.8 s      0.13 s       1.5 GB
MUMPS 5.5 seq. (SCOTCH), LDL^T    70 M               4.7 s      0.10 s       1.1 GB
MKL PARDISO (METIS), LDL^T        55 M               2.2 s      0.05 s       1.2 GB
================================  =================  =========  ===========  ==============

(factorise = ordering + symbolic + numerical; CHOLMOD and MUMPS are Debian's builds on OpenBLAS.)
MKL PARDISO is used when the optional package ``pypardiso`` (which brings Intel's ``mkl``) is
installed and the matrix has at least :data:`AUTO_MIN_SIZE` rows; SuperLU otherwise, called
exactly as before, so smaller models give bit-identical results whether or not MKL is there.

Large matrices with a narrow band (beams and shafts of 1000 DOFs and more: at most
:data:`BANDED_MAX_WIDTH` after reverse Cuthill-McKee) are factorised by LAPACK's banded LU
(:class:`discrete.linalg.banded.BandedLU`, ``dgbtrf``/``dgbtrs``) instead of SuperLU, whose solve
spends its time per supernode on such a band (one or two columns each): at 2000 DOFs a solve takes
0.065-0.075 ms against 0.165 ms, the factorisation 0.33-0.72 ms against 0.85-1.0 ms (measured), and
a shift-invert modal solve of the 2000-DOF beam or shaft is 2x faster.  Both are backward stable;
the eigenvalues agree to about eps lam_max / lam.

PARDISO runs as a symmetric *indefinite* LDL^T (``mtype = -2``, Bunch-Kaufman pivoting within
supernodes, METIS nested dissection): the same code for a positive definite ``K``, for ``K + tau M``
(free systems) and for an indefinite ``K - sigma M`` (a shift inside the spectrum), and the pivots
give the inertia (Sylvester's law: the number of negative pivots is the number of eigenvalues
below ``sigma``).  Where a pivot is tiny PARDISO does not stop but replaces it by
``1e-8 ||A||`` ("perturbed pivot"), i.e. factorises a nearby matrix; such a factorisation is thrown
away and SuperLU (threshold partial pivoting) used instead, with a note saying so.  Only the
upper triangle of ``A`` is read: ``A`` must be symmetric.

A caller that expects a positive definite matrix (``factorize(K, definite=True)``: the stiffness
of a supported structure at the default shift) gets PARDISO's Cholesky (``mtype = 2``) first: no
pivot search, 1.15 s instead of 1.7 s for the numerical factorisation of the 105k-DOF solid and
slightly faster solves (measured).  Its success proves the matrix positive definite (inertia
(n, 0)); a non-positive pivot (PARDISO error -4) sends the matrix to the indefinite LDL^T above.

pypardiso locates MKL's runtime library (pip wheel, conda or system); its own ``solve`` re-checks
the whole matrix and copies its index arrays on every call (18 ms here, a third of a solve), so
the factorisation calls MKL's documented ``pardiso`` entry point through ctypes with the arrays
kept alive, and releases MKL's memory when the factorisation is garbage-collected.
"""
from __future__ import annotations

import contextlib
import ctypes
import glob
import os
import sys
import weakref
from functools import cached_property, lru_cache

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import ModelError, SolverError
from .banded import _canonical, band_diagonal, narrow_layout

#: smallest matrix (rows) factorised by the fast library under ``solver="auto"``.  Below it a
#: modal solve takes seconds either way, and every model of the validation catalogue stays
#: below it (largest: rotor-vs-3d-solid, 25 899 DOFs), so the catalogue's numbers are the same
#: to the bit with and without MKL (docs/solid.md).
AUTO_MIN_SIZE = 30_000

SOLVERS = ("auto", "superlu", "pardiso")
#: environment variable that overrides the default choice (one of :data:`SOLVERS`)
ENV = "DRIVEFEM_SPARSE_DIRECT"
_preferred: list[str] = []


class SingularMatrixError(SolverError):
    """The matrix is exactly singular (a zero pivot that no pivoting avoids)."""


class Factorisation:
    """A factorised square matrix.  ``solve(b)`` for ``b`` of shape ``(n,)`` or ``(n, m)``.

    ``solver``: the library ("SuperLU", "MKL PARDISO" or "LAPACK"); ``kind``: "LU", "LDL^T", "LL^T"
    or "banded LU (...)";
    ``inertia``: (positive, negative) pivots where the library counts them, else None;
    ``notes``: why a faster library was not used, if it was tried."""

    def __init__(self, solver, kind, n, solve, pivots, inertia=None, notes=()):
        self.solver, self.kind, self.n = solver, kind, n
        self._solve, self._pivots = solve, pivots
        self.inertia = inertia
        self.notes = list(notes)

    @property
    def name(self) -> str:
        return f"{self.solver} {self.kind}"

    def solve(self, b: np.ndarray) -> np.ndarray:
        return self._solve(b)

    @cached_property
    def pivot_ratio(self) -> float:
        """Smallest over largest pivot magnitude (computed on first use: for SuperLU it copies U)."""
        piv = np.abs(self._pivots())
        return float(piv.min() / piv.max())

    def __repr__(self) -> str:
        return f"Factorisation({self.name}, n={self.n})"


# ------------------------------------------------------------------ choice
@contextlib.contextmanager
def preferred_solver(name: str):
    """Within the block, ``factorize(..., solver="auto")`` uses ``name`` (one of :data:`SOLVERS`);
    benchmarks use it to time SuperLU and PARDISO on the same model."""
    _check_name(name, "solver")
    _preferred.append(name)
    try:
        yield
    finally:
        _preferred.pop()


def _check_name(name, key):
    if name not in SOLVERS:
        raise ModelError("sparse direct solver", key, name, " | ".join(SOLVERS))


def available_solvers() -> list[str]:
    """The libraries importable here, in order of preference."""
    return (["pardiso"] if _mkl() is not None else []) + ["superlu"]


def _requested(solver: str) -> str:
    """``solver`` as asked for: an explicit name, else the innermost :func:`preferred_solver`, else
    the environment's :data:`ENV`, else "auto"."""
    _check_name(solver, "solver")
    if solver == "auto":
        solver = _preferred[-1] if _preferred else os.environ.get(ENV, "auto")
        _check_name(solver, ENV)
    return solver


def choose(n: int, solver: str = "auto") -> str:
    """The library ``factorize`` uses for an n x n matrix: "pardiso" or "superlu"."""
    solver = _requested(solver)
    if solver == "auto":
        solver = "pardiso" if n >= AUTO_MIN_SIZE and _mkl() is not None else "superlu"
    elif solver == "pardiso" and _mkl() is None:
        raise ModelError("sparse direct solver", "solver", "pardiso",
                         "'superlu' or 'auto' (MKL PARDISO is not installed: pip install pypardiso)")
    return solver


def factorize(A: sp.spmatrix, solver: str = "auto", definite: bool = False,
              fallback: bool = True) -> Factorisation:
    """Factorise the symmetric sparse matrix ``A`` (see the module notes for the choice);
    ``definite``: A is expected to be positive definite (PARDISO tries its Cholesky first).
    ``fallback = False``: a factorisation PARDISO turns away raises :class:`SolverError` instead
    of going to SuperLU (a caller that only wants PARDISO's inertia).

    Raises :class:`SingularMatrixError` if ``A`` is exactly singular, :class:`SolverError` if
    MKL PARDISO runs out of memory (SuperLU would need more)."""
    n = A.shape[0]
    choice = choose(n, solver)
    if choice == "pardiso":
        try:
            return _pardiso(A, definite)
        except _Rejected as why:
            if not fallback:
                raise SolverError(f"MKL PARDISO not used: {why}") from None
            return _superlu(A, notes=[f"MKL PARDISO not used: {why}; SuperLU instead"])
    if _requested(solver) == "auto" and n >= BANDED_MIN_SIZE:
        banded = _banded(A)
        if banded is not None:
            return banded
    return _superlu(A)


# ------------------------------------------------------------------ LAPACK banded LU
#: smallest matrix (rows) that ``solver="auto"`` factorises by LAPACK's banded LU when its band
#: (after reverse Cuthill-McKee) is at most :data:`BANDED_MAX_WIDTH` wide: the beams and shafts of
#: 1000 and more DOFs.  SuperLU's solve spends its time per supernode, one or two columns each on
#: such a band: at 2000 DOFs 0.19 ms (Hermite beam) and 0.35 ms (P2 shaft) per solve against
#: 0.03-0.05 ms for ``dgbtrs`` (measured), and a shift-invert solve does 30-40 of them.  Smaller
#: matrices keep SuperLU, so the validation catalogue's models below it give the same bits as before.
BANDED_MIN_SIZE = 1000
BANDED_MAX_WIDTH = 32


def _banded(A) -> Factorisation | None:
    """The banded LU of ``A`` (:class:`discrete.linalg.banded.BandedLU`), or None when its band is
    wider than :data:`BANDED_MAX_WIDTH` after reverse Cuthill-McKee."""
    A = _canonical(A)
    lay = narrow_layout(A, BANDED_MAX_WIDTH)
    if lay is None:
        return None
    try:
        fac = lay.factor(A.data)
    except SolverError as exc:                      # a zero pivot that partial pivoting cannot avoid
        raise SingularMatrixError(f"LAPACK banded LU: {exc}") from exc

    def solve(b):
        b = np.asarray(b)
        return fac.solve(b) if b.ndim == 1 else fac.solve_columns(b)

    return Factorisation("LAPACK", f"banded LU (band {lay.kl} + {lay.ku})", A.shape[0], solve,
                         lambda: band_diagonal(lay, fac))


# ------------------------------------------------------------------ SuperLU
def _superlu(A, notes=()) -> Factorisation:
    try:
        lu = spla.splu(sp.csc_matrix(A))
    except RuntimeError as exc:                    # "Factor is exactly singular"
        raise SingularMatrixError(f"SuperLU: {exc}") from exc
    return Factorisation("SuperLU", "LU", A.shape[0], lu.solve, lambda: lu.U.diagonal(), notes=notes)


# ------------------------------------------------------------------ MKL PARDISO
class _Rejected(Exception):
    """PARDISO's factorisation is not used (perturbed pivots, an internal error)."""


_P = ctypes.c_void_p
_ERRORS = {-1: "input inconsistent", -2: "not enough memory", -3: "reordering problem",
           -4: "zero pivot", -5: "unclassified internal error", -6: "reordering failed",
           -7: "diagonal matrix is singular", -8: "32-bit integer overflow", -9: "not enough memory for OOC",
           -10: "error opening OOC files", -11: "read/write error with OOC files"}
MTYPE = -2                                         # real symmetric indefinite


@lru_cache(maxsize=1)
def mkl_library():
    """MKL's runtime library (``ctypes.CDLL``) as pypardiso loads it, or None if not installed; one
    in ``sys.prefix/lib`` (where the MKL wheel puts it) is tried first, before pypardiso's own
    search (``find_library``, then a recursive search of ``sys.prefix``).
    Importing pypardiso already makes its default solver, which has found and loaded the library:
    that one is reused (a second ``PyPardisoSolver()`` searched again, 0.18 s per process)."""
    hint = "PYPARDISO_MKL_RT"
    near = _mkl_rt_in_prefix() if hint not in os.environ else None
    for guess in ([near] if near else []) + [None]:
        if guess:
            os.environ[hint] = guess                # for this import only: pypardiso searches no further
        try:
            import pypardiso
            solver = getattr(getattr(pypardiso, "scipy_aliases", None), "pypardiso_solver", None)
            return (solver if solver is not None else pypardiso.PyPardisoSolver()).libmkl
        except (ImportError, OSError, AttributeError):
            continue                                # the guess did not load: pypardiso's own search
        finally:
            if guess:
                os.environ.pop(hint, None)
    return None


def _mkl_rt_in_prefix():
    """MKL's runtime library where its wheel installs it (``sys.prefix/lib``), or None.  Without a
    hint pypardiso asks ``find_library`` and then searches all of ``sys.prefix/lib*`` recursively,
    site-packages included: 0.15 s of every process's first large solve."""
    hits = [p for pattern in ("libmkl_rt.so*", "libmkl_rt*.dylib")
            for p in glob.glob(os.path.join(sys.prefix, "lib", pattern))]
    return min(hits, key=len) if hits else None


@lru_cache(maxsize=1)
def _mkl():
    """MKL's ``pardiso`` and ``pardiso_getdiag`` entry points, or None if not installed."""
    lib = mkl_library()
    if lib is None:
        return None
    proto = ctypes.CFUNCTYPE(None, *([_P] * 16))
    getdiag = ctypes.CFUNCTYPE(None, _P, _P, _P, _P, _P)
    try:
        return proto(("pardiso", lib)), getdiag(("pardiso_getdiag", lib))
    except AttributeError:
        return None


def _upper_csr(A):
    """Upper triangle of ``A`` in CSR with int32 indices, sorted, every diagonal entry stored
    (PARDISO's input for symmetric matrices, zero-based)."""
    A = sp.csr_matrix(A, dtype=float)
    if not A.has_canonical_format:
        A = A.copy()
        A.sum_duplicates()
    n = A.shape[0]
    rows = np.repeat(np.arange(n, dtype=np.int32), np.diff(A.indptr))
    keep = A.indices >= rows
    rows, cols, data = rows[keep], A.indices[keep], A.data[keep]
    has_diag = np.zeros(n, dtype=bool)
    has_diag[rows[cols == rows]] = True
    if not has_diag.all():                          # explicit zeros on the missing diagonal
        miss = np.flatnonzero(~has_diag).astype(np.int32)
        U = sp.coo_matrix((np.concatenate([data, np.zeros(miss.size)]),
                           (np.concatenate([rows, miss]), np.concatenate([cols, miss]))), shape=(n, n)).tocsr()
        U.sum_duplicates()
        return U.indptr.astype(np.int32), U.indices.astype(np.int32), np.ascontiguousarray(U.data)
    indptr = np.zeros(n + 1, dtype=np.int32)
    np.cumsum(np.bincount(rows, minlength=n), out=indptr[1:])
    return indptr, np.ascontiguousarray(cols, dtype=np.int32), np.ascontiguousarray(data)


class _PardisoHandle:
    """One PARDISO factorisation (its internal handle ``pt`` and the arrays it refers to)."""

    def __init__(self, n: int, csr, mtype: int = MTYPE):
        self.fn, self.getdiag = _mkl()
        self.n = n
        self.mtype = mtype
        self.ia, self.ja, self.a = csr                  # _upper_csr of the matrix
        self.pt = np.zeros(64, dtype=np.int64)
        self.iparm = ip = np.zeros(64, dtype=np.int32)
        ip[0] = 1           # these values, not the defaults
        ip[1] = 3           # METIS nested dissection, its parallel (OpenMP) version: the analysis of the
        #                     104 400-DOF solid's K 0.2-1.0 s faster on 2 threads, the same results from run
        #                     to run and process to process (checked bitwise)
        ip[9] = 8           # pivot perturbation 1e-8 (the default for symmetric indefinite)
        ip[10] = 0          # no scaling ...
        ip[12] = 0          # ... nor weighted matching (symmetric indefinite default off)
        ip[20] = 1          # Bunch-Kaufman 1x1 and 2x2 pivots
        ip[34] = 1          # zero-based indices
        ip[55] = 1          # keep the pivots for pardiso_getdiag
        self._call(12, np.zeros(n), np.zeros(n), 1)              # analysis + numerical factorisation
        weakref.finalize(self, _release, self.fn, self.pt, self.iparm, mtype)
        self.perturbed = int(ip[13])
        # a Cholesky that succeeded: positive definite (PARDISO counts pivots only for mtype -2)
        self.inertia = (n, 0) if mtype == 2 else (int(ip[21]), int(ip[22]))

    def _call(self, phase, b, x, nrhs):
        err = ctypes.c_int32(0)
        i32 = ctypes.c_int32
        self.fn(_P(self.pt.ctypes.data), ctypes.byref(i32(1)), ctypes.byref(i32(1)), ctypes.byref(i32(self.mtype)),
                ctypes.byref(i32(phase)), ctypes.byref(i32(self.n)), _P(self.a.ctypes.data), _P(self.ia.ctypes.data),
                _P(self.ja.ctypes.data), None, ctypes.byref(i32(nrhs)), _P(self.iparm.ctypes.data),
                ctypes.byref(i32(0)), _P(b.ctypes.data), _P(x.ctypes.data), ctypes.byref(err))
        if err.value:
            if phase == 12:
                _release(self.fn, self.pt, self.iparm, self.mtype)
            msg = f"MKL PARDISO error {err.value} ({_ERRORS.get(err.value, 'see the MKL manual')})"
            if err.value in (-2, -8, -9):
                raise SolverError(f"{msg} factorising a {self.n} x {self.n} matrix with "
                                  f"{self.a.size} stored entries (upper triangle)")
            if phase == 12:
                raise _Rejected(msg)
            raise SolverError(msg)

    def solve(self, b):
        b = np.asarray(b, dtype=float)
        if b.shape[0] != self.n or b.ndim > 2:
            raise ValueError(f"right-hand side of shape {b.shape} for a {self.n} x {self.n} factorisation")
        nrhs = 1 if b.ndim == 1 else b.shape[1]
        b = np.asfortranarray(b)                    # column-major for several right-hand sides
        x = np.empty_like(b, order="F")
        if nrhs:
            self._call(33, b, x, nrhs)
        return x

    def pivots(self):
        df, da = np.zeros(self.n), np.zeros(self.n)
        err = ctypes.c_int32(0)
        self.getdiag(_P(self.pt.ctypes.data), _P(df.ctypes.data), _P(da.ctypes.data),
                     ctypes.byref(ctypes.c_int32(1)), ctypes.byref(err))
        if err.value:
            raise SolverError(f"MKL pardiso_getdiag error {err.value}")
        return df


def _release(fn, pt, iparm, mtype):
    """Free MKL's memory of the factorisation ``pt`` (phase -1); idempotent."""
    if not pt.any():
        return
    err = ctypes.c_int32(0)
    i32 = ctypes.c_int32
    dummy = np.zeros(1)
    fn(_P(pt.ctypes.data), ctypes.byref(i32(1)), ctypes.byref(i32(1)), ctypes.byref(i32(mtype)),
       ctypes.byref(i32(-1)), ctypes.byref(i32(1)), _P(dummy.ctypes.data), None, None, None, ctypes.byref(i32(1)),
       _P(iparm.ctypes.data), ctypes.byref(i32(0)), _P(dummy.ctypes.data), _P(dummy.ctypes.data), ctypes.byref(err))
    pt[:] = 0


def _pardiso(A, definite: bool = False) -> Factorisation:
    csr = _upper_csr(A)
    h, kind = None, "LDL^T"
    if definite:
        try:
            h, kind = _PardisoHandle(A.shape[0], csr, mtype=2), "LL^T"
        except _Rejected:
            pass                             # not positive definite: the indefinite LDL^T decides
    if h is None:
        h = _PardisoHandle(A.shape[0], csr)
        if h.perturbed:
            _release(h.fn, h.pt, h.iparm, h.mtype)
            raise _Rejected(f"{h.perturbed} pivot(s) below 1e-8 ||A|| were perturbed (nearly singular or "
                            f"strongly indefinite matrix)")
    return Factorisation("MKL PARDISO", kind, h.n, h.solve, h.pivots, inertia=h.inertia)
