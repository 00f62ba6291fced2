"""Closed-form rotordynamics references (independent of the finite elements).

Conventions: spin about +x; complex lateral position r = v + i w; a forward whirl r ~ e^{i omega t}
has omega > 0, a backward whirl omega < 0 (reported as |omega|).

* Textbook §5.12 (seed 001, (5.65)-(5.66)): a disc of mass m with eccentricity e on a shaft of
  stiffness c (no damping): the centre of mass runs on a circle of radius
  r = c e / |c - m w^2| = e / |1 - (w/w*)^2|, w* = sqrt(c/m).
* Tip stiffness of a massless Timoshenko cantilever (end force P, end moment M):
  v = P L^3/(3EI) + P L/(kGA) + M L^2/(2EI),  slope = P L^2/(2EI) + M L/(EI).
* Rigid disc (m, Id, Ip) on a massless shaft whose stiffness at the disc is [[k11, k12], [k12, k22]]
  (translation, tilt): with the tilt coordinate phi = theta_z - i theta_y,
      m r'' + k11 r + k12 phi = 0,   Id phi'' - i Ip Omega phi' + k12 r + k22 phi = 0,
  and r, phi ~ e^{i omega t}:  (k11 - m w^2)(k22 - Id w^2 + Ip Omega w) - k12^2 = 0,
  a quartic in w whose positive roots whirl forward and negative roots backward.
* Jeffcott rotor: massless shaft, disc at mid-span, supports at the ends.  Mid-span stiffness
  of a simply supported Timoshenko shaft: 1/k_s = L^3/(48 EI) + L/(4 kGA); bearings of stiffness
  k_b at both ends add in series: 1/k = 1/k_s + 1/(2 k_b), separately in y and z (two critical
  speeds with anisotropic bearings).  With a viscous damper c at the disc each direction is the
  SDOF m u'' + c u' + k u = m e Omega^2 cos(...), whose response u/e = s^2 / sqrt((1 - s^2)^2 + (2 zeta s)^2)
  peaks at s = 1 / sqrt(1 - 2 zeta^2); half-power speeds from the quadratic in u = s^2 below.
* Jeffcott with cross-coupled stiffness q (force -(k r - i q r) on r): m lam^2 + c lam + k - i q = 0
  is neutrally stable for q = c sqrt(k/m); with q = beta Omega the threshold speed is
  Omega_th = c sqrt(k/m) / beta.
* Simply supported spinning Timoshenko shaft (sin(n pi x / L) in both planes, q = n pi/L):
      (kGA q^2 - rho A w^2)(EI q^2 + kGA - rho I w^2 + rho Ip Omega w) - (kGA q)^2 = 0.
"""
from __future__ import annotations

import math

import numpy as np

#: Textbook §5.12 validation table (digest textbook_ch2-5.md): s = w/w* -> r/e as printed
TEXTBOOK_5_12 = (("0.5", "1.33333"), ("0.7", "1.96078"), ("0.9", "5.26316"), ("1.1", "4.76190"),
                 ("1.4", "1.04167"), ("2", "0.33333"), ("3", "0.125"), ("5", "0.041667"))
#: the operating band to avoid around the critical speed, printed in §5.12
TEXTBOOK_5_12_BAND = ("0.7", "1.4")

#: Friswell, Penny, Garvey & Lees, Dynamics of Rotating Machines (2010), Example 5.9.1: 6 Timoshenko
#: elements, 4000 rev/min: the five lowest lateral damped natural frequencies and the torsional one (rad/s)
FRISWELL_5_9_1_LATERAL = ("85.39", "87.80", "251.78", "294.71", "600.18")
FRISWELL_5_9_1_TORSION = "650.41"


def self_centring_ratio(s) -> np.ndarray:
    """(5.66): r/e = 1 / |1 - s^2|."""
    s = np.asarray(s, dtype=float)
    return 1.0 / np.abs(1.0 - s * s)


def cowper_solid(nu: float) -> float:
    return 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu)


def circle(d: float) -> tuple[float, float, float]:
    """A, I, Ip of a solid circle of diameter d."""
    A = math.pi * d * d / 4.0
    I = math.pi * d**4 / 64.0
    return A, I, 2.0 * I


def cantilever_tip_stiffness(E, G, kappa, A, I, L) -> tuple[float, float, float]:
    """(k11, k12, k22) of the tip (translation v, rotation dv/dx) of a massless Timoshenko cantilever."""
    c11 = L**3 / (3 * E * I) + L / (kappa * G * A)
    c12 = L**2 / (2 * E * I)
    c22 = L / (E * I)
    det = c11 * c22 - c12 * c12
    return c22 / det, -c12 / det, c11 / det


def disc_whirl_frequencies(m, Id, Ip, k11, k12, k22, speed) -> tuple[np.ndarray, np.ndarray]:
    """(forward, backward) whirl frequencies (rad/s, ascending) of the rigid disc on a massless shaft."""
    coeffs = [m * Id, -m * Ip * speed, -(m * k22 + Id * k11), k11 * Ip * speed, k11 * k22 - k12 * k12]
    roots = np.roots(coeffs)
    roots = roots[np.abs(roots.imag) <= 1e-9 * np.abs(roots)].real
    return np.sort(roots[roots > 0]), np.sort(-roots[roots < 0])


def simply_supported_midspan_stiffness(E, G, kappa, A, I, L) -> float:
    return 1.0 / (L**3 / (48 * E * I) + L / (4 * kappa * G * A))


def series(*k) -> float:
    return 1.0 / sum(1.0 / v for v in k)


def sdof_unbalance_peak(zeta: float) -> tuple[float, float, tuple[float, float]]:
    """(s_peak, amplitude u/e at the peak, (s1, s2) half-power) of u/e = s^2 / sqrt((1-s^2)^2 + (2 zeta s)^2).

    Peak amplitude 1 / (2 zeta sqrt(1 - zeta^2)); with P its square, the half-power points solve
    2 u^2 = P ((1 - u)^2 + 4 zeta^2 u), i.e. (2 - P) u^2 + P (2 - 4 zeta^2) u - P = 0 in u = s^2."""
    s_peak = 1.0 / math.sqrt(1.0 - 2.0 * zeta * zeta)
    a_peak = 1.0 / (2.0 * zeta * math.sqrt(1.0 - zeta * zeta))
    P = a_peak * a_peak
    a, b, c = 2.0 - P, P * (2.0 - 4.0 * zeta * zeta), -P
    disc = math.sqrt(b * b - 4 * a * c)
    u = sorted([(-b + disc) / (2 * a), (-b - disc) / (2 * a)])
    return s_peak, a_peak, (math.sqrt(u[0]), math.sqrt(u[1]))


def jeffcott_threshold(m: float, k: float, c: float, beta: float) -> float:
    """Onset speed of instability for a cross-coupled stiffness q = beta Omega: c sqrt(k/m) / beta."""
    return c * math.sqrt(k / m) / beta


def spinning_timoshenko_ss(E, G, kappa, rho, A, I, Ip, L, n: int, speed: float) -> tuple[float, float]:
    """(forward, backward) bending-branch whirl frequencies of mode n of a simply supported
    spinning Timoshenko shaft (rad/s): the lower positive and lower negative root of the quartic."""
    q = n * math.pi / L
    kGA = kappa * G * A
    p1 = np.array([-rho * A, 0.0, kGA * q * q])                     # kGA q^2 - rho A w^2
    p2 = np.array([-rho * I, rho * Ip * speed, E * I * q * q + kGA])  # EI q^2 + kGA - rho I w^2 + rho Ip Omega w
    poly = np.polysub(np.polymul(p1, p2), [(kGA * q) ** 2])
    roots = np.roots(poly)
    roots = roots[np.abs(roots.imag) <= 1e-9 * np.abs(roots)].real
    return float(np.min(roots[roots > 0])), float(np.min(-roots[roots < 0]))


# ---------------------------------------------------------------- Jeffcott rotor in a clearance ring
def annular_rub_radius(m: float, k: float, c: float, k_c: float, delta: float, mu: float, e: float,
                       speed: float, r_max: float) -> list[float]:
    """Radii R of the synchronous forward circular whirl of a Jeffcott rotor (mass m, shaft
    stiffness k, damping c, unbalance eccentricity e) in a compliant clearance ring (radial
    clearance delta, contact stiffness k_c, Coulomb friction mu at the contact): with z = R
    e^{i(Omega t - phi)} the contact force is -k_c (1 - delta/R)(1 + i mu) z (normal plus friction
    opposing the forward slip), so  |k - m Omega^2 + i c Omega + k_c (1 - delta/R)_+ (1 + i mu)| R
    = m e Omega^2.  All roots in (0, r_max] (a scan of 20 000 cells, each root refined by Brent)."""
    from scipy.optimize import brentq

    F = m * e * speed ** 2

    def g(R):
        a = k_c * (1 - delta / R) if R > delta else 0.0
        return abs(k - m * speed ** 2 + 1j * c * speed + a * (1 + 1j * mu)) * R - F

    grid = np.linspace(r_max * 1e-6, r_max, 20_001)
    val = np.array([g(R) for R in grid])
    return [brentq(g, grid[i], grid[i + 1], xtol=1e-300, rtol=4 * np.finfo(float).eps)
            for i in range(grid.size - 1) if val[i] * val[i + 1] < 0]


def annular_rub_force_rigid(m: float, k: float, c: float, delta: float, mu: float, e: float, speed: float) -> float:
    """Normal force N of the full annular rub of a Jeffcott rotor on a rigid ring (orbit radius =
    delta): (k - m Omega^2 + i c Omega) delta + N (1 + i mu) = m e Omega^2 e^{i phi}, so N is the
    non-negative root of (1 + mu^2) N^2 + 2 (a + mu b) N + a^2 + b^2 - F^2 = 0 with a = (k - m
    Omega^2) delta, b = c Omega delta, F = m e Omega^2 (nan when there is none)."""
    a, b, F = (k - m * speed ** 2) * delta, c * speed * delta, m * e * speed ** 2
    A, B, C = 1 + mu * mu, 2 * (a + mu * b), a * a + b * b - F * F
    disc = B * B - 4 * A * C
    if disc < 0:
        return float("nan")
    roots = [(-B + s * np.sqrt(disc)) / (2 * A) for s in (1.0, -1.0)]
    pos = [r for r in roots if r >= 0]
    return float(max(pos)) if pos else float("nan")
