"""How a continuation ends (issue 12, item 4): exactly at the end of the range asked for, solved there
by a corrector at the fixed end frequency -- or a precise reason, ``completed = False`` and exit code 1.

Regression: ``examples/steady_coulomb.toml`` used to end at 0.798 of 0.8 and the Den Hartog oscillator
asked for [6.5, 9.0] at 8.775, both reporting "reached the end of the frequency range" (the step that
crossed the end was dropped by the range filter instead of being landed on the end)."""
import json
from pathlib import Path

import numpy as np
import pytest

from discrete.errors import SolverError
from discrete.steady import HBModel, ShootingModel
from discrete.steady.continuation import arclength
from fem.app.cli import main
from fem.study import Study, forced, steady_model
from validation.analytic.steady_refs import den_hartog_amplitude
from validation.cases.steady_coulomb import doc as den_hartog_doc

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "steady_coulomb.toml"


def _circle(x, w, need_w=True):
    """The unit circle x^2 + w^2 = 1 as a one-unknown 'steady state': a fold at w = 1."""
    return np.array([x[0] ** 2 + w * w - 1.0]), np.array([[2 * x[0]]]), (np.array([2 * w]) if need_w else None)


def test_arclength_lands_exactly_on_the_range_end():
    br = arclength(_circle, np.array([1.0]), 0.0, 0.9, xscale=np.ones(1), wscale=0.9, ds=0.1, start_converged=True)
    assert br.completed and br.stop == "end" and br.w[-1] == 0.9 and br.stopped_at == 0.9
    assert abs(br.x[-1][0] - np.sqrt(1 - 0.81)) < 1e-12          # solved at w = 0.9, not interpolated
    assert all(0.0 <= w <= 0.9 for w in br.w)
    assert br.reason == "reached the end of the frequency range: omega = 0.9 (solved there)"


def test_arclength_turning_back_through_the_start_is_not_completion():
    br = arclength(_circle, np.array([1.0]), 0.0, 2.0, xscale=np.ones(1), wscale=2.0, ds=0.05, start_converged=True)
    assert not br.completed and br.stop == "left_range"
    assert br.w[-1] == 0.0 and abs(br.x[-1][0] + 1.0) < 1e-12     # landed on the start, other half of the circle
    assert len(br.folds) == 1 and abs(br.folds[0][1] - 1.0) < 1e-2
    assert "turned back at the fold near omega = " in br.reason and "through its start omega = 0" in br.reason
    assert "range end 2 not reached" in br.reason


def test_arclength_residual_failure_is_named_in_the_reason():
    """A residual that cannot be evaluated beyond w = 0.5 (as a failing period map): the branch stalls
    below 0.5 and the reason carries the frequency reached and the solver's own message."""
    def fun(x, w, need_w=True):
        if w > 0.5:
            raise SolverError(f"period map at omega = {w!r}: integrator failed")
        return _circle(x, w, need_w)

    br = arclength(fun, np.array([1.0]), 0.0, 0.9, xscale=np.ones(1), wscale=0.9, ds=0.1, start_converged=True)
    assert not br.completed and br.stop == "ds_min" and 0.49 < br.stopped_at <= 0.5
    assert br.reason.startswith(f"stalled at omega = {br.stopped_at:.10g} (range end 0.9 not reached): the step "
                                "fell below ds_min = 1e-05; last failure: period map at omega = ")
    assert br.reason.endswith("integrator failed")


def _last_point_is_the_exact_den_hartog_orbit(r, sm, w_end):
    """Last point: solved at exactly w_end, a fixed point of the exact period map (continuation Newton
    tolerance 1e-8 on the scaled update, so the residual is far below it), amplitude = closed form
    (both exact: 1e-9 as in the validation case)."""
    assert r.completed and r.stop_cause == "end" and r.omega[-1] == w_end and r.stopped_at == w_end
    assert np.all(np.diff(r.omega) > 0) and r.omega[-2] < w_end
    sh = ShootingModel(sm.factory, nu=sm.cfg.subharmonic, steps_per_period=sm.cfg.steps_per_period)
    y = r.states[-1]
    assert np.max(np.abs(sh.map(y, w_end) - y)) <= 1e-9 * np.max(np.abs(y))
    ref = den_hartog_amplitude(1.0, 1.0, 0.3, 1.0, w_end)
    assert abs(r.response[-1] - ref) <= 1e-9 * ref
    d = r.to_dict()
    assert d["completed"] is True and d["stopped_at_rad_s"] == w_end and d["omega_rad_s"][-1] == w_end


def test_example_steady_coulomb_reaches_0_8():
    study = Study.load(EXAMPLE)
    r = study.forced()
    _last_point_is_the_exact_den_hartog_orbit(r, study.steady_model(), 0.8)
    assert r.reason.startswith("reached the end of the frequency range: omega = 0.8")


def test_den_hartog_shooting_reaches_9():
    d = den_hartog_doc("shooting", omega=[6.5, 9.0], stability=False)
    _last_point_is_the_exact_den_hartog_orbit(forced(d), steady_model(d), 9.0)


def test_den_hartog_hb_reaches_9():
    """HB-15 (friction tanh(v/1e-3)): last point at exactly 9.0 with the HB residual at the Newton
    tolerance (update <= 1e-9 relative, quadratic convergence: residual << 1e-9 of the unit force)."""
    d = den_hartog_doc("hb", omega=[6.5, 9.0], harmonics=15)
    r = forced(d)
    assert r.completed and r.omega[-1] == 9.0 and r.stopped_at == 9.0 and r.omega[-2] < 9.0
    sm = steady_model(d)
    hb = HBModel(sm.system, harmonics=sm.cfg.harmonics, nu=sm.cfg.subharmonic, samples=sm.cfg.samples)
    assert np.max(np.abs(hb.residual(r.states[-1], 9.0, jac=False))) < 1e-9
    # the last point is the solution at 9.0 (a fresh fixed-frequency solve from the linear guess agrees)
    X, _ = hb.solve(hb.linear_guess(9.0), 9.0)
    assert np.max(np.abs(X - r.states[-1])) <= 1e-9 * np.max(np.abs(X))


def test_early_stop_max_steps_reports_where_and_why():
    r = forced(den_hartog_doc("hb", omega=[6.5, 9.0], max_steps=3))
    assert not r.completed and r.stop_cause == "max_steps" and r.omega.size == 4
    assert r.stopped_at == r.omega[-1] < 9.0
    assert r.reason == (f"stopped at omega = {r.stopped_at:.10g} (range end 9 not reached): max_steps = 3 reached")
    d = r.to_dict()
    assert d["completed"] is False and d["stopped_at_rad_s"] == r.omega[-1] and d["stop_cause"] == "max_steps"


def test_early_stop_ds_min_reports_the_failure():
    """A step floor too high to follow the Duffing fold near 1.2324: the tangent turns too fast."""
    d = {"body": [{"name": "m", "inertia": 1.0}], "spring": [{"between": ["ground", "m"], "k": 1.0}],
         "damper": [{"between": ["ground", "m"], "c": 0.1}], "cubic_spring": [{"between": ["ground", "m"], "k3": 0.5}],
         "force": [{"body": "m", "amplitude": 0.25, "omega": 1.0}],
         "steady": {"omega": [1.3, 1.2], "harmonics": 1, "response": {"body": "m"}, "ds": 0.5, "ds_max": 0.5,
                    "ds_min": 0.3}}
    r = forced(d)
    assert not r.completed and r.stop_cause == "ds_min" and r.stopped_at == r.omega[-1] > 1.2
    assert r.reason.startswith(f"stalled at omega = {r.stopped_at:.10g} (range end 1.2 not reached): the step fell "
                               "below ds_min = 0.3; last failure: the tangent turned by ")
    # the same branch with the default step floor follows the fold, turns back and leaves through its start
    d["steady"].update(ds=0.02, ds_max=0.1, ds_min=1e-5)
    r = forced(d)
    assert not r.completed and r.stop_cause == "left_range" and r.omega[-1] == 1.3
    assert len(r.folds) == 1 and abs(r.folds[0]["omega"] - 1.232427) < 1e-5
    assert "left the range through its start omega = 1.3" in r.reason


def test_cli_exit_code_and_json_flag(tmp_path, capsys):
    model = tmp_path / "stop.toml"
    model.write_text(EXAMPLE.read_text().replace("ds = 0.1", "ds = 0.1\nmax_steps = 2\nstability = false"))
    out = tmp_path / "stop.json"
    assert main(["forced", str(model), "--json", str(out)]) == 1
    data = json.loads(out.read_text())
    assert data["completed"] is False and data["stop_cause"] == "max_steps"
    assert data["stopped_at_rad_s"] == data["omega_rad_s"][-1] < 0.8
    err = capsys.readouterr().err
    assert "max_steps = 2 reached" in err and f"omega = {data['stopped_at_rad_s']:.10g}" in err
