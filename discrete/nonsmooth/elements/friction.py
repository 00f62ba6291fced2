"""Coulomb friction with a breakaway limit above the kinetic level (seed 000 (1); textbook (8.34);
seed 002 (1)) and an optionally moving counter-surface."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import ModelError
from .base import LAW_TANH_FRICTION, Element, Linearisation, StepLaw


@dataclass
class Friction(Element):
    """Relative slip velocity ``w = s' - surface_velocity`` (clutch at omega0 of seed 002, belt).
    Modes: +1 / -1 slip, 0 stick.

    Slip force ``F = -sign(w) (a0 + a1 |w| + a2 w^2 + a3 |w|^3)``: ``a0`` the kinetic level, ``a1``
    viscous, ``a2`` the quadratic term of the combined law B1 sign v + B2 v + B3 sign(v) v^2 of
    seed 002 (a0 = B1, a1 = B2, a2 = B3); ``a3`` allows the cubic falling/rising characteristic
    of (8.48).  Stick: ``w = 0`` enforced exactly by a constraint force ``lam``; breakaway when
    ``|lam|`` reaches ``static``.  At a momentary stop during slip the body sticks if
    ``|lam| <= static`` (restick = "static") or ``|lam| <= a0`` (restick = "kinetic", seed 000:
    otherwise the velocity reverses at once).  ``mass0``/``mass_rate`` (normal = "weight"): the
    levels are scaled by the current inertia m(t)/mass0 (seed 004 §2).
    """

    kinetic: float = 0.0
    static: float | None = None
    viscous: float = 0.0
    quadratic: float = 0.0
    cubic: float = 0.0
    surface_velocity: float = 0.0
    restick: str = "static"
    mass0: float | None = None
    mass_rate: float = 0.0

    kind = "friction"
    work = "friction"
    smoothness = 0
    soft_start_tags = ("stop",)

    def __post_init__(self):
        super().__post_init__()
        where = f"[[friction]] {self.name!r}"
        if self.static is None:
            self.static = self.kinetic
        if not self.kinetic >= 0:
            raise ModelError(where, "kinetic", self.kinetic, "a number >= 0")
        if not self.static >= self.kinetic:
            raise ModelError(where, "static", self.static, f"a number >= the kinetic level {self.kinetic!r}")
        if self.restick not in ("static", "kinetic"):
            raise ModelError(where, "restick", self.restick, "'static' | 'kinetic'")

    # ------------------------------------------------------------ the law
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
        return -sgn * fk * e0 - self.viscous * w - sgn * self.quadratic * w * w - sgn * self.cubic * w * w * np.abs(w)

    # ------------------------------------------------------------ event-driven solver
    def initial_mode(self, s, sd, scale_v):
        w = sd - self.surface_velocity
        return 0 if abs(w) <= 1e-14 * max(scale_v, abs(self.surface_velocity), 1.0) else int(np.sign(w))

    def is_constraint(self, mode):
        return mode == 0

    def force(self, mode, s, sd, e0, t):
        if mode != 0:
            return self.slip_force(mode, sd - self.surface_velocity * e0, e0, t)
        return None

    def guards(self, mode, s, sd, F, e0, t):
        fk, fs = self.levels(t)
        if mode != 0:
            return [(mode * (sd - self.surface_velocity * e0), "stop")]
        return [(fs * e0 - F, "break-"), (fs * e0 + F, "break+")]

    def constraint_excess(self, lam, t, limit, force_tol):
        lim = self.levels(t)[1] if limit is None else limit
        return (abs(lam) - lim) / max(lim, abs(lam) * 1e-12, 1e-300)

    def released_mode(self, lam):
        return -int(np.sign(lam)) or 1

    def release_event(self) -> str:
        return "slip"

    def on_event(self, tag, ctx):
        if tag == "stop":
            ctx.project_velocity(self.surface_velocity)
            ctx.mode = 0
            fk, fs = self.levels(ctx.t)
            ctx.limit = fs if self.restick == "static" else fk
            ctx.record("stop")                   # becomes "stick" or "reversal" once the mode is settled
        else:
            lam = ctx.constraint_force()
            ctx.mode = -int(np.sign(lam)) or (1 if tag == "break+" else -1)
            ctx.record("slip")

    def velocity_scale(self) -> float:
        return abs(self.surface_velocity)

    # ------------------------------------------------------------ outputs and linear analyses
    outputs = ("force", "slip_velocity")

    def output_law(self, quantity):
        if quantity == "slip_velocity":                 # w = s' - surface_velocity
            return 0.0, 1.0, -self.surface_velocity
        return super().output_law(quantity)

    linear_states = ("sliding", "stuck")

    def linearised(self, state=None):
        state = state or self.linear_state
        if state == "stuck":
            return Linearisation(state, hold=True, note="stuck: the coordinate held to the counter-surface "
                                 "(its force is the constraint force)")
        return Linearisation(state, c=self.viscous, note="sliding: the constant kinetic level (no stiffness)"
                             + (f", the slope of the slip law as damping c = {self.viscous:g}" if self.viscous
                                else ", no damping"))

    # ------------------------------------------------------------ smooth laws
    def smooth_force(self, s, sd, eps):
        """Regularised ``-a0 tanh(w / eps) - a1 w - a2 w|w| - a3 w^3`` (harmonic balance); a power-law
        term whose coefficient is zero is left out (the same values for finite w, fewer array
        passes)."""
        w = sd - self.surface_velocity
        fk = self.kinetic
        th = np.tanh(w / eps)
        F = -fk * th - self.viscous * w
        dF = -fk * (1 - th ** 2) / eps - self.viscous
        if self.quadratic:
            aw = np.abs(w)
            F = F - self.quadratic * w * aw
            dF = dF - 2 * self.quadratic * aw
        if self.cubic:
            F = F - self.cubic * w * w * w
            dF = dF - 3 * self.cubic * w * w
        return F, np.zeros_like(s), dF

    def compiled_law(self, eps):
        """:meth:`smooth_force` for the compiled kernel (the same terms, zero ones left out there too)."""
        return LAW_TANH_FRICTION, (float(self.kinetic), float(self.viscous), float(self.quadratic),
                                   float(self.cubic), float(self.surface_velocity), float(eps))

    def sampled_exactly(self, s, sd, eps):
        """Saturated: the slip velocity w keeps one sign with |w| >= 20 eps all along the orbit (the
        samples, less the largest step between neighbouring samples), so
        tanh(w / eps) = +-1 in double precision and the law is the cubic polynomial -+a0 - a1 w -+ a2 w^2
        - a3 w^3 (a clutch slipping one way, seed 002)."""
        w = np.asarray(sd, float) - self.surface_velocity
        if w.size < 3:
            return False
        lo, hi = float(w.min()), float(w.max())
        # the dip between samples is <= h^2 max|w"| / 8 <= (h H / 8) h max|w'| (Bernstein) -- a fraction of
        # the largest step for N >= 8 H samples
        step = float(np.max(np.abs(np.diff(w))))
        return lo - step >= 20.0 * eps or hi + step <= -20.0 * eps

    n_memory = 1

    def regularised_force(self, s, sd, t, memory, settings):
        """tanh law with a rest memory zeta (see :mod:`discrete.nonsmooth.regularised`)."""
        w = sd - self.surface_velocity
        fk, fs = self.levels(t)
        rest = 1.0 / (1.0 + (w / settings["eps_m"]) ** 8)
        if self.restick == "kinetic":
            z = memory[0]
            dz = rest * (1.0 - z) / settings["tau"] - (1.0 - rest) * z / settings["tau_f"]
        else:
            z, dz = rest, 0.0
        F = -(fk + (fs - fk) * z) * math.tanh(w / settings["eps"]) - self.viscous * w - self.quadratic * w * abs(w) \
            - self.cubic * w * w * w
        return F, np.array([dz])

    # ------------------------------------------------------------ Moreau-Jean
    def moreau(self, h, theta):
        if self.mass0 is not None and self.mass_rate:
            raise ModelError(f"element {self.name!r}", "normal", "weight", "constant levels for the time stepper")
        return CoulombStep(self, h)


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
