"""Closed forms of the continuum pseudo-medium (§10.5), used by the drive reports.

Shaft GI, inertia per length rho0, smeared mechanisms m_bar = n m/L, k = sqrt(c/m), Pi'.
Free vibrations (10.48)-(10.50): GI sigma^2 = rho(p) p^2 with rho(p) = rho0 + m_bar Pi'^2/(1 - p^2/k^2)
and sigma_r L = lambda_r of the boundary case; per r a biquadratic
rho0 s^2 - (rho0 k^2 + m_bar Pi'^2 k^2 + g) s + g k^2 = 0, s = p^2, g = GI lambda_r^2 / L^2.
(10.50) is the clamped-free case, lambda_r = (2r-1) pi/2.
"""
from __future__ import annotations

import numpy as np

from ..errors import ModelError
from .regular import check_boundary


def eigen_lambdas(boundary: str, n_r: int) -> np.ndarray:
    """sigma_r L for r = 1..n_r: clamped-free/free-clamped (2r-1) pi/2, clamped-clamped r pi,
    free-free (r-1) pi (r = 1: rigid rotation)."""
    check_boundary(boundary)
    r = np.arange(1, n_r + 1, dtype=float)
    if boundary in ("clamped-free", "free-clamped"):
        return (2 * r - 1) * np.pi / 2
    if boundary == "clamped-clamped":
        return r * np.pi
    return (r - 1) * np.pi


def pseudo_medium_frequencies(GI, rho, m_bar, k, ratio, L, boundary="clamped-free", n_r=3):
    """(lower, upper) roots p_r1 < k < p_*, p_r2 per shaft shape r ((10.50) generalised).
    rho = 0 (massless shaft): only the lower roots exist; the upper ones are returned as inf."""
    if ratio == 0:
        raise ModelError("[drive.mechanism]", "ratio", ratio, "a non-zero Pi'")
    lam = eigen_lambdas(boundary, n_r)
    g = GI * lam**2 / L**2
    if np.isinf(k):   # rigid mechanisms (10.51)
        return np.sqrt(g / (rho + m_bar * ratio**2)), np.full(n_r, np.inf)
    k2, mP = k**2, m_bar * ratio**2
    b = rho * k2 + mP * k2 + g
    disc = np.sqrt(b**2 - 4 * rho * g * k2)
    with np.errstate(divide="ignore"):
        s_lo = 2 * g * k2 / (b + disc)
        s_hi = np.where(rho > 0, (b + disc) / (2 * rho if rho > 0 else 1.0), np.inf)
    return np.sqrt(s_lo), np.sqrt(s_hi)


def stop_band(rho, m_bar, k, ratio) -> tuple[float, float]:
    """(k, p_*) with p_*/k = sqrt(1 + m_bar Pi'^2/rho0) (10.54)."""
    return k, k * float(np.sqrt(1 + m_bar * ratio**2 / rho))


def pseudo_medium_forced(x, omega, GI, rho, m_bar, k, ratio, L, f_bar):
    """Corrected forced shaft amplitude Y(x) of the clamped-free pseudo-medium under a
    distributed output force f_bar = n F / L ((10.58)-(10.61) with the digest's corrections):
    Y_* = -f_bar Pi' / (w^2 [rho0 (1 - w^2/k^2) + m_bar Pi'^2]),
    rho(w) > 0: Y = Y_* [1 - cos sx - tan(sL) sin sx];  rho(w) < 0: Y = Y_* [1 - ch s0x + th(s0L) sh s0x]."""
    x = np.asarray(x, dtype=float)
    w = float(omega)
    den = rho * (1 - w**2 / k**2) + m_bar * ratio**2
    if w == k:   # rho(w) infinite: the shaft is locked at Y_* = -f_bar/(c_bar Pi') except at the clamp
        return -f_bar * ratio / (w**2 * den) * (x > 0)
    rho_w = den / (1 - w**2 / k**2)
    Ystar = -f_bar * ratio / (w**2 * den)
    P = rho_w * w**2 / GI
    if P > 0:
        s = np.sqrt(P)
        return Ystar * (1 - np.cos(s * x) - np.tan(s * L) * np.sin(s * x))
    s0 = np.sqrt(-P)
    return Ystar * (1 - np.cosh(s0 * x) + np.tanh(s0 * L) * np.sinh(s0 * x))
