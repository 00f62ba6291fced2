"""Contact with stiffness and damping switched on at closure (textbook §11.2-11.3, (11.3)-(11.4)): a
Kelvin-Voigt gap or stop."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import ModelError
from .base import Element


@dataclass
class Contact(Element):
    """Clearance lower <= s <= upper (a lone bound: a stop, the other at infinity); beyond it a
    spring k and a dashpot c in parallel act on the penetration d (d = s - upper above, s - lower
    below): ``F = -k d - c s'``, switched by the geometry alone (the reading of (11.4)
    ``q'' + [2 delta N q' + N^2 (q - Delta sign q)] u(|q| - Delta) = cos phi``).  Modes: +1 in
    contact above, -1 below, 0 free.  The spring part is conservative (potential k d^2 / 2), the
    dashpot's power is contact work.  A free mass hitting it at speed v leaves after the half-period
    pi / omega_d of the damped contact oscillation with the restitution exp(-pi zeta / sqrt(1 - zeta^2))
    (zeta = c / (2 sqrt(k m))); the dashpot may pull at separation, as (11.4) prescribes."""

    k: float = 0.0
    c: float = 0.0
    lower: float = -math.inf
    upper: float = math.inf

    kind = "contact"
    work = "contacts"
    smoothness = 1

    def __post_init__(self):
        where = f"[[contact]] {self.name!r}"
        if not self.k > 0:
            raise ModelError(where, "k", self.k, "a number > 0")
        if not self.c >= 0:
            raise ModelError(where, "c", self.c, "a number >= 0")
        if not self.lower <= self.upper or (math.isinf(self.lower) and math.isinf(self.upper)):
            raise ModelError(where, "clearance", [self.lower, self.upper], "lower <= upper, at least one finite")

    has_potential = True

    def _bound(self, mode):
        return self.upper if mode == 1 else self.lower

    # ------------------------------------------------------------ event-driven solver
    def initial_mode(self, s, sd, scale_v):
        if s > self.upper or (s == self.upper and sd > 0):
            return 1
        if s < self.lower or (s == self.lower and sd < 0):
            return -1
        return 0

    def force(self, mode, s, sd, e0, t):
        if mode == 0:
            return None
        return -self.k * (s - self._bound(mode) * e0) - self.c * sd

    def guards(self, mode, s, sd, F, e0, t):
        if mode == 1:
            return [(s - self.upper * e0, "leave")]
        if mode == -1:
            return [(self.lower * e0 - s, "leave")]
        out = []
        if math.isfinite(self.upper):
            out.append((self.upper * e0 - s, "close+"))
        if math.isfinite(self.lower):
            out.append((s - self.lower * e0, "close-"))
        return out

    def on_event(self, tag, ctx):
        ctx.mode = {"leave": 0, "close+": 1, "close-": -1}[tag]
        ctx.record("contact_open" if tag == "leave" else "contact_close")

    def potential(self, s, mode):
        if mode == 0:
            return 0.0 * s
        return 0.5 * self.k * (s - self._bound(mode)) ** 2

    def split_force(self, mode, sd, F):
        if mode == 0:
            return None, None
        damper = -self.c * sd
        return F - damper, damper

    def stiffness(self) -> float:
        return self.k

    # ------------------------------------------------------------ smooth laws
    def _penetration(self, s):
        up = (s > self.upper).astype(float) if np.ndim(s) else float(s > self.upper)
        lo = (s < self.lower).astype(float) if np.ndim(s) else float(s < self.lower)
        d = np.where(up > 0, s - self.upper, 0.0) + np.where(lo > 0, s - self.lower, 0.0)
        return d, up + lo

    def smooth_force(self, s, sd, eps):
        """The piecewise-linear law itself (harmonic balance: AFT handles the switch)."""
        d, on = self._penetration(np.asarray(s, float))
        return -(self.k * d + self.c * sd * on), -self.k * on, -self.c * on

    def regularised_force(self, s, sd, t, memory, settings):
        d, on = self._penetration(np.asarray(s, float))
        return float(-(self.k * d + self.c * sd * on)), ()

    # ------------------------------------------------------------ Moreau-Jean
    def moreau(self, h, theta):
        from ...timestepping.laws import KelvinVoigtStep

        return KelvinVoigtStep(self, h, theta)
