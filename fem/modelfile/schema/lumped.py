"""Tables of the lumped part of a model file: ``[[body]]``, ``[[driver]]``, ``[[spring]]``,
``[[damper]]`` and ``[[gear]]`` -- the same tables in lumped and hybrid files (textbook §4.4-4.9)."""
from __future__ import annotations

from typing import Annotated, Union

from pydantic import Field, model_validator

from .base import NonNegative, Positive, Table, rule


class NodeEnd(Table):
    """An FE node as one end of a spring, damper or element (hybrid models): ``{ x = .., dof = .. }``."""

    x: float
    """Node position along the shaft, m."""
    dof: str | None = None
    """DOF name at the node (theta, u, w, w_x, phi; default: the primary field)."""


End = Union[Annotated[str, Field(min_length=1)], NodeEnd]
"""A body or driver name, "ground", or (hybrid models) an FE node { x = .., dof = .. }."""
Ends = Annotated[list[End], Field(min_length=2, max_length=2)]
Ratios = Annotated[list[float], Field(min_length=2, max_length=2)]


class Body(Table):
    """``[[body]]``: a lumped body with one generalised coordinate x (displacement or angle)."""

    name: Annotated[str, Field(min_length=1)]
    """Unique name (not "ground")."""
    inertia: Positive
    """Mass (kg) or moment of inertia (kg m^2) of the coordinate."""
    inertia_rate: float = 0.0
    """d(inertia)/dt: variable mass m0 + delta t (seed 004 (1), Newton form), kg/s."""
    reactive: float = 0.0
    """Reactive coefficient epsilon of seed 004 (reactive damping epsilon * inertia_rate)."""
    x0: float = 0.0
    """Initial displacement."""
    v0: float = 0.0
    """Initial velocity."""

    @model_validator(mode="after")
    def _name(self):
        if self.name == "ground":
            rule("name", self.name, "a non-empty name other than 'ground'")
        return self


class Driver(Table):
    """``[[driver]]``: prescribed motion x(t) = offset + velocity t + amplitude sin(omega t + phase).

    Lumped models: a named coordinate (``name``) with an optional inertia; hybrid models: an FE DOF
    (``x``, ``dof``)."""

    name: Annotated[str, Field(min_length=1)] | None = None
    """Name of the driven coordinate (lumped models: required; a body name for springs and elements)."""
    x: float | None = None
    """Hybrid models: position of the driven FE node, m."""
    dof: str | None = None
    """Hybrid models: driven DOF at the node (default: the primary field)."""
    offset: float = 0.0
    """Constant part of the motion."""
    velocity: float = 0.0
    """Constant velocity (x = velocity t), m/s or rad/s."""
    amplitude: float = 0.0
    """Harmonic amplitude."""
    omega: NonNegative = 0.0
    """Angular frequency of the harmonic part, rad/s."""
    phase: float = 0.0
    """Phase of the harmonic part, rad."""
    inertia: NonNegative = 0.0
    """Lumped models: inertia of the driven coordinate (enters the reactions only)."""

    @model_validator(mode="after")
    def _law(self):
        if self.amplitude != 0 and self.omega == 0:
            rule("omega", self.omega, "a number > 0 with amplitude")
        if self.name == "ground":
            rule("name", self.name, "a non-empty name other than 'ground'")
        return self


class Spring(Table):
    """``[[spring]]``: a linear spring (and parallel dashpot) acting on s = r_b x_b - r_a x_a."""

    between: Ends
    """The two ends: body/driver names, "ground", or (hybrid) FE nodes { x = .., dof = .. }."""
    ratios: Ratios = [1.0, 1.0]
    """[r_a, r_b]: transmission ratios of the two ends (radii of a belt, ...)."""
    k: NonNegative = 0.0
    """Stiffness, N/m or N m/rad."""
    c: NonNegative = 0.0
    """Viscous coefficient of a parallel dashpot, N s/m or N m s/rad."""
    psi: NonNegative = 0.0
    """Dissipation coefficient of the spring (hysteretic damping in harmonic analysis)."""

    @model_validator(mode="after")
    def _something(self):
        if not (self.given("k") or self.given("c")):
            rule("k", None, "the stiffness k (and/or a dashpot c) (required key missing)")
        return self


class Damper(Table):
    """``[[damper]]``: a viscous damper acting on s = r_b x_b - r_a x_a."""

    between: Ends
    """The two ends: body/driver names, "ground", or (hybrid) FE nodes { x = .., dof = .. }."""
    ratios: Ratios = [1.0, 1.0]
    """[r_a, r_b]: transmission ratios of the two ends."""
    c: NonNegative
    """Viscous coefficient, N s/m or N m s/rad."""


class Gear(Table):
    """``[[gear]]``: rigid transmission x_b = ratio x_a, eliminated exactly (lumped models)."""

    between: Annotated[list[Annotated[str, Field(min_length=1)]], Field(min_length=2, max_length=2)]
    """[driving, driven] body names."""
    ratio: float
    """Transmission ratio u (finite, non-zero)."""

    @model_validator(mode="after")
    def _nonzero(self):
        if self.ratio == 0:
            rule("ratio", self.ratio, "a finite non-zero number")
        return self
