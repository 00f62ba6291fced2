"""Units in model files: every numeric key declares its unit, quantity strings ("50 mm", "3000 rpm",
"210 GPa") are converted once (pint, imported only when a file has one), wrong dimensions and bad
strings are one-line errors, coordinate-dependent keys are checked against the model, and the
plausibility warnings name the likely cause (values not in SI) without a wrong diagnosis."""
from __future__ import annotations

import json
import math
import re
import subprocess
import sys
import tomllib
import warnings
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp
from pydantic import Field

from discrete.errors import ModelError
from fem.modelfile import load, parse
from fem.modelfile import units as U
from fem.modelfile.reference import _tables
from fem.modelfile.schema.base import Count, Positive, Real, Table, Unit, numeric_leaves
from fem.modelfile.schema.document import KINDS
from fem.study import Study
from tests.unit_strings import NON_SI, rewrite

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))
UNITS_EXAMPLE = ROOT / "examples" / "cantilever_units.toml"


def example(name: str) -> dict:
    return tomllib.loads((ROOT / "examples" / name).read_text())


# ------------------------------------------------------------------ declarations
def undeclared(models) -> list[str]:
    """Every number of the given tables (and their sub-tables) without a declared unit."""
    seen: dict = {}
    for cls in models:
        seen[cls.__name__] = cls
        _tables(cls, "", seen)
    return [f"{label}.{name} ({typ.__name__})" for label, model in seen.items()
            for name, f in model.model_fields.items()
            for typ, meta in numeric_leaves(f.annotation, f.metadata) if not any(isinstance(m, Unit) for m in meta)]


def test_every_numeric_key_of_every_kind_declares_its_unit():
    """A new numeric field must say its unit (Positive["Pa"], Real["m", "rad"], Count, Integer(..)):
    this is the test that fails when one does not."""
    missing = undeclared(KINDS.values())
    assert not missing, "declare the unit of: " + ", ".join(missing)


def test_the_declaration_test_can_fail():
    class Undeclared(Table):
        a: Positive = 1.0
        b: float = 0.0
        c: list[int] = []
        d: Positive | None = None
        ok: Positive["m"] = 1.0
        n: Count = 1
        word: str = ""

    assert [m.split(" ")[0] for m in undeclared([Undeclared])] == ["Undeclared.a", "Undeclared.b", "Undeclared.c",
                                                                  "Undeclared.d"]
    assert Undeclared(a=2.0, d=3.0).a == 2.0              # the undeclared types still validate


def test_catalogue_units_parse_and_their_examples_convert():
    for unit, dim in U.DIMENSIONS.items():
        value, alt = U.convert(dim.example, (unit,))
        assert alt == 0 and math.isfinite(value) and value != 0, unit
        assert unit in NON_SI, f"tests/unit_strings.NON_SI needs a non-SI unit for {unit}"
    with pytest.raises(KeyError, match="not in the catalogue"):
        Unit("furlong/fortnight")


# ------------------------------------------------------------------ conversions
@pytest.mark.parametrize("text,units,expected", [
    ("50 mm", ("m",), 0.05),
    ("210 GPa", ("Pa",), 210e9),
    ("7.85 g/cm^3", ("kg/m^3",), 7850.0),
    ("3000 rpm", ("rad/s",), 100 * math.pi),
    ("1200 1/min", ("rad/s",), 40 * math.pi),          # min^-1 counts revolutions (cycles rule)
    ("50 Hz", ("rad/s",), 100 * math.pi),
    ("314.1592653589793 rad/s", ("Hz",), 50.0),
    ("3000 rpm", ("Hz",), 50.0),
    ("3000 rpm", ("rpm",), 3000.0),                    # *_rpm keys: a string is converted to rpm
    ("314.1592653589793 rad/s", ("rpm",), 3000.0),
    ("1200 1/min", ("rpm",), 1200.0),
    ("0.5 deg", ("rad",), math.pi / 360),
    ("0.25 rev", ("deg",), 90.0),                      # *_deg keys: to degrees
    ("1 turn", ("rad",), 2 * math.pi),
    ("5 %", ("1",), 0.05),
    ("500 N*m", ("N*m/rad",), 500.0),                  # the angle of a stiffness may stay implicit
    ("5 N m/deg", ("N*m/rad",), 5 * 180 / math.pi),
    ("2 kN·m", ("N", "N*m"), 2000.0),
    ("2 kg*m²", ("kg", "kg*m^2"), 2.0),
    ("20 kN/mm", ("N/m",), 2e7),
    ("0.01 1/(kN*m)", ("1/(N*m)",), 1e-5),
    ("5 s⁻¹", ("Hz",), 5.0),
    ("-5 mm", ("m",), -0.005),
    (".5 mm", ("m",), 0.0005),
    ("1e-400 m", ("m",), 0.0),                         # underflows to an exact 0, as the number would
])
def test_conversions(text, units, expected):
    value, _ = U.convert(text, units)
    assert value == pytest.approx(expected, rel=1e-14, abs=1e-300)


def test_the_alternative_that_fits_is_chosen():
    assert U.convert("3 kN m", ("N", "N*m")) == (3000.0, 1)
    assert U.convert("3 kN", ("N", "N*m")) == (3000.0, 0)


@pytest.mark.parametrize("text,units,reason", [
    ("50 mm", ("Pa",), "'50 mm' is a length"),
    ("5 deg", ("1",), "is an angle"),                  # an angle where the key has none
    ("3000 rpm", ("1/s",), "is an angular speed"),
    ("0.5 %", ("rad",), "dimensionless"),              # an angle key needs an angle unit
    ("0.5", ("rad",), "the unit is missing"),
    ("210 Gpa", ("Pa",), "unknown unit 'Gpa'; did you mean 'GPa'?"),
    ("20 degC", ("m",), "temperature"),                # offsets refused
    ("20 degF", ("Pa",), "temperature"),
    ("300 K", ("m",), "temperature"),
    ("1e400 mm", ("m",), "not finite"),                # huge exponents
    ("1e200 mm", ("m",), "beyond any physical scale"),
    ("nan m", ("m",), "a number followed by a unit"),
    ("inf m", ("m",), "a number followed by a unit"),
    ("5,5 mm", ("m",), "cannot read ',5 mm'"),             # pint alone would read 55 mm
    ("2**2**40 m", ("m",), "a unit name expected"),    # pint alone would compute the power
    ("5 kg/m/s", ("kg/m^3",), "one factor only"),
    ("5 kg/m s", ("kg/m^3",), "one factor only"),
    ("5 m^2.5", ("m",), "is [length] ** 2.5"),        # fractional powers are read (Hertz contact: m^1.5)
    ("5 mm)", ("m",), "cannot read ')'"),
    ("5 (mm", ("m",), "unbalanced parentheses"),
    ("3 kNm", ("N*m",), "write N*m"),
    ("", ("m",), "a number followed by a unit"),
    ("5 " + "m*" * 60 + "m", ("m",), "at most 80 characters"),
])
def test_bad_quantity_strings(text, units, reason):
    with pytest.raises(U.UnitError, match=re.escape(reason)):
        U.convert(text, units)


# ------------------------------------------------------------------ in model files
def test_error_names_table_key_value_and_expected_dimension():
    doc = example("cantilever.toml")
    doc["material"]["E"] = "50 mm"
    with pytest.raises(ModelError) as exc:
        parse(doc)
    assert str(exc.value) == ("[material]: E = '50 mm' is not valid; allowed: a pressure (Pa) > 0, e.g. \"210 GPa\" "
                              "('50 mm' is a length)")
    doc["material"]["E"] = "-5 GPa"                                  # bounds apply to the converted value
    with pytest.raises(ModelError, match=r"E = '-5 GPa' .*> 0.*'-5 GPa' is -5e\+09 Pa"):
        parse(doc)
    doc = example("cantilever.toml")
    doc["segment"][0]["section"]["d"] = "50 mN"
    with pytest.raises(ModelError, match=r"\[\[segment\]\] #1 section: d = '50 mN' .*a length \(m\) > 0.*a force"):
        parse(doc)


def test_cli_refuses_a_wrong_dimension_in_one_line(tmp_path, capsys):
    from fem.app.cli import main

    text = (ROOT / "examples" / "cantilever.toml").read_text().replace("rho = 7810", 'rho = "7.81 kg/m"')
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert main(["modal", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["drivefem: error: [material]: rho = '7.81 kg/m' is not valid; allowed: a density (kg/m^3) > 0, "
                   "e.g. \"7.85 g/cm^3\" ('7.81 kg/m' is a mass per length)"]


def test_a_word_or_a_quantity():
    """Keys that take words or numbers (friction normal = "weight" or a force): a misspelt word is
    reported as such, a quantity of the wrong dimension as that."""
    doc = example("discrete_coulomb_decay.toml")
    doc["friction"][0].pop("kinetic")
    doc["friction"][0].update(mu=0.2, normal="weigth")
    with pytest.raises(ModelError, match=r"normal = 'weigth' .*'weight' \| 'given' or a number > 0 in N or N m"):
        parse(doc)
    doc["friction"][0]["normal"] = "5 m"
    with pytest.raises(ModelError, match=r"normal = '5 m' .*a force \(N\) or a torque \(N m\) > 0.*is a length"):
        parse(doc)
    doc["friction"][0]["normal"] = "5 kN"
    assert parse(doc).friction[0].normal == 5000.0


def test_rpm_and_degree_keys():
    doc = example("rotor_compressor.toml")
    doc["unbalance"][1]["phase_deg"] = "0.5 turn"
    typed = parse(doc)
    assert typed.unbalance[1].phase_deg == pytest.approx(180.0, rel=1e-15)
    doc = example("rotor_friswell.toml")
    doc["campbell"] = {"speeds_rpm": {"start": "0 rad/s", "stop": "100 Hz", "points": 3}}
    grid = parse(doc).campbell.speeds_rpm
    assert (grid.start, grid.stop) == (0.0, pytest.approx(6000.0, rel=1e-15))


def test_pint_is_imported_only_for_a_file_with_quantity_strings(tmp_path):
    """A file of plain numbers never imports pint (start-up time); one string does."""
    path = tmp_path / "q.toml"
    path.write_text((ROOT / "examples" / "cantilever.toml").read_text().replace("length = 1.5", 'length = "1.5 m"'))
    plain = [p for p in EXAMPLES if p != UNITS_EXAMPLE]
    code = ("import sys; from fem.modelfile import load\n"
            "for p in sys.argv[1:]: load(p); print('pint' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code, *map(str, plain), str(path)], capture_output=True,
                         text=True, cwd=ROOT, check=True).stdout.split()
    assert out == ["False"] * len(plain) + ["True"]


def test_the_units_example_is_the_si_cantilever():
    """examples/cantilever_units.toml (mm, GPa, g/cm^3) is examples/cantilever.toml bit for bit: the
    conversions of decimal units are exact."""
    units, si = Study.load(UNITS_EXAMPLE), Study.load(ROOT / "examples" / "cantilever.toml")
    assert units.doc.model_dump(exclude={"title"}) == si.doc.model_dump(exclude={"title"})
    assert np.array_equal(units.modal().omega_rad_s, si.modal().omega_rad_s)


# ------------------------------------------------------------------ coordinate-dependent keys
@pytest.mark.parametrize("name,edit,pattern", [
    ("torsion_shaft_disc.toml", lambda d: d["support"].append({"x": 0.5, "type": "spring", "k": "2e4 N/m"}),
     r"\[\[support\]\] #\d: k = '2e4 N/m' .*torsional stiffness \(N m/rad\).*'theta' of this torsion model is rotational"),
    ("cantilever.toml", lambda d: d["support"].append({"x": 0.5, "type": "spring", "k": "2e4 N*m/rad"}),
     r"k = '2e4 N\*m/rad' .*a stiffness \(N/m\).*'w' of this bending model is translational"),
    ("cantilever.toml", lambda d: d["segment"][0].update(rho_extra="2 kg*m^2/m"),
     r"rho_extra = .*a mass per length \(kg/m\)"),
    ("forced_torsion.toml", lambda d: d["load"][0].update(amplitude="5 N"), r"amplitude = '5 N' .*a torque \(N m\)"),
    ("forced_torsion.toml", lambda d: d["load"][0].update(amplitude="5 kg*m"),
     r"amplitude = '5 kg\*m' .*with scaling = 'constant'"),
    ("two_mass_chain.toml", lambda d: d["spring"][0].update(k="2 kN/mm", c="5 N*m*s/rad"),
     r"\[\[spring\]\] #1: c = '5 N\*m\*s/rad' .*N s/m.*k = '2 kN/mm' of the same table is translational"),
    ("two_mass_chain.toml", lambda d: d["body"][0].update(inertia="2 kg*m^2", x0="5 mm"),
     r"\[\[body\]\] #1: x0 = '5 mm' .*an angle \(rad\)"),
])
def test_coordinate_dependent_keys_are_checked(name, edit, pattern):
    doc = example(name)
    edit(doc)
    with pytest.raises(ModelError, match=pattern):
        parse(doc)


def test_coordinate_dependent_keys_accept_their_kind():
    doc = example("torsion_shaft_disc.toml")
    doc["support"].append({"x": 0.5, "type": "spring", "k": "20 kN*m/rad"})
    assert parse(doc).support[-1].k == 2e4
    doc = example("two_mass_chain.toml")
    doc["body"][0].update(inertia="2 kg*m^2", x0="5 deg", v0="60 rpm")
    b = parse(doc).body[0]
    assert (b.inertia, b.x0, b.v0) == (2.0, pytest.approx(math.radians(5)), pytest.approx(2 * math.pi))


# ------------------------------------------------------------------ every example with unit strings
def assert_same(a, b, where="", depth=0):
    """Recursive comparison: numbers and arrays to 1e-12 (relative to the array's scale)."""
    if sp.issparse(a):
        a, b = a.toarray(), b.toarray()
    if isinstance(a, np.ndarray) and a.dtype.kind in "fciu":
        assert a.shape == b.shape, where
        scale = float(np.nanmax(np.abs(a))) if a.size and not np.all(np.isnan(a)) else 0.0
        assert np.allclose(a, b, rtol=1e-12, atol=1e-12 * scale, equal_nan=True), where
    elif isinstance(a, float):
        assert b == pytest.approx(a, rel=1e-12, abs=1e-300), where
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            assert_same(x, y, f"{where}[{i}]", depth)
    elif isinstance(a, dict):
        assert a.keys() == b.keys(), where
        for k in a:
            assert_same(a[k], b[k], f"{where}.{k}", depth)
    elif hasattr(a, "__dict__") and depth < 4 and not callable(a):
        assert_same(vars(a), vars(b), where, depth + 1)
    elif isinstance(a, (int, str, bool, type(None))):
        assert a == b, where


def study(doc: dict, path: Path) -> Study:
    """The study of a model dict read as if it were the file ``path`` (its relative files resolved there)."""
    typed = parse(doc)
    object.__setattr__(typed, "__source__", path)
    return Study(typed, path)


@pytest.fixture(scope="module")
def rewritten():
    return {p.name: rewrite(tomllib.loads(p.read_text())) for p in EXAMPLES}


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_every_example_with_unit_strings_builds_the_same_model(path, rewritten):
    """Every example re-written with quantity strings in non-SI units (mm, g, MPa, rpm, deg, ...;
    generated from the schema's declarations) loads and builds the same model to 1e-12: the
    validated document, the linear system (K, M, C, G), the nonsmooth problem, the drive."""
    doc, n = rewritten[path.name]
    assert n > 0 or path == UNITS_EXAMPLE
    a, b = Study.load(path), study(doc, path)
    assert_same(a.doc.model_dump(), b.doc.model_dump(), "document")
    if a.kind == "drive":
        assert_same(a.drive, b.drive, "drive")
        return
    assert_same(a.linear_system(), b.linear_system(), "linear system")
    if a.kind in ("lumped", "hybrid") and (getattr(a.doc, "simulation", None) or getattr(a.doc, "steady", None)):
        assert_same(a.problem_spec(), b.problem_spec(), "problem")


FAST_FIRST = ("fe", "lumped")


@pytest.mark.parametrize("path", [p for p in EXAMPLES if tomllib.loads(p.read_text()).get("segment") is not None
                                  and "simulation" not in p.read_text()], ids=lambda p: p.name)
def test_fe_examples_with_unit_strings_give_the_same_first_modes(path, rewritten):
    a, b = Study.load(path), study(rewritten[path.name][0], path)
    if a.kind != "fe":
        pytest.skip("hybrid")
    ra, rb = a.modal(), b.modal()
    assert np.allclose(ra.omega_rad_s, rb.omega_rad_s, rtol=1e-12)


# ------------------------------------------------------------------ plausibility warnings
def plausibility(doc) -> list[str]:
    return parse(doc).__plausibility__.warnings


EXPECTED_WARNINGS = {
    "superelement_tail_shaft.toml": "slenderness L/d = 8.12",   # the last 0.16 m of a 0.5 m Euler-Bernoulli
}                                                                  # cantilever (L/d = 25), exported as a super-element
"""Examples whose warning is right and intended (the piece alone is a stubby beam)."""


def test_examples_are_plausible():
    for p in EXAMPLES:
        w = load(p).__plausibility__.warnings
        expected = EXPECTED_WARNINGS.get(p.name)
        assert (len(w) == 1 and expected in w[0]) if expected else not w, (p.name, w)


def test_section_larger_than_the_shaft_is_likely_in_mm():
    doc = example("cantilever.toml")
    doc["segment"][0]["length"] = 1.0
    doc["segment"][0]["section"]["d"] = 50
    assert plausibility(doc) == ["[[segment]] #1 section: d = 50 m on a 1 m shaft: the section is larger than the "
                                 "whole shaft; is the diameter in mm? drivefem reads plain numbers in SI; write "
                                 "d = \"50 mm\""]
    doc["segment"][0]["section"]["d"] = "50 m"                       # written with a unit: no guess
    assert plausibility(doc) == ["[[segment]] #1 section: d = 50 m on a 1 m shaft: the section is larger than the "
                                 "whole shaft (outside beam theory)"]


def test_explicit_section_constants_in_mm():
    doc = example("cantilever.toml")
    doc["segment"][0]["section"] = {"A": 2000.0, "I": 3e5, "J": 6e5}     # mm^2, mm^4 read as m^2, m^4
    w = plausibility(doc)
    assert len(w) == 3 and "A = 2000 m^2 (a section of equivalent diameter 50.5 m) on a 1.5 m shaft" in w[0]
    assert w[0].endswith('write A = "2000 mm^2"') and w[1].endswith('write I = "300000 mm^4"')
    doc["segment"][0]["section"] = {"A": 1.0, "I": 0.5, "J": 1.0}        # a scaled model's effective constants
    assert plausibility(doc) == []


def test_euler_bernoulli_on_a_stubby_shaft_suggests_timoshenko():
    doc = example("cantilever.toml")
    doc["segment"][0]["section"]["d"] = 0.5                          # L/d = 3
    assert plausibility(doc) == [
        "[model]: theory = 'euler-bernoulli' on a shaft of slenderness L/d = 3 (1.5 m / 0.5 m): Euler-Bernoulli "
        "beams neglect shear and rotary inertia and need L/d > 10; use theory = \"timoshenko\""]
    doc["model"]["theory"] = "timoshenko"
    assert plausibility(doc) == []
    doc["model"]["theory"] = "euler-bernoulli"
    doc["segment"][0]["section"]["d"] = 50                           # the units, not the theory
    assert [w.split(":")[0] for w in plausibility(doc)] == ["[[segment]] #1 section"]


@pytest.mark.parametrize("key,value,expected", [
    ("E", 210000, re.escape("E = 210000 Pa is far below the Young's modulus of engineering solids (1e+06 to "
                            "1.2e+12 Pa): is it in MPa? drivefem reads plain numbers in SI; write E = \"210000 MPa\"")),
    ("E", 210, "is it in GPa?"),
    ("G", 81000, "G = 81000 Pa is far below the shear modulus .*write G = \"81000 MPa\""),
    ("rho", 7.85, "rho = 7.85 kg/m\\^3 is far below the densities of engineering solids .*is it in g/cm\\^3\\? "
                  ".*write rho = \"7.85 g/cm\\^3\""),
    ("rho", 7.85e-9, "is it in t/mm\\^3\\?"),
    ("E", 2.1e20, "E = 2.1e\\+20 Pa is far above the Young's modulus of engineering solids \\(1e\\+06 to "
                  "1.2e\\+12 Pa\\)$"),
    ("E", "210 kPa", "E = 210000 Pa is far below .*\\(1e\\+06 to 1.2e\\+12 Pa\\)$"),     # a unit given: no guess
])
def test_material_off_the_range_of_solids(key, value, expected):
    doc = example("cantilever.toml")
    if key == "G":
        doc["material"].pop("G")
    doc["material"][key] = value
    w = plausibility(doc)
    assert len(w) == 1 and re.search(expected, w[0]), w


def test_rotor_section_and_material():
    doc = example("rotor_compressor.toml")
    doc["rotor"]["segment"][2]["d"] = 120
    doc["rotor"]["material"]["rho"] = 7.85
    w = plausibility(doc)
    assert [x.split(":")[0] for x in w] == ["[rotor.material]", "[[rotor.segment]] #3"]
    assert w[1].endswith('write d = "120 mm"')


def test_the_repro_warns_on_units_and_does_not_blame_the_mesh(tmp_path):
    """Issue 25's repro (d = 60, E = 210000 in an SI file): before, the Timoshenko shaft's first modes
    were reported "not reliable: the mesh is too fine".  Now the unit warnings come first (stderr and
    JSON) and the precision note names the units."""
    text = (ROOT / "examples" / "stepped_rotor_timoshenko.toml").read_text()
    path = tmp_path / "repro.toml"
    path.write_text(text.replace("E = 2.1e11", "E = 210000").replace("d = 0.06", "d = 60"))
    out = tmp_path / "r.json"
    run = subprocess.run([sys.executable, "-m", "fem.app.cli", "modal", str(path), "--json", str(out)],
                         capture_output=True, text=True, cwd=ROOT)
    data = json.loads(out.read_text())
    assert run.returncode == 3 and not data["reliable"][0], run.stderr
    w = data["warnings"]
    assert w[0].startswith("[material]: E = 210000 Pa") and "is the diameter in mm?" in w[1]
    assert not any("mesh is too fine" in x for x in w)
    assert any(x.startswith("mode 1: not reliable") and "values in other units than SI" in x for x in w)
    assert run.stderr.splitlines()[0].startswith("drivefem: warning: [material]: E = 210000 Pa")
    assert "likely cause: values in other units than SI" in run.stdout and "too fine" not in run.stdout


def test_warnings_never_change_results():
    doc = example("cantilever.toml")
    doc["material"]["E"] = 2.11e5
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        s = Study.parse(doc)
    assert len(caught) == 1 and "MPa" in str(caught[0].message)
    ref = Study.parse(example("cantilever.toml")).modal().omega_rad_s
    assert np.allclose(s.modal().omega_rad_s * math.sqrt(1e6), ref, rtol=1e-9)    # E / 1e6: omega / 1e3


# ------------------------------------------------------------------ slow: every example's main command
VOLATILE = ("wall", "time_s", "elapsed", "seconds", "cpu", "linear_solver", "solver")
"""JSON keys that hold timings or the name of a solver picked at run time (not results)."""


def _numeric(a):
    """A JSON value as a numeric array (complex numbers are {"re", "im"}), or None."""
    def conv(x):
        if isinstance(x, dict) and x.keys() == {"re", "im"}:
            return complex(x["re"], x["im"])
        if isinstance(x, list):
            return [conv(y) for y in x]
        if isinstance(x, (int, float)) and not isinstance(x, bool):
            return x
        raise TypeError
    try:
        arr = np.asarray(conv(a))
    except (TypeError, ValueError):
        return None
    return arr if arr.dtype.kind in "fciu" and arr.size else None


def assert_same_json(a, b, where=""):
    if isinstance(a, (list, dict)) and _numeric(a) is not None:
        x, y = _numeric(a), _numeric(b)
        assert y is not None and x.shape == y.shape, where
        scale = float(np.max(np.abs(x)))
        assert np.allclose(x, y, rtol=1e-12, atol=1e-12 * scale), (where, float(np.max(np.abs(x - y))), scale)
    elif isinstance(a, dict):
        assert a.keys() == b.keys(), where
        for k in a:
            if not any(v in k for v in VOLATILE):
                assert_same_json(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            assert_same_json(x, y, f"{where}[{i}]")
    elif isinstance(a, float):
        assert b == pytest.approx(a, rel=1e-12, abs=1e-300), where
    elif not isinstance(a, str) or where.endswith("title"):
        assert a == b, where


@pytest.mark.slow
@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_every_example_with_unit_strings_gives_the_same_results(path, tmp_path):
    """The example's main command (tests/fuzzing/examples.py) on the file as shipped and re-written
    with quantity strings that convert back to the same doubles (a conversion may differ from the SI
    number by an ulp, and iterative solvers -- eigsh, event location, continuation -- amplify an ulp
    beyond 1e-12 in round-off quantities such as residuals; the default tier checks the conversions
    themselves): the same JSON to 1e-12, timings aside."""
    import tomli_w

    from fem.app.cli import main
    from tests.fuzzing.examples import APPLICABLE, kind_of as fuzz_kind

    import shutil

    command = APPLICABLE[fuzz_kind(tomllib.loads(path.read_text()))][0]
    for sub in path.parent.iterdir():                # files the examples name relative to themselves
        if sub.is_dir():
            shutil.copytree(sub, tmp_path / sub.name)
    quantities = tmp_path / path.name
    doc, n = rewrite(tomllib.loads(path.read_text()), exact=True)
    assert (n > 0 or path == UNITS_EXAMPLE) and parse(doc).model_dump() == load(path).model_dump()      # bit for bit
    quantities.write_text(tomli_w.dumps(doc))
    out = {}
    for name, model in (("si", path), ("units", quantities)):
        argv = [command, str(model), "--json", str(tmp_path / f"{name}.json")]
        if command == "sweep":
            argv += ["--workers", "0", "--out", str(tmp_path / f"{name}-sweep")]
        if command == "render":
            argv = ["modal", str(model), "--json", str(tmp_path / f"{name}.json")]
        assert main(argv) in (0, 1, 3), argv
        out[name] = json.loads((tmp_path / f"{name}.json").read_text())
    assert_same_json(out["si"], out["units"])
