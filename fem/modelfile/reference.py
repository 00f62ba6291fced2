"""The model-file reference (docs/model_file.md) generated from the schema: one section per table,
one row per key with its type, default and description.  ``python -m fem.modelfile.reference`` writes
it; a test checks that the committed page is the generated one."""
from __future__ import annotations

import sys
from pathlib import Path

import types
from typing import Union, get_args, get_origin

from pydantic import BaseModel
from pydantic_core import PydanticUndefined

from .errors import _model_of, _unwrap, describe
from .schema.base import declared_unit
from .schema.document import KINDS

PAGE = Path(__file__).resolve().parents[2] / "docs" / "model_file.md"
HEADER = """# Model-file reference

Generated from the declared schema (`fem/modelfile/schema/`) by `python -m fem.modelfile.reference`;
do not edit by hand.  `drivefem schema [KIND]` prints the same declaration as JSON Schema for editors.
Unknown keys are errors at every level; numbers must be finite.

The column *unit* is the unit of a plain number; every such key also takes a quantity string in any
unit of the same dimension, converted when the file is read: `d = "50 mm"`, `E = "210 GPa"`,
`speed_rpm = "314.16 rad/s"` (see [Units](units.md)).  Two units joined by *or*: the key acts on a
coordinate that is a displacement or an angle, and its unit follows it.  *count*: an integer.
"""


def _sub_models(ann) -> list:
    """The table types a field holds (a table, an array of tables, or a union of tables)."""
    ann, _ = _unwrap(ann)
    if get_origin(ann) in (list, dict):
        ann, _ = _unwrap(get_args(ann)[-1])
    members = get_args(ann) if get_origin(ann) in (Union, types.UnionType) else (ann,)
    return [m for m in (_model_of(a) for a in members) if m is not None]


def _tables(model: type[BaseModel], prefix: str, seen: dict) -> None:
    """Collect {label: table type} for every sub-table below ``model``, depth first."""
    for key, f in model.model_fields.items():
        subs = _sub_models(f.annotation)
        for m in subs:
            label = f"{prefix}{f.alias or key}" + (f" ({m.__name__})" if len(subs) > 1 else "")
            if m not in seen.values():
                seen[label] = m
                _tables(m, f"{prefix}{f.alias or key}.", seen)


def _default(f) -> str:
    if f.is_required():
        return "required"
    if f.default_factory is not None:
        return "[]"
    d = f.default
    if d is None or d is PydanticUndefined:
        return "-"
    if isinstance(d, BaseModel):
        return "{}"
    return repr(d)


def table_rows(model: type[BaseModel]) -> list[tuple[str, str, str, str, str]]:
    """(key, allowed values, unit, default, meaning) of every key of a table."""
    rows = []
    for key, f in model.model_fields.items():
        text = " ".join((f.description or "").split())
        unit = declared_unit(f.annotation, f.metadata)
        rows.append((f.alias or key, describe(f.annotation, f.metadata, units=False), unit.label if unit else "", _default(f), text))
    return rows


def _rows(model) -> list[str]:
    cell = lambda text: text.replace("|", "&#124;")  # noqa: E731
    return [f"| `{key}` | {cell(typ)} | {cell(unit)} | {cell(default)} | {cell(text)} |"
            for key, typ, unit, default, text in table_rows(model)]


def render() -> str:
    from .schema.docstrings import attach

    attach()                          # the field descriptions
    out = [HEADER]
    for kind, cls in KINDS.items():
        out.append(f"\n## `{kind}` files ({cls.__doc__.strip().splitlines()[0]})\n")
        out.append("| top-level key | allowed | unit | default | meaning |\n| --- | --- | --- | --- | --- |")
        out += _rows(cls)
    seen: dict = {}
    for cls in KINDS.values():
        _tables(cls, "", seen)
    out.append("\n## Tables\n")
    for label, model in seen.items():
        doc = " ".join((model.__doc__ or "").split())
        out.append(f"\n### `{label}`\n\n{doc}\n")
        out.append("| key | allowed | unit | default | meaning |\n| --- | --- | --- | --- | --- |")
        out += _rows(model)
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    path = Path(sys.argv[1]) if len(sys.argv) > 1 else PAGE
    path.write_text(render())
    print(f"wrote {path}")
