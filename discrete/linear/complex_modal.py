"""Complex modes of a :class:`LinearSystem` with damping and gyroscopic terms.

    M q'' + D q' + K q = 0,   D = C + Omega G   ->   (lam^2 M + lam D + K) phi = 0

The quadratic eigenproblem is solved through its linearisation A z = lam B z with
z = (phi, lam phi), A = [[0, I], [-K, -D]], B = [[I, 0], [0, M]], by ARPACK (implicitly
restarted Arnoldi, ``scipy.sparse.linalg.eigs``) in shift-invert mode.  The state matrices are
never formed: one application of (A - s B)^-1 B to y = (y1, y2) is

    x1 = -Q(s)^-1 (M y2 + (D + s M) y1),   x2 = y1 + s x1,   Q(s) = K + s D + s^2 M,

i.e. one solve with the sparse n x n matrix Q(s), factorised once (never M^-1 K, never a dense
2n x 2n matrix except for tiny blocks, ``dense_max``).  The shift s is 0 (then Q = K, which does
not depend on D: one factorisation serves a whole speed range) unless K is singular (a free
rotor, an axial or torsional rigid-body motion); then s = -tau < 0, which still orders lightly
damped eigenvalues by frequency (|lam + tau|^2 = tau^2 + omega^2 + O(damping)).

The problem is split into the independent blocks of the DOF graph of M, K, C, G (a rotor's
lateral, axial and torsional motions decouple).  Damped or gyroscopic blocks are solved first, by
the shift-invert Arnoldi above (for tiny blocks the same operator is formed densely).  Undamped
blocks with symmetric K and positive M (a rotor's axial and torsional motion) are symmetric
problems K phi = w^2 M phi (lam = +-i w); only the eigenvalues below the n-th |lam| found so far
are needed, and Sylvester's law of inertia (:class:`discrete.linalg.shifted.ShiftedSolver`) counts
them exactly, so such a block is skipped or solved for a few modes by inverse subspace iteration
(Lanczos if that does not converge) with the banded LU of K + tau M, rigid-body modes included.
A chain block (tridiagonal: a rotor's axial or torsional line) is counted by a Sturm sequence
(LAPACK ``dstebz``) and factorised by ``dpttrf`` directly from its diagonals.

The split into blocks is computed once per sparsity pattern: a matrix on a pattern seen before
(a rotor assembles M, K, C, G and every speed's bearings on one) is split by gathering its
data, and D = C + Omega G, the Arnoldi operator's [D, M] and the band data are formed on the
shared pattern without sparse-matrix arithmetic.  Measured on the 198-element rotor of
``benchmarks/rotor.py``: the first solve on a fresh rotor 1.26-1.30x faster than with scipy.sparse
slicing and arithmetic (alternating runs, medians of 7), whose per-call overhead dominated it.

Every mode carries the backward error of the quadratic problem (Tisseur 2000)

    residual = ||(lam^2 M + lam D + K) phi|| / ((|lam|^2 ||M|| + |lam| ||D|| + ||K||) ||phi||)

(1-norms), and ``reliable`` = residual < tolerance.

The factorisations are :class:`discrete.linalg.banded.BandedLU`: matrices that share one sparsity
pattern (a rotor at many speeds or frequencies) get a reverse Cuthill-McKee ordering and a band
map computed once, and each factorisation is one LAPACK ``?gbtrf`` call.
"""
from __future__ import annotations

import functools
import warnings as _warnings
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.linalg import lapack
from scipy.sparse.csgraph import connected_components

from ..errors import ModelError, SolverError
from ..linear_system import LinearSystem
from ..linalg.banded import BandedLU, _canonical, _csr_rows, band_diagonal as _band_diagonal, pattern_key, same_array
from ..linalg.blas import single_threaded_blas
from ..linalg.shifted import ShiftedSolver, sturm_count
from .modal import _norm1 as _matrix_norm1

EPS = np.finfo(float).eps
#: implicit restarts of one Arnoldi run: a run converges in 1-3 (ncv ~ 2 k); one that stalls (a
#: wanted count that splits a group of eigenvalues of one modulus) is retried with a larger count
#: instead of spending ARPACK's default 10 N restarts (half a minute at 1600 unknowns)
ARNOLDI_RESTARTS = 60


# ====================================================================== result
class ComplexModeFigures:
    """The figures of complex modes derived from ``eigenvalues`` (one of each conjugate pair),
    ``rigid``, ``residuals`` and ``tolerance`` (rigid-body modes read 0)."""

    @property
    def natural_frequency_rad_s(self) -> np.ndarray:
        """|lam| (the undamped natural frequency of a viscously damped mode), rad/s."""
        return np.where(self.rigid, 0.0, np.abs(self.eigenvalues))

    @property
    def omega_damped_rad_s(self) -> np.ndarray:
        """Damped natural frequency Im lam, rad/s."""
        return np.where(self.rigid, 0.0, self.eigenvalues.imag)

    @property
    def frequencies_hz(self) -> np.ndarray:
        return self.omega_damped_rad_s / (2 * np.pi)

    @property
    def damping_ratio(self) -> np.ndarray:
        """zeta = -Re lam / |lam| (negative: the mode grows)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            z = -self.eigenvalues.real / np.abs(self.eigenvalues)
        return np.where(self.rigid, 0.0, z)

    @property
    def log_decrement(self) -> np.ndarray:
        """delta = 2 pi zeta / sqrt(1 - zeta^2) = -2 pi Re lam / Im lam (inf for an overdamped mode)."""
        lam = self.eigenvalues
        with np.errstate(divide="ignore", invalid="ignore"):
            d = np.where(lam.imag > 0, -2 * np.pi * lam.real / np.where(lam.imag > 0, lam.imag, 1.0), np.inf)
        return np.where(self.rigid, 0.0, d)

    @property
    def reliable(self) -> np.ndarray:
        return self.residuals < self.tolerance

    @property
    def n_modes(self) -> int:
        return int(self.eigenvalues.size)

    def frequency_fields(self) -> dict:
        """The frequency figures as JSON fields (the rotor and train modal contracts)."""
        ld = self.log_decrement
        return {"omega_rad_s": self.omega_damped_rad_s.tolist(), "frequencies_hz": self.frequencies_hz.tolist(),
                "natural_frequency_rad_s": self.natural_frequency_rad_s.tolist(),
                "eigenvalues_real": self.eigenvalues.real.tolist(), "eigenvalues_imag": self.eigenvalues.imag.tolist(),
                "damping_ratio": self.damping_ratio.tolist(),
                "log_decrement": [None if not np.isfinite(v) else float(v) for v in ld]}

    def reliability_fields(self) -> dict:
        """Residuals and what they say, as JSON fields (the rotor and train modal contracts)."""
        return {"residuals": self.residuals.tolist(), "reliable": self.reliable.tolist(),
                "rigid_body_modes": int(self.rigid.sum()), "method": self.method, "warnings": list(self.warnings)}


@dataclass
class ComplexModalResult(ComplexModeFigures):
    """Complex modes, lowest |lam| first (one of each conjugate pair: Im lam >= 0).

    ``shapes`` (n_dofs, n_modes) complex, each scaled so that its largest entry is 1 (real);
    constrained DOFs are zero.  ``block`` tells which independent block of the DOF graph a
    mode belongs to (see the module notes)."""

    eigenvalues: np.ndarray
    shapes: np.ndarray
    residuals: np.ndarray
    rigid: np.ndarray
    block: np.ndarray
    speed: float
    n_dofs: int
    method: str
    tolerance: float
    warnings: list[str] = field(default_factory=list)

    def to_dict(self) -> dict:
        ld = self.log_decrement
        return {"speed_rad_s": self.speed, "eigenvalues_real": self.eigenvalues.real.tolist(),
                "eigenvalues_imag": self.eigenvalues.imag.tolist(),
                "omega_damped_rad_s": self.omega_damped_rad_s.tolist(),
                "natural_frequency_rad_s": self.natural_frequency_rad_s.tolist(),
                "frequencies_hz": self.frequencies_hz.tolist(), "damping_ratio": self.damping_ratio.tolist(),
                "log_decrement": [None if not np.isfinite(v) else float(v) for v in ld],
                "residuals": self.residuals.tolist(), "reliable": self.reliable.tolist(),
                "rigid": self.rigid.tolist(), "n_dofs": self.n_dofs, "method": self.method,
                "warnings": list(self.warnings)}


# ====================================================================== solver
def _norm1(A: sp.spmatrix | None) -> float:
    """The 1-norm of A (:func:`discrete.linear.modal._norm1`), 0 for a missing matrix.  A block's
    CSR matrix (a few thousand entries) by a bincount over its column indices: the column sums
    accumulate in row order as the transposed product's do (the same bits: checked on 100 rotor
    matrices), without building two sparse matrices per call."""
    if A is None:
        return 0.0
    if sp.isspmatrix_csr(A) and A.nnz and A.data.dtype == np.float64:
        return float(np.bincount(A.indices, np.abs(A.data), minlength=A.shape[1]).max())
    return _matrix_norm1(A)


def _same_pattern(a: sp.csr_matrix, b: sp.csr_matrix) -> bool:
    return a.shape == b.shape and a.nnz == b.nnz and (
        (same_array(a.indptr, b.indptr) and same_array(a.indices, b.indices))
        or (np.array_equal(a.indptr, b.indptr) and np.array_equal(a.indices, b.indices)))


def _block_map(A: sp.csr_matrix, label: np.ndarray, local: np.ndarray, sizes) -> list:
    """Where each block's entries lie in the canonical CSR matrix A (label: block of each row
    and column index, -1 for none; local: its index within the block): per block the positions
    in A.data and the block's CSR indices and indptr (row-major order is kept: canonical)."""
    rows = _csr_rows(A)
    lr = label[rows]
    keep = (lr >= 0) & (lr == label[A.indices])
    parts = []
    for b, m in enumerate(sizes):
        pos = np.flatnonzero(keep & (lr == b))
        indptr = np.zeros(m + 1, dtype=A.indptr.dtype)
        np.cumsum(np.bincount(local[rows[pos]], minlength=m), out=indptr[1:])
        parts.append((pos, local[A.indices[pos]].astype(A.indices.dtype), indptr, int(m)))
    return parts


def _gather(A: sp.csr_matrix, parts: list) -> list:
    return [sp.csr_matrix((A.data[pos], idx, ptr), shape=(m, m)) for pos, idx, ptr, m in parts]


def _same(a: sp.csr_matrix | None, b: sp.csr_matrix | None) -> bool:
    """Same matrix: the same pattern and the same values."""
    if a is None or b is None:
        return False
    return (a is b) or (_same_pattern(a, b) and np.array_equal(a.data, b.data))


@dataclass
class _Block:
    dofs: np.ndarray                 # indices into the free DOFs
    pattern: sp.csr_matrix
    layout: BandedLU | None = None
    cache_key: tuple | None = None   # (K, D) of the cached result
    cache: object = None
    k_factor: tuple | None = None    # (K, factor, shift) of the cached factorisation
    sym_key: tuple | None = None     # (K, whether the block is a symmetric undamped problem)
    chain_diagonals: tuple | None = None   # (K, M, their diagonals and first superdiagonals): Sturm counts
    shifted: tuple | None = None     # (K, ShiftedSolver) for inertia counts
    start: np.ndarray | None = None  # Arnoldi start from the previous solve of a sweep (warm starts)
    tridiagonal: bool | None = None  # a chain (consecutive DOFs coupled only): Sturm counts, dpttrf
    hstack_map: tuple | None = None  # positions of [D, M] in the Arnoldi operator's matrix
    zero: sp.csr_matrix | None = None   # the block's empty D (undamped, non-gyroscopic)


class QuadraticEigensolver:
    """Complex modes of M q'' + D q' + K q = 0 for many (D, K) on one system: the block split,
    the orderings and band maps are computed once; a factorisation of K (shift 0) is reused
    while K does not change (e.g. a rotor on constant bearings over a speed range), and the
    result of a block that does not change at all is reused as it is.

    ``system`` gives M, the constrained DOFs and the labels; ``patterns`` lists extra matrices
    whose sparsity the later K and D may use (e.g. every speed's bearing entries)."""

    def __init__(self, system: LinearSystem, patterns=()):
        self.system = system
        free = system.free
        self.free = free
        n_all = system.n_dofs
        self._maps = []                              # (pattern, its split map): see _split
        # the DOF graph: the stored non-zero entries of the matrices and patterns, grouped by
        # sparsity pattern (a rotor assembles M, K, C, G and its bearings on one pattern)
        groups: list[tuple[sp.csr_matrix, np.ndarray]] = []
        for A in (_canonical(A) for A in [system.M, system.K, system.C, system.G, *patterns]):
            for g, (B, nz) in enumerate(groups):
                if _same_pattern(A, B):
                    groups[g] = (B, nz | (A.data != 0))
                    break
            else:
                groups.append((A, A.data != 0))
        if len(groups) == 1 and free.size == n_all:      # one pattern, nothing constrained: P is its non-zeros
            A, nz = groups[0]
            # its own index arrays: eliminate_zeros compacts them in place, and A is the caller's M
            P = sp.csr_matrix((nz.astype(float), A.indices.copy(), A.indptr.copy()), shape=A.shape)
            P.eliminate_zeros()
            perm = _transpose_positions(P)
            if perm is None:
                P = sp.csr_matrix(P + P.T)
        else:
            local = np.full(n_all, -1)
            local[free] = np.arange(free.size)
            rows, cols = [], []
            for A, nz in groups:
                r = local[_csr_rows(A)[nz]]
                c = local[A.indices[nz]]
                ok = (r >= 0) & (c >= 0)
                rows.append(r[ok])
                cols.append(c[ok])
            r, c = np.concatenate(rows), np.concatenate(cols)
            P = sp.csr_matrix((np.ones(2 * r.size), (np.concatenate([r, c]), np.concatenate([c, r]))),
                              shape=(free.size, free.size))
        n_comp, labels = connected_components(P, directed=False)
        # blocks in order of their first DOF (keeps results reproducible)
        _, first = np.unique(labels, return_index=True)
        rank = np.empty(n_comp, dtype=int)
        rank[np.argsort(first)] = np.arange(n_comp)
        labels = rank[labels]
        sizes = np.bincount(labels, minlength=n_comp)
        order = np.argsort(labels, kind="stable")
        within = np.empty(free.size, dtype=int)      # index of each free DOF within its block
        within[order] = np.arange(free.size) - np.repeat(np.cumsum(sizes) - sizes, sizes)
        self._label = np.full(n_all, -1)             # block of each DOF (-1: constrained)
        self._label[free] = labels
        self._local = np.full(n_all, -1)             # index of each DOF within its block
        self._local[free] = within
        self.blocks = [_Block(dofs=d, pattern=pat) for d, pat in zip(
            np.split(order, np.cumsum(sizes)[:-1]),
            _gather(P, _block_map(P, labels, within, sizes)))]
        self._split_cache = {}
        self.warm_start = False

    def _split(self, A: sp.spmatrix) -> list:
        """A's entries within each block, one canonical CSR matrix per block (entries on
        constrained DOFs are dropped; between blocks there are none by construction).  The
        positions are computed once per sparsity pattern: a matrix on a known pattern is split by
        gathering its data."""
        A = _canonical(A)
        for pat, parts in self._maps:
            if _same_pattern(A, pat):
                break
        else:
            parts = _block_map(A, self._label, self._local, [b.dofs.size for b in self.blocks])
            if len(self._maps) >= 8:                   # a caller passing ever new patterns: keep the recent
                self._maps.pop(0)
            self._maps.append((A, parts))
        return _gather(A, parts)

    def sweep(self, on: bool) -> None:
        """Warm starts for a sweep over nearby problems (a Campbell diagram): while on, each Arnoldi
        run starts from the previous run's wanted subspace (the sum of its Ritz vectors) instead of
        the fixed vector; switching on or off forgets it, so a sweep's results depend only on its own
        sequence of speeds (reproducible), and single solves keep the fixed start."""
        self.warm_start = bool(on)
        for b in self.blocks:
            b.start = None

    def _blocks_of(self, A: sp.spmatrix | None, name: str) -> list:
        """The blocks of the free part of A (A None: the system's), cached while A is the same
        object (a rotor on constant bearings passes the same K at every speed)."""
        src = getattr(self.system, name) if A is None else A
        hit = self._split_cache.get(name)
        if hit is not None and hit[0] is src:
            return hit[1]
        parts = self._split(src)
        self._split_cache[name] = (src, parts)           # holding src keeps its id unique
        return parts

    def solve(self, n_modes: int = 6, *, speed: float = 0.0, K: sp.spmatrix | None = None,
              C: sp.spmatrix | None = None, tolerance: float = 1e-6, dense_max: int = 64) -> ComplexModalResult:
        """Lowest ``n_modes`` complex modes at ``speed`` (D = C + speed G); ``K``, ``C``
        replace the system's (full size; e.g. speed-dependent bearings)."""
        sys_ = self.system
        n_free = self.free.size
        if isinstance(n_modes, bool) or not isinstance(n_modes, (int, np.integer)) or not 1 <= n_modes <= n_free:
            raise ModelError("[analysis]", "modes", n_modes, f"an integer from 1 to {n_free} (the free DOFs)")
        if not np.isfinite(speed):
            raise ModelError("[analysis]", "speed", speed, "a finite speed (rad/s)")
        Ks, Cs, Gs, Ms = (self._blocks_of(K, "K"), self._blocks_of(C, "C"), self._blocks_of(None, "G"),
                          self._blocks_of(None, "M"))
        lams, vecs, res, rigid, blk, methods, notes = [], [], [], [], [], [], []
        mats = []
        for b_no, b in enumerate(self.blocks):
            Mb, Kb, Cb, Gb = Ms[b_no], Ks[b_no], Cs[b_no], Gs[b_no]
            if Gb.nnz and speed:
                Db = sp.csr_matrix((Cb.data + float(speed) * Gb.data, Cb.indices, Cb.indptr), shape=Cb.shape) \
                    if _same_pattern(Cb, Gb) else sp.csr_matrix(Cb + float(speed) * Gb)
            else:
                Db = Cb
            if Db.nnz and not np.any(Db.data):
                if b.zero is None:
                    b.zero = sp.csr_matrix(Db.shape)     # one empty D per block (an undamped block at every speed)
                Db = b.zero
            mats.append((Mb, Kb, Db, self._is_symmetric(b, Mb, Kb, Db)))
        # general (damped, gyroscopic) blocks first; then the symmetric ones only for the
        # eigenvalues below the n_modes-th found so far, counted exactly by Sylvester's inertia.
        # In a sweep: the symmetric blocks' rigid-body modes (lam = 0, counted) come first in the
        # result, so the general blocks need only the n_modes - n_rigid lowest (a rotor's free axial
        # and torsional lines: 2; a Campbell diagram's Arnoldi runs 1.3x faster).  Single solves keep
        # the full count: from a fixed start the smaller subspace needs restarts and saves nothing.
        order_blocks = sorted(range(len(self.blocks)), key=lambda i: mats[i][3])
        n_general = sum(not mats[i][3] for i in order_blocks)
        n_rigid = sum(self._rigid_count(self.blocks[i], mats[i][0], mats[i][1])
                      for i in order_blocks if mats[i][3]) if n_general and self.warm_start else 0
        need = max(1, n_modes - n_rigid)
        bound = None                      # with n_rigid > 0: the need-th |lam| of the general blocks
        for j, b_no in enumerate(order_blocks):
            b = self.blocks[b_no]
            Mb, Kb, Db, symmetric = mats[b_no]
            idx = b.dofs
            k = min(n_modes, idx.size)
            if not symmetric:
                k = min(need, idx.size)
            elif n_rigid and j == n_general:
                found = np.sort(np.where(np.concatenate(rigid), 0.0, np.abs(np.concatenate(lams))))
                bound = found[need - 1] if found.size >= need else None
            if symmetric and bound is not None:
                k = min(k, self._count_at(b, Mb, Kb, bound * bound * (1 + 1e-8) + 1e-300, n_modes))
                if k == 0:
                    continue
            elif symmetric and lams:
                k = min(k, self._count_below(b, Mb, Kb, np.concatenate(lams), np.concatenate(rigid), n_modes))
                if k == 0:
                    continue
            key = (Kb, Db)
            if b.cache_key is not None and _same(b.cache_key[0], Kb) and _same(b.cache_key[1], Db) \
                    and b.cache is not None and b.cache[0] >= k:
                lam, phi, r, rg, meth, note = b.cache[1]
            else:
                lam, phi, r, rg, meth, note = self._solve_block(b, Mb, Kb, Db, k, tolerance, dense_max, symmetric)
                b.cache_key, b.cache = key, (k, (lam, phi, r, rg, meth, note))
            lams.append(lam)
            full = np.zeros((n_free, lam.size), dtype=complex)
            full[idx] = phi
            vecs.append(full)
            res.append(r)
            rigid.append(rg)
            blk.append(np.full(lam.size, b_no))
            methods.append(meth)
            notes += note
        lam = np.concatenate(lams)
        order = np.lexsort((np.concatenate(blk), np.where(np.concatenate(rigid), 0.0, np.abs(lam))))[:n_modes]
        phi = np.hstack(vecs)[:, order]
        result = ComplexModalResult(eigenvalues=lam[order], shapes=sys_.expand(phi), residuals=np.concatenate(res)[order],
                                    rigid=np.concatenate(rigid)[order], block=np.concatenate(blk)[order],
                                    speed=float(speed), n_dofs=n_free,
                                    method="; ".join(sorted(set(methods))), tolerance=tolerance)
        result.warnings.extend(notes)
        if result.rigid.any():
            result.warnings.append(f"{int(result.rigid.sum())} rigid-body mode(s) (lam = 0): reported with omega = 0")
        for r in np.flatnonzero(~result.reliable):
            result.warnings.append(f"mode {r + 1}: residual {result.residuals[r]:.1e} above {tolerance:g}")
        return result

    # ------------------------------------------------------------------ one block
    @staticmethod
    def _is_symmetric(b: _Block, M, K, D) -> bool:
        """Undamped, non-gyroscopic, symmetric K and a positive definite-looking M (massless
        DOFs -- a massless shaft carrying discs -- make the symmetric solver's M-inner product
        degenerate: those blocks go to Arnoldi)."""
        if D.nnz or M.shape[0] < 2 or M.diagonal().min() <= 0:
            return False
        if b.sym_key is not None and _same(b.sym_key[0], K):      # the same values: a sweep's axial K
            return b.sym_key[1]
        if K.nnz == 0:
            sym = True
        else:
            perm = _transpose_positions(K)
            asym = abs(K - K.T).max() if perm is None else np.max(np.abs(K.data - K.data[perm]))
            sym = bool(asym <= 1e-14 * np.max(np.abs(K.data)))
        b.sym_key = (K, sym)
        return sym

    @staticmethod
    def _count_below(b: _Block, M, K, lam_found, rigid_found, n_modes) -> int:
        """How many eigenvalues of the symmetric block lie at or below the n_modes-th |lam|
        found so far (Sylvester's inertia of K - w^2 M); n_modes when unknown."""
        if lam_found.size < n_modes:
            return n_modes
        bound = np.sort(np.where(rigid_found, 0.0, np.abs(lam_found)))[n_modes - 1]
        return QuadraticEigensolver._count_at(b, M, K, bound * bound * (1 + 1e-8) + 1e-300, n_modes)

    @staticmethod
    def _rigid_count(b: _Block, M, K) -> int:
        """The rigid-body modes of a symmetric chain block (Sturm count): its eigenvalues w^2 at or
        below the level that :meth:`_symmetric` reports as rigid (1e3 eps of the largest K_ii / M_ii).
        0 for other blocks (their count would cost a sparse factorisation)."""
        if not _tridiagonal(b):
            return 0
        level = 1e3 * EPS * float(np.max(np.abs(K.diagonal()) / M.diagonal()))
        return QuadraticEigensolver._count_at(b, M, K, level, 0)

    @staticmethod
    def _count_at(b: _Block, M, K, shift: float, unknown: int) -> int:
        """The eigenvalues w^2 <= ``shift`` of the symmetric block (Sylvester's inertia of
        K - shift M); ``unknown`` when the count fails."""
        if _tridiagonal(b):                  # a chain (a rotor's axial or torsional line): Sturm count
            if b.chain_diagonals is None or not _same(b.chain_diagonals[0], K) or not _same(b.chain_diagonals[1], M):
                b.chain_diagonals = (K, M, K.diagonal(), M.diagonal(), K.diagonal(1), M.diagonal(1))
            _, _, kd, md, ke, me = b.chain_diagonals
            return sturm_count(kd - shift * md, ke - shift * me)
        try:
            if b.shifted is None or b.shifted[0] is not K:
                b.shifted = (K, ShiftedSolver(K, M))
            return int(b.shifted[1].inertia(shift))
        except (SolverError, ValueError, np.linalg.LinAlgError):
            return unknown

    def _solve_block(self, b: _Block, M, K, D, k, tolerance, dense_max, symmetric):
        n = M.shape[0]
        notes = []
        if symmetric:
            return self._symmetric(b, M, K, k, tolerance) + (notes,)
        if 2 * n <= dense_max or 4 * k + 5 >= n:          # ARPACK's subspace would be about the whole space
            lam, phi, sigma = _dense(M, K, D)
            method = "dense shift-invert of the linearisation (tiny block)"
        else:
            if b.layout is None:
                b.layout = BandedLU(b.pattern)
            lam, phi, sigma = self._arnoldi(b, M, K, D, k)
            method = "shift-invert Arnoldi (eigs) of the linearised quadratic problem"
        lam, phi = _one_of_each_pair(lam, phi)
        scale = max(_scale(M, K), 1e-300)
        # rigid-body eigenvalues are defective (q = a + b t): computed to about tau sqrt(eps) cond,
        # measured 1e-3 tau for a free-free rotor; anything below tau / 100 is a rigid-body motion
        level = (1e-2 * abs(sigma)) if sigma else 1e-9 * scale
        rigid = np.abs(lam) <= level
        lam = np.where(rigid, 0.0, lam)
        order = np.lexsort((np.abs(lam.imag), np.abs(lam)))
        lam, phi, rigid = lam[order][:k], phi[:, order][:, :k], rigid[order][:k]
        phi = _normalise(phi)
        res = _residuals(M, K, D, lam, phi)
        return lam, phi, res, rigid, method, notes

    def _symmetric(self, b: _Block, M, K, k, tolerance):
        """K phi = w^2 M phi of an undamped block: dense for tiny blocks, else Lanczos (eigsh) in
        shift-invert mode at -tau (tau = 1e-8 of the largest K_ii/M_ii: rigid-body modes at 0 are
        found in the same single pass), with the block's banded LU of K + tau M."""
        n = M.shape[0]
        lam_max = float(np.max(np.abs(K.diagonal()) / M.diagonal()))
        if n <= 64 or k >= n - 1:
            w2, vec = sla.eigh(K.toarray(), M.toarray(), subset_by_index=[0, k - 1])
            method = "dense eigh (tiny undamped block)"
        else:
            tau = 1e-8 * lam_max
            fac = _TridiagonalFactor.of(K, M, tau) if _tridiagonal(b) else None
            if fac is None:
                if b.layout is None:
                    b.layout = BandedLU(b.pattern)
                fac = b.layout.factor(_data_on(b.layout, sp.csr_matrix(K + tau * M)))
            got = _subspace_iteration(K, M, k, fac) if k <= 8 else None
            if got is not None:
                w2, vec = got
                method = "symmetric shift-invert subspace iteration (undamped block, Sylvester-counted)"
            else:
                op = spla.LinearOperator((n, n), matvec=fac.solve, dtype=float)
                with _warnings.catch_warnings(), single_threaded_blas():
                    _warnings.simplefilter("ignore", sp.SparseEfficiencyWarning)
                    v0 = _fixed_start(0.5, 1.5, n)
                    w2, vec = spla.eigsh(K, k=k, M=M, sigma=-tau, which="LM", OPinv=op, v0=v0,
                                         ncv=min(n, max(2 * k + 1, 20)), tol=0.0)
                method = "symmetric shift-invert Lanczos (undamped block)"
        order = np.argsort(w2)
        w2, vec = w2[order], vec[:, order]
        rigid = w2 <= 1e3 * EPS * lam_max
        lam = 1j * np.sqrt(np.clip(np.where(rigid, 0.0, w2), 0.0, None))
        phi = _normalise(vec.astype(complex))
        res = _residuals(M, K, None, lam, phi)
        return lam, phi, res, rigid, method

    def _arnoldi(self, b: _Block, M, K, D, k):
        n = M.shape[0]
        lay = b.layout
        fac = None
        sigma = 0.0
        if b.k_factor is not None and _same(b.k_factor[0], K):
            fac, sigma = b.k_factor[1], b.k_factor[2]
        if fac is None:
            fac, sigma = self._factor_shift(lay, M, K, D, _data_on(lay, K))
            if sigma == 0.0:
                b.k_factor = (K, fac, 0.0)
        Ds = sp.csr_matrix(D + sigma * M) if sigma else D
        DM = _side_by_side(b, Ds, M)                     # (D + s M) y1 + M y2 in one product
        product = _csr_matvec(DM)
        solve = fac.solve_vector if hasattr(fac, "solve_vector") else fac.solve

        def op(y):
            x1 = solve(product(y))
            out = np.empty(2 * n)
            out[:n] = -x1
            out[n:] = y[:n] - sigma * x1 if sigma else y[:n]
            return out

        N = 2 * n
        kk = min(2 * k + 2, N - 2)
        ncv = min(N, max(2 * kk + 1, 24))
        A = _Operator(N, op)
        start = _fixed_start(0.5, 1.5, N)                  # fixed start: reproducible results
        if self.warm_start and b.start is not None and b.start.size == N:
            start = b.start         # a sweep: the previous solve's wanted subspace (its order fixes the results)
        with _warnings.catch_warnings(), single_threaded_blas():
            _warnings.simplefilter("ignore", sp.SparseEfficiencyWarning)
            for attempt in range(3):
                try:
                    mu, Z = spla.eigs(A, k=kk, which="LM", ncv=ncv, v0=start, tol=1e-13, maxiter=ARNOLDI_RESTARTS)
                    break
                except spla.ArpackNoConvergence as exc:
                    mu, Z = exc.eigenvalues, exc.eigenvectors
                    # an undamped rotor with cross-coupled bearings has eigenvalues in quadruples of
                    # one modulus (lam, -lam, conj): a count that cuts a quadruple stalls the
                    # restarts; two more eigenvalues take the whole group
                    if attempt == 2 or kk + 2 > N - 2:
                        break
                    kk += 2
                    ncv = min(N, max(2 * kk + 1, 24))
            if mu.size == 0:
                raise SolverError("ARPACK did not converge for the quadratic eigenproblem")
        keep = np.abs(mu) > 0
        mu, Z = mu[keep], Z[:, keep]
        if self.warm_start and Z.size:
            W = Z / np.linalg.norm(Z, axis=0)
            b.start = (W.real + W.imag).sum(axis=1)
        lam = sigma + 1.0 / mu
        top, bottom = Z[:n], Z[n:]
        # z = (phi, lam phi): take the better-scaled half
        use_bottom = np.abs(lam) > 1.0
        phi = np.where(use_bottom[None, :], bottom / np.where(use_bottom, lam, 1.0)[None, :], top)
        return lam, phi, sigma

    def _factor_shift(self, lay: BandedLU, M, K, D, kdata):
        """Factor K (shift 0) if it is safely non-singular, else Q(-tau) = K - tau D + tau^2 M."""
        scale = _scale(M, K)
        try:
            fac = lay.factor(kdata)
            if lay.banded:
                piv = np.abs(_band_diagonal(lay, fac))
                if piv.min() > 1e3 * EPS * piv.max():
                    return fac, 0.0
            else:
                piv = np.abs(fac.splu[0].U.diagonal())
                if piv.min() > 1e3 * EPS * piv.max():
                    return fac, 0.0
        except SolverError:
            pass
        tau = 1e-6 * scale
        Q = sp.csr_matrix(K - tau * D + tau * tau * M)
        try:
            return lay.factor(_data_on(lay, Q)), -tau
        except SolverError:
            tau *= 3.7
            Q = sp.csr_matrix(K - tau * D + tau * tau * M)
            return lay.factor(_data_on(lay, Q)), -tau


class _Operator(spla.LinearOperator):
    """The Arnoldi operator: ARPACK's vectors go to ``op`` as they are (LinearOperator.matvec's
    shape checks and reshapes cost as much as the banded solve on a few hundred unknowns)."""

    def __init__(self, n: int, op):
        self._op = op                  # before LinearOperator.__init__, which checks for a _matvec
        super().__init__(np.dtype(float), (n, n))
        self.matvec = op

    def _matvec(self, x):
        return self._op(x)


def _csr_matvec(A: sp.csr_matrix):
    """y -> A @ y for real float64 vectors, the same kernel as scipy's ``A @ y``
    (``_sparsetools.csr_matvec`` into a zeroed array) without its dispatch; ``A @ y`` where that
    private kernel is not there."""
    try:
        from scipy.sparse import _sparsetools
        kernel = _sparsetools.csr_matvec
    except (ImportError, AttributeError):          # pragma: no cover - another scipy layout
        return lambda y: A @ y
    m, n = A.shape
    indptr, indices, data = A.indptr, A.indices, A.data
    if data.dtype != np.float64:
        return lambda y: A @ y

    def product(y):
        if y.dtype != np.float64 or y.shape != (n,):
            return A @ y
        out = np.zeros(m)
        kernel(m, n, indptr, indices, data, y, out)
        return out
    return product


_TRANSPOSE_CACHE: dict = {}


def _transpose_positions(A: sp.csr_matrix) -> np.ndarray | None:
    """perm with A.T.data == A.data[perm] on A's own (canonical) pattern, or None when the pattern
    is not symmetric; cached per pattern object (blocks split on one map share their arrays)."""
    key = pattern_key(A)
    hit = _TRANSPOSE_CACHE.get(key)
    if hit is not None and same_array(hit[0], A.indices) and same_array(hit[1], A.indptr):
        return hit[2]
    n = A.shape[0]
    rows = _csr_rows(A)
    keys = rows * n + A.indices
    tkeys = A.indices.astype(np.int64) * n + rows
    pos = np.minimum(np.searchsorted(keys, tkeys), keys.size - 1)
    perm = pos if np.array_equal(keys[pos], tkeys) else None
    if len(_TRANSPOSE_CACHE) > 64:
        _TRANSPOSE_CACHE.clear()
    _TRANSPOSE_CACHE[key] = (A.indices, A.indptr, perm)   # holding the arrays keeps their buffers unique
    return perm


def _side_by_side(b: _Block, A: sp.csr_matrix, B: sp.csr_matrix) -> sp.csr_matrix:
    """[A, B] (canonical CSR, same number of rows); where both lie on patterns seen before the
    positions of their entries are reused (cached on the block)."""
    hit = b.hstack_map
    if not (hit is not None and same_array(hit[0], A.indices) and same_array(hit[1], A.indptr)
            and same_array(hit[2], B.indices) and same_array(hit[3], B.indptr)):
        n = A.shape[0]
        rows = np.concatenate([_csr_rows(A), _csr_rows(B)])
        order = np.argsort(rows, kind="stable")          # row by row: A's columns, then B's (shifted)
        cols = np.concatenate([A.indices, B.indices + A.shape[1]])[order]
        indptr = np.concatenate([[0], np.cumsum(np.bincount(rows, minlength=n))]).astype(A.indptr.dtype)
        hit = b.hstack_map = (A.indices, A.indptr, B.indices, B.indptr, order, cols.astype(A.indices.dtype), indptr)
    order, cols, indptr = hit[4], hit[5], hit[6]
    data = np.concatenate([A.data, B.data])[order]
    return sp.csr_matrix((data, cols, indptr), shape=(A.shape[0], A.shape[1] + B.shape[1]))


def _tridiagonal(b: _Block) -> bool:
    """Whether the block's pattern couples consecutive DOFs only (a chain), cached on the block."""
    if b.tridiagonal is None:
        P = b.pattern
        rows = _csr_rows(P)
        b.tridiagonal = bool(P.shape[0] > 1 and np.all(np.abs(rows - P.indices) <= 1))
    return b.tridiagonal


@dataclass
class _TridiagonalFactor:
    """LDL^T of the symmetric positive definite tridiagonal K + tau M (LAPACK ``dpttrf``)."""

    d: np.ndarray
    e: np.ndarray

    @classmethod
    def of(cls, K, M, tau) -> "_TridiagonalFactor | None":
        d, e, info = lapack.dpttrf(K.diagonal() + tau * M.diagonal(), K.diagonal(1) + tau * M.diagonal(1))
        return cls(d, e) if info == 0 else None             # not positive definite: the banded LU

    def solve_columns(self, B: np.ndarray) -> np.ndarray:
        x, info = lapack.dpttrs(self.d, self.e, B)
        return x

    def solve(self, b: np.ndarray) -> np.ndarray:
        """One right-hand side (the Lanczos fallback's operator)."""
        return self.solve_columns(np.asarray(b, dtype=float))


def _subspace_iteration(K, M, k, fac, tol: float = 1e-14, max_iter: int = 60):
    """Lowest k eigenpairs of K x = w2 M x by inverse subspace iteration with Rayleigh-Ritz
    (``fac``: LU of K + tau M, tau tiny): p = k + 3 vectors; converged when the k Ritz residuals
    ||K x - w2 M x|| / ((||K|| + |w2| ||M||) ||x||) are below ``tol``.  Fast when the k wanted
    eigenvalues are well separated from the next (rigid-body and low rod modes); None if not
    converged (the caller then uses Lanczos)."""
    n = K.shape[0]
    p = min(k + 3, n)
    nK, nM = _norm1(K), _norm1(M)
    X = _fixed_start(-1.0, 1.0, n, p)
    for _ in range(max_iter):
        Y = fac.solve_columns(M @ X)
        Kr, Mr = Y.T @ (K @ Y), Y.T @ (M @ Y)
        # LAPACK's dsygvd, as scipy.linalg.eigh(A, B) calls it, without the wrapper's checks
        # (a quarter of the small solve's time)
        w2, S, info = lapack.dsygvd(0.5 * (Kr + Kr.T), 0.5 * (Mr + Mr.T))
        if info != 0:
            return None
        X = Y @ S
        Xk = X[:, :k]
        KX, MX = K @ Xk, M @ Xk
        r = np.linalg.norm(KX - MX * w2[None, :k], axis=0)
        scale = (nK + np.abs(w2[:k]) * nM) * np.linalg.norm(Xk, axis=0)
        if np.all(r <= tol * np.maximum(scale, 1e-300)):
            return w2[:k], Xk
    return None


@functools.lru_cache(maxsize=32)
def _fixed_start(low: float, high: float, *shape: int) -> np.ndarray:
    """The fixed pseudo-random start of the iterative solvers (seed 12345: reproducible results),
    made once per shape and read-only (the solvers copy or only read it)."""
    x = np.random.default_rng(12345).uniform(low, high, shape)
    x.flags.writeable = False
    return x


def _data_on(lay: BandedLU, A: sp.spmatrix) -> np.ndarray:
    """Values of A at the pattern positions of ``lay`` (A's entries must lie on the pattern)."""
    A = _canonical(A)
    key = pattern_key(A)
    hit = lay.data_maps.get(key)
    if hit is not None and same_array(hit[0], A.indices) and same_array(hit[1], A.indptr):
        pos, ok = hit[2], hit[3]
    else:
        n = lay.n
        pkeys = lay._rows.astype(np.int64) * n + lay._cols
        akeys = _csr_rows(A) * n + A.indices
        pos = np.searchsorted(pkeys, akeys)
        ok = (pos < pkeys.size) & (pkeys[np.minimum(pos, pkeys.size - 1)] == akeys)
        if len(lay.data_maps) > 16:
            lay.data_maps.clear()
        lay.data_maps[key] = (A.indices, A.indptr, pos, ok)    # the arrays held: their buffers stay unique
    if not np.all(ok | (A.data == 0)):
        raise ValueError("a matrix entry lies outside the solver's sparsity pattern")
    out = np.zeros(lay._rows.size, dtype=A.dtype)
    if ok.all():
        out[pos] = A.data            # canonical A: every position once
    else:
        out[pos[ok]] = A.data[ok]
    return out


def _scale(M, K) -> float:
    """sqrt(max K_ii / M_ii): the order of the largest natural frequency (rad/s)."""
    k, m = np.abs(K.diagonal()), M.diagonal()
    mask = m > 0
    if not mask.any():
        raise ModelError("", "mass", 0.0, "a model with some inertia (all masses are zero)")
    return float(np.sqrt(np.max(k[mask] / m[mask]))) or 1.0


def _dense(M, K, D):
    """All eigenpairs of a tiny block from the dense shift-invert operator
    T = (A - s B)^-1 B = [[-Q^-1 Ds, -Q^-1 M], [I - s Q^-1 Ds, -s Q^-1 M]] (Q = K + s D + s^2 M,
    Ds = D + s M; s = 0 unless K is singular): its largest eigenvalues mu = 1/(lam - s), the low
    modes, come out accurate relative to themselves, unlike a QZ of the unscaled linearisation
    (whose error is eps times the largest K_ii / M_ii).  Returns (lam, phi, s)."""
    n = M.shape[0]
    Md, Kd, Dd = M.toarray(), K.toarray(), D.toarray()
    scale = _scale(M, K)
    for sigma in (0.0, -1e-6 * scale, -3.7e-6 * scale):
        Q = Kd + sigma * Dd + sigma * sigma * Md
        with _warnings.catch_warnings():           # a singular K (free rotor) is detected below
            _warnings.simplefilter("ignore", sla.LinAlgWarning)
            lu, piv = sla.lu_factor(Q, check_finite=False)
        d = np.abs(np.diag(lu))
        if d.min() > 1e3 * EPS * d.max():
            break
    Ds = Dd + sigma * Md
    X = sla.lu_solve((lu, piv), np.hstack([Ds, Md]), check_finite=False)
    T = np.empty((2 * n, 2 * n))
    T[:n, :n], T[:n, n:] = -X[:, :n], -X[:, n:]
    T[n:, :n] = np.eye(n) - sigma * X[:, :n]
    T[n:, n:] = -sigma * X[:, n:]
    mu, Z = sla.eig(T, check_finite=False)
    keep = np.abs(mu) > 1e-13 * np.max(np.abs(mu))          # mu = 0: infinite lam (massless DOFs)
    mu, Z = mu[keep], Z[:, keep]
    lam = sigma + 1.0 / mu
    big = np.abs(lam) > 1.0
    phi = np.where(big[None, :], Z[n:] / np.where(big, lam, 1.0)[None, :], Z[:n])
    return lam, phi, sigma


def _one_of_each_pair(lam, phi):
    """Keep Im lam >= 0 (real eigenvalues once, conjugate partners dropped)."""
    tol = 1e-10 * np.maximum(np.abs(lam), 1e-300)
    keep = lam.imag > tol
    real = np.abs(lam.imag) <= tol
    lam = np.where(real, lam.real + 0j, lam)
    return lam[keep | real], phi[:, keep | real]


_NORM_KEPT: list = []


def _norm1_kept(A) -> float:
    """:func:`_norm1` of a matrix that is passed again and again (a block's M): kept for the last
    few matrix objects (held, so their ids stay unique)."""
    for B, v in _NORM_KEPT:
        if B is A:
            return v
    v = _norm1(A)
    _NORM_KEPT.insert(0, (A, v))
    del _NORM_KEPT[4:]
    return v


def _normalise(phi):
    if phi.size == 0:
        return phi
    k = np.argmax(np.abs(phi), axis=0)
    piv = phi[k, np.arange(phi.shape[1])]
    piv = np.where(piv == 0, 1.0, piv)
    return phi / piv[None, :]


def _residuals(M, K, D, lam, phi):
    if lam.size == 0:
        return np.zeros(0)
    R = K @ phi
    if D is not None:                     # None: undamped (the terms in this order: results bit-stable)
        R = R + (D @ phi) * lam[None, :]
    R = R + (M @ phi) * (lam**2)[None, :]
    denom = (np.abs(lam) ** 2 * _norm1_kept(M) + np.abs(lam) * _norm1(D) + _norm1(K)) * np.linalg.norm(phi, axis=0)
    return np.linalg.norm(R, axis=0) / np.where(denom > 0, denom, 1.0)


def complex_modal_analysis(system: LinearSystem, n_modes: int = 6, *, speed: float = 0.0,
                           tolerance: float = 1e-6, dense_max: int = 64) -> ComplexModalResult:
    """Lowest ``n_modes`` complex modes of ``system`` at ``speed`` (D = C + speed G); see the
    module notes.  For repeated solves on one system use :class:`QuadraticEigensolver`."""
    return QuadraticEigensolver(system).solve(n_modes, speed=speed, tolerance=tolerance, dense_max=dense_max)
