"""Transfer-matrix method and regular-structure closed forms (discrete.transfer)."""
import numpy as np
import pytest

from discrete.errors import ModelError
from discrete.transfer import (Branch, Chain, Inertia, Load, Ratio, RegularDrive, Shaft, Spring, boundary_residual,
                               connection, count_below, element_matrix, forced_response, mechanism_branch,
                               naive_product, natural_frequencies, pass_band, propagate, rigid_ratios)

SET_R = dict(n=6, c0=6.0e4, J0=0.02 / 6, m=10.0 / 6, c=10.0 / 6 * 300.0**2, ratio=0.05)


def dense_roots(n, c0, J0, m, c, ratio, boundary="clamped-free"):
    """Eigenvalues of the full 2n-DOF chain written out by hand."""
    K = np.zeros((2 * n, 2 * n))
    M = np.diag([J0] * n + [m] * n)
    for j in range(n - 1):
        K[j:j + 2, j:j + 2] += c0 * np.array([[1, -1], [-1, 1]])
    if boundary.startswith("clamped"):
        K[0, 0] += c0
    if boundary.endswith("clamped"):
        K[n - 1, n - 1] += c0
    for j in range(n):
        idx = [j, n + j]
        K[np.ix_(idx, idx)] += c * np.array([[ratio**2, -ratio], [-ratio, 1]])
    import scipy.linalg as sla
    lam = sla.eigh(K, M, eigvals_only=True)
    return np.sqrt(np.clip(lam, 0, None))


@pytest.mark.parametrize("boundary", ["clamped-free", "clamped-clamped", "free-free", "free-clamped"])
def test_closed_form_and_tm_roots_equal_dense(boundary):
    reg = RegularDrive(boundary=boundary, **SET_R)
    ref = dense_roots(boundary=boundary, **SET_R)
    cf = reg.natural_frequencies()
    tm = natural_frequencies(reg.chain(), 12)
    scale = ref.max()
    s = slice(1, None) if boundary == "free-free" else slice(None)   # dense rigid root ~ sqrt(eps) noise
    assert np.max(np.abs(cf[s] - ref[s])) / scale < 1e-12
    assert np.max(np.abs(tm.omega_rad_s[s] - ref[s])) / scale < 1e-12
    if boundary == "free-free":
        assert tm.rigid[0] and tm.omega_rad_s[0] == 0.0 and cf[0] == 0.0


def test_count_crosses_pole_exactly_at_k():
    """A bisection midpoint exactly at the pole p = k must not corrupt the count."""
    reg = RegularDrive(**SET_R)
    ch = reg.chain()
    assert count_below(ch, [300.0])[0] == 6
    assert list(count_below(ch, [299.999, 300.0, 300.001, 449.9])) == [6, 6, 6, 6]


def test_boundary_residual_is_pole_free_and_vanishes_at_roots():
    reg = RegularDrive(**SET_R)
    ch = reg.chain()
    p = np.linspace(250, 500, 20001)
    f = boundary_residual(ch, p)
    assert np.all(np.abs(f) <= 1 + 1e-12)
    # sign changes of f are exactly the roots in the range (6 lower roots, none in the stop band)
    changes = np.count_nonzero(np.sign(f[:-1]) != np.sign(f[1:]))
    assert changes == 6
    roots = reg.natural_frequencies()
    assert np.all(np.abs(boundary_residual(ch, roots[:6])) < 1e-4)


def test_long_chain_no_overflow_and_roots():
    n = 600
    reg = RegularDrive(**dict(SET_R, n=n))
    ch = reg.chain()
    from scipy.optimize import brentq
    p15 = brentq(lambda q: reg.xi(q) - 15.0, 300.0 * (1 + 1e-9), 449.0)      # |xi| = 15, |eta| ~ 30
    v, log10 = propagate(ch, p15, (0.0, 1.0))
    assert np.all(np.isfinite(v)) and log10 > 800      # the literal product would be ~10^log10
    G = naive_product(ch, p15)
    assert not np.all(np.isfinite(G)) or np.nanmax(np.abs(G)) > 1e250
    roots = natural_frequencies(ch, 5, p_guess=100.0)
    assert np.allclose(roots.omega_rad_s, reg.natural_frequencies()[:5], rtol=1e-11, atol=0)
    f = boundary_residual(ch, roots.omega_rad_s)
    assert np.all(np.isfinite(f))


def test_scan_without_root_is_an_error():
    ch = RegularDrive(**SET_R).chain()
    with pytest.raises(ModelError, match="brackets at least one"):
        natural_frequencies(ch, p_range=(310.0, 440.0))        # inside the stop band
    got = natural_frequencies(ch, p_range=(1000.0, 3100.0)).omega_rad_s
    assert np.allclose(got, [1080.7345088, 3027.7431355], rtol=1e-9)


def test_too_many_modes_for_a_lumped_chain():
    ch = Chain([Spring(1.0), Inertia(1.0)], "clamped", "free")
    with pytest.raises(ModelError, match="at most 1"):
        natural_frequencies(ch, 2)


def test_regular_bad_input():
    with pytest.raises(ModelError, match="n"):
        RegularDrive(**dict(SET_R, n=0))
    with pytest.raises(ModelError, match="ratio"):
        RegularDrive(**dict(SET_R, ratio=0.0))
    with pytest.raises(ModelError, match="boundary"):
        RegularDrive(boundary="pinned-free", **SET_R)
    with pytest.raises(ModelError, match="identical"):
        RegularDrive.from_mechanisms(6e4, 1e-3, [1.0, 1.0, 1.1], 1e5, 0.05)
    ok = RegularDrive.from_mechanisms(6e4, 1e-3, [1.0, 1.0, 1.0], 1e5, 0.05)
    assert ok.n == 3
    with pytest.raises(ModelError, match="ratio"):
        Ratio(0.0)
    with pytest.raises(ModelError, match="elastic member"):
        Branch((Ratio(0.1), Inertia(1.0)))
    with pytest.raises(ModelError, match="name"):
        connection("c-c", 1.0, 1.0, 1.0, 1.0)


def test_rigid_tables_and_pass_band():
    assert np.allclose(rigid_ratios(6, "clamped-free"), [0.24107, 0.70921, 1.13613, 1.49702, 1.77091, 1.94188], atol=5e-6)
    lo, hi = pass_band(6, "clamped-clamped")
    assert np.isclose(lo, 2 * np.sin(np.pi / 14)) and hi == 2.0


def test_forced_tm_equals_closed_form_and_direct_at_long_n():
    """Corrected forced closed form, n = 300, both cases, against the TM line sweep."""
    for boundary in ("clamped-free", "clamped-clamped"):
        reg = RegularDrive(n=300, c0=1e4, J0=0.01, m=2.0, c=5e5, ratio=0.05, boundary=boundary)
        ch = reg.chain(load=1.0)
        discs = [i for i, e in enumerate(ch.elements) if isinstance(e, Inertia)]
        for w in (60.0, 470.0, 1200.0):
            a = forced_response(ch, [w]).a[0, discs].real
            cf = reg.forced_amplitudes(w)
            assert np.max(np.abs(a - cf)) <= 1e-8 * np.max(np.abs(cf))


def test_forced_damped_tm_equals_dense_complex_solve():
    n, c0, J0, m, c, P, d = 5, 1e4, 0.01, 2.0, 5e5, 0.05, 0.03
    reg = RegularDrive(n=n, c0=c0, J0=J0, m=m, c=c, ratio=P)
    br = mechanism_branch(m, c, P, load=1.0, delta=d)
    els = []
    for _ in range(n):
        els += [Spring(c0, d), Inertia(J0), br]
    ch = Chain(els, "clamped", "free")
    w = 420.0
    r = forced_response(ch, [w])
    cc, cm = c0 * (1 + 2j * d), c * (1 + 2j * d)
    K = np.zeros((2 * n, 2 * n), complex)
    for j in range(n):
        K[j, j] += cc
        if j + 1 < n:
            K[j:j + 2, j:j + 2] += cc * np.array([[0, -1], [-1, 1]]) + np.diag([cc, 0]) * 0
        K[np.ix_([j, n + j], [j, n + j])] += cm * np.array([[P * P, -P], [-P, 1]])
    # rebuild the chain stiffness cleanly
    K[:n, :n] = 0
    for j in range(n):
        K[j, j] += cc + (cc if j + 1 < n else 0)
        if j + 1 < n:
            K[j, j + 1] -= cc
            K[j + 1, j] -= cc
    for j in range(n):
        K[j, j] += cm * P * P
    M = np.diag([J0] * n + [m] * n)
    F = np.r_[np.zeros(n), np.ones(n)]
    x = np.linalg.solve(K - w**2 * M, F)
    discs = [i for i, e in enumerate(ch.elements) if isinstance(e, Inertia)]
    assert np.allclose(r.a[0, discs], x[:n], rtol=1e-11, atol=0)
    ends = [r.branch_a[i] for i in sorted(r.branch_a)]
    assert np.allclose(np.ravel(ends), x[n:], rtol=1e-11, atol=0)
    assert reg.n == n


def test_shaft_member_matches_fine_lumped_limit():
    """An exact continuous segment: clamped-free frequencies (2r-1) pi/2 sqrt(GI/(rho L^2))."""
    L, GI, rho = 1.3, 2e4, 0.02
    ch = Chain([Shaft(L / 3, GI, rho), Shaft(L / 3, GI, rho), Shaft(L / 3, GI, rho)], "clamped", "free")
    got = natural_frequencies(ch, 4).omega_rad_s
    exact = (2 * np.arange(1, 5) - 1) * np.pi / 2 * np.sqrt(GI / rho) / L
    assert np.allclose(got, exact, rtol=1e-12)


def test_element_determinants_and_load_sign():
    for e in (Spring(3.0), Inertia(2.0), Ratio(0.3), Shaft(0.5, 1e3, 0.1), mechanism_branch(1.0, 100.0, 0.2)):
        assert np.isclose(np.linalg.det(element_matrix(e, 7.0)), 1.0, rtol=1e-12)
    ch = Chain([Spring(10.0), Inertia(0.0), Load(2.0)], "clamped", "free")
    a = forced_response(ch, [1e-6]).a[0, -1]
    assert np.isclose(a.real, 0.2, rtol=1e-9)          # static: a = M/c, positive torque -> positive angle


@pytest.mark.parametrize("boundary", ["clamped-free", "clamped-clamped"])
def test_tm_mode_shapes_equal_fe_shapes(boundary):
    """Shape coefficients (§10.2) by back-substitution at a root = FE mode shapes (discs and outputs)."""
    from discrete.transfer import mode_shape
    from fem.drives import DriveModel, LumpedShaft, Mechanism
    from fem.drives.discrete import build_discrete
    from discrete.linear.modal import modal_analysis

    reg = RegularDrive(boundary=boundary, **SET_R)
    ch = reg.chain()
    roots = natural_frequencies(ch, 12).omega_rad_s
    model = DriveModel(n=6, shaft=LumpedShaft(SET_R["c0"], SET_R["J0"]),
                       mechanism=Mechanism(SET_R["m"], SET_R["c"], SET_R["ratio"]), boundary=boundary)
    dd = build_discrete(model)
    fe = modal_analysis(dd.system, 12)
    discs = [i for i, e in enumerate(ch.elements) if isinstance(e, Inertia)]
    for r in (0, 3, 6, 11):
        sh = mode_shape(ch, roots[r])
        tm_vec = np.r_[sh.a[0, discs], [sh.branch_a[i][0] for i in sorted(sh.branch_a)]]
        fe_vec = np.r_[fe.shapes[dd.theta, r], fe.shapes[dd.y, r]]
        tm_vec, fe_vec = tm_vec / np.linalg.norm(tm_vec), fe_vec / np.linalg.norm(fe_vec)
        assert min(np.linalg.norm(tm_vec - fe_vec), np.linalg.norm(tm_vec + fe_vec)) < 1e-7


def test_parallel_member_bad_input_and_spring_sum():
    from discrete.transfer import Parallel

    with pytest.raises(ModelError, match="at least two"):
        Parallel(((Spring(1.0),),))
    with pytest.raises(ModelError, match="elastic member"):
        Parallel(((Spring(1.0),), (Inertia(1.0), Spring(2.0))))
    # two springs in parallel = one spring of the summed stiffness (10.9), in a chain
    a = Chain([Parallel(((Spring(1e3),), (Spring(2e3),))), Inertia(3.0)], "clamped", "free")
    b = Chain([Spring(3e3), Inertia(3.0)], "clamped", "free")
    assert np.isclose(natural_frequencies(a, 1).omega_rad_s[0], natural_frequencies(b, 1).omega_rad_s[0], rtol=1e-13)
