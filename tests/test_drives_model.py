"""The [drive] model file, the three representations and the CLI entry points (fem.drives)."""
import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

from discrete.errors import ModelError
from fem.modelfile.schema.document import detect_kind
from fem.output import columns
from fem.study import Study


def drive_modal(doc, n_modes):
    return Study.parse(doc).modal(n_modes)


def drive_forced(doc):
    return Study.parse(doc).forced()


def compare(doc):
    return Study.parse(doc).compare()


def parse_drive(doc):
    return Study.parse(doc).drive

EX = Path(__file__).resolve().parent.parent / "examples"


def load(name):
    with open(EX / name, "rb") as fh:
        return tomllib.load(fh)


def test_kind_detection():
    assert detect_kind(load("drive_regular.toml")) == "drive" and detect_kind({"segment": []}) == "fe"


@pytest.mark.parametrize("rep", ["discrete", "transfer-matrix", "continuum"])
def test_modal_three_representations(rep):
    doc = load("drive_regular.toml")
    doc["drive"]["representation"] = rep
    res = drive_modal(doc, None)
    d = res.to_dict()
    json.dumps(d)
    for key in ("omega_rad_s", "frequencies_hz", "n_dofs", "residuals", "representation"):
        assert key in d
    assert len(d["omega_rad_s"]) == 12 and d["representation"] == rep
    assert np.allclose(d["frequencies_hz"], np.array(d["omega_rad_s"]) / (2 * np.pi))
    assert "omega [rad/s]" in res.table()
    if rep == "continuum":       # the pseudo-medium against (10.50): lowest root 286.34
        assert np.isclose(res.omega_rad_s[0], 286.3408, rtol=2e-6)
    else:                         # discrete and TM are exact: closed form to rounding
        assert np.max(res.rel_diff) < 1e-12
        assert np.isclose(res.omega_rad_s[6], 1080.7345, rtol=1e-7)


def test_forced_three_representations_agree():
    doc = load("drive_forced.toml")
    out = {}
    for rep in ("discrete", "transfer-matrix"):
        doc["drive"]["representation"] = rep
        r = drive_forced(doc)
        json.dumps(r.to_dict())
        assert "theta_n" in r.table()
        out[rep] = r.theta
        assert np.max(np.abs(r.theta - r.reference_theta)) < 1e-12 * np.max(np.abs(r.reference_theta))
    assert np.allclose(out["discrete"], out["transfer-matrix"], rtol=1e-10, atol=1e-18)


def test_forced_distributed_discrete_equals_exact_tm():
    """P2 FE shaft with 8 elements per segment vs exact continuous segments (TM), Set C n = 12."""
    doc = load("drive_continuum.toml")
    res = {}
    for rep in ("discrete", "transfer-matrix"):
        doc["drive"]["representation"] = rep
        res[rep] = drive_forced(doc).theta
    scale = np.max(np.abs(res["transfer-matrix"]), axis=1, keepdims=True)
    assert np.max(np.abs(res["discrete"] - res["transfer-matrix"]) / scale) < 1e-6


def test_damped_forced_discrete_tm_continuum_consistent():
    doc = load("drive_forced.toml")
    doc["damping"] = {"type": "hysteretic", "psi": 0.3}
    doc["analysis"]["omega_rad_s"] = [283.0, 480.0, 600.0]
    a = {}
    for rep in ("discrete", "transfer-matrix"):
        doc["drive"]["representation"] = rep
        r = drive_forced(doc)
        assert r.reference_theta is None and "hysteretic" in r.damping
        a[rep] = r.theta
    assert np.allclose(a["discrete"], a["transfer-matrix"], rtol=1e-10, atol=0)
    assert np.all(np.abs(a["discrete"].imag) > 0)


def test_compare_report_and_convergence():
    doc = load("drive_regular.toml")
    doc["analysis"]["convergence_n"] = [6, 12, 24]
    c = compare(doc)
    d = c.to_dict()
    json.dumps(d)
    rows = d["representations"]
    assert np.allclose(rows["discrete"]["lower_rad_s"], rows["transfer-matrix"]["lower_rad_s"], rtol=1e-10)
    assert np.allclose(rows["continuum"]["upper_rad_s"][:1], rows["pseudo-medium (10.50)"]["upper_rad_s"][:1], rtol=1e-6)
    orders = np.array(d["convergence"]["observed_order_r1"])
    assert np.all((orders > 0.9) & (orders < 1.1))          # O(1/n)
    assert "pseudo-medium" in c.table()


def _bad(mutate, match):
    doc = load("drive_regular.toml")
    mutate(doc)
    with pytest.raises(ModelError, match=match):
        parse_drive(doc)


def test_bad_input():
    _bad(lambda d: d["drive"].update(n=0), "n")
    _bad(lambda d: d["drive"].update(n=2.5), "n")
    _bad(lambda d: d["drive"]["mechanism"].update(ratio=0.0), "ratio")
    _bad(lambda d: d["drive"].update(boundary="pinned-free"), "boundary")
    _bad(lambda d: d["drive"].update(representation="fem"), "representation")
    _bad(lambda d: d["drive"].update(colour="red"), "colour")
    _bad(lambda d: d["drive"]["shaft"].update(length=2.0), "length")       # a distributed-shaft key
    _bad(lambda d: d["drive"]["mechanism"].update(c=1.0), "exactly one of c")
    _bad(lambda d: d["drive"]["mechanism"].pop("m"), "m")
    _bad(lambda d: d["drive"]["shaft"].update(c0=-1.0), "c0")
    _bad(lambda d: d.update(segment=[]), "segment")
    _bad(lambda d: d["drive"].update(boundary="free-free", n=1), "n >= 2")
    doc = load("drive_regular.toml")
    doc["analysis"]["modes"] = 0
    with pytest.raises(ModelError, match="modes"):
        drive_modal(doc, None)
    doc = load("drive_regular.toml")
    doc["damping"] = {"type": "rayleigh"}
    with pytest.raises(ModelError, match="damping|type"):
        drive_modal(doc, None)
    doc = load("drive_forced.toml")
    doc["drive"]["load"]["force"] = 0.0
    with pytest.raises(ModelError, match="force"):
        drive_forced(doc)


def test_rigid_mechanisms_from_toml_inf():
    doc = tomllib.loads((EX / "drive_regular.toml").read_text().replace("k = 300.0", "c = inf"))
    for rep in ("discrete", "transfer-matrix"):
        doc["drive"]["representation"] = rep
        w = drive_modal(doc, 3).omega_rad_s
        p0 = np.sqrt(6e4 / (0.02 / 6 + 10 / 6 * 0.05**2))
        assert np.allclose(w / p0, [0.24107336, 0.70920977, 1.13612949], rtol=1e-7)


@pytest.mark.parametrize("boundary", ["clamped-free", "clamped-clamped", "free-free", "free-clamped"])
def test_boundaries_three_ways(boundary):
    doc = load("drive_continuum.toml")
    doc["drive"]["boundary"] = boundary
    doc["drive"]["n"] = 6
    doc["drive"]["mechanism"]["m"] = 10.0 / 6
    w = {}
    for rep in ("discrete", "transfer-matrix"):
        doc["drive"]["representation"] = rep
        w[rep] = drive_modal(doc, 8).omega_rad_s
    assert np.allclose(w["discrete"], w["transfer-matrix"], rtol=1e-6, atol=1e-6)


def test_forced_csv_and_modal_ok(tmp_path):
    doc = load("drive_forced.toml")
    r = drive_forced(doc)
    columns.write(tmp_path / "f.csv", columns.drive_forced(r))
    data = np.loadtxt(tmp_path / "f.csv", delimiter=",", skiprows=1)
    assert data.shape == (7, 2 + 4 * 6)
    assert np.allclose(data[:, 2], r.theta[:, 0].real)
    m = drive_modal(load("drive_regular.toml"), None)
    assert m.ok


def test_distributed_discrete_reference_is_exact_tm():
    doc = load("drive_continuum.toml")
    doc["drive"]["representation"] = "discrete"
    r = drive_modal(doc, 14)
    assert "exact continuous" in r.reference
    assert np.max(r.rel_diff) < 1e-5          # P2 x 8 per segment vs exact segments
    assert np.max(r.rel_diff) > 1e-12         # a real discretisation error, not a self-comparison


def test_runner_json_and_exit_codes(tmp_path, capsys):
    from fem.app.cli import main

    out = tmp_path / "m.json"
    assert main(["modal", str(EX / "drive_regular.toml"), "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert {"omega_rad_s", "frequencies_hz", "n_dofs", "residuals", "representation"} <= set(d)
    assert main(["forced", str(EX / "drive_forced.toml"), "--json", str(out), "--csv", str(tmp_path / "f.csv")]) == 0
    assert json.loads(out.read_text())["omega_rad_s"][0] == 50.0
    assert main(["forced", str(EX / "drive_regular.toml")]) == 2          # [analysis] type = "modal"
    assert "forced" in capsys.readouterr().err
