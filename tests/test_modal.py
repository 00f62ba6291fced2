"""Properties of the modal solver that do not depend on a textbook number."""
import numpy as np
import pytest

from discrete.errors import ModelError
from discrete.linear_system import LinearSystem
from fem import assemble, modal_analysis
from validation.builders import uniform


def test_mass_normalised_and_orthogonal():
    fe = assemble(uniform("bending", 1.2, 20, supports=[(0.0, "clamped")]))
    res = modal_analysis(fe.system, 5)
    f = fe.system.free
    Phi = res.shapes[f]
    Mf = fe.system.free_block(fe.system.M)
    Kf = fe.system.free_block(fe.system.K)
    assert np.allclose(Phi.T @ Mf @ Phi, np.eye(5), atol=1e-10)
    assert np.allclose(Phi.T @ Kf @ Phi, np.diag(res.eigenvalues), rtol=1e-9, atol=1e-6 * res.eigenvalues.max())
    assert np.all(res.shapes[fe.system.constrained] == 0)


def test_vieta_trace_identity():
    """Sum of 1/k_r^2 over all modes equals trace(K^-1 M) (4.38), digest V4.7a."""
    fe = assemble(uniform("torsion", 1.0, 6, supports=[(0.0, "clamped")], order=1))
    res = modal_analysis(fe.system, fe.system.n_free)
    K = fe.system.free_block(fe.system.K).toarray()
    M = fe.system.free_block(fe.system.M).toarray()
    assert np.sum(1 / res.eigenvalues) == pytest.approx(np.trace(np.linalg.solve(K, M)), rel=1e-12)


def test_sparse_and_dense_paths_agree():
    fe = assemble(uniform("bending", 1.5, 200, supports=[(0.0, "clamped"), (1.5, "pinned")]))
    sparse = modal_analysis(fe.system, 4, dense_max=0)
    dense = modal_analysis(fe.system, 4, dense_max=10**6)
    assert "sparse" in sparse.method and "dense" in dense.method
    assert np.allclose(sparse.omega_rad_s, dense.omega_rad_s, rtol=1e-6)


def test_free_free_sparse_finds_rigid_modes():
    fe = assemble(uniform("bending", 1.5, 400, supports=[]))
    res = modal_analysis(fe.system, 5)
    assert "sparse" in res.method
    assert res.rigid_body_modes == 2
    assert np.all(res.omega_rad_s[:2] == 0) and res.omega_rad_s[2] > 0


def test_bare_matrices_detect_rigid_mode_numerically():
    K = np.array([[1.0, -1.0], [-1.0, 1.0]])
    sys_ = LinearSystem(M=np.eye(2), K=K, dof_field=["x", "x"])
    res = modal_analysis(sys_, 2)
    assert res.rigid.tolist() == [True, False]
    assert res.omega_rad_s[1] == pytest.approx(np.sqrt(2))


def test_more_modes_than_dofs_is_an_error():
    fe = assemble(uniform("torsion", 1.0, 3, supports=[], order=1))
    with pytest.raises(ModelError, match=r"modes = 5 .*1 to 4"):
        modal_analysis(fe.system, 5)


def test_lumped_mass_zero_rotation_inertia_limits_modes():
    fe = assemble(uniform("bending", 1.0, 4, supports=[(0.0, "clamped")], mass="lumped", d=0.05))
    res = modal_analysis(fe.system, 3)
    assert res.reliable.all()
