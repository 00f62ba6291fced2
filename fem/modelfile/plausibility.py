"""Plausibility of a model file: values very likely written in other units than SI, or a model
outside the validity of its theory.  These are warnings (``drivefem: warning: ...``, recorded first
in the JSON ``warnings``); they never change a result.

Each names the key and its value in SI, says what is implausible and gives the likely cause -- only
when one is likely: a value written as a quantity string (``"50 mm"``) has no unit problem, so its
warning states the fact without guessing.

* **a section larger than its shaft** (FE, hybrid and rotor files): a diameter above the whole
  shaft's length, or the equivalent diameter of an explicit A, I or J above :data:`EXPLICIT_MARGIN`
  times it (explicit constants are often effective values of a scaled model, A = J = 1); with
  numbers, likely mm (``d = 50`` on a 1 m shaft, ``A = 2000`` for 2000 mm^2);
* **Euler-Bernoulli on a stubby shaft**: bending with theory "euler-bernoulli" and L/d below
  :data:`EB_SLENDERNESS` (the shear and rotary inertia it neglects matter: suggest Timoshenko), d the
  largest circle or tube -- not given where the section warning already explains the ratio;
* **a material off the range of engineering solids by orders of magnitude**: E or G outside
  [:data:`E_RANGE`] (likely MPa or GPa), rho outside [:data:`RHO_RANGE`] (likely g/cm^3 or t/mm^3) --
  for the materials of geometric sections (circle, tube) and rotors; with explicit section constants
  only the products E A, E I, G J, rho A, rho Ip enter the model, and effective values are common
  (the drill string of examples/hybrid_drill_string.toml has G = 50 Pa with J = 1 m^4: G J = 50 N m^2).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

EXPLICIT_MARGIN = 10.0
"""Explicit section constants warn above this many shaft lengths of equivalent diameter (a value in
mm^2 or mm^4 read as m^2, m^4 is 1e3 times too wide, a scaled model's A = 1 m^2 about one length)."""
EB_SLENDERNESS = 10.0
"""Smallest L/d for Euler-Bernoulli bending: below it shear deformation and rotary inertia change
the first frequency by more than ~1-2 % (Timoshenko's correction ~ (d/L)^2 times a mode factor)."""
E_RANGE = (1e6, 1.2e12)
"""Young's and shear moduli of engineering solids, Pa: elastomers (~1 MPa) to diamond (1.2 TPa)."""
RHO_RANGE = (25.0, 2.3e4)
"""Densities of engineering solids, kg/m^3: rigid foams (~25) to osmium (22 600)."""
SCALES = {"kPa": 1e3, "MPa": 1e6, "GPa": 1e9}
DENSITY_SCALES = {"g/cm^3": 1e3, "kg/mm^3": 1e9, "t/mm^3": 1e12}
TYPICAL = {"Pa": 1e11, "kg/m^3": 5e3}
"""The middle of the engineering range (log scale): of several units that would put a value in range,
the one nearest to it is suggested (E = 210: GPa, not MPa)."""


class PlausibilityWarning(UserWarning):
    """A model-file value very likely in other units than SI, or outside the model's theory."""


@dataclass
class Plausibility:
    """The warnings of a model file; ``units_suspect``: some value is likely in other units than SI
    (then a precision problem of the analysis is not blamed on the mesh)."""

    warnings: list[str] = field(default_factory=list)
    units_suspect: bool = False


def check(doc, raw: dict, kind: str) -> Plausibility:
    """The plausibility warnings of a validated document (``raw``: the dict it came from)."""
    out = Plausibility()
    if kind in ("fe", "hybrid"):
        geometric = [s.section.shape in ("circle", "tube") for s in doc.segment]
        tables = [(f"[[segment]] #{i} material", s.material, _get(raw, "segment", i - 1, "material"))
                  for i, (s, g) in enumerate(zip(doc.segment, geometric), 1) if g]
        uses_defaults = any(g and (s.material is None or not {"E", "rho"} <= s.material.model_fields_set)
                            for s, g in zip(doc.segment, geometric))
        if uses_defaults:                         # [material] gives some geometric segment its E or rho
            tables.insert(0, ("[material]", doc.material, raw.get("material")))
        _materials(out, tables)
        _fe_sections(out, doc, raw)
    elif kind == "rotor":
        r, rr = doc.rotor, raw.get("rotor", {})
        _materials(out, [("[rotor.material]", r.material, rr.get("material"))]
                   + [(f"[[rotor.segment]] #{i} material", s.material, _get(rr, "segment", i - 1, "material"))
                      for i, s in enumerate(r.segment, 1)])
        _rotor_sections(out, doc, rr)
    return out


def _get(raw, *path):
    for p in path:
        try:
            raw = raw[p]
        except (KeyError, IndexError, TypeError):
            return None
    return raw


def _written(raw, key) -> bool:
    """Whether ``key`` was written as a plain number (a quantity string carries its own unit)."""
    return isinstance(raw, dict) and isinstance(raw.get(key), (int, float)) and not isinstance(raw.get(key), bool)


def _number(v: float) -> str:
    return f"{v:g}"


def _materials(out: Plausibility, tables) -> None:
    for where, mat, raw in tables:
        if mat is None:
            continue
        for key, name in (("E", "Young's modulus"), ("G", "shear modulus")):
            v = getattr(mat, key, None)
            if v is not None and not E_RANGE[0] <= v <= E_RANGE[1]:
                _off_range(out, where, key, v, raw, "Pa", E_RANGE, SCALES, f"the {name} of engineering solids")
        rho = getattr(mat, "rho", None)
        if rho is not None and rho > 0 and not RHO_RANGE[0] <= rho <= RHO_RANGE[1]:
            _off_range(out, where, "rho", rho, raw, "kg/m^3", RHO_RANGE, DENSITY_SCALES,
                       "the densities of engineering solids")


def _off_range(out, where, key, v, raw, unit, rng, scales, what) -> None:
    side = "below" if v < rng[0] else "above"
    text = (f"{where}: {key} = {_number(v)} {unit} is far {side} {what} ({_number(rng[0])} to {_number(rng[1])} "
            f"{unit})")
    if _written(raw, key) and v < rng[0]:
        fits = [u for u, f in scales.items() if rng[0] <= v * f <= rng[1]]
        if fits:
            likely = min(fits, key=lambda u: abs(math.log10(v * scales[u] / TYPICAL[unit])))
            written = raw[key]
            text += f": is it in {likely}? drivefem reads plain numbers in SI; write {key} = \"{written:g} {likely}\""
            out.units_suspect = True
    out.warnings.append(text)


def _equivalent_diameters(section) -> list[tuple[str, float, str]]:
    """(key, equivalent diameter, unit of the hint) of a section's given constants."""
    if section.shape in ("circle", "tube"):
        return [("d", section.d, "mm")]
    out = []
    if section.A is not None:
        out.append(("A", math.sqrt(4 * section.A / math.pi), "mm^2"))
    if section.I is not None:
        out.append(("I", (64 * section.I / math.pi) ** 0.25, "mm^4"))
    for k in ("J", "Ip"):
        if getattr(section, k) is not None:
            out.append((k, (32 * getattr(section, k) / math.pi) ** 0.25, "mm^4"))
    return out


def _section_warning(out, where, key, value, d_eq, hint_unit, length, raw, margin: float = 1.0) -> bool:
    if d_eq <= margin * length:
        return False
    size = f"{key} = {_number(value)} {'m' if key in ('d', 'di', 'd_end', 'di_end') else hint_unit.replace('mm', 'm')}"
    eq = "" if key in ("d", "di", "d_end", "di_end") else f" (a section of equivalent diameter {d_eq:.3g} m)"
    text = f"{where}: {size}{eq} on a {_number(length)} m shaft: the section is larger than the whole shaft"
    if _written(raw, key):
        text += (f"; is the {'diameter' if key.startswith('d') else 'section constant'} in {hint_unit}? drivefem "
                 f"reads plain numbers in SI; write {key} = \"{raw[key]:g} {hint_unit}\"")
        out.units_suspect = True
    else:
        text += " (outside beam theory)"
    out.warnings.append(text)
    return True


def _fe_sections(out: Plausibility, doc, raw: dict) -> None:
    length = sum(s.length for s in doc.segment)
    d_max, large = 0.0, False
    for i, s in enumerate(doc.segment, 1):
        sec_raw = _get(raw, "segment", i - 1, "section")
        for key, d_eq, unit in _equivalent_diameters(s.section):
            if s.section.shape in ("circle", "tube"):      # explicit constants: often a scaled model's
                d_max = max(d_max, d_eq)
            margin = 1.0 if s.section.shape in ("circle", "tube") else EXPLICIT_MARGIN
            large |= _section_warning(out, f"[[segment]] #{i} section", key, getattr(s.section, key), d_eq, unit,
                                      length, sec_raw, margin)
    m = doc.model
    if (m.physics == "bending" and m.theory == "euler-bernoulli" and not large and d_max > 0
            and length / d_max < EB_SLENDERNESS):
        out.warnings.append(
            f"[model]: theory = 'euler-bernoulli' on a shaft of slenderness L/d = {length / d_max:.3g} ({_number(length)} "
            f"m / {_number(d_max)} m): Euler-Bernoulli beams neglect shear and rotary inertia and need L/d > "
            f"{EB_SLENDERNESS:g}; use theory = \"timoshenko\"")


def _rotor_sections(out: Plausibility, doc, rr: dict) -> None:
    length = sum(s.length for s in doc.rotor.segment)
    for i, s in enumerate(doc.rotor.segment, 1):
        seg_raw = _get(rr, "segment", i - 1)
        for key in ("d", "d_end"):
            v = getattr(s, key)
            if v is not None:
                _section_warning(out, f"[[rotor.segment]] #{i}", key, v, v, "mm", length, seg_raw)
