"""Rigid unilateral stop with Newton's restitution and accumulation of impacts."""
from __future__ import annotations

import math
from dataclasses import dataclass

from ...errors import ModelError, SolverError
from .base import Element, Linearisation, StepLaw


def restitution_damping_ratio(e: float) -> float:
    """Damping ratio of a linear spring-dashpot contact with restitution coefficient e:
    e = exp(-pi z / sqrt(1 - z^2))."""
    if e >= 1:
        return 0.0
    if e <= 0:
        return 1.0
    le = -math.log(e)
    return le / math.sqrt(math.pi ** 2 + le ** 2)


@dataclass
class Impact(Element):
    """Stop ``s >= s_min`` with Newton's restitution ``s'+ = -e s'-``.

    Modes: 0 free flight, 1 persistent contact (s = s_min held by a constraint force lam >= 0,
    released when lam would become negative).  A bouncing sequence is closed into persistent
    contact when the rebound velocity falls below ``v_rest`` (accumulation of impacts; default
    rest_tol times the largest impact speed of the element)."""

    s_min: float = 0.0
    restitution: float = 1.0
    v_rest: float | None = None

    kind = "impact"
    work = "contacts"
    smoothness = 0
    unilateral = True
    smooth_law = False

    def __post_init__(self):
        super().__post_init__()
        if not 0.0 <= self.restitution <= 1.0:
            raise ModelError(f"[[impact]] {self.name!r}", "restitution", self.restitution, "a number in [0, 1]")
        if self.v_rest is not None and not self.v_rest > 0:
            raise ModelError(f"[[impact]] {self.name!r}", "v_rest", self.v_rest, "a number > 0 (or None: rest_tol "
                             "times the largest impact speed)")

    # ------------------------------------------------------------ event-driven solver
    def initial_mode(self, s, sd, scale_v):
        return 1 if s <= self.s_min and sd <= 0 else 0

    def is_constraint(self, mode):
        return mode == 1

    def guards(self, mode, s, sd, F, e0, t):
        if mode == 0:
            return [(s - self.s_min * e0, "hit")]
        return [(F.copy(), "release")]

    def constraint_excess(self, lam, t, limit, force_tol):
        return -lam / max(abs(lam), 1e-300) if lam < -force_tol else -1.0

    def on_event(self, tag, ctx):
        if tag != "hit":
            ctx.mode = 0
            ctx.record("contact_open")
            return
        sd = ctx.velocity()
        if sd >= 0:
            return
        E0 = ctx.energy()
        ref = ctx.impact_speed(abs(sd))
        vplus = -self.restitution * sd
        vrest = self.v_rest if self.v_rest is not None else ctx.rest_tol * ref
        ctx.project_position(self.s_min)
        ctx.record("impact")
        if vplus <= vrest:
            ctx.project_velocity(0.0)
            ctx.mode = 1
            ctx.record("contact_close")
        else:
            ctx.project_velocity(vplus)
        ctx.jump += ctx.energy() - E0

    # ------------------------------------------------------------ linear analyses
    linear_states = ("open", "closed")

    def linearised(self, state=None):
        state = state or self.linear_state
        if state == "closed":
            return Linearisation(state, hold=True, note="closed: the coordinate held at the stop (persistent contact)")
        return Linearisation(state, note="open: free flight, no force")

    # ------------------------------------------------------------ smooth laws
    def regularised_force(self, s, sd, t, memory, settings):
        """Penalty spring-dashpot whose linear-contact restitution is e."""
        penalty = settings["penalty"]
        if penalty is None:
            raise SolverError(f"impact {self.name!r} needs [simulation] penalty = stiffness for the "
                              "regularised method")
        F = 0.0
        if s < self.s_min:
            m_eff = settings["effective_mass"]()
            c = 2 * restitution_damping_ratio(self.restitution) * math.sqrt(penalty * m_eff)
            F = -penalty * (s - self.s_min) - c * sd
        return F, ()

    # ------------------------------------------------------------ Moreau-Jean
    def moreau(self, h, theta):
        return UnilateralStep(self, h)


class UnilateralStep(StepLaw):
    """Rigid stop s >= s_min with Newton restitution e: for an element whose predicted position
    s0 + h/2 s0' is at or beyond the stop, p >= 0 complementary to u + e u(t0) >= 0."""

    def __init__(self, element, h):
        super().__init__(element)
        self.h = h
        self.active = False
        self.target = 0.0
        self.contact = False

    def begin(self, s0, u0):
        el = self.el
        self.active = bool(s0 + 0.5 * self.h * u0 <= el.s_min)
        self.target = -el.restitution * min(u0, 0.0) if self.active else 0.0

    def project(self, u, D, p):
        r = u - D * p - self.target
        return max(0.0, -r / D)

    def finish(self, p):
        new = bool(self.active and p > 0)
        out = [] if new == self.contact else [(1, "impact")] if new else [(2, "contact_open")]
        self.contact = new
        return out
