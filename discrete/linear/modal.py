"""Modal analysis of a :class:`LinearSystem`: K phi = omega^2 M phi.

Sparse shift-invert Lanczos (ARPACK through ``scipy.sparse.linalg.eigsh`` with our own LU
of ``K - sigma M``); never ``M^-1 K``.  Tiny systems (or requests for all modes) use the
dense symmetric-definite solver ``scipy.linalg.eigh(K, M)``, which is less accurate for the
low modes of ill-conditioned FE matrices.  Each mode carries three checks:

* ``residuals``: backward error ||K phi - lam M phi|| / ((||K|| + |lam| ||M||) ||phi||);
* ``rayleigh_rel_diff``: |phi^T K phi / phi^T M phi - lam| / |lam|, the Rayleigh quotient
  recomputed from the returned vector.  Rounding in phi^T K phi grows like eps*lam_max/lam,
  as does the error of lam itself, so a mismatch above ``tolerance`` marks a mesh too fine
  for double precision (measured: a Hermite cantilever with 5000 elements gives a mismatch
  of 2e-3 and an eigenvalue error of 4e-4); such modes are flagged ``reliable = False``;
* ``precision_bound``: eps * lam_max / lam, the worst-case relative accuracy double
  precision allows (lam_max estimated from the diagonal ratios K_ii / M_ii); reported for
  information, it is typically 100-1000 times pessimistic.

Crowded spectra with good eigenvalue estimates (``seeds``; large drives pass the
pseudo-medium roots) go to the certified seeded solver :mod:`discrete.linalg.seeded` -- multi-shift
inverse iteration with a Sylvester-count certificate -- and back to shift-invert Lanczos if
it cannot certify its result.

Free (unconstrained) systems are solved with a negative shift; their rigid-body modes are
counted from the system's known rigid-body basis (FE and lumped builders provide it; for
bare matrices they are detected from the LU pivots of K and the size of the eigenvalue)
and reported with omega = 0.
"""
from __future__ import annotations

import warnings as _warnings
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import ModelError, SolverError
from ..linear_system import LinearSystem

from ..linalg.blas import single_threaded_blas
from ..linalg.seeded import seeded_eigenpairs
from ..linalg.shifted import ShiftedSolver, is_diagonal
from ..linalg.sparse_direct import SingularMatrixError, factorize

EPS = np.finfo(float).eps


@dataclass
class ModalResult:
    omega_rad_s: np.ndarray
    eigenvalues: np.ndarray
    shapes: np.ndarray              # (n_dofs, n_modes), mass-normalised, zeros at constrained DOFs
    residuals: np.ndarray
    rayleigh_rel_diff: np.ndarray
    precision_bound: np.ndarray
    rigid: np.ndarray               # bool per mode
    n_dofs: int                     # number of free DOFs
    method: str
    shift: float
    tolerance: float
    warnings: list[str] = field(default_factory=list)
    linear_solver: str = ""         # the sparse factorisation of the shift-invert (discrete.linalg.sparse_direct)

    @property
    def frequencies_hz(self) -> np.ndarray:
        return self.omega_rad_s / (2 * np.pi)

    @property
    def rigid_body_modes(self) -> int:
        return int(self.rigid.sum())

    @property
    def reliable(self) -> np.ndarray:
        ok = (self.residuals < self.tolerance) & (self.rayleigh_rel_diff < self.tolerance)
        return ok | self.rigid & (self.residuals < self.tolerance)

    def to_dict(self) -> dict:
        return {
            "omega_rad_s": self.omega_rad_s.tolist(),
            "frequencies_hz": self.frequencies_hz.tolist(),
            "n_dofs": self.n_dofs,
            "n_modes": int(self.omega_rad_s.size),
            "residuals": self.residuals.tolist(),
            "rayleigh_rel_diff": self.rayleigh_rel_diff.tolist(),
            "precision_bound": self.precision_bound.tolist(),
            "reliable": self.reliable.tolist(),
            "rigid_body_modes": self.rigid_body_modes,
            "method": self.method,
            "linear_solver": self.linear_solver,
            "shift": self.shift,
            "warnings": list(self.warnings),
        }


def lambda_scale(K: sp.spmatrix, M: sp.spmatrix) -> float:
    """Estimate of the largest eigenvalue: max K_ii / M_ii over DOFs with mass."""
    k, m = K.diagonal(), M.diagonal()
    mask = m > 0
    if not mask.any():
        raise ModelError("", "mass", 0.0, "a model with some inertia (all masses are zero)")
    return float(np.max(np.abs(k[mask]) / m[mask]))


def modal_analysis(system: LinearSystem, n_modes: int = 6, *, shift: float | None = None,
                   tolerance: float = 1e-5, dense_max: int = 12, seeds=None, seed_vectors=None) -> ModalResult:
    """Lowest ``n_modes`` natural frequencies and mass-normalised mode shapes of ``system``.

    ``seeds``: estimates of the lowest ``n_modes + 1`` eigenvalues (rad^2/s^2), optionally with
    estimated vectors ``seed_vectors`` (one row per seed over the free DOFs), for spectra that
    crowd (drives of many mechanisms): the certified seeded solver :mod:`discrete.linalg.seeded` is used,
    and shift-invert Lanczos below the seeds if it cannot certify its result."""
    n = system.n_free
    if isinstance(n_modes, bool) or not isinstance(n_modes, (int, np.integer)) or not 1 <= n_modes <= n:
        raise ModelError("[analysis]", "modes", n_modes, f"an integer from 1 to {n} (the number of free DOFs)")
    K = system.free_block(system.K)
    M = system.free_block(system.M)
    n_massive = int(np.count_nonzero(M.diagonal() > 0)) if is_diagonal(M) else n
    if n_modes > n_massive:
        raise ModelError("[analysis]", "modes", n_modes,
                         f"at most {n_massive}: the lumped mass matrix has {n_massive} DOFs with inertia")
    lam_max = lambda_scale(K, M)
    rigid_level = 1e3 * EPS * lam_max
    n_rigid = None if system.rigid_modes is None else system.rigid_modes.shape[1]
    # Shift-invert resolves the low modes to near-relative accuracy (it iterates with K^-1,
    # whose dominant eigenvalues are the ones wanted); the dense solver's error is
    # eps*lam_max in absolute terms, so it is used only for tiny systems or when (almost)
    # all modes are wanted, which ARPACK cannot deliver.
    notes = []
    solver = ""
    if (n <= dense_max or n_modes >= n - 1) and _is_positive_definite(M):
        lam, vec = sla.eigh(K.toarray(), M.toarray(), subset_by_index=[0, n_modes - 1])
        method, sigma = "dense eigh(K, M)", 0.0
    elif seeds is not None and not n_rigid:
        if shift is not None:
            notes.append(f"shift = {shift!r} not used: the seeded solver places its own shifts at the seeds")
        lam, vec, sigma, method, more, solver = _seeded_or_lanczos(K, M, n_modes, seeds, seed_vectors, lam_max,
                                                                   rigid_level)
        notes += more
    else:
        if seeds is not None:
            notes.append("seeds not used: the system has rigid-body modes (shift-invert Lanczos instead)")
        lam, vec, sigma, lu = _shift_invert(K, M, n_modes, shift, lam_max, rigid_level, n_rigid)
        method, solver = f"sparse shift-invert Lanczos (eigsh, {lu.name})", lu.name
        notes += lu.notes
    order = np.argsort(lam)
    if np.any(order != np.arange(lam.size)):
        lam, vec = lam[order], vec[:, order]
    Mv = M @ vec
    scale = 1.0 / np.sqrt(np.einsum("ij,ij->j", vec, Mv))      # mass-normalise
    if np.any(np.abs(scale - 1.0) > 1e-13):
        vec = vec * scale
        Mv *= scale
    Kv = K @ vec
    vnorm = np.sqrt(np.einsum("ij,ij->j", vec, vec))
    rq = np.einsum("ij,ij->j", vec, Kv) / np.einsum("ij,ij->j", vec, Mv)
    Mv *= lam
    np.subtract(Kv, Mv, out=Kv)
    num = np.sqrt(np.einsum("ij,ij->j", Kv, Kv))
    den = (_norm1(K) + np.abs(lam) * _norm1(M)) * vnorm
    # a system without any stiffness (K = 0): its rigid-body modes solve K phi = 0 phi exactly
    residuals = np.divide(num, den, out=np.where(num == 0, 0.0, np.inf), where=den > 0)
    if n_rigid is None:
        rigid = np.abs(lam) <= rigid_level
    else:
        rigid = np.arange(lam.size) < n_rigid
    with np.errstate(divide="ignore", invalid="ignore"):
        rq_diff = np.where(rigid, 0.0, np.abs(rq - lam) / np.abs(lam))
        bound = np.where(rigid, 0.0, EPS * lam_max / np.abs(lam))
    omega = np.sqrt(np.clip(lam, 0.0, None))
    omega[rigid] = 0.0
    result = ModalResult(omega_rad_s=omega, eigenvalues=lam, shapes=system.expand(vec), residuals=residuals,
                         rayleigh_rel_diff=rq_diff, precision_bound=bound, rigid=rigid, n_dofs=n,
                         method=method, shift=float(sigma), tolerance=tolerance, linear_solver=solver)
    result.warnings.extend(notes)
    if rigid.any():
        result.warnings.append(f"{int(rigid.sum())} rigid-body mode(s) (free system): reported with omega = 0")
    bad = np.flatnonzero(~result.reliable)
    for r in bad:
        if rq_diff[r] >= tolerance:
            result.warnings.append(
                f"mode {r + 1}: not reliable in double precision (Rayleigh-quotient mismatch {rq_diff[r]:.1e} >= "
                f"{tolerance:g}, worst-case bound eps*lam_max/lam = {bound[r]:.1e}); the mesh is too fine for "
                f"this mode: use fewer or higher-order elements")
        else:
            result.warnings.append(f"mode {r + 1}: residual {residuals[r]:.1e} above {tolerance:g}")
    return result


def _seeded_or_lanczos(K, M, k, seeds, seed_vectors, lam_max, rigid_level):
    """The seeded solver, or -- if it cannot certify its result -- shift-invert Lanczos at a
    shift below the seeds that a Sylvester count shows to lie below the lowest eigenvalue."""
    try:
        sol = seeded_eigenpairs(K, M, seeds, k, start=seed_vectors)
    except ModelError:
        raise                                      # bad seeds given by the caller: say so
    except (SolverError, ValueError, np.linalg.LinAlgError) as exc:      # not certified, or a numerical failure
        note = f"seeded solver not used ({exc}); shift-invert Lanczos below the seeds instead"
    else:
        notes = [] if sol.contamination.max() < 1e-6 else [
            f"seeded solver: vectors contaminated up to {sol.contamination.max():.1e} by neighbouring modes"]
        return sol.eigenvalues, sol.vectors, float(np.min(seeds)), sol.describe(), notes, ""
    sigma = 0.99 * float(np.min(seeds))
    try:
        counter = ShiftedSolver(K, M)
        for _ in range(60):
            if counter.inertia(sigma) == 0:
                break
            sigma *= 0.5
        else:
            sigma = None
    except SolverError:
        sigma = None                      # no count: the default shift (K itself)
    lam, vec, sigma, lu = _shift_invert(K, M, k, sigma, lam_max, rigid_level, 0)
    return lam, vec, sigma, f"sparse shift-invert Lanczos (eigsh, {lu.name})", [note] + lu.notes, lu.name


def _norm1(A: sp.spmatrix) -> float:
    """Largest column sum of |A| (the 1-norm)."""
    A = sp.csr_matrix(A)
    return float(np.bincount(A.indices, weights=np.abs(A.data), minlength=A.shape[1]).max()) if A.nnz else 0.0


def _is_positive_definite(M: sp.spmatrix) -> bool:
    """Well-conditioned positive definite (the dense solver factorises M; a nearly singular M,
    e.g. a beam of negligible own mass carrying point masses, goes to shift-invert instead)."""
    ev = np.linalg.eigvalsh(M.toarray())
    return bool(ev[0] > 1e-8 * ev[-1])


def _factor(A: sp.spmatrix):
    """Sparse factorisation of the symmetric A (:mod:`discrete.linalg.sparse_direct`: MKL PARDISO's
    LDL^T for large matrices where installed, else SuperLU's LU), None if A is exactly singular.
    Its ``pivot_ratio`` (smallest to largest pivot) is computed on first use."""
    try:
        return factorize(A)
    except SingularMatrixError:
        return None


def _eigsh(K, M, k, sigma, lu, tol=0.0):
    """ARPACK in shift-invert mode; its dense kernels are tiny (n x ncv), so the solve runs
    with single-threaded BLAS (:mod:`discrete.linalg.blas`)."""
    n = K.shape[0]
    op = spla.LinearOperator((n, n), matvec=lu.solve, dtype=float)
    ncv = min(n, max(2 * k + 1, 20))
    with _warnings.catch_warnings(), single_threaded_blas():
        _warnings.simplefilter("ignore", sp.SparseEfficiencyWarning)
        v0 = np.random.default_rng(12345).uniform(0.5, 1.5, n)  # fixed start: reproducible results
        return spla.eigsh(K, k=k, M=M, sigma=sigma, which="LM", OPinv=op, tol=tol, ncv=ncv, v0=v0)


def _shift_invert(K, M, k, shift, lam_max, rigid_level, n_rigid):
    if k >= K.shape[0]:
        raise ModelError("[analysis]", "modes", k, f"at most {K.shape[0] - 1} (the {K.shape[0]} DOFs less one) for the "
                         "sparse shift-invert solver, which small models use only when their mass matrix is nearly "
                         "singular (smallest / largest eigenvalue of M below 1e-8)")
    if shift is not None:
        lu = _factor(K - shift * M)
        if lu is None:
            raise SolverError(f"K - sigma M is singular at the requested shift {shift}: choose another shift")
        lam, vec = _eigsh(K, M, k, shift, lu)
        return lam, vec, shift, lu
    lu = _factor(K) if n_rigid in (0, None) else None
    if lu is not None and (n_rigid == 0 or lu.pivot_ratio > 1e3 * EPS):
        lam, vec = _eigsh(K, M, k, 0.0, lu)
        return lam, vec, 0.0, lu
    # Free (or nearly free) system: rigid-body modes.  First pass with a small negative
    # shift, then re-shift to a fraction of the lowest flexible eigenvalue found.
    tau = 1e-8 * lam_max
    lu = _factor(K + tau * M)
    lam, vec = _eigsh(K, M, k, -tau, lu, tol=1e-8)
    flexible = lam[lam > rigid_level]
    if flexible.size and 1e-2 * flexible.min() < tau:
        tau = max(1e-2 * flexible.min(), 10 * rigid_level)
        lu = _factor(K + tau * M)
        lam, vec = _eigsh(K, M, k, -tau, lu)
    else:
        lam, vec = _eigsh(K, M, k, -tau, lu)
    return lam, vec, -tau, lu
