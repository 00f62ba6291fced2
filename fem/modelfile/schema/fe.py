"""Tables of the finite-element part of a model file: ``[material]``, ``[model]``, ``[[segment]]``
(with its ``section``), ``[[support]]`` and ``[[point]]`` (design.md §4)."""

from typing import Annotated, Literal, Union

from pydantic import Discriminator, Tag, model_validator

from .base import Count, Name, NonNegative, Number, Positive, Real, Table, rule


class Material(Table):
    """Isotropic material; in ``[material]`` the defaults of every segment, in a segment's
    ``material`` an override of some of them."""

    E: Positive["Pa"] | None = None
    """Young's modulus, Pa."""
    G: Positive["Pa"] | None = None
    """Shear modulus, Pa (or give nu)."""
    nu: Number(gt=-1, lt=0.5)["1"] | None = None
    """Poisson's ratio in (-1, 0.5): G = E / (2 (1 + nu)) (or give G)."""
    rho: Positive["kg/m^3"] | None = None
    """Density, kg/m^3."""

    @model_validator(mode="after")
    def _g_or_nu(self):
        if self.G is not None and self.nu is not None:
            rule("nu", self.nu, "either G or nu, not both")
        return self


class ModelSettings(Table):
    """``[model]``: physics, beam theory, mass matrix and element order."""

    physics: Literal["torsion", "axial", "bending"]
    """What the segments carry: torsion (theta), axial (u) or bending (w and slope/rotation)."""
    theory: Literal["euler-bernoulli", "timoshenko"] = "euler-bernoulli"
    """Bending only: Euler-Bernoulli (Hermite cubic) or Timoshenko (shear and rotary inertia)."""
    mass: Literal["consistent", "lumped"] = "consistent"
    """Consistent mass, or lumped (row sum; HRZ for Hermite elements)."""
    order: Literal[1, 2] = 2
    """Lagrange order of rods and Timoshenko beams (1 linear, 2 quadratic); not for Euler-Bernoulli."""
    shear_coefficient: Number(gt=0, le=1.5)["1"] | None = None
    """Timoshenko shear coefficient kappa (default: Cowper's value for circle/tube sections)."""

    @model_validator(mode="after")
    def _theory_keys(self):
        if self.physics != "bending":
            for key, why in (("theory", "theory applies only to physics = 'bending'"),
                             ("shear_coefficient", "shear_coefficient applies only to Timoshenko bending models")):
                if self.given(key):
                    rule(key, getattr(self, key), f"{why} (this model: physics = {self.physics!r})")
        elif self.theory == "euler-bernoulli":
            if self.given("shear_coefficient"):
                rule("shear_coefficient", self.shear_coefficient,
                     "shear_coefficient applies only to Timoshenko bending models")
            if self.given("order"):
                rule("order", self.order, "no order for Euler-Bernoulli beams (Hermite cubic elements)")
        return self


class CircleSection(Table):
    """Solid circular section."""

    shape: Literal["circle"]
    d: Positive["m"]
    """Diameter, m."""
    kappa: Number(gt=0, le=1.5)["1"] | None = None
    """Timoshenko shear coefficient (default: Cowper's value)."""


class TubeSection(Table):
    """Hollow circular section."""

    shape: Literal["tube"]
    d: Positive["m"]
    """Outer diameter, m."""
    di: Positive["m"]
    """Inner diameter, m (< d)."""
    kappa: Number(gt=0, le=1.5)["1"] | None = None
    """Timoshenko shear coefficient (default: Cowper's value)."""

    @model_validator(mode="after")
    def _inner(self):
        if not self.di < self.d:
            rule("di", self.di, f"an inner diameter smaller than d = {self.d}")
        return self


class ExplicitSection(Table):
    """Section constants given directly (at least one of them)."""

    shape: Literal["explicit"] = "explicit"
    A: Positive["m^2"] | None = None
    """Area, m^2 (axial and bending models)."""
    I: Positive["m^4"] | None = None
    """Second moment of area for bending, m^4."""
    J: Positive["m^4"] | None = None
    """Torsion constant, m^4."""
    Ip: Positive["m^4"] | None = None
    """Polar moment of area for the rotary inertia rho Ip of torsion, m^4 (default J)."""
    kappa: Number(gt=0, le=1.5)["1"] | None = None
    """Timoshenko shear coefficient (required for Timoshenko models with explicit sections)."""

    @model_validator(mode="after")
    def _some(self):
        if all(getattr(self, k) is None for k in ("A", "I", "J", "Ip")):
            rule("section", {}, "{ shape = 'circle', d }, { shape = 'tube', d, di } or explicit { A, I, J } constants")
        return self


def _shape(v) -> str:
    return v.get("shape", "explicit") if isinstance(v, dict) else getattr(v, "shape", "explicit")


Section = Annotated[Union[Annotated[CircleSection, Tag("circle")], Annotated[TubeSection, Tag("tube")],
                          Annotated[ExplicitSection, Tag("explicit")]],
                    Discriminator(_shape)]


class Segment(Table):
    """``[[segment]]``: a uniform piece of shaft, consecutive from x = 0."""

    length: Positive["m"]
    """Length, m."""
    elements: Count
    """Number of finite elements."""
    section: Section
    """Cross-section: { shape = "circle", d }, { shape = "tube", d, di } or { A, I, J, Ip, kappa }."""
    material: Material | None = None
    """Per-segment override of [material] keys."""
    rho_extra: NonNegative["kg/m", "kg*m^2/m"] = 0.0
    """Extra distributed inertia per length (torsion: kg m^2/m as in (4.56); axial/bending: kg/m)."""
    psi: NonNegative["1"] = 0.0
    """Dissipation coefficient of the material (hysteretic damping, complex stiffness (1 + 2 i psi/(4 pi)))."""


class Support(Table):
    """``[[support]]`` at a node."""

    name: Name | None = None
    """Name of the support in the outputs (default: support[<index>] x=<x>)."""
    x: Real["m"]
    """Position along the shaft, m."""
    type: Literal["clamped", "pinned", "spring"] = "clamped"
    """clamped (all DOFs), pinned (bending: w only) or spring (k, kr)."""
    k: NonNegative["N/m", "N*m/rad"] = 0.0
    """Spring support: translational / axial / torsional stiffness (N/m or N m/rad)."""
    kr: NonNegative["N*m/rad"] = 0.0
    """Spring support, bending only: rotational stiffness, N m/rad."""


class Point(Table):
    """``[[point]]``: lumped attachment at a node."""

    x: Real["m"]
    """Position along the shaft, m."""
    mass: NonNegative["kg"] = 0.0
    """Mass, kg (axial and bending)."""
    inertia: NonNegative["kg*m^2"] = 0.0
    """Moment of inertia, kg m^2: polar for torsion, diametral for the bending rotation DOF."""
    k: NonNegative["N/m", "N*m/rad"] = 0.0
    """Spring to ground at the node (per physics)."""
    kr: NonNegative["N*m/rad"] = 0.0
    """Rotational spring to ground (bending only), N m/rad."""
