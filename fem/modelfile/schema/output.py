"""``[[output]]``: the named outputs of a lumped or hybrid file (docs/outputs.md).  Without any, every
analysis writes its default outputs: the deflection and force of every spring, damper, gear pair and
nonsmooth element and the reaction of every driver and support."""
from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, model_validator

from .base import Name, Table, rule
from .lumped import Ends, Ratios

WHERE_KEYS = ("element", "body", "between", "support", "x")
QUANTITY = Literal["displacement", "velocity", "acceleration", "deflection", "twist", "slip_velocity", "force",
                   "torque", "moment", "reaction"]
MOTIONS = ("displacement", "velocity", "acceleration", "deflection", "twist", "slip_velocity")


class Output(Table):
    """``[[output]]``: one named output of every analysis (time histories of drivefem simulate, complex
    amplitudes of drivefem forced, load shapes of drivefem modal), written under its name in the JSON,
    the CSV, the --h5 file and the plots."""

    name: Name | None = None
    """Name of the output (default: <where>.<quantity>, e.g. "mesh.force")."""
    quantity: QUANTITY
    """displacement | velocity | acceleration (of a body, an FE node, or relative between two points),
    deflection | twist (of an element, or between two points), slip_velocity (of a friction), force |
    torque | moment (of an element), reaction (of a driver or support)."""
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
    """A driver (lumped, hybrid) or support (hybrid: support[<index>]) by its name: its reaction."""
    x: float | None = None
    """Hybrid files: an FE node of the shaft, m: its displacement, velocity or acceleration (dof or
    components), or the reaction of a support or driver there."""
    dof: str | None = None
    """With x: the DOF at the node (default: the primary field)."""
    components: Annotated[list[Name], Field(min_length=1)] | None = None
    """With x: several DOFs at the node (e.g. ["w", "w_x"]), one output each (<name>.<component>)."""

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
                   "x": ("displacement", "velocity", "acceleration", "reaction")}[where]
        if q not in allowed:
            rule("quantity", q, f"one of {', '.join(allowed)} with {where} = .. (force, torque and moment are the "
                 "loads of elements; reaction that of drivers and supports)")
        if self.ratios is not None and self.between is None:
            rule("ratios", self.ratios, "only with between = [..]")
        if (self.dof is not None or self.components is not None) and self.x is None:
            rule("dof" if self.dof is not None else "components", self.dof or self.components, "only with x = ..")
        if self.dof is not None and self.components is not None:
            rule("components", self.components, "either dof = .. or components = [..]")
        return self
