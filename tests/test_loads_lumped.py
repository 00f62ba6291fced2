"""Loads as named outputs (issue 25): element forces and reactions balance the inertia forces of every
body at every recorded instant (every lumped and hybrid example), the solver's multipliers and impulses
are what the outputs report, a driver's reaction is m a minus the applied forces, and the linear
analyses name what they did with every nonsmooth element."""
from __future__ import annotations

import json
import subprocess
import tomllib
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as sla

from discrete.errors import ModelError
from fem.loads.analyses import modal_outputs, time_outputs
from fem import modelfile
from fem.study import Study

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"


def _sim_examples():
    """The lumped and hybrid examples with a [simulation] (rotor run-ups and geared trains balance their
    shafts in their own tests: tests/test_rotor_runup*.py, geared-two-stage-loads)."""
    from fem.modelfile.schema.document import detect_kind

    out = []
    for p in sorted(EXAMPLES.glob("*.toml")):
        d = tomllib.loads(p.read_text())
        if "simulation" in d and detect_kind(d) in ("lumped", "hybrid"):
            out.append(p.name)
    return out


def _shortened(name: str, factor: float = 0.2) -> Study:
    """The example with t_end shortened (the balance holds at every instant; the test stays fast)."""
    d = tomllib.loads((EXAMPLES / name).read_text())
    d["simulation"]["t_end"] *= factor
    d.pop("sweep", None)
    doc = modelfile.parse(d)
    object.__setattr__(doc, "__source__", EXAMPLES / name)    # sidecar files (super-elements) beside the example
    return Study(doc, EXAMPLES / name)


def _inertia_forces(study, solver, loads):
    """[({named coordinate: weight}, inertia force history)] to balance: each lumped body of a lumped file,
    (m0 + t dm/dt) a + epsilon dm/dt v (seed 004's Newton form); for a hybrid file each rigid-body motion
    r of the whole drive (the null space of its stiffness, held coordinates included): r^T (M a + C' v)
    with C' the damping that is not a [[damper]] or spring dashpot (whose forces are outputs)."""
    if study.kind == "lumped":
        names = study.lumped.names
        _, T = study.lumped.transformation()
        acc, vel = T @ solver.acceleration, T @ solver.v
        out = []
        for b in study.lumped.bodies:
            i = names.index(b.name)
            f = (b.inertia + b.inertia_rate * solver.t) * acc[i] + b.reactive * b.inertia_rate * vel[i]
            out.append(({b.name: 1.0}, f))
        return out
    sys_ = study.compiled.system
    K, M, C = sys_.K.toarray(), sys_.M.toarray(), sys_.C.toarray()
    for ln in loads.links:
        C = C - ln.c * np.outer(ln.g, ln.g)
    R = sla.null_space(K, rcond=1e-9)
    names = loads.coords.names
    return [({names[i]: r[i] for i in np.flatnonzero(r)}, r @ (M @ solver.acceleration + C @ solver.v)) for r in R.T]


def _balance(out, items) -> float:
    """max over the items and instants of |inertia force - the loads on it| / their scale."""
    worst = 0.0
    for weights, force in items:
        terms = [(sum(w * c.acts_on.get(n, 0.0) for n, w in weights.items()), out.values[k])
                 for k, c in enumerate(out.channels)]
        terms = [(w, y) for w, y in terms if w != 0]
        total = sum((w * y for w, y in terms), 0.0 * force)
        scale = max([np.max(np.abs(force))] + [np.max(np.abs(w * y)) for w, y in terms] + [1e-300])
        worst = max(worst, float(np.max(np.abs(force - total)) / scale))
    return worst


@pytest.mark.parametrize("name", _sim_examples())
def test_element_loads_balance_inertia_at_every_instant(name):
    """Every body of every lumped and hybrid example: inertia times its acceleration (the solver's, from
    its equations in each mode) equals the sum of the loads the outputs report on it -- link forces (from
    the file's k, c and ratios), element forces (laws and multipliers), gear forces, applied loads --
    at every recorded instant, to round-off."""
    st = _shortened(name)
    res = st.simulate()
    solver = res.solver if st.kind == "hybrid" else res
    loads = st.time_loads
    a, f_app = solver.acceleration, solver.applied
    if a is None:
        problem = st.compiled.problem if st.kind == "hybrid" else st.problem_spec().problem()
        a, f_app = problem.recover(solver.t, solver.x, solver.v, solver.element_forces)
        solver.acceleration = a
    out = time_outputs(loads.map, solver.t, solver.x, solver.v, a, solver.element_forces, f_app)
    items = _inertia_forces(st, solver, loads)
    assert items
    assert _balance(out, items) < 1e-9


def _stick_samples(res, element: str) -> np.ndarray:
    """Indices of the recorded samples strictly inside the stick phases of ``element``."""
    ev = [(e.t, e.kind) for e in res.events if e.element == element and e.kind in ("stick", "slip", "reversal")]
    mask = np.zeros(res.t.size, dtype=bool)
    for (t0, k0), (t1, _) in zip(ev, ev[1:]):
        if k0 == "stick":
            mask |= (res.t > t0) & (res.t < t1)
    return np.flatnonzero(mask)


@pytest.mark.parametrize("name, element", [("discrete_seed000_stick_slip.toml", "bit"),
                                           ("hybrid_drill_string.toml", "bit")])
def test_friction_force_in_stick_is_the_solvers_multiplier(name, element):
    """In stick the friction output is the Lagrange multiplier of the constraint s' = surface speed:
    recomputed here from the recorded state by solving the constrained equations afresh
    (Problem.evaluate in the stick mode), it equals the output at every stick sample (seed 000, the drill
    string's bit)."""
    st = Study.load(EXAMPLES / name)
    res = st.simulate()
    solver = res.solver if st.kind == "hybrid" else res
    out = st.outputs(res)
    p = st.compiled.problem if st.kind == "hybrid" else st.problem_spec().problem()
    i = [el.name for el in p.elements].index(element)
    ks = _stick_samples(solver, element)
    assert ks.size > 10
    lam = []
    for k in ks:
        e = p.basis(solver.t[k])
        mode = [0 if j == i else el.initial_mode(*p.coords(j, solver.x[p.f, k], solver.v[p.f, k], e), 1.0)
                for j, el in enumerate(p.elements)]
        ev = p.evaluate(solver.t[k], solver.x[p.f, k][:, None], solver.v[p.f, k][:, None], e[:, None], tuple(mode))
        lam.append(ev["F"][i, 0])
    F = out.column(f"{element}.force")[ks]
    assert np.max(np.abs(F - np.array(lam))) <= 1e-9 * np.max(np.abs(F))


def test_contact_forces_are_their_laws_of_the_recorded_deflection():
    """The backlash of the cam example: -k (s - bound) beyond the clearance, zero inside; seed 002's strand
    (discrete_strand_spool.toml): -k (s - s_open) while taut (s > s_open = -F0/k), zero when slack."""
    st = Study.load(EXAMPLES / "cam_clearance.toml")
    out = st.outputs(st.simulate())
    s, F = out.column("backlash.deflection"), out.column("backlash.force")
    k, d = 2.0e5, 0.0005
    law = np.where(s > d, -k * (s - d), np.where(s < -d, -k * (s + d), 0.0))
    assert np.any(law != 0)
    assert np.max(np.abs(F - law)) <= 1e-9 * np.max(np.abs(F))
    st = Study.load(EXAMPLES / "discrete_strand_spool.toml")
    res = st.simulate()
    out = st.outputs(res)
    s, F = out.column("strand.deflection"), out.column("strand.force")
    k = 43440.333333333336
    s_open = -30.0 / k
    law = np.where(s > s_open, -k * (s - s_open), 0.0)
    assert np.any(law == 0) and np.any(law != 0)                # slack phases and taut ones
    assert np.max(np.abs(F - law)) <= 1e-9 * np.max(np.abs(F))


@pytest.mark.parametrize("name, element", [("discrete_bouncing_ball.toml", "floor"), ("hybrid_bar_wall.toml", "wall")])
def test_impact_impulses_are_the_momentum_jumps(name, element):
    """The impulse of every impact event equals the momentum jump along the element's s, g . (M dv) / |g|^2,
    from the states recorded just before and after it; the element summary counts and sums them."""
    st = Study.load(EXAMPLES / name)
    res = st.simulate()
    solver = res.solver if st.kind == "hybrid" else res
    p = st.compiled.problem if st.kind == "hybrid" else st.problem_spec().problem()
    i = [el.name for el in p.elements].index(element)
    g = p.gf[i]
    impacts = [e for e in solver.events if e.kind == "impact" and e.element == element]
    assert impacts
    for e in impacts:
        ks = np.flatnonzero(solver.t == e.t)
        dv = solver.v[p.f, ks[-1]] - solver.v[p.f, ks[0]]
        P = float(g @ (p.M0 @ dv)) / float(g @ g)
        assert e.impulse == pytest.approx(P, rel=1e-9)
    summ = st.outputs(res).elements[element]
    assert summ["impacts"] == len(impacts)
    assert summ["impulse_sum"] == pytest.approx(sum(e.impulse for e in impacts), rel=1e-12)


def test_driver_reaction_is_inertia_times_acceleration_minus_applied_forces():
    """A driver of inertia J moving harmonically pulls a body through a spring: its reaction (the torque it
    must supply) is J a_d(t) - k (x_b - x_d), a_d from its law, x from the recorded history."""
    J, k, A, w = 0.3, 400.0, 0.02, 7.0
    doc = {"driver": [{"name": "crank", "inertia": J, "amplitude": A, "omega": w}],
           "body": [{"name": "slider", "inertia": 1.5}],
           "spring": [{"between": ["crank", "slider"], "k": k}],
           "friction": [{"name": "guide", "body": "slider", "kinetic": 0.5, "static": 0.8}],
           "simulation": {"t_end": 3.0, "output_step": 0.01}}
    st = Study.parse(doc)
    res = st.simulate()
    out = st.outputs(res)
    xd, xb = res.x[res.names.index("crank")], res.x[res.names.index("slider")]
    ad = -A * w * w * np.sin(w * res.t)
    R = J * ad - k * (xb - xd)
    assert np.max(np.abs(out.column("crank.reaction") - R)) <= 1e-9 * np.max(np.abs(R))


def test_friction_work_matches_the_energy_balance():
    """The sampled friction work of seed 000's bit equals the solver's exact friction work (the energy
    balance's category) to the sampling's accuracy."""
    st = Study.load(EXAMPLES / "discrete_seed000_stick_slip.toml")
    res = st.simulate()
    out = st.outputs(res)
    assert out.elements["bit"]["friction_work"] == pytest.approx(res.work_parts["friction"], rel=1e-3)


# ------------------------------------------------------------------ linear analyses
GAP_DRIVE = {"title": "gear mesh as a gap", "driver": [{"name": "motor"}],
             "body": [{"name": "pinion", "inertia": 0.02}, {"name": "wheel", "inertia": 0.5}],
             "spring": [{"between": ["motor", "pinion"], "k": 2e4}],
             "gap": [{"name": "mesh", "between": ["pinion", "wheel"], "ratios": [0.05, 0.15], "k": 2e8,
                      "delta": 5e-5}],
             "analysis": {"type": "modal"}}


def _hand(K, M):
    return np.sqrt(sla.eigh(np.array(K, float), np.diag(M), eigvals_only=True))


def test_modal_takes_a_gap_mesh_closed_by_default_and_says_so():
    """The issue's repro: a closed mesh is a spring 2e8 N/m along s = 0.15 phi_w - 0.05 phi_p; the two
    frequencies are those of the hand-assembled K and M; declared open, the wheel is free."""
    st = Study.parse(GAP_DRIVE)
    r = st.modal()
    kg = 2e8
    K = [[2e4 + kg * 0.05 ** 2, -kg * 0.05 * 0.15], [-kg * 0.05 * 0.15, kg * 0.15 ** 2]]
    assert np.allclose(r.omega_rad_s, _hand(K, [0.02, 0.5]), rtol=1e-12)
    assert st.linearisation == [{"element": "mesh", "kind": "gap", "state": "closed", "declared": False,
                                 "note": "closed: a spring of its contact stiffness k = 2e+08"}]
    doc = json.loads(json.dumps(GAP_DRIVE))
    doc["gap"][0]["linearise"] = "open"
    st2 = Study.parse(doc)
    r2 = st2.modal()
    assert r2.rigid[0] and r2.omega_rad_s[1] == pytest.approx(np.sqrt(2e4 / 0.02), rel=1e-12)
    assert st2.linearisation[0]["state"] == "open" and st2.linearisation[0]["declared"]


def test_modal_load_shapes_balance_the_modal_inertia_forces():
    """For every mode: -omega^2 I phi_b = the loads the load shapes put on body b (gap drive, geared
    example with its [[gear]] pair of geared_drive.toml)."""
    for doc in (GAP_DRIVE, tomllib.loads((EXAMPLES / "geared_drive.toml").read_text())):
        st = Study.parse(doc)
        r = st.modal()
        loads = st.linear_model
        out = modal_outputs(loads.load_map(), r.omega_rad_s, r.shapes[:loads.loads.coords.n])
        names = st.lumped.names
        _, T = st.lumped.transformation()
        acc = T @ (-(r.omega_rad_s ** 2) * r.shapes)
        items = [({b.name: 1.0}, b.inertia * acc[names.index(b.name)]) for b in st.lumped.bodies]
        assert _balance(out, items) < 1e-9


def test_modal_of_the_strand_spool_sees_the_taut_preloaded_strand():
    """examples/discrete_strand_spool.toml: the preloaded strand is taut at rest, so the spool oscillates at
    k = 54.15 rad/s (the file's header), not free at 0 Hz."""
    st = Study.load(EXAMPLES / "discrete_strand_spool.toml")
    r = st.modal()
    assert r.omega_rad_s[0] == pytest.approx(54.15, rel=1e-12)
    assert {(x["element"], x["state"]) for x in st.linearisation} == {("strand", "closed"), ("clutch", "sliding")}


def test_modal_of_the_cam_keeps_the_backlash_closed():
    """examples/cam_clearance.toml: follower (1 kg, 28 900 N/m to the cam) and output (0.5 kg, 500 N/m to
    ground) coupled by the closed backlash (2e5 N/m)."""
    st = Study.load(EXAMPLES / "cam_clearance.toml")
    r = st.modal()
    K = [[28900 + 2e5, -2e5], [-2e5, 2e5 + 500]]
    assert np.allclose(r.omega_rad_s, _hand(K, [1.0, 0.5]), rtol=1e-12)


def test_stuck_friction_holds_its_body_and_reports_the_constraint_force():
    """A stuck clutch between a driver and a body holds the body: the remaining mode is the other body's;
    the clutch's load shape balances the held body's inertia and spring forces."""
    doc = {"driver": [{"name": "shaft"}], "body": [{"name": "hub", "inertia": 0.4}, {"name": "rim", "inertia": 1.0}],
           "spring": [{"between": ["hub", "rim"], "k": 900.0}, {"between": ["ground", "hub"], "k": 100.0}],
           "friction": [{"name": "clutch", "between": ["shaft", "hub"], "kinetic": 5.0, "linearise": "stuck"}],
           "analysis": {"type": "modal"}}
    st = Study.parse(doc)
    r = st.modal()
    assert r.omega_rad_s.size == 1 and r.omega_rad_s[0] == pytest.approx(30.0, rel=1e-12)
    out = st.outputs(r)
    phi = r.shapes[:, 0]
    names = st.lumped.linear_system().dof_name.tolist()
    x_rim = phi[names.index("rim")]
    assert out.column("clutch.force")[0] == pytest.approx(-900.0 * x_rim, rel=1e-12)


def test_a_hold_across_two_free_bodies_is_refused_with_the_states_allowed():
    doc = {"body": [{"name": "a", "inertia": 1.0}, {"name": "b", "inertia": 1.0}],
           "spring": [{"between": ["ground", "a"], "k": 1.0}, {"between": ["ground", "b"], "k": 1.0}],
           "friction": [{"name": "f", "between": ["a", "b"], "kinetic": 1.0, "linearise": "stuck"}],
           "analysis": {"type": "modal"}}
    with pytest.raises(ModelError, match=r"\[\[friction\]\] 'f': linearise = 'stuck'.*'sliding'"):
        Study.parse(doc).modal()


def test_forced_loads_balance_at_every_frequency():
    """motor_drive_forced.toml: -omega^2 I Q_b equals the complex loads on each body (the motor's torque
    from its complex stiffness included)."""
    st = Study.load(EXAMPLES / "motor_drive_forced.toml")
    r = st.forced()
    out = st.outputs(r)
    names = st.lumped.names
    _, T = st.lumped.transformation()
    Q = T @ r.full[:, :T.shape[1]].T
    w = r.omega_rad_s
    items = [({b.name: 1.0}, -(w ** 2) * b.inertia * Q[names.index(b.name)]) for b in st.lumped.bodies]
    assert _balance(out, items) < 1e-9


# ------------------------------------------------------------------ command line
def _cli(*args):
    """``drivefem ARGS`` in this process: (exit code, stdout, stderr) as a CompletedProcess."""
    import contextlib
    import io

    from fem.app.cli import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(a) for a in args])
    return subprocess.CompletedProcess(args, code, out.getvalue(), err.getvalue())


def test_simulate_writes_loads_in_json_csv_and_h5(tmp_path):
    """seed 000 through the command line: the JSON summary names every output, the CSV has their columns,
    the HDF5 file (read with h5py alone) holds the same columns."""
    import h5py

    j, c, h = tmp_path / "s.json", tmp_path / "s.csv", tmp_path / "s.h5"
    p = _cli("simulate", EXAMPLES / "discrete_seed000_stick_slip.toml", "--json", j, "--csv", c, "--h5", h)
    assert p.returncode == 0, p.stderr
    d = json.loads(j.read_text())
    assert list(d["named_outputs"]) == ["spring[1] top-disk.deflection", "spring[1] top-disk.force", "bit.force",
                                  "bit.slip_velocity", "top.reaction"]
    assert d["named_outputs"]["top.reaction"]["dynamic_load_factor"] > 1
    assert d["history"]["file"] == str(h) and d["element_summary"]["bit"]["friction_dissipated"] > 0
    head = c.read_text().splitlines()[0].split(",")
    assert head[-5:] == list(d["named_outputs"])
    rows = np.array([[float(x) for x in line.split(",")] for line in c.read_text().splitlines()[1:]])
    with h5py.File(h, "r") as f:
        assert f.attrs["schema"] == "drivefem.history"
        names = [n.decode() for n in f["outputs/names"][()]]
        vals = f["outputs/values"][()]
        assert names == head[-5:]
        assert np.array_equal(vals, rows[:, -5:]) and np.array_equal(f["t"][()], rows[:, 0])
    assert "bit.force" in p.stdout and "DLF" in p.stdout


def test_output_tables_select_and_name_the_outputs(tmp_path):
    """geared_mesh.toml's [[output]] tables: the JSON keys and CSV columns are their names; the mesh
    force's mean is the brake torque over the wheel radius (50 / 0.15 N) to the transient's accuracy."""
    j, c = tmp_path / "g.json", tmp_path / "g.csv"
    p = _cli("simulate", EXAMPLES / "geared_mesh.toml", "--json", j, "--csv", c)
    assert p.returncode == 0, p.stderr
    d = json.loads(j.read_text())
    want = ["mesh force", "mesh deflection", "coupling torque", "output shaft twist", "motor torque", "drum speed"]
    assert list(d["named_outputs"]) == want
    assert c.read_text().splitlines()[0].split(",") == ["t"] + want
    mesh = d["named_outputs"]["mesh force"]
    assert mesh["mean"] == pytest.approx(50 / 0.15, rel=0.01)
    assert mesh["dynamic_load_factor"] == pytest.approx(mesh["peak"] / mesh["mean"], rel=1e-12)
    assert d["named_outputs"]["coupling torque"]["unit"] == "N m" and d["named_outputs"]["output shaft twist"]["unit"] == "rad"


def test_unknown_output_element_is_one_clear_line(tmp_path):
    doc = tomllib.loads((EXAMPLES / "discrete_seed000_stick_slip.toml").read_text())
    doc["output"] = [{"element": "bitt", "quantity": "torque"}]
    import tomli_w

    f = tmp_path / "m.toml"
    f.write_text(tomli_w.dumps(doc))
    p = _cli("simulate", f)
    assert p.returncode == 2
    assert "[[output]] #1: element = 'bitt'" in p.stderr and "'bit'" in p.stderr


def test_record_every_decimates_the_written_history_but_keeps_the_events(tmp_path):
    doc = tomllib.loads((EXAMPLES / "discrete_seed000_stick_slip.toml").read_text())
    doc["simulation"]["record_every"] = 10
    import tomli_w

    f = tmp_path / "m.toml"
    f.write_text(tomli_w.dumps(doc))
    full = Study.load(EXAMPLES / "discrete_seed000_stick_slip.toml").simulate()
    p = _cli("simulate", f, "--csv", tmp_path / "m.csv", "--json", tmp_path / "m.json")
    assert p.returncode == 0, p.stderr
    t = np.array([float(line.split(",")[0]) for line in (tmp_path / "m.csv").read_text().splitlines()[1:]])
    assert t.size < full.t.size / 5
    assert set(e.t for e in full.events) <= set(t.tolist())
    d = json.loads((tmp_path / "m.json").read_text())
    assert d["named_outputs"]["bit.force"]["peak"] == pytest.approx(18.0, rel=1e-12)     # summaries use every sample


def test_modal_and_forced_write_loads_and_the_linearisation(tmp_path):
    import tomli_w

    f = tmp_path / "gap.toml"
    f.write_text(tomli_w.dumps(GAP_DRIVE))
    p = _cli("modal", f, "--json", tmp_path / "m.json", "--csv", tmp_path / "m.csv")
    assert p.returncode == 0, p.stderr
    assert "linearised: gap 'mesh' closed (default): closed: a spring of its contact stiffness k = 2e+08" in p.stdout
    d = json.loads((tmp_path / "m.json").read_text())
    assert d["linearisation"][0]["element"] == "mesh"
    assert set(d["named_outputs"]) >= {"mesh.force", "motor.reaction", "spring[1] motor-pinion.force"}
    assert len(d["named_outputs"]["mesh.force"]["modes"]) == d["n_modes"]
    assert (tmp_path / "m.csv").read_text().splitlines()[0].startswith("mode,f_hz,omega_rad_s,spring[1] motor-pinion")
    p = _cli("forced", EXAMPLES / "motor_drive_forced.toml", "--json", tmp_path / "f.json", "--csv", tmp_path / "f.csv")
    assert p.returncode == 0, p.stderr
    d = json.loads((tmp_path / "f.json").read_text())
    assert "spring[1] rotor-load.force" in d["named_outputs"] and "motor.force" in d["named_outputs"]
    assert len(d["named_outputs"]["motor.force"]["response"]) == len(d["omega_rad_s"])
    assert "spring[1] rotor-load.force amplitude" in (tmp_path / "f.csv").read_text().splitlines()[0]


# ------------------------------------------------------------------ rotor files
def test_rotor_bearing_reactions_balance_the_bearing_stiffness_and_damping():
    """examples/rotor_friswell_damped.toml's unbalance response: the bearing reactions sum, per direction, to
    -1^T (K(Omega) + i Omega C(Omega)) Q over the lateral DOFs (the shaft's own stiffness moves no rigid
    translation), at every speed; the outputs carry the file's names (disc 1, disc 2)."""
    st = Study.load(EXAMPLES / "rotor_friswell_damped.toml")
    res = st.forced()
    rs = st.rotor
    out = st.outputs(res)
    assert {p.name for p in res.probes} >= {"disc 1", "disc 2"}
    for field, comp in (("v", "y"), ("w", "z")):
        r = np.zeros(rs.n_dofs)
        r[rs.node_dofs[field]] = 1.0
        cols = [k for k, c in enumerate(out.channels) if c.source == "bearing" and c.name.endswith(f".force_{comp}")]
        assert len(cols) == len(rs.rotor.bearings)
        total = out.values[cols].sum(axis=0)
        for j, s in enumerate(res.speeds_rad_s[::7]):
            jj = 7 * j
            sys_ = rs.system_at(s)
            D = sys_.K + 1j * s * sys_.C
            want = -(r @ (D @ res.response[jj]))
            assert total[jj] == pytest.approx(want, rel=1e-9, abs=1e-12 * abs(want) + 1e-300)


def test_hybrid_output_tables_at_fe_nodes():
    """The drill string with [[output]] at FE nodes: the twist between x = 0 and x = 1 is the bit's angle
    minus the rotary table's, the reaction at x = 0 is the driver's default reaction output, units from
    the DOF (rad, rad/s, N m)."""
    doc = tomllib.loads((EXAMPLES / "hybrid_drill_string.toml").read_text())
    doc["simulation"]["t_end"] = 8.0
    doc["output"] = [{"name": "twist", "between": [{"x": 0.0}, {"x": 1.0}], "quantity": "twist"},
                     {"x": 0.5, "quantity": "velocity"},
                     {"name": "table torque", "x": 0.0, "quantity": "reaction"},
                     {"element": "bit", "quantity": "torque"}]
    st = Study.parse(doc)
    res = st.simulate()
    out = st.outputs(res)
    assert out.names == ["twist", "x=0.5.velocity", "table torque", "bit.torque"]
    assert [c.unit for c in out.channels] == ["rad", "rad/s", "N m", "N m"]
    s = res.solver
    fe = st.hybrid.fe
    j0, j1 = fe.system.dof_index(field="theta", x=0.0), fe.system.dof_index(field="theta", x=1.0)
    full = st.compiled.field(s.x)                                      # (n_t, n_fe) full FE angles
    assert np.allclose(out.column("twist"), full[:, j1] - full[:, j0], rtol=0, atol=1e-12 * np.max(np.abs(full)))
    default = time_outputs(st.time_loads.map, s.t, s.x, s.v, s.acceleration, s.element_forces, s.applied)
    assert np.array_equal(out.column("table torque"), default.column("driver[1] x=0 theta.reaction"))


def test_hybrid_section_outputs_are_the_section_loads_of_the_run():
    """[[output]] at x on the drill string's FE shaft (torque at mid-length): the column is
    fem.loads.section_loads of the run's state (the drive's accelerations, the FE part expanded) at that
    station, and it joins the element loads in one table."""
    from fem.loads import section_loads
    from fem.loads.drive import time_signals

    doc = tomllib.loads((EXAMPLES / "hybrid_drill_string.toml").read_text())
    doc["simulation"]["t_end"] = 4.0
    doc["output"] = [{"element": "bit", "quantity": "torque"}, {"name": "mid torque", "x": 0.5, "quantity": "torque"}]
    st = Study.parse(doc)
    res = st.simulate()
    out = st.outputs(res)
    assert out.names == ["bit.torque", "mid torque"] and out.channels[1].unit == "N m"
    sig = time_signals(st, res)
    T, n = st.compiled.T, st.compiled.n_fe
    assert st.hybrid.rayleigh == (0.0, 0.0)                   # undamped shaft: no damping term in the recovery
    ref = section_loads(st.fe_model, T @ sig["x"][:n], qd=T @ sig["v"][:n], qdd=T @ sig["a"][:n], x=[0.5])["torque"][0]
    assert np.allclose(out.column("mid torque"), ref, rtol=1e-12, atol=1e-12 * np.abs(ref).max())
    assert out.describe()["mid torque"]["dynamic_load_factor"] > 1


def test_steady_curve_outputs_of_a_model_without_elements():
    """A [steady] file whose nonsmooth elements were all removed (the fuzzer's case) still gets its outputs
    along the curve (no element forces to evaluate)."""
    doc = tomllib.loads((EXAMPLES / "hybrid_afc_friction_rod.toml").read_text())
    doc["friction"] = []
    st = Study.parse(doc)
    r = st.forced()
    loads = st.outputs(r)
    assert loads and all(len(o["amplitude"]) == r.omega.size for o in loads.values())


@pytest.mark.parametrize("name", ["cam_clearance.toml", "discrete_gap_backlash.toml", "parametric_drive.toml",
                                  "steady_duffing.toml", "hybrid_afc_vibro_impact.toml"])
def test_basis_many_is_the_scalar_basis_bit_for_bit(name):
    """Problem.basis_many (the named outputs' and recover's exogenous states over a whole record) gives
    exactly the values of Problem.basis instant by instant: harmonics and programme laws (cam, knots)."""
    st = Study.load(EXAMPLES / name)
    p = st.compiled.problem if st.kind == "hybrid" else st.problem_spec().problem()
    t = np.concatenate([np.linspace(0.0, 3.0, 997), [0.0, 1e-12, 2.5]])
    E = p.basis_many(t)
    assert E.shape == (p.ne, t.size)
    assert np.array_equal(E, np.array([p.basis(tk) for tk in t]).T)


def test_basis_many_of_no_instant_is_empty():
    """An empty record (no instant) gives an (ne, 0) array, programme laws or not."""
    for name in ("cam_clearance.toml", "steady_duffing.toml"):
        st = Study.load(EXAMPLES / name)
        p = st.problem_spec().problem()
        assert p.basis_many(np.zeros(0)).shape == (p.ne, 0)
