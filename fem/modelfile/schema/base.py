"""Building blocks of the model-file schema: the strict table base and the number types.

Every table of every model-file kind is a :class:`Table`: unknown keys are errors, values are
checked strictly (a string is never a number, a float never an integer, a bool never a number)
and NaN or infinity are refused where they are given.  The docstring under each field states
its meaning and unit: it becomes the field's description in the JSON Schema (editor
completion) and the "allowed" part of error messages.
"""
from __future__ import annotations

from typing import Annotated, Any

from pydantic import BaseModel, ConfigDict, Field
from pydantic_core import PydanticCustomError


class Table(BaseModel):
    """A TOML table: strict types, finite numbers, unknown keys are an error."""

    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True,
                              defer_build=True)
    # field descriptions (the string under each field): attached on demand, docstrings.attach()

    def given(self, name: str) -> bool:
        """Whether the key was written in the file (not filled in by its default)."""
        return name in self.model_fields_set


def rule(key: str, value: Any, allowed: str):
    """Raise the error of a cross-field rule of a table: ``key = value`` is not valid; ``allowed``."""
    raise PydanticCustomError("drivefem_rule", "{key} = {value!r}: {allowed}",
                              {"key": key, "value": value, "allowed": allowed})


Positive = Annotated[float, Field(gt=0)]
NonNegative = Annotated[float, Field(ge=0)]
Count = Annotated[int, Field(ge=1)]
Fraction = Annotated[float, Field(ge=0, le=1)]
Name = Annotated[str, Field(min_length=1)]
Pair = Annotated[list[float], Field(min_length=2, max_length=2)]
