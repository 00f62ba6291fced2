"""``[drive]``: a drive of regular structure (textbook ch. 10) -- a main shaft with n identical
1-DOF mechanisms -- and its sub-tables (see docs/drives.md)."""

from typing import Annotated, Literal, Union

from pydantic import Discriminator, Field, Tag, model_validator

from .base import Count, NonNegative, Number, Positive, Real, Table, rule


class LumpedDriveShaft(Table):
    """``[drive.shaft] type = "lumped"``: discs J0 joined by shaft segments c0."""

    type: Literal["lumped"] = "lumped"
    c0: Positive["N*m/rad"]
    """Stiffness of one shaft segment, N m/rad."""
    J0: Positive["kg*m^2"]
    """Disc inertia at each mechanism, kg m^2."""


class DistributedDriveShaft(Table):
    """``[drive.shaft] type = "distributed"``: a continuous shaft with optional discs."""

    type: Literal["distributed"]
    length: Positive["m"]
    """Shaft length, m."""
    GI: Positive["N*m^2"]
    """Torsional stiffness G I_p, N m^2."""
    rho: NonNegative["kg*m^2/m"]
    """Polar inertia per length, kg m."""
    J0: NonNegative["kg*m^2"] = 0.0
    """Optional disc at each mechanism, kg m^2."""
    elements: Count = 8
    """FE elements per segment (discrete representation)."""
    order: Literal[1, 2] = 2
    """Lagrange order of the shaft elements."""
    mass: Literal["consistent", "lumped"] = "consistent"
    """Mass matrix of the shaft elements."""

    @model_validator(mode="after")
    def _inertia(self):
        if self.rho == 0 and self.J0 == 0:
            rule("rho", 0.0, "rho > 0 or discs J0 > 0 (the shaft needs inertia)")
        return self


def _shaft_type(v) -> str:
    return v.get("type", "lumped") if isinstance(v, dict) else getattr(v, "type", "lumped")


DriveShaft = Annotated[Union[Annotated[LumpedDriveShaft, Tag("lumped")],
                             Annotated[DistributedDriveShaft, Tag("distributed")]],
                       Discriminator(_shaft_type)]


class Mechanism(Table):
    """``[drive.mechanism]``: the identical 1-DOF cyclic mechanism (Fig. 10.2)."""

    m: Positive["kg"]
    """Output mass, kg."""
    c: Number(gt=0, allow_inf_nan=True)["N/m"] | None = None
    """Stiffness, N/m (c = inf: a rigid mechanism)."""
    k: Positive["rad/s"] | None = None
    """Partial frequency sqrt(c/m), rad/s (instead of c)."""
    ratio: Real["m/rad"]
    """First transfer function Pi' (m/rad), non-zero."""
    output: Literal["free", "grounded"] = "free"
    """Mechanism output free, or held by a spring to ground."""

    @model_validator(mode="after")
    def _stiffness(self):
        if (self.c is None) == (self.k is None):
            rule("c", self.c, "exactly one of c (N/m) or k = sqrt(c/m) (rad/s)")
        if self.c is not None and self.c != self.c:
            rule("c", self.c, "a stiffness > 0 or inf (rigid)")
        if self.ratio == 0:
            rule("ratio", self.ratio, "a non-zero first transfer function Pi' (m/rad)")
        return self


class DriveLoad(Table):
    """``[drive.load]``: a harmonic force on every mechanism output."""

    force: Real["N"] = 0.0
    """Force amplitude on each mechanism output, N."""


class DriveContinuum(Table):
    """``[drive.continuum]``: the two-field pseudo-medium FE model (§10.5)."""

    elements: Count = 64
    """Elements of the continuum model."""
    order: Literal[1, 2] = 2
    """Lagrange order of the continuum model."""
    length: Positive["m"] | None = None
    """Lumped shafts only: length of the continuum (the whole drive), m; default 1 m per segment."""


class Drive(Table):
    """``[drive]``: n identical mechanisms on a main shaft."""

    n: Count
    """Number of identical mechanisms."""
    boundary: Literal["clamped-free", "clamped-clamped", "free-free", "free-clamped"] = "clamped-free"
    """Ends of the main shaft."""
    representation: Literal["discrete", "transfer-matrix", "continuum"] = "discrete"
    """FE/lumped model, transfer matrices, or the continuum pseudo-medium."""
    shaft: DriveShaft
    """[drive.shaft]"""
    mechanism: Mechanism
    """[drive.mechanism]"""
    load: DriveLoad | None = None
    """[drive.load]"""
    continuum: DriveContinuum = DriveContinuum()
    """[drive.continuum]"""

    @model_validator(mode="after")
    def _consistent(self):
        if self.boundary == "free-free" and self.n < 2:
            rule("n", self.n, "n >= 2 for boundary = 'free-free' (n-1 shaft segments)")
        if self.continuum.length is not None and self.shaft.type == "distributed":
            rule("continuum.length", self.continuum.length,
                 "only for a lumped shaft (a distributed shaft has its own length)")
        return self
