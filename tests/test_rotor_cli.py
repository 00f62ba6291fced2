"""Rotor model files through the command line: ``drivefem modal | forced | campbell`` on [rotor] files,
the JSON output contract, and bad input (clear errors with exit code 2, never a traceback)."""
import copy
import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

from discrete.errors import ModelError
from fem.app.cli import main
from fem.study import Study

ROOT = Path(__file__).resolve().parent.parent
EX = ROOT / "examples"
ROTOR_EXAMPLES = sorted(EX.glob("rotor_*.toml"))


def _doc(name):
    return tomllib.loads((EX / name).read_text())


def _write(tmp_path, doc, name="rotor.toml"):
    import tomli_w

    p = tmp_path / name
    p.write_bytes(tomli_w.dumps(doc).encode())
    return p


def test_rotor_examples_are_rotor_files():
    assert len(ROTOR_EXAMPLES) >= 5
    for p in ROTOR_EXAMPLES:
        s = Study.load(p)
        assert s.kind == "rotor" and s.doc.campbell is not None, p.name


def test_modal_friswell_591_at_4000_rpm(tmp_path, capsys):
    """Friswell et al. (2010) Example 5.9.1, 6 elements, 4000 rev/min: 85.39, 87.80, 251.78, 294.71,
    600.18 rad/s lateral, 650.41 torsion (printed to 2 decimals: tolerance half a printed digit)."""
    out = tmp_path / "m.json"
    assert main(["modal", str(EX / "rotor_friswell.toml"), "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert d["schema"] == "drivefem.modal" and d["kind"] == "rotor" and d["rigid_body_modes"] == 2
    flex = [(w, k) for w, k in zip(d["omega_rad_s"], d["kind_of_mode"]) if k != "rigid"]
    lateral = [w for w, k in flex if k == "lateral"]
    assert lateral == pytest.approx([85.39, 87.80, 251.78, 294.71, 600.18], abs=0.005)
    assert [w for w, k in flex if k == "torsion"] == pytest.approx([650.41], abs=0.005)
    assert d["whirl"][2:4] == ["backward", "forward"]
    assert len(d["mode_shapes"]["v"]) == d["n_modes"] and "re" in d["mode_shapes"]["v"][2][1]
    assert "rigid-body" in capsys.readouterr().out


def test_cross_coupled_rotor_has_damped_and_destabilised_modes(tmp_path):
    out = tmp_path / "m.json"
    assert main(["modal", str(EX / "rotor_friswell_cross_coupled.toml"), "--json", str(out)]) == 0
    ld = np.array(json.loads(out.read_text())["log_decrement"])
    assert (ld > 0.05).any() and (ld < -0.05).any()


def test_campbell_json_png_csv(tmp_path):
    j, png, csv = tmp_path / "c.json", tmp_path / "c.png", tmp_path / "c.csv"
    assert main(["campbell", str(EX / "rotor_friswell_damped.toml"), "--json", str(j), "--png", str(png),
                 "--csv", str(csv)]) == 0
    d = json.loads(j.read_text())
    assert d["schema"] == "drivefem.campbell" and d["kind"] == "rotor"
    assert len(d["omega_rad_s"]) == 6 and len(d["omega_rad_s"][0]) == len(d["speeds_rad_s"]) == 31
    crit = [c for c in d["critical_speeds"] if c["order"] == 1]
    back = d["backward_crossings"]
    # every root satisfies omega = Omega (Brent's method); the critical speeds are the forward crossings,
    # the backward ones are listed apart (isotropic bearings: unbalance does not excite them)
    assert all(abs(c["frequency_rad_s"] - c["speed_rad_s"]) < 1e-6 * c["speed_rad_s"] for c in crit + back)
    assert {c["whirl"] for c in crit} == {"forward"} and {c["whirl"] for c in back} == {"backward"}
    assert d["isotropic_supports"] is True and crit[0]["speed_rpm"] == pytest.approx(835.7, abs=0.05)
    assert png.stat().st_size > 10_000 and csv.read_text().count("\n") == 32


def test_forced_unbalance_response_contract(tmp_path):
    j, csv = tmp_path / "f.json", tmp_path / "f.csv"
    assert main(["forced", str(EX / "rotor_friswell_damped.toml"), "--json", str(j), "--csv", str(csv)]) == 0
    d = json.loads(j.read_text())
    assert d["schema"] == "drivefem.forced" and d["kind"] == "rotor"
    n = len(d["omega_rad_s"])
    assert n == 300 and len(d["outputs"]) == 2 and len(d["amplitude"][0]) == n and len(d["response"][1]) == n
    assert d["omega_rad_s"][0] == pytest.approx(200 * np.pi / 30)
    first = min((p for p in d["peaks"] if p["probe"] == 0), key=lambda p: p["speed_rad_s"])
    assert first["amplification_factor"] > 2.5 and first["passes"] is True
    assert csv.read_text().splitlines()[0].startswith("speed_rpm,speed_rad_s,disc 1.major amplitude")   # the file's names
    assert d["outputs"] == ["disc 1.major", "disc 2.major"]
    assert {n for n, o in d["named_outputs"].items() if o["source"] == "bearing"} == \
        {f"bearing[{i}] x={x}.force_{c}" for i, x in ((1, "0"), (2, "1.5")) for c in "yz"}


def test_compressor_speed_dependent_bearings_and_seal(tmp_path):
    j = tmp_path / "c.json"
    assert main(["campbell", str(EX / "rotor_compressor.toml"), "--json", str(j)]) == 0
    d = json.loads(j.read_text())
    assert min(min(c) for c in d["log_decrement"]) > 0           # stable to 13000 rev/min
    assert {c["order"] for c in d["critical_speeds"]} == {1.0, 2.0}
    assert d["isotropic_supports"] is False and d["backward_crossings"]        # anisotropic bearings


# ------------------------------------------------------------------ bad input
def _fails(tmp_path, capsys, doc, command, pattern):
    p = _write(tmp_path, doc)
    assert main([command, str(p)]) == 2
    err = capsys.readouterr().err
    assert "drivefem: error:" in err and "Traceback" not in err
    import re

    assert re.search(pattern, err), err


def test_negative_bearing_damping(tmp_path, capsys):
    doc = _doc("rotor_friswell_anisotropic.toml")
    doc["rotor"]["bearing"][1]["czz"] = -1e3
    _fails(tmp_path, capsys, doc, "modal", r"\[\[rotor.bearing\]\] #2: czz = -1000.0 .*symmetric part is positive "
           r"semidefinite")


def test_negative_seal_stiffness_runs(tmp_path, capsys):
    """A seal's negative direct stiffness is a legitimate input (ROSS's extrapolated compressor seals)."""
    doc = _doc("rotor_friswell_anisotropic.toml")
    doc["rotor"]["bearing"].append({"x": 0.75, "kyy": -2e4, "kzz": -2e4, "name": "seal"})
    assert main(["modal", str(_write(tmp_path, doc))]) == 0


def test_negative_value_in_a_bearing_table(tmp_path, capsys):
    doc = _doc("rotor_compressor.toml")
    doc["rotor"]["bearing"][0]["cyy"][2] = -1.0
    _fails(tmp_path, capsys, doc, "modal", r"\[\[rotor.bearing\]\] #1: cyy = -1.0 ")


def test_disc_outside_the_shaft(tmp_path, capsys):
    doc = _doc("rotor_friswell_anisotropic.toml")
    doc["rotor"]["disc"][1]["x"] = 1.6
    _fails(tmp_path, capsys, doc, "modal", r"\[\[rotor.disc\]\] #2: x = 1.6 .*on the shaft, 0 <= x <= 1.5")


def test_disc_between_nodes(tmp_path, capsys):
    doc = _doc("rotor_friswell_anisotropic.toml")
    doc["rotor"]["disc"][0]["x"] = 0.6
    _fails(tmp_path, capsys, doc, "modal", r"\[\[rotor.disc\]\] #1: x = 0.6 .*node position")


def test_response_speeds_must_be_positive(tmp_path, capsys):
    doc = _doc("rotor_friswell_damped.toml")
    doc["unbalance_response"]["speeds_rpm"]["start"] = 0
    _fails(tmp_path, capsys, doc, "forced", r"\[unbalance_response\]: speeds_rpm = 0.0 .*speeds > 0")


def test_negative_modal_speed(tmp_path, capsys):
    doc = _doc("rotor_friswell_damped.toml")
    doc["analysis"]["speed_rpm"] = -100
    _fails(tmp_path, capsys, doc, "modal", r"speed_rpm = -100")


def test_speed_outside_the_bearing_table(tmp_path, capsys):
    doc = _doc("rotor_compressor.toml")
    doc["campbell"]["speeds_rpm"]["stop"] = 15000
    _fails(tmp_path, capsys, doc, "campbell", r"\[\[rotor.bearing\]\] #1: speed = .*inside the bearing table's range")


def test_table_without_speeds(tmp_path, capsys):
    doc = _doc("rotor_compressor.toml")
    del doc["rotor"]["bearing"][0]["speeds_rpm"]
    _fails(tmp_path, capsys, doc, "modal", r"kyy = .*give speeds")


def test_table_of_the_wrong_length(tmp_path, capsys):
    doc = _doc("rotor_compressor.toml")
    doc["rotor"]["bearing"][0]["kzz"] = [1e8, 2e8]
    _fails(tmp_path, capsys, doc, "modal", r"kzz = .*one value per speed \(5 values")


def test_unknown_key_and_both_units(tmp_path, capsys):
    doc = _doc("rotor_friswell_anisotropic.toml")
    doc["rotor"]["bearing"][0]["kxx"] = 1.0
    _fails(tmp_path, capsys, doc, "modal", r"kxx")
    doc = _doc("rotor_friswell_anisotropic.toml")
    doc["analysis"]["speed"] = 100.0
    _fails(tmp_path, capsys, doc, "modal", r"either speed \(rad/s\) or speed_rpm")


def test_missing_tables_for_a_command(tmp_path, capsys):
    _fails(tmp_path, capsys, _doc("rotor_friswell_anisotropic.toml"), "forced", r"unbalance_response")
    doc = _doc("rotor_friswell_anisotropic.toml")
    del doc["campbell"]
    _fails(tmp_path, capsys, doc, "campbell", r"campbell = None .*\[campbell\]")


def test_campbell_of_another_kind_is_an_error(capsys):
    assert main(["campbell", str(EX / "cantilever.toml")]) == 2
    assert "a model file with a [rotor] table" in capsys.readouterr().err


def test_free_free_rotor_reports_rigid_modes(tmp_path):
    """No bearing: at rest the four rigid-body modes of a free rotor (two translations, two tilts) are
    reported with omega = 0, then the flexible ones -- not a crash.  Spinning, the two tilts become
    the zero-frequency precession and the nutation of the rigid body at omega = Omega Ip / Id (Ip, Id
    of the whole rotor about its centre of mass; checked on a 1000x stiffer shaft, where flexibility
    shifts it by ~1e-6: tolerance 1e-4)."""
    doc = _doc("rotor_friswell_anisotropic.toml")
    del doc["rotor"]["bearing"]
    doc["analysis"].update(modes=6, speed_rpm=0)
    out = tmp_path / "m.json"
    assert main(["modal", str(_write(tmp_path, doc)), "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert d["rigid_body_modes"] == 4 and d["omega_rad_s"][:4] == [0.0] * 4 and d["omega_rad_s"][4] > 100
    c = tmp_path / "c.json"
    assert main(["campbell", str(_write(tmp_path, doc)), "--json", str(c)]) == 0
    assert all(cs["kind"] != "rigid" for cs in json.loads(c.read_text())["critical_speeds"])

    doc["analysis"]["speed_rpm"] = 4000
    doc["rotor"]["material"].update(E=211e12, G=81.2e12)
    m = Study.parse(doc).modal()
    assert m.rigid.sum() == 3 and m.whirl[3] == "forward"
    rho, r, L = 7810.0, 0.025, 1.5
    ms = rho * np.pi * r * r * L
    parts = [(ms, ms * r * r / 2, ms * L * L / 12 + ms * r * r / 4, 0.75)]
    for x, dd in ((0.5, 0.28), (1.0, 0.35)):
        md = rho * np.pi * (dd**2 - 0.05**2) * 0.07 / 4
        ip = md * (dd**2 + 0.05**2) / 8
        parts.append((md, ip, ip / 2 + md * 0.07**2 / 12, x))
    xc = sum(p[0] * p[3] for p in parts) / sum(p[0] for p in parts)
    Ip = sum(p[1] for p in parts)
    Id = sum(p[2] + p[0] * (p[3] - xc) ** 2 for p in parts)
    assert m.omega_damped_rad_s[3] == pytest.approx(4000 * np.pi / 30 * Ip / Id, rel=1e-4)


def test_python_api_and_file_agree():
    """The file maps field for field onto fem.rotor: the same rotor through the Python API."""
    from examples.rotor_friswell import VARIANTS, friswell
    from fem.rotor import rotor_modes, rpm

    m_api = rotor_modes(friswell(VARIANTS["anisotropic (5.9.2)"], dofs="lateral"), rpm(4000), 6)
    m_file = Study.load(EX / "rotor_friswell_anisotropic.toml").modal()
    assert m_file.omega_damped_rad_s == pytest.approx(m_api.omega_damped_rad_s, rel=1e-12)


def test_parse_rejects_geometry_and_inertia_together():
    doc = copy.deepcopy(_doc("rotor_friswell_anisotropic.toml"))
    doc["rotor"]["disc"][0]["mass"] = 10.0
    with pytest.raises(ModelError, match=r"either the inertia .* or the geometry"):
        Study.parse(doc)


def test_rotor_schema_kind(tmp_path):
    from fem.modelfile.load import schema_json

    s = schema_json("rotor")
    assert s["title"] == "drivefem rotor model file" and s["additionalProperties"] is False
    out = tmp_path / "rotor.schema.json"
    assert main(["schema", "rotor", "--out", str(out)]) == 0
    assert "RotorBearing" in json.loads(out.read_text())["$defs"]
