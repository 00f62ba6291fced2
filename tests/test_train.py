"""Geared trains (fem.train, kind train): one-shaft trains equal the single-shaft files, the mesh's
line of action, speed ratios, bad input."""
from __future__ import annotations

import math

import numpy as np
import pytest

from discrete.errors import ModelError
from fem.modelfile.source import read_toml
from fem.study import Study
from validation.examples import EXAMPLES


def test_one_fe_shaft_train_equals_the_fe_file_bit_for_bit():
    fe = read_toml(EXAMPLES / "cantilever.toml")
    doc = {"title": "t", "shaft": [{"name": "s", **{k: fe[k] for k in ("model", "material", "segment", "support",
                                                                        "point") if k in fe}}]}
    ts = Study.parse(doc).train
    sys_ = Study.load(EXAMPLES / "cantilever.toml").fe_model.system
    for a, b in ((ts.M, sys_.M), (ts.K0, sys_.K)):
        assert (abs(a - b) > 0).nnz == 0
    assert np.array_equal(ts.constrained, sys_.constrained)


def test_one_rotor_train_equals_the_rotor_file_bit_for_bit():
    rot = read_toml(EXAMPLES / "rotor_friswell_damped.toml")
    doc = {"title": "t", "shaft": [{"name": "r", "rotor": rot["rotor"]}], "analysis": {"speed_rpm": 4000.0}}
    st = Study.parse(doc)
    ref = Study.load(EXAMPLES / "rotor_friswell_damped.toml")
    ts, rs = st.train, ref.rotor
    for a, b in ((ts.M, rs.M), (ts.K0, rs.K0), (ts.C0, rs.C0), (ts.G, rs.G)):
        assert (abs(a - b) > 0).nnz == 0
    m1 = st.modal(6)
    m2 = ref.modal(6)
    assert np.allclose(m1.eigenvalues, m2.eigenvalues, rtol=1e-9, atol=0)


def test_speed_ratio_and_line_of_action_of_an_external_and_an_internal_pair():
    from fem.model import PointAttachment, Segment, ShaftModel
    from fem.sections import Material, Section
    from fem.train import GearMesh, Port, Train, TrainBody, assemble_train

    bodies = [TrainBody("a", 1.0), TrainBody("b", 2.0), TrainBody("c", 3.0)]
    ext = GearMesh("e", (Port(body="a"), Port(body="b")), stiffness=1e8, base_radius=(0.05, 0.1))
    inn = GearMesh("i", (Port(body="b"), Port(body="c")), stiffness=1e8, base_radius=(0.1, 0.3), internal=True)
    ts = assemble_train(Train([], bodies, [ext, inn]))
    assert ts.ratios == pytest.approx({"a": 1.0, "b": -0.5, "c": -0.5 / 3})
    # the rigid rotation at the ratios leaves both meshes unstrained
    r = np.array([ts.ratios[n] for n in "abc"])
    assert abs(ts.K0 @ r).max() < 1e-6
    # a loop that does not close is refused
    bad = GearMesh("x", (Port(body="a"), Port(body="c")), stiffness=1e8, base_radius=(0.05, 0.1))
    with pytest.raises(ModelError, match="does not close"):
        assemble_train(Train([], bodies, [ext, inn, bad]))


def _two_shaft(**mesh):
    doc = read_toml(EXAMPLES / "geared_two_shaft_torsion.toml")
    doc["mesh"][0].update(mesh)
    return doc


@pytest.mark.parametrize("change, key", [
    ({"between": [{"shaft": "nope", "x": 0.8}, {"shaft": "output", "x": 0.0}]}, "shaft = 'nope'"),
    ({"between": [{"shaft": "input", "x": 0.33}, {"shaft": "output", "x": 0.0}]}, "x = 0.33"),
    ({"between": [{"shaft": "input", "x": 0.8}, "ground"]}, "not the ground"),
    ({"base_radius": None}, "base_radius"),
    ({"variation": {"fourier": [[1, 0.1, 0.0]]}}, "teeth"),
    ({"stiffness": -1.0}, "stiffness"),
])
def test_bad_mesh_input_names_table_key_and_value(change, key):
    doc = _two_shaft(**change)
    if change.get("base_radius", 1) is None:
        del doc["mesh"][0]["base_radius"]
    with pytest.raises(ModelError) as exc:
        Study.parse(doc).train
    assert key in str(exc.value)


def test_train_keys_of_other_kinds_are_refused_with_a_hint():
    doc = read_toml(EXAMPLES / "geared_two_shaft_torsion.toml")
    doc["segment"] = [{"length": 1.0, "elements": 2, "section": {"shape": "circle", "d": 0.1}}]
    with pytest.raises(ModelError, match="shaft.segment"):
        Study.parse(doc)


def test_cli_modal_and_campbell_of_a_train(tmp_path):
    from fem.app.cli import main
    import json

    out = tmp_path / "m.json"
    assert main(["modal", str(EXAMPLES / "geared_two_shaft_torsion.toml"), "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert d["kind"] == "train" and len(d["omega_rad_s"]) == 6 and d["speed_ratios"]["output"] == pytest.approx(-1 / 3)
    out = tmp_path / "c.json"
    assert main(["campbell", str(EXAMPLES / "geared_ross_two_shaft.toml"), "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert d["critical_speeds"] and d["speed_ratios"]["turbine"] == pytest.approx(-328 / 23)


def _write(tmp_path, doc, name="m.toml"):
    import tomli_w

    p = tmp_path / name
    p.write_bytes(tomli_w.dumps(doc).encode())
    return p


def test_cli_forced_simulate_parametric_of_trains(tmp_path):
    """The commands on small versions of the examples: exit 0, the JSON's keys, the force balance."""
    import json

    from fem.app.cli import main

    doc = read_toml(EXAMPLES / "geared_two_stage.toml")
    doc["forced"]["speeds_rpm"]["points"] = 3
    doc["simulation"]["t_end"] = 0.002
    p = _write(tmp_path, doc)
    out = tmp_path / "f.json"
    assert main(["forced", str(p), "--json", str(out), "--csv", str(tmp_path / "f.csv")]) == 0
    d = json.loads(out.read_text())
    assert d["kind"] == "train" and d["force_balance_max_residual"] < 1e-10
    assert d["section_loads_static"]["intermediate"]["quantities"]
    out = tmp_path / "s.json"
    doc["simulation"]["record_every"] = 2
    p = _write(tmp_path, doc)
    assert main(["simulate", str(p), "--json", str(out), "--h5", str(tmp_path / "s.h5"), "--csv",
                 str(tmp_path / "s.csv")]) == 0
    d = json.loads(out.read_text())
    assert d["force_balance"]["max_residual"] < 1e-10 and "stage 1" in d["connection_forces"]
    named = d["named_outputs"]          # mesh forces with their load factors, bearing reactions (docs/outputs.md)
    assert named["stage 1.force"]["unit"] == "N" and named["stage 1.force"]["peak"] == pytest.approx(
        d["connection_forces"]["stage 1"]["max"], rel=1e-14)
    assert named["output:bearing1@x=0.force_y"]["source"] == "bearing"
    import h5py

    with h5py.File(tmp_path / "s.h5") as h:
        assert "stage 1.force" in [n.decode() for n in h["outputs/names"][()]] and h.attrs["record_every"] == 2
        assert h["t"].size == d["history"]["samples"] and h.attrs["n_samples_recorded"] > h["t"].size
    doc = read_toml(EXAMPLES / "geared_mesh_parametric.toml")
    doc["parametric"].update(speeds={"start": 600.0, "stop": 720.0, "points": 5}, depth={"stop": 1.0, "points": 2})
    p = _write(tmp_path, doc, "p.toml")
    out = tmp_path / "p.json"
    assert main(["parametric", str(p), "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert d["tooth_pass_per_speed"] == 30 and d["boundaries"]


def test_rattle_steady_by_shooting_and_a_sweep_point(tmp_path):
    """The gear pair's steady state by shooting at one frequency equals a long simulation's last period; the
    sweep command evaluates it (serially)."""
    from fem.app.sweep import evaluate_point

    doc = read_toml(EXAMPLES / "geared_rattle.toml")
    doc["steady"] = {"method": "shooting", "omega": [14000.0, 14100.0], "response": {"element": "mesh",
                                                                                       "measure": "max"}}
    rec = evaluate_point(doc, {"force.0.omega": 14000.0}, "steady", periods=200)
    assert rec["status"] == "ok", rec
    r = rec["result"]
    assert r["converged"] and r["stable"] and abs(r["response"] / r["response_observed"] - 1) < 1e-6


def test_mesh_contact_is_the_gap_law_and_refuses_bad_values():
    import scipy.sparse as sp_

    from discrete.linear_system import LinearSystem
    from discrete.nonsmooth import Problem, simulate
    from discrete.nonsmooth.elements import Gap, MeshContact

    ls = LinearSystem(M=sp_.eye(1), K=sp_.csr_matrix((1, 1)), dof_field=["x"], dof_name=["q"])
    runs = [simulate(Problem(ls, [el], x0=np.array([1.0])), 20.0)
            for el in (Gap("g", np.ones(1), k=1.0, lower=-0.1, upper=0.2),
                       MeshContact("m", np.ones(1), k=1.0, lower=-0.1, upper=0.2))]
    assert np.array_equal(runs[0].x, runs[1].x)
    with pytest.raises(ModelError, match="stiffness stays positive"):
        MeshContact("m", np.ones(1), k=1.0, harmonics=((1, 0.9, 0.5),), omega=1.0, engaged=True)
    with pytest.raises(ModelError, match="tooth-pass"):
        MeshContact("m", np.ones(1), k=1.0, harmonics=((1, 0.1, 0.0),), engaged=True)


def test_slip_coupling_sticks_when_the_load_catches_up():
    """A load body dragged by a slipping coupling from a driver at constant speed V: it accelerates at
    S / I until it reaches V, at t* = I V / S, and then sticks (exact events)."""
    I, V, S = 0.5, 10.0, 2.0
    doc = {"title": "slip coupling", "body": [{"name": "drive", "inertia": 1.0}, {"name": "load", "inertia": I}],
           "driver": [{"at": "drive", "velocity": V}],
           "coupling": [{"name": "clutch", "between": ["drive", "load"], "slip_torque": S}],
           "simulation": {"t_end": 4.0}}
    sim = Study.parse(doc).simulate()
    sticks = sim.result.event_times("stick")
    assert sticks.size == 1 and abs(sticks[0] - I * V / S) < 1e-12 * I * V / S
    assert sim.force_balance.max_residual < 1e-12
    # the named output of the clutch is its friction torque: the slip torque S while it slips (on the
    # load, positive: it drags the load forward), then the load's inertia force I a = 0 while stuck
    outs = Study.parse(doc).outputs(sim)
    T = outs.column("clutch.torque")
    t = outs.axis_values
    slipping, stuck = (t > 0) & (t < 0.99 * I * V / S), t > 1.01 * I * V / S
    assert outs.channels[outs.names.index("clutch.torque")].unit == "N*m"
    assert np.allclose(np.abs(T[slipping]), S, rtol=1e-12) and np.allclose(T[stuck], 0.0, atol=1e-9 * S)
    with pytest.raises(ModelError, match="slip coupling is rigid"):
        doc["coupling"][0]["k_torsion"] = 1e3
        Study.parse(doc).train


@pytest.mark.slow
def test_the_figures_script_reproduces_the_documented_numbers(tmp_path):
    """examples/geared_trains.py (the figures of docs/geared.md) and the numbers the page quotes."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("geared_trains", EXAMPLES / "geared_trains.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    r = mod.main(tmp_path)
    assert r["two_stage_static_mesh_force_N"]["stage 1"] == pytest.approx(354.726, rel=1e-5)
    assert r["two_stage_max_dlf"]["stage 2"] == pytest.approx(2.8816, rel=1e-3)
    assert r["two_stage_balance"] < 1e-11 and r["two_stage_sim_balance"] < 1e-11
    assert r["two_stage_sim_events"] > 10
    assert r["rattle_folds_shooting"] == pytest.approx(r["rattle_folds_exact"], rel=1e-6)
    assert r["rattle_folds_hb"] == pytest.approx(r["rattle_folds_exact"], rel=1e-4)
    assert r["parametric_principal_rad_s"] == pytest.approx([636.381, 696.453], rel=1e-5)
    assert sorted(p.name for p in tmp_path.glob("*.png")) == sorted(
        ["geared_compressor_campbell.png", "geared_mesh_parametric.png", "geared_rattle_afc.png",
         "geared_two_stage_loads.png", "geared_two_stage_rattle.png"])
