"""Simply supported uniform Timoshenko beam (exact), and Cowper's shear coefficient.

Not in the book (which stops at Euler-Bernoulli, §4.11); derived here as an independent
reference for shear-deformable beam elements.  Equations of motion::

    rho A w_tt   = kappa G A (w_x - phi)_x
    rho I phi_tt = E I phi_xx + kappa G A (w_x - phi)

With ``w = W sin(q x) e^{i omega t}``, ``phi = Phi cos(q x) e^{i omega t}``, ``q = r pi / L``
(this satisfies ``w = 0`` and ``M = EI phi_x = 0`` at both ends)::

    [ kappa G A q^2 - rho A omega^2     -kappa G A q                      ] [W  ]   [0]
    [ -kappa G A q                      E I q^2 + kappa G A - rho I omega^2] [Phi] = [0]

and setting its determinant to zero gives a quadratic in ``u = omega^2``::

    (rho^2 A I) u^2 - (X + Y + Z) u + kappa G A E I q^4 = 0,
    X = rho A E I q^2,  Y = rho I kappa G A q^2,  Z = rho A kappa G A,

whose product of roots is ``X Y / (rho^2 A I)^2`` and whose discriminant
``(X - Y)^2 + Z^2 + 2 Z (X + Y)`` is a sum of positive terms (no cancellation).
"""
from __future__ import annotations

import numpy as np


def timoshenko_ss_omegas_both(E, G, kappa, rho, A, I, length, n) -> np.ndarray:
    """Both branches ``(omega_bending, omega_shear)`` for modes ``r = 1..n``, shape ``(n, 2)``.

    Roots of the quadratic in the module docstring; the lower (bending) root is taken from
    Vieta's product so it stays accurate for very slender beams.
    """
    q = np.arange(1, n + 1, dtype=float) * np.pi / length
    kGA = kappa * G * A
    X = rho * A * E * I * q**2
    Y = rho * I * kGA * q**2
    Z = rho * A * kGA
    a = rho**2 * A * I
    c = kGA * E * I * q**4
    root = np.sqrt((X - Y) ** 2 + Z**2 + 2.0 * Z * (X + Y))
    u_high = (X + Y + Z + root) / (2.0 * a)
    u_low = c / (a * u_high)
    return np.sqrt(np.column_stack([u_low, u_high]))


def timoshenko_ss_omegas(E, G, kappa, rho, A, I, length, n) -> np.ndarray:
    """Exact bending-branch natural frequencies [rad/s] of a simply supported Timoshenko beam.

    Tends to the Euler-Bernoulli ``(r pi / L)^2 sqrt(E I / (rho A))`` (4.65) for slender beams
    and lies below it when shear and rotary inertia are included.
    """
    return timoshenko_ss_omegas_both(E, G, kappa, rho, A, I, length, n)[:, 0]


def cowper_shear_coefficient(nu: float, inner_to_outer: float = 0.0) -> float:
    """Cowper (1966) shear coefficient of a solid (``m = 0``) or hollow circular section.

    ``kappa = 6 (1 + nu) (1 + m^2)^2 / ((7 + 6 nu) (1 + m^2)^2 + (20 + 12 nu) m^2)``,
    ``m = inner_to_outer`` diameter ratio.  Solid: ``6 (1 + nu) / (7 + 6 nu)``; thin tube
    (``m -> 1``): ``2 (1 + nu) / (4 + 3 nu)``.
    """
    m2 = inner_to_outer**2
    return float(6.0 * (1.0 + nu) * (1.0 + m2) ** 2
                 / ((7.0 + 6.0 * nu) * (1.0 + m2) ** 2 + (20.0 + 12.0 * nu) * m2))
