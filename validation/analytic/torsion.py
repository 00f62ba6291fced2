"""Uniform shafts in torsion (and rods in axial vibration): book §2.2, §4.10, §5.11.

The wave equation (4.51) ``GI_p phi'' = (J/L) phi_tt`` is written per unit length here:
``stiffness * phi'' = inertia_per_length * phi_tt`` with ``stiffness = G*J_t`` (``E*A`` for an
axial rod) and ``inertia_per_length = rho*J_p`` plus any attached distributed inertia
(``rho*A`` for a rod).  Angular frequencies ``omega`` are in rad/s.
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

TORSION_BCS = ("fixed-free", "fixed-fixed", "free-free")

_XTOL = 1e-14


def torsion_roots(bc: str, n: int) -> np.ndarray:
    """First ``n`` positive roots ``sigma_r * L`` of the uniform-shaft frequency equation.

    (4.55): fixed-free ``cos(sigma L) = 0`` -> ``(2r - 1) pi / 2``;
    fixed-fixed and free-free ``sin(sigma L) = 0`` -> ``r pi``.
    The free-free shaft also has a rigid-body (zero-frequency) mode, which is NOT included.
    """
    r = np.arange(1, n + 1, dtype=float)
    if bc == "fixed-free":
        return (2.0 * r - 1.0) * np.pi / 2.0
    if bc in ("fixed-fixed", "free-free"):
        return r * np.pi
    raise ValueError(f"bc = {bc!r} is not valid; allowed: {', '.join(TORSION_BCS)}")


def torsion_omegas(stiffness: float, inertia_per_length: float, length: float,
                   bc: str, n: int) -> np.ndarray:
    """Natural frequencies ``omega_r = (sigma_r L) / L * sqrt(stiffness / inertia_per_length)``.

    This is (4.56) ``k_r = sigma_r L sqrt(G I_p / (J L))`` with ``J = inertia_per_length * L``.
    For a homogeneous rod it reduces to ``sigma_r sqrt(G / rho)``, independent of the diameter
    (the seed prints ``sqrt(GI/rho)`` -- a misprint, §4.10).
    """
    return torsion_roots(bc, n) / length * np.sqrt(stiffness / inertia_per_length)


def end_disc_roots(inertia_ratio: float, n: int) -> np.ndarray:
    """First ``n`` positive roots ``x = sigma L`` of ``x tan x = J_shaft / J_disc``.

    Shaft fixed at ``x = 0`` carrying a disc ``J_disc`` at ``x = L`` (digest V2.2b);
    ``omega_r = x_r sqrt(c / J_shaft)`` with ``c = G J_t / L``.  Root ``r`` lies in
    ``((r-1) pi, (r-1) pi + pi/2)``; ``x sin x - ratio cos x`` (no poles) is solved by brentq.
    """
    if not inertia_ratio > 0.0:
        raise ValueError(f"inertia_ratio = {inertia_ratio!r} is not valid; allowed: a number > 0")

    def f(x: float) -> float:
        return x * np.sin(x) - inertia_ratio * np.cos(x)

    lows = np.arange(n) * np.pi
    return np.array([brentq(f, lo, lo + np.pi / 2.0, xtol=_XTOL) for lo in lows])


def reduced_inertia_omega(stiffness_total: float, J_shaft: float, J_disc: float) -> float:
    """Book estimate ``sqrt(c / (J_disc + J_shaft / 3))`` of §2.2 (reduced model, Fig. 2.3b).

    ``c = G J_t / L`` is the total shaft stiffness; from the assumed shape ``x / l`` in (2.4).
    It is a Rayleigh upper bound of the exact first frequency (see :func:`end_disc_roots`).
    """
    return float(np.sqrt(stiffness_total / (J_disc + J_shaft / 3.0)))


def forced_torsion_end_amplitude(stiffness, inertia_per_length, length, omega, moment):
    """Amplitude of ``phi(L)`` for a shaft clamped at 0 under ``M cos(omega t)`` at ``x = L``.

    (5.61) with ``x = L``: ``A(L) = M tan(sigma L) / (sigma * stiffness)``,
    ``sigma = omega sqrt(inertia_per_length / stiffness)``.  At ``omega = 0`` the static value
    ``M L / stiffness`` is returned.  The sign changes (antiphase) above each resonance
    ``cos(sigma L) = 0``.  Accepts arrays of ``omega``.
    """
    x = np.asarray(omega, dtype=float) * np.sqrt(inertia_per_length / stiffness) * length
    safe = np.where(x == 0.0, 1.0, x)
    tan_over_x = np.where(x == 0.0, 1.0, np.tan(safe) / safe)
    out = moment * length / stiffness * tan_over_x
    return float(out) if out.ndim == 0 else out


def stepped_fixed_free_omegas(segments: list[tuple[float, float, float]], n: int,
                              omega_max: float | None = None) -> np.ndarray:
    """First ``n`` natural frequencies of a stepped shaft clamped at x = 0 and free at the end.

    ``segments``: (length, stiffness G J_t, inertia per length rho I_p) from the clamp.  Within
    segment i, phi = a cos(sigma_i s) + b sin(sigma_i s) (4.54), sigma_i = omega sqrt(inertia_i /
    stiffness_i); angle and torque GJ phi' are continuous at the steps.  The free-end torque
    T(L; omega) of the solution with phi(0) = 0, GJ phi'(0) = 1 vanishes at the natural
    frequencies; its sign changes are bracketed on a fine omega grid and refined by brentq.
    """
    def end_torque(omega: float) -> float:
        phi, torque = 0.0, 1.0
        for length, stiff, inert in segments:
            sig = omega * np.sqrt(inert / stiff)
            c, s = np.cos(sig * length), np.sin(sig * length)
            phi, torque = phi * c + torque * s / (stiff * sig), -phi * stiff * sig * s + torque * c
        return torque

    if omega_max is None:  # the r-th root lies near (2r - 1) pi / (2 T), T the wave travel time
        travel = sum(length * np.sqrt(inert / stiff) for length, stiff, inert in segments)
        omega_max = 2.0 * (n + 1) * np.pi / travel
    grid = np.linspace(1e-9 * omega_max, omega_max, 400 * (n + 2))
    vals = np.array([end_torque(w) for w in grid])
    idx = np.flatnonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))
    roots = [brentq(end_torque, grid[i], grid[i + 1], xtol=1e-13 * omega_max) for i in idx[:n]]
    if len(roots) < n:
        raise ValueError(f"n = {n} is not valid; allowed: at most {len(roots)} roots below omega_max = {omega_max:g}")
    return np.array(roots)
