"""Independent references for vibration protection (textbook ch. 6; digest textbook_ch6-9.md §6.4-6.7).

Closed forms written out from the book's equations and dense complex solves of the 1- and 2-DOF models;
nothing here imports the package.
"""
from __future__ import annotations

import math

import numpy as np


def sdof_transmitted_force(z, delta: float):
    """|c q + b q'| / F_0 for m q'' + b q' + c q = F_0 e^{i omega t}, delta = b/(2 sqrt(c m)) (dense solve)."""
    z = np.asarray(z, dtype=float)
    c, m = 1.0, 1.0
    b = 2 * delta
    q = 1.0 / (c - m * z**2 + 1j * z * b)
    return np.abs((c + 1j * z * b) * q)


def two_dof_amplitudes(m1, c1, m2, c2, omega, F1=1.0, b=0.0):
    """(A_1, A_2) of the main mass / absorber system by a dense complex solve."""
    w = omega
    D = np.array([[c1 + c2 + 1j * w * b - m1 * w * w, -(c2 + 1j * w * b)],
                  [-(c2 + 1j * w * b), c2 + 1j * w * b - m2 * w * w]])
    return np.linalg.solve(D, np.array([F1, 0.0], dtype=complex))


def two_dof_frequencies(m1, c1, m2, c2):
    """Natural frequencies from numpy's eigvals of M^-1 K (fine for a 2x2 reference)."""
    K = np.array([[c1 + c2, -c2], [-c2, c2]])
    return np.sort(np.sqrt(np.linalg.eigvals(np.linalg.solve(np.diag([m1, m2]), K)).real))


def unloading_least_squares_grid(pi, dpi, reaction, n: int = 20000):
    """(u_0, c_0) minimising the discrete sum of (R* + u_0 + c_0 Pi)^2 |Pi'| over a fine uniform phase grid
    (numpy lstsq on sqrt-weighted rows): an independent discretisation of (6.35)."""
    phi = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    w = np.sqrt(np.abs(dpi(phi)))
    A = np.column_stack([w, w * pi(phi)])
    rhs = -w * reaction(phi)
    sol, *_ = np.linalg.lstsq(A, rhs, rcond=None)
    return float(sol[0]), float(sol[1])


def kappa_direct(omega, M, c0, c1, r, unbalance, b):
    """Platform amplitude over A* from (6.40) solved as a complex 1-DOF equation with resistance b."""
    F = c1 * r - omega**2 * unbalance
    A = abs(F / (c0 + c1 - M * omega**2 + 1j * omega * b))
    return A / (c1 * r / (c0 + c1))
