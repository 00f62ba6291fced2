"""Independent references for programme motion and cam laws (textbook §5.8-5.9, §6.2).

Plain numpy/scipy: closed forms of the standard laws written out directly, adaptive Runge-Kutta
(DOP853) integration of the 1-DOF follower restarted at the knots, the 2x2 monodromy by scipy's expm.
Nothing here imports the package.
"""
from __future__ import annotations

import math

import numpy as np
import scipy.linalg as sla
from scipy.integrate import solve_ivp

# ------------------------------------------------------------------ the standard laws, closed form
TWO_PI = 2 * math.pi


def rise_derivatives(name: str, u):
    """(s, s', s'', s''') of the normalised rise on u in [0, 1] (cam-design closed forms)."""
    u = np.asarray(u, dtype=float)
    if name == "cycloidal":
        return (u - np.sin(TWO_PI * u) / TWO_PI, 1 - np.cos(TWO_PI * u), TWO_PI * np.sin(TWO_PI * u),
                TWO_PI**2 * np.cos(TWO_PI * u))
    if name == "harmonic":
        return (0.5 * (1 - np.cos(math.pi * u)), 0.5 * math.pi * np.sin(math.pi * u),
                0.5 * math.pi**2 * np.cos(math.pi * u), -0.5 * math.pi**3 * np.sin(math.pi * u))
    if name == "polynomial345":
        return (10 * u**3 - 15 * u**4 + 6 * u**5, 30 * u**2 - 60 * u**3 + 30 * u**4, 60 * u - 180 * u**2 + 120 * u**3,
                60 - 360 * u + 360 * u**2)
    if name == "constant_acceleration":
        lo = u < 0.5
        return (np.where(lo, 2 * u**2, 1 - 2 * (1 - u) ** 2), np.where(lo, 4 * u, 4 * (1 - u)), np.where(lo, 4.0, -4.0),
                np.zeros_like(u))
    raise ValueError(name)


# closed-form jumps of Pi^(m) at the ends of a rise of height h over beta (dwell before and after)
def end_jumps(name: str, h: float, beta: float) -> dict:
    """{order: (jump at the start, jump at the end)} of a rise from a dwell to a dwell."""
    if name == "cycloidal":
        return {3: (4 * math.pi**2 * h / beta**3, -4 * math.pi**2 * h / beta**3)}
    if name == "polynomial345":
        return {3: (60 * h / beta**3, -60 * h / beta**3)}
    if name == "harmonic":
        return {2: (0.5 * math.pi**2 * h / beta**2, 0.5 * math.pi**2 * h / beta**2)}
    if name == "constant_acceleration":
        return {2: (4 * h / beta**2, 4 * h / beta**2)}
    raise ValueError(name)


# ------------------------------------------------------------------ time integration
def integrate_piecewise(rhs_pieces, knots, kicks, y0, t_out, rtol=1e-12, atol=1e-14):
    """q'' + 2 n q' + k^2 q = W(t) piece by piece: ``rhs_pieces[i](t, y)`` on [knots[i], knots[i+1]],
    state kicks ``kicks[i]`` (dq, dq') applied at knots[i] for i >= 1; returns (q, q') at t_out (sorted,
    inside [knots[0], knots[-1]])."""
    t_out = np.asarray(t_out, dtype=float)
    out = np.zeros((t_out.size, 2))
    y = np.asarray(y0, dtype=float)
    for i in range(len(knots) - 1):
        a, b = knots[i], knots[i + 1]
        if i > 0:
            y = y + np.asarray(kicks[i], dtype=float)
        sel = (t_out >= a) & ((t_out < b) | ((i == len(knots) - 2) & (t_out <= b)))
        sol = solve_ivp(rhs_pieces[i], (a, b), y, method="DOP853", rtol=rtol, atol=atol, dense_output=True)
        if np.any(sel):
            out[sel] = sol.sol(t_out[sel]).T
        y = sol.y[:, -1]
    return out


def sdof_monodromy(k: float, n: float, tau: float) -> np.ndarray:
    """expm([[0, 1], [-k^2, -2 n]] tau)."""
    return sla.expm(np.array([[0.0, 1.0], [-k * k, -2 * n]]) * tau)


def sawtooth_periodic_state(k: float, n: float, tau: float, top: float) -> np.ndarray:
    """Periodic (q, q') at t = 0+ of q'' + 2 n q' + k^2 q = top t/tau on [0, tau) (V5.9): particular
    solution Y = (top/k^2)(t/tau - 2n/(k^2 tau)), monodromy by expm, (I - Phi) z = Y(tau) - Phi Y(0)."""
    Phi = sdof_monodromy(k, n, tau)
    s = top / k**2
    Y = lambda t: np.array([s * (t / tau - 2 * n / (k * k * tau)), s / tau])
    return np.linalg.solve(np.eye(2) - Phi, Y(tau) - Phi @ Y(0.0))


def sawtooth_undamped(t, k: float, tau: float):
    """V5.9a closed form (c = 1, a = 1/k^2, F* = 1): q = 0.5 cos kt - 0.5 ctg(k tau/2) sin kt + t/tau on [0, tau)."""
    t = np.asarray(t, dtype=float)
    return 0.5 * np.cos(k * t) - 0.5 / math.tan(0.5 * k * tau) * np.sin(k * t) + t / tau


def kick_map_amplitude(k: float, n: float, tau: float, cycles: int = 4000) -> float:
    """Steady free-vibration amplitude just after a unit velocity kick repeated every tau, divided by the
    single-kick amplitude 1/k_1: the discrete map z <- Phi z + (0, 1) iterated from rest (expm)."""
    Phi = sdof_monodromy(k, n, tau)
    z = np.zeros(2)
    kick = np.array([0.0, 1.0])
    for _ in range(cycles):
        z = Phi @ z + kick
    k1 = math.sqrt(k * k - n * n)
    return math.hypot(z[0], (z[1] + n * z[0]) / k1) * k1


def ramp_residual(nu: float, k: float = 1.0, acc: float = 1.0) -> float:
    """Undamped follower, programme acceleration rising linearly 0 -> acc over Delta t = nu T, then constant:
    residual vibration amplitude after the ramp divided by acc/k^2 (DOP853, rtol 1e-12)."""
    T = 2 * math.pi / k
    dt = nu * T
    f = lambda t, y: [y[1], -(acc * t / dt) - k * k * y[0]]
    sol = solve_ivp(f, (0.0, dt), [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-15)
    q, v = sol.y[:, -1]
    # after the ramp: q = -acc/k^2 + u, u free
    u = q + acc / k**2
    return math.hypot(u, v / k) / (acc / k**2)
