"""Multi-shift factorisations with leaf condensation (discrete.linalg.shifted), the certified seeded
eigen-solver (discrete.linalg.seeded) and its use for large drives (fem.drives.analysis.fe_modes).

References: scipy's sparse direct solve, dense symmetric eigenvalue counts and eigh, the
regular-structure closed form (10.36)/(10.16) and the transfer-matrix roots."""
from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from discrete.errors import ModelError, SolverError
from discrete.transfer import natural_frequencies
from fem.drives import DistributedShaft, DriveModel, LumpedShaft, Mechanism
from fem.drives.analysis import fe_modes, regular_of
from fem.drives.discrete import build_discrete
from fem.drives.tm import build_chain
from discrete.linear.modal import modal_analysis
from discrete.linalg.seeded import seeded_eigenpairs
from discrete.linalg.shifted import ShiftedSolver


def set_c(n: int, boundary: str = "clamped-free", c: float | None = None) -> DriveModel:
    """Set C of the digest discretised with n mechanisms (lumped shaft)."""
    base = DriveModel(n=6, shaft=LumpedShaft(c0=6.0e4, J0=0.02 / 6),
                      mechanism=Mechanism(m=10 / 6, c=10 / 6 * 300.0**2 if c is None else c, ratio=0.05),
                      continuum_length=2.0 / 6, boundary=boundary)
    return base.with_n(n)


def distributed(n: int) -> DriveModel:
    return DriveModel(n=n, shaft=DistributedShaft(length=2.0, GI=2.0e4, rho=0.01, elements=2, order=2),
                      mechanism=Mechanism(m=10 / n, c=10 / n * 300.0**2, ratio=0.05))


def matrices(system):
    return system.free_block(system.K), system.free_block(system.M)


def dense_eigenvalues(K, M):
    return sla.eigh(K.toarray(), M.toarray(), eigvals_only=True)


def odd_structure():
    """A banded core that needs reordering (b > 1), two leaves on one core DOF (shared
    scatter), a grounded leaf (no coupling) and a consistent-mass pair that stays core."""
    rng = np.random.default_rng(3)
    nc = 40
    order = rng.permutation(nc)                  # a chain in scrambled numbering
    K = sp.lil_matrix((nc + 5, nc + 5))
    M = sp.lil_matrix((nc + 5, nc + 5))
    for a, b in zip(order[:-1], order[1:]):
        k = rng.uniform(1, 3)
        K[a, a] += k; K[b, b] += k; K[a, b] -= k; K[b, a] -= k
        M[a, b] += 0.05; M[b, a] += 0.05
    for i in range(nc):
        K[i, i] += 0.1
        M[i, i] += rng.uniform(0.5, 1.5)
    for leaf, host in ((nc, 5), (nc + 1, 5), (nc + 2, 17)):
        c = rng.uniform(0.5, 2)
        K[leaf, leaf] += c; K[host, host] += c; K[leaf, host] -= c; K[host, leaf] -= c
        M[leaf, leaf] = rng.uniform(0.2, 1)
    K[nc + 3, nc + 3] = 2.0                      # grounded mass
    M[nc + 3, nc + 3] = 1.0
    K[nc + 4, nc + 4] = 1.0                      # a DOF hanging on the grounded one by M only
    M[nc + 4, nc + 4] = 1.0
    return K.tocsr(), M.tocsr()


CASES = {
    "lumped drive": lambda: matrices(build_discrete(set_c(60)).system),
    "distributed drive": lambda: matrices(build_discrete(distributed(30)).system),
    "clamped-clamped drive": lambda: matrices(build_discrete(set_c(40, "clamped-clamped")).system),
    "odd structure": odd_structure,
}


@pytest.mark.parametrize("case", CASES)
def test_shifted_solves_match_sparse_direct_solve(case):
    K, M = CASES[case]()
    solver = ShiftedSolver(K, M)
    lam = dense_eigenvalues(K, M)
    shifts = np.array([0.0, 0.5 * lam[0], 0.5 * (lam[3] + lam[4]), 1.7 * lam[-1]])
    B = np.random.default_rng(0).standard_normal((shifts.size, K.shape[0]))
    X = solver.factor(shifts).solve(B)
    for j, s in enumerate(shifts):
        ref = spla.spsolve(sp.csc_matrix(K - s * M), B[j])
        assert np.linalg.norm(X[j] - ref) <= 1e-8 * np.linalg.norm(ref)
    one = solver.factor(shifts[2:3]).solve(B)          # one shift, all rows
    ref = spla.spsolve(sp.csc_matrix(K - shifts[2] * M), B.T).T
    assert np.allclose(one, ref, rtol=0, atol=1e-8 * np.abs(ref).max())


def test_structure_detection():
    K, M = matrices(build_discrete(set_c(60)).system)
    s = ShiftedSolver(K, M)
    assert (s.leaves, s.bandwidth) == (60, 1)         # one mechanism leaf per disc, tridiagonal shaft
    s = ShiftedSolver(*odd_structure())
    assert s.leaves == 5 and s.bandwidth <= 3          # 3 attached + grounded + M-free one; RCM restored the band


@pytest.mark.parametrize("case", CASES)
def test_inertia_counts_eigenvalues_below_the_shift(case):
    K, M = CASES[case]()
    solver = ShiftedSolver(K, M)
    lam = dense_eigenvalues(K, M)
    for s in (0.5 * lam[0], 0.5 * (lam[0] + lam[1]), 0.5 * (lam[6] + lam[7]), 0.5 * (lam[-2] + lam[-1]), 2 * lam[-1]):
        assert solver.inertia(s) == int(np.count_nonzero(lam < s))


@pytest.mark.parametrize("case", CASES)
def test_seeded_pairs_from_rough_seeds_equal_dense(case):
    """Seeds off by 30 % of the distance to the nearest other eigenvalue (the crowded drive
    spectra allow no more), no start vectors."""
    K, M = CASES[case]()
    lam = dense_eigenvalues(K, M)
    k = 6
    gap = np.minimum(np.diff(lam[:k + 2])[:k + 1], np.diff(np.r_[0.0, lam[:k + 1]]))
    seeds = lam[:k + 1] + 0.3 * gap * np.cos(np.arange(k + 1))
    sol = seeded_eigenpairs(K, M, seeds, k)
    assert np.allclose(sol.eigenvalues, lam[:k], rtol=1e-10, atol=0)
    assert sol.count == k and sol.contamination.max() < 1e-6
    V = sol.vectors
    assert np.allclose(V.T @ (M @ V), np.eye(k), atol=1e-6)       # M-orthonormal to the contamination level
    resid = np.linalg.norm(K @ V - (M @ V) * sol.eigenvalues, axis=0) / np.linalg.norm(K @ V, axis=0)
    assert resid.max() < 1e-6


def test_bad_seeds_never_give_a_wrong_answer():
    """Seeds that skip the lowest modes either converge to the right pairs or raise; the
    Sylvester count decides (a wrong set would have more eigenvalues below the midpoint)."""
    K, M = CASES["lumped drive"]()
    lam = dense_eigenvalues(K, M)
    seeds = lam[3:10]                            # estimates of modes 4..10 for "the lowest 6"
    try:
        sol = seeded_eigenpairs(K, M, seeds, 6)
    except SolverError as exc:
        assert "Sylvester count" in str(exc) or "converge" in str(exc)
    else:
        assert np.allclose(sol.eigenvalues, lam[:6], rtol=1e-10)
    system = build_discrete(set_c(60)).system
    res = modal_analysis(system, 6, seeds=seeds)
    assert np.allclose(res.eigenvalues, lam[:6], rtol=1e-9)
    if "seeded" not in res.method:
        assert any("seeded solver not used" in w for w in res.warnings)


def test_seed_input_errors_name_the_argument():
    K, M = CASES["lumped drive"]()
    with pytest.raises(ModelError, match="seeds"):
        seeded_eigenpairs(K, M, [1.0, 2.0], 6)                # fewer than n_modes + 1
    with pytest.raises(ModelError, match="seeds"):
        seeded_eigenpairs(K, M, [-1.0] + [1.0] * 6, 6)        # non-positive
    with pytest.raises(ModelError, match="start"):
        seeded_eigenpairs(K, M, np.arange(1.0, 8.0), 6, start=np.ones((7, 3)))


def test_large_drive_uses_the_certified_seeded_path_and_matches_the_closed_form():
    """Set C with n = 1000 (the benchmark): 19 of the lowest 20 roots crowd within 0.6 %
    below k.  The seeded FE path equals the closed form to rounding."""
    model = set_c(1000)
    res = fe_modes(model, build_discrete(model).system, 20)
    assert res.method.startswith("seeded") and "Sylvester count 20" in res.method
    exact = regular_of(model).natural_frequencies()[:20]
    assert np.max(np.abs(res.omega_rad_s / exact - 1)) < 1e-12
    assert res.residuals.max() < 1e-12 and not res.warnings


@pytest.mark.parametrize("boundary, n, k", [("clamped-clamped", 400, 12), ("free-clamped", 400, 12),
                                            ("clamped-free", 300, 20), ("free-clamped", 300, 40)])
def test_seeded_path_for_other_boundary_cases(boundary, n, k):
    """Also requests whose vectors reach the rounding floor of the change measure (n = 300)."""
    model = set_c(n, boundary)
    res = fe_modes(model, build_discrete(model).system, k)
    assert res.method.startswith("seeded")
    exact = regular_of(model).natural_frequencies()[:k]
    assert np.max(np.abs(res.omega_rad_s / exact - 1)) < 1e-12 and not res.warnings


def test_too_many_modes_for_the_estimates_use_lanczos():
    """r/n above 1/6: the estimates no longer separate the crowd; plain Lanczos, no warning."""
    model = set_c(300)
    res = fe_modes(model, build_discrete(model).system, 60)
    assert res.method.startswith("sparse shift-invert") and not res.warnings
    exact = regular_of(model).natural_frequencies()[:60]
    assert np.max(np.abs(res.omega_rad_s / exact - 1)) < 1e-11


def test_seeded_path_for_a_distributed_shaft_matches_lanczos_and_transfer_matrices():
    model = distributed(150)                              # P2 shaft (banded core), 150 mechanism leaves
    system = build_discrete(model).system
    res = fe_modes(model, system, 10)
    assert res.method.startswith("seeded")
    lanczos = modal_analysis(system, 10)
    assert np.max(np.abs(res.omega_rad_s / lanczos.omega_rad_s - 1)) < 1e-11
    tm = natural_frequencies(build_chain(model)[0], 10, p_guess=150.0).omega_rad_s   # exact shaft: FE error only
    assert np.max(np.abs(res.omega_rad_s / tm - 1)) < 1e-5


def test_rigid_mechanisms_seeded():
    model = set_c(500, c=np.inf)
    res = fe_modes(model, build_discrete(model).system, 8)
    assert res.method.startswith("seeded")
    exact = regular_of(model).natural_frequencies()[:8]
    assert np.max(np.abs(res.omega_rad_s / exact - 1)) < 1e-12


# ---- regressions from the review of the seeded solver
def _chain(n, rng, ground=0.5):
    K = np.zeros((n, n))
    for i in range(n - 1):
        k = rng.uniform(1, 2)
        K[i, i] += k; K[i + 1, i + 1] += k; K[i, i + 1] -= k; K[i + 1, i] -= k
    K[0, 0] += ground
    return K, np.diag(rng.uniform(0.5, 1.5, n))


def _system(K, M):
    from discrete.linear_system import LinearSystem
    return LinearSystem(M=sp.csr_matrix(M), K=sp.csr_matrix(K), dof_field=np.array(["x"] * K.shape[0]))


def test_two_seeds_on_one_mode_are_refused_or_resolved_never_returned():
    """Seeds [l1, l1, l3, l4] for the lowest 3: a duplicated mode plus a missed one would pass a
    Sylvester count, so independence is checked first. Whether the Rayleigh-Ritz step and the shifts
    moved to the Ritz values separate the two rows (and find l2) depends on the rounding of the BLAS
    kernels (they do on an AMD EPYC, not on the machines this test was written on): the solver either
    refuses or returns the true lowest 3, never the duplicated mode. modal_analysis gives the true ones."""
    rng = np.random.default_rng(5)
    K, M = _chain(40, rng)
    lam = sla.eigh(K, M, eigvals_only=True)
    seeds = [lam[0] * (1 + 1e-4), lam[0] * (1 + 2e-4), lam[2] * (1 + 1e-4), lam[3] * (1 + 1e-4)]
    try:
        sol = seeded_eigenpairs(sp.csr_matrix(K), sp.csr_matrix(M), seeds, 3)
        refused = False
    except SolverError:
        refused = True
    else:
        assert np.allclose(sol.eigenvalues, lam[:3], rtol=1e-10) and sol.count == 3
    res = modal_analysis(_system(K, M), 3, seeds=seeds)
    assert np.allclose(res.eigenvalues, lam[:3], rtol=1e-10)
    assert any("seeded solver not used" in w for w in res.warnings) == refused


def test_star_with_a_one_dof_core():
    """A hub with 20 absorbers: the condensed core is one DOF (stacked size 2 for one mode)."""
    rng = np.random.default_rng(4)
    n = 21
    K, M = np.zeros((n, n)), np.diag(rng.uniform(0.5, 1.5, n))
    for leaf in range(1, n):
        k = rng.uniform(1, 2)
        K[leaf, leaf] += k + 0.05; K[0, 0] += k; K[0, leaf] -= k; K[leaf, 0] -= k
    lam = sla.eigh(K, M, eigvals_only=True)
    for k in (1, 2):
        res = modal_analysis(_system(K, M), k, seeds=lam[:k + 1] * 1.001)
        assert res.method.startswith("seeded") and np.allclose(res.eigenvalues, lam[:k], rtol=1e-10)


def test_stored_zeros_outside_the_band():
    """A zero-stiffness spring stored between distant DOFs must not widen (or break) the band."""
    rng = np.random.default_rng(4)
    K, M = _chain(30, rng)
    C = sp.coo_matrix(K)
    Kz = sp.coo_matrix((np.r_[C.data, 0.0, 0.0], (np.r_[C.row, 3, 20], np.r_[C.col, 20, 3])), shape=K.shape).tocsr()
    lam = sla.eigh(K, M, eigvals_only=True)
    assert ShiftedSolver(Kz, sp.csr_matrix(M)).bandwidth == 1
    res = modal_analysis(_system(Kz, M), 3, seeds=lam[:4] * 1.001)
    assert res.method.startswith("seeded") and np.allclose(res.eigenvalues, lam[:3], rtol=1e-10)


def test_tolerance_below_the_measurable_change_converges():
    rng = np.random.default_rng(5)
    K, M = _chain(200, rng)
    lam = sla.eigh(K, M, eigvals_only=True)
    sol = seeded_eigenpairs(sp.csr_matrix(K), sp.csr_matrix(M), lam[:7] * (1 + 1e-3), 6, tol=1e-13)
    assert np.allclose(sol.eigenvalues, lam[:6], rtol=1e-12)


def test_zero_start_row_is_bad_input():
    K, M = CASES["lumped drive"]()
    lam = dense_eigenvalues(K, M)
    start = np.ones((7, K.shape[0]))
    start[2] = 0.0
    with pytest.raises(ModelError, match="start"):
        seeded_eigenpairs(K, M, lam[:7], 6, start=start)


def test_stiffness_check_on_the_seeded_path_uses_the_solvers_count():
    """With seeds, the stiffness check counts through the ShiftedSolver that the seeded solver then
    uses (a Sturm count for a chain): a negative spring is still refused, naming the count, and
    the certified result is unchanged."""
    rng = np.random.default_rng(8)
    K, M = _chain(120, rng)
    lam = sla.eigh(K, M, eigvals_only=True)
    res = modal_analysis(_system(K, M), 5, seeds=lam[:6] * 1.001)
    assert res.method.startswith("seeded") and np.allclose(res.eigenvalues, lam[:5], rtol=1e-10)
    Kneg = K.copy()
    Kneg[60, 60] -= 40.0                       # a grounded spring of -40: one negative eigenvalue
    assert np.sum(sla.eigh(Kneg, M, eigvals_only=True) < 0) == 1
    with pytest.raises(ModelError, match=r"1 eigenvalue\(s\) below the round-off bound, Sylvester count"):
        modal_analysis(_system(Kneg, M), 5, seeds=np.abs(lam[:6]) * 1.001)
