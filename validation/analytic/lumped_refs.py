"""Closed-form and book-coordinate references for lumped drive models: §3.2, §4.4, §4.8, §4.10.

Matrices are built the book's way (kinetic/potential energy in the book's generalised
coordinates), not with a general assembler, so they check an assembler independently.
Angular frequencies in rad/s, ascending.
"""
from __future__ import annotations

import numpy as np
from scipy.linalg import eigh


def two_mass_three_spring(m: float, c: float) -> np.ndarray:
    """Wall-c-m-c-m-c-wall chain (§4.4, Fig. 4.7): ``(sqrt(c/m), sqrt(3c/m))``, beta = (1, -1)."""
    return np.array([np.sqrt(c / m), np.sqrt(3.0 * c / m)])


def two_discs(J1: float, J2: float, c: float) -> np.ndarray:
    """Two free discs on a shaft of stiffness ``c`` (4.41): ``(0, sqrt(c (J1+J2) / (J1 J2)))``."""
    return np.array([0.0, np.sqrt(c * (J1 + J2) / (J1 * J2))])


def geared_drive_314_matrices(J1, J2, J3, J4, u21, c1, c2) -> tuple[np.ndarray, np.ndarray]:
    """Inertia ``a_ik`` (3.9)-(3.10) and stiffness ``c_ik`` (3.11) of the drive of Fig. 2.1g.

    Coordinates ``q1 = phi1`` (cyclic), ``q2 = phi2 - phi1`` (coupling ``c1``),
    ``q3 = phi4 - phi3`` (shaft ``c2``), gear ``phi3 = u21 phi2``.
    """
    J34 = (J3 + J4) * u21**2
    a = np.array([
        [J1 + J2 + J34, J2 + J34, J4 * u21],
        [J2 + J34, J2 + J34, J4 * u21],
        [J4 * u21, J4 * u21, J4],
    ])
    c = np.diag([0.0, c1, c2])
    return a, c


def _omegas(a: np.ndarray, c: np.ndarray) -> np.ndarray:
    lam = eigh(c, a, eigvals_only=True)
    lam = np.where(np.abs(lam) <= 1e-12 * np.max(np.abs(lam)), 0.0, lam)
    return np.sqrt(lam)


def geared_drive_314(J1, J2, J3, J4, u21, c1, c2) -> np.ndarray:
    """Natural frequencies of the free drive (3.14), including the rigid-body zero frequency.

    Generalised symmetric eigenproblem ``c A = k^2 a A`` of the matrices of
    :func:`geared_drive_314_matrices`, solved with ``scipy.linalg.eigh(c, a)``.  Eigenvalues
    below ``1e-12`` of the largest (the rigid-body mode) are set to exactly zero.
    """
    return _omegas(*geared_drive_314_matrices(J1, J2, J3, J4, u21, c1, c2))


def geared_drive_314_driven(J1, J2, J3, J4, u21, c1, c2) -> np.ndarray:
    """Natural frequencies with ``q1`` prescribed (kinematic input): rows/columns 2-3 of (3.14).

    ``J1`` does not enter; it is accepted to keep the signature of :func:`geared_drive_314`.
    """
    a, c = geared_drive_314_matrices(J1, J2, J3, J4, u21, c1, c2)
    return _omegas(a[1:, 1:], c[1:, 1:])


def uniform_chain_lumped(n_segments: int, stiffness_total: float, inertia_total: float,
                         n_modes: int) -> np.ndarray:
    """Lumped model of a fixed-free uniform shaft (digest V4.10b), closed form.

    ``N`` equal springs ``N c`` (``c = G I_p / L``), node inertias ``J / N`` with half of it at the
    free end.  Substituting ``phi_j = sin(j theta)`` gives ``cos(N theta) = 0`` at the free end, so
    ``omega_r = 2 N sqrt(c / J) sin((2r - 1) pi / (4N))``, ``r = 1..n_modes <= N``; converges
    from below to (4.56) as ``O(1/N^2)``.
    """
    if not 1 <= n_modes <= n_segments:
        raise ValueError(f"n_modes = {n_modes!r} is not valid; allowed: 1..n_segments "
                         f"({n_segments})")
    r = np.arange(1, n_modes + 1, dtype=float)
    return (2.0 * n_segments * np.sqrt(stiffness_total / inertia_total)
            * np.sin((2.0 * r - 1.0) * np.pi / (4.0 * n_segments)))
