"""Quantity strings of coordinate-dependent keys, checked against the coordinate they act on.

Some keys take a translational or a rotational unit depending on the coordinate they act on: a
support's ``k`` is N/m in bending or axial models and N m/rad in torsion; a body's ``inertia`` is kg
or kg m^2.  The schema declares both alternatives (``NonNegative["N/m", "N*m/rad"]``; the catalogue
:data:`fem.modelfile.units.DIMENSIONS` gives each unit's kind) and accepts either; once the document
is validated this module checks the quantity strings where the kind is known:

* **FE tables** (``[[segment]]``, ``[[support]]``, ``[[point]]``, ``[[load]]``, ``[[base_motion]]`` of
  FE and hybrid files): the kind of the DOF -- torsion theta is rotational, axial u and bending w are
  translational, a bending slope (w_x, phi) is rotational;
* **one-coordinate tables** (a body, a driver and its programme, a spring, an element acting on s):
  every coordinate-dependent string of the table has the same kind;
* a key whose alternative is chosen by another key (``[[load]] amplitude``: a force or moment with
  ``scaling = "constant"``, m e with ``"omega2"``, :attr:`Table.unit_choice`).

Plain numbers are in the unit of the coordinate by definition and are not checked.  A model of
plain numbers never reaches pint: only strings are looked at.
"""
from __future__ import annotations

from discrete.errors import ModelError

from . import units as U
from .errors import _where
from .schema.base import Table, declared_unit

ROTATIONAL_DOFS = ("theta", "w_x", "phi")
"""DOF names of rotations (torsion angle, Hermite slope, Timoshenko section rotation)."""
PRIMARY_DOF = {"torsion": "theta", "axial": "u", "bending": "w"}
FE_TABLES = ("segment", "support", "point", "load", "base_motion")


def _coordinate_fields(cls: type[Table]) -> dict[str, tuple[str, Unit, tuple]]:
    """{field name: (key as written, unit, kinds)} of the coordinate-dependent keys of a table."""
    cache = cls.__dict__.get("_coordinate_fields_cache")
    if cache is None:
        cache = {}
        for name, f in cls.model_fields.items():
            unit = declared_unit(f.annotation, f.metadata)
            kinds = U.coordinate_kinds(unit.units) if unit is not None and unit.kind == "quantity" else None
            if kinds is not None:
                cache[name] = (f.alias or name, unit, kinds)
        type.__setattr__(cls, "_coordinate_fields_cache", cache)
    return cache


def check_document(model: Table, raw: dict, kind: str) -> None:
    """Check the quantity strings of coordinate-dependent keys of a validated document (``raw``: the
    dict it was validated from)."""
    physics = None
    if kind in ("fe", "hybrid"):
        physics = model.model.physics
    _walk(model, raw, [], kind, physics)
    if kind == "train":          # each FE shaft's nested FE tables by that shaft's physics
        for t, r in zip(model.shaft, raw.get("shaft", []) if isinstance(raw.get("shaft"), list) else []):
            if t.model is not None and isinstance(r, dict):
                _walk(t, r, [], kind, t.model.physics)


def _walk(table: Table, raw: dict, path: list, kind: str, physics: str | None) -> None:
    strings = []                                   # (field name, key as written, text, kind of coordinate)
    coordinate = _coordinate_fields(type(table))
    for name, f in type(table).model_fields.items():
        alias = f.alias or name
        if alias not in raw:
            continue
        value, rv = getattr(table, name), raw[alias]
        if isinstance(value, Table) and isinstance(rv, dict):
            _walk(value, rv, path + [(alias, "key")], kind, physics)
        elif isinstance(value, list) and isinstance(rv, list) and len(rv) == len(value):
            if value and all(isinstance(v, Table) for v in value):
                for i, (v, r) in enumerate(zip(value, rv)):
                    if isinstance(r, dict):
                        _walk(v, r, path + [(alias, f"item {i + 1}")], kind, physics)
            elif name in coordinate:
                strings += [(name, alias, r, _kind_of(r, coordinate[name])) for r, v in zip(rv, value)
                            if isinstance(r, str) and isinstance(v, float)]
        elif isinstance(rv, str) and isinstance(value, float) and name in coordinate:
            strings.append((name, alias, rv, _kind_of(rv, coordinate[name])))
    if strings or type(table).unit_choice:
        where = _where(path + [(None, "key")], kind)
        _check_table(table, raw, strings, where, path, physics)


def _kind_of(text: str, spec) -> str:
    _, unit, kinds = spec
    return kinds[U.convert(text, unit.units)[1]]


def _check_table(table: Table, raw: dict, strings: list, where: str, path: list, physics: str | None) -> None:
    for key, (by, choices) in type(table).unit_choice.items():
        text = raw.get(key)
        if isinstance(text, str) and isinstance(getattr(table, key), float):
            field = type(table).model_fields[key]
            unit = declared_unit(field.annotation, field.metadata)
            alt = U.convert(text, unit.units)[1]
            choice = getattr(table, by)
            if alt not in choices[choice]:
                units = tuple(unit.units[i] for i in choices[choice])
                raise ModelError(where, key, text, f"{U.allowed(units)} with {by} = {choice!r} "
                                 f"({text.strip()!r} is {U.dimension(unit.units[alt]).noun})")
    if not strings:
        return
    expected, why = None, ""
    table_name = path[-1][0] if path else ""
    if physics is not None and table_name in FE_TABLES and len(path) == 1:
        if table_name == "segment" or getattr(table, "x", None) is not None or table_name in ("support", "point"):
            dof = getattr(table, "dof", None) or PRIMARY_DOF[physics]
            expected = U.R if dof in ROTATIONAL_DOFS else U.T
            why = f"the DOF {dof!r} of this {physics} model is {expected}"
    elif type(table).one_coordinate:
        _, key, text, kind = strings[0]
        expected, why = kind, f"{key} = {text!r} of the same table is {kind} (one coordinate)"
    if expected is None:
        return
    for name, key, text, got in strings:
        if got != expected:
            _, unit, kinds = _coordinate_fields(type(table))[name]
            choice = type(table).unit_choice.get(name)
            keep = choice[1][getattr(table, choice[0])] if choice else range(len(kinds))
            units = tuple(u for i, (u, k) in enumerate(zip(unit.units, kinds)) if k == expected and i in keep)
            raise ModelError(where, key, text, f"{U.allowed(units)}: {why}, {text.strip()!r} is {got}")
