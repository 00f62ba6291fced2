"""psi in the time domain (discrete.linear.dissipation): the book's forms (9.3) and (9.14)-(9.18),
the report, the refusals (ModelError naming the key), drivers and free systems, and a simulated decay."""
import json
import math

import numpy as np
import pytest

from discrete.errors import ModelError
from discrete.linear import harmonic_response
from discrete.linear import dissipation as dis
from discrete.linear.dissipation import time_domain_psi
from discrete.linear_system import LinearSystem
from discrete.lumped import Body, Driver, Link, LumpedModel
from discrete.nonsmooth import MotionLaw, Problem, simulate
from validation.analytic import psi_refs as ref
from validation.cases.psi_time_domain import (book_2dof_chain, book_2dof_deformation_coordinates, decay_per_cycle,
                                              free_decay, sdof_with_psi)


def chain(n=4, psis=(0.1, 0.3, 0.5, 0.7), **kw):
    """ground - k - m1 - k - m2 ... with element psi."""
    names = [f"m{i}" for i in range(n)]
    ends = ["ground"] + names
    return LumpedModel(bodies=[Body(b, 1.0 + 0.5 * i) for i, b in enumerate(names)],
                       springs=[Link((ends[i], ends[i + 1]), 100.0 * (i + 1), psi=psis[i]) for i in range(n)],
                       **kw).linear_system()


def test_book_2dof_matrix_and_psi_star():
    C, rep = time_domain_psi(book_2dof_deformation_coordinates(), "modal")
    book = ref.book_modal_2dof([[2, 1], [1, 1]], np.eye(2), [0.2, 0.6])
    np.testing.assert_allclose(C.toarray(), book["b"], rtol=0, atol=1e-15)
    np.testing.assert_allclose(rep.psi_star, [0.310557, 0.489443], atol=0.5e-6)
    np.testing.assert_allclose(C.toarray(), [[0.071176, 0.014235], [0.014235, 0.056941]], atol=0.5e-6)
    assert rep.method == "modal" and rep.n_modes_used == 2 and rep.completion.startswith("complete")
    # physical coordinates through the lumped builder's element psi: b = T^T C_x T
    Cx, _ = time_domain_psi(book_2dof_chain().linear_system(), "modal")
    T = np.array([[1.0, 0.0], [1.0, 1.0]])
    np.testing.assert_allclose(T.T @ Cx.toarray() @ T, book["b"], atol=1e-15)
    json.dumps(rep.to_dict())


def test_equivalent_is_H_over_omega_and_keeps_the_harmonic_response():
    ls = chain()
    C, rep = time_domain_psi(ls, "equivalent", omega_ref=7.0)
    np.testing.assert_allclose(C.toarray(), ls.H.toarray() / 7.0, rtol=1e-15)
    F = np.zeros(ls.n_dofs, complex)
    F[-1] = 1.0
    hyst = harmonic_response(ls, [7.0], force=F).response
    visc = harmonic_response(LinearSystem(M=ls.M, K=ls.K, C=C, dof_field=ls.dof_field), [7.0], force=F).response
    np.testing.assert_allclose(visc, hyst, rtol=1e-12)
    # mode by mode: psi* omega_r / omega_ref
    np.testing.assert_allclose(rep.psi_represented, rep.psi_star * rep.omega_rad_s / 7.0, rtol=1e-12)
    assert rep.omega_ref_source == "given" and rep.omega_rad_s.size == 4
    assert any("outside [omega_ref/2, 2 omega_ref]" in w for w in rep.warnings)


def test_modal_all_modes_each_mode_its_psi_star_and_psd():
    ls = chain()
    C, rep = time_domain_psi(ls, "modal")
    np.testing.assert_allclose(rep.psi_represented, rep.psi_star, rtol=1e-12)
    A = C.toarray()
    assert np.allclose(A, A.T, rtol=0, atol=1e-15 * np.abs(A).max())
    assert np.linalg.eigvalsh(A).min() > -1e-12 * np.abs(A).max()
    assert 0 < rep.coupling < 1
    # the reduced coefficients are strain-energy averages of the element psi (9.14)
    assert np.all((rep.psi_star > 0.1 - 1e-12) & (rep.psi_star < 0.7 + 1e-12))


def test_truncated_modal_completion_and_none():
    ls = chain()
    C, rep = time_domain_psi(ls, "modal", n_modes=2)
    assert rep.n_modes_used == 2 and rep.completion == "stiffness"
    assert rep.completion_omega == pytest.approx(rep.omega_rad_s[2], rel=1e-14)
    np.testing.assert_allclose(rep.psi_represented[:3], rep.psi_star[:3], rtol=1e-12)   # 2 kept + first excluded
    Cn, repn = time_domain_psi(ls, "modal", n_modes=2, completion="none")
    assert repn.psi_represented[2] == pytest.approx(0.0, abs=1e-12)
    assert any("no damping from psi" in w for w in repn.warnings)
    np.testing.assert_allclose(repn.psi_represented[:2], rep.psi_star[:2], rtol=1e-12)


def test_sdof_modal_equals_equivalent_at_first_mode():
    ls = sdof_with_psi(0.3)
    Ce, rep = time_domain_psi(ls, "equivalent", omega_ref="first_mode")
    Cm, _ = time_domain_psi(ls, "modal")
    assert Ce.toarray()[0, 0] == pytest.approx(Cm.toarray()[0, 0], rel=1e-14)
    assert Ce.toarray()[0, 0] == pytest.approx(0.3 * 800.0 / (2 * math.pi * 20.0), rel=1e-14)     # (9.3)
    assert rep.omega_ref == pytest.approx(20.0) and rep.omega_ref_source == "first natural frequency"


def test_simulated_energy_loss_per_cycle():
    psi = 0.2
    ls = sdof_with_psi(psi)
    C, _ = time_domain_psi(ls, "equivalent", omega_ref=20.0)
    res, damped = free_decay(ls, C, np.array([1e-2]), 5.5, 20.0)
    ratios, _ = decay_per_cycle(res, damped, 0)
    loss = 1 - ratios**2
    assert loss.size >= 4
    np.testing.assert_allclose(loss, ref.energy_loss_per_cycle(psi), rtol=1e-8)
    assert abs(loss.mean() - psi) < psi**2 / 2          # psi to first order


def test_driver_at_constant_speed_is_not_braked():
    """Modal psi acts on the motion relative to the quasi-static (rigid) drive motion: a disk driven at
    constant speed through a spring with psi settles with zero deformation (no drag)."""
    lm = LumpedModel(bodies=[Body("disk", 2.0), Body("load", 1.0)], drivers=[Driver("motor", velocity=1.0)],
                     springs=[Link(("motor", "disk"), 50.0, psi=0.5), Link(("disk", "load"), 30.0, psi=0.3)])
    ls = lm.linear_system()
    for method in ("modal", "equivalent"):
        C, _ = time_domain_psi(ls, method, omega_ref="first_mode")
        np.testing.assert_allclose(C.toarray() @ np.ones(ls.n_dofs), 0.0, atol=1e-13)     # rigid rotation
        prob = Problem(ls.with_damping(C=C), [], drivers={int(ls.constrained[0]): MotionLaw(velocity=1.0)})
        res = simulate(prob, 150.0)
        i, j = res.names.index("load"), res.names.index("motor")
        assert abs(res.x[i, -1] - res.x[j, -1]) < 1e-8
        assert res.v[i, -1] == pytest.approx(1.0, abs=1e-8)


def test_free_system_rigid_mode_left_alone():
    lm = LumpedModel(bodies=[Body("a", 1.0), Body("b", 3.0)], springs=[Link(("a", "b"), 12.0, psi=0.4)])
    ls = lm.linear_system()
    C, rep = time_domain_psi(ls, "modal")
    assert rep.rigid_modes == 1 and rep.omega_rad_s.size == 1
    np.testing.assert_allclose(C.toarray() @ np.ones(2), 0.0, atol=1e-14)
    assert rep.psi_star[0] == pytest.approx(0.4, rel=1e-12)
    assert rep.psi_represented[0] == pytest.approx(0.4, rel=1e-12)


def test_no_psi_returns_zero():
    ls = LumpedModel(bodies=[Body("m", 1.0)], springs=[Link(("ground", "m"), 4.0)]).linear_system()
    C, rep = time_domain_psi(ls, "equivalent")          # nothing to represent: no reference frequency needed
    assert C.nnz == 0 and rep.method == "none" and rep.describe() == "no psi in the model"


def test_reference_frequency_from_forcing():
    ls = chain()
    C, rep = time_domain_psi(ls, "equivalent", forcing_omegas=[5.0, 5.0, 0.0])
    assert rep.omega_ref == 5.0 and rep.omega_ref_source == "forcing frequency"
    assert any("omega_ref not given" in w for w in rep.warnings)
    C2, rep2 = time_domain_psi(ls, "equivalent", omega_ref="forcing", forcing_omegas=[5.0])
    assert rep2.omega_ref == 5.0 and not any("omega_ref not given" in w for w in rep2.warnings)


@pytest.mark.parametrize("kwargs,key", [
    (dict(method="equivalent"), "omega_ref"),                                            # no reference, no forcing
    (dict(method="equivalent", forcing_omegas=[3.0, 4.0]), "omega_ref"),                 # ambiguous forcing
    (dict(method="equivalent", omega_ref="forcing"), "omega_ref"),
    (dict(method="equivalent", omega_ref="forcing", forcing_omegas=[3.0, 4.0]), "omega_ref"),
    (dict(method="equivalent", omega_ref="resonance"), "omega_ref"),
    (dict(method="equivalent", omega_ref=0.0), "omega_ref"),
    (dict(method="equivalent", omega_ref=-2.0), "omega_ref"),
    (dict(method="equivalent", omega_ref=float("nan")), "omega_ref"),
    (dict(method="equivalent", omega_ref=True), "omega_ref"),
    (dict(method="rayleigh"), "psi_time"),
    (dict(method="modal", n_modes=0), "psi_modes"),
    (dict(method="modal", n_modes=5), "psi_modes"),
    (dict(method="modal", n_modes=2.0), "psi_modes"),
    (dict(method="modal", completion="mass"), "psi_completion"),
])
def test_refusals_name_the_key(kwargs, key):
    with pytest.raises(ModelError) as err:
        time_domain_psi(chain(), **kwargs)
    assert err.value.key == key and err.value.where == "[damping]"


def test_modal_refused_on_models_too_large_for_a_dense_matrix(monkeypatch):
    monkeypatch.setattr(dis, "MODAL_DENSE_MAX", 3)
    with pytest.raises(ModelError) as err:
        time_domain_psi(chain(), "modal")
    assert err.value.key == "psi_time" and "equivalent" in err.value.allowed
    C, _ = time_domain_psi(chain(), "equivalent", omega_ref=10.0)       # the sparse form still works
    assert C.nnz == chain().H.nnz
