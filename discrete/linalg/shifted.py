"""Factorisations of ``K - s M`` for many shifts at once, and the Sylvester inertia count.

Drive and FE-plus-lumped models hang many one-DOF attachments (mechanisms, absorbers) on a
banded core (the shaft).  An attachment DOF -- a *leaf* -- couples to exactly one core DOF
and carries a diagonal mass, so it is condensed exactly: the Schur complement only changes
the core diagonal by ``-a_lc^2 / a_ll``.  The core is banded after reverse Cuthill-McKee
ordering.  The shifted cores for all shifts are stacked along the diagonal of one band
matrix and factorised by one LAPACK call (``dgttrf`` for a tridiagonal core, ``dgbtrf``
otherwise): measured on the 2000-DOF drive of ``benchmarks/drives.py`` (1000-DOF
tridiagonal core), 21 separate ``dgbtrf`` + ``dgbtrs`` calls on the uncondensed matrix cost
2.1 ms, the stacked condensed pair 0.5 ms.

The inertia follows from the same congruence (Sylvester's law of inertia): the number of
negative eigenvalues of ``K - s M`` is the number of negative leaf pivots plus that of the
Schur complement -- a Sturm count (LAPACK ``dstebz``) for a tridiagonal core, the LDL^T
pivots of SuperLU with diagonal pivoting and a symmetric ordering otherwise.  For positive
semi-definite ``M`` it is the number of eigenvalues below ``s``.

Blocks of vectors are stored one vector per row, shape ``(q, n)``, one row per shift.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.linalg import lapack
from scipy.sparse.csgraph import reverse_cuthill_mckee

from ..errors import SolverError

EPS = np.finfo(float).eps


def is_diagonal(A: sp.spmatrix) -> bool:
    """Whether A stores entries on its diagonal only."""
    A = sp.csr_matrix(A)
    return bool(np.array_equal(A.indices, np.repeat(np.arange(A.shape[0]), np.diff(A.indptr))))


def sturm_count(d: np.ndarray, e: np.ndarray) -> int:
    """Number of negative eigenvalues of the symmetric tridiagonal matrix with diagonal d and
    off-diagonal e: LAPACK ``dstebz`` with a tolerance wider than the spectrum counts at the
    interval ends and bisects nothing (it counts (-inf, 0]: callers take the count between
    eigenvalues, never on one)."""
    if d.size == 1:
        return int(d[0] < 0)
    return int(lapack.dstebz(d, e, 1, -np.inf, 0.0, 0, 0, np.inf, "B")[0])


class ShiftedSolver:
    """Solves ``(K - s_j M) x_j = b_j`` for a set of shifts ``s_j`` (see the module notes).

    ``K`` and ``M`` are the symmetric free-DOF matrices.  ``leaves`` and ``bandwidth`` tell
    what structure was found (a model without leaves is all core)."""

    def __init__(self, K: sp.spmatrix, M: sp.spmatrix):
        K, M = sp.csr_matrix(K), sp.csr_matrix(M)
        if not K.has_canonical_format:
            K = K.copy()                      # the caller's matrix stays as it is
            K.sum_duplicates()
        n = K.shape[0]
        Kc = K.tocoo()
        k_diag = K.diagonal()
        m_diag = M.diagonal()
        diagonal_mass = is_diagonal(M)
        # off-diagonal pattern of K and M, each coupling once (K canonical: unique entries)
        k_off = (Kc.row != Kc.col) & (Kc.data != 0)
        rows, cols = Kc.row[k_off], Kc.col[k_off]
        m_coupled = np.zeros(n, dtype=bool)
        if not diagonal_mass:
            Mc = M.tocoo()
            m_off = (Mc.row != Mc.col) & (Mc.data != 0)
            m_coupled[Mc.row[m_off]] = True
            keys = np.unique(np.concatenate([rows * n + cols, Mc.row[m_off] * n + Mc.col[m_off]]))
            rows, cols = keys // n, keys % n
        degree = np.bincount(rows, minlength=n)
        candidate = (degree <= 1) & ~m_coupled
        first = np.full(n, -1)
        one = degree[rows] == 1
        first[rows[one]] = cols[one]
        # a leaf hangs on a core DOF: two candidates coupled to each other stay in the core
        leaf = candidate & ~((degree == 1) & candidate[np.maximum(first, 0)])
        core = np.flatnonzero(~leaf)
        pos = np.full(n, -1)
        pos[core] = np.arange(core.size)
        in_core = (pos[rows] >= 0) & (pos[cols] >= 0)
        cr, cc = pos[rows[in_core]], pos[cols[in_core]]
        natural = int(np.max(np.abs(cr - cc))) if cr.size else 0
        perm = None
        if natural > 2:             # a narrow natural band is kept; a wide one is reordered
            pattern = sp.csr_matrix((np.ones(cr.size), (cr, cc)), shape=(core.size, core.size))
            rcm = reverse_cuthill_mckee(pattern, symmetric_mode=True)
            inv = np.empty_like(rcm)
            inv[rcm] = np.arange(rcm.size)
            if np.max(np.abs(inv[cr] - inv[cc])) < natural:
                perm, cr, cc = rcm, inv[cr], inv[cc]
        self.n = n
        self.core_idx = core if perm is None else core[perm]      # core DOFs in band order
        self.leaf_idx = np.flatnonzero(leaf)
        rank = np.full(n, -1)
        rank[self.core_idx] = np.arange(core.size)
        self.bandwidth = int(np.max(np.abs(cr - cc))) if cr.size else 0
        target = first[self.leaf_idx]
        # an unattached leaf (a grounded mass) points at core DOF 0 with zero coupling
        self.leaf_core = np.where(target >= 0, rank[np.maximum(target, 0)], 0) if core.size else np.zeros(0, int)
        self.leaf_k = k_diag[self.leaf_idx]
        self.leaf_m = m_diag[self.leaf_idx]
        # a leaf row holds its diagonal and at most one coupling, read directly (K summed: one entry)
        self.leaf_c = np.zeros(self.leaf_idx.size)
        leaf_no = np.full(n, -1)
        leaf_no[self.leaf_idx] = np.arange(self.leaf_idx.size)
        hit = k_off & (leaf_no[Kc.row] >= 0) & (first[Kc.row] == Kc.col)
        self.leaf_c[leaf_no[Kc.row[hit]]] = Kc.data[hit]
        self._unique = self.leaf_core.size == 0 or bool(np.bincount(self.leaf_core).max() <= 1)
        # index arrays that are contiguous ranges become slices: views instead of copies
        self._core, self._leaf, self._target = (_as_index(a) for a in (self.core_idx, self.leaf_idx, self.leaf_core))
        self._aligned = (isinstance(self._target, slice) and self._target == slice(0, core.size)
                         and self.leaf_idx.size == core.size > 0)
        b = self.bandwidth
        self._kband = self._band(Kc, rank, b)
        if diagonal_mass:
            self._mband = np.zeros_like(self._kband)
            self._mband[2 * b] = m_diag[self.core_idx]
        else:
            self._mband = self._band(M.tocoo(), rank, b)
        self._K, self._M, self._rank = Kc, M, rank

    @property
    def stiffness_coo(self) -> sp.coo_matrix:
        """K in summed COO form (each entry once)."""
        return self._K

    @property
    def leaves(self) -> int:
        return int(self.leaf_idx.size)

    @staticmethod
    def _band(A: sp.coo_matrix, rank: np.ndarray, b: int) -> np.ndarray:
        """Core block in LAPACK general band storage with room for the LU fill:
        A[i, j] at [2b + i - j, j] (i, j band-order positions); duplicates summed."""
        i, j = rank[A.row], rank[A.col]
        keep = (i >= 0) & (j >= 0) & (A.data != 0)      # stored zeros may lie outside the band
        nc = int(np.count_nonzero(rank >= 0))
        flat = (2 * b + i[keep] - j[keep]) * nc + j[keep]
        return np.bincount(flat, weights=A.data[keep], minlength=(3 * b + 1) * nc).reshape(3 * b + 1, nc)

    def _leaf_pivots(self, shifts: np.ndarray) -> np.ndarray:
        """(q, n_leaves) pivots K_ll - s M_ll."""
        a = self.leaf_k[None, :] - shifts[:, None] * self.leaf_m[None, :]
        if np.any(np.abs(a) <= 64 * EPS * np.abs(self.leaf_k)[None, :]):
            raise SolverError("a shift coincides with the natural frequency of a grounded attachment DOF "
                              "(zero leaf pivot): move the shift")
        return a

    def _scatter_sub(self, core_rows: np.ndarray, leaf_rows: np.ndarray) -> None:
        """core_rows[:, leaf_core] -= leaf_rows (in place; several leaves may share a core DOF)."""
        if not self.leaf_core.size or not core_rows.shape[1]:
            return
        if self._unique:
            core_rows[:, self._target] -= leaf_rows
        else:
            for r in range(core_rows.shape[0]):
                np.subtract.at(core_rows[r], self.leaf_core, leaf_rows[r])

    def _core_diagonal(self, s: np.ndarray, a: np.ndarray) -> np.ndarray:
        """(q, n_core) diagonal of the condensed cores: K - s M minus a_lc^2 / a_ll from the leaves."""
        b = self.bandwidth
        diag = self._kband[2 * b][None, :] - s[:, None] * self._mband[2 * b][None, :]
        self._scatter_sub(diag, self.leaf_c[None, :] ** 2 / a)
        return diag

    def _core_subdiagonal(self, s: np.ndarray) -> np.ndarray:
        """(q, n_core) first subdiagonal of a tridiagonal core (last column: no neighbour)."""
        return self._kband[3][None, :] - s[:, None] * self._mband[3][None, :]

    def factor(self, shifts) -> "ShiftedFactors":
        s = np.atleast_1d(np.asarray(shifts, dtype=float))
        a = self._leaf_pivots(s)
        q, nc, b = s.size, self.core_idx.size, self.bandwidth
        if nc == 0:
            return ShiftedFactors(self, s, a, None)
        diag = self._core_diagonal(s, a)
        if b <= 1 and q * nc >= 3:                  # (LAPACK's tridiagonal wrappers want n >= 3)
            off = self._core_subdiagonal(s) if b == 1 else np.zeros((q, nc))
            off[:, -1] = 0.0                          # no coupling between stacked blocks
            e = off.ravel()[:-1]
            dl, dd, du, du2, ipiv, info = lapack.dgttrf(e, diag.ravel(), e.copy())
            lu = ("gt", dl, dd, du, du2, ipiv)
        else:
            be = max(b, 1)
            bands = np.zeros((3 * be + 1, q, nc))
            for d in range(-b, b + 1):                # band row of offset i - j: 2 b + d here, 2 be + d there
                bands[2 * be + d] = self._kband[2 * b + d][None, :] - s[:, None] * self._mband[2 * b + d][None, :]
            bands[2 * be] = diag
            lu_, ipiv, info = lapack.dgbtrf(bands.reshape(3 * be + 1, q * nc), be, be)
            lu = ("gb", lu_, ipiv, be)
        if info > 0:
            raise SolverError(f"K - s M is exactly singular at a shift in {s.tolist()}: move the shift")
        return ShiftedFactors(self, s, a, lu)

    def inertia(self, shift: float) -> int:
        """Number of negative eigenvalues of K - shift M (eigenvalues below ``shift``)."""
        s = np.array([float(shift)])
        a = self._leaf_pivots(s)
        negative = int(np.count_nonzero(a < 0))
        nc, b = self.core_idx.size, self.bandwidth
        if nc == 0:
            return negative
        diag = self._core_diagonal(s, a)
        if b <= 1:
            e = self._core_subdiagonal(s)[0, :-1] if b == 1 else np.zeros(nc - 1)
            if nc == 1:
                return negative + int(diag[0, 0] < 0)
            return negative + sturm_count(diag[0], e)
        core = self.core_idx
        S = (sp.csr_matrix(self._K)[core][:, core] - shift * sp.csr_matrix(self._M)[core][:, core]).tolil()
        S.setdiag(diag[0])
        try:
            lu = spla.splu(sp.csc_matrix(S), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                           options={"SymmetricMode": True})
        except RuntimeError as exc:
            raise SolverError(f"K - s M is singular at s = {shift:.17g}: move the shift ({exc})") from None
        if not np.array_equal(lu.perm_r, lu.perm_c):
            raise SolverError(f"no symmetric LDL^T pivoting of K - s M at s = {shift:.17g}: inertia unavailable")
        return negative + int(np.count_nonzero(lu.U.diagonal() < 0))


@dataclass
class ShiftedFactors:
    solver: ShiftedSolver
    shifts: np.ndarray
    leaf_pivots: np.ndarray          # (q, n_leaves)
    lu: tuple | None

    def __post_init__(self):
        self.ratio = self.solver.leaf_c[None, :] / self.leaf_pivots        # a_lc / a_ll
        self.inverse = 1.0 / self.leaf_pivots

    def solve(self, B: np.ndarray) -> np.ndarray:
        """Row j of the result solves (K - shifts[j] M) x = B[j]  (B of shape (q, n)); a
        factorisation of a single shift solves every row of B with it."""
        sv = self.solver
        B = np.atleast_2d(np.asarray(B, dtype=float))
        q, nc, single = B.shape[0], sv.core_idx.size, self.shifts.size == 1
        if not single and q != self.shifts.size:
            raise ValueError(f"{q} right-hand sides for {self.shifts.size} shifts")
        bl = B[:, sv._leaf]
        if sv._aligned:                                 # leaf i hangs on core DOF i: no scatter
            bc = B[:, sv._core] - bl * self.ratio
        else:
            bc = np.array(B[:, sv._core])
            sv._scatter_sub(bc, bl * self.ratio)
        if nc:
            rhs = bc.T if single else bc.ravel()        # one factor, q columns | q stacked blocks
            if self.lu[0] == "gt":
                _, dl, dd, du, du2, ipiv = self.lu
                xc, info = lapack.dgttrs(dl, dd, du, du2, ipiv, rhs)
            else:
                _, lu, ipiv, be = self.lu
                xc, info = lapack.dgbtrs(lu, be, be, rhs, ipiv)
            xc = xc.T if single else xc.reshape(q, nc)
        else:
            xc = np.zeros((q, 0))
        X = np.empty((q, sv.n))
        X[:, sv._core] = xc
        leaf = bl * self.inverse
        if nc:
            leaf -= self.ratio * xc[:, sv._target]
        X[:, sv._leaf] = leaf
        return X


def _as_index(idx: np.ndarray):
    """A slice for a contiguous ascending range (basic indexing: a view), else the array."""
    if idx.size and idx[-1] - idx[0] == idx.size - 1 and np.all(np.diff(idx) == 1):
        return slice(int(idx[0]), int(idx[-1]) + 1)
    return idx
