"""Tables of the lumped part of a model file: ``[[body]]``, ``[[driver]]``, ``[[spring]]``,
``[[damper]]`` and ``[[gear]]`` -- the same tables in lumped and hybrid files (textbook §4.4-4.9)."""

import math
from typing import Annotated, ClassVar, Literal, Union

from pydantic import Field, model_validator

from .base import Fraction, NonNegative, Number, Positive, Real, Table, rule


class NodeEnd(Table):
    """An FE node as one end of a spring, damper or element (hybrid models): ``{ x = .., dof = .. }``."""

    x: Real["m"]
    """Node position along the shaft, m."""
    dof: str | None = None
    """DOF name at the node (theta, u, w, w_x, phi; default: the primary field)."""


End = Union[Annotated[str, Field(min_length=1)], NodeEnd]
"""A body or driver name, "ground", or (hybrid models) an FE node { x = .., dof = .. }."""
Ends = Annotated[list[End], Field(min_length=2, max_length=2)]
RATIO = ("1", "m/rad", "rad/m")
"""Units of a transmission ratio: dimensionless, or a radius (m/rad: a belt or rack on a rotating body),
or its inverse."""
Ratios = Annotated[list[Real[RATIO]], Field(min_length=2, max_length=2)]


class Body(Table):
    """``[[body]]``: a lumped body with one generalised coordinate x (displacement or angle)."""

    one_coordinate: ClassVar[bool] = True

    name: Annotated[str, Field(min_length=1)]
    """Unique name (not "ground")."""
    inertia: Positive["kg", "kg*m^2"]
    """Mass (kg) or moment of inertia (kg m^2) of the coordinate."""
    inertia_rate: Real["kg/s", "kg*m^2/s"] = 0.0
    """d(inertia)/dt: variable mass m0 + delta t (seed 004 (1), Newton form), kg/s."""
    reactive: Fraction = 0.0
    """Reactive coefficient epsilon of seed 004 (reactive damping epsilon * inertia_rate), in [0, 1]: 0 a mass
    change at zero relative velocity, 1 the momentum form (m x')' = F."""
    x0: Real["m", "rad"] = 0.0
    """Initial displacement."""
    v0: Real["m/s", "rad/s"] = 0.0
    """Initial velocity."""

    @model_validator(mode="after")
    def _name(self):
        if self.name == "ground":
            rule("name", self.name, "a non-empty name other than 'ground'")
        return self


CAM_LAWS = ("cycloidal", "harmonic", "polynomial345", "constant_acceleration", "constant_velocity")
"""The standard cam laws of :mod:`discrete.motion.cam_laws` (textbook §2.5, §6.2)."""


class Programme(Table):
    """``programme = {..}`` of a ``[[driver]]``: a programme (cam) motion added to the driver's law
    (textbook §2.5, §5.8-5.9, §6.1-6.2), integrated exactly by the event solver with events at its
    knots.  The law is given in the cam angle phi = cam_speed (t - start): a standard cam cycle
    (dwell-rise-dwell-return of height ``stroke``, ``law`` = cycloidal | harmonic | polynomial345 |
    constant_acceleration | constant_velocity) or ``law = "table"``: a C2 cubic spline through
    (``phi``, ``x``).  Time simulations of lumped models (method "event" or "regularised"); the
    linear analyses see the driver's constant/harmonic law only."""

    one_coordinate: ClassVar[bool] = True

    law: Literal["cycloidal", "harmonic", "polynomial345", "constant_acceleration", "constant_velocity", "table"]
    """Law of the rise (and of the return unless return_law): a standard cam law or "table"."""
    cam_speed: Positive["rad/s"]
    """Angular speed of the cam omega0, rad/s: phi = cam_speed (t - start) ((2.13): x' = omega0 Pi')."""
    start: Real["s"] = 0.0
    """Time at which the cycle starts (phi = 0; a table: its first angle), s; before it a periodic law
    is its periodic continuation (a non-periodic table must start at or before t = 0 and cover t_end)."""
    stroke: Real["m", "rad"] | None = None
    """Standard laws: the rise height h (displacement or angle of the driven coordinate)."""
    rise: Positive["rad"] | None = None
    """Standard laws: cam angle of the rise, rad."""
    top_dwell: NonNegative["rad"] = 0.0
    """Standard laws: cam angle of the dwell at the top, rad."""
    return_: Positive["rad"] | None = Field(default=None, alias="return")
    """Standard laws: cam angle of the return, rad."""
    return_law: Literal["cycloidal", "harmonic", "polynomial345", "constant_acceleration",
                        "constant_velocity"] | None = None
    """Standard laws: law of the return (default: law)."""
    cycle: Positive["rad"] = 2 * math.pi
    """Standard laws: cam angle of one cycle, rad (the rest after the return is a dwell at 0)."""
    phi: list[Real["rad"]] | None = None
    """law = "table": cam angles, rad (at least 3, strictly increasing)."""
    x: list[Real["m", "rad"]] | None = None
    """law = "table": the displacements at phi."""
    periodic: bool = True
    """law = "table": the table repeats with period phi[-1] - phi[0] (needs x[0] == x[-1])."""

    @model_validator(mode="after")
    def _keys(self):
        std = ("stroke", "rise", "return_", "top_dwell", "return_law", "cycle")
        if self.law == "table":
            for k in std:
                if self.given(k) or (k == "return_" and self.return_ is not None):
                    rule(k.rstrip("_"), getattr(self, k), 'only with a standard law (law = "table" takes phi and x)')
            if self.phi is None or self.x is None:
                rule("phi" if self.phi is None else "x", None, 'the table phi = [..], x = [..] with law = "table"')
            if len(self.phi) < 3 or any(b <= a for a, b in zip(self.phi, self.phi[1:])):
                rule("phi", self.phi, "at least 3 strictly increasing cam angles (rad)")
            if len(self.x) != len(self.phi):
                rule("x", self.x, f"{len(self.phi)} values (one per phi)")
            if self.periodic and abs(self.x[0] - self.x[-1]) > 1e-12 * max(1.0, max(map(abs, self.x))):
                rule("x", [self.x[0], self.x[-1]], "x[0] == x[-1] for a periodic table (or periodic = false)")
        else:
            for k in ("phi", "x"):
                if getattr(self, k) is not None:
                    rule(k, getattr(self, k), 'only with law = "table"')
            if self.given("periodic"):
                rule("periodic", self.periodic, 'only with law = "table" (a cam cycle is periodic)')
            if self.stroke is None or self.stroke == 0:
                rule("stroke", self.stroke, "the rise height, a non-zero number (required with a standard law)")
            if self.rise is None or self.return_ is None:
                k = "rise" if self.rise is None else "return"
                rule(k, None, f"the cam angle of the {k} in rad (required with a standard law)")
            total = self.rise + self.top_dwell + self.return_
            if total > self.cycle * (1 + 1e-12):
                rule("cycle", self.cycle, f"at least rise + top_dwell + return = {total!r} rad")
        return self


class Driver(Table):
    """``[[driver]]``: prescribed motion x(t) = offset + velocity t + amplitude sin(omega t + phase)
    (+ a programme law, ``programme = {..}``).

    Lumped models: a named coordinate (``name``) with an optional inertia; hybrid models: an FE DOF
    (``x``, ``dof``)."""

    one_coordinate: ClassVar[bool] = True

    name: Annotated[str, Field(min_length=1)] | None = None
    """Name of the driven coordinate (lumped models: required; a body name for springs and elements)."""
    x: Real["m"] | None = None
    """Hybrid models: position of the driven FE node, m."""
    dof: str | None = None
    """Hybrid models: driven DOF at the node (default: the primary field)."""
    offset: Real["m", "rad"] = 0.0
    """Constant part of the motion."""
    velocity: Real["m/s", "rad/s"] = 0.0
    """Constant velocity (x = velocity t), m/s or rad/s."""
    amplitude: Real["m", "rad"] = 0.0
    """Harmonic amplitude."""
    omega: NonNegative["rad/s"] = 0.0
    """Angular frequency of the harmonic part, rad/s."""
    phase: Real["rad"] = 0.0
    """Phase of the harmonic part, rad."""
    inertia: NonNegative["kg", "kg*m^2"] = 0.0
    """Lumped models: inertia of the driven coordinate (enters the reactions only)."""
    programme: Programme | None = None
    """A programme (cam) law added to the motion: { law, cam_speed, stroke, rise, top_dwell, return, .. }
    (time simulations of lumped models)."""

    @model_validator(mode="after")
    def _law(self):
        if self.amplitude != 0 and self.omega == 0:
            rule("omega", self.omega, "a number > 0 with amplitude")
        if self.name == "ground":
            rule("name", self.name, "a non-empty name other than 'ground'")
        return self


class Modulation(Table):
    """``modulation = {depth, omega, phase}`` of a ``[[spring]]``: the stiffness pulsates as
    k (1 - depth sin(omega t + phase)) (textbook (7.1), c(t) = c0 - dc sin(Omega t)), integrated by
    the event solver (time simulations of lumped models; the linear analyses use the constant k, the
    stability chart is [analysis] type = "parametric")."""

    depth: Number(ge=0, lt=1)["1"]
    """Relative depth eps = dc/c0 of the pulsation, 0 <= depth < 1 (the stiffness stays positive)."""
    omega: Positive["rad/s"]
    """Angular frequency Omega of the pulsation, rad/s."""
    phase: Real["rad"] = 0.0
    """Phase of the pulsation, rad (pi: k (1 + depth sin omega t))."""


class Spring(Table):
    """``[[spring]]``: a linear spring (and parallel dashpot) acting on s = r_b x_b - r_a x_a."""

    one_coordinate: ClassVar[bool] = True

    name: Annotated[str, Field(min_length=1)] | None = None
    """Name in the outputs (default: spring[<index>] <a>-<b>, e.g. spring[2] motor-pinion)."""
    between: Ends
    """The two ends: body/driver names, "ground", or (hybrid) FE nodes { x = .., dof = .. }."""
    ratios: Ratios = [1.0, 1.0]
    """[r_a, r_b]: transmission ratios of the two ends (radii of a belt, ...)."""
    k: NonNegative["N/m", "N*m/rad"] = 0.0
    """Stiffness, N/m or N m/rad."""
    c: NonNegative["N*s/m", "N*m*s/rad"] = 0.0
    """Viscous coefficient of a parallel dashpot, N s/m or N m s/rad."""
    psi: NonNegative["1"] = 0.0
    """Dissipation coefficient of the spring (hysteretic damping in harmonic analysis)."""
    modulation: Modulation | None = None
    """Periodically varying stiffness k (1 - depth sin(omega t + phase)): { depth, omega, phase }."""

    @model_validator(mode="after")
    def _something(self):
        if not (self.given("k") or self.given("c")):
            rule("k", None, "the stiffness k (and/or a dashpot c) (required key missing)")
        if self.modulation is not None and not self.k > 0:
            rule("modulation", self.modulation.model_dump(), "a stiffness k > 0 to modulate")
        return self


class Damper(Table):
    """``[[damper]]``: a viscous damper acting on s = r_b x_b - r_a x_a."""

    name: Annotated[str, Field(min_length=1)] | None = None
    """Name in the outputs (default: damper[<index>] <a>-<b>)."""
    between: Ends
    """The two ends: body/driver names, "ground", or (hybrid) FE nodes { x = .., dof = .. }."""
    ratios: Ratios = [1.0, 1.0]
    """[r_a, r_b]: transmission ratios of the two ends."""
    c: NonNegative["N*s/m", "N*m*s/rad"]
    """Viscous coefficient, N s/m or N m s/rad."""


class Gear(Table):
    """``[[gear]]``: rigid transmission x_b = ratio x_a, eliminated exactly (lumped models)."""

    name: Annotated[str, Field(min_length=1)] | None = None
    """Name in the outputs (default: gear[<index>] <a>-<b>)."""
    between: Annotated[list[Annotated[str, Field(min_length=1)]], Field(min_length=2, max_length=2)]
    """[driving, driven] body names."""
    ratio: Real[RATIO]
    """Transmission ratio u (finite, non-zero)."""

    @model_validator(mode="after")
    def _nonzero(self):
        if self.ratio == 0:
            rule("ratio", self.ratio, "a finite non-zero number")
        return self
