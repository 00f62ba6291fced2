"""``load(path)`` and ``parse(doc)``: a model file (or its dict) validated against the schema of
its kind; the typed document is what every builder consumes."""
from __future__ import annotations

import json
from pathlib import Path

from pydantic import ValidationError

from discrete.errors import ModelError

from . import plausibility
from .coordinates import check_document as check_coordinates
from .errors import to_model_error
from .schema.document import HINTS, KINDS, detect_kind
from .source import read_toml


def load(path: str | Path):
    """Read, validate and type the model file at ``path`` (read once; kind decided once).

    Returns the typed document (``FEFile``, ``LumpedFile``, ``HybridFile`` or ``DriveFile``) with
    ``kind`` and ``path`` set."""
    doc = read_toml(path)
    model = parse(doc)
    object.__setattr__(model, "__source__", Path(path))
    return model


def parse(doc: dict, kind: str | None = None):
    """Validate a parsed model file (a dict as from TOML) against the schema of its kind."""
    if not isinstance(doc, dict):
        raise ModelError("model file", "document", type(doc).__name__, "a TOML document (a table of tables)")
    kind = kind or detect_kind(doc)
    if kind not in KINDS:
        raise ModelError("model file", "kind", kind, " | ".join(map(repr, KINDS)))
    cls = KINDS[kind]
    try:
        model = cls.model_validate(doc)
    except ValidationError as exc:
        raise to_model_error(exc, cls, kind, HINTS[kind]) from None
    check_coordinates(model, doc, kind)
    object.__setattr__(model, "__plausibility__", plausibility.check(model, doc, kind))
    return model


def kind_of(model) -> str:
    """The kind name of a typed document."""
    for name, cls in KINDS.items():
        if isinstance(model, cls):
            return name
    raise TypeError(type(model).__name__)


def schema_json(kind: str | None = None) -> dict:
    """The JSON Schema of one kind of model file, or of any model file (``kind`` None)."""
    from .schema.docstrings import attach

    attach()                          # the field descriptions
    if kind is not None:
        if kind not in KINDS:
            raise ModelError("drivefem schema", "KIND", kind, " | ".join(map(repr, KINDS)))
        out = KINDS[kind].model_json_schema(mode="validation")
        out["title"] = f"drivefem {kind} model file"
    else:
        parts = {k: c.model_json_schema(mode="validation", ref_template="#/$defs/{model}")
                 for k, c in KINDS.items()}
        defs = {}
        for s in parts.values():
            defs.update(s.pop("$defs", {}))
        out = {"title": "drivefem model file", "anyOf": [{"$ref": f"#/$defs/{k}_file"} for k in parts],
               "$defs": defs | {f"{k}_file": s for k, s in parts.items()}}
    out["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    return out


SCHEMA_FILE = Path(__file__).resolve().parent / "drivefem.schema.json"
"""The JSON Schema of any model file, shipped with the package (``#:schema`` line of the examples)."""


def dumps_schema(kind: str | None = None) -> str:
    return json.dumps(schema_json(kind), indent=2) + "\n"
