"""Clearance / backlash (textbook (11.1)) and its smooth arctan law (11.2)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...errors import ModelError
from .base import Element, Linearisation, PiecewiseAffineLaw, StepLaw
from .contact import flank_event, flank_guards, flank_mode


@dataclass
class Gap(Element):
    """No force for lower <= s <= upper, ``F = -k (s - upper)`` above, ``F = -k (s - lower)`` below
    (symmetric: lower = -Delta, upper = Delta, Delta = half the gap s).  Modes: +1, 0, -1.

    ``law = "arctan"``: the smooth law (11.2) for a symmetric gap,
    ``F = -k (s - Delta sign s) (1/2 + arctan(L (|s| - Delta)/Delta)/pi)`` (no modes, no events).
    """

    k: float = 0.0
    lower: float = 0.0
    upper: float = 0.0
    law: str = "exact"
    L: float = 1e3

    kind = "gap"
    smoothness = 1

    def __post_init__(self):
        super().__post_init__()
        where = f"[[gap]] {self.name!r}"
        if not self.k > 0:
            raise ModelError(where, "k", self.k, "a number > 0")
        if not self.lower <= self.upper:
            raise ModelError(where, "clearance", [self.lower, self.upper], "lower <= upper")
        if self.law not in ("exact", "arctan"):
            raise ModelError(where, "law", self.law, "'exact' | 'arctan'")
        if self.law == "arctan":
            if not abs(self.lower + self.upper) <= 1e-14 * max(abs(self.upper), 1e-300) or self.upper <= 0:
                raise ModelError(where, "clearance", [self.lower, self.upper],
                                 "a symmetric clearance [-Delta, Delta] with Delta > 0 for law = 'arctan' (11.2)")
            if not self.L > 0:
                raise ModelError(where, "L", self.L, "a number > 0")

    @property
    def work(self) -> str:
        """The exact law is conservative (its potential is tracked); the arctan law's power is element work."""
        return "conservative" if self.law == "exact" else "elements"

    @property
    def event_driven(self) -> bool:
        return self.law == "exact"

    @property
    def affine(self) -> bool:
        return self.law == "exact"

    def arctan_force(self, s):
        d = self.upper
        u = 0.5 + np.arctan(self.L * (np.abs(s) - d) / d) / np.pi
        return -self.k * (s - d * np.sign(s)) * u

    # ------------------------------------------------------------ event-driven solver
    def initial_mode(self, s, sd, scale_v):
        return 0 if self.law == "arctan" else flank_mode(s, sd, self.upper, self.lower)

    def force(self, mode, s, sd, e0, t):
        if self.law == "arctan":
            return self.arctan_force(s)
        if mode == 1:
            return -self.k * (s - self.upper * e0)
        if mode == -1:
            return -self.k * (s - self.lower * e0)
        return None

    def guards(self, mode, s, sd, F, e0, t):
        return flank_guards(mode, s, self.upper, self.lower, e0) if self.law == "exact" else []

    def on_event(self, tag, ctx):
        flank_event(tag, ctx)

    def potential(self, s, mode):
        if self.law == "arctan":
            return 0.0 * s  # not conservative-tracked: its power is counted as element work
        return 0.5 * self.k * ((s - self.upper) ** 2 * (mode == 1) + (s - self.lower) ** 2 * (mode == -1))

    def stiffness(self) -> float:
        return self.k

    # ------------------------------------------------------------ linear analyses
    linear_states = ("closed", "open")

    def linearised(self, state=None):
        state = state or self.linear_state
        if state == "closed":
            return Linearisation(state, k=self.k, note=f"closed: a spring of its contact stiffness k = {self.k:g}")
        return Linearisation(state, note="open: no force (free inside the clearance)")

    # ------------------------------------------------------------ smooth laws
    def smooth_force(self, s, sd, eps):
        z = np.zeros_like(s)
        if self.law == "arctan":
            h = 1e-7 * max(self.upper, 1e-300)
            return self.arctan_force(s), (self.arctan_force(s + h) - self.arctan_force(s - h)) / (2 * h), z
        up = (s > self.upper).astype(float)
        lo = (s < self.lower).astype(float)
        F = -self.k * ((s - self.upper) * up + (s - self.lower) * lo)
        return F, -self.k * (up + lo), z

    def piecewise_law(self):
        """The exact law (11.1): -k (s - lower) below, 0 inside, -k (s - upper) above (None: arctan law)."""
        if self.law != "exact":
            return None
        k, lo, up = self.k, self.lower, self.upper
        if lo == up:
            return PiecewiseAffineLaw((up,), (k * lo, k * up), (-k, -k), (0.0, 0.0))
        return PiecewiseAffineLaw((lo, up), (k * lo, 0.0, k * up), (-k, 0.0, -k), (0.0, 0.0, 0.0))

    def regularised_force(self, s, sd, t, memory, settings):
        F = 0.0
        if self.law == "arctan":
            F = float(self.arctan_force(s))
        elif s > self.upper:
            F = -self.k * (s - self.upper)
        elif s < self.lower:
            F = -self.k * (s - self.lower)
        return F, ()

    # ------------------------------------------------------------ Moreau-Jean
    def clearance(self) -> tuple[float, float]:
        return self.lower, self.upper

    def moreau(self, h, theta):
        if self.law != "exact":
            raise ModelError(f"element {self.name!r}", "law", self.law,
                             "'exact' for the Moreau-Jean scheme (use method = 'event' for the smooth law (11.2))")
        return ClearanceSpringStep(self, h, theta)


class ClearanceSpringStep(StepLaw):
    """Piecewise-linear spring with clearance (one-sided spring, exact gap): the impulse h F(s_theta)
    of the force at the theta-point position s_theta = s0 + h theta ((1 - theta) u0 + theta u1),
    solved exactly on its branch (implicit: a stiff stop does not limit the step)."""

    conservative = True

    def __init__(self, element, h, theta):
        super().__init__(element)
        self.h = h
        self.k = element.k
        self.lo, self.up = element.clearance()
        self.sb = h * theta * theta
        self.hkb = h * self.k * self.sb
        self.theta = theta
        self.contact = False

    def begin(self, s0, u0):
        th = self.theta
        self.sa = s0 + self.h * th * (1 - th) * u0

    def project(self, u, D, p):
        r = u - D * p
        sfree = self.sa + self.sb * r
        if sfree > self.up:
            return -self.h * self.k * (sfree - self.up) / (1.0 + self.hkb * D)
        if sfree < self.lo:
            return -self.h * self.k * (sfree - self.lo) / (1.0 + self.hkb * D)
        return 0.0

    def energy_term(self, s: float) -> float:
        """k d^2 (twice the potential energy), d the penetration beyond the clearance."""
        d = s - self.up if s > self.up else (s - self.lo if s < self.lo else 0.0)
        return self.k * d * d

    def finish(self, p):
        new = bool(p != 0)
        out = [] if new == self.contact else [(1, "contact_close")] if new else [(2, "contact_open")]
        self.contact = new
        return out
