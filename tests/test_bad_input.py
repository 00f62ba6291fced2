"""Bad input gets a clear error naming the key, its value and what is allowed."""
import copy
import subprocess
import sys

import numpy as np
import pytest

from discrete.errors import ModelError
from discrete.linear.harmonic import harmonic_response
from discrete.linear.static import static_deflection
from fem import assemble, modal_analysis
from fem.modelfile.build.linear import forced_spec
from fem.study import Study


def parse_model(doc):
    """The built shaft of an FE model dict (schema and model checks)."""
    study = Study.parse(doc)
    study.shaft
    return study

BASE = {
    "material": {"E": 2.1e11, "G": 8.1e10, "rho": 7850.0},
    "model": {"physics": "bending"},
    "segment": [{"length": 1.0, "elements": 10, "section": {"shape": "circle", "d": 0.05}}],
    "support": [{"x": 0.0, "type": "clamped"}],
    "analysis": {"type": "modal", "modes": 4},
}


def with_(path, value, base=BASE):
    doc = copy.deepcopy(base)
    *head, last = path
    node = doc
    for k in head:
        node = node[k]
    if value is DELETE:
        del node[last]
    else:
        node[last] = value
    return doc


DELETE = object()


@pytest.mark.parametrize("path,value,pattern", [
    (("segment", 0, "length"), -1.0, r"\[\[segment\]\] #1: length = -1.0 .*> 0"),
    (("segment", 0, "length"), 0.0, r"length = 0.0 .*> 0"),
    (("segment", 0, "elements"), 0, r"elements = 0 .*integer >= 1"),
    (("segment", 0, "elements"), 2.5, r"elements = 2.5 .*integer >= 1"),
    (("material", "E"), -2e11, r"\[material\]: E = -2.*> 0"),
    (("material", "rho"), 0.0, r"rho = 0.0 .*> 0"),
    (("material", "G"), "steel", r"G = 'steel' .*a number"),
    (("segment", 0, "section", "d"), -0.05, r"section: d = -0.05 .*> 0"),
    (("segment", 0, "section", "shape"), "square", r"shape = 'square' .*'circle' \| 'tube'"),
    (("support", 0, "x"), 1.5, r"\[\[support\]\] #1: x = 1.5 .*0 <= x <= 1"),
    (("support", 0, "type"), "welded", r"type = 'welded' .*'clamped' \| 'pinned' \| 'spring'"),
    (("segment", 0, "lenght"), 1.0, r"lenght = 1.0 .*unknown keys are an error"),
    (("frobnicate",), 1, r"model file \(fe\): frobnicate = 1 .*unknown keys are an error"),
    (("model", "physics"), "acoustic", r"physics = 'acoustic' .*'torsion' \| 'axial' \| 'bending'"),
    (("model", "mass"), "diagonal", r"mass = 'diagonal' .*'consistent' \| 'lumped'"),
])
def test_fe_model_errors(path, value, pattern):
    with pytest.raises(ModelError, match=pattern):
        parse_model(with_(path, value))


def test_bending_only_keys_in_torsion_model():
    doc = with_(("model",), {"physics": "torsion", "theory": "timoshenko"})
    with pytest.raises(ModelError, match=r"theory = 'timoshenko' .*only to physics = 'bending'"):
        parse_model(doc)
    doc = with_(("support", 0, "type"), "pinned", with_(("model",), {"physics": "torsion"}))
    with pytest.raises(ModelError, match=r"type = 'pinned' .*'clamped' \| 'spring' for torsion"):
        parse_model(doc)
    doc = with_(("point",), [{"x": 1.0, "kr": 10.0}], with_(("model",), {"physics": "torsion"}))
    with pytest.raises(ModelError, match=r"kr = 10.0 .*only for physics = 'bending'"):
        parse_model(doc)


def test_spring_support_needs_stiffness():
    with pytest.raises(ModelError, match=r"k = 0.0 .*stiffness > 0"):
        parse_model(with_(("support", 0, "type"), "spring"))


def test_timoshenko_explicit_section_needs_kappa():
    doc = with_(("model",), {"physics": "bending", "theory": "timoshenko"})
    doc["segment"][0]["section"] = {"A": 1e-3, "I": 1e-7, "J": 2e-7}
    with pytest.raises(ModelError, match=r"kappa = None .*shear coefficient"):
        assemble(parse_model(doc).shaft)


def test_free_free_more_modes_than_dofs():
    doc = with_(("support",), [])
    doc["segment"][0]["elements"] = 2
    fe = assemble(parse_model(doc).shaft)
    with pytest.raises(ModelError, match=r"modes = 7 .*from 1 to 6"):
        modal_analysis(fe.system, 7)


def test_singular_static_problem():
    fe = assemble(parse_model(with_(("support",), [{"x": 0.0, "type": "pinned"}])).shaft)
    F = np.zeros(fe.system.n_dofs)
    F[fe.system.dof_index(field="w", x=1.0)] = 1.0
    with pytest.raises(ModelError, match=r"1 rigid-body mode\(s\).*singular"):
        static_deflection(fe.system, F)
    with pytest.raises(ModelError, match=r"frequencies = 0.0 .*rigid-body"):
        harmonic_response(fe.system, [0.0, 10.0], force=F)


def test_load_and_base_motion_placement():
    doc = with_(("analysis",), {"type": "forced", "frequencies_hz": [10.0]})
    doc["load"] = [{"x": 0.0, "dof": "w", "amplitude": 1.0}]
    mf = parse_model(doc)
    with pytest.raises(ModelError, match=r"\[\[load\]\] #1: x = 0.0 .*free DOF"):
        forced_spec(mf.doc, mf.linear_system())
    doc["load"] = [{"x": 0.5, "dof": "theta", "amplitude": 1.0}]
    mf = parse_model(doc)
    with pytest.raises(ModelError, match=r"dof = 'theta' .*'w', 'w_x'"):
        forced_spec(mf.doc, mf.linear_system())
    doc["load"] = [{"x": 0.55, "dof": "w", "amplitude": 1.0}]
    mf = parse_model(doc)
    with pytest.raises(ModelError, match=r"x = 0.55 .*node position.*nearest node at x = 0.5"):
        forced_spec(mf.doc, mf.linear_system())
    del doc["load"]
    doc["base_motion"] = [{"x": 1.0, "dof": "w", "amplitude": 1e-3}]
    mf = parse_model(doc)
    with pytest.raises(ModelError, match=r"\[\[base_motion\]\] #1: x = 1.0 .*held DOF"):
        forced_spec(mf.doc, mf.linear_system())


def test_forced_needs_frequencies_and_load():
    doc = with_(("analysis",), {"type": "forced"})
    with pytest.raises(ModelError, match=r"\[analysis\]: frequencies_hz = None .*exactly one of frequencies_hz"):
        parse_model(doc)
    doc = with_(("analysis",), {"type": "forced", "frequencies_hz": [1.0], "omega_rad_s": [2.0]})
    with pytest.raises(ModelError, match=r"exactly one of frequencies_hz"):
        parse_model(doc)


@pytest.mark.parametrize("doc,pattern", [
    ({"body": [{"name": "a", "inertia": -1.0}]}, r"\[\[body\]\] #1: inertia = -1.0 .*> 0"),
    ({"body": [{"name": "a", "inertia": 1.0}], "spring": [{"between": ["a", "b"], "k": 1.0}]},
     r"\[\[spring\]\] #1: between = 'b' .*'a', 'ground'"),
    ({"body": [{"name": "a", "inertia": 1.0}], "spring": [{"between": ["ground", "a"], "k": -5.0}]},
     r"k = -5.0 .*>= 0"),
    ({"body": [{"name": "a", "inertia": 1.0}, {"name": "a", "inertia": 2.0}]}, r"name = 'a' .*unique"),
    ({"body": [{"name": "a", "inertia": 1.0}], "driver": [{"velocity": 1.0}]}, r"\[\[driver\]\] #1: name = None .*required"),
    ({"body": [{"name": "a", "inertia": 1.0}], "driver": [{"name": "d", "amplitude": 1.0}]},
     r"\[\[driver\]\] #1: omega = 0.0 .*> 0 with amplitude"),
    ({"body": [{"name": "a", "inertia": 1.0, "mass": 2.0}]}, r"mass = 2.0 .*unknown keys"),
])
def test_lumped_errors(doc, pattern):
    with pytest.raises(ModelError, match=pattern):
        Study.parse(doc).lumped


def test_cli_reports_bad_input_with_exit_code_2(tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text('[model]\nphysics = "torsion"\ntheory = "timoshenko"\n[material]\nE = 1.0\nG = 1.0\nrho = 1.0\n'
                 '[[segment]]\nlength = 1.0\nelements = 2\nsection = { shape = "circle", d = 0.1 }\n')
    r = subprocess.run([sys.executable, "-m", "fem.app.cli", "modal", str(f)], capture_output=True, text=True)
    assert r.returncode == 2
    assert "theory = 'timoshenko'" in r.stderr and "bending" in r.stderr
    r = subprocess.run([sys.executable, "-m", "fem.app.cli", "modal", str(tmp_path / "missing.toml")],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "existing TOML file" in r.stderr
