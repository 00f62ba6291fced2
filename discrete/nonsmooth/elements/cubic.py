"""Smooth cubic spring (textbook (8.20)): an element with a smooth force only."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .base import LAW_CUBIC, Element, Linearisation, StepLaw


@dataclass
class Cubic(Element):
    """Cubic spring on s = g . x: force along s ``F = -k3 s^3`` (hardening for k3 > 0)."""

    k3: float = 0.0

    kind = "cubic"
    event_driven = False
    work = "conservative"

    @property
    def affine(self) -> bool:
        return False

    def force(self, mode, s, sd, e0, t):
        return -self.k3 * s ** 3

    def potential(self, s, mode):
        return 0.25 * self.k3 * s ** 4

    def smooth_force(self, s, sd, eps):
        return -self.k3 * s ** 3, -3 * self.k3 * s ** 2, np.zeros_like(s)

    def compiled_law(self, eps):
        return LAW_CUBIC, (float(self.k3),)

    def regularised_force(self, s, sd, t, memory, settings):
        return -self.k3 * s ** 3, ()

    def moreau(self, h, theta):
        return CubicStep(self, h, theta)

    def linearised(self, state=None):
        return Linearisation(state or self.linear_state, note="linear part at s = 0: no stiffness (the force "
                             "-k3 s^3 has zero slope there; the drive's linear spring is its [[spring]])")


class CubicStep(StepLaw):
    """The cubic spring over one Moreau-Jean step: the impulse is h times the discrete gradient of
    its potential V(s) = k3 s^4 / 4 between the step's end positions,

        p = -h (V(s1) - V(s0)) / (s1 - s0) = -h k3 (s0^3 + s0^2 s1 + s0 s1^2 + s1^3) / 4,
        s1 = s0 + h ((1 - theta) u0 + theta u1),

    solved exactly for p (implicit: the stiffening does not limit the step).  The work of this impulse
    over the step is exactly -(V(s1) - V(s0)), so with theta = 1/2 (where the scheme's displacement update
    is the midpoint rule) the energy balance closes to the solve tolerance.  The equation
    g(p) = p + h k3 (..)/4 = 0 has g' = 1 + h^2 theta D k3 ((s0 + s1)^2 + 2 s1^2)/4 >= 1: one root,
    found by Newton safeguarded with bisection."""

    conservative = True

    def __init__(self, element, h, theta):
        super().__init__(element)
        self.h, self.theta, self.k3 = h, theta, element.k3

    def begin(self, s0, u0):
        self.s0 = s0
        self.a = s0 + self.h * (1 - self.theta) * u0

    def _g(self, p, base, b):
        s0, s1 = self.s0, base + b * p
        q = s0 * s0 * s0 + s0 * s0 * s1 + s0 * s1 * s1 + s1 * s1 * s1
        dq = (s0 * s0 + 2 * s0 * s1 + 3 * s1 * s1) * b
        c = 0.25 * self.h * self.k3
        return p + c * q, 1.0 + c * dq

    def project(self, u, D, p):
        b = self.h * self.theta * D
        base = self.a + self.h * self.theta * (u - D * p)     # s1 without the own impulse
        lo, hi = -np.inf, np.inf
        x = p
        for _ in range(100):
            g, dg = self._g(x, base, b)
            if g > 0:
                hi = min(hi, x)
            else:
                lo = max(lo, x)
            step = g / dg
            xn = x - step
            if not (lo < xn < hi) and np.isfinite(lo) and np.isfinite(hi):
                xn = 0.5 * (lo + hi)
            if abs(xn - x) <= 1e-15 * max(abs(xn), 1e-300) or g == 0:
                return xn
            x = xn
        return x

    def energy_term(self, s):
        """Twice the potential energy, k3 s^4 / 2."""
        return 0.5 * self.k3 * s ** 4
