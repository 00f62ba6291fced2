"""Closed forms for psi in the time domain (textbook §9.1, (9.3), (9.11)-(9.18); §4.2 (4.15)-(4.16)).

* :func:`book_modal_2dof` follows the book's own route literally for two DOFs: the roots of the
  frequency equation det(c - k^2 a) = 0 by the quadratic formula, form coefficients with beta_1r = 1
  (not mass-normalised), a* = beta^T a beta, c* = beta^T c beta, psi_r* (9.14), b_r* (9.15) and
  b = (beta^T)^-1 b* beta^-1 (9.18) with explicit 2x2 inverses.  It shares no code with
  :mod:`discrete.linear.dissipation` (mass-normalised modes from a sparse eigen-solver,
  M Phi diag Phi^T M).
* :func:`viscous_decrement` and :func:`energy_loss_per_cycle`: the exact free decay of a viscous
  oscillator with ratio zeta, x(t) = e^{-zeta k t} (A cos k_d t + B sin k_d t), k_d = k sqrt(1 - zeta^2):
  state (x, v) scales by exp(-lambda) over each damped period 2 pi/k_d, lambda = 2 pi zeta / sqrt(1 - zeta^2),
  so the energy by exp(-2 lambda) from any instant to the same phase one period later.  The (9.3)
  equivalent at omega_ref = k has zeta = psi/(4 pi).
"""
from __future__ import annotations

import math

import numpy as np


def book_modal_2dof(a, c, psi) -> dict:
    """(9.11)-(9.18) for a 2-DOF system whose coordinates are the deformations of its two elastic
    elements (c diagonal, element j with stiffness c_jj and dissipation coefficient psi_j)."""
    a, c = np.asarray(a, float), np.asarray(c, float)
    psi = np.asarray(psi, float)
    # det(c - u a) = A u^2 + B u + D = 0, u = k^2
    A = a[0, 0] * a[1, 1] - a[0, 1] * a[1, 0]
    B = -(c[0, 0] * a[1, 1] + c[1, 1] * a[0, 0] - c[0, 1] * a[1, 0] - c[1, 0] * a[0, 1])
    D = c[0, 0] * c[1, 1] - c[0, 1] * c[1, 0]
    disc = math.sqrt(B * B - 4 * A * D)
    u = np.array([(-B - disc) / (2 * A), (-B + disc) / (2 * A)])
    k = np.sqrt(u)
    # first row of (c - u a) beta = 0 with beta_1r = 1
    beta = np.array([[1.0, 1.0], -(c[0, 0] - u * a[0, 0]) / (c[0, 1] - u * a[0, 1])])
    a_star = np.diag(beta.T @ a @ beta)
    c_star = np.diag(beta.T @ c @ beta)
    cj = np.diag(c)
    psi_star = (psi[:, None] * cj[:, None] * beta**2).sum(0) / (cj[:, None] * beta**2).sum(0)      # (9.14)
    b_star = psi_star * c_star / (2 * math.pi * k)                                                 # (9.15)
    det = beta[0, 0] * beta[1, 1] - beta[0, 1] * beta[1, 0]
    beta_inv = np.array([[beta[1, 1], -beta[0, 1]], [-beta[1, 0], beta[0, 0]]]) / det
    b = beta_inv.T @ np.diag(b_star) @ beta_inv                                                    # (9.18)
    return {"k": k, "beta": beta, "a_star": a_star, "c_star": c_star, "psi_star": psi_star, "b_star": b_star, "b": b}


def viscous_decrement(zeta):
    """Logarithmic decrement per damped period of a viscous oscillator: 2 pi zeta / sqrt(1 - zeta^2)."""
    zeta = np.asarray(zeta, float)
    return 2 * np.pi * zeta / np.sqrt(1 - zeta**2)


def equivalent_zeta(psi, omega_ratio=1.0):
    """Viscous ratio of (9.3) b = psi c/(2 pi omega_ref) on an oscillator of frequency k:
    zeta = b/(2 m k) = psi/(4 pi) * k/omega_ref (``omega_ratio`` = k/omega_ref)."""
    return np.asarray(psi, float) * omega_ratio / (4 * np.pi)


def energy_loss_per_cycle(psi, omega_ratio=1.0):
    """Delta E / E over one damped period of the (9.3) equivalent: 1 - exp(-2 lambda); = psi - psi^2/2 + O(psi^3)
    at omega_ref = k."""
    return -np.expm1(-2 * viscous_decrement(equivalent_zeta(psi, omega_ratio)))


def amplitude_after(psi, periods: float):
    """Envelope exp(-lambda n) of the (9.3) equivalent (omega_ref = k) after ``periods`` damped periods,
    and -- for comparison -- (1 - psi)^(n/2) of the exact free-decay definition psi = 1 - (A2/A1)^2 (4.16)."""
    lam = viscous_decrement(equivalent_zeta(psi))
    return float(np.exp(-lam * periods)), float((1 - psi) ** (periods / 2))
