"""Harmonic balance, continuation, folds and the textbook estimates."""
import numpy as np
import pytest

from discrete.steady import HBModel, estimates
from fem.output import columns
from fem.output.figures import plot_afc
from fem.study import forced
from fem.study import steady_model
from discrete.steady.continuation import newton_fixed
from discrete.errors import SolverError


def duffing(H=1, omega=(0.5, 2.2), **kw):
    return {"body": [{"name": "m", "inertia": 1.0}], "spring": [{"between": ["ground", "m"], "k": 1.0}],
            "damper": [{"between": ["ground", "m"], "c": 0.1}],
            "cubic_spring": [{"between": ["ground", "m"], "k3": 0.5}],
            "force": [{"body": "m", "amplitude": 0.25, "omega": 1.0}],
            "steady": {"omega": list(omega), "harmonics": H, "response": {"body": "m", "measure": "h1"}, **kw}}


def test_hb_linear_equals_frf():
    d = duffing(H=3)
    d["cubic_spring"][0]["k3"] = 0.0
    sm = steady_model(d)
    hb = HBModel(sm.system, harmonics=3)
    for w in (0.5, 1.0, 1.7):
        X, _ = hb.solve(np.zeros(hb.nq) + 1e-3, w)
        H = 0.25 / complex(1 - w * w, 0.1 * w)
        assert abs(np.hypot(X[1], X[2]) - abs(H)) < 1e-12
        assert np.max(np.abs(X[3:])) < 1e-14


def _folds_817():
    """Folds of (8.17) for the test Duffing: extrema of the upper root omega(A) (dense scan + polish)."""
    from scipy.optimize import minimize_scalar

    def wplus(A, sign):
        k2 = 1 + 0.375 * A * A
        b = -(2 * k2 - 0.01)
        c = k2 * k2 - 0.0625 / A ** 2
        with np.errstate(invalid="ignore"):      # no real root outside the response band: nan
            return np.sqrt((-b + sign * np.sqrt(b * b - 4 * c)) / 2)

    wr = -minimize_scalar(lambda A: -wplus(A, 1), bounds=(1.5, 1.9), method="bounded", options={"xatol": 1e-12}).fun
    wl = minimize_scalar(lambda A: wplus(A, 1), bounds=(0.55, 1.0), method="bounded", options={"xatol": 1e-12}).fun
    return wl, wr


def test_continuation_folds_match_817_and_stability():
    r = forced(duffing(H=1))
    wl, wr = _folds_817()
    f = sorted(x["omega"] for x in r.folds)
    assert len(f) == 2
    assert abs(f[0] - wl) < 1e-6 and abs(f[1] - wr) < 1e-6
    # points strictly between the folds on the middle branch are unstable, the end points stable
    assert r.stable[0] and r.stable[-1] and np.any(~r.stable)
    assert r.jump_intervals() == [(f[0], f[1])]


def test_stall_keeps_partial_result():
    r = forced(duffing(H=1, ds=1e-3, ds_min=0.5))
    assert "stalled" in r.reason and r.omega.size == 1


def test_max_steps_reported():
    r = forced(duffing(H=1, max_steps=5))
    assert "max_steps" in r.reason and r.omega.size == 6


def test_newton_cannot_start():
    def fun(x, w, need_w=True):
        return np.array([x[0] ** 2 + 1.0]), np.array([[2 * x[0] + 1e-3]]), np.zeros(1)
    with pytest.raises(SolverError, match="no start"):
        newton_fixed(fun, np.array([0.3]), 1.0, maxit=10)


def test_outputs(tmp_path):
    r = forced(duffing(H=1, omega=(0.8, 1.0)))
    d = r.to_dict()
    assert d["omega_rad_s"][0] == pytest.approx(0.8) and len(d["response"]) == r.omega.size
    columns.write(tmp_path / "a.csv", columns.afc(r))
    rows = (tmp_path / "a.csv").read_text().splitlines()
    assert len(rows) == r.omega.size + 1
    plot_afc(r, tmp_path / "a.png")
    assert (tmp_path / "a.png").stat().st_size > 1000
    assert "omega" in r.table()


def test_estimates():
    assert estimates.hl_backlash(1.0, 0.5, 1.0) == pytest.approx(0.39100, abs=5e-6)
    assert estimates.hl_backlash(1.0, 0.1, 1.0) == pytest.approx(0.87289, abs=5e-6)
    assert estimates.hl_backlash(1.0, 2.0, 1.0) == 0.0
    # the coefficients are the first-harmonic Fourier coefficients of the force (independent quadrature)
    th = np.linspace(0, 2 * np.pi, 200001)[:-1]
    A = 1.3
    q = A * np.sin(th)
    for c1, c2 in ((4.0, 1.0), (9.0, 0.0)):
        U = np.where(q > 0, c1 * q, c2 * q)
        k2, U0 = estimates.hl_bilinear(c1, c2, A)
        assert np.mean(U * np.sin(th)) * 2 / A == pytest.approx(k2, rel=1e-9)
        assert np.mean(U) == pytest.approx(U0, rel=1e-9)
    U = 2.0 * q * (1 + 0.4 * q * q)
    assert np.mean(U * np.sin(th)) * 2 / A == pytest.approx(estimates.hl_cubic(2.0, 0.4, A), rel=1e-9)
    dead = np.where(q > 0.5, q - 0.5, np.where(q < -0.5, q + 0.5, 0.0))
    assert np.mean(dead * np.sin(th)) * 2 / A == pytest.approx(estimates.hl_backlash(1.0, 0.5, A), rel=1e-7)
    assert estimates.energy_balance_resonance(1.0, 0.05, 1.0, 0.3) == pytest.approx((np.pi - 1.2) / (np.pi * 0.05))
    roots = estimates.hl_forced_amplitudes(1.0, 0.1, lambda A: 1 + 0.375 * A * A, 0.25, 1.3, A_max=5)
    assert len(roots) == 3 and roots[0] == pytest.approx(0.3863, abs=5e-5)
