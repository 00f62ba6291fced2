"""The sparse direct factorisation (discrete.linalg.sparse_direct): MKL PARDISO against SuperLU on
SPD and indefinite shifted matrices, the fallback without MKL, and the solver reported.

Tolerances: both factorisations are backward stable, so two solutions differ by about
cond(A) * eps; the matrices here have cond < 1e5 (printed by the dense eigenvalues), hence 1e-9."""
import gc
import sys

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from discrete.errors import ModelError, SolverError
from discrete.linalg import sparse_direct as sd
from discrete.linear_system import LinearSystem
from discrete.linear.modal import modal_analysis

HAVE_PARDISO = "pardiso" in sd.available_solvers()
needs_pardiso = pytest.mark.skipif(not HAVE_PARDISO, reason="MKL PARDISO not installed (pip install pypardiso)")


def _pair(n=8):
    """K and M of a 3D grid of n^3 nodes with 3 coupled DOFs each (the block pattern of solid
    elements), K positive definite, M positive diagonal with unequal entries."""
    L = sp.diags([-np.ones(n - 1), 2.0 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1])
    I = sp.identity(n)
    lap = sp.kron(sp.kron(L, I), I) + sp.kron(sp.kron(I, L), I) + sp.kron(sp.kron(I, I), L)
    block = np.array([[2.0, 0.5, 0.0], [0.5, 3.0, 0.5], [0.0, 0.5, 2.0]])
    K = (sp.kron(lap, block) + 0.1 * sp.identity(3 * n**3)).tocsr()
    M = sp.diags(np.random.default_rng(3).uniform(0.5, 1.5, 3 * n**3)).tocsr()
    return K, M


@pytest.fixture
def fresh_library_cache():
    sd._mkl.cache_clear()
    sd.mkl_library.cache_clear()
    yield
    sd._mkl.cache_clear()
    sd.mkl_library.cache_clear()


def test_superlu_path_is_scipy_splu_bit_for_bit():
    K, _ = _pair(5)
    b = np.random.default_rng(0).standard_normal(K.shape[0])
    f = sd.factorize(K, solver="superlu")
    lu = spla.splu(sp.csc_matrix(K))
    assert f.solver == "SuperLU" and f.name == "SuperLU LU" and f.inertia is None
    assert np.array_equal(f.solve(b), lu.solve(b))
    piv = np.abs(lu.U.diagonal())
    assert f.pivot_ratio == piv.min() / piv.max()


def test_small_matrices_stay_on_superlu_under_auto():
    K, _ = _pair(5)
    assert K.shape[0] < sd.AUTO_MIN_SIZE
    assert sd.choose(K.shape[0]) == "superlu" and sd.factorize(K).solver == "SuperLU"


@needs_pardiso
def test_pardiso_agrees_with_superlu_on_spd():
    K, _ = _pair(8)
    rng = np.random.default_rng(1)
    b, B = rng.standard_normal(K.shape[0]), rng.standard_normal((K.shape[0], 3))
    fast, ref = sd.factorize(K, solver="pardiso"), sd.factorize(K, solver="superlu")
    assert fast.name == "MKL PARDISO LDL^T" and not fast.notes
    assert fast.inertia == (K.shape[0], 0)                     # positive definite: no negative pivot
    assert np.allclose(fast.solve(b), ref.solve(b), rtol=1e-9, atol=0)
    X = fast.solve(B)
    assert X.shape == B.shape and np.allclose(X, ref.solve(B), rtol=1e-9, atol=0)
    assert np.linalg.norm(K @ X - B) <= 1e-13 * np.linalg.norm(B) * spla.norm(K, 1)
    assert 0 < fast.pivot_ratio <= 1


@needs_pardiso
@pytest.mark.parametrize("between", [3, 40])
def test_pardiso_indefinite_shift_inertia_and_solution(between):
    """K - sigma M with sigma between eigenvalues ``between`` and ``between + 1``: the LDL^T inertia
    is Sylvester's count of eigenvalues below sigma, the solution agrees with SuperLU's LU."""
    K, M = _pair(6)
    lam = sp.linalg.eigsh(K, k=between + 2, M=M, sigma=0.0, return_eigenvectors=False)
    lam = np.sort(lam)
    sigma = 0.5 * (lam[between - 1] + lam[between])
    A = (K - sigma * M).tocsr()
    b = np.random.default_rng(2).standard_normal(A.shape[0])
    fast = sd.factorize(A, solver="pardiso")
    assert fast.solver == "MKL PARDISO", fast.notes
    assert fast.inertia == (A.shape[0] - between, between)
    ref = sd.factorize(A, solver="superlu").solve(b)
    assert np.allclose(fast.solve(b), ref, rtol=1e-9, atol=1e-9 * np.abs(ref).max())


@needs_pardiso
def test_definite_hint_uses_cholesky_and_falls_back_to_ldlt():
    """``definite=True``: PARDISO's Cholesky on a positive definite matrix (inertia (n, 0), the
    same solution as SuperLU's, the same pivots as the LDL^T); on an indefinite one its failure
    hands the matrix to the LDL^T, whose inertia counts the negative eigenvalues."""
    K, M = _pair(6)
    b = np.random.default_rng(4).standard_normal(K.shape[0])
    chol = sd.factorize(K, solver="pardiso", definite=True)
    ldlt = sd.factorize(K, solver="pardiso")
    assert chol.name == "MKL PARDISO LL^T" and chol.inertia == (K.shape[0], 0)
    assert np.allclose(chol.solve(b), sd.factorize(K, solver="superlu").solve(b), rtol=1e-9, atol=0)
    assert np.isclose(chol.pivot_ratio, ldlt.pivot_ratio, rtol=1e-8)
    lam = np.sort(sp.linalg.eigsh(K, k=5, M=M, sigma=0.0, return_eigenvectors=False))
    A = (K - 0.5 * (lam[2] + lam[3]) * M).tocsr()
    indefinite = sd.factorize(A, solver="pardiso", definite=True)
    assert indefinite.name == "MKL PARDISO LDL^T" and indefinite.inertia == (A.shape[0] - 3, 3)


@needs_pardiso
def test_nearly_singular_matrix_goes_to_superlu_with_a_note():
    """A free-free Laplacian is singular (constant null vector): PARDISO perturbs the last pivot,
    that factorisation is dropped, and SuperLU answers (exactly singular) or is used with a note."""
    n = 400
    L = sp.diags([-np.ones(n - 1), np.r_[1.0, 2.0 * np.ones(n - 2), 1.0], -np.ones(n - 1)], [-1, 0, 1]).tocsr()
    try:
        f = sd.factorize(L, solver="pardiso")
    except sd.SingularMatrixError:
        return
    assert f.solver == "SuperLU" and "perturbed" in f.notes[0]
    with pytest.raises(SolverError, match="perturbed"):        # PARDISO only: no SuperLU behind it
        sd.factorize(L, solver="pardiso", fallback=False)


@needs_pardiso
def test_missing_diagonal_entries_are_stored_as_zeros():
    """PARDISO needs every diagonal entry in the pattern of a symmetric matrix; a saddle point
    [[A, B^T], [B, 0]] has none in its lower block."""
    A = sp.diags([4.0, 5.0, 6.0])
    B = sp.csr_matrix(np.array([[1.0, 1.0, 0.0]]))
    S = sp.bmat([[A, B.T], [B, None]]).tocsr()
    b = np.arange(1.0, 5.0)
    f = sd.factorize(S, solver="pardiso")
    assert f.inertia == (3, 1)
    assert np.allclose(f.solve(b), np.linalg.solve(S.toarray(), b), rtol=1e-12)


@needs_pardiso
def test_pardiso_memory_released_with_the_factorisation():
    K, _ = _pair(4)
    f = sd.factorize(K, solver="pardiso")
    pt = f._solve.__self__.pt
    assert pt.any()
    del f
    gc.collect()
    assert not pt.any()


def test_missing_library_falls_back_to_superlu(monkeypatch, fresh_library_cache):
    monkeypatch.setitem(sys.modules, "pypardiso", None)          # `import pypardiso` fails
    monkeypatch.setattr(sd, "AUTO_MIN_SIZE", 10)
    K, _ = _pair(4)
    assert sd.available_solvers() == ["superlu"]
    assert sd.choose(10**6) == "superlu"
    assert sd.factorize(K).name == "SuperLU LU"
    with pytest.raises(ModelError, match="pip install pypardiso"):
        sd.factorize(K, solver="pardiso")


@needs_pardiso
def test_auto_choice_threshold_env_and_context(monkeypatch):
    monkeypatch.setattr(sd, "AUTO_MIN_SIZE", 100)
    K, _ = _pair(4)                                              # 192 rows
    assert sd.factorize(K).solver == "MKL PARDISO"
    assert sd.factorize(K[:60, :60]).solver == "SuperLU"
    with sd.preferred_solver("superlu"):
        assert sd.factorize(K).solver == "SuperLU"
    monkeypatch.setenv(sd.ENV, "superlu")
    assert sd.factorize(K).solver == "SuperLU"
    monkeypatch.setenv(sd.ENV, "fastest")
    with pytest.raises(ModelError, match=sd.ENV):
        sd.factorize(K)


def test_bad_solver_name():
    with pytest.raises(ModelError, match="auto | superlu | pardiso"):
        sd.factorize(sp.identity(3, format="csr"), solver="umfpack")


def _system(n=6):
    K, M = _pair(n)
    return LinearSystem(M=M, K=K, dof_field=np.array(["x"] * K.shape[0], dtype=object),
                        rigid_modes=np.zeros((K.shape[0], 0)))


def test_modal_analysis_reports_the_factorisation():
    res = modal_analysis(_system(), 4)
    assert res.linear_solver == "SuperLU LU" and res.method.endswith("(eigsh, SuperLU LU)")
    assert res.to_dict()["linear_solver"] == "SuperLU LU"


@needs_pardiso
def test_modal_analysis_with_pardiso_agrees_with_superlu():
    """Same Lanczos, another factorisation of K: eigenvalues agree to rounding (cond(K) ~ 1e3)."""
    system = _system()
    ref = modal_analysis(system, 12)
    sigma = 0.5 * (ref.eigenvalues[2] + ref.eigenvalues[3])
    with sd.preferred_solver("pardiso"):
        fast = modal_analysis(system, 6)
        shifted = modal_analysis(system, 4, shift=sigma)
    assert fast.linear_solver == "MKL PARDISO LL^T" and "MKL PARDISO" in fast.method   # K definite: Cholesky
    assert np.allclose(fast.eigenvalues, ref.eigenvalues[:6], rtol=1e-10)
    assert shifted.linear_solver == "MKL PARDISO LDL^T"          # indefinite K - sigma M
    nearest = np.sort(ref.eigenvalues[np.argsort(np.abs(ref.eigenvalues - sigma))[:4]])
    assert np.allclose(shifted.eigenvalues, nearest, rtol=1e-10)


@pytest.mark.slow
@needs_pardiso
def test_solid_shaft_above_threshold_uses_pardiso():
    """A 3D solid cantilever of ~35k DOFs: automatic choice, frequencies as SuperLU's (1e-9:
    the eigenvalues' own rounding level, eps * lam_max / lam, is ~1e-10 here)."""
    from fem.solid import ShaftMeshSpec, build_solid
    from validation.builders import uniform

    solid = build_solid(uniform("bending", 1.0, 40, d=0.05, supports=[(0.0, "clamped")]), ShaftMeshSpec(n_quarter=3))
    assert solid.system.n_free >= sd.AUTO_MIN_SIZE
    fast = modal_analysis(solid.system, 6)
    with sd.preferred_solver("superlu"):
        ref = modal_analysis(solid.system, 6)
    assert fast.linear_solver == "MKL PARDISO LL^T" and ref.linear_solver == "SuperLU LU"
    assert np.allclose(fast.frequencies_hz, ref.frequencies_hz, rtol=1e-9)
    assert fast.reliable.all()


@needs_pardiso
def test_mkl_is_found_in_the_prefix_without_a_search(monkeypatch):
    """Where the MKL wheel installs it (sys.prefix/lib) the library is handed to pypardiso as a hint,
    so pypardiso's recursive search of sys.prefix (0.15 s per process) does not run; the hint is
    not left in the environment."""
    import pypardiso.pardiso_wrapper as pw

    near = sd._mkl_rt_in_prefix()
    if near is None:
        pytest.skip("MKL is not installed in sys.prefix/lib here")
    monkeypatch.delenv("PYPARDISO_MKL_RT", raising=False)
    real_glob = pw.glob.glob

    def no_search(pattern, *a, **k):
        if "**" in pattern:
            pytest.fail("pypardiso searched sys.prefix")
        return real_glob(pattern, *a, **k)

    monkeypatch.setattr(pw.glob, "glob", no_search)
    monkeypatch.setattr(pw, "find_library", lambda name: pytest.fail("pypardiso asked find_library"))
    monkeypatch.delitem(sys.modules, "pypardiso", raising=False)
    monkeypatch.delitem(sys.modules, "pypardiso.scipy_aliases", raising=False)
    sd.mkl_library.cache_clear()
    try:
        lib = sd.mkl_library()
    finally:
        sd.mkl_library.cache_clear()
    assert lib is not None and lib._name == near
    assert "PYPARDISO_MKL_RT" not in __import__("os").environ


@needs_pardiso
def test_a_hint_that_does_not_load_falls_back_on_pypardisos_search(monkeypatch):
    """A library in the prefix that cannot be loaded (a dangling link) does not switch PARDISO off:
    pypardiso's own search runs; a PYPARDISO_MKL_RT set by the user is used and left as it is."""
    import os

    def fresh():
        for name in ("pypardiso", "pypardiso.scipy_aliases"):
            monkeypatch.delitem(sys.modules, name, raising=False)
        sd.mkl_library.cache_clear()

    monkeypatch.delenv("PYPARDISO_MKL_RT", raising=False)
    monkeypatch.setattr(sd, "_mkl_rt_in_prefix", lambda: "/nonexistent/libmkl_rt.so.3")
    fresh()
    try:
        assert sd.mkl_library() is not None
        assert "PYPARDISO_MKL_RT" not in os.environ
        real = sd.mkl_library()._name
        monkeypatch.setenv("PYPARDISO_MKL_RT", real)
        monkeypatch.setattr(sd, "_mkl_rt_in_prefix", lambda: pytest.fail("the user's setting was overridden"))
        fresh()
        assert sd.mkl_library()._name == real and os.environ["PYPARDISO_MKL_RT"] == real
    finally:
        sd.mkl_library.cache_clear()
