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
and reported with omega = 0 -- only when |lam| is within the round-off bound below.

The solver checks its own assumptions (M positive definite, K positive semi-definite on the
free DOFs) before solving:

* round-off bound ``zero_level = 1e3 eps lam_max`` (lam_max = max K_ii / M_ii, a lower bound of
  the largest eigenvalue): a backward-stable eigen-solver returns eigenvalues with absolute errors
  of a modest multiple of eps ||M^-1/2 K M^-1/2||; 1e3 covers that multiple.  When the builder
  declares rigid-body modes r (K r = 0 exactly), the rounding the matrices carry is measured too:
  zero_level is raised to 10 max ||K r|| ||r|| / r^T M r (projected matrices T^T K T carry the
  rounding of the full K: a reduced floating bar shows lam = -1.1e-11 with lam_max = 55).  An
  eigenvalue with |lam| <= zero_level is a rigid-body mode (omega = 0); one below -zero_level is
  not round-off;
* M: a negative diagonal entry is an error naming the DOF; a non-diagonal M must have no
  eigenvalue below -1e3 eps max M_ii (Sylvester count of the LDL^T pivots of that shift of M);
* K: the number of eigenvalues below -zero_level is the number of negative pivots of the
  symmetric LDL^T of ``K + zero_level M`` (Sylvester's law of inertia); it must be 0 (on a large
  model a factorisation of K itself without a negative pivot proves it, M being >= 0).  The same
  count catches negative eigenvalues that shift-invert at sigma = 0 would never find (it returns
  the eigenvalues nearest the shift);
* every computed eigenvalue below -zero_level is an error as well (the models above
  :data:`INERTIA_MAX` DOFs, whose count is skipped, rely on this check alone).

A negative eigenvalue is a :class:`~discrete.errors.ModelError` naming its value, not a flagged
mode: lam < 0 means a static instability (divergence), not a vibration, and a reported
omega = sqrt(lam) would be meaningless; the likely cause (a negative modulus, spring or mass,
a sign error in K) is named.

Models small enough for the dense solver (:data:`DENSE_FALLBACK_MAX` free DOFs) whose requested
modes the sparse path cannot deliver (ARPACK needs n_modes < n; a badly conditioned M, e.g. masses
1e12 apart) are solved densely with each eigenpair taken from whichever of the pencils (K, M) and
(M, K) resolves it to relative accuracy (:func:`_dense_both_ends`); ``method`` says so.
"""
from __future__ import annotations

import warnings as _warnings
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.csgraph as csgraph
import scipy.sparse.linalg as spla

from ..errors import ModelError, SolverError
from ..linear_system import LinearSystem, check_finite

from ..linalg.banded import positive_definite
from ..linalg.blas import single_threaded_blas
from ..linalg.mkl_sparse import mkl_operator
from ..linalg.seeded import seeded_eigenpairs
from ..linalg.shifted import ShiftedSolver, is_diagonal
from ..linalg.sparse_direct import BANDED_MAX_WIDTH, BANDED_MIN_SIZE, SingularMatrixError, choose, factorize

EPS = np.finfo(float).eps
#: largest number of free DOFs whose definiteness is checked by a sparse LDL^T inertia count
INERTIA_MAX = 200_000
#: most coupled blocks the mass check factorises one by one (more: the whole matrix at once)
MAX_BLOCKS = 16
#: largest number of free DOFs solved by the dense generalized eigen-solver as a fallback
DENSE_FALLBACK_MAX = 2_000


def as_linear_system(system, where: str = "analysis") -> LinearSystem:
    """The :class:`LinearSystem` to analyse: ``system`` itself, or the ``.system`` of an assembled model
    (fem's ``FEModel``); anything else is a ModelError saying what to pass."""
    if isinstance(system, LinearSystem):
        return system
    inner = getattr(system, "system", None)
    if isinstance(inner, LinearSystem):
        return inner
    kind = type(system).__name__
    hint = ("an unassembled model: call fem.assemble(model) first and pass the result (or its .system)"
            if hasattr(system, "segments") else "build one with fem.assemble(ShaftModel), a lumped/drive builder or "
            "LinearSystem(M=..., K=..., dof_field=...)")
    raise ModelError(where, "system", f"<{kind}>", f"a discrete.linear_system.LinearSystem or an assembled FEModel; "
                     f"got {kind}, {hint}")


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


PRECISION_ADVICE = "the mesh is too fine for this mode: use fewer or higher-order elements"
"""The likely cause of a mode not reliable in double precision, unless the caller knows better."""


def modal_analysis(system: LinearSystem, n_modes: int = 6, *, shift: float | None = None,
                   tolerance: float = 1e-5, dense_max: int = 12, seeds=None, seed_vectors=None,
                   precision_advice: str = PRECISION_ADVICE) -> ModalResult:
    """Lowest ``n_modes`` natural frequencies and mass-normalised mode shapes of ``system``.

    ``seeds``: estimates of the lowest ``n_modes + 1`` eigenvalues (rad^2/s^2), optionally with
    estimated vectors ``seed_vectors`` (one row per seed over the free DOFs), for spectra that
    crowd (drives of many mechanisms): the certified seeded solver :mod:`discrete.linalg.seeded` is used,
    and shift-invert Lanczos below the seeds if it cannot certify its result.  ``precision_advice``: the
    likely cause named in the warning of a mode not reliable in double precision (default: the mesh)."""
    system = as_linear_system(system, "modal_analysis")
    n = system.n_free
    if isinstance(n_modes, bool) or not isinstance(n_modes, (int, np.integer)) or not 1 <= n_modes <= n:
        raise ModelError("[analysis]", "modes", n_modes, f"an integer from 1 to {n} (the number of free DOFs)")
    K = system.free_block(system.K)
    M = system.free_block(system.M)
    _check_finite_matrices(system, K, M)
    _check_mass(system, M)
    n_massive = int(np.count_nonzero(M.diagonal() > 0)) if is_diagonal(M) else n
    if n_modes > n_massive:
        raise ModelError("[analysis]", "modes", n_modes,
                         f"at most {n_massive}: the lumped mass matrix has {n_massive} DOFs with inertia")
    if shift is not None and (isinstance(shift, bool) or not isinstance(shift, (int, float, np.floating, np.integer))
                              or not np.isfinite(shift)):
        raise ModelError("[analysis]", "shift", shift, "a finite real number (rad^2/s^2), or None for the default")
    if not (isinstance(tolerance, (int, float, np.floating)) and 0 < tolerance < 1):
        raise ModelError("[analysis]", "tolerance", tolerance, "a number in (0, 1)")
    lam_max = lambda_scale(K, M)
    rigid_level = 1e3 * EPS * lam_max
    zero_level = max(rigid_level, _declared_rigid_level(system, K, M))
    n_rigid = None if system.rigid_modes is None else system.rigid_modes.shape[1]
    # the seeded solver factorises through a ShiftedSolver (leaf condensation, banded core): built
    # once here, it also gives the stiffness check its Sylvester count (a Sturm count for a drive)
    counter = _shifted_solver(K, M) if seeds is not None and not n_rigid else None
    # a large model on the default shift: the factorisation of K that shift-invert needs is made
    # first, and its inertia (MKL PARDISO's Cholesky or LDL^T) proves the stiffness check
    k_factor = _stiffness_factor(K, shift, n_rigid) if seeds is None else None
    _check_stiffness(system, K, M, zero_level, lam_max, counter, k_factor)
    # Shift-invert resolves the low modes to near-relative accuracy (it iterates with K^-1,
    # whose dominant eigenvalues are the ones wanted); the dense solver's error is
    # eps*lam_max in absolute terms, so it is used only for tiny systems or when (almost)
    # all modes are wanted, which ARPACK cannot deliver.
    notes = []
    solver = ""
    if (n <= dense_max or n_modes >= n - 1) and _is_positive_definite(M):
        lam, vec = sla.eigh(K.toarray(), M.toarray(), subset_by_index=[0, n_modes - 1])
        method, sigma = "dense eigh(K, M)", 0.0
    elif n_modes >= n and n <= DENSE_FALLBACK_MAX:
        # all modes: beyond ARPACK (k < n); M is ill-conditioned (else the branch above): both pencils
        lam, vec = _dense_both_ends(K, M, n_modes)
        method, sigma = "dense eigh of (K, M) and (M, K + s M), per mode the better-conditioned one", 0.0
        notes.append(f"dense solver used: the sparse shift-invert solver cannot return all {n} modes and the mass "
                     "matrix is ill-conditioned (smallest / largest eigenvalue of M below 1e-8)")
    elif is_diagonal(M) and n_massive < n and n_modes >= n_massive - 1 and n_massive <= DENSE_FALLBACK_MAX:
        # a lumped mass matrix with massless DOFs and (nearly) every finite mode wanted: Lanczos in the
        # M-semi-inner product has no room (its Krylov space lives in the n_massive-dimensional range of M)
        lam, vec = _condensed_massless(system, K, M, n_modes)
        method, sigma = "static condensation of the massless DOFs + dense eigh", 0.0
        notes.append(f"{n - n_massive} massless DOFs condensed out exactly (K_mm - K_m0 K_00^-1 K_0m): "
                     f"{n_massive} DOFs carry inertia, {n_modes} of their modes wanted")
    elif seeds is not None and not n_rigid:
        if shift is not None:
            notes.append(f"shift = {shift!r} not used: the seeded solver places its own shifts at the seeds")
        lam, vec, sigma, method, more, solver = _seeded_or_lanczos(K, M, n_modes, seeds, seed_vectors, lam_max,
                                                                   rigid_level, counter)
        notes += more
    else:
        if seeds is not None:
            notes.append("seeds not used: the system has rigid-body modes (shift-invert Lanczos instead)")
        lam, vec, sigma, lu = _shift_invert(K, M, n_modes, shift, lam_max, rigid_level, n_rigid, k_factor)
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
    negative = np.flatnonzero(lam < -zero_level)
    if negative.size:
        raise _negative_eigenvalue(system, lam[negative[0]], zero_level, lam_max)
    if n_rigid is None:
        rigid = np.abs(lam) <= rigid_level
    else:
        rigid = (np.arange(lam.size) < n_rigid) & (np.abs(lam) <= zero_level)
        if np.count_nonzero(rigid) < min(n_rigid, lam.size):
            notes.append(f"the model declares {n_rigid} rigid-body mode(s), but only {int(rigid.sum())} computed "
                         f"eigenvalue(s) are within the round-off bound |lam| <= {zero_level:.2e}: the others are "
                         "reported as flexible modes")
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
                f"{tolerance:g}, worst-case bound eps*lam_max/lam = {bound[r]:.1e}); {precision_advice}")
        else:
            result.warnings.append(f"mode {r + 1}: residual {residuals[r]:.1e} above {tolerance:g}")
    return result


def _condensed_massless(system: LinearSystem, K, M, n_modes: int):
    """Modes of a system whose diagonal M leaves some DOFs massless: those DOFs follow the others statically
    (q_0 = -K_00^-1 K_0m q_m, exact, they have no inertia), so the finite eigenpairs are those of
    (K_mm - K_m0 K_00^-1 K_0m, M_mm), dense; the massless part of each vector is recovered."""
    import scipy.sparse.linalg as spla

    d = M.diagonal()
    mm = d > 0
    zz = ~mm
    Kc = sp.csc_matrix(K)
    Kzz = Kc[zz][:, zz].tocsc()
    Kzm = Kc[zz][:, mm].toarray()
    Kmm = Kc[mm][:, mm].toarray()
    try:
        X = spla.splu(Kzz).solve(Kzm)
    except RuntimeError as exc:
        raise ModelError(system.title or "modal_analysis", "K", "singular on the massless DOFs",
                         "a model whose massless DOFs are held by stiffness (they form a mechanism: give them "
                         f"inertia or supports) ({exc})") from None
    Kr = Kmm - Kzm.T @ X
    Kr = 0.5 * (Kr + Kr.T)
    lam, V = sla.eigh(Kr, np.diag(d[mm]), subset_by_index=[0, n_modes - 1])
    vec = np.zeros((d.size, n_modes))
    vec[mm] = V
    vec[zz] = -X @ V
    return lam, vec


def _declared_rigid_level(system: LinearSystem, K, M) -> float:
    """Round-off carried by the matrices themselves, measured on the builder's rigid-body modes r
    (exactly K r = 0): 10 max ||K r|| ||r|| / (r^T M r), the size of the eigenvalue a rigid mode can
    get from that rounding (large for projected matrices T^T K T, whose rounding is that of the
    full K).  0 when no rigid-body modes are declared."""
    if system.rigid_modes is None or not system.rigid_modes.shape[1]:
        return 0.0
    R = system.rigid_modes[system.free]
    level = 0.0
    for r in R.T:
        rMr = float(r @ (M @ r))
        if rMr > 0:
            level = max(level, float(np.linalg.norm(K @ r) * np.linalg.norm(r)) / rMr)
    return 10.0 * level


def _check_finite_matrices(system: LinearSystem, K, M) -> None:
    """NaN/inf or complex entries (matrices replaced after construction) are refused; the finiteness rule is
    the constructor's own (:func:`discrete.linear_system.check_finite`)."""
    for name, A in (("K", K), ("M", M)):
        if np.iscomplexobj(A.data):
            raise ModelError(system.title or "modal_analysis", name, "complex entries",
                             "real symmetric matrices (complex stiffness belongs in H, used by harmonic analysis)")
    check_finite(system.title or "modal_analysis", K=K, M=M)


def _check_mass(system: LinearSystem, M) -> None:
    """M must be positive semi-definite (massless DOFs allowed where the mass matrix is lumped):
    a negative diagonal entry names its DOF; a non-diagonal M is checked by a Sylvester count
    (block by block), unless its assembler proved it semi-definite by construction
    (``LinearSystem.prove_mass_semidefinite``: the 3D solids, whose count cost 0.9-1.4 s of a
    7 s solve at 104 400 DOFs)."""
    d = M.diagonal()
    bad = np.flatnonzero(d < 0)
    if bad.size:
        i = int(system.free[bad[0]])
        raise ModelError(system.title or "modal_analysis", f"mass matrix M[{i}, {i}] ({system.label(i)})",
                         float(d[bad[0]]), "a positive semi-definite mass matrix: masses, inertias and densities >= 0 "
                         f"({bad.size} negative diagonal entr{'y' if bad.size == 1 else 'ies'})")
    if is_diagonal(M) or M.shape[0] > INERTIA_MAX or system.mass_semidefinite_reason:
        return                        # (a proof by construction: M's free block is a principal submatrix)
    level = 1e3 * EPS * float(d.max(initial=0.0))
    count = _blockwise_negative_count(M + level * sp.identity(M.shape[0], format="csr"))
    if count:
        raise ModelError(system.title or "modal_analysis", "mass matrix M", f"{count} negative eigenvalue(s)",
                         f"a positive semi-definite mass matrix (eigenvalues >= -{level:.1e}, Sylvester count of the "
                         "LDL^T pivots of M + that bound): a negative mass, inertia or density, or a sign error in M")


def _blockwise_negative_count(A: sp.spmatrix) -> int | None:
    """Sylvester count of the symmetric ``A`` block by block: the count of a matrix that
    decouples into blocks (connected components of its graph) is the sum of theirs, and equal
    blocks are factorised once.  A solid's consistent mass matrix couples no two displacement
    components, so it is three equal blocks: at 104 400 DOFs one factorisation of a third of the
    size instead of the whole (4.3 s with SuperLU before, 0.9 s now).  Blocks of
    ``sparse_direct.AUTO_MIN_SIZE`` rows and more are counted by PARDISO where installed (its
    Cholesky, else its LDL^T), smaller ones -- and any PARDISO turns away -- by SuperLU's
    symmetric mode.  A block without a count leaves the total a lower bound: None if it is 0."""
    A = sp.csr_matrix(A)
    n_blocks, label = csgraph.connected_components(A, directed=False)
    sizes = np.bincount(label)
    if n_blocks == 1 or np.count_nonzero(sizes > 1) > MAX_BLOCKS:
        return _negative_count(A, definite=True)            # (PARDISO from AUTO_MIN_SIZE rows)
    single = sizes[label] == 1                       # uncoupled DOFs: their diagonal entries
    total = int(np.count_nonzero(A.diagonal()[single] < 0))
    order = np.argsort(label, kind="stable")
    starts = np.searchsorted(label[order], np.arange(n_blocks + 1))
    seen: dict = {}
    unknown = False
    for b in np.flatnonzero(sizes > 1):
        idx = order[starts[b]:starts[b + 1]]
        block = A[idx][:, idx]
        block.sort_indices()
        key = (block.indptr.tobytes(), block.indices.tobytes(), block.data.tobytes())
        if key not in seen:
            counted = _pardiso_count(block)
            seen[key] = counted if counted is not None else _negative_count(block, library=False)
        if seen[key] is None:
            unknown = True                # a block without a count: the total is a lower bound
        else:
            total += seen[key]
    return (total or None) if unknown else total


def _shifted_solver(K, M) -> ShiftedSolver | None:
    """The ShiftedSolver of (K, M), or None where the seeded solver would fail on it too (it then
    builds it again, fails the same way and hands over to Lanczos, as without this)."""
    try:
        return ShiftedSolver(K, M)
    except (SolverError, ValueError, np.linalg.LinAlgError):
        return None


def _stiffness_factor(K, shift, n_rigid):
    """The factorisation of K that :func:`_shift_invert` makes at the default shift, made ahead of
    the stiffness check when the library counts its inertia (MKL PARDISO, from
    ``sparse_direct.AUTO_MIN_SIZE`` DOFs), as a one-item list ``[factorisation or None if K is
    exactly singular]`` that :func:`_shift_invert` empties (so the caller holds no large factor
    it does not use); None when not made here.  K is expected positive definite (PARDISO's Cholesky
    first).  (Until issue 13 this path factorised K with the LDL^T and METIS's order after a
    separate LDL^T count of K + zero_level M: the frequencies move by ~1e-10, the eigenvalues'
    own rounding level eps lam_max / lam.)"""
    if shift is not None or n_rigid not in (0, None) or choose(K.shape[0]) != "pardiso":
        return None
    return [_factor(K, definite=True)]


def _check_stiffness(system: LinearSystem, K, M, zero_level: float, lam_max: float,
                     counter: ShiftedSolver | None = None, k_factor=None) -> None:
    """No eigenvalue of (K, M) below -zero_level: the Sylvester count of K + zero_level M is 0
    (from ``counter``'s condensed LDL^T when given, else SuperLU's symmetric-mode LDL^T).

    ``k_factor``: :func:`_stiffness_factor`'s factorisation of K with its inertia.  No negative
    pivot there proves the count 0 for K + zero_level M as well (M is positive semi-definite,
    checked before), which saves a second factorisation of the same size (104 400-DOF solid: 4.8
    of 17 s); with a negative pivot (round-off of a nearly free system) the count of
    K + zero_level M decides."""
    n = K.shape[0]
    if n > INERTIA_MAX:
        return
    lu = k_factor[0] if k_factor else None
    if lu is not None and lu.inertia is not None and lu.inertia[1] == 0:
        return
    count = None
    if counter is not None:
        try:
            count = counter.inertia(-zero_level)
        except (SolverError, ValueError, np.linalg.LinAlgError):
            count = None                  # no condensed count: SuperLU's below
    if count is None:
        count = _negative_count(K + zero_level * M)
    if not count:
        return
    value = None                      # the lowest eigenvalue, where a dense solve is affordable and M regular
    if n <= DENSE_FALLBACK_MAX and _is_positive_definite(M):
        value = float(sla.eigh(K.toarray(), M.toarray(), eigvals_only=True, subset_by_index=[0, 0])[0])
    raise _negative_eigenvalue(system, value, zero_level, lam_max, count)


def _negative_eigenvalue(system: LinearSystem, value, zero_level: float, lam_max: float, count=None) -> ModelError:
    what = (f"{value:.6g} rad^2/s^2" if value is not None else "negative") + (
        f" ({count} eigenvalue(s) below the round-off bound, Sylvester count of K + {zero_level:.2e} M)" if count else "")
    return ModelError(system.title or "modal_analysis", "eigenvalue of (K, M)", what,
                      f"eigenvalues >= -{zero_level:.2e} (round-off bound 1e3 eps lam_max, lam_max = {lam_max:.3e}): "
                      "the stiffness matrix on the free DOFs must be positive semi-definite -- a negative eigenvalue "
                      "is a static instability, not a vibration; likely cause: a negative Young's/shear modulus or "
                      "spring stiffness, or a sign error in K (or a negative mass)")


def _pardiso_count(A: sp.spmatrix, definite: bool = True) -> int | None:
    """The negative count of A from MKL PARDISO's inertia where ``factorize`` chooses it for A,
    else None (also when PARDISO turns A away: no SuperLU factorisation is made here)."""
    if choose(A.shape[0]) != "pardiso":
        return None
    try:
        fac = factorize(A, "pardiso", definite=definite, fallback=False)
    except SolverError:                   # turned away (perturbed pivots) or out of memory
        return None
    return None if fac.inertia is None else int(fac.inertia[1])


def _negative_count(A: sp.spmatrix, library: bool = True, definite: bool = False) -> int | None:
    """Number of negative eigenvalues of the symmetric ``A`` (Sylvester's law of inertia) from the
    pivots of its LDL^T (SuperLU restricted to diagonal pivots with a symmetric ordering); None when
    the count is unavailable (an exactly singular A, or an off-diagonal pivot was needed).  Large
    matrices use MKL PARDISO's Bunch-Kaufman LDL^T inertia where installed and ``library`` (as
    ``factorize`` does; measured: K + z M of a 34 800-DOF solid shaft 1.6 s with PARDISO, 4.9 s
    with SuperLU's symmetric mode; a 34 800-row component block of the 104 400-DOF solid's mass
    matrix 0.9 s against 1.5 s).  ``definite``: A is expected positive definite (PARDISO's
    Cholesky first; its success is the count 0)."""
    if A.shape[0] >= BANDED_MIN_SIZE and positive_definite(A, BANDED_MAX_WIDTH):
        return 0                          # a narrow band: one banded Cholesky proves the count is 0
    counted = _pardiso_count(A, definite) if library else None
    if counted is not None:
        return counted
    try:
        lu = spla.splu(sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                       options={"SymmetricMode": True})
    except RuntimeError:
        return None
    if not np.array_equal(lu.perm_r, lu.perm_c):
        return None
    return int(np.count_nonzero(lu.U.diagonal() < 0))


def _dense_both_ends(K, M, k: int) -> tuple[np.ndarray, np.ndarray]:
    """The lowest ``k`` eigenpairs of (K, M) for a small system with an ill-conditioned M.

    The dense solve of (K, M) errs by about eps lam_max in absolute terms (fine for the high
    modes, not for the low ones); the inverse pencil (M, K + s M), mu = 1 / (lam + s), errs by
    about eps / (lam_min + s) (fine for the low ones).  Each eigenpair is taken from the solve
    whose error bound is the smaller relative to it: the inverse pencil for lam + s below
    sqrt((lam_min + s) (lam_max + s)).  s = 0 unless K is singular; then s = 1e-8 lam_max (a shift
    that keeps rigid-body modes apart from it)."""
    Kd, Md = K.toarray(), M.toarray()
    lam, vec = sla.eigh(Kd, Md, subset_by_index=[0, k - 1])
    top = max(abs(lam).max(), 1e-300)
    for s in (0.0, 1e-8 * top):
        try:
            mu, w = sla.eigh(Md, Kd + s * Md)
            break
        except np.linalg.LinAlgError:
            continue
    else:
        return lam, vec
    mu, w = mu[::-1][:k], w[:, ::-1][:, :k]             # largest mu = lowest lam
    if np.any(mu <= 0):
        return lam, vec
    lam_inv = 1.0 / mu - s
    lo, hi = lam_inv[0] + s, lam[-1] + s
    use_inv = lam_inv + s < np.sqrt(lo * hi)
    lam = np.where(use_inv, lam_inv, lam)
    vec = np.where(use_inv[None, :], w, vec)
    return lam, vec


def _seeded_or_lanczos(K, M, k, seeds, seed_vectors, lam_max, rigid_level, counter=None):
    """The seeded solver, or -- if it cannot certify its result -- shift-invert Lanczos at a
    shift below the seeds that a Sylvester count shows to lie below the lowest eigenvalue
    (``counter``: the ShiftedSolver of (K, M), when already built)."""
    try:
        sol = seeded_eigenpairs(K, M, seeds, k, start=seed_vectors, solver=counter)
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
        counter = counter or ShiftedSolver(K, M)
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
    """Largest column sum of |A| (the 1-norm): |A|^T 1, which sums each column in row order as a
    bincount over the column indices would, to the same bits, 4x faster (0.075 s against 0.3 s
    for the 18.6 M entries of the 104 400-DOF solid's K)."""
    A = sp.csr_matrix(A)
    if not A.nnz:
        return 0.0
    absA = sp.csr_matrix((np.abs(A.data), A.indices, A.indptr), shape=A.shape)
    return float((absA.T @ np.ones(A.shape[0])).max())


def _is_positive_definite(M: sp.spmatrix) -> bool:
    """Well-conditioned positive definite (the dense solver factorises M; a nearly singular M,
    e.g. a beam of negligible own mass carrying point masses, goes to shift-invert instead)."""
    ev = np.linalg.eigvalsh(M.toarray())
    return bool(ev[0] > 1e-8 * ev[-1])


def _factor(A: sp.spmatrix, definite: bool = False):
    """Sparse factorisation of the symmetric A (:mod:`discrete.linalg.sparse_direct`: MKL PARDISO's
    LDL^T -- its Cholesky first when A is expected ``definite`` -- for large matrices where
    installed, else SuperLU's LU), None if A is exactly singular.  Its ``pivot_ratio`` (smallest
    to largest pivot) is computed on first use."""
    try:
        return factorize(A, definite=definite)
    except SingularMatrixError:
        return None


def _eigsh(K, M, k, sigma, lu, tol=0.0):
    """ARPACK in shift-invert mode; its dense kernels are tiny (n x ncv), so the solve runs
    with single-threaded BLAS (:mod:`discrete.linalg.blas`), except MKL's when PARDISO solves; M's
    products then run in MKL's sparse BLAS as well (:mod:`discrete.linalg.mkl_sparse`)."""
    n = K.shape[0]
    op = spla.LinearOperator((n, n), matvec=lu.solve, dtype=float)
    ncv = min(n, max(2 * k + 1, 20))
    pardiso = lu.solver == "MKL PARDISO"
    if pardiso:                       # ARPACK's M products on MKL's two threads (mkl_sparse)
        M = mkl_operator(M) or M
    with _warnings.catch_warnings(), single_threaded_blas(keep_mkl=pardiso):
        _warnings.simplefilter("ignore", sp.SparseEfficiencyWarning)
        v0 = np.random.default_rng(12345).uniform(0.5, 1.5, n)  # fixed start: reproducible results
        return spla.eigsh(K, k=k, M=M, sigma=sigma, which="LM", OPinv=op, tol=tol, ncv=ncv, v0=v0)


def _shift_invert(K, M, k, shift, lam_max, rigid_level, n_rigid, k_factor=None):
    """Shift-invert Lanczos at ``shift``, or at 0 / a small negative shift for a (nearly) free
    system; ``k_factor``: :func:`_stiffness_factor`'s factorisation of K, when it made one."""
    if k >= K.shape[0]:
        raise ModelError("[analysis]", "modes", k, f"at most {K.shape[0] - 1} (the {K.shape[0]} DOFs less one) for the "
                         "sparse shift-invert solver (ARPACK needs fewer modes than DOFs), which this model needs: its "
                         "mass matrix is nearly singular (smallest / largest eigenvalue of M below 1e-8) and it has "
                         f"more than {DENSE_FALLBACK_MAX} free DOFs, the limit of the dense fallback")
    if shift is not None:
        lu = _factor(K - shift * M)
        if lu is None:
            raise SolverError(f"K - sigma M is singular at the requested shift {shift}: choose another shift")
        lam, vec = _eigsh(K, M, k, shift, lu)
        return lam, vec, shift, lu
    lu = (k_factor.pop() if k_factor else _factor(K)) if n_rigid in (0, None) else None
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
