"""One- and two-DOF forced response and damping conventions: book §2.4, §4.2, §5.4, §5.5, §5.13.

``z = omega / k`` is the frequency ratio, ``delta = n / k`` the damping ratio, ``lambda`` the
logarithmic decrement and ``psi`` the dissipation (absorption) coefficient.  All functions
accept numpy arrays where that makes sense.
"""
from __future__ import annotations

import numpy as np


def _denominator(z, delta):
    z = np.asarray(z, dtype=float)
    return np.sqrt((1.0 - z**2) ** 2 + 4.0 * z**2 * np.asarray(delta, dtype=float) ** 2)


def amplification(z, delta):
    """Dynamic amplification factor (5.20): ``alpha = 1 / sqrt((1 - z^2)^2 + 4 z^2 delta^2)``."""
    return 1.0 / _denominator(z, delta)


def phase_lag(z, delta):
    """Phase lag (5.24) ``gamma = atan2(2 delta z, 1 - z^2)`` in ``[0, pi]``.

    The printed ``arctg[2 delta z / (1 - z^2)]`` jumps by ``pi`` at ``z = 1``; atan2 gives the
    continuous branch (``pi/2`` at resonance; ``pi`` only for ``delta = 0``, ``z > 1``).
    """
    z = np.asarray(z, dtype=float)
    return np.arctan2(2.0 * np.asarray(delta, dtype=float) * z, 1.0 - z**2)


def peak_frequency_ratio(delta):
    """Frequency ratio of the amplification peak: ``z* = sqrt(1 - 2 delta^2)``.

    Corrected (5.21): the seed prints ``sqrt(1 - delta^2)``, a misprint (the minimum of
    ``(1 - u)^2 + 4 u delta^2`` is at ``u = 1 - 2 delta^2``).  ``nan`` when ``delta^2 >= 0.5``
    (``alpha`` then decreases monotonically; no peak).
    """
    d2 = np.asarray(delta, dtype=float) ** 2
    return np.where(d2 < 0.5, np.sqrt(np.abs(1.0 - 2.0 * d2)), np.nan)[()]


def peak_amplification(delta):
    """Peak amplification (5.21): ``alpha_max = 1 / (2 delta sqrt(1 - delta^2))``.

    Also the peak of the kinematic factor (5.28).  ``nan`` when ``delta^2 >= 0.5`` (no peak).
    """
    d = np.asarray(delta, dtype=float)
    with np.errstate(divide="ignore"):
        return np.where(d**2 < 0.5, 1.0 / (2.0 * d * np.sqrt(np.abs(1.0 - d**2))), np.nan)[()]


def kinematic_amplification(z, delta):
    """Relative-motion factor for base excitation (5.28): ``alpha_1 = z^2 alpha(z)``."""
    return np.asarray(z, dtype=float) ** 2 / _denominator(z, delta)


def kinematic_peak_frequency_ratio(delta):
    """Peak location of (5.28): ``z = 1 / sqrt(1 - 2 delta^2)``; ``nan`` if ``delta^2 >= 0.5``."""
    return 1.0 / peak_frequency_ratio(delta)


def psi_from_delta(delta):
    """Exact book mapping (4.15)-(4.16): ``psi = 1 - exp(-2 lambda)``, ``lambda = 2 pi delta``.

    For small ``lambda`` the book also uses ``psi ~ 2 lambda = 4 pi delta``; the two differ by
    up to ~40 % at ``psi = 0.7`` (digest V2.4a).
    """
    return 1.0 - np.exp(-4.0 * np.pi * np.asarray(delta, dtype=float))


def delta_from_psi(psi):
    """Inverse of :func:`psi_from_delta`: ``lambda = -ln(1 - psi) / 2``, ``delta = lambda/(2 pi)``."""
    return -np.log1p(-np.asarray(psi, dtype=float)) / (4.0 * np.pi)


def hysteretic_delta(psi):
    """Damping ratio ``delta_h = psi / (4 pi)`` of the package's complex-stiffness convention.

    A hysteretic element ``c (1 + 2 i delta_h) = c (1 + i eta)``, ``eta = psi / (2 pi)``,
    dissipates ``pi eta c A^2 = psi c A^2 / 2`` per cycle, exactly (5.69); its resonance amplitude
    ``F0 / (2 delta_h c)`` therefore equals the energy-balance value ``2 pi F0 / (psi c)`` (5.76).
    This is the small-damping mapping ``psi = 4 pi delta``, NOT the exact free-decay mapping of
    :func:`psi_from_delta` (which gives a ~22 % smaller amplitude at ``psi = 0.4``; V5.13a).
    """
    return np.asarray(psi, dtype=float) / (4.0 * np.pi)


def energy_balance_resonance_amplitude(F0, c, psi, friction=0.0):
    """1-DOF resonance amplitude by energy balance (5.75)-(5.76).

    ``pi A F0 = 4 |P| A + psi c A^2 / 2``  ->  ``A* = 2 (pi F0 - 4 |P|) / (psi c)``;
    ``P = 0`` gives ``2 pi F0 / (psi c)``.  Returns 0 when ``pi F0 <= 4 |P|`` (vibration dies
    out) and ``inf`` when ``psi = 0`` and ``pi F0 > 4 |P|`` (unbounded growth).
    """
    excess = np.pi * F0 - 4.0 * abs(friction)
    if excess <= 0.0:
        return 0.0
    if psi == 0.0:
        return float("inf")
    return float(2.0 * excess / (psi * c))


def energy_balance_2dof(c1, c2, psi1, psi2, F1, F2, beta) -> tuple[float, float]:
    """2-DOF resonance amplitudes by energy balance (5.73).

    ``A1 = 2 pi (F1 + beta F2) / (psi1 c1 + psi2 c2 beta^2)``, ``A2 = beta A1``, with coordinates
    equal to the spring deformations (``c_i``, ``psi_i`` their stiffness and dissipation
    coefficient), generalised forces ``F_i`` and ``beta = beta_r`` the form coefficient of the
    resonant mode (5.33).  Signs are kept (``A1 < 0`` means antiphase with the force).
    """
    A1 = 2.0 * np.pi * (F1 + beta * F2) / (psi1 * c1 + psi2 * c2 * beta**2)
    return float(A1), float(beta * A1)


def energy_balance_ndof(c, psi, F, beta) -> np.ndarray:
    """N-DOF generalisation (5.74): ``A_j = 2 pi sum_i beta_i F_i / sum_i psi_i c_i beta_i^2``.

    ``beta`` is the resonant mode (the book normalises ``beta_j = 1``; the result does not depend
    on the normalisation); returns all amplitudes ``A_i = A_j beta_i``.
    """
    c, psi, F, beta = (np.asarray(v, dtype=float) for v in (c, psi, F, beta))
    return 2.0 * np.pi * np.dot(beta, F) / np.dot(psi * c, beta**2) * beta
