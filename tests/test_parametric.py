"""Parametric vibrations (discrete.linear.parametric): Floquet monodromy, Mathieu points, bad input,
and the Python-API example examples/parametric_chart.py."""
from __future__ import annotations

import importlib.util
import json
import math
from pathlib import Path

import numpy as np

from discrete.linalg import expm_batch
import pytest
import scipy.linalg as sla
import scipy.sparse as sp
from scipy.special import mathieu_a, mathieu_b

from discrete.errors import ModelError
from discrete.linear import parametric as par
from discrete.linear.harmonic import Damping
from discrete.linear_system import LinearSystem
from discrete.lumped import Body, Driver, Link, LumpedModel

ROOT = Path(__file__).resolve().parent.parent


def sdof(m=1.0, c0=1.0):
    return LinearSystem(M=sp.csr_matrix([[m]]), K=sp.csr_matrix([[c0]]), dof_field=["x"])


def three_mass(dampers=True):
    """ground -- 2.0 -- a (1 kg) -- 1.5 -- b (2 kg) -- 1.0 -- c (0.5 kg), with dampers."""
    damp = [Link(("ground", "a"), 0.05), Link(("b", "c"), 0.02)] if dampers else []
    lm = LumpedModel(bodies=[Body("a", 1.0), Body("b", 2.0), Body("c", 0.5)],
                     springs=[Link(("ground", "a"), 2.0), Link(("a", "b"), 1.5), Link(("b", "c"), 1.0)],
                     dampers=damp)
    return lm.linear_system()


def test_constant_system_monodromy_is_expm():
    """eps = 0: the monodromy equals expm(A T) of the constant first-order system (Magnus is exact
    for constant A; only the modal similarity and products add round-off)."""
    S = three_mass()
    prob = par.ParametricProblem.build(S, [par.Modulation()], damping=Damping("viscous"))
    Om = 0.7
    f = prob.floquet(Om, 0.0)
    M, K, C = S.M.toarray(), S.K.toarray(), S.C.toarray()
    n = M.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    ref = sla.expm(A * 2 * math.pi / Om)
    assert np.abs(prob.physical_monodromy(f.monodromy) - ref).max() < 1e-12 * np.abs(ref).max()
    assert f.error_estimate < 1e-14 and f.liouville_residual < 1e-12
    assert f.liouville_reference == pytest.approx(-2 * math.pi / Om * np.trace(np.linalg.solve(M, C)), rel=1e-13)


@pytest.mark.parametrize("func, s, crossing", [(mathieu_a, 1, -1.0), (mathieu_b, 1, -1.0), (mathieu_a, 2, 1.0),
                                               (mathieu_b, 2, 1.0)])
def test_mathieu_point(func, s, crossing):
    """On a Mathieu characteristic curve a = a_s(q) (or b_s) the equation has a periodic (s even)
    or antiperiodic (s odd) solution: with a = 4 k0^2/Omega^2, q = eps a / 2 the monodromy has a
    double multiplier +-1, i.e. tr Phi = +-2 (error ~ the 1e-10 monodromy tolerance)."""
    q = 0.3
    a = float(func(s, q))
    omega, eps = 2.0 / math.sqrt(a), 2 * q / a
    f = par.floquet(sdof(), par.Modulation(), omega=omega, depth=eps, damping=Damping("none"))
    assert np.trace(f.monodromy) == pytest.approx(2 * crossing, abs=1e-8)


def test_magnus_is_sixth_order_and_symplectic():
    prob = par.ParametricProblem.build(sdof(), [par.Modulation()], damping=Damping("none"))
    e, w = np.array([0.3]), np.array([1.3])
    ref = prob._magnus(e, w, 512)[0]
    errs = [np.abs(prob._magnus(e, w, N)[0] - ref).max() for N in (16, 32)]
    assert 40 < errs[0] / errs[1] < 90                         # 2^6 = 64
    f = prob.floquet(1.3, 0.3)                                 # stable, undamped: |rho| = 1
    assert f.stable and np.abs(np.abs(f.multipliers) - 1).max() < 1e-12


def test_projection_on_all_modes_equals_dense():
    S = three_mass()
    mods = [par.Modulation(), par.Modulation(target="inertia", depth=0.5, harmonic=2, phase=0.3)]
    dense = par.floquet(S, mods, omega=1.1, depth=0.2, damping=Damping("viscous"))
    proj = par.floquet(S, mods, omega=1.1, depth=0.2, damping=Damping("viscous"), modes=3)
    assert np.sort(np.abs(proj.multipliers)) == pytest.approx(np.sort(np.abs(dense.multipliers)), rel=1e-9)


def test_expm_closed_form_2x2():
    """Closed-form 2 x 2 and batched Pade exponentials against scipy.linalg.expm, per matrix:
    1e-14 for step-sized exponents (norm < 2, as in the integrator), 1e-12 for large ones (several
    squarings)."""
    rng = np.random.default_rng(3)
    small = np.concatenate([0.4 * rng.standard_normal((200, 2, 2)), np.zeros((1, 2, 2)),
                            np.array([[[1e-9, 1.0], [-1e-9, 0.0]], [[0.0, 1.0], [-1.0, 0.0]]])])
    large = 3.0 * rng.standard_normal((20, 2, 2))
    for X, tol in ((small, 1e-14), (large, 1e-12)):
        ref = np.array([sla.expm(x) for x in X])
        for f in (par._expm_batch, expm_batch):
            rel = np.abs(f(X) - ref).max(axis=(1, 2)) / np.abs(ref).max(axis=(1, 2))
            assert rel.max() <= tol
    X4 = 0.5 * rng.standard_normal((50, 4, 4))
    ref = np.array([sla.expm(x) for x in X4])
    assert np.abs(par._expm_batch(X4) - ref).max() <= 1e-14 * np.abs(ref).max()


def test_results_serialise():
    ch = par.stability_chart(sdof(), par.Modulation(), omega_min=1.5, omega_max=2.5, n_omega=11, depth_max=0.2,
                             n_depth=3, damping=Damping("hysteretic", psi=0.2), boundaries_at=0.15)
    d = json.loads(json.dumps(ch.to_dict()))
    assert d["thresholds"][0]["depth_at_centre"] == pytest.approx(0.0636655046, rel=1e-8)
    assert len(d["boundaries"][0]["omega_low_rad_s"]) == 1 and d["rho_max"] and d["warnings"] == []
    json.dumps(par.floquet(sdof(), par.Modulation(), omega=2.0, depth=0.1).to_dict())


def _key(exc_info):
    return exc_info.value.key


@pytest.mark.parametrize("kwargs, key", [
    ({"omega": 0.0}, "omega"), ({"omega": -2.0}, "omega"), ({"omega": float("nan")}, "omega"),
    ({"omega": 2.0, "depth": 1.0}, "depth"), ({"omega": 2.0, "depth": -0.1}, "depth"),
    ({"omega": 2.0, "inertia_form": "lagrange"}, "inertia_form"), ({"omega": 2.0, "tolerance": 0.1}, "tolerance"),
])
def test_bad_point_input(kwargs, key):
    with pytest.raises(ModelError) as e:
        par.floquet(sdof(), par.Modulation(), **kwargs)
    assert _key(e) == key and key in str(e.value)


def test_depth_limits_name_the_key():
    # K(t) = c0 (1 - eps sin): indefinite for eps >= 1; M(t) likewise
    with pytest.raises(ModelError, match="K\\(t\\)") as e:
        par.floquet(sdof(), par.Modulation(), omega=2.0, depth=1.2)
    assert _key(e) == "depth"
    with pytest.raises(ModelError, match="M\\(t\\)") as e:
        par.floquet(sdof(), par.Modulation(target="inertia", depth=2.0), omega=2.0, depth=0.6)
    assert _key(e) == "depth"
    # a pulsating part of one spring: limit c_part/... computed from the generalised eigenvalues
    S = three_mass()
    part = np.zeros((3, 3))
    part[0, 0] = 2.0                                            # the ground spring of body a
    prob = par.ParametricProblem.build(S, [par.Modulation(part=part)])
    assert prob.depth_limit == pytest.approx(1.0, rel=1e-9)


@pytest.mark.parametrize("kwargs, key", [
    ({"n_omega": 1}, "n_omega"), ({"n_depth": 0}, "n_depth"), ({"n_omega": 2.5}, "n_omega"),
    ({"omega_max": 0.5}, "omega_max"), ({"omega_min": -1.0}, "omega_min"),
    ({"depth_min": 0.2, "depth_max": 0.1}, "depth_max"), ({"depth_max": 1.5}, "depth_max"),
    ({"boundaries_at": [0.1, 3.0]}, "boundaries_at[1]"), ({"boundary_samples": 1}, "boundary_samples"),
])
def test_bad_grid_input(kwargs, key):
    args = dict(omega_min=1.0, omega_max=3.0, n_omega=5, depth_max=0.3, n_depth=3, thresholds=False)
    args.update(kwargs)
    with pytest.raises(ModelError) as e:
        par.stability_chart(sdof(), par.Modulation(), **args)
    assert _key(e) == key


@pytest.mark.parametrize("make, key", [
    (lambda: par.Modulation(target="damping"), "target"),
    (lambda: par.Modulation(harmonic=0), "harmonic"),
    (lambda: par.Modulation(harmonic=1.5), "harmonic"),
    (lambda: par.Modulation(phase=float("inf")), "phase"),
    (lambda: par.floquet(sdof(), par.Modulation(part=np.eye(2)), omega=1.0), "part"),
    (lambda: par.floquet(sdof(), par.Modulation(part=np.array([[np.nan]])), omega=1.0), "part"),
    (lambda: par.floquet(sdof(), [], omega=1.0), "modulation"),
    (lambda: par.floquet(sdof(), par.Modulation(), omega=1.0, modes=2), "modes"),
    (lambda: par.damping_threshold(sdof(), par.Modulation(), mode=2), "mode"),
])
def test_bad_model_input(make, key):
    with pytest.raises(ModelError) as e:
        make()
    assert _key(e) == key


def test_rigid_body_mode_is_refused():
    free = LumpedModel(bodies=[Body("a", 1.0), Body("b", 1.0)], springs=[Link(("a", "b"), 1.0)]).linear_system()
    with pytest.raises(ModelError) as e:
        par.floquet(free, par.Modulation(), omega=1.0, depth=0.1)
    assert _key(e) == "supports" and "rigid-body" in str(e.value)
    held = LumpedModel(bodies=[Body("a", 1.0)], drivers=[Driver("motor", velocity=1.0)],
                       springs=[Link(("motor", "a"), 1.0)]).linear_system()
    assert par.floquet(held, par.Modulation(), omega=1.5, depth=0.1).stable      # between the tongues


def _example():
    spec = importlib.util.spec_from_file_location("parametric_chart", ROOT / "examples" / "parametric_chart.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_example_book_chart(tmp_path):
    """examples/parametric_chart.py (book chart): the threshold numbers of §7.3."""
    r = _example().book_chart(tmp_path)
    assert r["threshold_at_2k0"] == pytest.approx(0.063666, abs=5e-7)        # digest, printed digits
    assert r["threshold_at_2k0"] == pytest.approx(0.2 / math.pi, rel=1e-4)   # (7.28), first order
    assert r["energy_estimate"] == pytest.approx(0.2 / math.pi, rel=1e-14)
    assert r["threshold_tip"] == pytest.approx(0.06366097, rel=1e-6) and r["threshold_tip"] < r["threshold_at_2k0"]
    assert r["edges_eps_0.1"] == pytest.approx((1.96088, 2.03799), abs=5e-6)
    assert r["max_error_estimate"] <= 1e-10 and r["max_liouville_residual"] < 1e-12
    d = json.loads((tmp_path / "parametric_book.json").read_text())
    assert d["thresholds"][0]["depth_minimum"] == pytest.approx(r["threshold_tip"])
    assert (tmp_path / "parametric_book.png").stat().st_size > 10_000


@pytest.mark.slow
def test_example_drive_chart(tmp_path):
    r = _example().drive_chart(tmp_path)
    labels = [t[0] for t in r["tongues_eps_0.4"]]
    assert labels == ["2 w1/1", "2 w2/2", "(w1+w2)/1", "2 w2/1"]
    assert [t[1] for t in r["tongues_eps_0.4"]] == ["-1", "+1", "complex", "-1"]
    assert r["thresholds_tip"][1] < r["thresholds_tip"][0]
    assert (tmp_path / "parametric_drive.png").stat().st_size > 10_000
