"""Time-domain tables of issue 14: a pulsating [[spring]] (modulation), a programme (cam) law of a
[[driver]] and the [[motor]] element -- model-file errors and short runs against their references
(the full comparisons are the validation cases timedomain_*)."""
import math

import numpy as np
import pytest

from discrete.errors import ModelError
from discrete.motion.follower import PiecewiseOscillator
from discrete.nonsmooth.elements import ModulatedSpring, Motor
from discrete.nonsmooth.problem import ProgrammeMotion
from fem.study import Study
from validation.cases.timedomain_cam import _follower_doc, _law
from validation.cases.timedomain_motor import runup_closed_form
from validation.cases.timedomain_parametric import floquet_monodromy, time_domain_monodromy
from validation.examples import example_doc


def _spring_doc(**modulation):
    return {"body": [{"name": "m", "inertia": 1.0, "x0": 0.1}],
            "spring": [{"between": ["ground", "m"], "k": 1.0, "modulation": modulation}],
            "simulation": {"t_end": 1.0}}


def _cam_doc(**programme):
    p = {"law": "cycloidal", "cam_speed": 20.0, "stroke": 0.02, "rise": 1.0, "return": 1.0}
    p.update(programme)
    return {"body": [{"name": "f", "inertia": 1.0}], "driver": [{"name": "cam", "programme": p}],
            "spring": [{"between": ["cam", "f"], "k": 1e4}], "simulation": {"t_end": 0.1}}


@pytest.mark.parametrize("doc,pattern", [
    (_spring_doc(depth=1.0, omega=2.0), r"depth = 1.0 .*"),
    (_spring_doc(depth=0.1, omega=0.0), r"omega = 0.0 .*> 0"),
    (_spring_doc(depth=0.1), r"omega"),
    ({"body": [{"name": "m", "inertia": 1.0}], "simulation": {"t_end": 1.0},
      "spring": [{"between": ["ground", "m"], "c": 1.0, "modulation": {"depth": 0.1, "omega": 2.0}}]},
     r"modulation = .*a stiffness k > 0"),
    (_cam_doc(law="cubic"), r"law = 'cubic'"),
    (_cam_doc(rise=None), r"rise = None .*cam angle of the rise"),
    (_cam_doc(stroke=0.0), r"stroke = 0.0 .*non-zero"),
    (_cam_doc(rise=4.0, **{"return": 3.0}), r"cycle = .*at least rise \+ top_dwell \+ return"),
    (_cam_doc(law="table", stroke=None, rise=None, **{"return": None}), r"phi = None .*table"),
    (_cam_doc(law="table", stroke=None, rise=None, phi=[0.0, 1.0, 2.0], x=[0.0, 1.0, 0.5], **{"return": None}),
     r"x = \[0.0, 0.5\] .*periodic"),
    (_cam_doc(phi=[0.0, 1.0, 2.0]), r"phi = .*only with law = \"table\""),
    (_cam_doc(law="table", stroke=None, rise=None, phi=[0.0, 1.0, 2.0], x=[0.0, 1.0, 0.5], periodic=False,
              start=0.5, **{"return": None}), r"start = 0.5 .*<= 0 for a non-periodic table"),
    (_cam_doc(law="table", stroke=None, rise=None, phi=[0.0, 1.0, 1.5], x=[0.0, 1.0, 0.5], periodic=False,
              **{"return": None}), r"phi = \[0.0, 1.5\] .*covering the run: its end t = 0.075 s"),
    ({"body": [{"name": "r", "inertia": 1.0}], "motor": [{"body": "r", "omega0": 100.0, "nu": -1.0}],
      "simulation": {"t_end": 1.0}}, r"nu = -1.0 .*> 0"),
    ({"body": [{"name": "r", "inertia": 1.0}], "motor": [{"body": "r", "omega0": 100.0, "nu": 1e-3, "torque0": 5.0}],
      "simulation": {"t_end": 1.0}}, r"torque0 = 5.0 .*T = 0"),
    ({"body": [{"name": "r", "inertia": 1.0}], "motor": [{"omega0": 100.0, "nu": 1e-3}],
      "simulation": {"t_end": 1.0}}, r"body = None"),
])
def test_bad_time_domain_tables_are_clear_errors(doc, pattern):
    doc = {k: v for k, v in doc.items()}
    for t in doc.get("driver", []):
        t["programme"] = {k: v for k, v in t["programme"].items() if v is not None}
    with pytest.raises(ModelError, match=pattern):
        Study.parse(doc).simulate()


def test_solvers_that_cannot_integrate_them_refuse():
    doc = _cam_doc()
    doc["simulation"].update(method="moreau", dt=1e-4)
    with pytest.raises(ModelError, match=r"programme = 'cycloidal' .*method = 'event'"):
        Study.parse(doc).simulate()
    doc = _spring_doc(depth=0.1, omega=2.0)
    doc["friction"] = [{"body": "m", "kinetic": 0.01}]
    doc["steady"] = {"omega": [1.5, 2.5]}
    with pytest.raises(ModelError, match=r"modulation = .*\[steady\]"):
        Study.parse(doc).steady_model()


def test_the_partial_solver_api_checks_its_input():
    with pytest.raises(ModelError, match=r"law = 'str'"):
        ProgrammeMotion(law="cycloidal")
    with pytest.raises(ModelError, match=r"depth = 1.5"):
        ModulatedSpring(name="s", g=np.ones(1), k=1.0, depth=1.5, omega=1.0)
    with pytest.raises(ModelError, match=r"T = -1.0"):
        Motor(name="m", g=np.ones(1), omega0=1.0, nu=1.0, T=-1.0)


def test_modulated_spring_monodromy_equals_floquet():
    """In the principal tongue (eps = 0.1, Omega = 2 k0): rho_max = 1.08168 in both methods."""
    Pt, Pf = time_domain_monodromy(0.1, 2.0), floquet_monodromy(0.1, 2.0)
    assert np.max(np.abs(Pt - Pf)) < 1e-9 * np.max(np.abs(Pf))
    assert np.max(np.abs(np.linalg.eigvals(Pt))) > 1.08


def test_motor_runup_is_the_closed_form():
    doc = example_doc("motor_runup.toml")
    doc["simulation"]["t_end"] = 0.05
    r = Study.parse(doc).simulate()
    phi, w = r.series("rotor")
    mot = doc["motor"][0]
    ref = runup_closed_form(r.t, J=0.05, omega0=mot["omega0"], nu=mot["nu"], T=mot["T"], load=50.0)
    assert np.max(np.abs(w - ref[1])) < 1e-10 * mot["omega0"]
    assert abs(r.energy_error) < 1e-10


def test_cam_follower_is_the_exact_programme_response():
    doc = example_doc("cam_clearance.toml")
    lt = _law(doc)
    r = Study.parse(_follower_doc(doc, lt.span)).simulate()
    q = r.series("follower")[0] - r.series("cam")[0]
    k, n = math.sqrt(doc["spring"][0]["k"]), doc["spring"][0]["c"] / 2
    exact = PiecewiseOscillator.follower(lt, k, n).response(r.t, z0=np.zeros(2))[:, 0]
    assert np.max(np.abs(q - exact)) < 1e-9 * np.max(np.abs(exact))
    assert r.event_times("knot").size == lt.n_pieces
