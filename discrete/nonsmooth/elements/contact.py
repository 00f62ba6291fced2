"""Contact with stiffness and damping switched on at closure (textbook §11.2-11.3, (11.3)-(11.4)): a
Kelvin-Voigt gap or stop."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import ModelError
from .base import Element, Linearisation, PiecewiseAffineLaw, StepLaw


def flank_mode(s, sd, upper: float, lower: float) -> int:
    """The starting mode of a contact between two flanks: +1 beyond ``upper`` (or on it, moving out),
    -1 beyond ``lower`` (or on it, moving out), else 0 (free)."""
    if s > upper or (s == upper and sd > 0):
        return 1
    if s < lower or (s == lower and sd < 0):
        return -1
    return 0


def flank_guards(mode: int, s, upper: float, lower: float, e0) -> list:
    """Event functions of a contact between two flanks (``upper``/``lower`` scaled by ``e0``; an
    infinite flank is never reached): in contact (mode +1 / -1) the separation, else closing on
    either finite flank."""
    if mode == 1:
        return [(s - upper * e0, "leave")]
    if mode == -1:
        return [(lower * e0 - s, "leave")]
    out = []
    if math.isfinite(upper):
        out.append((upper * e0 - s, "close+"))
    if math.isfinite(lower):
        out.append((s - lower * e0, "close-"))
    return out


def flank_event(tag: str, ctx) -> None:
    """The mode after a flank event of :func:`flank_guards`, recorded as contact_open / contact_close."""
    ctx.mode = {"leave": 0, "close+": 1, "close-": -1}[tag]
    ctx.record("contact_open" if tag == "leave" else "contact_close")


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
    infinite_ok = ("lower", "upper")
    work = "contacts"
    smoothness = 1

    def __post_init__(self):
        super().__post_init__()
        where = f"[[contact]] {self.name!r}"
        if not self.k > 0:
            raise ModelError(where, "k", self.k, "a number > 0")
        if not self.c >= 0:
            raise ModelError(where, "c", self.c, "a number >= 0")
        if not self.lower <= self.upper or (math.isinf(self.lower) and math.isinf(self.upper)):
            raise ModelError(where, "clearance", [self.lower, self.upper], "lower <= upper, at least one finite")

    linear_states = ("closed", "open")

    def linearised(self, state=None):
        state = state or self.linear_state
        if state == "closed":
            return Linearisation(state, k=self.k, c=self.c, note=f"closed: its spring k = {self.k:g} and dashpot "
                                 f"c = {self.c:g}")
        return Linearisation(state, note="open: no force (free inside the clearance)")

    has_potential = True

    def _bound(self, mode):
        return self.upper if mode == 1 else self.lower

    # ------------------------------------------------------------ event-driven solver
    def initial_mode(self, s, sd, scale_v):
        return flank_mode(s, sd, self.upper, self.lower)

    def force(self, mode, s, sd, e0, t):
        if mode == 0:
            return None
        return -self.k * (s - self._bound(mode) * e0) - self.c * sd

    def guards(self, mode, s, sd, F, e0, t):
        return flank_guards(mode, s, self.upper, self.lower, e0)

    def on_event(self, tag, ctx):
        flank_event(tag, ctx)

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

    def piecewise_law(self):
        """-k (s - bound) - c s' beyond each finite bound, 0 inside (the dashpot makes it jump at a
        crossing with s' != 0)."""
        k, c = self.k, self.c
        breaks, a, b, cc = [], [], [], []
        if math.isfinite(self.lower):
            breaks.append(self.lower)
            a.append(k * self.lower), b.append(-k), cc.append(-c)
        a.append(0.0), b.append(0.0), cc.append(0.0)
        if math.isfinite(self.upper):
            if breaks and self.upper == self.lower:       # zero clearance: one break, contact on both sides
                a.pop(), b.pop(), cc.pop()
            else:
                breaks.append(self.upper)
            a.append(k * self.upper), b.append(-k), cc.append(-c)
        return PiecewiseAffineLaw(tuple(breaks), tuple(a), tuple(b), tuple(cc))

    def regularised_force(self, s, sd, t, memory, settings):
        d, on = self._penetration(np.asarray(s, float))
        return float(-(self.k * d + self.c * sd * on)), ()

    # ------------------------------------------------------------ Moreau-Jean
    def moreau(self, h, theta):
        return KelvinVoigtStep(self, h, theta)


class KelvinVoigtStep(StepLaw):
    """Spring k and dashpot c beyond a clearance: the impulse -h (k d_theta + c u_theta) at the
    theta-point, d_theta = s_theta - bound, u_theta = (1 - theta) u0 + theta u1, solved exactly
    on the branch of the predicted position (implicit: stiff and strongly damped contacts do not
    limit the step).  Its whole impulse counts as work (the spring's too): the balance closes."""

    def __init__(self, element, h, theta):
        super().__init__(element)
        self.h, self.theta = h, theta
        self.k, self.c = element.k, element.c
        self.lo, self.up = element.lower, element.upper
        self.sb = h * theta * theta
        self.contact = False

    def begin(self, s0, u0):
        th = self.theta
        self.u0 = u0
        self.sa = s0 + self.h * th * (1 - th) * u0

    def project(self, u, D, p):
        r = u - D * p
        sfree = self.sa + self.sb * r
        if sfree > self.up:
            bound = self.up
        elif sfree < self.lo:
            bound = self.lo
        else:
            return 0.0
        th, h = self.theta, self.h
        rhs = self.k * (self.sa + self.sb * r - bound) + self.c * ((1 - th) * self.u0 + th * r)
        return -h * rhs / (1.0 + h * D * (self.k * self.sb + self.c * th))

    def finish(self, p):
        new = bool(p != 0)
        out = [] if new == self.contact else [(1, "contact_close")] if new else [(2, "contact_open")]
        self.contact = new
        return out
