"""One-sided spring with preload: a tension-only strand or a compression-only support (seed 002
(1)-(2))."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...errors import ModelError
from .base import Element, Linearisation, PiecewiseAffineLaw
from .gap import ClearanceSpringStep


@dataclass
class OneSided(Element):
    """Engaged when ``side * (s - s_open) > 0`` (side = +1 tension: stretched beyond the slack
    length; side = -1 compression).  Force ``F = -k (s - s_open)`` engaged, 0 otherwise; with
    ``preload`` P (the element force magnitude at s = 0) ``s_open = -side * P / k``.
    Modes: 1 engaged, 0 open (slack)."""

    k: float = 0.0
    s_open: float = 0.0
    side: int = 1

    kind = "one_sided"
    work = "conservative"
    smoothness = 1

    def __post_init__(self):
        super().__post_init__()
        if not self.k > 0:
            raise ModelError(f"[[one_sided]] {self.name!r}", "k", self.k, "a number > 0")
        if isinstance(self.side, bool) or self.side not in (1, -1):
            raise ModelError(f"[[one_sided]] {self.name!r}", "side", self.side, "+1 (tension) | -1 (compression)")

    # ------------------------------------------------------------ event-driven solver
    def initial_mode(self, s, sd, scale_v):
        d = self.side * (s - self.s_open)
        return 1 if d > 0 or (d == 0 and self.side * sd > 0) else 0

    def force(self, mode, s, sd, e0, t):
        return -self.k * (s - self.s_open * e0) if mode == 1 else None

    def guards(self, mode, s, sd, F, e0, t):
        d = self.side * (s - self.s_open * e0)
        return [(d, "open")] if mode == 1 else [(-d, "close")]

    def on_event(self, tag, ctx):
        ctx.mode = 0 if tag == "open" else 1
        ctx.record("contact_open" if tag == "open" else "contact_close")

    def potential(self, s, mode):
        return 0.5 * self.k * (s - self.s_open) ** 2 * (mode == 1)

    def stiffness(self) -> float:
        return self.k

    # ------------------------------------------------------------ linear analyses
    linear_states = ("closed", "open")

    def default_linear_state(self) -> str:
        """Its state at s = 0: engaged ("closed", a preloaded strand taut) when side (0 - s_open) > 0."""
        return "closed" if self.side * (0.0 - self.s_open) > 0 else "open"

    def linearised(self, state=None):
        state = state or self.linear_state
        what = "taut" if self.side == 1 else "in contact"
        if state == "closed":
            return Linearisation(state, k=self.k, note=f"closed ({what}): a spring of its stiffness k = {self.k:g}")
        return Linearisation(state, note="open (slack)" if self.side == 1 else "open: no force")

    # ------------------------------------------------------------ smooth laws
    def smooth_force(self, s, sd, eps):
        """The piecewise-linear (continuous) law itself: AFT handles the kink."""
        d = s - self.s_open
        on = (self.side * d > 0).astype(float)
        return -self.k * d * on, -self.k * on, np.zeros_like(s)

    def piecewise_law(self):
        """-k (s - s_open) on the engaged side of s_open, 0 on the other."""
        k, s0 = self.k, self.s_open
        on = (k * s0, -k, 0.0)
        off = (0.0, 0.0, 0.0)
        lo, hi = (off, on) if self.side == 1 else (on, off)
        return PiecewiseAffineLaw((s0,), (lo[0], hi[0]), (lo[1], hi[1]), (lo[2], hi[2]))

    def regularised_force(self, s, sd, t, memory, settings):
        F = 0.0
        if self.side * (s - self.s_open) > 0:
            F = -self.k * (s - self.s_open)
        return F, ()

    # ------------------------------------------------------------ Moreau-Jean
    def clearance(self) -> tuple[float, float]:
        """(lower, upper): the spring acts below lower or above upper."""
        inf = float("inf")
        return (self.s_open if self.side == -1 else -inf), (self.s_open if self.side == 1 else inf)

    def moreau(self, h, theta):
        return ClearanceSpringStep(self, h, theta)
