"""Building blocks of the model-file schema: the strict table base and the number types.

Every table of every model-file kind is a :class:`Table`: unknown keys are errors, values are
checked strictly (a string is never a number, a float never an integer, a bool never a number)
and NaN or infinity are refused where they are given.  The docstring under each field states
its meaning and unit: it becomes the field's description in the JSON Schema (editor
completion) and the "allowed" part of error messages.

Every numeric key declares its unit with the number type (the tests refuse one that does not)::

    E: Positive["Pa"]                      # a number > 0 in Pa, or a quantity string "210 GPa"
    x: Real["m"]                           # any finite number, m
    k: NonNegative["N/m", "N*m/rad"]       # alternatives: translational or rotational coordinate
    nu: Number(gt=-1, lt=0.5)["1"]         # other bounds; "1": dimensionless
    elements: Count                        # integers are counts: dimensionless, no quantity strings
    points: Integer(ge=2)

The unit is the one of the plain number (SI, or rpm/deg/Hz for keys named so); it must be in the
catalogue :data:`fem.modelfile.units.DIMENSIONS`.  A quantity string is converted to it once, when
the file is read (:mod:`fem.modelfile.units`).
"""

import types
from functools import partial
from typing import Annotated, Any, ClassVar, Iterator, Literal, Union, get_args, get_origin

from pydantic import BaseModel, ConfigDict, Field, ValidationError
from pydantic_core import PydanticCustomError, core_schema

from .. import units as U


class Table(BaseModel):
    """A TOML table: strict types, finite numbers, unknown keys are an error."""

    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True,
                              defer_build=True)
    # field descriptions (the string under each field): attached on demand, docstrings.attach()

    one_coordinate: ClassVar[bool] = False
    """Whether every coordinate-dependent key of the table refers to one coordinate (a body, an
    element's s): quantity strings in them must then agree on its kind (translational or rotational)."""

    unit_choice: ClassVar[dict] = {}
    """{key: (other key, {its value: indices of the key's unit alternatives allowed})}: alternatives
    chosen by another key of the table (checked by :mod:`fem.modelfile.coordinates`)."""

    def given(self, name: str) -> bool:
        """Whether the key was written in the file (not filled in by its default)."""
        return name in self.model_fields_set


def rule(key: str, value: Any, allowed: str):
    """Raise the error of a cross-field rule of a table: ``key = value`` is not valid; ``allowed``."""
    raise PydanticCustomError("drivefem_rule", "{key} = {value!r}: {allowed}",
                              {"key": key, "value": value, "allowed": allowed})


QUANTITY_PATTERN = r"^\s*[+-]?\.?\d"
"""JSON Schema pattern of a quantity string (it starts with a number) for editors; the loader's
grammar (a number, then a unit) is :mod:`fem.modelfile.units`."""


class Unit:
    """The declared unit of a numeric key (metadata of its type): ``units`` are the alternatives
    (usually one), ``kind`` is "quantity" (numbers or quantity strings), "count" (integers: no
    strings) or "swept" (the unit of the swept key of a [sweep] axis: numbers only)."""

    __slots__ = ("units", "kind")

    def __init__(self, *units: str, kind: str = "quantity"):
        for u in units:
            U.dimension(u)                  # declared units are in the catalogue (KeyError names it)
        self.units, self.kind = tuple(units), kind

    def __repr__(self) -> str:
        return f"Unit({', '.join(map(repr, self.units))}{'' if self.kind == 'quantity' else ', kind=' + repr(self.kind)})"

    @property
    def label(self) -> str:
        """The unit as shown in the reference page and the JSON Schema."""
        if self.kind == "count":
            return "count"
        if self.kind == "swept":
            return "of the swept key"
        return " or ".join(U.display(u) for u in self.units)

    def __get_pydantic_core_schema__(self, source, handler):
        inner = handler(source)
        if self.kind != "quantity":
            return inner
        bounds = " and ".join(f"{op} {inner[k]}" for k, op in (("gt", ">"), ("ge", ">="), ("lt", "<"), ("le", "<="))
                              if k in inner)
        allowed = U.allowed(self.units, bounds)
        return core_schema.no_info_wrap_validator_function(partial(self._validate, allowed=allowed), inner)

    def _validate(self, value, handler, allowed: str):
        if not isinstance(value, str):
            return handler(value)
        try:
            si, alt = U.convert(value, self.units)
        except U.UnitError as exc:
            raise PydanticCustomError("drivefem_unit", "{text}: {allowed}",
                                      {"text": value, "allowed": f"{allowed} ({exc.reason})",
                                       "parsed": exc.parsed}) from None
        try:
            return handler(si)
        except ValidationError:
            shown = f"{value.strip()!r} is {si:.6g} {U.display(self.units[alt])}"
            raise PydanticCustomError("drivefem_unit", "{text}: {allowed}",
                                      {"text": value, "allowed": f"{allowed} ({shown})", "parsed": True}) from None

    def __get_pydantic_json_schema__(self, schema, handler):
        out = handler(schema)
        if self.kind != "quantity":
            return {**out, "unit": "1" if self.kind == "count" else self.label}
        text = {"type": "string", "pattern": QUANTITY_PATTERN}
        return {"anyOf": [out, text], "unit": self.label, "examples": [U.dimension(self.units[0]).example]}


COUNT = Unit(kind="count")
SWEPT = Unit(kind="swept")


class Number:
    """A number type with bounds; ``Number(...)[unit, ...]`` is the type with its declared unit(s).
    Used bare (no unit) it is still a valid type, which the schema tests refuse."""

    __slots__ = ("bounds", "plain", "_typed")

    def __init__(self, **bounds):
        self.bounds = bounds
        self.plain = Annotated[float, Field(**bounds)]
        """The type without a unit."""
        self._typed: dict = {}

    def __getitem__(self, units) -> Any:
        units = units if isinstance(units, tuple) else (units,)
        typed = self._typed.get(units)
        if typed is None:                   # one type per unit: the schema evaluates each annotation
            typed = self._typed[units] = Annotated[self.plain, Unit(*units)]
        return typed

    def __get_pydantic_core_schema__(self, source, handler):
        return handler.generate_schema(self.plain)

    def __or__(self, other) -> Any:
        return Union[self.plain, other]

    def __ror__(self, other) -> Any:
        return Union[other, self.plain]

    def __repr__(self) -> str:
        return f"Number({', '.join(f'{k}={v!r}' for k, v in self.bounds.items())})"


def Integer(**bounds) -> Any:
    """A count or index (dimensionless; integers take no quantity strings) with bounds."""
    return Annotated[int, Field(**bounds), COUNT]


def numeric_leaves(ann, metadata=()) -> Iterator[tuple[type, list]]:
    """(int or float, its metadata) of every number a declared type holds: the type itself, union
    members, list items, table values (sub-tables are not entered; Literal choices and bools are not
    numbers).  A number type used without its unit yields metadata without a :class:`Unit`."""
    meta = list(metadata)
    if isinstance(ann, Number):
        yield float, meta + [ann.plain]
        return
    origin = get_origin(ann)
    if origin is Annotated:
        args = get_args(ann)
        yield from numeric_leaves(args[0], meta + list(args[1:]))
    elif origin in (Union, types.UnionType):
        for a in get_args(ann):
            yield from numeric_leaves(a, meta if len(get_args(ann)) == 2 and type(None) in get_args(ann) else ())
    elif origin in (list, dict):
        yield from numeric_leaves(get_args(ann)[-1])
    elif origin is Literal or ann is bool or ann is type(None):
        return
    elif ann in (int, float):
        yield ann, meta


def declared_unit(ann, metadata=()) -> Unit | None:
    """The unit declared for the numbers of a type (the first one found), or None."""
    for _, meta in numeric_leaves(ann, metadata):
        for m in meta:
            if isinstance(m, Unit):
                return m
    return None


Real = Number()
Positive = Number(gt=0)
NonNegative = Number(ge=0)
Count = Integer(ge=1)
Fraction = Number(ge=0, le=1)["1"]
Name = Annotated[str, Field(min_length=1)]
Pair = Annotated[list[float], Field(min_length=2, max_length=2)]
"""Two numbers (no unit declared: prefer :func:`pair`)."""


def pair(*units: str) -> Any:
    """Two numbers [a, b] of the declared unit(s)."""
    return Annotated[list[Real[units]], Field(min_length=2, max_length=2)]
