"""Seed 000 (Belokobyl'sky & Koronatov 2013): relaxation friction self-oscillations of a one-mass
torsional system with instantaneous velocity reversals.  Closed forms (16)-(20).

Dimensionless map of the paper:  tau = sqrt(c/I) t,  xi = (c/M0)(phi - omega t),
Omega = omega sqrt(c I) / M0,  epsilon = M1/M0 > 1.
"""
from __future__ import annotations

import math


def k_star(eps: float) -> int:
    """(16): number of instantaneous reversals per period, k* = [(eps - 1)/2 - 1e-5]."""
    return int(math.floor((eps - 1.0) / 2.0 - 1e-5))


def local_interval(k: int, eps: float, Omega: float) -> float:
    """(14): duration tau_k of the k-th local slip interval."""
    return 2.0 * (math.pi * (1 - (-1) ** k) / 2 + (-1) ** (k + 1) * math.atan((2 * k - (eps + 1)) / Omega))


def xi_end(k: int, eps: float) -> float:
    """(13): xi at the end of the k-th local interval, xi_k = (-1)^k (2k - eps)."""
    return (-1) ** k * (2 * k - eps)


def slip_time(eps: float, Omega: float) -> float:
    """(17): tau_* = sum of tau_k, k = 1 .. k*+1."""
    return sum(local_interval(k, eps, Omega) for k in range(1, k_star(eps) + 2))


def stick_time(eps: float, Omega: float) -> float:
    """(19): tau^* = (eps + (-1)^k* (eps - 2(k*+1))) / Omega."""
    ks = k_star(eps)
    return (eps + (-1) ** ks * (eps - 2 * (ks + 1))) / Omega


def period(eps: float, Omega: float) -> float:
    """(20): Lambda = tau_* + tau^* (dimensionless)."""
    return slip_time(eps, Omega) + stick_time(eps, Omega)


def dimensional(eps: float, Omega: float, I: float, c: float, M0: float) -> dict:
    """Period, slip and stick time in seconds and the model data (omega, M1) for given I, c, M0."""
    s = math.sqrt(I / c)
    return {"omega": Omega * M0 / math.sqrt(c * I), "M1": eps * M0, "k_star": k_star(eps),
            "period": period(eps, Omega) * s, "slip_time": slip_time(eps, Omega) * s,
            "stick_time": stick_time(eps, Omega) * s}


def recurrence(eps: float, Omega: float) -> tuple[int, float, float]:
    """Independent check of (16)-(20) by the recurrences (6)-(10): march the local intervals,
    reversing while the reversal condition (10) holds; returns (k*, tau_*, tau^*)."""
    xi_prev, tau_s, k = -eps, 0.0, 1
    while True:
        b = xi_prev + (-1) ** (k + 1)       # amplitude term of (6)
        # (6): xi = b cos tau - Omega sin tau + (-1)^k ; xi' = -b sin tau - Omega cos tau; first tau>0 with xi' = -Omega
        # -b sin tau = Omega (cos tau - 1)  ->  tan(tau/2) = b / Omega  (nonzero root)
        t = 2.0 * math.atan2(b, Omega)
        if t <= 0:
            t += 2 * math.pi
        tau_s += t
        xi_k = b * math.cos(t) - Omega * math.sin(t) + (-1) ** k
        # (10): reversal iff the acceleration with the opposite friction sign keeps the new direction
        acc_after = -xi_k + (-1) ** (k + 1)
        reverse = acc_after < 0 if k % 2 == 1 else acc_after > 0
        if not reverse:
            return k - 1, tau_s, (eps + xi_k) / Omega
        xi_prev, k = xi_k, k + 1
