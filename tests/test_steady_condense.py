"""Exact dynamic condensation of HB onto the nonlinear DOFs (discrete/steady/condense.py)."""
import numpy as np
import pytest

from discrete.errors import ModelError
from discrete.steady import HBModel
from discrete.steady.condense import CondensedHB, condensation_rule
from fem.study import Study
from validation.examples import example_doc


def _model(name, **steady):
    d = example_doc(name)
    d["steady"].update(steady)
    sm = Study.parse(d).steady_model()
    c = sm.cfg
    return sm, HBModel(sm.system, harmonics=c.harmonics, nu=c.subharmonic, samples=c.samples)


@pytest.mark.parametrize("name", ["hybrid_afc_vibro_impact.toml", "hybrid_afc_friction_rod.toml"])
def test_condensed_solution_is_the_full_one(name):
    sm, hb = _model(name)
    cond = CondensedHB(hb)
    lo, hi = sm.cfg.range
    for w in (lo, 0.5 * (lo + hi), hi):
        Xf, _ = hb.solve(hb.linear_guess(w), w, tol=1e-13)
        Xc, _ = cond.solve(cond.restrict(Xf), w, tol=1e-13)
        X = cond.expand(Xc, w)
        assert np.max(np.abs(X - Xf)) <= 1e-10 * np.max(np.abs(Xf))
        # the expanded state solves the full equations (residual at the level of round-off)
        R = hb.residual(X, w, jac=False)
        assert np.linalg.norm(R) <= 1e-9 * np.linalg.norm(hb.residual(np.zeros_like(X), w, jac=False))


def test_condensed_jacobians_match_finite_differences():
    sm, hb = _model("hybrid_afc_vibro_impact.toml")
    cond = CondensedHB(hb)
    w = 405.0
    Xf, _ = hb.solve(hb.linear_guess(w), w)
    X = cond.restrict(Xf) * 1.3           # in contact
    R, J, Rw = cond.evaluate_residual(X, w, dw=True)
    h = 1e-6 * w
    Rw_fd = (cond.residual(X, w + h, jac=False) - cond.residual(X, w - h, jac=False)) / (2 * h)
    assert np.max(np.abs(Rw_fd - Rw)) <= 1e-6 * np.max(np.abs(Rw))
    e = np.zeros_like(X)
    for j in (0, 1, 4, 17):
        e[:] = 0.0
        e[j] = 1e-7 * np.max(np.abs(X))
        col = (cond.residual(X + e, w, jac=False) - cond.residual(X - e, w, jac=False)) / (2 * e[j])
        assert np.max(np.abs(col - J[:, j])) <= 1e-6 * np.max(np.abs(J[:, j]))


def test_rule_auto_yes_no():
    sm, hb = _model("hybrid_afc_vibro_impact.toml")
    assert condensation_rule(sm.system, 25, "auto")[0]            # 204 HB unknowns, 1 of 4 DOFs nonlinear
    assert not condensation_rule(sm.system, 25, "no")[0]
    assert not condensation_rule(sm.system, 2, "auto")[0]         # 20 unknowns: the dense solve is cheaper
    one = Study.parse(example_doc("steady_duffing.toml")).steady_model()
    ok, why = condensation_rule(one.system, 7, "auto")
    assert not ok and "every one of the 1 DOFs" in why
    with pytest.raises(ModelError, match="condense"):
        condensation_rule(one.system, 7, "yes")


def test_condensed_curve_reports_and_equals_full_at_the_smooth_fold():
    sm, _ = _model("hybrid_afc_vibro_impact.toml", condense="yes", stability=False)
    from discrete.steady import afc
    r = afc(sm)
    assert r.completed and r.extra["condensation"].startswith("condense = \"yes\": 4 -> 1")
    d = example_doc("hybrid_afc_vibro_impact.toml")
    d["steady"].update(condense="no", stability=False)
    rf = afc(Study.parse(d).steady_model())
    assert rf.extra["condensation"] is None
    lo = min(f["omega"] for f in r.folds)
    lo_f = min(f["omega"] for f in rf.folds)
    assert abs(lo - lo_f) <= 1e-10 * lo_f


def test_compiled_operator_equals_the_numpy_one():
    sm, hb = _model("hybrid_afc_vibro_impact.toml")
    cond = CondensedHB(hb)
    for w in (250.0, 383.9, 450.0):
        a, b = cond.operator(w), cond.operator_numpy(w)
        for key in ("S", "dS", "f", "df", "X", "wf", "J"):
            assert np.max(np.abs(a[key] - b[key])) <= 1e-13 * np.max(np.abs(b[key])), key
