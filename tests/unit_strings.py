"""Model files rewritten with quantity strings, programmatically (for the tests and the fuzzer).

:func:`rewrite` replaces every number of a declared dimension in a model file by the same value as a
quantity string in a non-SI unit of that dimension (``length = 1.5`` -> ``"1500.0 mm"``, ``E = 2.1e11``
-> ``"210000.0 MPa"``, ``speed_rpm = 3000`` -> ``"314.159... rad/s"``), walking the document along its
validated schema, so that every declared key of every kind is covered without a list of keys here.
A coordinate-dependent key gets the unit of its coordinate where the model says it (FE tables: the
DOF's kind), else the translational one (a lumped body's coordinate is not declared; the numbers are
the same).
"""
from __future__ import annotations

import copy
import math
from decimal import Decimal, localcontext
from fractions import Fraction

from fem.modelfile import parse
from fem.modelfile import units as U
from fem.modelfile.coordinates import FE_TABLES, PRIMARY_DOF, ROTATIONAL_DOFS
from fem.modelfile.load import kind_of
from fem.modelfile.schema.base import Table, declared_unit

NON_SI = {
    "1": "%", "m": "mm", "m^2": "cm^2", "m^4": "mm^4", "rad": "deg", "deg": "rad", "1/m": "1/mm",
    "1/rad": "1/deg", "s": "ms", "1/s": "1/min", "1/s^2": "1/min^2", "rad^2/s^2": "deg^2/s^2",
    "rad/s": "rpm", "Hz": "rpm", "rpm": "rad/s", "m/s": "mm/s", "m/s^2": "mm/s^2", "kg": "g",
    "kg*m^2": "g*cm^2", "kg/s": "g/s", "kg*m^2/s": "g*cm^2/s", "kg/m": "g/mm", "kg*m^2/m": "g*cm^2/mm",
    "kg/m^3": "g/cm^3", "kg*m": "g*mm", "kg*m^2*rad": "g*cm^2*deg", "Pa": "MPa", "N": "kN", "N*m": "kN*m", "W": "kW",
    "N/m": "N/mm", "N*m/rad": "N*m/deg", "N*m/m": "N*m/mm", "N/m^3": "N/mm^3", "N*m/rad^3": "N*m/deg^3",
    "N*m^2": "kN*mm^2", "N*s/m": "N*s/mm", "N*m*s/rad": "N*m*s/deg", "N*s^2/m^2": "N*s^2/mm^2",
    "N*m*s^2/rad^2": "N*m*s^2/deg^2", "N*s^3/m^3": "N*s^3/mm^3", "N*m*s^3/rad^3": "N*m*s^3/deg^3",
    "1/(N*m)": "1/(kN*m)", "m/rad": "mm/deg", "rad/m": "deg/mm", "Pa*s": "mPa*s", "N/m^1.5": "N/mm^1.5",
    "N/m^(10/9)": "N/mm^(10/9)",
}
"""A non-SI unit of the same dimension for every declared unit."""
def quantity(value: float, unit: str, exact: bool = False) -> str:
    """``value`` (in the declared ``unit``) as a string in :data:`NON_SI` of it: the magnitude as the
    nearest double, or (``exact``) with 25 digits, which the loader converts back to ``value`` bit for
    bit.  The factor is the loader's own (exact rational, cycles rule included)."""
    target = NON_SI[unit]
    root, parsed = U.parse(f"1 {target}")
    per_target = U._value_in(root, parsed, unit)        # declared units in one target unit, exact
    magnitude = Fraction(value) / per_target
    if exact:
        with localcontext() as ctx:
            ctx.prec = 30
            text = format(Decimal(magnitude.numerator) / Decimal(magnitude.denominator), ".25g")
        return f"{text} {target}"
    return f"{float(magnitude)!r} {target}"


def rewrite(raw: dict, exact: bool = False) -> tuple[dict, int]:
    """A copy of the model file ``raw`` with every number of a declared dimension written as a
    quantity string in another unit, and the number of values rewritten; ``exact``: strings that
    convert back to the very same doubles (then every result is bit-identical)."""
    model = parse(raw)
    kind = kind_of(model)
    physics = model.model.physics if kind in ("fe", "hybrid") else None
    out = copy.deepcopy(raw)
    return out, _walk(model, out, [], physics, exact)


def _coordinate_kind(table: Table, path: list, physics: str | None) -> str:
    name = path[-1] if path else ""
    if physics is not None and name in FE_TABLES and len(path) == 1:
        dof = getattr(table, "dof", None) or PRIMARY_DOF[physics]
        return U.R if dof in ROTATIONAL_DOFS else U.T
    return U.T


def _pick(table: Table, key: str, units: tuple[str, ...], path: list, physics) -> str:
    kinds = U.coordinate_kinds(units)
    allowed = range(len(units))
    choice = type(table).unit_choice.get(key)
    if choice is not None:
        allowed = choice[1][getattr(table, choice[0])]
    if kinds is None:
        return units[allowed[0]]
    want = _coordinate_kind(table, path, physics)
    return next(units[i] for i in allowed if kinds[i] == want)


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _walk(table: Table, raw: dict, path: list, physics, exact: bool) -> int:
    n = 0
    for name, f in type(table).model_fields.items():
        key = f.alias or name
        if key not in raw:
            continue
        value, rv = getattr(table, name), raw[key]
        if isinstance(value, Table):
            n += _walk(value, rv, path + [key], physics, exact)
            continue
        if isinstance(value, list) and value and all(isinstance(v, Table) for v in value):
            for v, r in zip(value, rv):
                n += _walk(v, r, path + [key], physics, exact)
            continue
        unit = declared_unit(f.annotation, f.metadata)
        if unit is None or unit.kind != "quantity":
            continue
        target = _pick(table, name, unit.units, path, physics)
        if _is_number(rv) and isinstance(value, float):
            raw[key] = quantity(float(rv), target, exact)
            n += 1
        elif isinstance(rv, list) and all(_is_number(x) for x in rv):
            raw[key] = [quantity(float(x), target, exact) for x in rv]
            n += len(rv)
    return n
