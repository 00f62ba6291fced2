"""``drivefem parametric`` and ``[analysis] type = "parametric"``: the model-file chart (JSON contract, PNG,
CSV), the modulation parts of lumped and FE files, and bad input (exit 2 with table, key, value, allowed).
The book's numbers from the full example are checked by the validation case parametric_model_file."""
from __future__ import annotations

import copy
import csv
import json
import tomllib
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp

from discrete.errors import ModelError
from discrete.linear import parametric as par
from discrete.linear.harmonic import Damping
from fem.app.cli import main
from fem.modelfile.build.parametric import modulations, parametric_spec, run
from fem.study import Study
from validation.analytic import parametric as ref

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "parametric_drive.toml"


def small_example(tmp_path, **analysis) -> Path:
    """The example with a coarse grid (the test stays fast), and ``analysis`` keys replaced."""
    text = EXAMPLE.read_text().replace("points = 161", "points = 41").replace("points = 61", "points = 13")
    doc = tomllib.loads(text)
    path = tmp_path / "model.toml"
    if analysis:
        doc["analysis"].update(analysis)
        path.write_text(_dumps(doc))
    else:
        path.write_text(text)
    return path


def _dumps(doc: dict) -> str:
    """A minimal TOML writer for the dicts of these tests (tables, arrays of tables, inline values)."""
    def val(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, dict):
            return "{ " + ", ".join(f"{k} = {val(x)}" for k, x in v.items()) + " }"
        if isinstance(v, list):
            return "[" + ", ".join(val(x) for x in v) + "]"
        return repr(v)

    lines = [f"{k} = {val(v)}" for k, v in doc.items() if not isinstance(v, (dict, list)) or
             (isinstance(v, list) and not (v and isinstance(v[0], dict)))]
    for k, v in doc.items():
        if isinstance(v, dict):
            lines.append(f"[{k}]")
            subs = {s: x for s, x in v.items() if isinstance(x, list) and x and isinstance(x[0], dict)}
            lines += [f"{s} = {val(x)}" for s, x in v.items() if s not in subs]
            for s, items in subs.items():
                for it in items:
                    lines.append(f"[[{k}.{s}]]")
                    lines += [f"{a} = {val(b)}" for a, b in it.items()]
        elif isinstance(v, list) and v and isinstance(v[0], dict):
            for it in v:
                lines.append(f"[[{k}]]")
                lines += [f"{a} = {val(b)}" for a, b in it.items()]
    return "\n".join(lines) + "\n"


def test_cli_writes_json_png_csv(tmp_path, capsys):
    model = small_example(tmp_path)
    js, png, table = tmp_path / "c.json", tmp_path / "c.png", tmp_path / "c.csv"
    assert main(["parametric", str(model), "--json", str(js), "--png", str(png), "--csv", str(table)]) == 0
    d = json.loads(js.read_text())
    assert d["schema"] == "drivefem.parametric" and d["version"] >= 1 and d["kind"] == "lumped"
    assert np.shape(d["rho_max"]) == (13, 41) and len(d["omega_ratio"]) == 41
    assert d["omega_ratio"][0] == pytest.approx(0.5) and d["omega_rad_s"][-1] == pytest.approx(250.0)
    th = d["thresholds"][0]
    hill = ref.hill_damped_threshold(2.0, zeta=ref.zeta_from_psi(0.2))
    assert th["depth_at_centre"] == pytest.approx(hill, rel=1e-8)            # independent of the grid
    b = [x for x in d["boundaries"] if x["depth"] == 0.1][0]
    lo, hi = ref.hill_damped_edges(0.1, zeta=ref.zeta_from_psi(0.2))
    assert np.array(b["omega_low_rad_s"]) / 100 == pytest.approx([lo], rel=1e-8)
    assert np.array(b["omega_high_rad_s"]) / 100 == pytest.approx([hi], rel=1e-8)
    assert d["parts"] == ["[[spring]] #1 ['motor', 'rotor'] stiffness"] and d["omega_grid_unit"] == "omega_1"
    assert png.stat().st_size > 10_000 and png.read_bytes()[:4] == b"\x89PNG"
    rows = list(csv.DictReader(table.open()))
    assert len(rows) == 13 * 41
    unstable = [r for r in rows if r["stable"] == "0"]
    assert unstable and all(float(r["rho_max"]) >= 1.0 for r in unstable)
    assert all(float(r["depth"]) >= th["depth_minimum"] for r in unstable)
    out = capsys.readouterr().out
    assert "0.0636655" in out and "(1.960883, 2.037988)" in out


def test_body_inertia_modulation_equals_the_python_api():
    """``body = "rotor"`` (target inertia) builds the same part as the API's whole-M modulation of this
    one-body model, and the same threshold; a gear-reduced body carries u^2 J."""
    doc = tomllib.loads(EXAMPLE.read_text())
    doc["analysis"]["modulation"] = [{"target": "inertia", "body": "rotor", "harmonic": 1}]
    doc["analysis"]["depth"] = {"max": 0.3, "points": 2}
    doc["analysis"]["omega_ratio"] = {"start": 1.5, "stop": 2.5, "points": 5}
    spec = parametric_spec(Study.parse(doc))
    api = par.damping_threshold(Study.parse(doc).linear_system(), par.Modulation(target="inertia"),
                                damping=Damping("viscous"), search_minimum=False)
    th = par.damping_threshold(spec.problem, search_minimum=False)
    assert th.depth_at_centre == pytest.approx(api.depth_at_centre, rel=1e-12)
    # a geared body: x_b = u x_a, its inertia appears as u^2 J_b on the coordinate of a
    geared = {"body": [{"name": "a", "inertia": 1.0}, {"name": "b", "inertia": 0.5}],
              "driver": [{"name": "motor"}], "spring": [{"between": ["motor", "a"], "k": 1.0}],
              "gear": [{"between": ["a", "b"], "ratio": 3.0}],
              "analysis": {"type": "parametric", "omega_rad_s": {"start": 0.1, "stop": 1.0},
                           "depth": {"max": 0.5}, "modulation": [{"target": "inertia", "body": "b"}]}}
    study = Study.parse(geared)
    mods, parts = modulations(study, study.linear_system())
    assert mods[0].part.toarray() == pytest.approx(np.array([[0.5 * 9.0, 0.0], [0.0, 0.0]]))
    assert parts == ["[[body]] 'b' inertia"]


def test_fe_segment_and_point_parts():
    """FE parts: the stiffness parts of two segments add up to K (no point springs); the point's inertia
    part is its inertia on its DOF; the chart of a point-inertia pulsation projected on 4 modes equals the
    API's with the same part (omega_ratio scaled by the first mode of the mean system)."""
    doc = tomllib.loads((ROOT / "examples" / "torsion_shaft_disc.toml").read_text())
    doc["segment"] = [dict(doc["segment"][0], length=0.7, elements=7), dict(doc["segment"][0], length=0.5, elements=5)]
    doc["analysis"] = {"type": "parametric", "omega_ratio": {"start": 1.8, "stop": 2.2, "points": 3},
                       "depth": {"max": 0.2, "points": 2}, "thresholds": False, "modes": 4,
                       "modulation": [{"segment": 1}, {"segment": 2}, {"target": "inertia", "point": 1}]}
    doc["damping"] = {"psi": 0.2}
    study = Study.parse(doc)
    system = study.linear_system()
    mods, parts = modulations(study, system)
    K = system.K.toarray()
    assert (mods[0].part + mods[1].part).toarray() == pytest.approx(K, abs=1e-9 * np.abs(K).max())
    assert mods[0].part.toarray()[-1, -1] == 0.0 and mods[1].part.toarray()[0, 0] == 0.0
    tip = system.dof_index(field="theta", x=1.2)
    P = mods[2].part.toarray()
    assert P[tip, tip] == pytest.approx(0.00578, rel=1e-12) and np.count_nonzero(P) == 1
    assert parts[2] == "[[point]] #1 at x = 1.2 inertia"
    doc["analysis"]["modulation"] = [{"target": "inertia", "point": 1}]
    spec, chart = run(Study.parse(doc))
    part = sp.csr_matrix(([0.00578], ([tip], [tip])), shape=(system.n_dofs, system.n_dofs))
    api = par.stability_chart(system, par.Modulation(target="inertia", part=part), modes=4, thresholds=False,
                              damping=Damping("hysteretic", psi=0.2), omega_min=spec.omega_min,
                              omega_max=spec.omega_max, n_omega=3, depth_max=0.2, n_depth=2)
    assert chart.rho_max == pytest.approx(api.rho_max, rel=1e-12)
    assert spec.omega_min == pytest.approx(1.8 * api.natural_omega_rad_s[0], rel=1e-12)
    assert chart.projected and chart.n_dofs == 4


BAD = [
    (lambda a: a["modulation"][0].update(sprong=1), r"\[analysis\] modulation #1: sprong = 1 .*did you mean 'spring'"),
    (lambda a: a["modulation"][0].update(spring=3), r"\[analysis\] modulation #1: spring = 3 .*from 1 to 1"),
    (lambda a: a["modulation"][0].update(target="inertia"),
     r"\[analysis\] modulation #1: spring = 1 .*target = 'stiffness'"),
    (lambda a: a["modulation"].__setitem__(0, {"target": "inertia", "body": "rotr"}),
     r"\[analysis\] modulation #1: body = 'rotr' .*'rotor'"),
    (lambda a: a["modulation"].__setitem__(0, {"segment": 1}),
     r"\[analysis\] modulation #1: segment = 1 .*spring = \.\. .*lumped model"),
    (lambda a: a["modulation"][0].update(harmonic=0), r"\[analysis\] modulation #1: harmonic = 0 .*integer >= 1"),
    (lambda a: a.update(modulation=[]), r"\[analysis\]: modulation = \[\] .*at least one"),
    (lambda a: a.update(depth={"max": 1.5}), r"\[analysis.depth\]: max = 1.5 .*below 1"),
    (lambda a: a.update(depth={"max": 0.2, "min": 0.3}), r"\[analysis.depth\]: max = 0.2 .*above min = 0.3"),
    (lambda a: a.update(omega_ratio={"start": 2.0, "stop": 1.0}), r"\[analysis.omega_ratio\]: stop = 1.0 .*above start"),
    (lambda a: a.update(omega_rad_s={"start": 1.0, "stop": 2.0}), r"\[analysis\]: omega_rad_s = .*exactly one of"),
    (lambda a: a.pop("omega_ratio"), r"\[analysis\]: omega_rad_s = None .*exactly one of"),
    (lambda a: a.update(inertia_form="lagrange"), r"\[analysis\]: inertia_form = 'lagrange' .*'programme' \| 'momentum'"),
    (lambda a: a.update(boundaries_at=[0.5]), r"\[analysis\]: boundaries_at = \[0.5\] .*depth.max"),
    (lambda a: a.update(tolerance=0.1), r"\[analysis\]: tolerance = 0.1 .*<= 0.0001"),
    (lambda a: a.update(modes=5), r"modes = 5 .*from 1 to 1"),
    (lambda a: a.update(type="parametrik"), r"\[analysis\]: type = 'parametrik' .*'parametric'"),
]


@pytest.mark.parametrize("edit, message", BAD, ids=[m[:40] for _, m in BAD])
def test_bad_input_exits_2_with_a_clear_message(tmp_path, capsys, edit, message):
    doc = tomllib.loads(EXAMPLE.read_text())
    edit(doc["analysis"])
    path = tmp_path / "bad.toml"
    path.write_text(_dumps(doc))
    assert main(["parametric", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("drivefem: error: ") and "Traceback" not in err
    import re

    assert re.search(message, err), err


def test_wrong_analysis_kind_and_paths(tmp_path, capsys):
    assert main(["parametric", str(ROOT / "examples" / "two_mass_chain.toml")]) == 2
    assert "[analysis]: type = 'modal'" in capsys.readouterr().err
    assert main(["parametric", str(EXAMPLE), "--json", str(tmp_path)]) == 2           # a directory
    assert "--json" in capsys.readouterr().err
    drive = tomllib.loads((ROOT / "examples" / "drive_regular.toml").read_text())
    drive["analysis"] = {"type": "parametric", "omega_rad_s": {"start": 1.0, "stop": 2.0}, "depth": {"max": 0.1},
                         "modulation": [{}]}
    with pytest.raises(ModelError, match=r"\[analysis\]: type = 'parametric' .*FE or lumped model file"):
        run(Study.parse(drive))
    fe = tomllib.loads((ROOT / "examples" / "torsion_shaft_disc.toml").read_text())
    fe["analysis"] = copy.deepcopy(drive["analysis"])
    fe["analysis"]["modulation"] = [{"point": 1}]
    with pytest.raises(ModelError, match=r"modulation #1: point = 1 .*spring k or kr > 0"):
        run(Study.parse(fe))
