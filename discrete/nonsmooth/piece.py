"""One exact piece of the event-driven solver: an affine, time-invariant mode, ``z' = A z``.

Everything here depends on the mode only, so it is computed once per distinct mode and reused
at every return to it (stick, slip forward and slip backward repeat all run long):

* the step ``h <= 2 pi / (steps_per_period rho(A))`` and its propagator ``Phi(h) = expm(A h)``;
* the guard rows ``Cg`` and their time derivatives ``Cg A`` (values and slopes at the step
  ends: the Hermite model of the event search);
* the exact work matrices ``G_p(h) = int_0^h Phi^T Q_p Phi ds`` of every power category
  (Van Loan 1978), so the work over a step is ``z^T G_p z``, and the power forms ``Q_p``;
* the local expansion about a step start, ``z(t_k + sigma h) = sum_j sigma^j T_j z_k`` with
  ``T_j = (h A)^j / j!`` formed in the balanced coordinates of A (scipy's ``matrix_balance``,
  exact power-of-two scaling).  On a step with ``rho h <= 2 pi / steps_per_period`` the terms
  fall from j = 0 on; the series is cut where they drop below 1e-17 relative, so it is the
  exact solution to round-off.  Along it every guard is a polynomial in sigma and the work is
  a polynomial integral: events are located by Newton on the polynomial, without a matrix
  exponential per iteration (:mod:`discrete.nonsmooth.kernel`).  A nilpotent A (stick under
  polynomial drives) gives a finite, exact series on any step.  A mode whose balanced ``h A``
  is too non-normal for the expansion on h (terms growing above 16 before they fall) gets a
  shorter step (h halved until they do not; ``halvings`` counts it).

The step, its expansion and propagator, and the work matrices are functions of the numbers in
``A`` and ``Q_p`` alone, so they are kept in small caches keyed by those numbers
(:func:`_step_maps`, :func:`_work_matrices`; the power forms per problem and mode,
:func:`_power_form_of`): another run of the same model (a shooting iteration, a benchmark's
repeated call, a sweep point that leaves the mode's matrix unchanged) finds them instead of
recomputing eigenvalues, the expansion, a Van Loan exponential per part and the polarization.
A key holds the matrices' bytes, so a changed model does not find a stale entry; the same numbers
give the same arrays, bit for bit.
"""
from __future__ import annotations

import weakref

import numpy as np
from scipy.linalg import expm, matrix_balance

from ..errors import SolverError

TAYLOR_TOL = 1e-17         # last term kept, relative to the identity term
TAYLOR_MAX = 48            # most terms of the local expansion
TAYLOR_GROWTH = 16.0       # largest term (1-norm, balanced) for which the expansion is used
CACHE_SIZE = 64            # entries of each content-keyed cache (cleared when full; a T of 26 states: 0.3 MB)

_RHO: dict = {}
_STEP_MAPS: dict = {}
_WORK: dict = {}
_POWER: dict = {}


class AffinePiece:
    """Cached linear maps, propagator, work matrices and local expansion of one mode (contiguous
    float arrays, as :func:`discrete.nonsmooth.kernel.advance` takes them)."""

    def __init__(self, prob, mode, steps_per_period: int, max_step: float | None, span: float):
        self.A, self.Cg, self.tags, self.Fm, self.Sm, self.Sdm = prob.linear_maps(mode)
        self.rows = prob.constraint_rows(mode)
        self.R = np.ascontiguousarray(np.vstack([self.Cg, self.Cg @ self.A]))
        self.ng = self.Cg.shape[0]
        self.nz = self.A.shape[0]
        maps = _step_maps(self.A, steps_per_period, max_step, span)
        if maps is None:
            raise SolverError(f"no convergent local expansion of the mode {mode!r} (A not finite?)")
        self.h, self.halvings, self.T, self.P = maps
        Q = _power_form_of(prob, mode, self.A, self.Fm, self.Sdm)
        self.parts = list(Q)
        self.Q = np.ascontiguousarray(np.array([Q[k] for k in self.parts]) if Q else np.zeros((0, self.nz, self.nz)))
        self.G = _work_matrices(self.A, self.Q, self.h)
        self.work_total = np.zeros(len(self.parts))   # work of each part in this mode (the kernel adds to it)
        self.hits = np.zeros(self.ng, dtype=bool)      # the guards of the last event (set by the kernel)


def _remember(cache: dict, key, value):
    if len(cache) >= CACHE_SIZE:
        cache.clear()
    cache[key] = value
    return value


def _step_maps(A: np.ndarray, steps_per_period: int, max_step: float | None, span: float):
    """(h, halvings, T, P) of the mode matrix A: the step h <= 2 pi / (steps_per_period rho(A))
    (and <= max_step, span), halved while the expansion does not suit A on it; T the expansion's
    terms, P = expm(A h) their sum.  None when no step gives a convergent expansion."""
    data = (A.dtype.str, A.tobytes())
    rho = _RHO.get((A.shape, data))
    if rho is None:
        ev = np.linalg.eigvals(A)
        rho = _remember(_RHO, (A.shape, data), float(np.max(np.abs(ev))) if ev.size else 0.0)
    h = np.inf if rho == 0 else 2 * np.pi / (steps_per_period * rho)
    if max_step:
        h = min(h, max_step)
    h = min(h, span)
    key = (A.shape, data, h)
    found = _STEP_MAPS.get(key)
    if found is not None:
        return found
    T = _taylor_terms(A, h)
    halvings = 0
    while T is None and halvings < 40:       # too non-normal on h: a shorter step
        h *= 0.5
        halvings += 1
        T = _taylor_terms(A, h)
    if T is None:
        return None
    P = np.ascontiguousarray(T.sum(axis=0))   # expm(A h): the expansion at s = 1
    return _remember(_STEP_MAPS, key, (h, halvings, T, P))


def _work_matrices(A: np.ndarray, Qs: np.ndarray, hh: float) -> np.ndarray:
    """G_p(hh) = int_0^hh Phi(s)^T Q_p Phi(s) ds of every part (Van Loan 1978)."""
    key = (A.shape, A.dtype.str, A.tobytes(), Qs.shape, Qs.tobytes(), hh)
    found = _WORK.get(key)
    if found is not None:
        return found
    n = A.shape[0]
    out = np.zeros_like(Qs)
    for k, Q in enumerate(Qs):
        Cm = np.zeros((2 * n, 2 * n))
        Cm[:n, :n] = -A.T
        Cm[:n, n:] = Q
        Cm[n:, n:] = A
        F = expm(Cm * hh)
        out[k] = F[n:, n:].T @ F[:n, n:]
    return _remember(_WORK, key, out)


def _taylor_terms(A: np.ndarray, h: float):
    """T_j = (h A)^j / j!, j = 0..J, shape (J+1, n, n) (None when the expansion does not suit A on h)."""
    n = A.shape[0]
    if not np.isfinite(h) or n == 0:
        return None
    Ab, (scale, _) = matrix_balance(A, permute=False, separate=True)
    terms = [np.eye(n)]
    T = terms[0]
    largest = 1.0
    for j in range(1, TAYLOR_MAX + 1):
        T = (T @ Ab) * (h / j)
        size = float(np.abs(T).sum(axis=0).max())
        if size == 0.0:           # nilpotent (stick, polynomial drives): the series is finite, exact
            break
        largest = max(largest, size)
        if not np.isfinite(size) or (j >= n and largest > TAYLOR_GROWTH):
            return None           # (a nilpotent matrix vanishes by its n-th power)
        terms.append(T)
        if size < TAYLOR_TOL:
            if largest > TAYLOR_GROWTH:
                return None
            break
    else:
        return None
    # back to the original coordinates: D T D^-1 (scale: powers of two, exact)
    return np.ascontiguousarray(np.array(terms) * scale[None, :, None] / scale[None, None, :])


def _power_form_of(prob, mode, A, Fm, Sdm) -> dict:
    """:func:`power_form`, kept per problem and mode with the mode's maps A, Fm, Sdm as part of
    the key (a problem is not changed after it is built; its maps are checked all the same).  The
    entry holds a weak reference to the problem, so an ``id`` reused by another problem is not
    taken for the first one's and the cache keeps no problem alive."""
    key = (id(prob), mode, A.tobytes(), Fm.tobytes(), Sdm.tobytes())
    found = _POWER.get(key)
    if found is not None and found[0]() is prob:
        return found[1]
    return _remember(_POWER, key, (weakref.ref(prob), power_form(prob, mode, Fm, Sdm)))[1]


def power_form(prob, mode, Fm, Sdm) -> dict:
    """{part: symmetric Q} with power_part(z) = z^T Q z in an affine, time-invariant mode (by
    polarization); parts that vanish identically are left out."""
    nz = Fm.shape[1]
    iu = np.triu_indices(nz)
    Z = np.zeros((nz, iu[0].size))
    cols = np.arange(iu[0].size)
    Z[iu[0], cols] += 1.0
    Z[iu[1], cols] += 1.0 * (iu[0] != iu[1])
    D = np.eye(nz)

    def P(Zc):
        q, v, _, e = prob.split(Zc)
        return prob.power_parts(0.0, q, v, e, mode, Fm @ Zc, Sdm @ Zc)

    pd, pz = P(D), P(Z)
    out = {}
    for part in prob.WORK_PARTS:
        d, z = np.asarray(pd[part], dtype=float), np.asarray(pz[part], dtype=float)
        Q = np.zeros((nz, nz))
        Q[iu] = 0.5 * (z - d[iu[0]] - d[iu[1]])            # off-diagonal by polarization
        Q[iu[1], iu[0]] = Q[iu]
        Q[np.diag_indices(nz)] = d                          # (the diagonal's own values)
        if Q.any():
            out[part] = Q
    return out
