"""``[[output]]``: the named outputs of a model file (docs/outputs.md).  Without any, every analysis
writes its default outputs: the deflection and force of every spring, damper, gear pair and nonsmooth
element, the reaction of every driver, support and bearing, and the section loads of FE shafts and
rotors at their key stations."""

from typing import Annotated, Literal

from pydantic import Field, model_validator

from .base import Name, Real, Table, rule
from .lumped import Ends, Ratios

WHERE_KEYS = ("element", "body", "between", "support", "x")
QUANTITY = Literal["displacement", "velocity", "acceleration", "deflection", "twist", "slip_velocity", "force",
                   "torque", "moment", "shear", "reaction"]
SECTION = ("torque", "moment", "force", "shear")
MOTIONS = ("displacement", "velocity", "acceleration", "deflection", "twist", "slip_velocity")


class Output(Table):
    """``[[output]]``: one named output of every analysis (time histories of drivefem simulate, complex
    amplitudes of drivefem forced, load shapes of drivefem modal), written under its name in the JSON,
    the CSV, the --h5 file and the plots.  Lumped and hybrid files: elements, bodies, relative motions,
    reactions; FE, hybrid and rotor files: section loads at x on the shaft and support (bearing)
    reactions."""

    name: Name | None = None
    """Name of the output (default: <where>.<quantity>, e.g. "mesh.force")."""
    quantity: QUANTITY
    """displacement | velocity | acceleration (of a body, an FE node, or relative between two points),
    deflection | twist (of an element, or between two points), slip_velocity (of a friction), force |
    torque | moment (of an element; at x: the section's axial force, torque, bending moment), shear (at x:
    the section's shear force), reaction (of a driver, support or bearing)."""
    element: Name | None = None
    """A spring, damper, gear or nonsmooth element by its name (generated names: spring[2] motor-pinion)."""
    body: Name | None = None
    """A body or driver by its name: its displacement, velocity or acceleration (a driver: also reaction)."""
    between: Ends | None = None
    """Two points [a, b] (bodies, drivers, "ground", hybrid FE nodes { x, dof }): the relative motion
    r_b x_b - r_a x_a."""
    ratios: Ratios | None = None
    """[r_a, r_b] with between (default [1, 1])."""
    support: Name | None = None
    """A driver (lumped, hybrid), support (FE, hybrid: its name, else support[<index>] x=<x>), bearing or
    pedestal (rotor: its name, else <table>[<index>] x=<x>) by its name: its reaction."""
    x: Real["m"] | None = None
    """A station on the shaft, m (FE, hybrid, rotor files): the section load there (quantity torque,
    moment, force, shear), the displacement, velocity or acceleration of the FE node (dof or components),
    or the reaction of a support or driver there."""
    side: Literal["left", "right"] | None = None
    """With a section load at x: the section just left or right of x, where a load jumps (a support, a
    point mass, a disc); default right (the only side at the shaft's ends)."""
    dof: str | None = None
    """With x: the DOF at the node (default: the primary field)."""
    components: Annotated[list[Name], Field(min_length=1)] | None = None
    """With x: several DOFs at the node (e.g. ["w", "w_x"]), one output each (<name>.<component>); a
    rotor's moment or shear: the planes ["y", "z"] (default both)."""

    @model_validator(mode="after")
    def _where(self):
        given = [k for k in WHERE_KEYS if getattr(self, k) is not None]
        if len(given) != 1:
            rule(given[1] if len(given) > 1 else "element", getattr(self, given[1]) if len(given) > 1 else None,
                 "exactly one of element = .., body = .., between = [..], support = .. or x = .. (where the "
                 "output is taken)")
        where = given[0]
        q = self.quantity
        allowed = {"element": ("deflection", "twist", "velocity", "slip_velocity", "force", "torque", "moment"),
                   "body": ("displacement", "velocity", "acceleration", "reaction"),
                   "between": ("deflection", "twist", "velocity", "acceleration"),
                   "support": ("reaction", "force", "torque", "moment"),
                   "x": ("displacement", "velocity", "acceleration", "reaction") + SECTION}[where]
        if q not in allowed:
            rule("quantity", q, f"one of {', '.join(allowed)} with {where} = .. (force, torque and moment are the "
                 "loads of elements and, at x, of the shaft's section; reaction that of drivers, supports and "
                 "bearings)")
        if self.side is not None and not (where == "x" and q in SECTION):
            rule("side", self.side, "only with x = .. and a section load (quantity torque, moment, force or shear)")
        if self.dof is not None and where == "x" and q in SECTION:
            rule("dof", self.dof, "not with a section load (the quantity names it; components = ['y', 'z'] picks "
                 "a rotor's planes)")
        if self.ratios is not None and self.between is None:
            rule("ratios", self.ratios, "only with between = [..]")
        if (self.dof is not None or self.components is not None) and self.x is None:
            rule("dof" if self.dof is not None else "components", self.dof or self.components, "only with x = ..")
        if self.dof is not None and self.components is not None:
            rule("components", self.components, "either dof = .. or components = [..]")
        return self
