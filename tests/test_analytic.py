"""Tests of the independent analytic references in ``validation.analytic``.

Numbers quoted as strings are copied exactly as printed in the digest
(shared/reference/textbook_ch2-5.md, case ids V…); :func:`printed` turns such a string into a
tolerance of half a unit in its last printed digit, which is what the printing guarantees.
Independent cross-checks (eigen-solvers, determinants, limits) use tight tolerances.
"""
from decimal import Decimal

import numpy as np
import pytest
from scipy.linalg import eigh
from scipy.optimize import brentq, minimize_scalar

from validation.analytic import bending, lumped_refs, sdof, timoshenko, torsion


def printed(text: str, units: float = 0.5):
    """``pytest.approx`` for a number printed to its last digit: +- ``units`` of that digit."""
    ulp = 10.0 ** Decimal(text).as_tuple().exponent
    return pytest.approx(float(text), abs=units * ulp * (1.0 + 1e-9) + 1e-15)


def assert_printed(values, *texts, units: float = 0.5):
    """Each of ``values`` equals the corresponding printed number (see :func:`printed`)."""
    values = np.atleast_1d(np.asarray(values, dtype=float))
    assert values.shape == (len(texts),)
    for value, text in zip(values, texts):
        assert value == printed(text, units), f"{value!r} differs from the printed {text}"


# --------------------------------------------------------------------------------------------
# torsion.py
# --------------------------------------------------------------------------------------------

def test_torsion_roots_v4_10a():
    assert_printed(torsion.torsion_roots("fixed-free", 3), "1.570796", "4.712389", "7.853982")
    expected = np.pi * np.arange(1, 5)
    np.testing.assert_allclose(torsion.torsion_roots("fixed-fixed", 4), expected, rtol=1e-15)
    free = torsion.torsion_roots("free-free", 4)
    np.testing.assert_allclose(free, expected, rtol=1e-15)
    assert free.min() > 0.0  # rigid-body mode excluded


def test_torsion_bad_bc_names_argument_and_choices():
    with pytest.raises(ValueError, match=r"bc = 'clamped'.*fixed-free, fixed-fixed, free-free"):
        torsion.torsion_roots("clamped", 2)


def test_torsion_omegas_match_book_form_4_56():
    GIp, J_total, L = 2.0, 3.0, 1.5
    omegas = torsion.torsion_omegas(GIp, J_total / L, L, "fixed-free", 4)
    r = np.arange(1, 5)
    np.testing.assert_allclose(omegas, 0.5 * (2 * r - 1) * np.pi * np.sqrt(GIp / (J_total * L)),
                               rtol=1e-14)


def test_torsion_omegas_steel_v4_10c_independent_of_diameter():
    G, rho, L = 8.1e10, 7850.0, 1.0
    k1 = [torsion.torsion_omegas(G * Ip, rho * Ip, L, "fixed-free", 1)[0]
          for Ip in (np.pi * 0.02**4 / 32, np.pi * 0.3**4 / 32)]
    assert k1[0] == printed("5045.8")
    assert k1[1] == pytest.approx(k1[0], rel=1e-14)
    assert k1[0] / (2 * np.pi) == printed("803.06")


V2_2B = [  # J1/J2, exact k sqrt(J2/c), reduced J1/3 model
    (0.1, "0.983635", "0.983739"),
    (0.5, "0.923865", "0.925820"),
    (1.0, "0.860334", "0.866025"),
    (2.0, "0.761465", "0.774597"),
    (5.0, "0.587566", "0.612372"),
]


@pytest.mark.parametrize("ratio, exact, reduced", V2_2B)
def test_end_disc_v2_2b(ratio, exact, reduced):
    c, J2 = 7.0, 0.3
    J1 = ratio * J2
    k_exact = torsion.end_disc_roots(ratio, 1)[0] * np.sqrt(c / J1)
    k_reduced = torsion.reduced_inertia_omega(c, J1, J2)
    assert k_exact * np.sqrt(J2 / c) == printed(exact)
    assert k_reduced * np.sqrt(J2 / c) == printed(reduced)
    assert k_reduced > k_exact  # Rayleigh upper bound


@pytest.mark.parametrize("ratio", [1e-6, 0.3, 1.0, 40.0, 1e6])
def test_end_disc_roots_solve_equation_in_their_brackets(ratio):
    x = torsion.end_disc_roots(ratio, 8)
    lows = np.arange(8) * np.pi
    assert np.all((x > lows) & (x < lows + np.pi / 2))
    np.testing.assert_allclose(x * np.sin(x), ratio * np.cos(x), atol=1e-12 * max(1.0, ratio))


def test_end_disc_roots_reject_nonpositive_ratio():
    with pytest.raises(ValueError, match="inertia_ratio"):
        torsion.end_disc_roots(0.0, 1)


def test_forced_torsion_v5_11a():
    amp = torsion.forced_torsion_end_amplitude
    assert amp(1.0, 1.0, 1.0, 0.0, 1.0) == 1.0  # static M L / (G I_p)
    assert amp(1.0, 1.0, 1.0, 1e-6, 1.0) == printed("1.0000")
    for omega, text in [(0.5, "1.092605"), (1.0, "1.557408"), (1.5, "9.400947"),
                        (2.0, "-1.092520"), (3.0, "-0.047516")]:
        assert amp(1.0, 1.0, 1.0, omega, 1.0) == printed(text)
    vector = amp(1.0, 1.0, 1.0, np.array([0.0, 0.5, 3.0]), 1.0)
    np.testing.assert_allclose(vector, [1.0, 1.092605, -0.047516], atol=5e-7)


def test_forced_torsion_matches_second_form_of_5_61():
    GIp, J_total, L, M = 3.0, 0.7, 1.3, 2.5
    for omega in (0.4, 2.2, 7.9):
        sigma_L = omega * np.sqrt(J_total / (GIp * L)) * L
        book = M * np.sin(sigma_L) / (omega * np.cos(sigma_L)) * np.sqrt(L / (J_total * GIp))
        assert torsion.forced_torsion_end_amplitude(GIp, J_total / L, L, omega, M) == \
            pytest.approx(book, rel=1e-13)


# --------------------------------------------------------------------------------------------
# bending.py
# --------------------------------------------------------------------------------------------

def test_euler_bernoulli_roots_v4_11a():
    cantilever = bending.euler_bernoulli_roots("clamped-free", 4)
    assert_printed(cantilever, "1.8751041", "4.6940911", "7.8547574", "10.9955407")
    clamped_pinned = bending.euler_bernoulli_roots("clamped-pinned", 3)
    assert_printed(clamped_pinned, "3.9266023", "7.0685827", "10.2101761")
    assert (clamped_pinned[0] / cantilever[0]) ** 2 == printed("4.38514")
    assert (clamped_pinned[1] / cantilever[1]) ** 2 == printed("2.26757")
    # the book's rounded ratios 4.387 / 2.268 (from roots 3.927/1.875 etc.)
    assert (clamped_pinned[0] / cantilever[0]) ** 2 == pytest.approx(4.387, rel=5e-4)
    assert (clamped_pinned[1] / cantilever[1]) ** 2 == pytest.approx(2.268, rel=5e-4)


@pytest.mark.parametrize("bc, residual, asymptote", [
    ("clamped-free", lambda x: np.cos(x) + 1 / np.cosh(x), lambda r: (2 * r - 1) * np.pi / 2),
    ("clamped-clamped", lambda x: np.cos(x) - 1 / np.cosh(x), lambda r: (2 * r + 1) * np.pi / 2),
    ("free-free", lambda x: np.cos(x) - 1 / np.cosh(x), lambda r: (2 * r + 1) * np.pi / 2),
    ("clamped-pinned", lambda x: np.sin(x) - np.cos(x) * np.tanh(x),
     lambda r: (4 * r + 1) * np.pi / 4),
    ("pinned-free", lambda x: np.sin(x) - np.cos(x) * np.tanh(x),
     lambda r: (4 * r + 1) * np.pi / 4),
])
def test_euler_bernoulli_roots_accurate_up_to_high_modes(bc, residual, asymptote):
    x = bending.euler_bernoulli_roots(bc, 25)
    r = np.arange(1, 26)
    assert np.all(np.diff(x) > 2.5)
    np.testing.assert_allclose(residual(x), 0.0, atol=1e-13)
    np.testing.assert_allclose(x[8:], asymptote(r[8:]), atol=1e-8)


def test_euler_bernoulli_roots_pinned_pinned_and_bad_bc():
    np.testing.assert_allclose(bending.euler_bernoulli_roots("pinned-pinned", 3),
                               np.pi * np.arange(1, 4), rtol=1e-15)
    with pytest.raises(ValueError, match=r"bc = 'sliding'.*clamped-free"):
        bending.euler_bernoulli_roots("sliding", 2)


def test_euler_bernoulli_omegas_v4_11b_c():
    cantilever = bending.euler_bernoulli_omegas(1.0, 1.0, 1.0,
                                                bending.euler_bernoulli_roots("clamped-free", 3))
    assert_printed(cantilever, "3.51602", "22.0345", "61.6972")
    ss = bending.euler_bernoulli_omegas(1.0, 1.0, 1.0,
                                        bending.euler_bernoulli_roots("pinned-pinned", 3))
    assert_printed(ss, "9.8696", "39.478", "88.826")


def test_euler_bernoulli_omegas_match_book_form_4_73():
    EI, mu, L = 2.0, 3.0, 1.7
    roots = bending.euler_bernoulli_roots("clamped-free", 3)
    m = mu * L
    sigma = roots / L
    np.testing.assert_allclose(bending.euler_bernoulli_omegas(EI, mu, L, roots),
                               sigma**2 * np.sqrt(EI * L / m), rtol=1e-14)


def _tip_mass_matrix_4x4(x, eta, j):
    """4x4 matrix of the four conditions on the constants of (4.60), written in the equivalent
    basis (cos, sin, e^{-s}, e^{s - x}), s = beta * position (well scaled for high modes).

    Rows: A(0) = 0, A'(0) = 0, EI A''(L) - Jt w^2 A'(L) = 0, EI A'''(L) + M w^2 A(L) = 0,
    in d/ds form, tip rows divided by their positive scale.
    """
    def derivs(s):
        c, sn, em, ep = np.cos(s), np.sin(s), np.exp(-s), np.exp(s - x)
        return (np.array([c, sn, em, ep]), np.array([-sn, c, -em, ep]),
                np.array([-c, -sn, em, ep]), np.array([sn, -c, -em, ep]))

    d0_root, d1_root = derivs(0.0)[:2]
    d0, d1, d2, d3 = derivs(x)
    return np.array([d0_root, d1_root,
                     (d2 - j * x**3 * d1) / (1 + j * x**3),
                     (d3 + eta * x * d0) / (1 + eta * x)])


@pytest.mark.parametrize("eta, j", [(0.0, 0.0), (0.5, 0.0), (3.0, 0.0), (1.0, 0.2), (0.0, 0.5),
                                    (50.0, 2.0)])
def test_tip_mass_roots_make_4x4_determinant_singular(eta, j):
    for x in bending.cantilever_tip_mass_roots(eta, 4, j):
        sv = np.linalg.svd(_tip_mass_matrix_4x4(x, eta, j), compute_uv=False)
        assert sv[-1] / sv[0] < 1e-10
        for dx in (-0.02, 0.02):
            sv = np.linalg.svd(_tip_mass_matrix_4x4(x + dx, eta, j), compute_uv=False)
            assert sv[-1] / sv[0] > 1e-4


def test_tip_mass_limits():
    np.testing.assert_allclose(bending.cantilever_tip_mass_roots(0.0, 5),
                               bending.euler_bernoulli_roots("clamped-free", 5), rtol=1e-13)
    heavy = bending.cantilever_tip_mass_roots(1e6, 4)
    assert heavy[0] == pytest.approx((3.0 / 1e6) ** 0.25, rel=1e-6)  # massless-beam limit
    np.testing.assert_allclose(heavy[1:], bending.euler_bernoulli_roots("clamped-pinned", 3),
                               rtol=1e-6)
    # huge tip rotary inertia alone -> clamped-guided end (tan x + tanh x = 0) after the first root
    guided = bending.cantilever_tip_mass_roots(0.0, 3, inertia_ratio=1e8)[1:]
    exact = [brentq(lambda x: np.sin(x) + np.cos(x) * np.tanh(x), lo, lo + np.pi / 2)
             for lo in (np.pi / 2, 3 * np.pi / 2)]
    np.testing.assert_allclose(guided, exact, rtol=1e-6)


@pytest.mark.parametrize("eta", [0.5, 1.0, 2.0, 5.0, 20.0])
def test_tip_mass_first_frequency_close_to_effective_mass_formula(eta):
    # omega = sqrt(3 EI / (L^3 (M + 0.2357 m))) in units sqrt(EI / (m L^3)) is x^2
    x1 = bending.cantilever_tip_mass_roots(eta, 1)[0]
    assert x1**2 == pytest.approx(np.sqrt(3.0 / (eta + 0.2357)), rel=0.01)
    assert x1 < bending.euler_bernoulli_roots("clamped-free", 1)[0]


TABLE_3_1 = [  # case, c, e11, e22, e12  (EI = 1, l = 1, a = 0.3)
    (1, 0.8, "0.009", "0.1706667", "0.0315"),
    (2, 0.7, "0.0147", "0.0147", "0.0123"),
    (3, 0.7, "0.00407925", "0.00848925", "0.00417825"),
    (4, 0.7, "0.003087", "0.003087", "0.001863"),
    (5, 0.4, "0.0147", "0.0746667", "-0.0182"),
    (6, 0.4, "0.00407925", "0.0613333", "-0.0063"),
]


@pytest.mark.parametrize("case, c, e11, e22, e12", TABLE_3_1)
def test_influence_coefficients_table_3_1(case, c, e11, e22, e12):
    assert bending.influence_coefficients(case, 1.0, 0.3, c) == \
        (printed(e11), printed(e22), printed(e12))
    scaled = bending.influence_coefficients(case, 1.0, 0.3, c, EI=4.0)
    np.testing.assert_allclose(scaled, np.array(bending.influence_coefficients(case, 1.0, 0.3, c))
                               / 4.0, rtol=1e-15)


@pytest.mark.parametrize("case", [1, 2, 3, 4])
def test_influence_coefficients_coincident_points(case):
    e11, e22, e12 = bending.influence_coefficients(case, 1.3, 0.45, 0.45, EI=2.0)
    assert e22 == pytest.approx(e11, rel=1e-13)
    assert e12 == pytest.approx(e11, rel=1e-13)


def test_influence_coefficients_known_cases_and_bad_case():
    # clamped-clamped midspan l^3/(192 EI); simply supported midspan l^3/(48 EI)
    assert bending.influence_coefficients(4, 2.0, 1.0, 1.0)[0] == pytest.approx(8 / 192, rel=1e-14)
    assert bending.influence_coefficients(2, 2.0, 1.0, 1.0)[0] == pytest.approx(8 / 48, rel=1e-14)
    with pytest.raises(ValueError, match="case = 7"):
        bending.influence_coefficients(7, 1.0, 0.3, 0.7)


def test_two_mass_frequencies_v4_5a():
    e11, e22, e12 = bending.influence_coefficients(2, 1.0, 1 / 3, 2 / 3)
    np.testing.assert_allclose([e11, e22, e12], [4 / 243, 4 / 243, 7 / 486], rtol=1e-14)
    k, beta = bending.two_mass_frequencies(e11, e22, e12, 1.0, 1.0)
    assert_printed(k, "5.69210", "22.0454")
    np.testing.assert_allclose(beta, [1.0, -1.0], rtol=1e-12)


def test_two_mass_frequencies_v4_5b_and_both_forms_of_4_32():
    e11, e22, e12 = bending.influence_coefficients(1, 1.0, 0.5, 1.0)
    np.testing.assert_allclose([e11, e22, e12], [1 / 24, 1 / 3, 5 / 48], rtol=1e-14)
    m1, m2 = 1.0, 1.0
    k, beta = bending.two_mass_frequencies(e11, e22, e12, m1, m2)
    assert_printed(k, "1.65134", "10.9864")
    assert_printed(beta, "3.12047", "-0.32047")
    k2 = k**2
    np.testing.assert_allclose((1 - e11 * m1 * k2) / (e12 * m2 * k2),
                               e12 * m1 * k2 / (1 - e22 * m2 * k2), rtol=1e-12)


def test_two_mass_frequencies_against_eigen_solver():
    rng = np.random.default_rng(3)
    for _ in range(20):
        f = rng.normal(size=(2, 2))
        e = f @ f.T + 0.1 * np.eye(2)
        m = rng.uniform(0.1, 5.0, size=2)
        k, beta = bending.two_mass_frequencies(e[0, 0], e[1, 1], e[0, 1], *m)
        h = np.sort(np.linalg.eigvals(e @ np.diag(m)).real)[::-1]  # eigenvalues of e m are k^-2
        np.testing.assert_allclose(k, 1 / np.sqrt(h), rtol=1e-12)
        for kr, br in zip(k, beta):  # (4.31) matrix annihilates the mode (1, beta)
            mat = np.eye(2) - e @ np.diag(m) * kr**2
            np.testing.assert_allclose(mat @ [1.0, br], 0.0, atol=1e-10 * (1 + abs(br)))


def test_two_mass_frequencies_uncoupled():
    k, beta = bending.two_mass_frequencies(1.0, 4.0, 0.0, 1.0, 1.0)
    np.testing.assert_allclose(k, [0.5, 1.0], rtol=1e-15)
    assert np.isinf(beta[0]) and beta[1] == 0.0


def test_dunkerley_v4_7b_c():
    c = 1000.0
    chain = bending.dunkerley_bound([2 / (3 * c), 2 / (3 * c)], [1.0, 1.0])
    assert chain == printed("27.386")
    assert chain < np.sqrt(c)  # exact k1 = 31.623
    ss = bending.dunkerley_bound([4 / 243, 4 / 243], [1.0, 1.0])
    cantilever = bending.dunkerley_bound([1 / 24, 1 / 3], [1.0, 1.0])
    assert_printed((ss, cantilever), "5.51135", "1.63299")
    assert ss < 5.69210 and cantilever < 1.65134


# --------------------------------------------------------------------------------------------
# timoshenko.py
# --------------------------------------------------------------------------------------------

STEEL = dict(E=2.1e11, G=8.1e10, rho=7850.0)


def _circle(D):
    return np.pi * D**2 / 4, np.pi * D**4 / 64


def _euler_bernoulli_ss(E, rho, A, I, L, n):
    return (np.arange(1, n + 1) * np.pi / L) ** 2 * np.sqrt(E * I / (rho * A))


def test_cowper_shear_coefficient():
    assert timoshenko.cowper_shear_coefficient(0.3) == pytest.approx(39 / 44, rel=1e-15)
    assert timoshenko.cowper_shear_coefficient(0.3) == printed("0.886")
    assert timoshenko.cowper_shear_coefficient(0.3, 1.0) == pytest.approx(2.6 / 4.9, rel=1e-15)


@pytest.mark.parametrize("D", [0.01, 0.001])
def test_timoshenko_slender_limit_is_euler_bernoulli(D):
    L, n, kappa = 1.0, 4, timoshenko.cowper_shear_coefficient(0.3)
    A, I = _circle(D)
    omega = timoshenko.timoshenko_ss_omegas(STEEL["E"], STEEL["G"], kappa, STEEL["rho"],
                                            A, I, L, n)
    ratio = omega / _euler_bernoulli_ss(STEEL["E"], STEEL["rho"], A, I, L, n)
    # leading correction: 1 - ratio = q^2 r_g^2 (1 + E/(kappa G)) / 2,  q = r pi / L, r_g^2 = I/A
    q = np.arange(1, n + 1) * np.pi / L
    first_order = q**2 * (I / A) * (1 + STEEL["E"] / (kappa * STEEL["G"])) / 2
    assert np.all(ratio < 1.0)
    np.testing.assert_allclose(1.0 - ratio, first_order, rtol=0.01)


def test_timoshenko_roots_make_substituted_equations_singular():
    E, G, rho, kappa, L = STEEL["E"], STEEL["G"], STEEL["rho"], 0.85, 0.6
    A, I = _circle(0.08)
    both = timoshenko.timoshenko_ss_omegas_both(E, G, kappa, rho, A, I, L, 6)
    assert both.shape == (6, 2) and np.all(both[:, 1] > both[:, 0])
    kGA = kappa * G * A
    for r, pair in enumerate(both, start=1):
        q = r * np.pi / L
        for omega in pair:
            m = np.array([[kGA * q**2 - rho * A * omega**2, -kGA * q],
                          [-kGA * q, E * I * q**2 + kGA - rho * I * omega**2]])
            scale = abs(m[0, 0] * m[1, 1]) + abs(m[0, 1] * m[1, 0])
            assert abs(np.linalg.det(m)) / scale < 1e-10


def test_timoshenko_below_euler_bernoulli_and_rayleigh_limit():
    E, G, rho, L = STEEL["E"], STEEL["G"], STEEL["rho"], 1.0
    A, I = _circle(0.1)
    omega = timoshenko.timoshenko_ss_omegas(E, G, 0.886, rho, A, I, L, 5)
    assert np.all(omega < _euler_bernoulli_ss(E, rho, A, I, L, 5))
    # infinitely shear-stiff -> Rayleigh beam: omega^2 = E I q^4 / (rho A (1 + q^2 I / A))
    rayleigh = timoshenko.timoshenko_ss_omegas(E, 1e30, 1.0, rho, A, I, L, 5)
    q = np.arange(1, 6) * np.pi / L
    np.testing.assert_allclose(rayleigh, np.sqrt(E * I * q**4 / (rho * A * (1 + q**2 * I / A))),
                               rtol=1e-12)
    assert np.all(omega < rayleigh)


# --------------------------------------------------------------------------------------------
# sdof.py
# --------------------------------------------------------------------------------------------

SECTION_5_4_PEAKS = [  # delta, alpha_res, alpha_max, z*, alpha at the seed's sqrt(1 - delta^2)
    (0.025, "20.0", "20.00625", "0.999375", "20.00469"),
    (0.05, "10.0", "10.01252", "0.997497", "10.00939"),
    (0.07, "7.142857", "7.160422", "0.995088", "7.156018"),
    (0.1, "5.0", "5.025189", "0.989949", "5.018856"),
    (0.2, "2.5", "2.551552", "0.959166", "2.538365"),
]


@pytest.mark.parametrize("delta, a_res, a_max, z_star, a_seed", SECTION_5_4_PEAKS)
def test_peak_table_section_5_4(delta, a_res, a_max, z_star, a_seed):
    assert sdof.amplification(1.0, delta) == pytest.approx(1 / (2 * delta), rel=1e-14)
    assert sdof.amplification(1.0, delta) == printed(a_res)
    assert sdof.peak_amplification(delta) == printed(a_max)
    assert sdof.peak_frequency_ratio(delta) == printed(z_star)
    assert sdof.amplification(sdof.peak_frequency_ratio(delta), delta) == \
        pytest.approx(sdof.peak_amplification(delta), rel=1e-14)
    assert sdof.amplification(np.sqrt(1 - delta**2), delta) == printed(a_seed)
    best = minimize_scalar(lambda z: -sdof.amplification(z, delta), bounds=(0.5, 1.5),
                           method="bounded", options={"xatol": 1e-10})
    assert best.x == pytest.approx(float(sdof.peak_frequency_ratio(delta)), abs=1e-6)


SECTION_5_4_CURVES = [  # z, alpha(0), alpha(0.05), alpha(0.1), gamma(0.05) [deg]
    (0.5, "1.333333", "1.330380", "1.321637", "3.814"),
    (0.7, "1.960784", "1.942572", "1.890836", "7.815"),
    (1.4, "1.041667", "1.030764", "1.000000", "171.703"),
    (np.sqrt(2), "1.000000", "0.990148", "0.962250", "171.951"),
    (2.0, "0.333333", "0.332595", "0.330409", "176.186"),
    (3.0, "0.125", "0.124912", "0.124650", "177.852"),
]


@pytest.mark.parametrize("z, a0, a05, a10, gamma05", SECTION_5_4_CURVES)
def test_afc_pfc_table_section_5_4(z, a0, a05, a10, gamma05):
    assert sdof.amplification(z, 0.0) == printed(a0)
    assert sdof.amplification(z, 0.05) == printed(a05)
    assert sdof.amplification(z, 0.1) == printed(a10)
    assert np.degrees(sdof.phase_lag(z, 0.05)) == printed(gamma05)


def test_amplification_vectorised_and_no_peak_for_heavy_damping():
    z = np.linspace(0.0, 3.0, 301)
    np.testing.assert_allclose(sdof.amplification(z, 0.1),
                               [sdof.amplification(zi, 0.1) for zi in z], rtol=1e-15)
    assert np.all(np.diff(sdof.amplification(z, 0.8)) < 0)
    assert np.isnan(sdof.peak_frequency_ratio(0.8)) and np.isnan(sdof.peak_amplification(0.8))
    assert np.isnan(sdof.kinematic_peak_frequency_ratio(np.sqrt(0.5)))


def test_phase_lag_is_continuous_through_resonance():
    assert sdof.phase_lag(1.0, 0.05) == pytest.approx(np.pi / 2, rel=1e-15)
    z = np.linspace(0.0, 4.0, 4001)
    gamma = sdof.phase_lag(z, 0.05)
    assert np.all(np.diff(gamma) > 0) and np.all((gamma >= 0) & (gamma < np.pi))
    off = z != 1.0
    printed_form = np.arctan(2 * 0.05 * z[off] / (1 - z[off] ** 2))  # as printed in (5.24)
    branch = np.where(z[off] < 1, printed_form, printed_form + np.pi)
    np.testing.assert_allclose(gamma[off], branch, rtol=1e-13)
    assert sdof.phase_lag(2.0, 0.0) == pytest.approx(np.pi)


@pytest.mark.parametrize("delta, a_max, z_peak, a_at_3", [
    (0.05, "10.01252", "1.002509", "1.124210"),
    (0.1, "5.025189", "1.010153", "1.121849"),
])
def test_kinematic_excitation_v5_5a(delta, a_max, z_peak, a_at_3):
    z_star = sdof.kinematic_peak_frequency_ratio(delta)
    assert z_star == printed(z_peak)
    assert sdof.kinematic_amplification(z_star, delta) == printed(a_max)
    assert sdof.kinematic_amplification(z_star, delta) == \
        pytest.approx(sdof.peak_amplification(delta), rel=1e-13)
    assert sdof.kinematic_amplification(1.0, delta) == pytest.approx(1 / (2 * delta), rel=1e-14)
    assert sdof.kinematic_amplification(3.0, delta) == printed(a_at_3)
    best = minimize_scalar(lambda z: -sdof.kinematic_amplification(z, delta), bounds=(0.5, 1.5),
                           method="bounded", options={"xatol": 1e-10})
    assert best.x == pytest.approx(float(z_star), abs=1e-6)


@pytest.mark.parametrize("delta, lam, psi", [
    (0.025, "0.15708", "0.26960"), (0.05, "0.31416", "0.46651"),
    (0.07, "0.43982", "0.58507"), (0.1, "0.62832", "0.71539"),
])
def test_psi_from_delta_v2_4a(delta, lam, psi):
    assert 2 * np.pi * delta == printed(lam)
    assert sdof.psi_from_delta(delta) == printed(psi)
    assert sdof.delta_from_psi(sdof.psi_from_delta(delta)) == pytest.approx(delta, rel=1e-13)


@pytest.mark.parametrize("psi, lam, delta", [
    (0.3, "0.17834", "0.02838"), (0.5, "0.34657", "0.05516"), (0.7, "0.60199", "0.09581"),
])
def test_delta_from_psi_v2_4a(psi, lam, delta):
    assert 2 * np.pi * sdof.delta_from_psi(psi) == printed(lam)
    assert sdof.delta_from_psi(psi) == printed(delta)
    # psi = 1 - (A2/A1)^2 with A2/A1 = exp(-lambda)   (2.9)
    assert 1 - np.exp(-2 * np.pi * sdof.delta_from_psi(psi)) ** 2 == pytest.approx(psi, rel=1e-14)


def test_decrement_v2_4a():
    assert np.exp(-2 * np.pi * 0.05) == printed("0.73040")


def test_energy_balance_1dof_v5_13a_and_hysteretic_convention():
    F0, c, psi, m = 10.0, 1000.0, 0.4, 2.0
    amp = sdof.energy_balance_resonance_amplitude(F0, c, psi)
    assert amp == printed("0.157080")
    assert amp == pytest.approx(2 * np.pi * F0 / (psi * c), rel=1e-15)
    # complex stiffness c (1 + 2 i delta_h) at omega^2 = c / m reproduces it exactly
    delta_h = sdof.hysteretic_delta(psi)
    assert abs(F0 / (c * (1 + 2j * delta_h) - m * c / m)) == pytest.approx(amp, rel=1e-14)
    # ... and dissipates psi c A^2 / 2 per cycle, (5.69): pi * Im(stiffness) * A^2
    assert np.pi * c * 2 * delta_h * amp**2 == pytest.approx(0.5 * psi * c * amp**2, rel=1e-14)
    # the exact free-decay mapping gives a ~22 % smaller viscous amplitude
    delta_exact = sdof.delta_from_psi(psi)
    assert delta_exact == printed("0.04065")
    assert F0 / (2 * delta_exact * c) == printed("0.123001")


def test_energy_balance_with_friction_v5_13c():
    assert sdof.energy_balance_resonance_amplitude(10.0, 1000.0, 0.4, friction=1.0) == \
        printed("0.137080")
    assert sdof.energy_balance_resonance_amplitude(10.0, 1000.0, 0.4, friction=-1.0) == \
        printed("0.137080")
    threshold = 4 * 1.0 / np.pi
    assert threshold == printed("1.27324")
    assert sdof.energy_balance_resonance_amplitude(0.999 * threshold, 1000.0, 0.4, 1.0) == 0.0
    assert sdof.energy_balance_resonance_amplitude(1.001 * threshold, 1000.0, 0.4, 1.0) > 0.0
    assert sdof.energy_balance_resonance_amplitude(1.001 * threshold, 1000.0, 0.0, 1.0) == np.inf


def test_energy_balance_2dof_v5_13b():
    m, c, psi, F = 1.0, 1000.0, 0.4, 10.0
    # q1 = x1, q2 = x2 - x1: a = [[2m, m], [m, m]], c = diag(c, c); force on m2 -> Q1 = Q2 = F
    a_mat, c_mat = np.array([[2 * m, m], [m, m]]), np.diag([c, c])
    lam, vec = eigh(c_mat, a_mat)
    assert_printed(np.sqrt(lam), "19.5440", "51.1667")
    beta = vec[1] / vec[0]
    np.testing.assert_allclose(beta, [(np.sqrt(5) - 1) / 2, -(1 + np.sqrt(5)) / 2], rtol=1e-12)

    A1, A2 = sdof.energy_balance_2dof(c, c, psi, psi, F, F, beta[0])
    assert_printed((A1, A2), "0.183912", "0.113664")
    B1, B2 = sdof.energy_balance_2dof(c, c, psi, psi, F, F, beta[1])
    assert_printed((abs(B1), abs(B2)), "0.026832", "0.043416")
    assert B1 < 0 < B2

    # N-DOF form (5.74) agrees and does not depend on the normalisation of beta
    for b, expected in ((beta[0], (A1, A2)), (beta[1], (B1, B2))):
        for scale in (1.0, -3.7):
            np.testing.assert_allclose(
                sdof.energy_balance_ndof([c, c], [psi, psi], [F, F], scale * np.array([1.0, b])),
                expected, rtol=1e-13)

    # exact complex-stiffness solve at omega = k_r with the package convention (digest values)
    exact = []
    for k in np.sqrt(lam):
        stiff = np.diag([c, c]) * (1 + 2j * sdof.hysteretic_delta(psi))
        exact.append(np.abs(np.linalg.solve(stiff - k**2 * a_mat, [F, F])))
    assert_printed(exact[0], "0.183775", "0.113949")
    assert_printed(exact[1], "0.026885", "0.043447")
    np.testing.assert_allclose([abs(A1), abs(A2)], exact[0], rtol=3e-3)
    np.testing.assert_allclose([abs(B1), abs(B2)], exact[1], rtol=3e-3)


# --------------------------------------------------------------------------------------------
# lumped_refs.py
# --------------------------------------------------------------------------------------------

def test_two_mass_three_spring_v4_4a():
    m, c = 1.0, 1000.0
    k = lumped_refs.two_mass_three_spring(m, c)
    assert_printed(k, "31.6228", "54.7723")
    lam = eigh(np.array([[2 * c, -c], [-c, 2 * c]]), m * np.eye(2), eigvals_only=True)
    np.testing.assert_allclose(k, np.sqrt(lam), rtol=1e-14)


def test_two_discs_v4_8a_b():
    for J1, text in ((1.0, "1.41421"), (2.0, "1.22474")):
        k = lumped_refs.two_discs(J1, 1.0, 1.0)
        assert k[0] == 0.0
        assert_printed(k[1:], text)
    assert lumped_refs.two_discs(1000.0, 1.0, 1.0)[1] / np.sqrt(1.0) == printed("1.0005")


DRIVE = dict(J1=1.0, J2=0.5, J3=0.2, J4=2.0, u21=0.5, c1=1000.0, c2=500.0)


def _reduced_chain(J1, J2, J3, J4, u21, c1, c2):
    """Absolute-coordinate chain reduced to shaft 1: (J1, J2 + J3 u^2, J4 u^2), (c1, c2 u^2)."""
    J = np.array([J1, J2 + J3 * u21**2, J4 * u21**2])
    k1, k2 = c1, c2 * u21**2
    K = np.array([[k1, -k1, 0.0], [-k1, k1 + k2, -k2], [0.0, -k2, k2]])
    return np.diag(J), K


def test_geared_drive_v3_2a():
    k = lumped_refs.geared_drive_314(**DRIVE)
    assert k[0] == 0.0
    assert_printed(k[1:], "17.6739", "54.6176")
    M, K = _reduced_chain(**DRIVE)
    lam = eigh(K, M, eigvals_only=True)
    np.testing.assert_allclose(k[1:], np.sqrt(lam[1:]), rtol=1e-12)
    a, c = lumped_refs.geared_drive_314_matrices(**DRIVE)
    np.testing.assert_array_equal(a, a.T)
    assert np.all(np.linalg.eigvalsh(a) > 0)


def test_geared_drive_driven_v3_2b():
    k = lumped_refs.geared_drive_314_driven(**DRIVE)
    assert_printed(k, "14.7950", "45.5693")
    M, K = _reduced_chain(**DRIVE)  # input disc clamped: drop its row/column
    np.testing.assert_allclose(k, np.sqrt(eigh(K[1:, 1:], M[1:, 1:], eigvals_only=True)),
                               rtol=1e-12)


V4_10B = {
    5: ("1.56434", "4.53991", "7.07107"),
    10: ("1.56918", "4.66891", "7.65367"),
    20: ("1.57039", "4.70150", "7.80361"),
    50: ("1.57073", "4.71065", "7.84591"),
    100: ("1.57078", "4.71195", "7.85196"),
}


@pytest.mark.parametrize("N", sorted(V4_10B))
def test_uniform_chain_lumped_v4_10b(N):
    k = lumped_refs.uniform_chain_lumped(N, 1.0, 1.0, 3)
    # one unit: the digest prints 10 sin(3 pi / 20) = 4.5399049974 as 4.53991 (double rounding
    # via 4.539905); the closed form itself is checked against eigh to 1e-12 below.
    assert_printed(k, *V4_10B[N], units=1.0)
    assert np.all(k < torsion.torsion_omegas(1.0, 1.0, 1.0, "fixed-free", 3))


def test_uniform_chain_lumped_against_tridiagonal_eigenproblem():
    N, c, J = 12, 3.0, 0.8
    ks = N * c
    K = 2 * ks * np.eye(N) - ks * (np.eye(N, k=1) + np.eye(N, k=-1))
    K[-1, -1] = ks
    masses = np.full(N, J / N)
    masses[-1] /= 2
    lam = eigh(K, np.diag(masses), eigvals_only=True)
    np.testing.assert_allclose(lumped_refs.uniform_chain_lumped(N, c, J, N), np.sqrt(lam),
                               rtol=1e-12)
    with pytest.raises(ValueError, match="n_modes"):
        lumped_refs.uniform_chain_lumped(3, 1.0, 1.0, 4)
