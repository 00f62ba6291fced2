"""The elements' laws over one Moreau-Jean step (returned by ``Element.moreau(h, theta)``).

Each law answers, for its element and the current step: whether it takes part in the local
contact problem, the impulse that solves its own law given the local velocity (projected
Gauss-Seidel), its impulse bound, and what happened (stick/slip, contact closing/opening)."""
from __future__ import annotations


class StepLaw:
    """Defaults: no explicit force, no bound, not conservative, takes part every step."""

    conservative = False       # its energy is a potential (not counted as impulse work)
    bound = 0.0                # impulse bound of the step (Coulomb); 0: none
    active = True
    has_explicit = False       # a velocity-dependent force treated explicitly

    def __init__(self, element):
        self.el = element

    def explicit_force(self, u: float) -> float:
        """The explicit force at the element's velocity u (only where ``has_explicit``)."""
        return 0.0

    def start(self, u0: float, v_scale: float) -> None:
        """State at t0 (u0: the element's velocity)."""

    def begin(self, s0: float, u0: float) -> None:
        """Set up the step from the element's position and velocity at its start."""

    def project(self, u: float, D: float, p: float) -> float:
        """The impulse that satisfies the law given the local velocity u (own impulse p included,
        D the diagonal Delassus entry)."""
        raise NotImplementedError

    def retry(self, p: float) -> bool:
        """Whether the step must be solved again with a changed bound (a breakaway within it)."""
        return False

    def retry_clip(self, p: float) -> float:
        return min(max(p, -self.bound), self.bound)

    def finish(self, p: float) -> list:
        """[(rank, event kind)] of the step (rank orders the kinds of events of one step)."""
        return []


class CoulombStep(StepLaw):
    """Coulomb friction: -p in h F Sign(u - surface velocity), F the static level for an element at
    rest at the start of the step, else the kinetic level; the viscous/quadratic/cubic part of the
    slip law is explicit; a saturated static bound means breakaway (kinetic level, solved again)."""

    def __init__(self, element, h):
        super().__init__(element)
        self.h = h
        self.fk, self.fs, self.sv = element.kinetic, element.static, element.surface_velocity
        self.stick = False
        el = element
        self.has_explicit = bool(el.viscous or el.quadratic or el.cubic)

    def explicit_force(self, u):
        el = self.el
        w = u - self.sv
        return -el.viscous * w - el.quadratic * w * abs(w) - el.cubic * w * w * w

    def start(self, u0, v_scale):
        self.stick = bool(abs(u0 - self.sv) <= 1e-12 * v_scale)

    def begin(self, s0, u0):
        self.bound = self.h * (self.fs if self.stick else self.fk)

    def project(self, u, D, p):
        r = u - self.sv - D * p
        return min(max(-r / D, -self.bound), self.bound)

    def retry(self, p):
        if self.stick and abs(p) >= self.bound * (1 - 1e-12) and self.fs > self.fk:
            self.bound = self.h * self.fk
            return True
        return False

    def finish(self, p):
        new = bool(abs(p) < self.bound * (1 - 1e-9) and self.bound > 0)
        out = [] if new == self.stick else [(0, "stick" if new else "slip")]
        self.stick = new
        return out


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
