"""The linear solvers check their own assumptions (issue 16, items 2 and 3).

Every probe ends in a clear error (ModelError/SolverError naming the key, its value and what is
allowed or what to do), a flagged result, or a correct result checked against a closed form:
never a raw exception, never a silently wrong number."""
from __future__ import annotations

import math
import time

import numpy as np
import pytest
import scipy.sparse as sp

import fem
from discrete.errors import ModelError, SolverError
from discrete.linear import Damping, frf, harmonic_response, modal_analysis, reduce, static_deflection
from discrete.linear_system import LinearSystem
from fem import Material, Section, Segment, ShaftModel, Support
from fem.assembly import hermite_max_ratio


def system(M, K, **kw) -> LinearSystem:
    M, K = np.asarray(M, float), np.asarray(K, float)
    return LinearSystem(M=sp.csr_matrix(M), K=sp.csr_matrix(K), dof_field=["x"] * len(M), **kw)


def chain(n: int, k: float = 1.0) -> np.ndarray:
    """Fixed-free spring chain: ground - 1 - 2 - ... - n."""
    K = np.diag(np.full(n, 2 * k)) - np.diag(np.full(n - 1, k), 1) - np.diag(np.full(n - 1, k), -1)
    K[-1, -1] = k
    return K


def cantilever(elements: int, length: float = 1.0) -> ShaftModel:
    return ShaftModel(physics="bending", segments=[Segment(length=length, elements=elements,
                                                           section=Section.circle(0.05),
                                                           material=Material.with_nu(211e9, 0.3, 7810))],
                      supports=[Support(x=0.0, type="clamped")])


def two_dof_eigenvalues(M, K) -> np.ndarray:
    """Roots of det(K - lam M) = 0 for diagonal M (closed form, no cancellation):
    a lam^2 - b lam + c = 0 with a = m1 m2, b = k11 m2 + k22 m1, c = k11 k22 - k12^2;
    b^2 - 4ac = (k11 m2 - k22 m1)^2 + 4 m1 m2 k12^2; the large root from the formula with the
    sum, the small one as c / (a lam_big)."""
    (m1, m2), ((k11, k12), (_, k22)) = np.diag(M), K
    a, b, c = m1 * m2, k11 * m2 + k22 * m1, k11 * k22 - k12**2
    big = (b + math.sqrt((k11 * m2 - k22 * m1) ** 2 + 4 * m1 * m2 * k12**2)) / (2 * a)
    return np.array([c / (a * big), big])


# ------------------------------------------------------------ definiteness of K and M
def test_negative_stiffness_is_an_error_naming_the_eigenvalue():
    """E < 0 as the solver sees it: K of a valid cantilever negated (the constructor check of
    Material is another line of defence).  Was: lam = -1.2e7 reported as a reliable omega = 0."""
    fe = fem.assemble(cantilever(20))
    s = fe.system
    neg = LinearSystem(M=s.M, K=-s.K, dof_field=s.dof_field, dof_x=s.dof_x, constrained=s.constrained)
    with pytest.raises(ModelError, match=r"eigenvalue of \(K, M\).*-[0-9.e+]+ rad\^2/s\^2.*positive semi-definite"
                                         r".*negative Young"):
        modal_analysis(neg, 3)


def test_indefinite_stiffness_small_dense():
    """lam = -2.449 was a reliable 0 Hz mode."""
    with pytest.raises(ModelError, match=r"-2\.449 rad\^2/s\^2"):
        modal_analysis(system(np.eye(3), np.diag([-2.449, 1.0, 3.0])), 2)


def test_indefinite_stiffness_sparse_path_that_shift_invert_would_miss():
    """One negative eigenvalue far from 0: shift-invert at sigma = 0 returns the eigenvalues nearest
    0 and never sees it; the Sylvester count of K + zero_level M does."""
    n = 40
    K = chain(n)
    K[10, 10] = -10.0
    with pytest.raises(ModelError, match=r"1 eigenvalue\(s\) below the round-off bound"):
        modal_analysis(system(np.eye(n), K), 3)


@pytest.mark.parametrize("M", [-np.eye(3), np.diag([1.0, -1.0, 1.0])])
def test_negative_mass_diagonal(M):
    with pytest.raises(ModelError, match=r"mass matrix M\[\d, \d\].*= -1\.0.*positive semi-definite"):
        modal_analysis(system(M, chain(3)), 2)


def test_indefinite_consistent_mass():
    """Positive diagonal, negative eigenvalue (off-diagonal entries too large): Sylvester count of M."""
    n = 30
    M = np.eye(n) + 0.9 * (np.eye(n, k=1) + np.eye(n, k=-1))          # eigenvalues 1 + 1.8 cos(...) < 0 for some
    assert np.linalg.eigvalsh(M)[0] < -0.5
    with pytest.raises(ModelError, match=r"mass matrix M = '\d+ negative eigenvalue"):
        modal_analysis(system(M, chain(n)), 3)


def test_nan_in_mass_refused_at_construction_and_in_the_solver():
    M = np.eye(2)
    M[1, 1] = np.nan
    with pytest.raises(ModelError, match="M = 'inf/NaN entries'"):
        system(M, chain(2))
    s = system(np.eye(2), chain(2))
    s.M = sp.csr_matrix(M)                              # replaced after construction
    with pytest.raises(ModelError, match="M = 'inf/NaN entries'"):
        modal_analysis(s, 1)


def test_rigid_modes_only_within_the_round_off_bound():
    """A free-free chain: one rigid mode at omega = 0 (|lam| at round-off), the others flexible and
    equal to the closed form 4 sin^2(k pi / 2n) (unit masses and springs)."""
    n = 30
    K = chain(n)
    K[0, 0] = 1.0                                       # free-free
    res = modal_analysis(system(np.eye(n), K), 3)
    assert res.rigid.tolist() == [True, False, False] and res.reliable.all()
    assert abs(res.eigenvalues[0]) <= 1e3 * np.finfo(float).eps * 4
    k = np.arange(1, 3)
    np.testing.assert_allclose(res.eigenvalues[1:], 4 * np.sin(k * np.pi / (2 * n)) ** 2, rtol=1e-10)


# ------------------------------------------------------------ entry points
def test_unassembled_model_says_what_to_call():
    model = cantilever(10)
    for call in (lambda: modal_analysis(model, 2), lambda: harmonic_response(model, [1.0]),
                 lambda: static_deflection(model, np.zeros(3)), lambda: frf(model, [1.0], drive=0, response=0),
                 lambda: reduce(model, [0], 1)):
        with pytest.raises(ModelError, match=r"ShaftModel.*fem\.assemble\(model\)"):
            call()
    with pytest.raises(ModelError, match="LinearSystem or an assembled FEModel"):
        modal_analysis("not a model", 2)


def test_assembled_fe_model_is_accepted_as_its_system():
    fe = fem.assemble(cantilever(40, 1.5))
    EI, rhoA = 211e9 * np.pi * 0.05**4 / 64, 7810 * np.pi * 0.05**2 / 4
    w1 = modal_analysis(fe, 1).omega_rad_s[0]
    assert w1 == pytest.approx(1.8751040687**2 / 1.5**2 * np.sqrt(EI / rhoA), rel=1e-7)   # (4.72)


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_non_finite_force(bad):
    s = system(np.eye(3), chain(3))
    F = np.array([1.0, bad, 0.0])
    with pytest.raises(ModelError, match=r"force\[1\].*finite"):
        harmonic_response(s, [0.5], force=F)
    with pytest.raises(ModelError, match=r"force\[1\].*finite"):
        static_deflection(s, F)


def test_complex_force_static_refused_harmonic_accepted():
    s = system(np.eye(2), chain(2))
    F = np.array([0.0, 1.0 + 2.0j])
    with pytest.raises(ModelError, match="static load has no phase"):
        static_deflection(s, F)
    # harmonic: the complex amplitude is kept; static limit omega -> 0: Q = K^-1 F exactly
    Q = harmonic_response(s, [0.0], force=F, damping=Damping("none")).response[0]
    np.testing.assert_allclose(Q, np.linalg.solve(chain(2), F), rtol=1e-14)


def test_force_shape_and_type():
    s = system(np.eye(2), chain(2))
    with pytest.raises(ModelError, match=r"shape \(3,\).*shape \(2,\)"):
        static_deflection(s, np.ones(3))
    with pytest.raises(ModelError, match="force"):
        harmonic_response(s, [1.0], force="abc")


@pytest.mark.parametrize("omegas", [[np.nan], [np.inf], [-1.0], [], [1 + 1j], "fast"])
def test_bad_frequencies(omegas):
    with pytest.raises(ModelError, match="frequencies"):
        harmonic_response(system(np.eye(2), chain(2)), omegas, force=np.array([0.0, 1.0]))


@pytest.mark.parametrize("key,value", [("zeta", np.nan), ("alpha", np.inf), ("psi", -1.0), ("beta", "x")])
def test_bad_damping(key, value):
    with pytest.raises(ModelError, match=key):
        Damping(type="rayleigh", **{key: value})


def test_dof_index_out_of_range_names_the_range():
    s = system(np.eye(3), chain(3))
    with pytest.raises(ModelError, match=r"drive = 7.*from 0 to 2"):
        frf(s, [1.0], drive=7, response=0)
    with pytest.raises(ModelError, match=r"response = -1.*from 0 to 2"):
        frf(s, [1.0], drive=0, response=-1)
    with pytest.raises(ModelError, match=r"outputs = 3.*from 0 to 2"):
        harmonic_response(s, [1.0], force=np.array([1.0, 0, 0]), outputs=[3])
    with pytest.raises(ModelError, match=r"drive = 1.5.*integer"):
        frf(s, [1.0], drive=1.5, response=0)
    with pytest.raises(ModelError, match=r"coupling DOF = 5.*from 0 to 2"):
        reduce(s, [5], 1)
    with pytest.raises(ModelError, match="coupling"):
        reduce(s, [0.7], 1)


def test_bad_shift():
    with pytest.raises(ModelError, match="shift"):
        modal_analysis(system(np.eye(3), chain(3)), 1, shift=np.nan)


# ------------------------------------------------------------ numerical traps
def test_hermite_mesh_beyond_double_precision_refused_before_assembling():
    """100 000 Hermite elements used to end in LinAlgError: Singular matrix inside scikit-fem; now a
    ModelError before any assembly (hence fast), saying how many elements the model can carry."""
    t0 = time.perf_counter()
    with pytest.raises(ModelError, match=r"elements = 100000.*at most about 16514 .*Hermite"):
        fem.assemble(cantilever(100_000, 10.0))
    assert time.perf_counter() - t0 < 0.5
    assert math.floor(hermite_max_ratio()) == 16514          # (1e-3 / eps)^(1/3)


def test_hermite_limit_in_the_message_follows_the_mesh():
    """Two segments: the second is fine-meshed; the message counts elements uniformly spread."""
    mat, sec = Material.with_nu(211e9, 0.3, 7810), Section.circle(0.05)
    model = ShaftModel(physics="bending", segments=[Segment(1.0, 10, sec, mat), Segment(1.0, 40_000, sec, mat)],
                       supports=[Support(x=0.0)])
    with pytest.raises(ModelError, match=r"at most about 16514 "):
        fem.assemble(model)


def test_hermite_mesh_below_the_limit_is_assembled_and_flagged_downstream():
    """5 000 elements: assembled; modal analysis withholds mode 1 (too fine for double precision)."""
    res = modal_analysis(fem.assemble(cantilever(5000, 1.5)), 1)
    assert not res.reliable[0] and any("too fine" in w for w in res.warnings)


def test_mass_ratio_1e12_both_modes_exact():
    """m1 = 1e12 m2: ARPACK cannot return both modes and M is ill-conditioned; the dense fallback
    takes each mode from the pencil that resolves it (the closed form to 1e-12)."""
    M, K = np.diag([1e12, 1.0]), np.array([[2.0, -1.0], [-1.0, 1.0]])
    res = modal_analysis(system(M, K), 2)
    np.testing.assert_allclose(res.eigenvalues, two_dof_eigenvalues(M, K), rtol=1e-12)
    assert res.reliable.all() and not res.rigid.any() and res.method.startswith("dense")
    assert any("dense solver used" in w for w in res.warnings)
    assert modal_analysis(system(M, K), 1).eigenvalues[0] == pytest.approx(two_dof_eigenvalues(M, K)[0], rel=1e-12)
