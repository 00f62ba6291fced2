"""The short-bearing film (Ocvirk; Dubois & Ocvirk, NACA Report 1157, 1953) in closed form.

For L/D -> 0 the circumferential pressure flow drops out of the Reynolds equation, which then
integrates in z: with g = a sin(theta) + b cos(theta) (the source of :mod:`.reynolds`,
a = -6 omega X + 12 Y', b = 6 omega Y + 12 X') and H = 1 - X cos(theta) - Y sin(theta),

    P(theta, zeta) = g (zeta^2 - (L/D)^2) / (2 H^3),        zeta = z / R,

and the force on the journal, F = (mu R^4 / c^2) f with

    f = -(L/R)^3 / 12 * int g / H^3 (cos theta, sin theta) dtheta

over the pressurised film: ``"pi"`` (Guembel's half-Sommerfeld condition: where g > 0, an
interval of length pi that turns with the journal's velocity) or ``"2pi"`` (uncavitated: the
whole circle; a squeeze-film damper with a high supply pressure).  At rest in the bearing
(omega = 0) the same law is the short squeeze-film damper (Vance, *Rotordynamics of
Turbomachinery* (1988) §6; San Andres, *Squeeze film dampers* (2010)).

The integral is in closed form: Sommerfeld's substitution (1 + e cos gamma)(1 - e cos psi) =
1 - e^2 (psi = theta - attitude, e = |(X, Y)|) turns g (cos, sin)(theta) dtheta / H^3 into a
trigonometric polynomial of degree 2 in gamma over (1 - e^2)^(5/2), whose antiderivative is
elementary, on any interval (the pi film's ends turn with the velocity).
"""
from __future__ import annotations

import math

import numpy as np

from discrete.errors import SolverError

FILMS = ("pi", "2pi")


def _gamma(psi, e):
    """Sommerfeld's angle of psi (monotone, gamma(psi + 2 pi) = gamma(psi) + 2 pi)."""
    r = math.sqrt((1 + e) / (1 - e))
    return psi + 2 * math.atan((r - 1) * math.sin(psi) / ((1 + r) + (1 - r) * math.cos(psi)))


def _moments(g0: float, g1: float, e: float) -> tuple[float, float, float]:
    """int u^2, u s, s^2 dtheta / H^3 over gamma in [g0, g1] (u, s = cos, sin psi)."""
    def uu(g):
        return 0.5 * g + 0.25 * math.sin(2 * g) + 2 * e * math.sin(g) + e * e * g

    def us(g):
        return 0.5 * math.sin(g) ** 2 - e * math.cos(g)

    def ss(g):
        return 0.5 * g - 0.25 * math.sin(2 * g)

    k = (1 - e * e) ** -2.5
    return (k * (uu(g1) - uu(g0)), k * math.sqrt(1 - e * e) * (us(g1) - us(g0)), k * (1 - e * e) * (ss(g1) - ss(g0)))


class ShortFilm:
    """The short-bearing film of length ratio L/D with the film extent ``film`` ("pi" or "2pi")."""

    def __init__(self, length_ratio: float, film: str = "pi"):
        self.length_ratio = float(length_ratio)
        self.film = film
        self._scale = (2.0 * self.length_ratio) ** 3 / 12.0          # (L/R)^3 / 12

    def force(self, X: float, Y: float, a: float, b: float) -> np.ndarray:
        """Dimensionless force on the journal, F = mu R^4 / c^2 * f (see the module notes)."""
        e = math.hypot(X, Y)
        if e >= 1.0:
            raise SolverError(f"journal at eccentricity ratio {e:.6g} >= 1: the film has closed")
        if a == 0.0 and b == 0.0:
            return np.zeros(2)
        att = math.atan2(Y, X) if e > 0 else 0.0
        if self.film == "2pi":
            lo, hi = -math.pi, math.pi
        else:                              # g = rho sin(theta + beta) > 0 on theta in (-beta, pi - beta)
            lo = -math.atan2(b, a) - att
            hi = lo + math.pi
        Iuu, Ius, Iss = _moments(_gamma(lo, e), _gamma(hi, e), e)
        ca, sa = math.cos(att), math.sin(att)
        p, q = a * sa + b * ca, a * ca - b * sa          # g = p cos(psi) + q sin(psi)
        fy = p * ca * Iuu + (q * ca - p * sa) * Ius - q * sa * Iss
        fz = p * sa * Iuu + (p * ca + q * sa) * Ius + q * ca * Iss
        return np.array([-self._scale * fy, -self._scale * fz])

    def force_and_jacobian(self, X: float, Y: float, a: float, b: float):
        """(f, df/d(X, Y, a, b))."""
        return self.force(X, Y, a, b), self.jacobian(X, Y, a, b)

    def jacobian(self, X: float, Y: float, a: float, b: float) -> np.ndarray:
        """(2, 4) derivatives of :meth:`force` with respect to (X, Y, a, b): central differences of the
        closed form (steps 1e-6 of the scales: truncation ~1e-12, round-off ~1e-10 relative)."""
        e = math.hypot(X, Y)
        hx = 1e-6 * max(1.0 - e, 1e-3)
        ha = 1e-6 * max(abs(a), abs(b), 1e-300)
        out = np.zeros((2, 4))
        base = np.array([X, Y, a, b], dtype=float)
        for j, h in enumerate((hx, hx, ha, ha)):
            up, dn = base.copy(), base.copy()
            up[j] += h
            dn[j] -= h
            out[:, j] = (self.force(*up) - self.force(*dn)) / (2 * h)
        return out
