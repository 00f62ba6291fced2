"""Banded LU factorisations of sparse matrices that share one sparsity pattern.

:class:`BandedLU` computes once per pattern a reverse Cuthill-McKee ordering (when it narrows the
band) and the position of every stored entry in LAPACK band storage; each factorisation is then
one LAPACK ``?gbtrf`` call on the matrix's data, and many matrices on the pattern can be factorised
in one call by stacking them along the band (a rotor at many speeds or frequencies).  A band that
stays wide falls back to SuperLU.  On the narrow bands of beams, shafts and rotors, LAPACK's
banded solve is several times faster than SuperLU's supernodal one (``dgbtrs``: 0.05 ms against
0.2-0.35 ms at 2000 unknowns, measured), which is why :mod:`discrete.linalg.sparse_direct` uses it
for large narrow-band matrices too.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.linalg import lapack
from scipy.sparse.csgraph import reverse_cuthill_mckee

from ..errors import SolverError


def _csr_rows(A: sp.csr_matrix) -> np.ndarray:
    """The row index of every stored entry of the CSR matrix A (int64: safe in row * n + col keys)."""
    return np.repeat(np.arange(A.shape[0], dtype=np.int64), np.diff(A.indptr))


def same_array(a: np.ndarray, b: np.ndarray) -> bool:
    """``a`` and ``b`` are the same memory (one object, or views of one buffer with the same
    layout): scipy's CSR constructor wraps the index arrays it is given in new views, so pattern
    caches compare buffers, not objects.  A cache that compares with a held array keeps that
    buffer alive, so an equal address cannot belong to a later allocation."""
    return a is b or (a.dtype == b.dtype and a.shape == b.shape and a.strides == b.strides
                      and a.__array_interface__["data"][0] == b.__array_interface__["data"][0])


def pattern_key(A: sp.csr_matrix) -> tuple:
    """Dictionary key of a CSR matrix's index arrays by their buffers (see :func:`same_array`);
    a cache holds the arrays with the key and checks them with :func:`same_array`."""
    return (A.indices.__array_interface__["data"][0], A.indptr.__array_interface__["data"][0], A.indices.size,
            A.shape)


def _canonical(A: sp.spmatrix) -> sp.csr_matrix:
    """A as CSR with sorted, unique indices (A itself when it already is)."""
    A = A if sp.isspmatrix_csr(A) else sp.csr_matrix(A)
    if not A.has_canonical_format:
        A = A.copy()
        A.sum_duplicates()
    return A


class BandedLU:
    """LU factorisations of square matrices that share the sparsity ``pattern`` (CSR).

    The ordering (reverse Cuthill-McKee when it narrows the band) and the position of every
    stored entry in LAPACK band storage are computed here once; :meth:`factor` takes the data
    array of a matrix on the pattern (real or complex).  Matrices whose band stays wide
    (more than ``max(64, n / 8)``) are factorised by SuperLU instead."""

    def __init__(self, pattern: sp.spmatrix):
        P = sp.csr_matrix(pattern, copy=True)
        P.sum_duplicates()
        P.sort_indices()
        n = P.shape[0]
        self.n = n
        self.indptr, self.indices = P.indptr, P.indices
        rows = _csr_rows(P)
        cols = P.indices
        natural = int(np.max(np.abs(rows - cols))) if cols.size else 0
        perm = np.arange(n)
        if natural > 16:            # a band this narrow is kept as it is (RCM costs more than it saves)
            sym = sp.csr_matrix((np.ones(cols.size), (rows, cols)), shape=(n, n))
            rcm = reverse_cuthill_mckee(sp.csr_matrix(sym + sym.T), symmetric_mode=True)
            inv = np.empty_like(rcm)
            inv[rcm] = np.arange(n)
            if np.max(np.abs(inv[rows] - inv[cols])) < natural:
                perm = rcm
        inv = np.empty_like(perm)
        inv[perm] = np.arange(n)
        self.perm, self.inv = perm, inv
        self.identity = bool(np.array_equal(perm, np.arange(n)))
        pr, pc = inv[rows], inv[cols]
        self.kl = int(max(np.max(pr - pc), 0)) if cols.size else 0
        self.ku = int(max(np.max(pc - pr), 0)) if cols.size else 0
        self.banded = max(self.kl, self.ku) <= max(64, n // 8)
        ldab = 2 * self.kl + self.ku + 1
        self.ldab = ldab
        self._band_row, self._band_col = self.kl + self.ku + pr - pc, pc   # LAPACK band storage position
        self._rows, self._cols = rows, cols
        self.data_maps = {}          # positions on the pattern of matrices seen (see _data_on)

    @property
    def bandwidth(self) -> int:
        return max(self.kl, self.ku)

    def matrix(self, data: np.ndarray) -> sp.csc_matrix:
        return sp.csc_matrix(sp.csr_matrix((data, self.indices, self.indptr), shape=(self.n, self.n)))

    def to_band(self, data: np.ndarray) -> np.ndarray:
        """The matrix with values ``data`` in transposed LAPACK band storage, shape (n, ldab):
        a stack of q of these, shape (q, n, ldab) in C order, is the Fortran-ordered
        (ldab, q n) array that :meth:`factor_band` hands to LAPACK without a copy."""
        out = np.zeros((self.n, self.ldab), dtype=np.asarray(data).dtype)
        out[self._band_col, self._band_row] = data
        return out

    def factor_band(self, bands: np.ndarray) -> "BandFactor":
        """Factorise q matrices given as a (q, n, ldab) C-ordered stack of :meth:`to_band`
        arrays (overwritten by the factors; banded layouts only)."""
        if not self.banded:
            raise ValueError("factor_band needs a banded layout")
        q = bands.shape[0]
        cplx = np.iscomplexobj(bands)
        ab = bands.reshape(q * self.n, self.ldab).T          # Fortran-ordered view, no copy
        return self._getrf(ab, q, cplx)

    def _getrf(self, ab: np.ndarray, q: int, cplx: bool) -> "BandFactor":
        """LAPACK ``?gbtrf`` in place on the Fortran-ordered band array ``ab`` of q matrices."""
        getrf = lapack.zgbtrf if cplx else lapack.dgbtrf
        lu, piv, info = getrf(ab, self.kl, self.ku, overwrite_ab=True)
        if info > 0:
            raise SolverError(f"singular matrix in a banded LU (zero pivot at row {info}): the system is "
                              "singular at this shift or frequency")
        return BandFactor(self, lu, piv, None, q, cplx)

    def factor(self, data: np.ndarray) -> "BandFactor":
        """Factorise the matrix with values ``data`` on the pattern."""
        return self.factor_many(np.asarray(data)[None, :])

    def factor_many(self, data: np.ndarray) -> "BandFactor":
        """Factorise q matrices at once (``data`` of shape (q, nnz)); row j of a right-hand side
        block is later solved with matrix j."""
        data = np.atleast_2d(np.asarray(data))
        q, n = data.shape[0], self.n
        cplx = np.iscomplexobj(data)
        if not self.banded:
            lus = []
            for r in range(q):
                try:
                    lus.append(spla.splu(self.matrix(data[r])))
                except RuntimeError as exc:
                    raise SolverError(f"singular matrix in a sparse LU ({exc})") from None
            return BandFactor(self, None, None, lus, q, cplx)
        # Fortran order: LAPACK works in place (a C-ordered band array would be transposed by a copy)
        ab = np.zeros((self.ldab, q * n), dtype=complex if cplx else float, order="F")
        flat = (self._band_col[None, :] + (np.arange(q) * n)[:, None]) * self.ldab + self._band_row[None, :]
        ab.T.reshape(-1)[flat.ravel()] = data.ravel()
        return self._getrf(ab, q, cplx)


@dataclass
class BandFactor:
    layout: BandedLU
    lu: np.ndarray | None
    piv: np.ndarray | None
    splu: list | None
    q: int
    complex: bool

    def solve_columns(self, B: np.ndarray) -> np.ndarray:
        """Solve with the (single) factorised matrix for every column of the real (n, p) array B."""
        lay = self.layout
        if self.splu is not None or self.q != 1 or self.complex:
            return np.column_stack([self.solve(B[:, j]) for j in range(B.shape[1])])
        Bp = np.asfortranarray(B if lay.identity else B[lay.perm])
        x, info = lapack.dgbtrs(self.lu, lay.kl, lay.ku, Bp, self.piv)
        return x if lay.identity else x[lay.inv]

    def solve_vector(self, b: np.ndarray) -> np.ndarray:
        """:meth:`solve` for one real float vector with one real banded factor (an iterative
        solver's operator: the same LAPACK call without the general path's checks)."""
        lay = self.layout
        if self.splu is not None or self.q != 1 or self.complex or b.dtype != np.float64 or b.ndim != 1:
            return self.solve(b)
        x, info = lapack.dgbtrs(self.lu, lay.kl, lay.ku, b if lay.identity else b[lay.perm], self.piv)
        return x if lay.identity else x[lay.inv]

    def solve(self, b: np.ndarray) -> np.ndarray:
        """Solve with every factorised matrix: ``b`` of shape (q, n) (or (n,) when q = 1)."""
        lay = self.layout
        b = np.asarray(b)
        single = b.ndim == 1
        B = b[None, :] if single else b
        out_complex = self.complex or np.iscomplexobj(B)
        if self.splu is not None:
            X = np.stack([self.splu[r].solve(B[r].astype(complex if out_complex else float)) for r in range(self.q)])
            return X[0] if single else X
        Bp = (B if lay.identity else B[:, lay.perm]).reshape(-1)
        if out_complex and not self.complex:
            xr, info = lapack.dgbtrs(self.lu, lay.kl, lay.ku, Bp.real.copy(), self.piv)
            xi, _ = lapack.dgbtrs(self.lu, lay.kl, lay.ku, Bp.imag.copy(), self.piv)
            x = xr + 1j * xi
        else:
            getrs = lapack.zgbtrs if self.complex else lapack.dgbtrs
            x, info = getrs(self.lu, lay.kl, lay.ku, Bp if Bp.dtype == (complex if self.complex else float)
                            else Bp.astype(complex if self.complex else float), self.piv)
        X = x.reshape(self.q, lay.n)
        if not lay.identity:
            X = X[:, lay.inv]
        return X[0] if single else X


_LAYOUTS: list = []                 # the narrow layouts of the last few patterns (see narrow_layout)


def narrow_layout(A: sp.csr_matrix, max_width: int) -> BandedLU | None:
    """The :class:`BandedLU` of the canonical CSR ``A``'s sparsity pattern when its band (after
    reverse Cuthill-McKee) is at most ``max_width`` wide, else None.  A row with more than
    2 max_width + 1 entries rules the band out before any ordering is computed (a solid's rows
    hold hundreds).  Narrow layouts are shared by the matrices on one pattern: a modal solve's
    mass check (M), stiffness check (K + z M) and factorisation (K) compute the ordering once
    instead of three times (1.1 ms each for the 2000-DOF P2 shaft, measured); the last four
    patterns are kept."""
    if A.nnz and int(np.diff(A.indptr).max()) > 2 * max_width + 1:
        return None
    for indptr, indices, lay in _LAYOUTS:
        if indptr.shape == A.indptr.shape and indices.shape == A.indices.shape \
                and np.array_equal(indptr, A.indptr) and np.array_equal(indices, A.indices):
            return lay if lay.bandwidth <= max_width else None
    lay = BandedLU(A)
    if not lay.banded or lay.bandwidth > max_width:
        return None
    _LAYOUTS.append((lay.indptr, lay.indices, lay))
    if len(_LAYOUTS) > 4:
        _LAYOUTS.pop(0)
    return lay


def band_diagonal(lay: BandedLU, fac: BandFactor) -> np.ndarray:
    """Diagonal of U in a banded LU (row kl + ku of the LAPACK storage)."""
    return fac.lu[lay.kl + lay.ku, :lay.n]


def positive_definite(A: sp.spmatrix, max_width: int = 32) -> bool | None:
    """Whether the symmetric sparse ``A`` is positive definite: LAPACK's banded Cholesky
    (``dpbtrf``) in :class:`BandedLU`'s ordering succeeds.  None when the band is wider than
    ``max_width`` (or not symmetric in shape): ask a general LDL^T instead.  A Sylvester count of
    zero negative eigenvalues for the price of one banded factorisation (a tenth of SuperLU's
    symmetric-mode LDL^T at 2000 unknowns)."""
    A = _canonical(A)
    lay = narrow_layout(A, max_width)
    if lay is None or lay.kl != lay.ku:
        return None
    kd = lay.ku
    # LU band storage row kl + ku + i - j; the upper Cholesky storage row kd + i - j (i <= j)
    ab = np.asfortranarray(lay.to_band(A.data).T[lay.kl:lay.kl + kd + 1, :])
    _, info = lapack.dpbtrf(ab, lower=0, overwrite_ab=1)
    return info == 0
