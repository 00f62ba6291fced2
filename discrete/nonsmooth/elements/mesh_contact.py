"""A contact of periodically varying stiffness with a clearance: the law of a gear mesh along its line
of action (backlash, both flanks or one, mesh-stiffness variation at the tooth-pass frequency)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import ModelError
from .base import Element
from .contact import KelvinVoigtStep, flank_event, flank_guards, flank_mode
from .gap import ClearanceSpringStep


@dataclass
class MeshContact(Element):
    """No force for lower <= s <= upper; beyond it ``F = -k(t) d - c s'`` on the penetration d
    (d = s - upper above, s - lower below): the backlash function of a gear mesh (Kahraman & Singh,
    J. Sound Vib. 142 (1990) 49, with the stiffness k(t) of their 1991 paper) and, for constant k and
    c = 0, exactly the gap law (11.1) of the textbook.  A bound may be infinite (one flank: a stop);
    ``engaged = True`` means no clearance at all (a spring of varying stiffness, one mode).

    Stiffness ``k(t) = k (1 + sum_h a_h cos(h omega t) + b_h sin(h omega t))`` over ``harmonics``
    = ((h, a_h, b_h), ...) at the tooth-pass frequency ``omega`` (rad/s); it must stay positive.
    With harmonics the law depends on t explicitly: the pieces are integrated numerically (DOP853)
    with the same guards, the potential k(t) d^2 / 2 is time dependent and its explicit derivative
    k'(t) d^2 / 2 is the work category ``modulation``.  Without harmonics the pieces are exact.
    ``c``: a dashpot acting in contact only (contact work).  Modes: +1 contact above, -1 below, 0 free
    (``engaged``: 1 always)."""

    k: float = 0.0
    c: float = 0.0
    lower: float = 0.0
    upper: float = 0.0
    harmonics: tuple = ()
    omega: float = 0.0
    engaged: bool = False
    table: str = "mesh"

    @property
    def kind(self) -> str:
        """The model-file table of the connection the element belongs to ("mesh", "coupling")."""
        return self.table
    infinite_ok = ("lower", "upper")
    smoothness = 1
    work = "contacts"

    def __post_init__(self):
        super().__post_init__()
        where = f"[[{self.table}]] {self.name!r}"
        if not (math.isfinite(self.k) and self.k > 0):
            raise ModelError(where, "stiffness", self.k, "a mesh stiffness > 0 (N/m)")
        if not self.c >= 0:
            raise ModelError(where, "damping", self.c, "a number >= 0 (N s/m)")
        if not self.engaged and (not self.lower <= self.upper or (math.isinf(self.lower) and math.isinf(self.upper))):
            raise ModelError(where, "backlash", [self.lower, self.upper], "lower <= upper, at least one finite")
        harm = []
        for row in self.harmonics:
            h, a, b = row
            if isinstance(h, bool) or int(h) != h or h < 1:
                raise ModelError(where, "harmonics", h, "harmonic numbers >= 1 of the tooth-pass frequency")
            if not (math.isfinite(a) and math.isfinite(b)):
                raise ModelError(where, "harmonics", [a, b], "finite Fourier coefficients")
            harm.append((int(h), float(a), float(b)))
        self.harmonics = tuple(harm)
        if self.harmonics:
            if not (math.isfinite(self.omega) and self.omega > 0):
                raise ModelError(where, "omega", self.omega, "a tooth-pass frequency > 0 (rad/s) with a "
                                 "stiffness variation")
            if self.variation_bound() >= 1.0:
                raise ModelError(where, "variation", [list(r) for r in self.harmonics],
                                 "Fourier coefficients with sum |a_h| + |b_h| < 1 (the stiffness stays positive)")

    # ------------------------------------------------------------ the law
    def variation_bound(self) -> float:
        """An upper bound of |k(t)/k - 1|."""
        return float(sum(math.hypot(a, b) for _, a, b in self.harmonics))

    def stiffness_at(self, t):
        """k(t) (N/m), t scalar or array."""
        t = np.asarray(t, dtype=float)
        v = np.ones_like(t)
        for h, a, b in self.harmonics:
            v = v + a * np.cos(h * self.omega * t) + b * np.sin(h * self.omega * t)
        return self.k * v

    def stiffness_rate(self, t):
        """dk/dt (N/(m s))."""
        t = np.asarray(t, dtype=float)
        v = np.zeros_like(t)
        for h, a, b in self.harmonics:
            w = h * self.omega
            v = v - a * w * np.sin(w * t) + b * w * np.cos(w * t)
        return self.k * v

    def _bound(self, mode):
        return 0.0 if self.engaged else (self.upper if mode == 1 else self.lower)

    @property
    def time_dependent(self) -> bool:
        return bool(self.harmonics)

    @property
    def affine(self) -> bool:
        return not self.harmonics

    has_potential = True

    # ------------------------------------------------------------ event-driven solver
    def initial_mode(self, s, sd, scale_v):
        return 1 if self.engaged else flank_mode(s, sd, self.upper, self.lower)

    def force(self, mode, s, sd, e0, t):
        if mode == 0:
            return None
        k = self.stiffness_at(t) if self.harmonics else self.k
        F = -k * (s - self._bound(mode) * e0)
        return F - self.c * sd if self.c else F

    def guards(self, mode, s, sd, F, e0, t):
        return [] if self.engaged else flank_guards(mode, s, self.upper, self.lower, e0)

    def on_event(self, tag, ctx):
        flank_event(tag, ctx)

    def potential(self, s, mode):
        return self.potential_at(s, mode, 0.0)

    def potential_at(self, s, mode, t):
        if mode == 0:
            return 0.0 * s
        k = self.stiffness_at(t) if self.harmonics else self.k
        return 0.5 * k * (s - self._bound(mode)) ** 2

    def explicit_power(self, s, mode, t):
        if mode == 0 or not self.harmonics:
            return 0.0 * s
        return 0.5 * self.stiffness_rate(t) * (s - self._bound(mode)) ** 2

    def split_force(self, mode, sd, F):
        if mode == 0:
            return None, None
        damper = -self.c * sd
        return F - damper, damper

    def stiffness(self) -> float:
        return self.k * (1.0 + self.variation_bound())

    def frequency(self) -> float:
        return max((h for h, _, _ in self.harmonics), default=0) * self.omega

    # ------------------------------------------------------------ smooth laws
    def _penetration(self, s):
        if self.engaged:
            return s, np.ones_like(s)
        up = (s > self.upper).astype(float)
        lo = (s < self.lower).astype(float)
        d = np.where(up > 0, s - self.upper, 0.0) + np.where(lo > 0, s - self.lower, 0.0)
        return d, up + lo

    @property
    def smooth_law(self) -> bool:
        return not self.harmonics

    def smooth_force(self, s, sd, eps):
        """The piecewise-linear law itself (time-invariant stiffness only)."""
        if self.harmonics:
            raise ModelError(f"[[{self.table}]] {self.name!r}", "variation", "a time-dependent mesh stiffness",
                             "the time simulation or shooting (harmonic balance needs time-invariant laws; the "
                             "stability of the mesh-stiffness variation is drivefem parametric)")
        s = np.asarray(s, float)
        d, on = self._penetration(s)
        return -(self.k * d + self.c * np.asarray(sd, float) * on), -self.k * on, -self.c * on

    def regularised_force(self, s, sd, t, memory, settings):
        d, on = self._penetration(np.asarray(s, float))
        k = float(self.stiffness_at(t)) if self.harmonics else self.k
        return float(-(k * d + self.c * sd * on)), ()

    # ------------------------------------------------------------ Moreau-Jean
    def clearance(self) -> tuple[float, float]:
        return (-math.inf, math.inf) if self.engaged else (self.lower, self.upper)

    def moreau(self, h, theta):
        if self.harmonics or self.engaged:
            raise ModelError(f"element {self.name!r}", "variation" if self.harmonics else "backlash",
                             "a varying or clearance-free mesh", "method = 'event' (the Moreau-Jean law covers "
                             "a constant-stiffness mesh with backlash)")
        return KelvinVoigtStep(self, h, theta) if self.c else ClearanceSpringStep(self, h, theta)
