"""LAPACK's banded LU for large narrow-band matrices (discrete.linalg.sparse_direct, ``solver="auto"``,
from BANDED_MIN_SIZE rows on) and the banded Cholesky test of positive definiteness
(discrete.linalg.banded.positive_definite) that the modal stiffness and mass checks use there.

References: SuperLU on the same matrices (both backward stable: solutions agree to cond(A) eps,
so each test states its matrix's condition), dense eigenvalues, and the Sylvester count of
SuperLU's LDL^T (the count the Cholesky test replaces)."""
from dataclasses import replace

import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse as sp

from discrete.errors import ModelError
from discrete.linalg import sparse_direct as sd
from discrete.linalg.banded import positive_definite
from discrete.linear.modal import _negative_count, modal_analysis
from fem import Material, Section, Segment, ShaftModel, Support, assemble


def _shaft(kind: str, n_dofs: int):
    physics = "torsion" if kind == "shaft" else "bending"
    model = ShaftModel(physics, [Segment(1.5, n_dofs // 2, Section.circle(0.05),
                                         Material(E=2.1e11, G=8.1e10, rho=7850.0))],
                       supports=[Support(0.0)], order=2)
    return assemble(model).system


def _backward_error(A, x, b):
    return np.linalg.norm(A @ x - b) / (sp.linalg.norm(A, 1) * np.linalg.norm(x) + np.linalg.norm(b))


@pytest.mark.parametrize("kind", ["shaft", "beam"])
def test_large_narrow_band_matrices_use_the_banded_lu(kind):
    system = _shaft(kind, 2000)
    K = system.free_block(system.K)
    f = sd.factorize(K)
    assert f.solver == "LAPACK" and f.name.startswith("LAPACK banded LU")
    b = np.random.default_rng(1).standard_normal(K.shape[0])
    x = f.solve(b)
    assert _backward_error(K, x, b) < 1e-15                   # backward stable, as SuperLU
    ref = sd.factorize(K, solver="superlu").solve(b)
    cond = np.linalg.cond(K.toarray()) if kind == "shaft" else 1e12       # the Hermite beam: ~1e12
    assert np.max(np.abs(x - ref)) <= 10 * cond * np.finfo(float).eps * np.max(np.abs(ref))
    X = f.solve(np.column_stack([b, 2 * b]))                 # several right-hand sides
    assert np.allclose(X[:, 1], 2 * X[:, 0], rtol=0, atol=1e-14 * np.max(np.abs(X)))
    assert f.pivot_ratio > 0


def test_small_wide_or_overridden_stay_on_superlu(monkeypatch):
    small = _shaft("beam", 400)
    assert sd.factorize(small.free_block(small.K)).solver == "SuperLU"      # below BANDED_MIN_SIZE
    rng = np.random.default_rng(2)
    A = sp.random(1500, 1500, density=0.004, random_state=rng)
    A = (A + A.T + 20 * sp.identity(1500)).tocsr()                           # no narrow band exists
    assert sd.factorize(A).solver == "SuperLU"
    big = _shaft("beam", 2000)
    K = big.free_block(big.K)
    with sd.preferred_solver("superlu"):
        assert sd.factorize(K).solver == "SuperLU"
    monkeypatch.setenv(sd.ENV, "superlu")
    assert sd.factorize(K).solver == "SuperLU"
    assert sd.factorize(K, solver="superlu").solver == "SuperLU"


def test_a_singular_banded_matrix_is_reported_as_singular():
    n = 1200
    K = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1]).tolil()
    K[n // 2, n // 2 - 1:n // 2 + 2] = 0.0                                   # an exactly zero row
    K = K.tocsr()
    K.eliminate_zeros()
    with pytest.raises(sd.SingularMatrixError, match="banded LU"):
        sd.factorize(K)


def test_positive_definite_agrees_with_the_sylvester_count():
    n = 1500
    T = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1], format="csr")
    lam = 2 - 2 * np.cos(np.pi * np.arange(1, n + 1) / (n + 1))             # its eigenvalues, exactly
    for shift, negative in [(-1e-3, 0), (0.5 * (lam[2] + lam[3]), 3)]:
        A = (T - shift * sp.identity(n)).tocsr()
        assert positive_definite(A) is (negative == 0)
        assert _negative_count(A, library=False) == negative                # with the banded shortcut
    assert positive_definite((T - sp.identity(n)).tocsr()) is False           # half the spectrum below
    perm = np.random.default_rng(4).permutation(n)                           # a band hidden by the order
    assert positive_definite(T[perm][:, perm]) is True                       # (reverse Cuthill-McKee)
    wide = (sp.random(n, n, density=0.01, random_state=5) + sp.identity(n)).tocsr()
    assert positive_definite(wide + wide.T) is None


@pytest.mark.parametrize("kind", ["shaft", "beam"])
def test_modal_analysis_with_the_banded_lu_agrees_with_superlu_and_dense(kind):
    system = _shaft(kind, 2000)
    fast = modal_analysis(system, 10, dense_max=0)
    with sd.preferred_solver("superlu"):
        ref = modal_analysis(system, 10, dense_max=0)
    assert fast.linear_solver.startswith("LAPACK banded LU") and ref.linear_solver == "SuperLU LU"
    if kind == "shaft":
        # torsion P2, 1000 elements: any backward-stable solve errs by about eps lam_max / lam_1,
        # lam_max / lam_1 ~ 1e6 here (2e-10; the two differ by 1.0e-10 on mode 1, measured)
        np.testing.assert_allclose(fast.eigenvalues, ref.eigenvalues, rtol=1e-9)
        K, M = system.free_block(system.K).toarray(), system.free_block(system.M).toarray()
        dense = sla.eigh(K, M, eigvals_only=True, subset_by_index=[0, 9])
        np.testing.assert_allclose(fast.eigenvalues, dense, rtol=1e-9)
    else:
        # The 1000-element Hermite cantilever's condition grows like N^4: its first eigenvalue is
        # known only to ~1e-6 by any backward-stable solver (closed form (1.8751)^4 EI / (rho A L^4):
        # SuperLU errs by 9e-8 here, the banded LU by 1.2e-6; at 1400 elements 2.8e-6 and 2.6e-6;
        # at 4000 7.3e-5 and 6.6e-5 -- measured), and both flag it by their Rayleigh-quotient check
        d, L = 0.05, 1.5
        EI, rhoA = 2.1e11 * np.pi * d**4 / 64, 7850.0 * np.pi * d**2 / 4
        exact = np.array([1.8751040687119611, 4.694091132974175, 7.854757438237613])**4 * EI / (rhoA * L**4)
        for res in (fast, ref):
            np.testing.assert_allclose(res.eigenvalues[:3], exact, rtol=5e-6)
        np.testing.assert_allclose(fast.eigenvalues[1:], ref.eigenvalues[1:], rtol=1e-7)


def test_stiffness_check_still_refuses_a_negative_spring_at_large_size():
    system = _shaft("shaft", 2000)
    K = system.K.tolil()
    i = int(system.free[-1])
    K[i, i] = K[i, i] - 1e12                                                 # a grounded negative spring
    bad = replace(system, K=K.tocsr())
    with pytest.raises(ModelError, match="eigenvalue of"):
        modal_analysis(bad, 4, dense_max=0)


def test_one_ordering_per_pattern_and_fat_rows_rejected_before_ordering(monkeypatch):
    from discrete.linalg import banded

    system = _shaft("shaft", 2000)                       # P2: natural band 1001, reverse Cuthill-McKee 2
    K, M = system.free_block(system.K), system.free_block(system.M)
    built = []
    real = banded.BandedLU.__init__
    monkeypatch.setattr(banded.BandedLU, "__init__", lambda self, P: (built.append(1), real(self, P))[1])
    monkeypatch.setattr(banded, "_LAYOUTS", [])
    lay = banded.narrow_layout(banded._canonical(K), 32)
    assert lay is not None and lay.bandwidth == 2
    assert banded.narrow_layout(banded._canonical((K + 1e-9 * M).tocsr()), 32) is lay     # same pattern
    modal_analysis(system, 4, dense_max=0)               # mass check, stiffness check, factorisation
    assert len(built) == 1
    fat = sp.random(1200, 1200, density=0.06, random_state=6, format="csr") + sp.identity(1200, format="csr")
    assert int(np.diff(fat.indptr).max()) > 65
    assert banded.narrow_layout(banded._canonical(fat), 32) is None and len(built) == 1
