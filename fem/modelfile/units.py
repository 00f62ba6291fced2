"""Units of model-file keys: the catalogue of declared units and the conversion of quantity strings.

Every numeric key declares its unit in the schema (``E: Positive["Pa"]``, see
:mod:`.schema.base`).  In a model file a value is either a plain number in that unit (SI, except keys
whose name says otherwise: ``*_rpm``, ``*_deg``, ``*_hz``) or a quantity string such as ``"50 mm"``,
``"210 GPa"``, ``"3000 rpm"``, converted here once, when the file is read.  The units are pint's
(https://pint.readthedocs.io); pint is imported on the first quantity string only, so a file of plain
numbers never pays its import (about 0.3 s with its registry).  Each unit's factor is the shortest
decimal of pint's and products are exact fractions, so a decimal unit converts exactly: "50 mm" is
0.05 and "8 g/cm^3" is 8000.0, the doubles an SI file would hold.

Rules beyond plain dimensional analysis (radians are dimensionless in pint, so these are decided here):

* **cycles and radians** -- for a key in rad/s, Hz or rpm a unit without an angle counts cycles:
  ``"50 Hz"`` is 2 pi 50 rad/s, ``"1200 1/min"`` is 1200 rev/min (the engineer's min^-1), and
  ``"314.16 rad/s"`` in a Hz key is 50 Hz;
* **angles** -- a key that is an angle (rad, deg) needs an angle unit (rad, deg, rev, turn); a unit
  with an angle is refused where the key has none (``"3000 rpm"`` is not a rate in 1/s);
  an angle may be left implicit where the key divides by it (``"500 N*m"`` for N m/rad);
* **no offsets, no temperatures** -- no key is a temperature: degC/degF are refused;
* **strict syntax** -- a decimal number, then a unit: names with optional exponents (``^2``, ``**-1``,
  ``²``, ``^1.5``, ``^(10/9)``), joined by ``*``, ``·`` or a space, at most one ``/`` followed by one
  factor (``"kg/(m*s)"``, not ``"kg/m/s"`` or ``"kg/m s"``, as the SI brochure writes them); pint's
  own parser would also take ``"5,5 mm"`` (as 55 mm) or ``"2**2**40 m"``, which are refused here.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache

MAX_MAGNITUDE = 1e100
"""Largest magnitude of a converted value, and 1 / it the smallest nonzero one (as for numbers,
:data:`fem.modelfile.source.MAX_MAGNITUDE`)."""
MAX_LENGTH = 80
"""Longest quantity string."""


@dataclass(frozen=True)
class Dimension:
    """A declared unit: ``unit`` in pint syntax (also the catalogue key), what it measures (``noun``),
    an ``example`` quantity in another unit, and for coordinate-dependent keys the ``kind`` of
    coordinate the unit belongs to ("translational" or "rotational")."""

    unit: str
    noun: str
    example: str
    kind: str | None = None

    @property
    def display(self) -> str:
        return display(self.unit)


T, R = "translational", "rotational"
_CATALOGUE = (
    Dimension("1", "a dimensionless number", "5 %"),
    Dimension("m", "a length", "50 mm", T),
    Dimension("m^2", "an area", "20 cm^2"),
    Dimension("m^4", "a second moment of area", "30 cm^4"),
    Dimension("rad", "an angle", "30 deg", R),
    Dimension("deg", "an angle in degrees", "0.5 rad"),
    Dimension("1/m", "a sharpness per length", "1 1/mm", T),
    Dimension("1/rad", "a sharpness per angle", "1 1/deg", R),
    Dimension("s", "a time", "20 ms"),
    Dimension("1/s", "a rate", "0.5 1/ms"),
    Dimension("1/s^2", "a rate squared", "1 1/ms^2"),
    Dimension("rad^2/s^2", "an eigenvalue omega^2", "1e4 rad^2/s^2"),
    Dimension("rad/s", "an angular speed", "3000 rpm", R),
    Dimension("Hz", "a frequency", "1.2 kHz"),
    Dimension("rpm", "a speed in rev/min", "314.16 rad/s"),
    Dimension("m/s", "a velocity", "20 mm/s", T),
    Dimension("m/s^2", "an acceleration", "981 cm/s^2"),
    Dimension("kg", "a mass", "500 g", T),
    Dimension("kg*m^2", "a moment of inertia", "500 kg*cm^2", R),
    Dimension("kg/s", "a mass rate", "50 g/s", T),
    Dimension("kg*m^2/s", "a moment-of-inertia rate", "5 kg*cm^2/s", R),
    Dimension("kg/m", "a mass per length", "500 g/m", T),
    Dimension("kg*m^2/m", "a polar inertia per length", "50 kg*cm^2/m", R),
    Dimension("kg/m^3", "a density", "7.85 g/cm^3"),
    Dimension("kg*m", "a mass times an eccentricity (unbalance)", "50 g*mm", T),
    Dimension("kg*m^2*rad", "an inertia times an angle (rotational unbalance)", "50 kg*cm^2*deg", R),
    Dimension("Pa", "a pressure", "210 GPa"),
    Dimension("Pa*s", "a dynamic viscosity", "20 mPa*s"),
    Dimension("N/m^1.5", "a Hertz point-contact constant", "1e4 N/mm^1.5"),
    Dimension("N/m^(10/9)", "a line-contact constant", "1e8 N/mm^(10/9)"),
    Dimension("N", "a force", "2 kN", T),
    Dimension("N*m", "a torque", "1.5 kN*m", R),
    Dimension("W", "a power", "1.5 MW"),
    Dimension("N/m", "a stiffness", "20 kN/mm", T),
    Dimension("N*m/rad", "a torsional stiffness", "5 kN*m/rad", R),
    Dimension("N*m/m", "a torque per length", "5 N*m/mm", R),
    Dimension("N/m^3", "a cubic stiffness", "2 N/mm^3", T),
    Dimension("N*m/rad^3", "a cubic torsional stiffness", "2 kN*m/rad^3", R),
    Dimension("N*m^2", "a torsional rigidity G Ip", "5 kN*m^2"),
    Dimension("N*s/m", "a damping coefficient", "50 N*s/mm", T),
    Dimension("N*m*s/rad", "a torsional damping coefficient", "2 N*m*s/rad", R),
    Dimension("N*s^2/m^2", "a quadratic friction coefficient", "1 N*s^2/mm^2", T),
    Dimension("N*m*s^2/rad^2", "a quadratic rotational friction coefficient", "1 N*m*s^2/rad^2", R),
    Dimension("N*s^3/m^3", "a cubic friction coefficient", "1 N*s^3/mm^3", T),
    Dimension("N*m*s^3/rad^3", "a cubic rotational friction coefficient", "1 N*m*s^3/rad^3", R),
    Dimension("1/(N*m)", "a motor characteristic slope 1/torque", "0.01 1/(kN*m)"),
    Dimension("m/rad", "a length per angle (a radius as ratio)", "50 mm/rad"),
    Dimension("rad/m", "an angle per length", "2 rad/mm"),
)
DIMENSIONS: dict[str, Dimension] = {d.unit: d for d in _CATALOGUE}
"""The declared units (pint syntax, as written in the schema) with their names and examples."""
FREQUENCY_UNITS = ("rad/s", "Hz", "rpm")
"""Keys in these units count cycles for a unit without an angle (module docstring)."""
COMMON = ("m", "mm", "cm", "km", "um", "in", "ft", "kg", "g", "t", "lb", "s", "ms", "min", "h", "N", "kN", "MN",
          "Pa", "kPa", "MPa", "GPa", "bar", "psi", "rad", "deg", "rev", "turn", "rpm", "rps", "Hz", "kHz", "%")
"""Units suggested for a misspelt one."""


def display(unit: str) -> str:
    """A declared unit as written in messages and docs: "N*m/rad" -> "N m/rad"."""
    return unit.replace("*", " ")


def dimension(unit: str) -> Dimension:
    """The catalogue entry of a declared unit (KeyError names the missing declaration)."""
    try:
        return DIMENSIONS[unit]
    except KeyError:
        raise KeyError(f"unit {unit!r} is not in the catalogue fem.modelfile.units.DIMENSIONS: add it "
                       "there with its name and an example") from None


def allowed(units: tuple[str, ...], bounds: str = "") -> str:
    """What a key of the declared ``units`` takes: 'a pressure (Pa) > 0, e.g. "210 GPa"' (``bounds``:
    the key's bounds on the value in its unit, "> 0")."""
    parts = [d.noun if d.unit == "1" else f"{d.noun} ({d.display})" for d in map(dimension, units)]
    return " or ".join(parts) + (f" {bounds}" if bounds else "") + f', e.g. "{dimension(units[0]).example}"'


def coordinate_kinds(units: tuple[str, ...]) -> tuple[str | None, ...] | None:
    """The coordinate kind of each alternative if the key depends on the coordinate (its alternatives
    include a translational and a rotational unit and nothing else), else None."""
    kinds = tuple(dimension(u).kind for u in units)
    return kinds if None not in kinds and {T, R} <= set(kinds) else None


class UnitError(ValueError):
    """A quantity string that is not valid for its key; ``reason`` says why in a few words."""

    def __init__(self, reason: str, parsed: bool):
        super().__init__(reason)
        self.reason, self.parsed = reason, parsed


# ------------------------------------------------------------------ parsing (pint imported here only)
@lru_cache(maxsize=1)
def registry():
    """pint's unit registry (imported and built on first use, ~0.3 s), with ``rev`` for revolution."""
    import pint

    ureg = pint.UnitRegistry(cache_folder=None)
    ureg.define("rev = revolution")
    return ureg


_NUMBER = re.compile(r"\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)")
_SUPERSCRIPT = str.maketrans("⁺⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "+-0123456789")
_TOKEN = re.compile(r"\s*(?:(?P<exp>(?:\^|\*\*)\s*(?:[+-]?\d{1,2}(?:\.\d{1,3})?(?![\d.])"
                    r"|\(\s*[+-]?\d{1,2}\s*/\s*\d{1,2}\s*\))|[⁺⁻]?[⁰¹²³⁴⁵⁶⁷⁸⁹]{1,2})"
                    r"|(?P<name>[A-Za-zµμΩ°%][A-Za-z_µμΩ°]*)|(?P<one>1)(?=\s*/)|(?P<op>[*·/()]))")


def _tokens(text: str) -> list[tuple[str, str]]:
    out, pos = [], 0
    while pos < len(text):
        if text[pos:].strip() == "":
            break
        m = _TOKEN.match(text, pos)
        if m is None or m.end() == pos:
            bad = text[pos:].strip()[:12]
            raise UnitError(f"cannot read {bad!r} as part of a unit", False)
        kind = m.lastgroup
        tok = m.group(kind)
        if kind == "exp":
            tok = tok.translate(_SUPERSCRIPT).lstrip("^*").strip().strip("()").replace(" ", "")
        out.append((kind, tok))
        pos = m.end()
    return out


class _Parser:
    """unit := term ['/' factor];  term := '1' | factor {['*' | '·'] factor};
    factor := (name | '(' unit ')') [exponent].

    Each rule returns (pint unit, its factor to pint's root units as an exact Fraction): a unit name's
    factor is the shortest decimal of pint's float (mm: 1/1000, g/cm^3: 1000 exactly, where pint's
    float arithmetic gives 999.9999999999999), so that "8 g/cm^3" is 8000.0 and "50 mm" is 0.05, the
    doubles an SI file would hold."""

    def __init__(self, tokens, ureg):
        self.t, self.i, self.u = tokens, 0, ureg

    def peek(self):
        return self.t[self.i] if self.i < len(self.t) else (None, None)

    def take(self):
        tok = self.peek()
        self.i += 1
        return tok

    def unit(self):
        num = self.term()
        kind, tok = self.peek()
        if tok == "/":
            self.take()
            den = self.factor()
            kind, tok = self.peek()
            if tok in ("/", "*", "·") or kind in ("name",) or tok == "(":
                raise UnitError("after '/' one factor only: write the denominator in parentheses, "
                                "e.g. \"kg/(m*s)\"", False)
            num = (num[0] / den[0], num[1] / den[1])
        return num

    def term(self):
        kind, tok = self.peek()
        if kind == "one":
            self.take()
            return self.u.dimensionless, Fraction(1)
        out = self.factor()
        while True:
            kind, tok = self.peek()
            if tok in ("*", "·"):
                self.take()
            elif not (kind == "name" or tok == "("):
                return out
            f = self.factor()
            out = (out[0] * f[0], out[1] * f[1])

    def factor(self):
        kind, tok = self.take()
        if kind == "name":
            out = self._name(tok)
        elif tok == "(":
            out = self.unit()
            if self.take()[1] != ")":
                raise UnitError("unbalanced parentheses", False)
        else:
            raise UnitError("a unit name expected" + (f" before {tok!r}" if tok else " (the unit is missing)"),
                            False)
        kind, tok = self.peek()
        if kind == "exp":
            self.take()
            e = Fraction(tok)
            if e.denominator == 1:
                out = (out[0] ** int(e), out[1] ** int(e))
            else:                                   # a fractional power (Hertz contact: m^1.5)
                out = (out[0] ** float(e), Fraction(float(out[1]) ** float(e)))
        return out

    def _name(self, name: str):
        import pint

        try:
            unit = self.u.Unit(name)
            return unit, Fraction(repr(float(self.u.get_root_units(unit)[0])))
        except (pint.errors.UndefinedUnitError, AttributeError, ValueError, TypeError):
            import difflib

            near = [c for c in COMMON if c.lower() == name.lower()] or difflib.get_close_matches(name, COMMON, n=1)
            hint = f"; did you mean {near[0]!r}?" if near else ""
            raise UnitError(f"unknown unit {name!r}{hint}", False) from None


@lru_cache(maxsize=4096)
def parse(text: str):
    """(magnitude, pint unit) of a quantity string, the magnitude an exact Fraction in pint's root
    units; :class:`UnitError` if it is not one."""
    if len(text) > MAX_LENGTH:
        raise UnitError(f"a quantity string of at most {MAX_LENGTH} characters", False)
    m = _NUMBER.match(text)
    if m is None:
        raise UnitError("a quantity is a number followed by a unit", False)
    if not math.isfinite(float(m.group(1))):
        raise UnitError("the number is not finite", False)
    magnitude = Fraction(m.group(1))
    toks = _tokens(text[m.end():])
    if not toks:
        raise UnitError("the unit is missing (a plain number is written without quotes)", False)
    ureg = registry()
    p = _Parser(toks, ureg)
    unit, factor = p.unit()
    if p.i != len(toks):
        raise UnitError(f"cannot read {toks[p.i][1]!r} here", False)
    if "[temperature]" in unit.dimensionality:
        raise UnitError(f"{text.strip()!r} is a temperature, which no key takes: offset units such as degC, "
                        "degF are refused", True)
    return magnitude * factor, unit


def _radian_power(unit) -> float:
    return registry().get_root_units(unit)[1]._units.get("radian", 0)


@lru_cache(maxsize=None)
def _declared(unit: str):
    """(pint unit, exact factor to pint's root units) of a declared unit."""
    if unit == "1":
        return registry().dimensionless, Fraction(1)
    return _Parser(_tokens(unit), registry()).unit()


def _target(unit: str):
    return _declared(unit)[0]


def _value_in(root: Fraction, unit, target: str) -> Fraction | None:
    """The quantity (``root``: its magnitude in pint's root units) in ``target`` (a declared unit), or
    None if its dimension is not that of the key."""
    p = _radian_power(unit)
    if target in FREQUENCY_UNITS:
        if unit.dimensionality != _target("1/s").dimensionality:
            return None
        per = {"rad/s": "rad/s", "Hz": "turn/s", "rpm": "rpm"} if p == 1 else \
              {"rad/s": "1/(turn*s)", "Hz": "1/s", "rpm": "1/min"} if p == 0 else None
        if per is None:
            return None                             # p == 1: radians per time; p == 0: cycles per time
        return root / _declared(per[target])[1]
    t, factor = _declared(target)
    if unit.dimensionality != t.dimensionality:
        return None
    pt = _radian_power(t)
    if pt != 0 and t.dimensionless and p != pt:     # an angle key needs an angle unit
        return None
    if p != 0 and p != pt:                          # an angle where the key has none
        return None
    return root / factor


def _what(unit) -> str:
    """What a parsed unit measures, in the catalogue's words if it is there."""
    p = _radian_power(unit)
    for d in _CATALOGUE:
        t = _target(d.unit)
        if t.dimensionality == unit.dimensionality and _radian_power(t) == p:
            return d.noun
    dim = str(unit.dimensionality)
    return "dimensionless" if dim == "dimensionless" else dim


@lru_cache(maxsize=4096)
def convert(text: str, units: tuple[str, ...]) -> tuple[float, int]:
    """``text`` in the first of the declared ``units`` its dimension fits, and that unit's index.

    Raises :class:`UnitError` for a string that is not a quantity, a quantity of another dimension,
    or a value beyond :data:`MAX_MAGNITUDE`."""
    root, unit = parse(text)
    for i, target in enumerate(units):
        exact = _value_in(root, unit, target)
        if exact is not None:
            try:
                value = float(exact)
            except OverflowError:
                value = math.inf if exact > 0 else -math.inf
            if value != 0 and not (1 / MAX_MAGNITUDE <= abs(value) <= MAX_MAGNITUDE):
                raise UnitError(f"{value:.3g} {display(target)} is beyond any physical scale (magnitudes "
                                f"{1 / MAX_MAGNITUDE:g} to {MAX_MAGNITUDE:g})", True)
            return value, i
    hint = " (write N*m for newton metres: pint reads 'Nm' as nano-metres or 'kNm' as kilo-number-metres)" \
        if re.search(r"Nm\b", text) else ""
    raise UnitError(f"{text.strip()!r} is {_what(unit)}{hint}", True)
