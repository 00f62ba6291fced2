"""The element protocol: what every nonlinear element of a drive provides to the solvers.

An element acts on the coordinate ``s = g . x`` (x: every DOF, drivers included) and applies the
force ``F`` along s (``g F`` on the DOFs).  It owns its law in every form a solver needs:

* the event-driven solver (exact pieces): its modes (small integers), the initial mode from (s, s'),
  which modes are constraints (stick, persistent contact: a Lagrange row with force ``lam``), the
  force along s in a free mode (affine in (s, s', e0) in an affine element, e0 the constant basis
  function of the exogenous state), the guard functions of the current mode (admissible while >= 0,
  an event at a zero crossing) and the event rule that picks the next mode and projects the state;
* the energy balance: the potential energy (conservative elements) or the work category of its
  power ("friction", "contacts", "elements");
* the smooth (regularised) law of the regularised integrator and of harmonic balance (AFT);
* the Moreau-Jean time stepper: the impulse of one step given the local free velocity;
* optionally (hooks with defaults): internal states of its own (``n_states``, the motor torque of
  (5.54): part of the exact state z = [q, v, w, e], with an affine rate law
  :meth:`Element.state_rates` and the force :meth:`Element.state_force`), and an explicit time
  dependence (``time_dependent``: a modulated spring; its pieces are integrated numerically, its
  potential :meth:`Element.potential_at` depends on t and the explicit derivative dV/dt at fixed s,
  :meth:`Element.explicit_power`, is the work of the category ``time_work``).

The solvers loop over the elements and call these methods; none of them looks at the element's
type.  A smooth nonlinear spring is an element with a smooth force only (``event_driven`` False
and no modes).  Arrays: s, sd, e0 have one value per evaluation point (the solvers evaluate many
states at once).
"""
from __future__ import annotations

from dataclasses import dataclass, field, fields

import numpy as np

from ... import checks
from ...errors import ModelError

#: the power categories of the energy balance (keys of Problem.power_parts)
WORK = ("conservative", "friction", "contacts", "elements")


#: codes of :meth:`Element.compiled_law` (the compiled harmonic-balance kernel's laws)
LAW_CUBIC = 1              # F = -k3 s^3
LAW_TANH_FRICTION = 2      # F = -a0 tanh(w / eps) - a1 w - a2 w |w| - a3 w^3, w = s' - v0


@dataclass(frozen=True)
class Linearisation:
    """What a linear analysis (modal, forced, Campbell) puts in place of a nonsmooth element: a
    stiffness ``k`` and a viscous coefficient ``c`` along s, or (``hold``) the coordinate s held by a
    constraint (stick, a closed rigid stop); ``Z``: a frequency-dependent complex stiffness
    ``Z(omega)`` (forced response only; None: ``k + i omega c``).  ``note`` says it in words (printed
    and recorded in the JSON of every linear analysis)."""

    state: str
    k: float = 0.0
    c: float = 0.0
    hold: bool = False
    note: str = ""
    Z: object = None

    def dynamic_stiffness(self, omega):
        """Complex stiffness along s at the angular frequency ``omega``: the force is ``-Z s``."""
        return self.Z(omega) if self.Z is not None else self.k + 1j * np.asarray(omega) * self.c


@dataclass
class Element:
    """Base of the nonlinear elements (see the module docstring for the protocol)."""

    name: str
    g: np.ndarray
    linearise: str | None = field(default=None, kw_only=True)
    """The state a linear analysis puts the element in (one of ``linear_states``; None: the element's
    default, :meth:`default_linear_state`)."""

    kind = "element"              # the model-file table of the element
    work = "elements"             # power category ("conservative": counted through its potential)
    event_driven = True           # has modes and events (False: a smooth law only)
    smoothness = 2                # 0: discontinuous law (friction), 1: kinked (contact), 2: smooth
    unilateral = False            # a constraint whose force must stay >= 0 (persistent contact)
    infinite_ok = ()              # float parameters that may be +-inf (a lone bound of a clearance)

    def __post_init__(self):
        """Every float parameter of an element is a real, finite number (NaN never; +-inf only for the
        names in ``infinite_ok``); an element's own rules follow in its ``__post_init__`` after this."""
        if not isinstance(self.name, str):
            raise ModelError(f"[[{self.kind}]]", "name", self.name, "a string")
        where = f"[[{self.kind}]] {self.name!r}"
        if self.linearise is not None and self.linearise not in self.linear_states:
            raise ModelError(where, "linearise", self.linearise, " | ".join(map(repr, self.linear_states)))
        for f in fields(self):
            if f.type is float or str(f.type) in ("float", "float | None", "typing.Optional[float]"):
                v = getattr(self, f.name)
                if v is not None:
                    setattr(self, f.name, checks.number(where, f.name, v, "a finite number" if f.name not in
                                                        self.infinite_ok else "a number (or +-inf)",
                                                        allow_inf=f.name in self.infinite_ok))

    # ------------------------------------------------------------ event-driven solver
    @property
    def affine(self) -> bool:
        """The force is affine in (s, s', e0) in every mode (exact pieces propagate by expm)."""
        return True

    def initial_mode(self, s: float, sd: float, scale_v: float) -> int:
        """The mode of a state (s, s') at the start (``scale_v``: the state's velocity scale)."""
        return 0

    def is_constraint(self, mode: int) -> bool:
        """Whether ``mode`` holds s' (or s) by a constraint force (a Lagrange row)."""
        return False

    def force(self, mode: int, s, sd, e0, t):
        """Force along s in a free mode (None: zero)."""
        return None

    def guards(self, mode: int, s, sd, F, e0, t) -> list:
        """[(guard values, tag)]: admissible while >= 0; an event when one crosses zero."""
        return []

    def constraint_excess(self, lam: float, t: float, limit, force_tol: float) -> float:
        """How far the constraint force ``lam`` lies outside its admissible set (> 0: release)."""
        return -1.0

    def released_mode(self, lam: float) -> int:
        """The mode after releasing the constraint with force ``lam``."""
        return 0

    def release_event(self) -> str:
        """The event kind recorded when the element leaves a constraint without its own event."""
        return "contact_open"

    def on_event(self, tag: str, ctx) -> None:
        """Apply the element's rule for the guard ``tag`` at an event (through ``ctx``)."""

    def potential(self, s, mode):
        """Potential energy (conservative elements; elements with ``has_potential``)."""
        return 0.0 * s

    @property
    def has_potential(self) -> bool:
        """The element stores energy (its potential is part of the mechanical energy)."""
        return self.work == "conservative"

    def split_force(self, mode, sd, F):
        """(conservative part, dissipative part) of the force F along s for the energy balance: the
        first is -dV/ds of the potential, the second does the work of the category ``work`` (None:
        no such part)."""
        return (F, None) if self.work == "conservative" else (None, F)

    def stiffness(self) -> float:
        """The largest stiffness the element adds to s (for the time scale of the model)."""
        return 0.0

    def velocity_scale(self) -> float:
        """A velocity scale of the element's own (a moving counter-surface)."""
        return 0.0

    soft_start_tags = ()          # guards that, starting on their boundary, fire only once clearly crossed

    # ------------------------------------------------------------ outputs (discrete.loads)
    outputs = ("deflection", "force")
    """The element's default outputs (docs/outputs.md): its deflection s and its force F along s."""

    def output_law(self, quantity: str) -> tuple[float, float, float]:
        """A motion output as ``(a, b, c)``: ``quantity = a s + b s' + c`` (``deflection``: s,
        ``velocity``: s')."""
        if quantity in ("deflection", "twist", "displacement"):
            return 1.0, 0.0, 0.0
        if quantity in ("velocity", "slip_velocity"):
            return 0.0, 1.0, 0.0
        raise ModelError(f"[[{self.kind}]] {self.name!r}", "quantity", quantity,
                         "deflection | velocity (or a force: force, torque, moment)")

    # ------------------------------------------------------------ linear analyses
    linear_states = ("linear",)
    """The words of the element's ``linearise`` key (docs/outputs.md)."""

    def default_linear_state(self) -> str:
        """The state of :meth:`linearised` when ``linearise`` is not given."""
        return self.linear_states[0]

    @property
    def linear_state(self) -> str:
        return self.linearise if self.linearise is not None else self.default_linear_state()

    def linearised(self, state: str | None = None) -> Linearisation:
        """The element in a linear analysis: by default no stiffness, no damping (a smooth law's
        linear part at s = 0 is its own affair: elements override this)."""
        return Linearisation(state or self.linear_state, note="no stiffness, no damping")

    # ------------------------------------------------------------ optional: internal states
    n_states = 0
    """Internal states of the element in the exact state z = [q, v, w, e] (the motor torque)."""

    def initial_states(self) -> list:
        """Values of the internal states at the start."""
        return [0.0] * self.n_states

    def state_force(self, mode: int, s, sd, w, e0, t):
        """Force along s of an element with internal states ``w`` ((n_states, m) array)."""
        return self.force(mode, s, sd, e0, t)

    def state_rates(self, mode: int, s, sd, w, e0, t):
        """w' ((n_states, m)); affine in (s, s', w, e0) for an affine element."""
        return np.zeros((self.n_states, np.size(s)))

    def state_scale(self) -> float:
        """A magnitude of the internal states (absolute tolerances of numeric pieces)."""
        return 1.0

    # ------------------------------------------------------------ optional: explicit time dependence
    time_dependent = False
    """The law depends on t explicitly (not through the exogenous state): numeric pieces."""
    time_work = "modulation"
    """Work category of the explicit time derivative of the potential."""

    def potential_at(self, s, mode, t):
        """Potential energy at time t (t may be an array, one value per column)."""
        return self.potential(s, mode)

    def explicit_power(self, s, mode, t):
        """dV/dt at fixed s of a time-dependent potential (the work the pulsation does)."""
        return 0.0 * s

    def frequency(self) -> float:
        """The highest frequency of the element's own time dependence (step limits), rad/s."""
        return 0.0

    def rate(self, mass: float) -> float:
        """The fastest rate (1/s) of the element's own dynamics acting on a coordinate of effective inertia
        ``mass`` (a damping b: b / mass; an internal state's time constant T: 1 / T), for the step budget."""
        return 0.0

    # ------------------------------------------------------------ smooth laws
    def smooth_force(self, s, sd, eps: float):
        """(F, dF/ds, dF/ds') of the smooth or regularised law (harmonic balance)."""
        raise ModelError(f"element {self.name!r}", "kind", self.kind,
                         "an element with a smooth force law for harmonic balance (use shooting)")

    smooth_law = True
    """Whether :meth:`smooth_force` exists (harmonic balance can use the element)."""

    def sampled_exactly(self, s, sd, eps: float) -> bool:
        """Whether the smooth law, on one orbit sampled at s, s' (equidistant, one period), is a polynomial
        of degree <= 3 in (s, s') between and at the samples -- then harmonic balance's AFT on 4 H + 2 or
        more samples projects it exactly and the dense grid of a rough law is not needed (a smooth law:
        True; a discontinuous or kinked one: False unless it says otherwise)."""
        return self.smoothness == 2

    def piecewise_law(self):
        """The smooth law as a piecewise-affine function of (s, s') with breaks in s
        (:class:`PiecewiseAffineLaw`: ``F = a_p + b_p s + c_p s'`` between the
        breaks), which harmonic balance integrates exactly over the crossings; None (default): the law is
        sampled (AFT)."""
        return None

    def compiled_law(self, eps: float):
        """The smooth law as the compiled harmonic-balance kernel evaluates it (discrete/steady/hb_kernel.py):
        ``(code, parameters)`` with code ``LAW_CUBIC`` (k3) or ``LAW_TANH_FRICTION`` (a0, a1, a2, a3, the
        surface velocity, eps), or None (default): the kernel then takes the law only through
        :meth:`piecewise_law` (integrated exactly), and a model with any other law is evaluated by numpy."""
        return None

    n_memory = 0
    """Internal states of the regularised law (friction's rest memory)."""

    def regularised_force(self, s, sd, t, memory, settings) -> tuple:
        """(F, d memory/dt) of the regularised integrator's law; ``settings``: eps, eps_m, tau, tau_f,
        penalty and the effective mass of s (a function)."""
        F, _, _ = self.smooth_force(np.asarray(s, float), np.asarray(sd, float), settings["eps"])
        return float(F), np.zeros(0)

    # ------------------------------------------------------------ Moreau-Jean time stepping
    def moreau(self, h: float, theta: float):
        """The element's law of one Moreau-Jean step (:class:`discrete.timestepping.moreau.StepLaw`),
        or an error naming the element if it has none."""
        raise ModelError(f"element {self.name!r}", "kind", self.kind, "an element with a Moreau-Jean law "
                         "(use method = 'event')")


# ---------------------------------------------------------------- Moreau-Jean step laws
class StepLaw:
    """An element's law over one Moreau-Jean step (returned by ``Element.moreau(h, theta)``): whether
    it takes part in the local contact problem, the impulse that solves its own law given the local
    velocity (projected Gauss-Seidel), its impulse bound, and what happened.  Defaults: no explicit force, no bound, not conservative, takes part every step."""

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


@dataclass(frozen=True)
class PiecewiseAffineLaw:
    """``F = a[p] + b[p] s + c[p] s'`` for ``breaks[p-1] < s < breaks[p]`` (breaks increasing, finite;
    len(a) = len(b) = len(c) = len(breaks) + 1)."""

    breaks: tuple
    a: tuple
    b: tuple
    c: tuple

    def __post_init__(self):
        k = len(self.breaks)
        if not (len(self.a) == len(self.b) == len(self.c) == k + 1):
            raise ValueError("a piecewise-affine law needs one (a, b, c) per piece (breaks + 1)")
        if k and not np.all(np.diff(self.breaks) > 0):
            raise ValueError("the breaks of a piecewise-affine law must increase strictly")

    def piece(self, s):
        return np.searchsorted(np.asarray(self.breaks, float), s, side="right")

    def force(self, s, sd):
        p = self.piece(s)
        a, b, c = (np.asarray(x, float)[p] for x in (self.a, self.b, self.c))
        return a + b * s + c * sd
