"""Tables of the nonlinear elements and forces, shared by lumped and hybrid files: ``[[friction]]``,
``[[one_sided]]``, ``[[gap]]``, ``[[impact]]``, ``[[cubic_spring]]``, ``[[force]]`` and (hybrid)
``[[distributed_friction]]``.  Each element acts on a coordinate s given by the keys of
:class:`Coordinate` (see docs/discrete.md and docs/hybrid.md for the laws)."""

from typing import Annotated, ClassVar, Literal

from pydantic import Field, model_validator

from discrete.errors import ModelError
from discrete.nonsmooth import elements as E

from ..deprecation import warn_deprecated
from .base import Fraction, NonNegative, Positive, Real, Table, rule
from .lumped import RATIO, Ends, Ratios

ELEMENT_TABLES: dict[str, type] = {}
"""{table name: schema class} of the element tables, in the order the solvers list the elements."""


def element_table(name: str):
    """Register a schema class as the model-file table ``[[name]]`` of an element: it gets a field of
    that name in lumped and hybrid files, and its ``element()`` builds the element."""
    def deco(cls):
        setattr(cls, "table_name", name)
        ELEMENT_TABLES[name] = cls
        return cls
    return deco


class Coordinate(Table):
    """Where an element acts: ``body`` (s = x of a body or driver), ``x``/``dof`` (hybrid: an FE DOF)
    or ``between`` two ends (s = r_b x_b - r_a x_a with ``ratios``); ``ratio`` scales a single
    coordinate (s = ratio x)."""

    one_coordinate: ClassVar[bool] = True

    name: Annotated[str, Field(min_length=1)] | None = None
    """Element name (unique among elements; default <table><index>)."""
    body: Annotated[str, Field(min_length=1)] | None = None
    """A body or driver name: s = its coordinate."""
    x: Real["m"] | None = None
    """Hybrid models: position of the FE node, m."""
    dof: str | None = None
    """Hybrid models: DOF name at the node (default: the primary field)."""
    between: Ends | None = None
    """Two ends: names, "ground" or (hybrid) { x = .., dof = .. }."""
    ratios: Ratios | None = None
    """[r_a, r_b] with between (default [1, 1])."""
    ratio: Real[RATIO] | None = None
    """Scale of a single coordinate (body or x), s = ratio * x (default 1)."""

    @model_validator(mode="after")
    def _where(self):
        given = [k for k in ("body", "x", "between") if getattr(self, k) is not None]
        if len(given) > 1:
            rule(given[1], getattr(self, given[1]), f"either body = .., x = .. (FE node) or between = [..], "
                                                    f"not {given[0]} and {given[1]}")
        if self.ratios is not None and self.between is None:
            rule("ratios", self.ratios, "only with between = [..] (use ratio for a single coordinate)")
        if self.ratio is not None and self.between is not None:
            rule("ratio", self.ratio, "only with body or x (use ratios = [r_a, r_b] with between)")
        if self.dof is not None and self.x is None:
            rule("dof", self.dof, "only with x = .. (an FE node)")
        return self

    def element(self, where: str, kind: str, weight=None) -> tuple[type, dict, bool]:
        """(element class, keyword arguments without name and g, whether s is negated); ``kind``: the
        kind of file (for legacy defaults), ``weight(table, where)``: (g m, m, dm/dt) of a body."""
        raise NotImplementedError

    def _require_where(self):
        if self.body is None and self.x is None and self.between is None:
            rule("body", None, "body = \"name\", x = .. (FE node) or between = [\"a\", \"b\"] (required)")


@element_table("friction")
class Friction(Coordinate):
    """``[[friction]]``: Coulomb friction with breakaway above the kinetic level and an optionally
    moving counter-surface (seed 000 (1), textbook (8.34), seed 002 (1)).  Slip force
    -sign(w) (kinetic + viscous |w| + quadratic w^2 + cubic |w|^3), w = s' - surface_velocity.

    Levels as forces (``kinetic``, ``static``) or as a friction coefficient on a normal force
    (``mu``, ``mu_static`` with ``normal``)."""

    kinetic: NonNegative["N", "N*m"] | None = None
    """Kinetic friction level (force or torque)."""
    static: NonNegative["N", "N*m"] | None = None
    """Breakaway (static) limit, >= kinetic (default: the kinetic level)."""
    mu: NonNegative["1"] | None = None
    """Friction coefficient (with normal)."""
    mu_static: NonNegative["1"] | None = None
    """Static friction coefficient, >= mu (default mu)."""
    normal: Literal["weight", "given"] | Positive["N", "N*m"] | None = None
    """Normal force for mu: "weight" (g times the current inertia of the body, seed 004 §2) or a force."""
    viscous: Real["N*s/m", "N*m*s/rad"] = 0.0
    """Velocity-proportional term a1 of the slip law."""
    quadratic: Real["N*s^2/m^2", "N*m*s^2/rad^2"] = 0.0
    """Quadratic term a2 of the slip law (seed 002 combined law)."""
    cubic: Real["N*s^3/m^3", "N*m*s^3/rad^3"] = 0.0
    """Cubic term a3 of the slip law (falling characteristic (8.48))."""
    surface_velocity: Real["m/s", "rad/s"] = 0.0
    """Velocity of the counter-surface (clutch, belt)."""
    restick: Literal["static", "kinetic"] = "static"
    """At a stop during slip: stick within the static limit ("static") or within the kinetic level,
    else reverse at once ("kinetic", seed 000)."""
    linearise: Literal["sliding", "stuck"] | None = None
    """Linear analyses (modal, forced): "sliding" (default; the constant kinetic level: no stiffness, the
    viscous term as damping) or "stuck" (the coordinate held to the counter-surface)."""

    @model_validator(mode="after")
    def _levels(self):
        self._require_where()
        by_mu = self.normal is not None and self.normal != "given"
        if by_mu:
            for k in ("kinetic", "static"):
                if getattr(self, k) is not None:
                    rule(k, getattr(self, k), "not with normal = .. (give mu and mu_static)")
            if self.mu is None:
                rule("mu", None, "the friction coefficient with normal = .. (required key missing)")
            if self.mu_static is not None and self.mu_static < self.mu:
                rule("mu_static", self.mu_static, f"a number >= mu = {self.mu!r}")
        else:
            for k in ("mu", "mu_static"):
                if getattr(self, k) is not None:
                    rule(k, getattr(self, k), "only with normal = \"weight\" or a normal force")
            if self.kinetic is None:
                rule("kinetic", None, "the kinetic friction level (force or torque) (required key missing)")
            if self.static is not None and self.static < self.kinetic:
                rule("static", self.static, f"a number >= the kinetic level {self.kinetic!r}")
        return self

    def levels(self, where: str, weight=None) -> dict:
        """Kinetic and static levels (and the variable-weight data of normal = "weight")."""
        if self.normal == "given":
            warn_deprecated(where, "normal = \"given\" is the default: omit normal (levels kinetic/static)")
        if self.normal is None or self.normal == "given":
            return dict(kinetic=self.kinetic, static=self.kinetic if self.static is None else self.static)
        mus = self.mu if self.mu_static is None else self.mu_static
        if self.normal == "weight":
            if weight is None:
                raise ModelError(where, "normal", "weight", "a normal force (a number) in this kind of model")
            w, m0, rate = weight(self, where)
            return dict(kinetic=self.mu * w, static=mus * w, mass0=m0, mass_rate=rate)
        return dict(kinetic=self.mu * self.normal, static=mus * self.normal)

    def element(self, where, kind, weight=None):
        return E.Friction, dict(self.levels(where, weight), viscous=self.viscous, quadratic=self.quadratic,
                                cubic=self.cubic, surface_velocity=self.surface_velocity, restick=self.restick), False


@element_table("one_sided")
class OneSided(Coordinate):
    """``[[one_sided]]``: one-sided spring with preload -- a tension-only strand or a
    compression-only support (seed 002 (1)-(2))."""

    k: Positive["N/m", "N*m/rad"]
    """Stiffness."""
    preload: Real["N", "N*m"] = 0.0
    """Element force magnitude at s = 0 (initial tension F0 of a strand)."""
    side: Literal["tension", "compression"] | None = None
    """Which side carries load: "tension" (engaged when stretched) or "compression"."""
    linearise: Literal["closed", "open"] | None = None
    """Linear analyses: "closed" (engaged: a spring k; a preloaded strand taut) or "open" (slack); default:
    its state at s = 0 (closed when preloaded)."""

    LEGACY_SIDE: ClassVar[dict] = {"lumped": "tension", "hybrid": "compression"}

    @model_validator(mode="after")
    def _where_given(self):
        self._require_where()
        return self

    def element(self, where, kind, weight=None):
        side = self.side
        if side is None:
            side = self.LEGACY_SIDE[kind]
            warn_deprecated(where, f"side is not given: it defaults to {side!r} in {kind} files for now; "
                            "write side = \"tension\" or side = \"compression\"")
        sgn = 1 if side == "tension" else -1
        return E.OneSided, dict(k=self.k, s_open=-sgn * self.preload / self.k, side=sgn), False


def _clearance_rules(t, what: str) -> None:
    """The bounds of a clearance table (gap, contact): ``delta`` or ``lower``/``upper``, at least one,
    ``lower <= upper``."""
    if t.delta is not None and (t.lower is not None or t.upper is not None):
        rule("delta", t.delta, "either delta (symmetric) or lower/upper")
    if t.delta is None and t.lower is None and t.upper is None:
        rule("delta", None, f"delta = .. or lower = .. / upper = .. ({what})")
    if t.lower is not None and t.upper is not None and t.lower > t.upper:
        rule("lower", t.lower, f"a number <= upper = {t.upper!r}")


@element_table("gap")
class Gap(Coordinate):
    """``[[gap]]``: clearance/backlash (11.1): no force for lower <= s <= upper, spring k beyond.
    A lone ``lower`` or ``upper`` is a stop: the spring engaged beyond that bound only.
    ``law = "arctan"``: the smooth law (11.2) of a symmetric gap."""

    k: Positive["N/m", "N*m/rad"]
    """Contact stiffness."""
    delta: NonNegative["m", "rad"] | None = None
    """Half the clearance of a symmetric gap: lower = -delta, upper = delta."""
    lower: Real["m", "rad"] | None = None
    """Lower bound of the clearance."""
    upper: Real["m", "rad"] | None = None
    """Upper bound of the clearance."""
    law: Literal["exact", "arctan"] = "exact"
    """Exact piecewise-linear law (11.1) or the smooth arctan law (11.2)."""
    L: Positive["1/m", "1/rad"] = 1e3
    """Sharpness of the arctan law (11.2)."""
    linearise: Literal["closed", "open"] | None = None
    """Linear analyses: "closed" (a spring of its contact stiffness k: the default of a clearance, a gear
    mesh in mesh) or "open" (no force); a stop (one bound) defaults to its state at s = 0."""

    @model_validator(mode="after")
    def _bounds(self):
        self._require_where()
        _clearance_rules(self, "the clearance")
        if self.stop and (self.law != "exact" or self.given("L")):
            rule("law" if self.law != "exact" else "L", self.law if self.law != "exact" else self.L,
                 "lower and upper (or delta): the arctan law (11.2) is a symmetric clearance")
        return self

    @property
    def stop(self) -> bool:
        """A lone bound: a one-sided stop."""
        return self.delta is None and (self.lower is None) != (self.upper is None)

    def element(self, where, kind, weight=None):
        if self.stop:
            side, bound = (1, self.upper) if self.upper is not None else (-1, self.lower)
            return E.OneSided, dict(k=self.k, s_open=bound, side=side, linearise=self.linearise), False
        lower, upper = (-self.delta, self.delta) if self.delta is not None else (self.lower, self.upper)
        return E.Gap, dict(k=self.k, lower=lower, upper=upper, law=self.law, L=self.L), False


@element_table("impact")
class Impact(Coordinate):
    """``[[impact]]``: rigid unilateral stop s >= stop (side "lower") or s <= stop ("upper") with
    Newton's restitution."""

    restitution: Fraction
    """Restitution coefficient e in [0, 1]: s'+ = -e s'-."""
    stop: Real["m", "rad"] = 0.0
    """Position of the stop."""
    side: Literal["lower", "upper"] = "lower"
    """"lower": s >= stop; "upper": s <= stop."""
    v_rest: Positive["m/s", "rad/s"] | None = None
    """Rebound speed below which the bouncing closes into persistent contact (default: relative 1e-9)."""
    linearise: Literal["open", "closed"] | None = None
    """Linear analyses: "open" (default: free flight) or "closed" (the coordinate held at the stop)."""

    @model_validator(mode="after")
    def _where_given(self):
        self._require_where()
        return self

    def element(self, where, kind, weight=None):
        upper = self.side == "upper"           # s <= stop  <=>  -s >= -stop
        return E.Impact, dict(s_min=-self.stop if upper else self.stop, restitution=self.restitution,
                              v_rest=self.v_rest), upper


@element_table("cubic_spring")
class CubicSpring(Coordinate):
    """``[[cubic_spring]]``: smooth cubic spring, force along s -k3 s^3 (textbook (8.20))."""

    k3: Real["N/m^3", "N*m/rad^3"]
    """Cubic stiffness (hardening for k3 > 0)."""
    linearise: Literal["linear"] | None = None
    """Linear analyses: "linear" (its linear part at s = 0: no stiffness)."""

    @model_validator(mode="after")
    def _where_given(self):
        self._require_where()
        return self

    def element(self, where, kind, weight=None):
        return E.Cubic, dict(k3=self.k3), False


class Force(Coordinate):
    """``[[force]]``: external force along s: value + amplitude sin(omega t + phase) (+ weight)."""

    value: Real["N", "N*m"] = 0.0
    """Constant part."""
    amplitude: Real["N", "N*m"] = 0.0
    """Harmonic amplitude."""
    omega: NonNegative["rad/s"] = 0.0
    """Angular frequency, rad/s."""
    phase: Real["rad"] = 0.0
    """Phase, rad."""
    gravity: bool = False
    """Add the weight -g * inertia of the body ([constants] g)."""

    @model_validator(mode="after")
    def _law(self):
        self._require_where()
        if self.amplitude != 0 and self.omega == 0:
            rule("omega", self.omega, "a number > 0 with amplitude")
        if self.gravity and self.body is None:
            rule("gravity", True, "a body = .. for gravity = true")
        return self


class DistributedFriction(Table):
    """``[[distributed_friction]]`` (hybrid models): dry friction along the member, lumped at every
    node with its tributary length (seed 003)."""

    name: Annotated[str, Field(min_length=1)] | None = None
    """Name (the nodes' elements are named <name>@x=..)."""
    dof: str | None = None
    """DOF the friction acts on (default: the primary field)."""
    from_: Real["m"] | None = Field(default=None, alias="from")
    """Start of the rough zone, m (default 0)."""
    to: Real["m"] | None = None
    """End of the rough zone, m (default: the member's length)."""
    intensity: NonNegative["N/m", "N*m/m"] | None = None
    """Kinetic friction per length (force or torque per m, e.g. f P / l of seed 003)."""
    static_intensity: NonNegative["N/m", "N*m/m"] | None = None
    """Static friction per length (default: intensity)."""
    mu: NonNegative["1"] | None = None
    """Friction coefficient on the model's own weight per length."""
    radius: Positive["m"] | None = None
    """With mu on a torsion model: radius at which the friction acts, m."""

    @model_validator(mode="after")
    def _one(self):
        if (self.intensity is None) == (self.mu is None):
            rule("intensity", self.intensity, "either intensity = .. (force or torque per length, e.g. f P / l of "
                                              "seed 003) or mu = .. (friction coefficient on the model's own weight "
                                              "per length)")
        return self


@element_table("contact")
class Contact(Coordinate):
    """``[[contact]]``: a contact with stiffness and damping switched on at closure (textbook §11.2-11.3,
    (11.4)): no force for lower <= s <= upper, beyond it F = -k d - c s' on the penetration d.  A lone
    ``lower`` or ``upper`` is a stop."""

    k: Positive["N/m", "N*m/rad"]
    """Contact stiffness."""
    c: NonNegative["N*s/m", "N*m*s/rad"] = 0.0
    """Contact damping (a dashpot acting only in contact)."""
    delta: NonNegative["m", "rad"] | None = None
    """Half the clearance of a symmetric gap: lower = -delta, upper = delta."""
    lower: Real["m", "rad"] | None = None
    """Lower bound of the clearance."""
    upper: Real["m", "rad"] | None = None
    """Upper bound of the clearance."""
    linearise: Literal["closed", "open"] | None = None
    """Linear analyses: "closed" (default: its spring k and dashpot c) or "open" (no force)."""

    @model_validator(mode="after")
    def _bounds(self):
        self._require_where()
        _clearance_rules(self, "the clearance or the stop")
        return self

    def element(self, where, kind, weight=None):
        inf = float("inf")
        lower, upper = (-self.delta, self.delta) if self.delta is not None else (
            -inf if self.lower is None else self.lower, inf if self.upper is None else self.upper)
        return E.Contact, dict(k=self.k, c=self.c, lower=lower, upper=upper), False


@element_table("motor")
class Motor(Coordinate):
    """``[[motor]]``: the motor as a model element, torque M along s (the rotor's angle) with the
    dynamic characteristic T M' + M = (1 - s'/omega0)/nu (textbook (5.54), §5.10, (3.15)): the torque
    is one more state of the event solver's exact pieces; T = 0 is the static characteristic."""

    omega0: Positive["rad/s"]
    """Ideal no-load speed omega_d0, rad/s."""
    nu: Positive["1/(N*m)"]
    """Slope nu_d of the static characteristic, 1/(N m): M = (1 - omega/omega0)/nu."""
    T: NonNegative["s"] = 0.0
    """Electromagnetic time constant T_d, s (0: the static characteristic, no torque state)."""
    torque0: Real["N*m"] = 0.0
    """Torque at t = 0 (default 0: the motor switched on at t = 0; only with T > 0), N m."""
    linearise: Literal["characteristic"] | None = None
    """Linear analyses: "characteristic" (its dynamic characteristic as a complex stiffness in the forced
    response; the undamped modes do not see it)."""

    @model_validator(mode="after")
    def _where_given(self):
        self._require_where()
        if self.torque0 != 0 and self.T == 0:
            rule("torque0", self.torque0, "0 with T = 0 (the static characteristic has no torque state)")
        return self

    def element(self, where, kind, weight=None):
        return E.Motor, dict(omega0=self.omega0, nu=self.nu, T=self.T, torque0=self.torque0), False
