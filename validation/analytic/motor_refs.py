"""Independent references for the motor as a model element (textbook §5.10, (3.15), §10.6).

Catalogue conversion written out from §5.10, the characteristic polynomials of the rotor alone and of
the two-inertia drive with the motor (numpy.roots), and a dense complex solve of the forced drive with
the motor's dynamic stiffness Z = i omega b/(1 + i omega T).  Nothing here imports the package.
"""
from __future__ import annotations

import math

import numpy as np


def catalogue(f_mains, pole_pairs, slip_nominal, torque_nominal, torque_ratio):
    """(omega0, s_k, T, nu, c_d, b_d, n) from the §5.10 formulas."""
    omega0 = 2 * math.pi * f_mains / pole_pairs
    xi = torque_ratio
    sk = slip_nominal * (xi + math.sqrt(xi * xi + 1))
    T = 1 / (2 * math.pi * f_mains * sk)
    nu = sk / (2 * torque_nominal * xi)
    return {"omega0": omega0, "s_k": sk, "T": T, "nu": nu, "c_d": 1 / (nu * omega0 * T), "b_d": 1 / (nu * omega0),
            "n": 0.5 / T}


def rotor_roots(omega0, nu, T, J):
    """Roots of s^2 + s/T + 1/(nu T J omega0) = 0 ((5.58) with the term k^2 Delta omega)."""
    return np.roots([1.0, 1.0 / T, 1.0 / (nu * T * J * omega0)])


def drive_roots(omega0, nu, T, J0, J1, c1):
    """Non-zero roots of det [[J0 s^2 + c1 + Z(s), -c1], [-c1, J1 s^2 + c1]] = 0, Z = s b/(1 + s T),
    b = 1/(nu omega0), multiplied by (1 + s T): a degree-5 polynomial with one root s = 0."""
    b = 1 / (nu * omega0)
    P = np.polynomial.Polynomial
    one_sT = P([1.0, T])
    a11 = P([c1, 0.0, J0]) * one_sT + P([0.0, b])
    a22 = P([c1, 0.0, J1])
    det = a11 * a22 - c1**2 * one_sT
    return det.roots()


def drive_forced(omega, omega0, nu, T, J0, J1, c1, delta1, M1=1.0):
    """(a_rotor, a_load, M_D) of the §10.6 drive under M1 on the load: dense complex solve with Z(omega)."""
    b = 1 / (nu * omega0)
    Z = 1j * omega * b / (1 + 1j * omega * T)
    ct = c1 * (1 + 2j * delta1)
    A = np.array([[Z + ct - J0 * omega**2, -ct], [-ct, ct - J1 * omega**2]])
    x = np.linalg.solve(A, np.array([0.0, M1], dtype=complex))
    return x[0], x[1], -Z * x[0]


def drive_forced_condition(omega, omega0, nu, T, J0, J1, c1, delta1) -> float:
    """2-norm condition number of the dense dynamic stiffness of :func:`drive_forced` at ``omega``: two
    backward-stable solves of the same system differ by O(cond * eps) relative (Higham, Accuracy and
    Stability of Numerical Algorithms, §7.1), which is the round-off tolerance of comparisons against it."""
    b = 1 / (nu * omega0)
    Z = 1j * omega * b / (1 + 1j * omega * T)
    ct = c1 * (1 + 2j * delta1)
    return float(np.linalg.cond(np.array([[Z + ct - J0 * omega**2, -ct], [-ct, ct - J1 * omega**2]])))
