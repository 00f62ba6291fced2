"""``[[superelement]]`` (hybrid models): a linear super-element read from matrix files (fem/superelement.py)
joined to the shaft; its other DOFs are addressed as ``body = "NAME:DOF"``."""

from typing import Annotated

from pydantic import Field, model_validator

from .base import Name, Real, Table, rule


class Join(Table):
    """One super-element DOF made one with a DOF of the shaft."""

    dof: Name
    """The super-element DOF (a name of its ``dofs`` list)."""
    x: Real["m"]
    """Position of the shaft node, m."""
    field: Name | None = None
    """The shaft DOF's field at that node (default: the primary field: u, theta or w)."""


class SuperElement(Table):
    """``[[superelement]]``: M, K (and C) of a linear part from Matrix Market / Harwell-Boeing files, described
    by a JSON file (fem/superelement.py), joined to the shaft at ``join``; its other DOFs are new DOFs named
    ``NAME:DOF`` that elements, forces and springs address with ``body = "NAME:DOF"``."""

    name: Name
    """Name of the super-element (prefix of its DOFs' names)."""
    file: Name
    """The super-element's description (JSON), relative to the model file."""
    join: Annotated[list[Join], Field(min_length=1)]
    """[{ dof = .., x = .., field = .. }]: the super-element DOFs that are shaft DOFs (at least one)."""

    @model_validator(mode="after")
    def _unique(self):
        dofs = [j.dof for j in self.join]
        if len(set(dofs)) != len(dofs):
            rule("join", dofs, "each super-element DOF joined once")
        return self
