"""The definiteness checks of modal_analysis on large models (discrete.linear.modal):

* the mass check counts a matrix that decouples (a solid's consistent mass: one block per
  displacement component) block by block, equal blocks once -- the same Sylvester count, and a
  lower bound when a block has none;
* on the PARDISO path at the default shift, K is factorised once: its LDL^T inertia proves the
  stiffness check, and the same factorisation drives the Lanczos run (no second factorisation
  of K + zero_level M), while an indefinite K is still refused with its count;
* the shift-invert run keeps MKL's threads (PARDISO's solves) and limits OpenBLAS's.
"""
import numpy as np
import pytest
import scipy.sparse as sp

import discrete.linear.modal as modal
from discrete.errors import ModelError
from discrete.linalg import sparse_direct as sd
from discrete.linalg.blas import single_threaded_blas
from discrete.linear_system import LinearSystem

HAVE_PARDISO = "pardiso" in sd.available_solvers()
needs_pardiso = pytest.mark.skipif(not HAVE_PARDISO, reason="MKL PARDISO not installed (pip install pypardiso)")


def _laplacian(n, shift=0.0):
    return sp.diags([-np.ones(n - 1), (2.0 + shift) * np.ones(n), -np.ones(n - 1)], [-1, 0, 1])


def _solid_like(n=30, negative_block=False):
    """K of 3 coupled components per node and M = (scalar consistent mass) (x) I_3, the pattern of
    a solid; optionally one of M's three component blocks with a negative eigenvalue."""
    Ms = (sp.diags([np.ones(n - 1), 4.0 * np.ones(n), np.ones(n - 1)], [-1, 0, 1]) / 6.0).tocsr()
    blocks = [Ms, Ms, Ms]
    if negative_block:
        bad = Ms.tolil()
        k = n // 2
        bad[k, k + 1] = bad[k + 1, k] = 1.0          # [[2/3, 1], [1, 2/3]] inside: indefinite, diagonal > 0
        blocks[1] = bad.tocsr()
    M = sp.block_diag(blocks).tocsr()
    perm = np.arange(3 * n).reshape(3, n).T.ravel()          # node-major DOF order: x0 y0 z0 x1 ...
    M = M[perm][:, perm].tocsr()
    coupling = np.array([[2.0, 0.5, 0.0], [0.5, 3.0, 0.5], [0.0, 0.5, 2.0]])
    K = (sp.kron(_laplacian(n, 0.01), coupling)).tocsr()
    return K, M


def _system(K, M, rigid=0):
    return LinearSystem(M=M, K=K, dof_field=np.array(["x"] * K.shape[0], dtype=object),
                        rigid_modes=None if rigid is None else np.zeros((K.shape[0], rigid)))


def test_blockwise_count_equals_the_whole_count():
    """Three equal blocks, a different block with 2 negative eigenvalues, and uncoupled DOFs
    (two of them negative), shuffled: the block-wise count is the count of the whole matrix."""
    A = _laplacian(20, 0.1).tocsr()
    B = (_laplacian(15) - 0.2 * sp.identity(15)).tocsr()       # 2 eigenvalues 2 - 2cos(k pi/16) below 0.2 (k = 1, 2)
    singles = sp.diags([1.0, -2.0, 3.0, -4.0])
    whole = sp.block_diag([A, A, B, A, singles]).tocsr()
    perm = np.random.default_rng(5).permutation(whole.shape[0])
    whole = whole[perm][:, perm].tocsr()
    expected = int(np.sum(np.linalg.eigvalsh(whole.toarray()) < 0))
    assert expected == 4
    assert modal._negative_count(whole, library=False) == expected
    assert modal._blockwise_negative_count(whole) == expected


def test_blockwise_count_factorises_equal_blocks_once(monkeypatch):
    monkeypatch.delenv(sd.ENV, raising=False)             # the automatic choice: SuperLU at this size
    K, M = _solid_like(40)
    calls = []
    inner = modal._negative_count
    monkeypatch.setattr(modal, "_negative_count", lambda A, **kw: calls.append(A.shape[0]) or inner(A, **kw))
    assert modal._blockwise_negative_count(M) == 0
    assert calls == [40]                            # one of the three 40 x 40 component blocks


def test_mass_check_finds_a_negative_eigenvalue_in_one_component():
    K, M = _solid_like(30, negative_block=True)
    negatives = int(np.sum(np.linalg.eigvalsh(M.toarray()) < 0))
    assert negatives >= 1 and M.diagonal().min() > 0
    with pytest.raises(ModelError, match=f"{negatives} negative eigenvalue"):
        modal.modal_analysis(_system(K, M), 3)


@needs_pardiso
def test_pardiso_path_factorises_k_once_and_agrees(monkeypatch):
    """Above the PARDISO threshold (lowered here) K is factorised once and no K + z M count is
    made; the eigenvalues are those of the SuperLU path to rounding (cond(K) ~ 1e5 here)."""
    monkeypatch.setattr(sd, "AUTO_MIN_SIZE", 50)
    K, M = _solid_like(60)
    factored, counted = [], []
    inner_factor, inner_count = modal._factor, modal._negative_count
    monkeypatch.setattr(modal, "_factor", lambda A, **kw: factored.append((A.shape[0], kw)) or inner_factor(A, **kw))
    monkeypatch.setattr(modal, "_negative_count",
                        lambda A, **kw: counted.append(kw.get("definite")) or inner_count(A, **kw))
    fast = modal.modal_analysis(_system(K, M), 5)
    assert fast.linear_solver == "MKL PARDISO LL^T"          # K positive definite: Cholesky
    assert factored == [(180, {"definite": True})]
    assert counted == []            # the mass check's block is counted by PARDISO itself, no K + z M count
    with sd.preferred_solver("superlu"):
        ref = modal.modal_analysis(_system(K, M), 5)
    assert np.allclose(fast.eigenvalues, ref.eigenvalues, rtol=1e-10)
    dense = np.linalg.eigvalsh(np.linalg.solve(M.toarray(), K.toarray()))   # M regular: the closed reference
    assert np.allclose(fast.eigenvalues, np.sort(dense)[:5], rtol=1e-9)


@needs_pardiso
def test_pardiso_path_still_refuses_an_indefinite_stiffness(monkeypatch):
    monkeypatch.setattr(sd, "AUTO_MIN_SIZE", 50)
    K, M = _solid_like(30)
    K = (K - 0.05 * sp.identity(K.shape[0])).tocsr()          # lowest eigenvalues of K now negative
    negatives = int(np.sum(np.linalg.eigvalsh(K.toarray()) < 0))
    assert negatives > 0
    with pytest.raises(ModelError, match=rf"\({negatives} eigenvalue\(s\) below the round-off bound"):
        modal.modal_analysis(_system(K, M), 3)


@needs_pardiso
def test_pardiso_path_free_system_without_declared_rigid_modes(monkeypatch):
    """K singular (a free chain), rigid modes not declared: the K factorisation cannot prove the
    check (no factorisation, or a negative round-off pivot); the K + z M count decides, as
    before, and the rigid mode is found."""
    monkeypatch.setattr(sd, "AUTO_MIN_SIZE", 50)
    n = 60
    K = sp.diags([-np.ones(n - 1), np.r_[1.0, 2.0 * np.ones(n - 2), 1.0], -np.ones(n - 1)], [-1, 0, 1]).tocsr()
    M = sp.identity(n, format="csr")
    res = modal.modal_analysis(_system(K, M, rigid=None), 3)
    assert res.rigid[0] and not res.rigid[1:].any()
    exact = 2 - 2 * np.cos(np.arange(1, 3) * np.pi / n)      # free-free chain: 2 - 2 cos(k pi / n)
    assert np.allclose(res.eigenvalues[1:], exact, rtol=1e-10)


@needs_pardiso
def test_keep_mkl_limits_openblas_only():
    from threadpoolctl import threadpool_info

    def threads(api):
        return [lib["num_threads"] for lib in threadpool_info() if lib["internal_api"] == api]

    mkl_before = threads("mkl")
    if not mkl_before or max(mkl_before) < 2:
        pytest.skip("MKL runs one thread here: nothing to keep")
    with single_threaded_blas(keep_mkl=True):
        assert set(threads("openblas")) <= {1}
        assert threads("mkl") == mkl_before
    with single_threaded_blas():
        assert set(threads("mkl")) <= {1}


@needs_pardiso
def test_mkl_sparse_products_agree_with_scipy(monkeypatch):
    """ARPACK's M products on the PARDISO path run in MKL's sparse BLAS: the same products to
    rounding; without MKL there is no operator (the caller keeps scipy's)."""
    from discrete.linalg import mkl_sparse

    _, M = _solid_like(50)
    X = np.random.default_rng(7).standard_normal((M.shape[0], 3))
    op = mkl_sparse.mkl_operator(M)
    for x in X.T:
        ref = M @ x
        assert np.allclose(op.matvec(x), ref, rtol=0, atol=1e-14 * np.abs(ref).max())
    monkeypatch.setattr(mkl_sparse, "mkl_library", lambda: None)
    assert mkl_sparse.mkl_operator(M) is None


def test_unknown_block_count_keeps_the_negatives_found(monkeypatch):
    """A block whose count is unavailable (SuperLU needed an off-diagonal pivot) leaves the total a
    lower bound: negative eigenvalues found in the other blocks are still reported; with none the
    count is unknown (None), as for a whole matrix."""
    A = _laplacian(20, 0.1).tocsr()
    B = (_laplacian(15) - 0.2 * sp.identity(15)).tocsr()      # 2 negative eigenvalues
    inner = modal._negative_count
    monkeypatch.setattr(modal, "_negative_count", lambda X, **kw: None if X.shape[0] == 20 else inner(X, **kw))
    assert modal._blockwise_negative_count(sp.block_diag([A, B]).tocsr()) == 2
    assert modal._blockwise_negative_count(sp.block_diag([A, A]).tocsr()) is None


def _small_solid(**kw):
    from fem.solid import ShaftMeshSpec, build_solid
    from validation.builders import uniform

    return build_solid(uniform("bending", 0.6, 8, d=0.04, supports=[(0.0, "clamped")], **kw), ShaftMeshSpec(n_quarter=2))


def test_solid_mass_is_proven_by_construction_and_not_counted(monkeypatch):
    """A 3D solid's consistent mass is sum_q rho_q dx_q phi_q phi_q^T with rho, dx >= 0: its
    assembler records the proof, and modal_analysis skips the Sylvester count of M (0.9-1.4 s at
    104 400 DOFs); the modes are those found with the count."""
    solid = _small_solid(points=[{"x": 0.6, "mass": 0.3}])     # a tip mass: section integrals, weights >= 0
    system = solid.system
    reason = system.mass_semidefinite_reason
    assert reason and "densities >= 0" in reason and "point masses" in reason
    calls = []
    inner = modal._blockwise_negative_count
    monkeypatch.setattr(modal, "_blockwise_negative_count", lambda A: calls.append(A.shape[0]) or inner(A))
    proven = modal.modal_analysis(system, 4)
    assert calls == []
    system.mass_proof = None
    counted = modal.modal_analysis(system, 4)
    assert len(calls) == 1
    assert np.array_equal(proven.frequencies_hz, counted.frequencies_hz)


def test_a_mass_proof_does_not_outlive_its_matrix():
    """The proof holds for the matrix object it was given for: a system whose M is replaced (or
    rebuilt by LinearSystem) has none, and a pickled system keeps it; a negative density gives no
    proof, so the check runs and refuses the matrix (a negative point mass stops at the model's own
    check before any assembly)."""
    import dataclasses
    import pickle

    from fem.solid.model import assemble_solid

    system = _small_solid().system
    assert dataclasses.replace(system, M=system.M.copy()).mass_semidefinite_reason is None
    assert dataclasses.replace(system, title="other").mass_semidefinite_reason is None     # M converted anew
    assert pickle.loads(pickle.dumps(system)).mass_semidefinite_reason == system.mass_semidefinite_reason
    solid = _small_solid()
    rho = np.full(solid.mesh.t.shape[1], 7800.0)
    rho[3] = -7800.0
    bad = assemble_solid(solid.mesh, np.full(rho.size, 8e10), np.full(rho.size, 1.2e11), rho).system
    assert bad.mass_semidefinite_reason is None
    with pytest.raises(ModelError, match="negative"):
        modal.modal_analysis(dataclasses.replace(bad, constrained=np.arange(30)), 2)
