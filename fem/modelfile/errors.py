"""The adapter from the schema's validation errors to the package's :class:`ModelError`:
``where: key = value is not valid; allowed: ...`` with ``where`` the table as written in TOML
(``[analysis]``, ``[[segment]] #2 section``, ``[drive.shaft]``) and ``allowed`` built from the
field's declared type, bounds, choices and description."""
from __future__ import annotations

import difflib
import types
from typing import Annotated, Literal, Union, get_args, get_origin

import annotated_types as at
from pydantic import BaseModel, ValidationError
from pydantic.fields import FieldInfo

from discrete.errors import ModelError

from .schema.base import Number, Unit


def to_model_error(exc: ValidationError, root: type[BaseModel], kind: str, hints: dict[str, str]) -> ModelError:
    """The first problem of ``exc`` (raised validating ``root``) as a :class:`ModelError`."""
    from .schema.docstrings import attach

    attach()                          # the field descriptions (the "allowed" part)
    errors = exc.errors(include_url=False)
    err = _pick(errors)
    loc, etype, ctx = tuple(err["loc"]), err["type"], err.get("ctx") or {}
    path, owner, field, ann = _walk(root, loc)
    where = _where(path, kind)
    key = path[-1][0] if path else "model file"
    value = err.get("input")
    if etype == "drivefem_rule":
        key = ctx["key"]
        tables = list(path)
        if "." in key:                           # a rule of a parent table about a sub-table's key
            sub, key = key.rsplit(".", 1)
            tables += [(s, "key") for s in sub.split(".")]
        where = _where(tables + [(None, "key")], kind)
        return ModelError(where, key, ctx.get("value"), ctx["allowed"])
    if etype == "drivefem_unit":                 # a quantity string (units.py; the message is the validator's)
        return ModelError(where, key, ctx["text"], ctx["allowed"])
    if etype in ("union_tag_invalid", "union_tag_not_found"):
        tag_key = TAG_KEYS.get(str(ctx.get("discriminator", "")).strip("'").split("(")[0], "type")
        tags = str(ctx.get("expected_tags", "")).replace(", ", " | ")
        return ModelError(_where(path + [(None, "key")], kind), tag_key,
                          value.get(tag_key) if isinstance(value, dict) else value,
                          tags if isinstance(value, dict) else "a table")
    if etype == "extra_forbidden":
        allowed_keys = sorted(_aliases(owner)) if owner is not None else []
        near = difflib.get_close_matches(str(key), allowed_keys, n=1)
        if not path[:-1] and key in hints:
            return ModelError(where, key, _short(value), hints[key])
        allowed = "one of " + ", ".join(allowed_keys) + " (unknown keys are an error)"
        if near:
            allowed = f"did you mean {near[0]!r}? " + allowed
        return ModelError(where, key, _short(value), allowed)
    if ann is not None and field is not None and ann is not field.annotation:
        allowed = describe(ann)                  # an item of a list or a value of a table
    else:
        allowed = describe(field.annotation, field.metadata) if field is not None else _generic(etype, ctx)
    if field is not None and field.description and ann is field.annotation:
        allowed += f" ({_first_sentence(field.description)})"
    if etype == "missing":
        return ModelError(where, key, None, allowed + " (required key missing)")
    if etype in ("too_short", "too_long") and isinstance(value, (list, dict)):
        allowed += f" [{err['msg'].lower()}]"
    return ModelError(where, key, _short(value), allowed)


#: the key each callable discriminator of the schema reads
TAG_KEYS = {"_shape": "shape", "_analysis_type": "type", "_shaft_type": "type"}


def _pick(errors: list[dict]) -> dict:
    """The error to report: a cross-field rule first, then a quantity string that was read but does not
    fit its key; a string that is no quantity where the key also takes words (a union with a Literal)
    is reported as not one of the words either (the generic description lists both)."""
    for e in errors:
        if e["type"] == "drivefem_rule":
            return e
    for e in errors:
        if e["type"] == "drivefem_unit" and e["ctx"].get("parsed"):
            return e
    first = errors[0]
    if first["type"] == "drivefem_unit":
        field_loc = tuple(first["loc"][:-1])
        words = [e for e in errors if e["type"] == "literal_error" and tuple(e["loc"][:-1]) == field_loc]
        if words:
            return words[0]
    return first


def _short(value):
    if isinstance(value, dict):
        return {k: "..." if isinstance(v, (dict, list)) else v for k, v in list(value.items())[:6]}
    if isinstance(value, list) and len(value) > 8:
        return value[:8] + ["..."]
    return value


def _first_sentence(text: str) -> str:
    text = " ".join(text.split()).rstrip(".")
    return text if len(text) < 160 else text[:157] + "..."


# ------------------------------------------------------------------ navigation
def _unwrap(ann):
    """Strip Annotated and Optional; returns (annotation, metadata list)."""
    meta = []
    while True:
        if isinstance(ann, Number):              # a number type used without its unit
            ann = ann.plain
            continue
        if get_origin(ann) is Annotated:
            args = get_args(ann)
            ann = args[0]
            for m in args[1:]:
                meta += list(getattr(m, "metadata", [])) if isinstance(m, FieldInfo) else [m]
            continue
        if _is_union(ann):
            args = [a for a in get_args(ann) if a is not type(None)]
            if len(args) == 1:
                ann = args[0]
                continue
        return ann, meta


def _is_union(ann) -> bool:
    return get_origin(ann) in (Union, types.UnionType)


def _model_of(ann):
    ann, _ = _unwrap(ann)
    return ann if isinstance(ann, type) and issubclass(ann, BaseModel) else None


def _aliases(model: type[BaseModel]) -> list[str]:
    return [f.alias or name for name, f in model.model_fields.items()]


def _field(model: type[BaseModel], key):
    for name, f in model.model_fields.items():
        if key in (name, f.alias):
            return f
    return None


def _walk(root: type[BaseModel], loc: tuple):
    """Follow ``loc`` through the declared types: the table path [(name, role)], the model owning the
    last key, and that key's FieldInfo (None where the path leaves the declared tables)."""
    path: list = []
    model, ann, field, owner = root, None, None, root
    for part in loc:
        if model is not None and isinstance(part, str) and _field(model, part) is not None:
            owner, field = model, _field(model, part)
            ann = field.annotation
            path.append((part, "key"))
            model = _model_of(ann)
            continue
        base, _ = _unwrap(ann) if ann is not None else (None, [])
        if isinstance(part, int) and get_origin(base) is list:
            ann = get_args(base)[0]
            path[-1] = (path[-1][0], f"item {part + 1}")
            model = _model_of(ann)
            continue
        if isinstance(part, str) and base is not None and _is_union(base):
            members = [m for m in get_args(base) if m is not type(None)]
            pick = None
            for m in members:
                mm, meta = _unwrap(m)
                tags = [getattr(x, "tag", None) for x in (get_args(m)[1:] if get_origin(m) is Annotated else [])]
                if part in tags or (isinstance(mm, type) and mm.__name__ == part):
                    pick = m
            if pick is not None:
                ann = pick
                model = _model_of(pick)
            continue                      # a union member label: not part of the table path
        if isinstance(part, str) and model is None and get_origin(base) is dict:
            ann = get_args(base)[1]
            path.append((part, "key"))
            continue
        if model is not None and isinstance(part, str):
            owner, field = model, None
            path.append((part, "key"))
            model = None
            continue
    return path, owner, field, ann


def _where(path: list, kind: str) -> str:
    """The table holding the last key of ``path``, written as in TOML: ``[a]``, ``[a.b]``,
    ``[[a]] #2``, ``[[a]] #2 b``."""
    out = ""
    for name, role in path[:-1]:
        if name is None:
            continue
        item = f" #{role.split()[1]}" if role.startswith("item") else ""
        if not out:
            out = f"[[{name}]]{item}" if item else f"[{name}]"
        elif " " not in out and not out.startswith("[[") and not item:
            out = out[:-1] + f".{name}]"
        else:
            out = f"{out} {name}{item}"
    return out or f"model file ({kind})"


# ------------------------------------------------------------------ descriptions
def describe(ann, metadata=(), units: bool = True) -> str:
    """What a value of a declared type may be, in words ("a number > 0 in m", "'a' | 'b'", ...);
    ``units``: name the declared unit of numbers."""
    ann, meta = _unwrap(ann)
    meta = list(metadata) + meta
    if _is_union(ann):
        members = [a for a in get_args(ann) if a is not type(None)]
        if all(_model_of(a) is not None for a in members):
            return "a table"
        parts = [describe(a, units=units) for a in members]
        return " or ".join(dict.fromkeys(parts))
    origin = get_origin(ann)
    if origin is Literal:
        return " | ".join(repr(a) for a in get_args(ann))
    if ann is bool:
        return "true | false"
    if ann is str:
        return "a non-empty string" if any(isinstance(m, at.MinLen) for m in meta) else "a string"
    if ann in (int, float):
        noun = "an integer" if ann is int else "a number"
        bounds = []
        for m in meta:
            for cls, op in ((at.Gt, ">"), (at.Ge, ">="), (at.Lt, "<"), (at.Le, "<=")):
                if isinstance(m, cls):
                    bounds.append(f"{op} {getattr(m, cls.__name__.lower())}")
        unit = next((m for m in meta if isinstance(m, Unit) and m.kind == "quantity" and m.units != ("1",)), None)
        return noun + (" " + " and ".join(bounds) if bounds else "") + (f" in {unit.label}" if unit and units else "")
    if origin is list:
        item = describe(get_args(ann)[0], units=units)
        lo = next((m.min_length for m in meta if isinstance(m, at.MinLen)), None)
        hi = next((m.max_length for m in meta if isinstance(m, at.MaxLen)), None)
        model = _model_of(get_args(ann)[0])
        if model is not None:
            return "an array of tables" + (" (at least one)" if lo else "")
        size = f"{lo} " if lo is not None and lo == hi else ("a non-empty " if lo else "")
        return f"a list of {size}{item}".replace("a list of a ", "a list of ").replace("list of 2 a ", "list of 2 ")
    if origin is dict:
        return "a table of key = value"
    if isinstance(ann, type) and issubclass(ann, BaseModel):
        return "a table { " + ", ".join(_aliases(ann)) + " }"
    return getattr(ann, "__name__", str(ann))


def _generic(etype: str, ctx: dict) -> str:
    return {"float_type": "a number", "int_type": "an integer", "bool_type": "true | false",
            "string_type": "a string", "model_type": "a table", "list_type": "an array",
            "dict_type": "a table", "finite_number": "a finite number"}.get(etype, etype)
