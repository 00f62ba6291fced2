"""Certified eigenpairs from eigenvalue estimates (seeds): the crowded-spectrum solver.

A drive with n identical mechanisms has n lower-branch natural frequencies crowding below
the partial frequency k (§10.4-10.5): for Set C with n = 1000, modes 2..20 lie within
0.6 % of k and consecutive ones differ by 1e-5 relative.  Shift-invert Lanczos separates
them only after ~400 iterations (a single pole cannot spread an accumulation point).
Estimates of the wanted eigenpairs are cheap -- the pseudo-medium roots (10.50) and shapes
are good to O(1/n) in the distance to k -- and turn the problem into one of refinement:

1. one shift per estimate; all shifted matrices factorised at once
   (:class:`discrete.linalg.shifted.ShiftedSolver`);
2. inverse iteration of the block, each vector with its own shift, each step followed by a
   Rayleigh-Ritz step (which separates vectors drawn to the same eigenvalue), from the
   estimated vectors or from random ones after two plain steps; the shifts move to the
   Ritz values when convergence slows (Rayleigh-quotient iteration); it stops when one
   more step would change a wanted vector by less than ``tol`` -- and returns that step;
3. eigenvalues from rounding-free quotients (:func:`_eigenvalues`);
4. completeness certified by Sylvester's law of inertia: exactly ``n_modes`` eigenvalues
   below the midpoint of the last wanted and the next computed one.  A failed certificate
   raises :class:`SolverError` -- no result is ever returned from bad seeds.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from ..errors import ModelError, SolverError

from .blas import single_threaded_blas
from .shifted import ShiftedSolver, is_diagonal

# The change of a vector is measured as sqrt(y'My / mu^2 - 1), which rounding resolves to ~1e-7
# (the square root of a few eps): smaller tolerances are taken as this floor.
CHANGE_FLOOR = 1e-7


@dataclass
class SeededSolution:
    eigenvalues: np.ndarray        # (n_modes,)
    vectors: np.ndarray            # (n_free, n_modes), M-normalised
    contamination: np.ndarray      # estimated M-norm contamination of each returned vector by other modes
    sweeps: int
    refactorisations: int
    certificate_shift: float       # Sylvester count taken here ...
    count: int                     # ... equals n_modes
    leaves: int                    # condensed one-DOF attachments
    bandwidth: int                 # of the condensed core
    shifts: int                    # number of shifts (seeds)

    def describe(self) -> str:
        return (f"seeded multi-shift inverse iteration + Rayleigh-Ritz ({self.sweeps} sweeps, "
                f"{self.refactorisations + 1} factorisations of {self.shifts} shifts; "
                f"{self.leaves} leaf DOFs condensed, core bandwidth {self.bandwidth}); "
                f"Sylvester count {self.count} below {self.certificate_shift:.10g} rad^2/s^2")


def seeded_eigenpairs(K: sp.spmatrix, M: sp.spmatrix, seeds_lambda, n_modes: int, *, start=None,
                      tol: float = 1e-6, max_sweeps: int = 12, solver: ShiftedSolver | None = None) -> SeededSolution:
    """Lowest ``n_modes`` eigenpairs of K phi = lam M phi from ``n_modes + 1`` (or more)
    eigenvalue estimates ``seeds_lambda`` (rad^2/s^2) and, optionally, estimates of their
    vectors ``start`` (one row per seed; random vectors otherwise).  K positive definite
    (no rigid-body modes), M positive semi-definite.  ``tol`` bounds the estimated
    contamination of each returned wanted vector by other modes (M-norm): its change under
    the last measured inverse iteration times the observed contraction per iteration -- an
    estimate within the block, blind to modes far outside it, resolved down to
    ``CHANGE_FLOOR`` = 1e-7; the iteration also stops when that change stagnates below 1e-6.  Before the certificate the returned vectors
    are checked for independence (two estimates drawn to one mode raise).  ``solver``: the
    :class:`ShiftedSolver` of (K, M) when the caller has built it already."""
    if isinstance(n_modes, bool) or not isinstance(n_modes, (int, np.integer)) or n_modes < 1:
        raise ModelError("seeds", "n_modes", n_modes, "an integer >= 1")
    seeds = np.asarray(seeds_lambda, dtype=float)
    order = np.argsort(seeds)
    seeds = seeds[order]
    if seeds.size < n_modes + 1:
        raise ModelError("seeds", "size", seeds.size, f"at least n_modes + 1 = {n_modes + 1} eigenvalue estimates")
    if not np.all(np.isfinite(seeds)) or seeds[0] <= 0:
        raise ModelError("seeds", "values", seeds[:3].tolist(), "finite positive eigenvalue estimates")
    K, M = sp.csr_matrix(K), sp.csr_matrix(M)
    n, q = K.shape[0], seeds.size
    if q >= n:
        raise ModelError("seeds", "size", q, f"fewer than the {n} free DOFs")
    with single_threaded_blas():
        return _iterate(K, M, seeds, order, n_modes, start, tol, max_sweeps, solver)


def _iterate(K, M, seeds, order, n_modes, start, tol, max_sweeps, solver=None) -> SeededSolution:
    n, q = K.shape[0], seeds.size
    mass = _mass_product(M)
    solver = solver if solver is not None else ShiftedSolver(K, M)
    factors = _factor(solver, seeds)
    if start is None:
        V = np.random.default_rng(12345).uniform(-1.0, 1.0, (q, n))      # one vector per row
        warmup = 2                  # plain inverse iteration first: each row to its shift's eigenvector
    else:
        V = np.asarray(start, dtype=float)
        if V.shape != (q, n):
            raise ModelError("seeds", "start", V.shape, f"one start vector per seed: shape ({q}, {n})")
        V, warmup = (V if np.array_equal(order, np.arange(q)) else V[order]), 0
        norms = np.einsum("ij,ij->i", V, mass(V))
        if not np.all(np.isfinite(norms) & (norms > 0)):
            raise ModelError("seeds", "start", "a zero, massless or non-finite row", "finite vectors with mass")
        V = V / np.sqrt(norms)[:, None]
    for _ in range(warmup):
        V = factors.solve(mass(V))
        V /= np.sqrt(np.einsum("ij,ij->i", V, mass(V)))[:, None]
    previous, refactor = np.full(q, np.inf), 0
    MV = mass(V)
    for sweep in range(1, max_sweeps + 1):
        Y = factors.solve(MV)
        MY = mass(Y)
        G = Y @ MY.T                                          # Gram matrix of the block, for Rayleigh-Ritz
        mu = np.einsum("ij,ij->i", MV, Y)                     # v'M (K - sM)^-1 M v, with v'Mv = 1
        # ||Y/mu - V||_M^2 = y'My/mu^2 - 1: the vector's change under one inverse iteration
        change = np.sqrt(np.maximum(np.diag(G) / mu**2 - 1.0, 0.0))
        rate = np.ones(q)                                     # contraction per step (1 while unknown)
        known = np.isfinite(previous) & (previous > 0)
        rate[known] = np.minimum(change[known] / previous[known], 1.0)
        left = change * rate                                  # contamination left after one more (returned)
        wanted, extra = float(left[:n_modes].max()), float(left[n_modes:].max())
        # stop only on Ritz vectors (sweep > 1: two rows drawn to one mode were separated), when
        # converged or stagnating at rounding (a measured rate, change below 1e-6)
        stalled = bool(known[:n_modes].all()) and rate[:n_modes].max() > 0.5 and wanted < 1e-6
        if sweep > 1 and ((wanted < max(tol, CHANGE_FLOOR) and extra < 1e-3) or stalled):
            break
        V, MV, theta = _rayleigh_ritz(K, Y, MY, G)
        slow = known & (rate > 0.1) & (left > max(tol, 1e-6))        # measured, slow, above rounding
        if slow.any() and refactor < 3 and sweep < max_sweeps:
            shifts = factors.shifts.copy()                    # slow rows: shift to their Ritz values (RQI)
            shifts[slow] = theta[slow]
            factors = _factor(solver, shifts)
            refactor += 1
            change = np.where(slow, np.inf, change)           # new shifts: no rate yet
        previous = change
    else:
        raise SolverError(f"seeded inverse iteration did not converge in {max_sweeps} sweeps (largest vector change "
                          f"{change.max():.1e}): the estimates are too far from the eigenvalues")
    V = Y / np.sqrt(np.diag(G))[:, None]                                # one more inverse iteration
    lam = _eigenvalues(K, solver, mass, V)
    order = np.argsort(lam)
    if not np.array_equal(order, np.arange(q)):
        lam, V, left = lam[order], V[order], left[order]
    overlap = np.abs(V @ mass(V).T - np.eye(q)).max()
    if overlap > 1e-2:
        raise SolverError(f"the seeded vectors are not independent (M-overlap {overlap:.1e}): two estimates drew "
                          "the same mode")
    if not lam[n_modes] - lam[n_modes - 1] > 1e-12 * abs(lam[n_modes]):
        raise SolverError(f"eigenvalues {n_modes} and {n_modes + 1} coincide ({lam[n_modes - 1]:.17g}, a multiple "
                          "eigenvalue): ask for one mode more or fewer")
    sigma = 0.5 * (lam[n_modes - 1] + lam[n_modes])
    count = solver.inertia(sigma)
    if count != n_modes:
        raise SolverError(f"Sylvester count: {count} eigenvalues below {sigma:.10g}, the seeded iteration found "
                          f"{n_modes}: the estimates missed a mode")
    return SeededSolution(eigenvalues=lam[:n_modes], vectors=V[:n_modes].T.copy(), contamination=left[:n_modes],
                          sweeps=sweep, refactorisations=refactor, certificate_shift=float(sigma), count=count,
                          leaves=solver.leaves, bandwidth=solver.bandwidth, shifts=q)


def _eigenvalues(K: sp.csr_matrix, solver: ShiftedSolver, mass, V: np.ndarray) -> np.ndarray:
    """Eigenvalues of the converged vectors (rows of V), free of the rounding that limits
    the obvious quotients.  A shift-invert quotient with s next to lam loses the shift where
    s M_ii << K_ii (the stiff shaft of a drive: K_ii - s M_ii = 2e7 - 1.6), and v'Kv cancels
    down to eps*lam_max/lam: both measured ~1e-12 on the lowest mode of benchmarks/drives.py.

    * K with non-positive off-diagonals (springs between DOFs, as drives and rods have):
      the energy split v'Kv = sum_{i<j} -K_ij (v_i - v_j)^2 + sum_i r_i v_i^2 (r = row sums),
      non-negative spring energies plus a grounding term that is small where the springs
      dominate -- measured 1e-15;
    * otherwise the Schwarz quotient (v, Bv)_M / (Bv, Bv)_M of B = K^-1 M from a
      factorisation of K itself (no shift to lose) -- measured 6e-14."""
    MV = mass(V)
    C = solver.stiffness_coo
    upper = C.row < C.col
    w = -C.data[upper]
    if np.all(w >= 0):
        D = V[:, C.row[upper]] - V[:, C.col[upper]]
        D *= D
        r = np.bincount(C.row, weights=C.data, minlength=C.shape[0])
        return (D @ w + (V * V) @ r) / np.einsum("ij,ij->i", V, MV)
    Y = solver.factor(np.zeros(1)).solve(MV)
    return np.einsum("ij,ij->i", MV, Y) / np.einsum("ij,ij->i", Y, mass(Y))


def _mass_product(M: sp.csr_matrix):
    """rows -> rows M (a diagonal M as a broadcast product)."""
    if is_diagonal(M):
        m = M.diagonal()
        return lambda V: V * m[None, :]
    return lambda V: (M @ V.T).T


def _rayleigh_ritz(K, Y, MY, G):
    """M-orthonormal Ritz vectors (rows, ascending Ritz values) of the row space of Y, their
    products with M, and the Ritz values.  G = Y M Y'."""
    G = 0.5 * (G + G.T)
    try:
        T = sla.solve_triangular(np.linalg.cholesky(G), np.eye(G.shape[0]), lower=True, check_finite=False)
    except np.linalg.LinAlgError:
        w, U = np.linalg.eigh(G)
        keep = w > 1e-13 * w.max()
        if keep.sum() < Y.shape[0]:
            raise SolverError("the seeded block collapsed (two shifts drew the same vector): "
                              "estimates not distinct enough") from None
        T = (U[:, keep] / np.sqrt(w[keep])).T
    Q = T @ Y
    A = Q @ (K @ Q.T)
    theta, C = np.linalg.eigh(0.5 * (A + A.T))
    R = C.T @ T
    return R @ Y, R @ MY, theta


def _factor(solver: ShiftedSolver, shifts: np.ndarray):
    """Factors at ``shifts`` moved off the leaves' own eigenvalues; a shift that lands exactly on
    an eigenvalue (a converged Ritz value can) is moved by 1e-10 relative and refactored once."""
    shifts = _nudge(solver, shifts)
    try:
        return solver.factor(shifts)
    except SolverError:
        return solver.factor(_nudge(solver, shifts * (1 + 1e-10)))


def _nudge(solver: ShiftedSolver, shifts: np.ndarray) -> np.ndarray:
    """Shifts moved off the attachments' own eigenvalues (a zero leaf pivot)."""
    s = np.array(shifts, dtype=float)
    own = solver.leaf_k / np.where(solver.leaf_m > 0, solver.leaf_m, np.inf)
    for _ in range(3):
        if own.size == 0:
            break
        close = np.min(np.abs(s[:, None] - own[None, :]), axis=1) <= 1e-12 * np.abs(s)
        if not close.any():
            break
        s[close] *= 1 + 1e-10
    return s
