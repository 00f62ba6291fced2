"""Independent references for drives of regular structure (textbook ch. 10, digest
textbook_ch10-11.md).  Written without the package's solvers: roots by brentq on the
frequency equations as the book states them, forced responses by the corrected closed forms
and by a dense direct solve of the reduced equations, the book's PRINTED (wrong) forced
formulas for regression guards, Table 10.1 as printed, the motor example and the
slowly-varying oscillator.
"""
from __future__ import annotations

import numpy as np
import scipy.linalg as sla
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

# ----------------------------------------------------------------- parameter sets (digest)
SET_R = dict(n=6, c0=6.0e4, J0=0.02 / 6, m=10.0 / 6, c=10.0 / 6 * 300.0**2, ratio=0.05)      # k = 300
SET_C = dict(L=2.0, GI=2.0e4, rho=0.01, M_total=10.0, ratio=0.05, k=300.0)                   # continuum
SET_D = dict(n=6, c0=1.0e4, J0=0.01, m=2.0, c=5.0e5, ratio=0.05, F=1.0)                      # k = 500
MOTOR = dict(omega0=157.0, nu=3e-3, T=0.043, J0=0.224, p1=150.0, delta1=0.02, M1=1.0)

# digest "Validation cases" (a)1: Set R roots (case 2 and case 1), printed to 4 decimals
SET_R_CASE2 = "283.9146 298.1352 299.2735 299.5816 299.7010 299.7514 1080.7345 3027.7431 4831.8898 6360.1943 7520.8384 8245.5483"
SET_R_CASE1 = "295.2626 298.7546 299.3970 299.6165 299.7112 299.7534 1918.4475 3696.9735 5301.1421 6642.5510 7652.3399 8279.3434"
# digest tables of p_r/p0 (rigid mechanisms)
RIGID_CASE2 = {6: "0.24107 0.70921 1.13613 1.49702 1.77091 1.94188",
               9: "0.16516 0.49097 0.80339 1.09390 1.35456 1.57828 1.75895 1.89163 1.97272",
               12: "0.12558 0.37476 0.61803 0.85156 1.07165 1.27485 1.45794 1.61803 1.75261 1.85955 1.93717 1.98423"}
RIGID_CASE1 = {6: "0.44504 0.86777 1.24698 1.56366 1.80194 1.94986",
               9: "0.31287 0.61803 0.90798 1.17557 1.41421 1.61803 1.78201 1.90211 1.97538",
               12: "0.24107 0.47863 0.70921 0.92945 1.13613 1.32625 1.49702 1.64597 1.77091 1.87003 1.94188 1.98542"}
# digest Set C (10.50) roots and forced Y(L), Y(L/2)
SET_C_ROOTS = {"p11": "286.3408", "p12": "1163.7051", "p21": "298.4795", "p22": "3349.1364", "p31": "299.4528",
               "p32": "5563.7525", "rigid": "740.4805"}
SET_C_FORCED_L = {100: "2.870022e-05", 200: "5.045119e-05", 350: "-5.526251e-05", 400: "-2.973139e-05",
                  449: "-2.013386e-05", 451: "-1.986785e-05", 600: "-1.009187e-05", 2000: "3.060482e-07"}
SET_C_FORCED_HALF = {100: "2.15035e-05", 200: "3.76312e-05", 350: "-4.19548e-05", 400: "-2.23881e-05",
                     600: "-7.50150e-06"}
# digest Set D forced table: (case, omega) -> (a_01, a_03, a_06)
SET_D_FORCED = {
    (1, 50): ("1.542266e-05", "3.090357e-05", "1.542266e-05"), (1, 200): ("2.567646e-05", "5.310300e-05", "2.567646e-05"),
    (1, 400): ("-3.630357e-05", "-9.506833e-05", "-3.630357e-05"), (1, 480): ("-1.724417e-04", "7.397832e-05", "-1.724417e-04"),
    (1, 700): ("7.545390e-05", "1.740596e-04", "7.545390e-05"), (1, 1500): ("5.122639e-07", "5.050489e-08", "5.122639e-07"),
    (2, 50): ("3.215058e-05", "8.083580e-05", "1.136005e-04"), (2, 200): ("-3.118443e-04", "-8.746853e-04", "-1.319509e-03"),
    (2, 400): ("2.254955e-05", "1.092258e-07", "-9.524487e-05"), (2, 480): ("-3.917551e-05", "-4.727698e-05", "-6.651562e-05"),
    (2, 700): ("2.190374e-06", "1.903687e-05", "4.372162e-05"), (2, 1500): ("-3.330148e-07", "8.856716e-07", "7.852102e-07")}
# digest motor example: h -> (omega_peak, |a1|_peak)
MOTOR_PEAKS = {0.25: ("167.87", "1.2593e-02"), 0.5: ("183.99", "4.3624e-03"), 1.0: ("212.56", "1.2280e-03"),
               3.0: ("300.98", "1.0407e-04")}


def nums(text: str) -> list[str]:
    return text.split()


# ----------------------------------------------------------------- regular structure
def _gamma(n: int, case: int) -> np.ndarray:
    """(10.34) case 1: r pi/(n+1); (10.38) case 2: pi (2r-1)/(2(n+1/2))."""
    r = np.arange(1, n + 1)
    return r * np.pi / (n + 1) if case == 1 else np.pi * (2 * r - 1) / (2 * (n + 0.5))


def regular_roots(n, c0, J0, m, c, ratio, case: int) -> np.ndarray:
    """All 2n roots of (10.36) 1 - cos gamma_r = J*(p) p^2/(2 c0) with J* of (10.16), by brentq
    on the pole-free form (1 - p^2/k^2)(1 - cos g) 2 c0 - p^2 [J0 (1 - p^2/k^2) + m Pi'^2] = 0
    in (0, k) and (p_*, inf).  1 - cos g is evaluated as 2 sin^2(g/2): for n = 1000 the lowest
    g ~ 1.6e-3 and 1 - cos g cancels to ~1e-10, which moved the lowest root by 1.6e-12."""
    k = np.sqrt(c / m)
    p_star = k * np.sqrt(1 + m * ratio**2 / J0)
    out = []
    for g in _gamma(n, case):
        one_minus_cos = 2 * np.sin(g / 2) ** 2
        f = lambda p: (1 - p**2 / k**2) * one_minus_cos * 2 * c0 - p**2 * (J0 * (1 - p**2 / k**2) + m * ratio**2)
        out.append(brentq(f, 1e-12 * k, k, xtol=1e-14 * k, rtol=1e-15))
        hi = 2 * p_star
        while f(hi) * f(p_star) > 0:
            hi *= 2
        out.append(brentq(f, p_star, hi, xtol=1e-14 * k, rtol=1e-15))
    return np.sort(out)


def rigid_ratio_formula(n: int, case: int) -> np.ndarray:
    """(10.37) p_r/p0 = 2 sin(r pi/(2(n+1))); (10.39) p_r/p0 = 2 sin(pi (2r-1)/(4(n+0.5)))."""
    r = np.arange(1, n + 1)
    if case == 1:
        return 2 * np.sin(r * np.pi / (2 * (n + 1)))
    return 2 * np.sin(np.pi * (2 * r - 1) / (4 * (n + 0.5)))


def regular_forced_corrected(omega, n, c0, J0, m, c, ratio, F, case: int) -> np.ndarray:
    """Digest's corrected (10.41)/(10.45): a_0j = F Pi'/(w^2 [J0 (1 - w^2/k^2) + m Pi'^2]) *
    [cos j g - 1 + t sin j g], t = tan((n+1/2) g) (case 2) or tan((n+1) g/2) (case 1)."""
    k2 = c / m
    w2 = omega**2
    Jstar = J0 + m * ratio**2 / (1 - w2 / k2)
    g = np.arccos(complex(1 - Jstar * w2 / (2 * c0)))
    j = np.arange(1, n + 1)
    t = np.tan((n + 0.5) * g) if case == 2 else np.tan((n + 1) * g / 2)
    pref = F * ratio / (w2 * (J0 * (1 - w2 / k2) + m * ratio**2))
    return (pref * (np.cos(j * g) - 1 + t * np.sin(j * g))).real


def regular_forced_printed(omega, n, c0, J0, m, c, ratio, F, case: int) -> np.ndarray:
    """The book's PRINTED (10.41) (case 1) and (10.45) (case 2) with B0 = 1/c0 and D_j of
    (10.46) as printed -- known wrong (regression guard only)."""
    k2 = c / m
    w2 = omega**2
    Jstar = J0 + m * ratio**2 / (1 - w2 / k2)
    Dj = 1 - Jstar * w2 / c0                 # (10.46) as printed
    g = np.arccos(complex(1 - Jstar * w2 / (2 * c0)))
    j = np.arange(1, n + 1)
    pre = F * (1 / c0) / Dj
    if case == 1:
        return (pre * (np.cos(j * g) - 1 / np.tan((n + 1) * g) * np.sin(j * g) - 1)).real
    return (pre * (np.cos(j * g) - 1 + np.tan((n + 0.5) * g) * np.sin(j * g))).real


def regular_forced_direct(omega, n, c0, J0, m, c, ratio, F, case: int) -> np.ndarray:
    """Dense direct solve of the disc equations with the mechanisms condensed:
    (K_chain - J*(w) w^2 I) a = (F/D_j) 1, D_j = (1 - w^2/k^2)/Pi' (torque F Pi'/(1 - w^2/k^2) per disc)."""
    k2 = c / m
    w2 = omega**2
    Jstar = J0 + m * ratio**2 / (1 - w2 / k2)
    K = 2 * c0 * np.eye(n) - c0 * (np.eye(n, k=1) + np.eye(n, k=-1))
    if case == 2:
        K[-1, -1] = c0
    rhs = np.full(n, F * ratio / (1 - w2 / k2))
    return np.linalg.solve(K - Jstar * w2 * np.eye(n), rhs)


# ----------------------------------------------------------------- pseudo-medium
def pseudo_medium_roots(L, GI, rho, M_total, ratio, k, r: int) -> tuple[float, float]:
    """(10.50) p^2 = c pi^2 (2r-1)^2 / (4 [J0 + n m Pi'^2/(1 - p^2/k^2)]), c = GI/L, J0 = rho L
    (total shaft inertia, digest flag): brentq on the pole-free form in (0, k) and (p_*, inf)."""
    c, J = GI / L, rho * L
    A = c * np.pi**2 * (2 * r - 1) ** 2 / 4
    f = lambda p: p**2 * (J * (1 - p**2 / k**2) + M_total * ratio**2) - A * (1 - p**2 / k**2)
    p_star = k * np.sqrt(1 + M_total * ratio**2 / J)
    lo = brentq(f, 1e-9 * k, k, xtol=1e-13 * k, rtol=1e-15)
    hi = 2 * p_star
    while f(hi) * f(p_star * (1 + 1e-12)) > 0:
        hi *= 2
    return lo, brentq(f, p_star * (1 + 1e-12), hi, xtol=1e-13 * k, rtol=1e-15)


def pseudo_medium_rigid(L, GI, rho, M_total, ratio, r: int) -> float:
    """(10.51) p_r = (pi (2r-1)/2) sqrt(c/(J0 + n m Pi'^2))."""
    return np.pi * (2 * r - 1) / 2 * np.sqrt(GI / L / (rho * L + M_total * ratio**2))


def _pseudo_medium_forced_parameters(omega, L, GI, rho, M_total, ratio, k, F_total):
    """Particular amplitude Y_* of (10.58), wavenumber s (rho(w) > 0, trigonometric) or s0
    (rho(w) < 0, hyperbolic) of the pseudo-medium with rho(w) = rho0 + m_bar Pi'^2/(1 - w^2/k^2)."""
    fbar, mbar = F_total / L, M_total / L
    w2 = omega**2
    rho_w = rho + mbar * ratio**2 / (1 - w2 / k**2)
    Ys = -fbar * ratio / (w2 * (rho * (1 - w2 / k**2) + mbar * ratio**2))
    return Ys, omega * np.sqrt(abs(rho_w) / GI), bool(rho_w > 0)


def pseudo_medium_forced_corrected(x, omega, L, GI, rho, M_total, ratio, k, F_total):
    """Corrected (10.58)-(10.61): Y_* = -(nF/L) Pi'/(w^2 [rho0 (1 - w^2/k^2) + m_bar Pi'^2]);
    rho(w) > 0: Y = Y_*[1 - cos sx - tan(sL) sin sx]; rho(w) < 0: Y = Y_*[1 - ch s0x + th(s0L) sh s0x]."""
    Ys, s, trig = _pseudo_medium_forced_parameters(omega, L, GI, rho, M_total, ratio, k, F_total)
    x = np.asarray(x, float)
    if trig:
        return Ys * (1 - np.cos(s * x) - np.tan(s * L) * np.sin(s * x))
    return Ys * (1 - np.cosh(s * x) + np.tanh(s * L) * np.sinh(s * x))


def pseudo_medium_forced_printed(x, omega, L, GI, rho, M_total, ratio, k, F_total):
    """The book's PRINTED (10.59)-(10.61) (with the n/L factor restored so that only the shape
    differs): Y = -Y_*(cos sx + tg sL sin sx) (rho > 0), Y = Y_*(ch s0x - th s0L sh s0x) (rho < 0)."""
    Ys, s, trig = _pseudo_medium_forced_parameters(omega, L, GI, rho, M_total, ratio, k, F_total)
    x = np.asarray(x, float)
    if trig:
        return -Ys * (np.cos(s * x) + np.tan(s * L) * np.sin(s * x))
    return Ys * (np.cosh(s * x) - np.tanh(s * L) * np.sinh(s * x))


# ----------------------------------------------------------------- Table 10.1
def table_10_1(name: str, p, c, J, P, printed: bool = False) -> np.ndarray:
    """Rows of Table 10.1 as printed (``printed=True`` keeps the misprinted C of c-Pi-J)."""
    q = J * p**2
    rows = {
        "c": (1, 1 / c, 0, 1), "J": (1, 0, -q, 1), "Pi": (P, 0, 0, 1 / P),
        "c-J-Pi": (P, P / c, -q / P, (1 - q / c) / P),
        "c-Pi-J": (P, P / c, -q / P if printed else -q * P, -q * P / c + 1 / P),
        "J-c-Pi": (P * (1 - q / c), P / c, -q / P, 1 / P),
        "J-Pi-c": (P - q / (c * P), 1 / (c * P), -q / P, 1 / P),
        "Pi-J-c": (P * (1 - q / c), 1 / (c * P), -q * P, 1 / P),
        "Pi-c-J": (P, 1 / (c * P), -q * P, (1 - q / c) / P),
    }
    A, B, C, D = rows[name]
    return np.array([[A, B], [C, D]], dtype=float)


# ----------------------------------------------------------------- lumped chains by hand
def chain_eigen(J: list, springs: list) -> np.ndarray:
    """sqrt of the eigenvalues of a lumped chain: J = inertias, springs = (i, j, c) with -1 = ground."""
    n = len(J)
    K = np.zeros((n, n))
    for i, j, c in springs:
        for a in (i, j):
            if a >= 0:
                K[a, a] += c
        if i >= 0 and j >= 0:
            K[i, j] -= c
            K[j, i] -= c
    return np.sqrt(sla.eigh(K, np.diag(J), eigvals_only=True))


# ----------------------------------------------------------------- motor example §10.6
def motor_constants(omega0, nu, T, J0, **_):
    """b_D = 1/(nu omega0), c_D = 1/(nu omega0 T), k^2 = 1/(nu T J0 omega0), n^2 = 1/(4 T^2), p0 = sqrt(k^2 - n^2)."""
    b = 1 / (nu * omega0)
    c = 1 / (nu * omega0 * T)
    k2 = 1 / (nu * T * J0 * omega0)
    n2 = 0.25 / T**2
    return b, c, np.sqrt(k2 - n2)


def motor_direct(omega, h, omega0, nu, T, J0, p1, delta1, M1):
    """Direct complex solve of the 3-DOF system (Maxwell node z, rotor, load) of the digest:
    [[i w b + c_D, -c_D, 0], [-c_D, c_D + c1~ - J0 w^2, -c1~], [0, -c1~, c1~ - J1 w^2]] x = [0, 0, M1]."""
    b, cD, _ = motor_constants(omega0, nu, T, J0)
    J1 = h * J0
    c1 = p1**2 * J1 * (1 + 2j * delta1)
    w = omega
    A = np.array([[1j * w * b + cD, -cD, 0], [-cD, cD + c1 - J0 * w**2, -c1], [0, -c1, c1 - J1 * w**2]])
    return np.linalg.solve(A, np.array([0, 0, M1], dtype=complex))


# ----------------------------------------------------------------- slow variation (10.20)
def slow_oscillator_envelope(p0: float, eps: float, t_end: float, amp: float = 0.5, n_out: int = 4000):
    """Integrate q'' + p(t)^2 q = 0, p = p0 (1 + amp sin eps t), q(0) = 1, q'(0) = 0 (DOP853,
    rtol 1e-11); return (t, numerical envelope sqrt(q^2 + (q'/p)^2))."""
    p = lambda t: p0 * (1 + amp * np.sin(eps * t))
    sol = solve_ivp(lambda t, y: [y[1], -p(t) ** 2 * y[0]], (0, t_end), [1.0, 0.0], method="DOP853",
                    rtol=1e-11, atol=1e-13, dense_output=True)
    t = np.linspace(0, t_end, n_out)
    q, v = sol.sol(t)
    return t, np.sqrt(q**2 + (v / p(t)) ** 2)


def slow_oscillator_turning_points(p0: float, eps: float, t_end: float, amp: float = 0.5):
    """Same integration; (t_i, |q(t_i)|) at the turning points q' = 0 (located by events)."""
    p = lambda t: p0 * (1 + amp * np.sin(eps * t))
    ev = lambda t, y: y[1]
    sol = solve_ivp(lambda t, y: [y[1], -p(t) ** 2 * y[0]], (0, t_end), [1.0, 0.0], method="DOP853",
                    rtol=1e-11, atol=1e-13, events=ev)
    t, y = sol.t_events[0], sol.y_events[0]
    keep = t > 0
    return t[keep], np.abs(y[keep, 0])
