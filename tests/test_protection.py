"""Vibration protection helpers (discrete.protection) and element forces / reactions (discrete.linear.reactions)."""
import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

from discrete.errors import ModelError
from discrete.linear.harmonic import Damping, harmonic_response
from discrete.linear.reactions import (LinkElement, constraint_reactions, element_forces, lumped_links,
                                       reactions_from_result)
from discrete.lumped import Body, Driver, Link, LumpedModel
from discrete.motion import PiecewiseLaw
from discrete.protection import (Absorber, MovingMassIsolation, QuasiConstantPlatform, damped_stiffness_limit,
                                 dynamic_factor, force_transmissibility, harmonic_unloading, isolation_design, kappa,
                                 kappa_extrema, relative_motion_factor, tuned_stiffness, unbalance_response,
                                 unbalance_spectrum, unloading_spring)

ROOT = Path(__file__).resolve().parents[1]


def test_reactions_balance_element_forces_on_a_driven_chain():
    """Driver -> spring -> mass -> spring+damper -> ground: the driver reaction equals the force of the
    first spring, the foundation force that of the grounded spring and damper, and the sum of external
    forces on the mass balances its inertia."""
    mdl = LumpedModel(bodies=[Body("m", 2.0)], drivers=[Driver("d", amplitude=0.01, omega=5.0)],
                      springs=[Link(("d", "m"), 300.0), Link(("m", "ground"), 100.0, psi=0.3)],
                      dampers=[Link(("m", "ground"), 1.5)])
    ls = mdl.linear_system()
    w = np.array([3.0, 11.0, 20.0])
    d = ls.dof_index(name="d")
    r = harmonic_response(ls, w, base_motion={d: 0.01})
    R = reactions_from_result(ls, r)
    P = element_forces(lumped_links(mdl), w, r.response)
    # spring 1 pushes its end a (the massless driver) with +P; the actuator force R balances it: R = -P
    assert np.allclose(R.values[:, 0], -P.values[:, 0], rtol=1e-12)
    assert R.equilibrium_residual < 1e-14
    m = ls.dof_index(name="m")
    Q = r.response[:, m]
    # mass: m (i w)^2 Q = -P1 (end b of spring 1) + P2 + P3 (end a of the grounded links)
    lhs = 2.0 * (1j * w) ** 2 * Q
    assert np.allclose(lhs, -P.values[:, 0] + P.values[:, 1] + P.values[:, 2], rtol=1e-12)
    # foundation force: -r_b P for links ending on ground
    assert np.allclose(P.foundation, -(P.values[:, 1] + P.values[:, 2]), rtol=1e-14)
    assert "foundation_amplitude" in P.to_dict() and "equilibrium_residual" in R.to_dict()


def test_transmissibility_identities():
    z = np.array([0.3, 1.0, math.sqrt(2), 2.5])
    assert np.allclose(force_transmissibility(z, 0.0)[[0, 2, 3]], 1 / np.abs(1 - z[[0, 2, 3]] ** 2))
    assert force_transmissibility(math.sqrt(2), 0.37) == pytest.approx(1.0)
    assert force_transmissibility(math.sqrt(2), 0.2, "hysteretic") == pytest.approx(1.0)
    assert np.allclose(relative_motion_factor(z, 0.1), z**2 * dynamic_factor(z, 0.1))


def test_unbalance_spectrum_scales_with_omega_squared():
    ls = LumpedModel(bodies=[Body("rotor", 3.0)], springs=[Link(("ground", "rotor"), 3e4)]).linear_system()
    r, spec = unbalance_response(ls, [10.0, 50.0], 0, 0.02)
    assert np.allclose(spec, 0.02 * np.array([100.0, 2500.0]))
    assert r.response[0, 0] == pytest.approx(2.0 / (3e4 - 300.0))
    assert np.allclose(unbalance_spectrum([2.0], 1.0, math.pi / 2), 4j)


def test_design_helpers():
    assert tuned_stiffness(0.5, 40.0) == pytest.approx(800.0)
    a = Absorber.design(100.0, 1e6, 95.0, 500.0, 0.005)
    assert a.c2 == pytest.approx(1e5) and a.m2 == pytest.approx(1e5 / 95.0**2)
    A1, A2 = a.amplitudes(95.0, 500.0)
    assert abs(A1) < 1e-15 and A2 == pytest.approx(-0.005)
    d = isolation_design(100.0, 300.0, xi_allowed=0.1, settlement_allowed=0.005, mass_range=(50.0, 200.0))
    assert d.feasible and d.m_opt == pytest.approx(50.0)
    assert damped_stiffness_limit(100.0, 300.0, 0.1, 0.0) == pytest.approx(d.c_max)
    assert damped_stiffness_limit(100.0, 300.0, 0.1, 0.1) < d.c_max
    mm = MovingMassIsolation(900.0, 100.0, 2.5e6, 100.0)
    assert mm.xi1 == pytest.approx(1 / 3) and mm.amplitude_ratio == pytest.approx(2 / 15)
    h = harmonic_unloading(1.0, [10.0, 20.0], 0.01, 100.0)
    assert h["R0_max"][0] == 0.0 and h["break_even"] == pytest.approx(10 / math.sqrt(2))
    ex = kappa_extrema(0.05, 0.9)
    assert ex["z_peak"] == pytest.approx(0.95346, abs=5e-6) and ex["kappa_peak"] == pytest.approx(math.sqrt(2), rel=1e-9)
    p = QuasiConstantPlatform.synthesised(10.0, 2e4, 5e4, 0.01, delta=0.05)
    assert p.theta2 == pytest.approx(1.0) and p.amplitude(p.p) == pytest.approx(0.0, abs=1e-15)


def test_unloading_spring_harmonic_law_unloads_completely():
    law = PiecewiseLaw([0.0, 2 * math.pi], [[0.02]], freq=[[1.0]], cos=[[-0.02]], periodic=True)
    u = unloading_spring(law, lambda p: 2.0 * 50.0**2 * (0.02 - law(p)))
    assert u.c0 == pytest.approx(5000.0, rel=1e-10) and u.u0 == pytest.approx(-100.0, rel=1e-10)
    assert u.peak_after < 1e-9 * u.peak_before and u.functional_after < 1e-20


def test_bad_input_names_the_key():
    ls = LumpedModel(bodies=[Body("m", 1.0)], springs=[Link(("ground", "m"), 1.0)]).linear_system()
    r = harmonic_response(ls, [0.5], force=np.array([1.0]))
    with pytest.raises(ModelError, match="modal"):
        constraint_reactions(ls, [0.5], r.response, damping=Damping("modal", zeta=0.1))
    with pytest.raises(ModelError, match="response"):
        constraint_reactions(ls, [0.5], np.zeros((1, 3)))
    two = LumpedModel(bodies=[Body("a", 1.0), Body("b", 1.0)], springs=[Link(("ground", "a"), 1.0), Link(("a", "b"), 1.0)])
    ls2 = two.linear_system()
    r2 = harmonic_response(ls2, [0.5], force=np.array([1.0, 0.0]), outputs=[0])
    with pytest.raises(ModelError, match="outputs"):
        reactions_from_result(ls2, r2)
    with pytest.raises(ModelError, match="k"):
        LinkElement("x", np.ones(1), k=-1.0)
    with pytest.raises(ModelError, match="m2"):
        Absorber(1.0, 1.0, 0.0, 1.0)
    with pytest.raises(ModelError, match="xi_allowed"):
        isolation_design(100.0, 300.0, xi_allowed=1.2)
    with pytest.raises(ModelError, match="force_amplitude"):
        isolation_design(100.0, 300.0, amplitude_allowed=1e-3)
    with pytest.raises(ModelError, match="damping"):
        kappa(1.0, 0.05, damping="coulomb")
    with pytest.raises(ModelError, match="damping"):
        force_transmissibility(1.0, 0.1, damping="coulomb")
    with pytest.raises(ModelError, match="delta"):
        force_transmissibility(1.0, -0.1)
    with pytest.raises(ModelError, match="law"):
        unloading_spring(PiecewiseLaw([0.0, 1.0], [[0.0, 1.0]]), lambda p: p)
    with pytest.raises(ModelError, match="dof"):
        unbalance_response(ls, [1.0], 3, 0.1)
    with pytest.raises(ModelError, match="c0"):
        harmonic_unloading(1.0, 1.0, 0.01, -5.0)


def test_absorber_design_example(tmp_path):
    spec = importlib.util.spec_from_file_location("absorber_example", ROOT / "examples" / "absorber_design.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    r = mod.main(tmp_path)
    assert (tmp_path / "absorber_design.json").exists() and all(Path(f).exists() for f in r["figures"])
    a = r["absorber"]
    assert a["c2"] == pytest.approx(500.0 / 0.005) and a["m2"] == pytest.approx(1e5 / 95.0**2)
    assert np.allclose(r["modal_frequencies"], a["natural_frequencies"], rtol=1e-10)
    k1, k2 = a["natural_frequencies"]
    assert k1 < 95.0 < k2 and k1 == pytest.approx(82.7659, abs=1e-4) and k2 == pytest.approx(114.7815, abs=1e-4)
    # tuned: the machine stands still, the absorber moves by the allowed stroke, nothing reaches the foundation
    assert r["A1_at_omega_star"] < 1e-12 * r["A1_without_absorber_at_omega_star"]
    assert r["A2_at_omega_star"] == pytest.approx(0.005, rel=1e-12)
    assert r["foundation_force_at_omega_star"] < 1e-9 * 500.0
    # without absorber (psi = 0.2): A = F/(c |1 - z^2 + 2 i delta|) at omega* = 95
    delta = 0.2 / (4 * math.pi)
    assert r["A1_without_absorber_at_omega_star"] == pytest.approx(500.0 / 1e6 / abs(1 - 0.95**2 + 2j * delta), rel=1e-12)
    # Fig. 6.10: the damper lowers the resonance peaks but A1(omega*) is no longer zero
    assert r["peak_A1_with_damper"] < 0.5 * r["peak_A1_with_absorber"]
    assert r["A1_with_damper_at_omega_star"] > 1e-5
