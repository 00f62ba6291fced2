"""Independent closed-form references for the steady-state cases (no package solver used).

* Den Hartog (1930) exact steady state of ``m x'' + k x + F sign x' = P0 cos w t`` with two stops per
  period and no sticking: ``X k / P0 = sqrt(V^2 - (F U / P0)^2)``, ``V = 1/(1 - r^2)``,
  ``U = sin(pi/r) / (r (1 + cos(pi/r)))``, r = w / w0.  Cross-checked against the piecewise-analytic
  half-period boundary-value solution (:func:`den_hartog_bvp`).
* Exact free cubic oscillator ``q'' + k0^2 q (1 + xi q^2) = 0`` of peak amplitude A (elliptic integral):
  ``w = k0 sqrt(1 + xi A^2) pi / (2 K(m))``, ``m = xi A^2 / (2 (1 + xi A^2))`` (hardening xi > 0).
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import fsolve
from scipy.special import ellipk


def den_hartog_amplitude(m: float, k: float, F: float, P0: float, omega: float) -> float:
    w0 = np.sqrt(k / m)
    r = omega / w0
    V = 1.0 / (1.0 - r * r)
    U = np.sin(np.pi / r) / (r * (1.0 + np.cos(np.pi / r)))
    val = V * V - (F * U / P0) ** 2
    return float(P0 / k * np.sqrt(val)) if val > 0 else float("nan")


def den_hartog_bvp(m: float, k: float, F: float, P0: float, omega: float, guess: float) -> float:
    """Half-period solution: x'' + w0^2 x = (-F + P0 cos(w t + phi))/m on 0 < t < pi/w with
    x(0) = -X, x'(0) = 0, x(pi/w) = X, x'(pi/w) = 0 (symmetric motion); unknowns A, B, X, phi."""
    w0 = np.sqrt(k / m)
    D = P0 / (k - m * omega ** 2)
    th = np.pi / omega

    def eqs(u):
        A, B, X, ph = u
        x = lambda t: A * np.cos(w0 * t) + B * np.sin(w0 * t) - F / k + D * np.cos(omega * t + ph)
        v = lambda t: -A * w0 * np.sin(w0 * t) + B * w0 * np.cos(w0 * t) - D * omega * np.sin(omega * t + ph)
        return [x(0) + X, v(0), x(th) - X, v(th)]

    best = None
    for ph0 in np.linspace(0, 2 * np.pi, 12, endpoint=False):
        sol, info, ier, _ = fsolve(eqs, [-guess, 0.0, guess, ph0], full_output=True, xtol=1e-14)
        if ier == 1 and sol[2] > 0 and np.max(np.abs(eqs(sol))) < 1e-12 * max(guess, 1):
            if best is None or abs(sol[2] - guess) < abs(best - guess):
                best = sol[2]
    return float(best) if best is not None else float("nan")


def duffing_backbone_exact(k0: float, xi: float, A) -> np.ndarray:
    A = np.asarray(A, float)
    mpar = xi * A * A / (2 * (1 + xi * A * A))
    return k0 * np.sqrt(1 + xi * A * A) * np.pi / (2 * ellipk(mpar))


def duffing_rk4_sweep(omegas, c: float = 0.1, k: float = 1.0, k3: float = 0.5, W: float = 0.25,
                      periods: int = 400, steps: int = 64, x0=(0.0, 0.0), tol: float = 1e-9):
    """Brute-force time integration of q'' + c q' + k q + k3 q^3 = W sin(w t) (classical RK4, fixed
    ``steps`` per period, pure Python), sweeping w through ``omegas`` and starting each frequency
    from the final state of the previous one (the paper/textbook method).  Each frequency runs until
    the stroboscopic point changes by < tol over a period (at most ``periods``).  Returns the
    fundamental amplitude at each w (Fourier coefficient over the last period) and the final state."""
    import math

    x, v = float(x0[0]), float(x0[1])
    amps = []
    for w in omegas:
        T = 2 * math.pi / w
        h = T / steps

        def f(t, x, v):
            return v, W * math.sin(w * t) - c * v - k * x - k3 * x * x * x

        for p in range(periods):
            xs, vs = x, v
            ca = sa = 0.0
            for i in range(steps):
                t = i * h
                k1x, k1v = f(t, x, v)
                k2x, k2v = f(t + h / 2, x + h / 2 * k1x, v + h / 2 * k1v)
                k3x, k3v = f(t + h / 2, x + h / 2 * k2x, v + h / 2 * k2v)
                k4x, k4v = f(t + h, x + h * k3x, v + h * k3v)
                ca += x * math.cos(w * t)
                sa += x * math.sin(w * t)
                x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
                v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
            if abs(x - xs) + abs(v - vs) < tol:
                break
        amps.append(2 / steps * math.hypot(ca, sa))
    return np.array(amps), (x, v)
