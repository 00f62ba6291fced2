"""Nonsmooth lumped elements acting on a relative coordinate s = g . x (x: all DOFs, drivers included).

Sign convention (all elements): ``F`` is the generalised force the element applies *along s*;
the force on the DOFs is ``g * F``.  An element on one body has ``g`` = unit vector of that body;
between bodies a and b with ratios (r_a, r_b) it acts on ``s = r_b x_b - r_a x_a`` as the springs
of :mod:`discrete.lumped` do.  Each element documents its modes (integers), its force law in each
mode, and the guards whose zero-crossings switch the mode.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ModelError


@dataclass
class Friction:
    """Coulomb friction with breakaway limit above the kinetic level (seed 000 (1); textbook (8.34)).

    Relative slip velocity ``w = s' - surface_velocity`` (moving counter-surface: clutch at omega0
    of seed 002, belt).  Modes: +1 / -1 slip, 0 stick.
    Slip force ``F = -sign(w) (a0 + a1 |w| + a2 w^2 + a3 |w|^3)``: ``a0`` the kinetic level, ``a1``
    viscous, ``a2`` the quadratic term of the combined law B1 sign v + B2 v + B3 sign(v) v^2 of
    seed 002 (a0 = B1, a1 = B2, a2 = B3); ``a3`` allows the cubic falling/rising characteristic
    of (8.48).  Stick: ``w = 0`` enforced exactly by a constraint force ``lam``; breakaway when
    ``|lam|`` reaches ``static``.  At a momentary stop during slip the body sticks if
    ``|lam| <= static`` (restick = "static") or ``|lam| <= a0`` (restick = "kinetic", seed 000:
    otherwise the velocity reverses at once).
    ``normal = "weight"``: the levels are ``mu g m(t)`` and ``mu_static g m(t)`` with m(t) the
    current inertia of ``weight_body`` (seed 004 §2).
    """

    name: str
    g: np.ndarray
    kinetic: float
    static: float | None = None
    viscous: float = 0.0
    quadratic: float = 0.0
    cubic: float = 0.0
    surface_velocity: float = 0.0
    restick: str = "static"
    mass0: float | None = None       # set for normal = "weight": m(t) = mass0 + mass_rate t
    mass_rate: float = 0.0
    kind = "friction"

    def __post_init__(self):
        where = f"[[friction]] {self.name!r}"
        if self.static is None:
            self.static = self.kinetic
        if not self.kinetic >= 0:
            raise ModelError(where, "kinetic", self.kinetic, "a number >= 0")
        if not self.static >= self.kinetic:
            raise ModelError(where, "static", self.static, f"a number >= the kinetic level {self.kinetic!r}")
        if self.restick not in ("static", "kinetic"):
            raise ModelError(where, "restick", self.restick, "'static' | 'kinetic'")

    @property
    def affine(self) -> bool:
        return self.quadratic == 0.0 and self.cubic == 0.0 and self.mass_rate == 0.0

    def scale(self, t):
        """Factor m(t)/mass0 for normal = "weight" (1 otherwise)."""
        if self.mass0 is None or self.mass_rate == 0.0:
            return 1.0
        return (self.mass0 + self.mass_rate * t) / self.mass0

    def levels(self, t) -> tuple[float, float]:
        f = self.scale(t)
        return self.kinetic * f, self.static * f

    def slip_force(self, sgn: int, w, e0, t):
        """Force along s in slip mode ``sgn`` (linear in (w, e0) when ``affine``)."""
        fk = self.levels(t)[0]
        return -sgn * fk * e0 - self.viscous * w - sgn * self.quadratic * w * w - self.cubic * w * w * np.abs(w)


@dataclass
class OneSided:
    """One-sided spring with preload: tension-only strand or compression-only support (seed 002 (1)-(2)).

    Engaged when ``side * (s - s_open) > 0`` (side = +1 tension: stretched beyond the slack
    length; side = -1 compression).  Force ``F = -k (s - s_open)`` engaged, 0 otherwise; with
    ``preload`` P (the element force magnitude at s = 0) ``s_open = -side * P / k``.
    Modes: 1 engaged, 0 open (slack).
    """

    name: str
    g: np.ndarray
    k: float
    s_open: float = 0.0
    side: int = 1
    kind = "one_sided"
    affine = True

    def __post_init__(self):
        if not self.k > 0:
            raise ModelError(f"[[one_sided]] {self.name!r}", "k", self.k, "a number > 0")

    def potential(self, s, mode):
        return 0.5 * self.k * (s - self.s_open) ** 2 * (mode == 1)


@dataclass
class Gap:
    """Clearance / backlash (textbook (11.1)): no force for lower <= s <= upper,
    ``F = -k (s - upper)`` above, ``F = -k (s - lower)`` below (symmetric: lower = -Delta,
    upper = Delta, Delta = half the gap s).  Modes: +1, 0, -1.

    ``law = "arctan"``: the smooth law (11.2) for a symmetric gap,
    ``F = -k (s - Delta sign s) (1/2 + arctan(L (|s| - Delta)/Delta)/pi)`` (no modes, no events).
    """

    name: str
    g: np.ndarray
    k: float
    lower: float
    upper: float
    law: str = "exact"
    L: float = 1e3
    kind = "gap"

    def __post_init__(self):
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
    def affine(self) -> bool:
        return self.law == "exact"

    def smooth_force(self, s):
        d = self.upper
        u = 0.5 + np.arctan(self.L * (np.abs(s) - d) / d) / np.pi
        return -self.k * (s - d * np.sign(s)) * u

    def potential(self, s, mode):
        if self.law == "arctan":
            return 0.0 * s  # not conservative-tracked: its power is counted as element work
        return 0.5 * self.k * ((s - self.upper) ** 2 * (mode == 1) + (s - self.lower) ** 2 * (mode == -1))


@dataclass
class Impact:
    """Rigid unilateral stop ``s >= s_min`` with Newton's restitution ``s'+ = -e s'-``.

    Modes: 0 free flight, 1 persistent contact (s = s_min held by a constraint force lam >= 0,
    released when lam would become negative).  A bouncing sequence is closed into persistent
    contact when the rebound velocity falls below ``v_rest`` (accumulation of impacts).
    """

    name: str
    g: np.ndarray
    s_min: float = 0.0
    restitution: float = 1.0
    v_rest: float | None = None
    kind = "impact"
    affine = True

    def __post_init__(self):
        if not 0.0 <= self.restitution <= 1.0:
            raise ModelError(f"[[impact]] {self.name!r}", "restitution", self.restitution, "a number in [0, 1]")


ELEMENT_TYPES = (Friction, OneSided, Gap, Impact)
