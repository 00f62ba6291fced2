"""Dry-friction references from the textbook digest (Vulfson 2017): Coulomb free decay (§4.3, §8.2)
and friction self-oscillations (§8.6: (8.37)-(8.47), (8.55)).

Model of §8.6 (Fig. 8.10): link 1 moves at v0 and drags body m through a spring c (and dashpot b);
friction F0 static, F1 < F0 kinetic; q = element deformation, body velocity v0 + q'.
Corrections followed (digest errata): (8.34) b = psi sqrt(cm)/(2 pi); (8.51) the q'^2 coefficient is h2.
"""
from __future__ import annotations

import math

from scipy.optimize import brentq


# ----------------------------------------------------------------- Coulomb decay (§4.3)
def coulomb_extrema(q0: float, P: float, c: float, static: float | None = None) -> list[float]:
    """Successive extrema of m q'' + c q = -P sign q' from q0 at rest (static limit ``static``, default P):
    |q| drops by 2P/c per half-cycle; the motion stops at the first extremum with c|q| <= static."""
    static = P if static is None else static
    out = [q0]
    q = q0
    while abs(c * q) > static:
        s = 1.0 if q > 0 else -1.0
        q = -(q - 2 * s * P / c)          # mirror about the shifted centre s P / c
        out.append(q)
    return out


# -------------------------------------------------------- relaxation stick-slip (§8.6)
def phi0(k: float, c: float, dF: float, v0: float) -> float:
    """(8.37) phi0 = arctg(k dF / (c v0))."""
    return math.atan(k * dF / (c * v0))


def stick_slip_period(k: float, c: float, dF: float, v0: float) -> dict:
    """(8.38)-(8.39): undamped period tau = (2 pi - 2 phi0)/k + 2 dF/(c v0), slip and stick times."""
    p = phi0(k, c, dF, v0)
    slip = (2 * math.pi - 2 * p) / k
    stick = 2 * dF / (c * v0)
    return {"phi0": p, "period": slip + stick, "slip_time": slip, "stick_time": stick,
            "A0": math.hypot(dF / c, v0 / k)}


def critical_phi0(lam: float) -> float:
    """(8.43): lam (1 - phi0*/(2 pi)) = -ln cos phi0*, root in (0, pi/2)."""
    return brentq(lambda p: lam * (1 - p / (2 * math.pi)) + math.log(math.cos(p)), 1e-9, math.pi / 2 - 1e-12)


def critical_speed_book(k: float, c: float, dF: float, lam: float) -> dict:
    """(8.44): v0* = k dF / (c sqrt(exp(2 lam*) - 1)), lam* = lam (1 - phi0*/(2 pi)); (8.46) ds*, tau*."""
    p = critical_phi0(lam)
    ls = lam * (1 - p / (2 * math.pi))
    v = k * dF / (c * math.sqrt(math.exp(2 * ls) - 1))
    ds = v / k * (2 * math.pi - math.atan(k * dF / (c * v))) + dF / c
    return {"phi0": p, "lam_star": ls, "v0": v, "ds": ds, "tau": ds / v,
            "dtau": (math.tan(p) - p) / k}


def critical_speed_exact(m: float, c: float, b: float, F0: float, F1: float) -> float:
    """Exact critical link speed of the damped model (independent of the simulator).

    Dashpot b in parallel with the spring; during stick it loads the body with b v0, so breakaway
    is at -c q + b v0 = F0.  Slip from q_b with q' = -v0 obeys m q'' + b q' + c q = -F1 (closed
    form); v0* is where the body velocity v0 + q' has its first minimum exactly at zero (tangency).
    """
    k = math.sqrt(c / m)
    n = b / (2 * m)
    kd = math.sqrt(k * k - n * n)

    def min_body_velocity(v0):
        y0 = (b * v0 - F0) / c + F1 / c        # deviation from the slip equilibrium q = -F1/c
        yd0 = -v0
        # y = e^{-nt}(A cos kd t + B sin kd t)
        A, B = y0, (yd0 + n * y0) / kd
        # y' = e^{-nt}(P cos + Q sin); y'' = e^{-nt}(R cos + S sin)
        P, Q = -n * A + kd * B, -n * B - kd * A
        R, S = -n * P + kd * Q, -n * Q - kd * P
        # zeros of y'': R cos + S sin = 0 -> t = (atan2(-R, S) mod pi) + j pi/kd; take the 2nd zero after the velocity maximum
        t1 = (math.atan2(-R, S) % math.pi) / kd
        ts = [t1 + j * math.pi / kd for j in range(3)]
        vals = [v0 + math.exp(-n * t) * (P * math.cos(kd * t) + Q * math.sin(kd * t)) for t in ts]
        return min(vals)

    lo, hi = 1e-6, 1.0
    return brentq(min_body_velocity, lo, hi, xtol=1e-15, rtol=1e-13)


def quasi_harmonic_amplitude(b: float, h1: float, h3: float, k: float) -> float:
    """(8.55): A = 2 sqrt(-(b + h1) / (3 h3 k^2)) (falling characteristic, -(b + h1) > 0)."""
    return 2 * math.sqrt(-(b + h1) / (3 * h3 * k * k))
