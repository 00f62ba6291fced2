"""The model-file layer: one declared schema (JSON Schema for editors, the generated reference page),
strict values, one meaning per table, clear messages, deprecations that name the new key."""
import copy
import json
import tomllib
import warnings
from pathlib import Path

import pytest

from discrete.errors import ModelError
from fem.modelfile import ModelDeprecationWarning, load, parse
from fem.modelfile.load import SCHEMA_FILE, dumps_schema, schema_json
from fem.modelfile.reference import PAGE, render
from fem.modelfile.schema.document import detect_kind
from fem.study import Study

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))


def example(name):
    return tomllib.loads((ROOT / "examples" / name).read_text())


def test_shipped_schema_is_the_declared_one():
    assert SCHEMA_FILE.read_text() == dumps_schema(), "regenerate: drivefem schema --out fem/modelfile/drivefem.schema.json"


def test_reference_page_is_generated_from_the_schema():
    assert PAGE.read_text() == render(), "regenerate: python -m fem.modelfile.reference"


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_every_example_matches_the_json_schema_and_the_loader(path):
    jsonschema = pytest.importorskip("jsonschema")
    text = path.read_text()
    assert text.startswith("#:schema ../fem/modelfile/drivefem.schema.json\n")   # editors find the schema
    validator = jsonschema.Draft202012Validator(json.loads(SCHEMA_FILE.read_text()))
    doc = tomllib.loads(text)
    assert not list(validator.iter_errors(doc))
    load(path)


def test_json_schema_catches_what_the_loader_catches():
    jsonschema = pytest.importorskip("jsonschema")
    validator = jsonschema.Draft202012Validator(schema_json("fe"))
    doc = example("cantilever.toml")
    doc["analysis"]["modez"] = 3
    assert list(validator.iter_errors(doc))
    with pytest.raises(ModelError, match=r"\[analysis\]: modez = 3 .*did you mean 'modes'"):
        parse(doc)


@pytest.mark.parametrize("kind", ["fe", "lumped", "hybrid", "drive"])
def test_schema_per_kind(kind):
    s = schema_json(kind)
    assert s["title"] == f"drivefem {kind} model file" and s["additionalProperties"] is False


@pytest.mark.parametrize("mutate,pattern", [
    (lambda d: d["analysis"].update(tolerance="abc"), r"tolerance = 'abc' .*a dimensionless number > 0 and < 1.*"
                                                      r"a number followed by a unit"),        # strings are quantities
    (lambda d: d["analysis"].update(shift="abc"), r"shift = 'abc' .*a number"),
    (lambda d: d["analysis"].update(modes=2.7), r"modes = 2.7 .*an integer >= 1"),
    (lambda d: d["analysis"].update(modes=True), r"modes = True .*an integer"),
    (lambda d: d["segment"][0].update(length=float("nan")), r"length = nan .*a number > 0"),
    (lambda d: d["segment"][0].update(length=float("inf")), r"length = inf .*a number > 0"),
    (lambda d: d["segment"][0].update(elements=10 ** 9), r"elements.*FE unknowns.*DRIVEFEM_BUDGET"),
    (lambda d: d.update(segment={"length": 1.0}), r"segment = .*an array of tables"),
    (lambda d: d.update(analysis=[{"type": "modal"}]), r"analysis = .*a table"),
    (lambda d: d["material"].update(nu=0.3), r"nu = 0.3 .*either G or nu"),
    (lambda d: d.update(constants={"g": 9.81}), r"constants = .*time simulations"),
])
def test_strict_values_and_clear_messages(mutate, pattern):
    doc = example("cantilever.toml")
    mutate(doc)
    with pytest.raises(ModelError, match=pattern):
        Study.parse(doc)


def test_kinds_are_decided_once_from_the_tables():
    assert detect_kind(example("cantilever.toml")) == "fe"
    assert detect_kind(example("two_mass_chain.toml")) == "lumped"
    assert detect_kind(example("hybrid_drill_string.toml")) == "hybrid"
    assert detect_kind(example("drive_regular.toml")) == "drive"
    with pytest.raises(ModelError, match=r"at least one \[\[segment\]\].*\[\[body\]\].*\[drive\]"):
        detect_kind({"title": "nothing"})


def test_a_table_of_another_kind_says_where_it_belongs():
    doc = example("two_mass_chain.toml")
    doc["reduction"] = {"modes": 2}
    with pytest.raises(ModelError, match=r"model file \(lumped\): reduction = .*only together with \[\[segment\]\]"):
        parse(doc)


def test_modes_default_is_capped_but_an_explicit_request_is_checked():
    doc = example("two_mass_chain.toml")
    del doc["analysis"]["modes"]
    assert Study.parse(doc).modal().omega_rad_s.size == 2          # 6 capped at the 2 free DOFs
    doc["analysis"]["modes"] = 6
    with pytest.raises(ModelError, match="modes = 6"):
        Study.parse(doc).modal()


def test_one_sided_without_side_keeps_its_old_default_with_a_warning():
    doc = example("discrete_strand_spool.toml")
    del doc["one_sided"][0]["side"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        spec = Study.parse(doc).problem_spec()
    msg = [str(w.message) for w in caught if issubclass(w.category, ModelDeprecationWarning)]
    assert msg and "side" in msg[0] and "'tension'" in msg[0]
    assert spec.elements[1].side == 1                           # tension, as before in lumped files


def test_lone_gap_bound_is_a_stop_in_every_kind():
    doc = example("discrete_gap_backlash.toml")
    del doc["gap"][0]["delta"]
    doc["gap"][0]["upper"] = 0.1
    el = Study.parse(doc).problem_spec().elements[0]
    assert type(el).__name__ == "OneSided" and el.side == 1 and el.s_open == 0.1


def test_friction_coefficient_with_a_normal_force():
    doc = example("discrete_coulomb_decay.toml")
    doc["friction"][0].pop("kinetic")
    doc["friction"][0].update(mu=0.2, mu_static=0.3, normal=5.0)
    el = Study.parse(doc).problem_spec().elements[0]
    assert (el.kinetic, el.static) == pytest.approx((1.0, 1.5))


def test_damping_has_one_meaning():
    doc = example("two_mass_chain.toml")
    doc["damping"] = {"alpha": 1.0, "zeta": 0.1}
    with pytest.raises(ModelError, match=r"\[damping\]: zeta = 0.1 .*only with type = 'modal'"):
        parse(doc)
    doc = example("hybrid_vibro_impact_beam.toml")
    assert Study.parse(doc).doc.damping.kind == "rayleigh"        # alpha alone: Rayleigh in every kind
    doc["damping"] = {"type": "modal", "zeta": 0.05}
    with pytest.raises(ModelError, match=r"\[damping\]: type = 'modal'"):
        Study.parse(doc).hybrid


def test_unreadable_files(tmp_path):
    binary = tmp_path / "b.toml"
    binary.write_bytes(b"title = 'x'\x00\x01")
    latin = tmp_path / "l.toml"
    latin.write_bytes('title = "Grüße"'.encode("latin-1"))
    deep = tmp_path / "d.toml"
    deep.write_text("a = " + "[" * 40 + "1" + "]" * 40 + "\n")
    broken = tmp_path / "x.toml"
    broken.write_text("[model\nphysics = 'torsion'\n")
    for path, pattern in ((binary, "binary data"), (latin, "not UTF-8"), (deep, "nested at most"),
                          (broken, "valid TOML syntax"), (tmp_path, "directory"), (tmp_path / "no.toml", "existing")):
        with pytest.raises(ModelError, match=pattern):
            load(path)


def test_simulation_keys_belong_to_their_method():
    doc = example("discrete_seed000_stick_slip.toml")
    doc["simulation"]["dt"] = 1e-3
    with pytest.raises(ModelError, match=r"\[simulation\]: dt = 0.001 .*only with method = 'moreau'"):
        parse(doc)
    doc = example("discrete_seed000_stick_slip.toml")
    doc["simulation"]["max_step"] = 1e-300
    with pytest.raises(ModelError, match=r"max_step.*steps.*DRIVEFEM_BUDGET"):
        Study.parse(doc)


def test_event_allowance_is_budgeted(monkeypatch):
    """max_events keeps two recorded states per event in memory: 1e8 is refused with the factor it
    needs (a run of that size once filled 23 GB), the default and the budgeted run are accepted."""
    doc = example("discrete_seed000_stick_slip.toml")
    doc["simulation"]["max_events"] = 100_000_000
    with pytest.raises(ModelError, match=r"\[simulation\]: max_events = 100000000 .*recorded instants.*"
                                         r"DRIVEFEM_BUDGET >= 100"):
        Study.parse(doc)
    monkeypatch.setenv("DRIVEFEM_BUDGET", "100")
    Study.parse(doc)
    monkeypatch.delenv("DRIVEFEM_BUDGET")
    doc["simulation"]["max_events"] = 1_000_000
    Study.parse(doc)


def test_budget_of_a_stiff_or_tiny_model():
    doc = example("discrete_coulomb_decay.toml")
    doc["body"][0]["inertia"] = 1e-300
    with pytest.raises(ModelError, match=r"\[simulation\]: t_end = .*steps.*highest frequency"):
        Study.parse(doc).simulate()
