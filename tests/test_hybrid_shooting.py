"""Shooting continuation on the hybrid FE examples through the two places where it used to stall
(issue 12): a slip reversal crossing the shooting section (friction rod, z = 1.0015) and the grazing
onset of contact (cantilever with a stop, 313.67 rad/s)."""
import sys

import numpy as np
import pytest

from discrete.steady import ShootingModel, afc
from discrete.steady.continuation import arclength
from discrete.steady.shooting import section_phase
from fem.study import Study
from validation.examples import example_doc

AFC = sys.modules["discrete.steady.afc"]       # the module (the package exports the function afc)


def _steady(name, **steady):
    doc = example_doc(name)
    doc["steady"].update(method="shooting", stability=False, **steady)
    return Study.parse(doc).steady_model()


def test_rod_section_moves_off_a_slip_reversal_and_the_curve_goes_on():
    sm = _steady("hybrid_afc_friction_rod.toml", z=[0.995, 1.01])
    r = afc(sm)
    assert r.completed, r.reason
    assert r.extra["section_changes"] >= 1, r.reason
    phases = np.array(r.extra["section_phase_rad"])
    k = int(np.argmax(phases != 0.0))                # the first point on the moved section
    assert k > 0 and 1.001 < r.z[k] < 1.002          # the stall of the fixed section t = 0 was at z = 1.0015
    # the point on the new section is a periodic orbit: a fixed point of that section's map, and the same
    # orbit seen from t = 0 (transferred there) is a fixed point of the old map, with the same amplitude
    sh = ShootingModel(sm.factory)
    y, w, ph = r.states[k], float(r.omega[k]), float(phases[k])
    sc = np.maximum(np.abs(y), 1e-12)
    assert np.max(np.abs(sh.map(y, w, ph) - y) / np.max(sc)) < 1e-7
    y0 = sh.transfer(y, w, ph, 0.0)
    assert np.max(np.abs(sh.map(y0, w) - y0) / np.max(sc)) < 1e-7
    assert AFC._shoot_measure(sm, sh, y0, w) == pytest.approx(r.response[k], rel=1e-6)
    # the new section lies in the middle of the largest gap between the orbit's events
    _, res = sh.run(y, w, phase=ph)
    _, clear = section_phase(res, w)
    ev = np.mod(w * np.array([e.t for e in res.events]), 2 * np.pi)
    assert ev.size >= 2 and clear > 0.5
    # the curve is smooth through the move: amplitude differences change sign once (at the peak)
    assert np.count_nonzero(np.diff(np.sign(np.diff(r.response)))) <= 1


def test_cantilever_continuation_steps_over_the_grazing_onset_of_contact():
    sm = _steady("hybrid_afc_vibro_impact.toml")
    sh = ShootingModel(sm.factory)
    w0, w1 = 313.6, 313.75
    y, _, _ = sh.settle(np.zeros(sh.n), w0, periods=400, tol=1e-8, scale=np.ones(sh.n))
    _, res = sh.run(y, w0, dense=True)
    p = sh.problem(w0)
    sc = np.concatenate([np.max(np.abs(res.x[p.f]), axis=1), np.max(np.abs(res.v[p.f]), axis=1)])
    y, _ = sh.solve(y, w0, sc)
    kw = dict(xscale=sc, wscale=30.0, ds=0.02, ds_min=1e-5, start_converged=True, tol=1e-8)
    stalled = arclength(sh.fun(sc), y, w0, w1, **kw)
    assert stalled.stop == "ds_min" and 313.66 < stalled.stopped_at < 313.68, stalled.reason
    br = arclength(sh.fun(sc), y, w0, w1, transition=AFC._event_change(sh, 0.0), **kw)
    assert br.completed, br.reason
    assert len(br.transitions) >= 1 and "grazing" in br.transitions[0][2]
    assert 313.66 < br.transitions[0][0] < 313.68
    # no contact before the grazing, contact (stop force > 0) after it
    F = [AFC._shoot_measure(sm, sh, x, w) for x, w in zip(br.x, br.w)]
    assert F[0] == 0.0 and F[-1] > 0.1
