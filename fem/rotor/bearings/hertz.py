"""Hertzian load-deflection of a rolling element between its races: Q = K delta^n.

**Point contact (ball, n = 3/2).**  Two bodies with principal curvatures rho_1I, rho_1II (ball)
and rho_2I, rho_2II (race; concave negative) in the planes I (rolling) and II (transverse):
curvature sum S = sum rho = 1/R, curvature difference F = [(rho_1I - rho_1II) + (rho_2I - rho_2II)]/S.
The contact ellipse's aspect ratio kappa = a/b follows from

    F = [(kappa^2 + 1) E(m) - 2 K(m)] / [(kappa^2 - 1) E(m)],   m = 1 - 1/kappa^2

(complete elliptic integrals of the first and second kind K, E with parameter m), and the mutual
approach is  delta = K(m) [9 / (2 E(m) R) (Q / (pi kappa E'))^2]^(1/3),  2/E' = (1 - nu_1^2)/E_1 +
(1 - nu_2^2)/E_2 (Harris & Kotzalas, *Rolling Bearing Analysis* 5th ed. (2007), vol. 1 ch. 6;
Hamrock & Dowson, *Ball Bearing Lubrication* (1981) ch. 3), i.e.

    Q = K delta^(3/2),   K = pi kappa E' sqrt(2 E(m) R / 9) / K(m)^(3/2).

The ellipticity is solved from F exactly (Brent's method on kappa; scipy's ellipk/ellipe).  A
ball touches the inner and the outer race; the two approaches add, so the element's constant is
K_n = [K_i^(-2/3) + K_o^(-2/3)]^(-3/2) (Harris ch. 7).

**Line contact (roller, n = 10/9).**  Palmgren's load-deflection of a roller of effective length
l: delta = 3.84e-5 Q^0.9 / l^0.8 (mm, N; Palmgren, *Ball and Roller Bearing Engineering* (1959),
quoted in Harris ch. 6), the same law at both races: K_n = K_c 2^(-10/9),
K_c = (l^0.8 / 3.84e-5)^(1/0.9) in N/mm^(10/9).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

from discrete.errors import ModelError


@dataclass
class PointContact:
    """One Hertzian point contact: ``K`` (N/m^1.5: Q = K delta^1.5), the ellipticity ``kappa`` =
    a/b, the elliptic integrals ``K_m``, ``E_m``, the curvature sum ``curvature_sum`` (1/m) and
    difference ``curvature_difference``, the effective modulus ``E_eff`` E' (Pa)."""

    K: float
    kappa: float
    K_m: float
    E_m: float
    curvature_sum: float
    curvature_difference: float
    E_eff: float

    def deflection(self, Q: float) -> float:
        """delta (m) at the load Q (N)."""
        return (Q / self.K) ** (2.0 / 3.0)


def effective_modulus(E1: float, nu1: float, E2: float, nu2: float) -> float:
    """E' = 2 / [(1 - nu1^2)/E1 + (1 - nu2^2)/E2]."""
    return 2.0 / ((1 - nu1 * nu1) / E1 + (1 - nu2 * nu2) / E2)


def point_contact(rho_1I: float, rho_1II: float, rho_2I: float, rho_2II: float, E_eff: float) -> PointContact:
    """The Hertzian constant of a point contact from the four principal curvatures (1/m)."""
    S = rho_1I + rho_1II + rho_2I + rho_2II
    if not S > 0:
        raise ModelError("rolling-element bearing", "geometry", S, "a convex contact (curvature sum > 0): check the "
                         "groove conformity (> 0.5) and the diameters")
    F = abs((rho_1I - rho_1II) + (rho_2I - rho_2II)) / S
    if F < 1e-12:
        kappa = 1.0
        K_m = E_m = 0.5 * math.pi
    else:
        def residual(k):
            m = 1.0 - 1.0 / (k * k)
            return ((k * k + 1) * ellipe(m) - 2 * ellipk(m)) / ((k * k - 1) * ellipe(m)) - F

        if F >= 1.0 - 1e-15:
            raise ModelError("rolling-element bearing", "geometry", F, "a point contact (curvature difference < 1)")
        kappa = brentq(residual, 1.0 + 1e-9, 1e4, xtol=1e-14, rtol=1e-15)
        m = 1.0 - 1.0 / (kappa * kappa)
        K_m, E_m = float(ellipk(m)), float(ellipe(m))
    R = 1.0 / S
    K = math.pi * kappa * E_eff * math.sqrt(2.0 * E_m * R / 9.0) / K_m ** 1.5
    return PointContact(K=K, kappa=kappa, K_m=K_m, E_m=E_m, curvature_sum=S, curvature_difference=F, E_eff=E_eff)


def ball_contacts(ball_diameter: float, pitch_diameter: float, inner_conformity: float, outer_conformity: float,
                  contact_angle: float, E_eff: float) -> tuple[PointContact, PointContact]:
    """(inner, outer) point contacts of a ball (Harris ch. 2: gamma = D cos(alpha) / d_m; groove
    radii r = f D)."""
    D = ball_diameter
    g = D * math.cos(contact_angle) / pitch_diameter
    inner = point_contact(2 / D, 2 / D, 2 / D * g / (1 - g), -1 / (inner_conformity * D), E_eff)
    outer = point_contact(2 / D, 2 / D, -2 / D * g / (1 + g), -1 / (outer_conformity * D), E_eff)
    return inner, outer


def series_constant(K_inner: float, K_outer: float, exponent: float) -> float:
    """The element's constant of two contacts in series, Q = K_n (delta_i + delta_o)^n."""
    return ((1.0 / K_inner) ** (1.0 / exponent) + (1.0 / K_outer) ** (1.0 / exponent)) ** (-exponent)


def roller_constant(effective_length: float) -> float:
    """Palmgren's line contact of one race, Q = K_c delta^(10/9) in SI (N/m^(10/9))."""
    l_mm = effective_length * 1e3
    K_mm = (l_mm ** 0.8 / 3.84e-5) ** (1.0 / 0.9)            # N / mm^(10/9)
    return K_mm * 1e3 ** (10.0 / 9.0)
