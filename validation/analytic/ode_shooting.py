"""Periodic orbits of a smooth forced ODE by shooting with an independent high-accuracy integrator --
the reference for harmonic balance on smooth models (Neimark-Sacker points of coupled Duffing
oscillators).

The state y (n) obeys y' = f(t, y); the monodromy matrix comes from the variational equation
Phi' = df/dy Phi, integrated together with y by scipy's DOP853 (rtol 1e-12, atol 1e-14).  A periodic
orbit of period T solves P(y) = y (Newton with the exact monodromy).  Nothing here uses drivefem.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq


class ForcedODE:
    """y' = rhs(t, y, w), with the Jacobian jac(t, y, w) (n x n), forced with period 2 pi / w."""

    def __init__(self, rhs, jac, n):
        self.rhs, self.jac, self.n = rhs, jac, int(n)

    def period_map(self, y0, w, nu=1):
        """(P(y0), monodromy) over nu forcing periods."""
        n = self.n
        T = nu * 2 * np.pi / w

        def f(t, z):
            y = z[:n]
            Phi = z[n:].reshape(n, n)
            return np.concatenate([self.rhs(t, y, w), (self.jac(t, y, w) @ Phi).ravel()])

        z0 = np.concatenate([np.asarray(y0, float), np.eye(n).ravel()])
        sol = solve_ivp(f, (0.0, T), z0, method="DOP853", rtol=1e-12, atol=1e-14)
        z = sol.y[:, -1]
        return z[:n], z[n:].reshape(n, n)

    def periodic(self, y0, w, nu=1, tol=1e-12, maxit=40):
        """The periodic orbit near y0 at w and its Floquet multipliers."""
        y = np.array(y0, float)
        for _ in range(maxit):
            P, Phi = self.period_map(y, w, nu)
            dy = np.linalg.solve(Phi - np.eye(self.n), -(P - y))
            y = y + dy
            if np.max(np.abs(dy)) <= tol * max(np.max(np.abs(y)), 1e-300):
                P, Phi = self.period_map(y, w, nu)
                return y, np.linalg.eigvals(Phi)
        raise RuntimeError(f"no periodic orbit at w = {w}")

    def locate(self, test, wa, wb, y0, nu=1):
        """The frequency in [wa, wb] where test(multipliers) changes sign (Brent; orbits at fixed w)."""
        state = {"y": np.array(y0, float)}

        def f(w):
            y, mu = self.periodic(state["y"], w, nu)
            state["y"] = y
            return test(mu)

        w = brentq(f, wa, wb, xtol=1e-13 * wb, rtol=1e-14)
        y, mu = self.periodic(state["y"], w, nu)
        return w, y, mu


def coupled_duffing(m, k, kc, c, k3, F):
    """Two oscillators m x_i'' + c x_i' + k x_i + k3 x_i^3 + kc (x_i - x_j) = F sin(w t) delta_i1."""
    def rhs(t, y, w):
        x1, x2, v1, v2 = y
        a1 = (F * np.sin(w * t) - c * v1 - k * x1 - k3 * x1 ** 3 - kc * (x1 - x2)) / m
        a2 = (-c * v2 - k * x2 - k3 * x2 ** 3 - kc * (x2 - x1)) / m
        return np.array([v1, v2, a1, a2])

    def jac(t, y, w):
        x1, x2 = y[0], y[1]
        J = np.zeros((4, 4))
        J[0, 2] = J[1, 3] = 1.0
        J[2, 0] = -(k + 3 * k3 * x1 * x1 + kc) / m
        J[2, 1] = kc / m
        J[3, 1] = -(k + 3 * k3 * x2 * x2 + kc) / m
        J[3, 0] = kc / m
        J[2, 2] = J[3, 3] = -c / m
        return J

    return ForcedODE(rhs, jac, 4)


def complex_pair_modulus(mu) -> float:
    """|mu| - 1 of the complex multiplier pair closest to the unit circle (the Neimark-Sacker test);
    +inf if there is none."""
    mu = np.asarray(mu, complex)
    c = mu[np.abs(mu.imag) > 1e-10]
    if c.size == 0:
        return np.inf
    return float(np.abs(c[np.argmin(np.abs(np.abs(c) - 1.0))]) - 1.0)
