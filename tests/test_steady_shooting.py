"""Shooting on the exact event-driven integrator: FD monodromy against closed forms (incl. saltation)."""
import numpy as np
from scipy.linalg import expm

from discrete.steady import HBModel, ShootingModel, floquet_hb
from fem.study import steady_model
from validation.analytic.steady_refs import den_hartog_amplitude, den_hartog_bvp


def sdof(c=0.0, friction=0.0, F=1.0, gap=None):
    d = {"body": [{"name": "m", "inertia": 1.0}], "spring": [{"between": ["ground", "m"], "k": 1.0}],
         "force": [{"body": "m", "amplitude": F, "omega": 1.0}],
         "steady": {"method": "shooting", "omega": [0.5, 2.0], "response": {"body": "m"}}}
    if c:
        d["damper"] = [{"between": ["ground", "m"], "c": c}]
    if friction:
        d["friction"] = [{"name": "dry", "body": "m", "kinetic": friction}]
    if gap:
        d.pop("spring")
        d["gap"] = [{"name": "g", "body": "m", "k": 1.0, "delta": gap}]
    return d


def test_monodromy_linear_equals_expm():
    c, w = 0.2, 1.3
    sm = steady_model(sdof(c=c))
    sh = ShootingModel(sm.factory)
    y, _ = sh.solve(np.zeros(2), w, np.ones(2))
    mu = np.sort_complex(sh.floquet(y, w, np.ones(2)))
    A = np.array([[0, 1], [-1, -c]])
    ref = np.sort_complex(np.linalg.eigvals(expm(A * 2 * np.pi / w)))
    assert np.max(np.abs(mu - ref)) < 1e-7
    # the orbit is the closed-form linear steady state
    H = 1.0 / complex(1 - w * w, c * w)
    assert abs(np.hypot(*y * [1, 1 / w]) - abs(H)) < 1e-10


def test_monodromy_coulomb_includes_saltation():
    """Coulomb oscillator: Phi = e^{A(T-t2)} S2 e^{A(t2-t1)} S1 e^{A t1}, S = diag(1, a+/a-) at a reversal."""
    P, w = 0.3, 0.8
    sm = steady_model(sdof(friction=P))
    sh = ShootingModel(sm.factory)
    A0 = den_hartog_amplitude(1, 1, P, 1, w)
    sc = np.array([A0, A0 * w])
    y, _, _ = sh.settle(np.zeros(2), w, periods=100, tol=1e-6, scale=sc)
    y, _ = sh.solve(y, w, sc)
    J, _ = sh.jacobian(y, w, sc, central=True)
    _, res = sh.run(y, w)
    T = 2 * np.pi / w
    A = np.array([[0.0, 1.0], [-1.0, 0.0]])
    Phi = np.eye(2)
    t_prev = 0.0
    evs = [e for e in res.events if e.kind == "reversal"]
    assert len(evs) == 2
    for e in evs:
        x = e.state["m"]["x"]
        Phi = expm(A * (e.t - t_prev)) @ Phi
        f_ext = np.sin(w * e.t) - x
        # the velocity was positive before the event if x is at its maximum (x > 0)
        s_before = 1.0 if x > 0 else -1.0
        a_minus, a_plus = f_ext - P * s_before, f_ext + P * s_before
        Phi = np.array([[1.0, 0.0], [0.0, a_plus / a_minus]]) @ Phi
        t_prev = e.t
    Phi = expm(A * (T - t_prev)) @ Phi
    assert np.max(np.abs(J - Phi)) < 1e-6 * np.max(np.abs(Phi))
    assert np.max(np.abs(np.linalg.eigvals(Phi))) < 1


def test_den_hartog_formula_vs_bvp():
    for w in (0.6, 1.3, 1.6):
        a = den_hartog_amplitude(1, 1, 0.3, 1, w)
        assert abs(den_hartog_bvp(1, 1, 0.3, 1, w, a) - a) < 1e-10 * a


def test_hb_floquet_vs_shooting_gap():
    d = sdof(c=0.1, F=0.3, gap=0.1)
    d["steady"]["method"] = "hb"
    sm = steady_model(d)
    w = 0.8
    hb = HBModel(sm.system, harmonics=25)
    sh = ShootingModel(sm.factory)
    y, _, _ = sh.settle(np.zeros(2), w, periods=300, tol=1e-10, scale=np.ones(2))
    y, _ = sh.solve(y, w, np.ones(2))
    mus = np.sort(np.abs(sh.floquet(y, w, np.ones(2))))
    from discrete.steady.hb import time_guess
    X, _ = hb.solve(time_guess(hb, w), w)
    muh = np.sort(np.abs(floquet_hb(hb, X, w)))
    assert np.max(np.abs(mus - muh)) < 5e-3


def test_shooting_continuation_tracks_den_hartog():
    from fem.study import forced
    d = sdof(friction=0.3)
    d["steady"].update(omega=[1.3, 1.6], ds=0.1)
    r = forced(d)
    assert r.omega.size >= 3 and r.reason.startswith("reached")
    ref = np.array([den_hartog_amplitude(1, 1, 0.3, 1, w) for w in r.omega])
    assert np.max(np.abs(r.response - ref) / ref) < 1e-9
    assert np.all(r.stable)


def test_settle_from_rest_with_quadratic_friction():
    """Seed 002 combined losses started exactly at rest: the losses break away tangentially
    (static = kinetic, zero slip acceleration) in a numerically integrated piece.  This used to
    stall (stick/slip alternating at one instant, then a failed piece with atol ~ 1e-310); now
    the period map from rest equals the one from a 1e-6 velocity to the transient's accuracy,
    and the settled state is a fixed point of the exact period map."""
    from validation.analytic.steady_seed002 import K_NAT, seed002_doc

    sm = steady_model(seed002_doc(8.6e-4, "combined"))
    sh = ShootingModel(sm.factory)
    w = 0.69 * K_NAT
    rest, nudged = sh.map(np.zeros(2), w), sh.map(np.array([0.0, 1e-9]), w)
    assert np.max(np.abs(rest - nudged)) < 1e-6 * np.max(np.abs(rest))
    sc = np.array([0.01, 0.5])
    y, n, ok = sh.settle(np.zeros(2), w, periods=300, tol=1e-9, scale=sc)
    assert ok
    y2, _ = sh.solve(y, w, sc)
    assert np.max(np.abs(sh.map(y2, w) - y2) / sc) < 1e-9


def test_cubic_spring_by_shooting_agrees_with_harmonic_balance():
    """The smooth cubic spring is an element like any other: the exact event-driven integrator runs
    it in numerically integrated pieces, so shooting gives the same periodic orbit as HB (the cubic
    oscillator of textbook (8.20) at omega = 0.8 (below the folds), H = 9: HB's truncation error ~1e-8)."""
    from fem.study import Study

    doc = {"body": [{"name": "m", "inertia": 1.0}], "spring": [{"between": ["ground", "m"], "k": 1.0}],
           "damper": [{"between": ["ground", "m"], "c": 0.1}],
           "cubic_spring": [{"between": ["ground", "m"], "k3": 0.5}],
           "force": [{"body": "m", "amplitude": 0.25, "omega": 0.8}],
           "steady": {"omega": [0.8, 0.9], "harmonics": 9, "response": {"body": "m", "measure": "amplitude"}}}
    sm = Study.parse(doc).steady_model()
    hb = HBModel(sm.system, harmonics=9)
    X, _ = hb.solve(hb.linear_guess(0.8), 0.8)
    t, q, v = hb.evaluate(X, 0.8, points=1024)
    sh = ShootingModel(sm.factory, steps_per_period=200)
    y0 = np.array([q[0, 0], v[0, 0]])
    y, _ = sh.solve(y0, 0.8, np.ones(2))
    assert np.allclose(y, y0, rtol=0, atol=1e-6)
