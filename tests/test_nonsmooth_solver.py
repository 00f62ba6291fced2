"""Event-driven nonsmooth solver: exactness, switching rules, breakaway guard, general LinearSystem input."""
import math

import numpy as np
import pytest

from discrete.linear_system import LinearSystem
from discrete.nonsmooth import Friction, Problem, simulate, simulate_regularised
from fem.study import Study
from fem.study import simulate as simulate_doc
from validation.analytic import seed000


def seed000_doc(eps, Om, restick="kinetic", periods=3.5, I=2.0, c=50.0, M0=3.0):
    d = seed000.dimensional(eps, Om, I, c, M0)
    return {"body": [{"name": "disk", "inertia": I}],
            "driver": [{"name": "top", "velocity": d["omega"]}],
            "spring": [{"between": ["top", "disk"], "k": c}],
            "friction": [{"name": "bit", "body": "disk", "kinetic": M0, "static": d["M1"], "restick": restick}],
            "simulation": {"t_end": d["M1"] / (c * d["omega"]) + periods * d["period"]}}, d


@pytest.mark.parametrize("eps,Om", [(2.5, 0.7), (5.5, 1.2), (9.5, 0.4)])
def test_seed000_period_and_reversals(eps, Om):
    doc, d = seed000_doc(eps, Om)
    res = simulate_doc(doc)
    slips = res.event_times("slip")
    assert slips.size >= 3
    assert abs((slips[-1] - slips[-2]) / d["period"] - 1) < 1e-10
    rev = res.event_times("reversal")
    assert np.sum((rev > slips[-2]) & (rev < slips[-1])) == d["k_star"]
    assert res.period == pytest.approx(d["period"], rel=1e-10)
    assert res.period_info["per_period"].get("reversal", 0) == d["k_star"]
    assert res.energy_error < 1e-10


def test_restick_rules_differ():
    """With eps = 6 the kinetic rule reverses twice per period; the static rule sticks at the first stop."""
    doc_k, d = seed000_doc(6.0, 1.0, "kinetic")
    doc_s, _ = seed000_doc(6.0, 1.0, "static")
    rk, rs = simulate_doc(doc_k), simulate_doc(doc_s)
    assert len(rk.events_of("reversal")) > 0
    assert len(rs.events_of("reversal")) == 0
    # static rule: one slip arc of the undamped oscillator, then stick (textbook (8.38) form)
    eps = 6.0
    T = (2 * math.pi - 2 * math.atan((eps - 1) / 1.0) + 2 * (eps - 1) / 1.0) * math.sqrt(2.0 / 50.0)
    assert rs.period == pytest.approx(T, rel=1e-10)


def test_breakaway_not_stepped_over():
    """Harmonic driver whose spring force exceeds the static limit only for ~1e-3 of a period around
    its peak: the breakaway must be found at the exact instant c a sin(w t) = F_s."""
    c, a, w = 10.0, 1.0, 2.0
    Fs = c * a * (1 - 1e-6)
    doc = {"body": [{"name": "b", "inertia": 1.0}],
           "driver": [{"name": "d", "amplitude": a, "omega": w}],
           "spring": [{"between": ["d", "b"], "k": c}],
           "friction": [{"name": "f", "body": "b", "kinetic": 0.5 * Fs, "static": Fs}],
           "simulation": {"t_end": 1.0}}
    res = simulate_doc(doc)
    slips = res.event_times("slip")
    assert slips.size >= 1
    assert slips[0] == pytest.approx(math.asin(Fs / (c * a)) / w, rel=1e-9)


def test_moving_belt_stick_slip_and_linear_system_input():
    """Mass on a belt (surface velocity V) tied to the wall by a spring: the classic stick-slip cycle;
    built directly from a LinearSystem + elements (the path FE models take)."""
    m, k, V, Fk, Fs = 1.0, 1.0, 0.5, 1.0, 2.0
    ls = LinearSystem(M=np.array([[m]]), K=np.array([[k]]), dof_field=np.array(["x"]), dof_name=np.array(["m"]))
    fr = Friction("belt", np.array([1.0]), kinetic=Fk, static=Fs, surface_velocity=V)
    prob = Problem(ls, [fr], x0=np.array([0.0]), v0=np.array([V]))
    res = simulate(prob, 60.0)
    # stick until k x = Fs, then a slip arc about x = Fk/k of radius sqrt((Fs-Fk)^2/k^2 + V^2 m/k)
    w = math.sqrt(k / m)
    dx = (Fs - Fk) / k
    phi = math.atan2(dx * w, V)
    slip = (2 * math.pi - 2 * phi) / w
    stick = 2 * dx / V
    assert res.period == pytest.approx(slip + stick, rel=1e-10)
    assert res.energy_error < 1e-10


def test_two_frictions_multi_dof():
    """Two bodies in a chain, both with friction: runs to t_end, energy balanced, events consistent."""
    doc = {"body": [{"name": "a", "inertia": 1.0}, {"name": "b", "inertia": 2.0}],
           "driver": [{"name": "d", "velocity": 0.3}],
           "spring": [{"between": ["d", "a"], "k": 4.0}, {"between": ["a", "b"], "k": 3.0}],
           "damper": [{"between": ["a", "b"], "c": 0.1}],
           "friction": [{"name": "fa", "body": "a", "kinetic": 1.0, "static": 1.5},
                        {"name": "fb", "body": "b", "kinetic": 2.0, "static": 3.0, "restick": "kinetic"}],
           "simulation": {"t_end": 40.0}}
    res = simulate_doc(doc)
    assert not res.stopped_early
    assert res.t[-1] == 40.0
    assert res.energy_error < 1e-9
    for e in res.events_of("stick"):
        assert abs(e.state[{"fa": "a", "fb": "b"}[e.element]]["v"]) < 1e-12


def test_regularised_alternative_close_to_exact():
    """The tanh + rest-memory regularisation reproduces the seed 000 cycle (2 reversals) to ~1 %
    at eps = 1e-3 omega (benchmarks/stick_slip.py tunes it to 1e-3)."""
    import sys, pathlib
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "benchmarks"))
    import stick_slip as bench

    doc, d = seed000_doc(6.0, 1.0, periods=5.0)
    study = Study.parse(doc)
    prob, st = study.problem_spec().problem(), study.simulation_settings()
    res = simulate_regularised(prob, st["t_end"], regularisation=1e-3 * d["omega"], memory_time=1e-2 * d["period"],
                               rtol=1e-8)
    T = bench.regularised_period(res, d)
    assert abs(T / d["period"] - 1) < 2e-2
    v = res.v[res.names.index("disk")]
    assert np.min(v) < -0.1 * d["omega"]          # velocity reversals happen
    assert "regularised" in res.method and np.isnan(res.energy_error)


def test_event_limit_stops_with_message():
    doc, d = seed000_doc(6.0, 1.0, periods=10)
    doc["simulation"]["max_events"] = 7
    res = simulate_doc(doc)
    assert res.stopped_early
    assert "max_events = 7" in res.reason and "t = " in res.reason
    assert len(res.events) == 7 and res.t.size > 2          # what was computed is kept
    assert res.to_dict()["stopped_early"] is True


def test_recorder_keeps_both_sides_of_every_event_and_reports_progress():
    """The kernel records the state reaching an event, the next piece's call the state leaving it (a
    pending sample, flushed on a stop): every event time appears twice, reaching and leaving states
    as the event's, and the progress callback (throttled) is told the final time."""
    doc, d = seed000_doc(6.0, 1.0, periods=5.0)
    seen = []
    res = Study.parse(doc).simulate(progress=seen.append)
    assert len(res.events) > 10 and not res.stopped_early
    k = res.names.index("disk")
    for ev in res.events:
        at = np.flatnonzero(res.t == ev.t)
        assert at.size >= 2, (ev.kind, ev.t, at)        # (3 where a zero-length piece follows)
        assert any(res.x[k, j] == ev.state["disk"]["x"] and res.v[k, j] == ev.state["disk"]["v"] for j in at)
    assert seen[-1] == res.t[-1] and seen == sorted(seen) and len(seen) < res.t.size / 50
    doc["simulation"]["max_events"] = 7                       # the stop: the last event's leaving state kept
    res = Study.parse(doc).simulate()
    assert res.stopped_early and res.t[-1] == res.events[-1].t and np.sum(res.t == res.events[-1].t) >= 2


def test_impact_between_bodies_momentum_and_restitution():
    """Two free bodies colliding: momentum conserved, relative velocity reversed times e."""
    doc = {"body": [{"name": "a", "inertia": 1.0, "v0": 1.0}, {"name": "b", "inertia": 3.0, "x0": 1.0}],
           "impact": [{"name": "contact", "between": ["a", "b"], "stop": 0.0, "restitution": 0.6}],
           "simulation": {"t_end": 2.0}}
    res = simulate_doc(doc)
    (e,) = res.events_of("impact")
    assert e.t == pytest.approx(1.0, rel=1e-12)
    va, vb = e.state["a"]["v"], e.state["b"]["v"]
    assert va * 1.0 + vb * 3.0 == pytest.approx(1.0, rel=1e-12)
    assert vb - va == pytest.approx(0.6, rel=1e-12)


def test_gear_reduced_friction_matches_equivalent_body():
    """Friction on a gear-driven body acts through the ratio: the same stick-slip cycle as the
    equivalent single body with inertia J1 + u^2 J2 and friction torque u * M on the driving shaft."""
    u = 2.5
    geared = {"body": [{"name": "pinion", "inertia": 0.5}, {"name": "wheel", "inertia": 0.24}],
              "gear": [{"between": ["pinion", "wheel"], "ratio": u}],
              "driver": [{"name": "motor", "velocity": 0.4}],
              "spring": [{"between": ["motor", "pinion"], "k": 30.0}],
              "friction": [{"name": "f", "body": "wheel", "kinetic": 1.0, "static": 1.6}],
              "simulation": {"t_end": 30.0}}
    equiv = {"body": [{"name": "pinion", "inertia": 0.5 + u * u * 0.24}],
             "driver": [{"name": "motor", "velocity": 0.4}],
             "spring": [{"between": ["motor", "pinion"], "k": 30.0}],
             "friction": [{"name": "f", "body": "pinion", "kinetic": u * 1.0, "static": u * 1.6}],
             "simulation": {"t_end": 30.0}}
    rg, re_ = simulate_doc(geared), simulate_doc(equiv)
    assert rg.period == pytest.approx(re_.period, rel=1e-12)
    np.testing.assert_allclose(rg.event_times(), re_.event_times(), rtol=1e-12)
    w = rg.names.index("wheel") if "wheel" in rg.names else None
    assert w is None          # the driven body is eliminated (gear constraint), as in discrete.lumped


def test_combined_power_law_deceleration():
    """Seed 002 combined law B1 sign v + B2 v + B3 sign(v) v^2 with B2 = 0 on a free body:
    m v' = -(B1 + B3 v^2) gives v = a tan(atan(v0/a) - a B3 t/m), a = sqrt(B1/B3); the body stops
    (and sticks) at t* = m atan(v0/a)/(a B3).  Numeric (DOP853) piece, event to ~1e-12."""
    m, B1, B3, v0 = 2.0, 0.5, 0.8, 3.0
    doc = {"body": [{"name": "b", "inertia": m, "v0": v0}],
           "friction": [{"name": "f", "body": "b", "kinetic": B1, "quadratic": B3}],
           "simulation": {"t_end": 5.0}}
    res = simulate_doc(doc)
    a = math.sqrt(B1 / B3)
    tstar = m * math.atan(v0 / a) / (a * B3)
    (st,) = res.events_of("stick")
    assert st.t == pytest.approx(tstar, rel=1e-10)
    k = np.searchsorted(res.t, 0.5 * tstar)
    assert res.v[0, k] == pytest.approx(a * math.tan(math.atan(v0 / a) - a * B3 * res.t[k] / m), rel=1e-9)
    assert res.energy_error < 1e-9
    assert res.v[0, -1] == 0.0 and res.t[-1] == 5.0


def test_penalty_impact_regularised_close_to_event_driven():
    doc = {"body": [{"name": "ball", "inertia": 0.2, "x0": 1.0}],
           "force": [{"body": "ball", "gravity": True}],
           "impact": [{"name": "floor", "body": "ball", "restitution": 0.7}],
           "simulation": {"t_end": 2.0}}
    ex = simulate_doc(doc)
    doc["simulation"].update({"method": "regularised", "penalty": 1e7, "rtol": 1e-9})
    rg = simulate_doc(doc)
    x = rg.x[0]
    # first and second contacts of the penalty model: x crosses 0 downwards
    down = rg.t[1:][(x[:-1] > 0) & (x[1:] <= 0)]
    ti = ex.event_times("impact")
    assert down[0] == pytest.approx(ti[0], rel=1e-3)
    assert down[1] == pytest.approx(ti[1], rel=5e-3)


def test_friction_clutch_between_bodies_breakaway():
    """Clutch between two disks (friction on s = x2 - x1): the pair starts from rest as one body
    J1 + J2 driven through a spring by a motor at V: x = V t - (V/w) sin(w t), w^2 = k/(J1 + J2);
    the clutch transmits J2 x'' and slips when that reaches F_s: sin(w t_b) = F_s/(J2 V w)."""
    J1, J2, k, V, Fs = 1.0, 0.5, 6.0, 1.0, 0.7
    doc = {"body": [{"name": "d1", "inertia": J1}, {"name": "d2", "inertia": J2}],
           "driver": [{"name": "motor", "velocity": V}],
           "spring": [{"between": ["motor", "d1"], "k": k}],
           "friction": [{"name": "clutch", "between": ["d1", "d2"], "kinetic": 0.5, "static": Fs}],
           "simulation": {"t_end": 2.0}}
    res = simulate_doc(doc)
    w = math.sqrt(k / (J1 + J2))
    tb = math.asin(Fs / (J2 * V * w)) / w
    first = res.events[0]
    assert first.kind == "slip" and first.element == "clutch"
    assert first.t == pytest.approx(tb, rel=1e-10)
    assert first.state["d1"]["x"] == pytest.approx(first.state["d2"]["x"], abs=1e-14)
    assert first.state["d1"]["v"] == pytest.approx(V - V * math.cos(w * tb), rel=1e-10)
    assert res.energy_error < 1e-10


def test_work_by_source():
    """Energy balance by source: Coulomb decay loses exactly its elastic energy to friction; a ball
    dropped from h receives m g h from gravity and loses it all in impacts."""
    doc = {"body": [{"name": "m", "inertia": 1.0, "x0": 1.005}],
           "spring": [{"between": ["ground", "m"], "k": 100.0}],
           "friction": [{"name": "dry", "body": "m", "kinetic": 1.0}],
           "simulation": {"t_end": 20.0}}
    res = simulate_doc(doc)
    assert res.work_parts["friction"] == pytest.approx(0.5 * 100 * (0.005 ** 2 - 1.005 ** 2), rel=1e-12)
    assert set(res.work_parts) == {"friction"}
    ball = {"body": [{"name": "b", "inertia": 0.2, "x0": 1.0}], "force": [{"body": "b", "gravity": True}],
            "impact": [{"name": "floor", "body": "b", "restitution": 0.5}], "constants": {"g": 9.81},
            "simulation": {"t_end": 2.0}}
    rb = simulate_doc(ball).to_dict()
    assert rb["work_parts"]["external"] == pytest.approx(0.2 * 9.81, rel=1e-12)
    assert rb["work_parts"]["impacts"] == pytest.approx(-0.2 * 9.81, rel=1e-8)
