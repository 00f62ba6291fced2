"""The textbook's quick estimates of steady forced response (reported against the exact steady state).

Harmonic linearisation (textbook §8.3, (8.13)): a nonlinear force U(q, q') of q = A0 + A sin phi is
replaced by ``U0 + 2n(A) q' + k^2(A) q`` with the first-harmonic coefficients

* cubic  c0 q (1 + xi q^2):            k^2 = c0 (1 + 0.75 xi A^2)                    (8.22)
* Coulomb P sign q':                    b_eq = 4P/(pi A omega)                        (§9.2)
* symmetric backlash +-Delta, c outside: k^2 = c [1 - (2/pi)(asin d + d sqrt(1 - d^2))], d = Delta/A
* bilinear c1 (q > 0), c2 (q < 0):      k^2 = (c1 + c2)/2, U0 = (c1 - c2) A / pi
* one-sided spring c (q > 0 only):      k^2 = c/2, U0 = c A / pi

(coefficients per unit of the generalised coordinate; divide by the inertia for (8.8)).
Forced response of the linearised system, (8.15)/(8.17): ``A^2 [(k^2(A) - m w^2)^2 + (b(A) w)^2] = F^2``.

Energy balance (textbook §5.13, (5.69)-(5.76)): at resonance (gamma = pi/2) the input per cycle
``pi A F0`` equals the losses ``pi b w A^2 + 4 P A`` (viscous b, Coulomb P), so
``A* = (pi F0 - 4 P) / (pi b w)``  ((5.76) with psi c = 2 pi b w).
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import brentq
from ..errors import ModelError


def hl_cubic(c0: float, xi: float, A):
    return c0 * (1 + 0.75 * xi * np.asarray(A, float) ** 2)


def hl_coulomb(P: float, A, omega):
    """Equivalent viscous coefficient of Coulomb friction P sign q'."""
    return 4 * P / (np.pi * np.asarray(A, float) * omega)


def hl_backlash(c: float, delta: float, A):
    A = np.asarray(A, float)
    d = np.clip(delta / np.where(A > 0, A, np.inf), 0, 1)
    return np.where(A > delta, c * (1 - 2 / np.pi * (np.arcsin(d) + d * np.sqrt(1 - d * d))), 0.0)


def hl_bilinear(c1: float, c2: float, A):
    """(k^2, U0) of the bilinear spring c1 (q > 0), c2 (q < 0), about q = 0."""
    A = np.asarray(A, float)
    return 0.5 * (c1 + c2) + 0 * A, (c1 - c2) * A / np.pi


def hl_one_sided(c: float, A):
    return hl_bilinear(c, 0.0, A)


def hl_forced_amplitudes(m: float, b: float, k_of_A, F: float, omega: float, coulomb: float = 0.0,
                         A_max: float = 1e3, n_scan: int = 4000):
    """All roots A of (8.17) ``A^2[(k^2(A) - m w^2)^2 + (b_eq(A) w)^2] = F^2`` with
    ``b_eq = b + 4 coulomb / (pi A w)`` (harmonic linearisation), found by scanning + Brent."""
    def g(A):
        if A <= 0:
            return -F * F
        beq = b + (4 * coulomb / (np.pi * A * omega) if coulomb else 0.0)
        return A * A * ((k_of_A(A) - m * omega ** 2) ** 2 + (beq * omega) ** 2) - F * F

    As = np.geomspace(1e-9 * max(A_max, 1), A_max, n_scan)
    vals = np.array([g(a) for a in As])
    roots = []
    for i in range(n_scan - 1):
        if np.sign(vals[i]) != np.sign(vals[i + 1]):
            roots.append(brentq(g, As[i], As[i + 1], xtol=1e-14, rtol=1e-13))
    return roots


def coulomb_hl_amplitude(m: float, k: float, P: float, F0: float, omega: float):
    """Harmonic-linearisation amplitude of m x'' + k x + P sign x' = F0 sin w t (closed form):
    ``A = (F0/|k - m w^2|) sqrt(1 - (4P/(pi F0))^2)``."""
    r = 4 * P / (np.pi * F0)
    if r >= 1:
        return 0.0
    return F0 / abs(k - m * omega ** 2) * np.sqrt(1 - r * r)


def energy_balance_resonance(F0: float, b: float, omega: float, P: float = 0.0):
    """Resonant amplitude from the energy balance (5.75)-(5.76): pi A F0 = pi b w A^2 + 4 P A."""
    return max((np.pi * F0 - 4 * P) / (np.pi * b * omega), 0.0)


def backbone_book(k0: float, xi: float, A):
    """Backbone of the cubic oscillator by harmonic linearisation, w = k0 sqrt(1 + 0.75 xi A^2)."""
    return k0 * np.sqrt(1 + 0.75 * xi * np.asarray(A, float) ** 2)


def energy_balance_amplitude(F0: float, omega: float, viscous: float = 0.0, coulomb: float = 0.0,
                             quadratic: float = 0.0) -> float:
    """Resonant amplitude from the energy balance per cycle (textbook §5.13) with the losses of the
    combined power law (seed 002): ``pi F0 A = 4 P A + pi b w A^2 + (8/3) c2 w^2 A^3`` (Coulomb P,
    viscous b, quadratic c2 sign(v) v^2; the works over one cycle of A sin(w t))."""
    a3 = 8.0 / 3.0 * quadratic * omega ** 2
    a2 = np.pi * viscous * omega
    a1 = 4 * coulomb - np.pi * F0
    if a1 >= 0:
        return 0.0
    if a3 == 0:
        return -a1 / a2 if a2 > 0 else float("inf")
    return float((-a2 + np.sqrt(a2 * a2 - 4 * a3 * a1)) / (2 * a3))


def subharmonic_third(k0: float, xi: float, omega: float, a: float = 1.0) -> tuple[float, float, float]:
    """The textbook's estimate of the 1/3 subharmonic of q'' + 2 n0 q' + k0^2 q (1 + xi q^2) = (F3/a) cos 3 omega t
    (§8.4): the amplitude on the backbone (8.33) ``A1 = 2 sqrt((omega^2 - k0^2) / (3 xi k0^2))``, the third
    harmonic's share (8.28) ``alpha = 0.25 xi k0^2 A1^2 / (9 k^2(A1) - k0^2)`` with k(A1) = omega, and the
    threshold (8.32) per unit force ``psi*/F3 = 6 pi alpha / (a k0^2 A1 (1 + 0.5 xi A1^2))``: the subharmonic
    can exist only for a dissipation coefficient psi < psi*.  (8.28) follows from the corrected second line of
    (8.27), whose sign before 0.25 xi k0^2 A1^2 (A1 + 6 A3) is printed '+' (the harmonic balance gives '-').
    Returns (A1, alpha, psi*/F3); omega must lie above k0 (hardening, xi > 0) for a real A1."""
    if not (xi > 0 and omega > k0 > 0 and a > 0):
        raise ModelError("subharmonic_third", "omega", omega,
                         f"omega > k0 = {k0!r} with xi > 0 and a > 0 (a point of the hardening backbone)")
    A1 = 2.0 * np.sqrt((omega ** 2 - k0 ** 2) / (3.0 * xi * k0 ** 2))
    alpha = 0.25 * xi * k0 ** 2 * A1 ** 2 / (9.0 * omega ** 2 - k0 ** 2)
    psi_per_F3 = 6.0 * np.pi * alpha / (a * k0 ** 2 * A1 * (1.0 + 0.5 * xi * A1 ** 2))
    return float(A1), float(alpha), float(psi_per_F3)
