"""The compiled harmonic-balance evaluation (discrete/steady/hb_kernel.py) against the numpy path it
replaces: residual, Jacobian and dR/domega on every kind of law (cubic, tanh friction on the HB and the
dense grid, exactly integrated gap, one-sided spring and Kelvin-Voigt stop with its moving-boundary term),
several DOFs, a subharmonic; the batch helpers (crossings, projections on 0..2H, constant coefficients,
Floquet intervals, series extremes); and which models use it."""
import numpy as np
import pytest

from discrete.steady import HBModel, hb as hbmod
from discrete.steady.hb import floquet_hb_batch
from discrete.steady.truncation import estimates, response_direction
from fem.study import Study, steady_model

hb_kernel = pytest.importorskip("discrete.steady.hb_kernel")
if not hb_kernel.JIT:
    pytest.skip("numba not available (or DRIVEFEM_JIT=0)", allow_module_level=True)


def stop_doc(element, **steady):
    d = {"title": "stop", "body": [{"name": "mass", "inertia": 2.0}],
         "spring": [{"between": ["ground", "mass"], "k": 8e4}], "damper": [{"between": ["ground", "mass"], "c": 20.0}],
         "force": [{"body": "mass", "amplitude": 60.0, "omega": 200.0}],
         "steady": {"method": "hb", "omega": [300.0, 700.0], "harmonics": 11}}
    d.update(element)
    d["steady"].update(steady)
    return d


def two_dof_doc():
    """Two bodies, a cubic spring between them and a friction on the second (pairs off the diagonal)."""
    return {"title": "two DOFs", "body": [{"name": "a", "inertia": 1.0}, {"name": "b", "inertia": 0.5}],
            "spring": [{"between": ["ground", "a"], "k": 1.0}, {"between": ["a", "b"], "k": 2.0}],
            "damper": [{"between": ["ground", "a"], "c": 0.05}],
            "cubic_spring": [{"between": ["a", "b"], "k3": 0.7}],
            "friction": [{"name": "f", "body": "b", "kinetic": 0.02, "viscous": 0.01}],
            "force": [{"body": "a", "amplitude": 0.2, "omega": 1.0}],
            "steady": {"method": "hb", "omega": [0.5, 2.0], "harmonics": 7}}


MODELS = {
    "duffing": lambda: Study.load("examples/steady_duffing.toml").steady_model(),
    "subharmonic": lambda: Study.load("examples/steady_subharmonic.toml").steady_model(),
    "seed002": lambda: Study.load("examples/steady_seed002.toml").steady_model(),
    "gap": lambda: steady_model(stop_doc({"gap": [{"name": "s", "body": "mass", "k": 8e5, "delta": 1e-3}]})),
    "kelvin_voigt": lambda: steady_model(stop_doc({"contact": [{"name": "s", "body": "mass", "k": 8e5, "c": 300.0,
                                                                "upper": 1e-3}]})),
    "two_dof_friction": lambda: steady_model(two_dof_doc()),
    "vibro_impact": lambda: Study.load("examples/hybrid_afc_vibro_impact.toml").steady_model(),
}


def _pair(sm):
    c = sm.cfg
    kw = dict(harmonics=c.harmonics, nu=c.subharmonic, samples=c.samples, kinks=c.kinks)
    return HBModel(sm.system, compiled=False, **kw), HBModel(sm.system, compiled=True, **kw)


def _states(hb, w0, rng, k=5):
    """States around the linear guess: large enough to cross the kinks, with higher harmonics."""
    X = hb.linear_guess(w0)
    sc = max(np.max(np.abs(X)), 1e-6)
    harm = 1.0 + np.arange(X.size) % hb.m
    return [X * (1 + 3 * rng.random()) + 0.4 * sc * rng.standard_normal(X.size) / harm for _ in range(k)]


@pytest.mark.parametrize("name", sorted(MODELS))
def test_compiled_evaluation_equals_numpy(name):
    sm = MODELS[name]()
    hn, hc = _pair(sm)
    assert hc._kernel(), "the kernel evaluates every law of these models"
    rng = np.random.default_rng(7)
    w0, w1 = sm.cfg.range
    for X in _states(hn, w0, rng):
        w = w0 + (w1 - w0) * rng.random()
        for jac, dw in ((True, True), (False, False), (True, False)):
            a = hn.evaluate_residual(X, w, jac=jac, dw=dw)
            b = hc.evaluate_residual(X, w, jac=jac, dw=dw)
            for p, q in zip(a, b):
                assert (p is None) == (q is None)
                if p is not None:
                    assert np.max(np.abs(p - q)) <= 1e-12 * max(np.max(np.abs(p)), 1e-300)
    assert hn.fine_evaluations == hc.fine_evaluations         # the dense grid taken at the same evaluations


def test_friction_switches_to_the_dense_grid_like_numpy():
    """A friction law not saturated on the HB grid goes to the dense grid, and back once saturated."""
    sm = steady_model(two_dof_doc())
    hn, hc = _pair(sm)
    X = hn.linear_guess(1.0)
    slow, fast = 0.01 * X, 30.0 * X                    # sticking / slipping one way all the period? (mixed)
    seq = [slow, slow, fast, slow, fast, fast]
    for X_ in seq:
        a = hn.evaluate_residual(X_, 1.1, jac=True, dw=True)
        b = hc.evaluate_residual(X_, 1.1, jac=True, dw=True)
        assert all(np.max(np.abs(p - q)) <= 1e-12 * max(np.max(np.abs(p)), 1e-300) for p, q in zip(a, b))
        assert np.array_equal(hn._go_fine, hc._go_fine)
    assert hn.fine_evaluations == hc.fine_evaluations > 0


@pytest.mark.parametrize("name", ["seed002", "gap", "kelvin_voigt", "vibro_impact"])
def test_batch_helpers_equal_numpy(name):
    """Crossing phases, projections on 0..2H (truncation estimates), constant coefficients and the Floquet
    intervals cut at the crossings, compiled and by numpy, along orbits of the curve."""
    sm = MODELS[name]()
    hn, hc = _pair(sm)
    w0, w1 = sm.cfg.range
    rng = np.random.default_rng(3)
    Xs = []
    for X in _states(hn, w0, rng, k=4):
        try:
            Xs.append(hn.solve(X, w0)[0])
        except Exception:
            Xs.append(X)
    ws = np.full(len(Xs), w0)
    Q = np.asarray(Xs).reshape(len(Xs), sm.system.n, hn.m)
    for a, b in zip(hn.crossing_phases(Q), hc.crossing_phases(Q)):
        assert a.shape == b.shape and np.allclose(a, b, rtol=0, atol=1e-13)
    g = response_direction(sm)
    ea, eb = estimates(hn, Xs, ws, g), estimates(hc, Xs, ws, g)
    assert np.allclose(ea, eb, rtol=1e-10, atol=1e-300)
    ca = np.array([hn.constant_coefficients(X, w) for X, w in zip(Xs, ws)])
    assert np.array_equal(ca, hc._kernel().constant_coefficients(Q, ws))
    fa, fb = floquet_hb_batch(hn, Xs, ws), floquet_hb_batch(hc, Xs, ws)
    assert np.allclose(np.sort_complex(fa), np.sort_complex(fb), rtol=0, atol=1e-10)


def test_series_extremes_compiled_equals_numpy():
    from discrete.steady import measures

    rng = np.random.default_rng(0)
    C = rng.standard_normal((40, 21)) / (1 + np.arange(21)) ** 2
    a, b = measures.series_extremes(C), measures.series_extremes(C, compiled=True)
    assert np.allclose(a[0], b[0], rtol=0, atol=1e-14) and np.allclose(a[1], b[1], rtol=0, atol=1e-14)


def test_which_models_use_the_kernel(monkeypatch):
    """In a Python session every model whose laws the kernel evaluates, a small smooth one included (numba's
    load is paid once per session); a law it does not evaluate (a sampled kink) by numpy; DRIVEFEM_JIT=0
    (COMPILED) switches it off."""
    duffing = MODELS["duffing"]()
    assert HBModel(duffing.system, harmonics=7)._kernel()
    assert not HBModel(duffing.system, harmonics=7, compiled=False)._kernel()
    assert HBModel(duffing.system, harmonics=60)._kernel()                    # 121 unknowns
    gap = MODELS["gap"]()
    assert HBModel(gap.system, harmonics=11)._kernel()
    assert not HBModel(gap.system, harmonics=11, kinks="sampled")._kernel()   # a sampled kink: numpy
    monkeypatch.setattr(hbmod, "COMPILED", False)
    assert not HBModel(gap.system, harmonics=11)._kernel()


def test_the_command_keeps_the_kernel_to_large_models(monkeypatch):
    """DRIVEFEM_JIT=large (what the drivefem program sets for its one-shot process): an exact-kink model of
    one DOF by numpy (numba's ~0.5 s load would not pay back in one curve), a large one compiled."""
    monkeypatch.setenv("DRIVEFEM_JIT", "large")
    assert not HBModel(MODELS["duffing"]().system, harmonics=7)._kernel()
    gap = MODELS["gap"]()
    assert not HBModel(gap.system, harmonics=11)._kernel()
    assert HBModel(gap.system, harmonics=11, compiled=True)._kernel()
    assert HBModel(MODELS["duffing"]().system, harmonics=60)._kernel()       # 121 unknowns


def test_the_program_sets_the_one_shot_policy_only_as_a_program(monkeypatch, tmp_path):
    """fem.app.cli.main() as the console script sets DRIVEFEM_JIT=large unless the user set it; main(argv)
    (tests, Python sessions) leaves the process environment alone."""
    import os
    import subprocess
    import sys

    from fem.app import cli

    monkeypatch.delenv("DRIVEFEM_JIT", raising=False)
    assert cli.main(["schema"]) == 0
    assert "DRIVEFEM_JIT" not in os.environ
    # a one-shot command ends its process inside main() (cli._end_process runs the exit handlers first)
    code = ("import atexit, os, sys; from fem.app import cli; sys.argv = ['drivefem', 'schema']; "
            "atexit.register(lambda: print('JIT', os.environ.get('DRIVEFEM_JIT'), 0)); cli.main()")
    env = {k: v for k, v in os.environ.items() if k != "DRIVEFEM_JIT"}
    for given, expected in ((None, "large"), ("always", "always"), ("0", "0")):
        if given is not None:
            env["DRIVEFEM_JIT"] = given
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=tmp_path)
        assert out.stdout.strip().splitlines()[-1] == f"JIT {expected} 0" and out.returncode == 0, out.stderr[-2000:]
    # a long-lived command (drivefem validate: ~170 cases in one process) keeps the session's rule
    env.pop("DRIVEFEM_JIT")
    code = code.replace("['drivefem', 'schema']", "['drivefem', 'validate', '--case', 'no-such-case']")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert out.stdout.strip().splitlines()[-1].startswith("JIT None "), out.stdout[-2000:] + out.stderr[-2000:]
    assert "validate" in cli.LONG_LIVED and "forced" not in cli.LONG_LIVED


@pytest.mark.parametrize("name", ["hybrid_afc_vibro_impact.toml", "hybrid_afc_friction_rod.toml"])
def test_condensation_compiled_equals_numpy(name):
    """The condensed HB model (condense_kernel: the operator, the real Jacobian, the condensed linear residual,
    the expansion; the inner element model as the full one decides) against the same model all by numpy."""
    from discrete.steady.condense import CondensedHB
    from fem.study import Study
    from validation.examples import example_doc

    d = example_doc(name)
    sm = Study.parse(d).steady_model()
    c = sm.cfg
    hb = HBModel(sm.system, harmonics=c.harmonics, nu=c.subharmonic, samples=c.samples)
    a, b = CondensedHB(hb), CondensedHB(hb, compiled=False)
    assert a.compiled and a.inner._kernel() and not b.compiled and not b.inner._kernel()
    lo, hi = c.range
    for w in (lo, 0.5 * (lo + hi), hi):
        Xf, _ = hb.solve(hb.linear_guess(w), w)
        X = a.restrict(Xf) * 1.3                       # beyond the linear orbit: the nonlinear element acts
        for p, q in zip(a.evaluate_residual(X, w, dw=True), b.evaluate_residual(X, w, dw=True)):
            assert np.max(np.abs(p - q)) <= 1e-12 * np.max(np.abs(q))
        ea, eb = a.expand(X, w), b.expand(X, w)
        assert np.max(np.abs(ea - eb)) <= 1e-12 * np.max(np.abs(eb))


def test_large_policy_decides_the_condensed_model_as_the_full_one(monkeypatch):
    """DRIVEFEM_JIT=large: the vibro-impact cantilever (4 DOFs, H = 25: 204 unknowns) is large, so its
    condensed model (51 unknowns on the stop's DOF) is compiled too -- not numba loaded for a numpy inner
    model; an unknown DRIVEFEM_JIT value is refused with the variable's name."""
    from discrete.errors import ModelError
    from discrete.steady.condense import CondensedHB
    from fem.study import Study
    from validation.examples import example_doc

    monkeypatch.setenv("DRIVEFEM_JIT", "large")
    sm = Study.parse(example_doc("hybrid_afc_vibro_impact.toml")).steady_model()
    c = sm.cfg
    hb = HBModel(sm.system, harmonics=c.harmonics, nu=c.subharmonic, samples=c.samples)
    cond = CondensedHB(hb)
    assert cond.compiled and cond.inner._kernel() and cond.inner.nq < hbmod.COMPILED_MIN_UNKNOWNS
    monkeypatch.setenv("DRIVEFEM_JIT", "off")
    with pytest.raises(ModelError, match="DRIVEFEM_JIT"):
        HBModel(MODELS["gap"]().system, harmonics=11)._kernel()


def test_the_program_refuses_an_unknown_jit_setting(tmp_path):
    """DRIVEFEM_JIT=off (not one of 0, 1, large, always): exit 2 before any work, the message naming the
    variable, its value and the allowed values -- not a silent 'on'."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    model = Path(__file__).resolve().parent.parent / "examples" / "steady_duffing.toml"
    env = dict(os.environ, DRIVEFEM_JIT="off")
    code = "import sys; from fem.app import cli; sys.argv = ['drivefem'] + sys.argv[1:]; sys.exit(cli.main())"
    out = subprocess.run([sys.executable, "-c", code, "forced", str(model), "--json", str(tmp_path / "r.json")],
                         capture_output=True, text=True, env=env, cwd=tmp_path)
    assert out.returncode == 2, out.stderr[-2000:]
    assert "DRIVEFEM_JIT = 'off' is not valid" in out.stderr and "large" in out.stderr and "always" in out.stderr
    assert not (tmp_path / "r.json").exists()
