"""The quadratic eigensolver's pattern-gathered block split and its chain-block shortcuts, against the
scipy.sparse operations they replace: the same block matrices, the same [D, M], the same transpose,
Sylvester counts equal to ShiftedSolver's, and chain-block frequencies equal to a dense solve."""
import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse as sp

from discrete.linalg.shifted import ShiftedSolver
from discrete.linear.complex_modal import (QuadraticEigensolver, _side_by_side, _transpose_positions,
                                           complex_modal_analysis)
from discrete.linear_system import LinearSystem


def _chain(n, k, m):
    K = sp.diags([-k * np.ones(n - 1), 2 * k * np.ones(n), -k * np.ones(n - 1)], [-1, 0, 1]).tolil()
    K[0, 0] = K[n - 1, n - 1] = k                        # free-free: one rigid-body mode
    M = sp.diags([m / 6 * np.ones(n - 1), 4 * m / 6 * np.ones(n), m / 6 * np.ones(n - 1)], [-1, 0, 1]).tolil()
    M[0, 0] = M[n - 1, n - 1] = 2 * m / 6
    return K.tocsr(), M.tocsr()


def _system(rng, constrained=()):
    """A gyroscopic, damped 2-DOF-per-node line (DOFs 0..2p-1) beside an undamped chain (2p..2p+c-1):
    two blocks, K and C on other patterns than M, optional constraints."""
    p, c = 40, 100
    n = 2 * p + c
    A = sp.random(2 * p, 2 * p, density=0.08, random_state=rng) + sp.eye(2 * p)
    K_lat = sp.csr_matrix(A @ A.T * 1e4 + 1e4 * sp.eye(2 * p))
    M_lat = sp.diags(rng.uniform(1, 2, 2 * p))
    G_lat = sp.lil_matrix((2 * p, 2 * p))
    for j in range(p):
        G_lat[2 * j, 2 * j + 1], G_lat[2 * j + 1, 2 * j] = 0.3, -0.3
    C_lat = sp.diags(rng.uniform(0.1, 0.5, 2 * p))
    Kc, Mc = _chain(c, 5e4, 0.7)
    K = sp.block_diag([K_lat, Kc]).tocsr()
    M = sp.block_diag([M_lat, Mc]).tocsr()
    C = sp.block_diag([C_lat, sp.csr_matrix((c, c))]).tocsr()
    G = sp.block_diag([G_lat.tocsr(), sp.csr_matrix((c, c))]).tocsr()
    return LinearSystem(M=M, K=K, C=C, G=G, dof_field=np.full(n, "q", dtype=object),
                        constrained=np.asarray(constrained, dtype=int))


@pytest.mark.parametrize("constrained", [(), (3, 17)])
def test_split_equals_sparse_slicing(constrained):
    rng = np.random.default_rng(7)
    s = _system(rng, constrained)
    q = QuadraticEigensolver(s)
    assert len(q.blocks) == 2
    f = s.free
    for name in "MKCG":
        A = getattr(s, name)
        parts = q._split(A)
        Af = A.tocsr()[f][:, f]
        for b, part in zip(q.blocks, parts):
            assert part.has_canonical_format
            np.testing.assert_array_equal(part.toarray(), Af[b.dofs][:, b.dofs].toarray())
    # a matrix on a known pattern is split from the stored map: same result with other data
    K2 = s.K.copy()
    K2.data = rng.uniform(size=K2.data.size)
    n_maps = len(q._maps)
    for b, part in zip(q.blocks, q._split(K2)):
        np.testing.assert_array_equal(part.toarray(), K2[f][:, f][b.dofs][:, b.dofs].toarray())
    assert len(q._maps) == n_maps


def test_side_by_side_and_transpose_positions():
    rng = np.random.default_rng(3)
    q = QuadraticEigensolver(_system(rng))
    b = q.blocks[0]
    D = sp.csr_matrix(sp.random(80, 80, density=0.1, random_state=rng))
    M = sp.csr_matrix(sp.random(80, 80, density=0.1, random_state=rng))
    for _ in range(2):                                  # the second call reuses the block's map
        np.testing.assert_array_equal(_side_by_side(b, D, M).toarray(), sp.hstack([D, M]).toarray())
    S = sp.csr_matrix(D + D.T)
    S.data = rng.uniform(size=S.data.size)              # symmetric pattern, unsymmetric values
    perm = _transpose_positions(S)
    np.testing.assert_array_equal(sp.csr_matrix((S.data[perm], S.indices, S.indptr), shape=S.shape).toarray(),
                                  S.T.toarray())
    U = sp.csr_matrix(([1.0, 2.0], ([0, 1], [1, 2])), shape=(3, 3))
    assert _transpose_positions(U) is None


@pytest.mark.parametrize("n_modes, path", [(6, "subspace iteration"), (12, "Lanczos")])
def test_chain_block_counts_and_modes(n_modes, path):
    """The chain's Sturm count equals ShiftedSolver's inertia at every shift, and its modes (the
    rigid one included) equal a dense generalized eigensolve, by either symmetric path (both
    factorise the chain by dpttrf)."""
    rng = np.random.default_rng(11)
    s = _system(rng)
    q = QuadraticEigensolver(s)
    chain = q.blocks[1]
    Kc, Mc = q._split(s.K)[1], q._split(s.M)[1]
    w2 = sla.eigh(Kc.toarray(), Mc.toarray(), eigvals_only=True)
    ref = ShiftedSolver(Kc, Mc)
    for bound in (0.5 * np.sqrt(w2[1]), np.sqrt(0.5 * (w2[3] + w2[4])), np.sqrt(w2[-1]) * 2):
        lam = np.array([1j * bound])
        got = q._count_below(chain, Mc, Kc, lam, np.array([False]), 1)
        assert got == ref.inertia(bound * bound * (1 + 1e-8) + 1e-300)
    res = complex_modal_analysis(s, n_modes)
    assert path in res.method
    on_chain = res.block == 1
    w = np.sort(np.where(res.rigid[on_chain], 0.0, res.eigenvalues[on_chain].imag))
    assert w.size >= 2 and res.rigid[on_chain].sum() == 1
    np.testing.assert_allclose(w[1:], np.sqrt(w2[1:w.size]), rtol=1e-11)
    assert np.all(res.residuals < 1e-10)
