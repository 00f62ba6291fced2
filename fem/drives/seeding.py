"""Pseudo-medium estimates of a discrete drive's lowest modes: seeds and start vectors for
the certified seeded solver :func:`discrete.linalg.seeded.seeded_eigenpairs`.

The continuum (§10.5) has the shaft shapes of a uniform rod, theta_r(x) = sin(s_r x) or
cos(s_r x) with s_r L from :func:`discrete.transfer.continuum.eigen_lambdas`, and per shape
a lower and an upper root of (10.50); a free mechanism output follows the shaft as
y = Pi' k^2 / (k^2 - p^2) theta(x_j) (its equation of motion at frequency p).  For the
discrete drive these are accurate to O(1/n) -- in the crowd of lower roots below k, to
~1e-3 of the distance p_r - k for Set C at n = 1000 -- which is what inverse iteration
needs; the FE matrices decide the digits.
"""
from __future__ import annotations

import numpy as np

from discrete.transfer.continuum import eigen_lambdas, pseudo_medium_frequencies

from .model import DriveModel


def continuum_roots(model: DriveModel, n_r: int) -> tuple[np.ndarray, np.ndarray]:
    """(10.50) generalised to the boundary case: (lower, upper) roots for r = 1..n_r."""
    s = model.smeared()
    return pseudo_medium_frequencies(s["GI"], s["rho"], s["m_bar"], s["k"], s["ratio"], s["L"], model.boundary, n_r)


def continuum_sorted(model: DriveModel, n: int) -> np.ndarray:
    lo, hi = continuum_roots(model, n)
    return np.sort(np.concatenate([lo, hi]))[:n]


def seedable(model: DriveModel, system, n_modes: int) -> bool:
    """The estimates apply: a constrained drive (no rigid-body mode) whose mechanism outputs
    are free or rigid (a grounded output changes the continuum), large enough for shift-invert
    Lanczos to be slow (over 300 DOFs) and for the estimates to separate the crowded roots:
    shapes r <= n/6 (measured on Set C and a P2 shaft, n = 150..2000: up to r/n ~ 0.15 every
    request certified, from r/n ~ 0.2 modes were missed -- and caught by the Sylvester count)."""
    me = model.mechanism
    return (model.boundary != "free-free" and (me.rigid or me.output == "free") and system.n_free > 300
            and n_modes + 1 <= model.n / 6 and n_modes + 1 < system.n_free)


def continuum_estimates(model: DriveModel, system, q: int) -> tuple[np.ndarray, np.ndarray]:
    """The ``q`` lowest continuum eigenvalues (rad^2/s^2) and their shapes sampled at the
    free DOFs of ``system`` (rows), from the drive's smeared parameters."""
    lo, hi = continuum_roots(model, q)
    r = np.concatenate([np.arange(q), np.arange(q)])
    lam = np.concatenate([lo, hi]) ** 2
    keep = np.argsort(lam, kind="stable")[:q]
    lam, r = lam[keep], r[keep]
    s = eigen_lambdas(model.boundary, q)[r] / model.length
    free = system.free
    x = np.asarray(system.dof_x, dtype=float)[free]
    field = np.asarray(system.dof_field, dtype=object)[free]
    shape = np.cos if model.start == "free" else np.sin
    xu, at = np.unique(x, return_inverse=True)         # theta and y of a station share x
    rows = shape(s[:, None] * xu[None, :])[:, at]
    is_y = field == "y"
    if is_y.any():
        k2 = model.mechanism.k ** 2
        rows[:, is_y] *= model.mechanism.ratio * k2 / (k2 - lam)[:, None]
    return lam, rows
