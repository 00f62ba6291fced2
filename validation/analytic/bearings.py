"""Closed forms of bearings, written independently of :mod:`fem.rotor.bearings`.

Fluid films (dimensionless force f = F c^2 / (mu omega R^4) on a journal at eccentricity ratio e,
a Guembel (half-Sommerfeld) film):

* short bearing (Ocvirk; Dubois & Ocvirk, NACA Report 1157 (1953); Hamrock, Schmid & Jacobson,
  *Fundamentals of Machine Elements* §12): F_r = mu U L^3 e^2 / (c^2 (1 - e^2)^2),
  F_t = pi mu U L^3 e / (4 c^2 (1 - e^2)^1.5), U = omega R;
* long bearing (Sommerfeld, half-Sommerfeld film; Hamrock et al. §12): F_r = 12 mu U R^2 L e^2 /
  (c^2 (2 + e^2)(1 - e^2)), F_t = 6 pi mu U R^2 L e / (c^2 (2 + e^2) sqrt(1 - e^2));
* the short bearing's load capacity W = mu omega R L^3 e sqrt(pi^2 (1 - e^2) + 16 e^2) / (4 c^2 (1 - e^2)^2)
  and its 8 dimensionless coefficients K = (W/c) a, C = (W/(c omega)) b (Friswell, Penny, Garvey &
  Lees, *Dynamics of Rotating Machines* (2010) §5.5.2; u across, v along the load);
* the stability threshold of a symmetric rotor on two identical bearings (Lund, J. Appl. Mech. 32
  (1965) 911-920; Childs, *Turbomachinery Rotordynamics* (1993) §3): at neutral stability the
  whirl frequency nu = gamma omega and each bearing acts as a real spring K_eq, with
  K_eq = (K_xx C_yy + K_yy C_xx - K_xy C_yx - K_yx C_xy) / (C_xx + C_yy),
  gamma^2 omega^2 = ((K_xx - K_eq)(K_yy - K_eq) - K_xy K_yx) / (C_xx C_yy - C_xy C_yx);
  for a disc m on a massless shaft of mid-span stiffness k_s with journals m_j the symmetric mode's
  threshold solves K_eq = m_j nu^2 + (k_s / 2) m nu^2 / (k_s - m nu^2) (derived in the case);
* the squeeze-film damper on a circular centred orbit (radius e c, whirl w): pi film
  F_r = -2 mu R L^3 e^2 w / (c^2 (1 - e^2)^2), F_t = -pi mu R L^3 e w / (2 c^2 (1 - e^2)^1.5);
  2 pi film F_r = 0, F_t = -pi mu R L^3 e w / (c^2 (1 - e^2)^1.5) (San Andres, *Squeeze film
  dampers* (2010) §2; Vance (1988) §6).

Rolling elements:

* Sjoevall's integral of the load zone (Harris & Kotzalas (2007) vol. 1 ch. 7):
  F_r = Z K_n delta_max^n J_r(eps), J_r = (1/2 pi) int (1 - (1 - cos psi)/(2 eps))^n cos psi dpsi
  over the loaded arc, eps = (1 - P_d / (2 delta_r)) / 2; for zero clearance eps = 1/2 and
  1 / J_r = 4.37 (balls), 4.08 (rollers): Stribeck's Q_max = 4.37 F_r / Z (NSK technical report
  E728g §5, Table 1; Harris ch. 7);
* the Brewe-Hamrock approximations of a point contact (Brewe & Hamrock, J. Lubr. Technol. 99
  (1977) 485-487; Hamrock & Dowson, *Ball Bearing Lubrication* (1981) ch. 3): kappa = 1.0339
  (R_y/R_x)^0.636, E = 1.0003 + 0.5968 R_x/R_y, K = 1.5277 + 0.6023 ln(R_y/R_x).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq


def ocvirk_forces(eps: float, length_ratio: float) -> tuple[float, float]:
    """(F_r, F_t) / (mu omega R^4 / c^2) of the short bearing (F_r towards the bearing centre)."""
    LR = 2.0 * length_ratio
    return LR ** 3 * eps ** 2 / (1 - eps ** 2) ** 2, math.pi * LR ** 3 * eps / (4 * (1 - eps ** 2) ** 1.5)


def sommerfeld_forces(eps: float, length_ratio: float) -> tuple[float, float]:
    """(F_r, F_t) / (mu omega R^4 / c^2) of the long bearing with Guembel's film."""
    LR = 2.0 * length_ratio
    return (12 * LR * eps ** 2 / ((2 + eps ** 2) * (1 - eps ** 2)),
            6 * math.pi * LR * eps / ((2 + eps ** 2) * math.sqrt(1 - eps ** 2)))


def sommerfeld_forces_by_quadrature(eps: float) -> tuple[float, float]:
    """The same per unit length ratio, by quadrature of Sommerfeld's pressure (a check of the closed form)."""
    P = lambda t: 6 * eps * math.sin(t) * (2 + eps * math.cos(t)) / ((2 + eps ** 2) * (1 + eps * math.cos(t)) ** 2)  # noqa: E731
    return (-quad(lambda t: P(t) * math.cos(t), 0, math.pi, epsabs=0, epsrel=1e-13)[0],
            quad(lambda t: P(t) * math.sin(t), 0, math.pi, epsabs=0, epsrel=1e-13)[0])


def short_load(eps: float, mu: float, omega: float, R: float, L: float, c: float) -> float:
    """Load capacity W (N) of the short bearing at eccentricity ratio eps."""
    return mu * omega * R * L ** 3 * eps * math.sqrt(math.pi ** 2 * (1 - eps ** 2) + 16 * eps ** 2) / (4 * c * c * (1 - eps ** 2) ** 2)


def short_eccentricity(W: float, mu: float, omega: float, R: float, L: float, c: float) -> float:
    """The eccentricity ratio at which the short bearing carries W."""
    return brentq(lambda e: short_load(e, mu, omega, R, L, c) - W, 1e-12, 1 - 1e-12, xtol=1e-15, rtol=1e-15)


def short_coefficients(eps: float) -> tuple[np.ndarray, np.ndarray]:
    """(a, b): dimensionless stiffness and damping of the short bearing, rows/columns (u, v), u across
    the load and v along it (Friswell et al. 2010, §5.5.2)."""
    e2 = eps * eps
    h0 = 1.0 / (math.pi ** 2 * (1 - e2) + 16 * e2) ** 1.5
    s = math.sqrt(1 - e2)
    a = h0 * np.array([[4 * (math.pi ** 2 * (2 - e2) + 16 * e2),
                        math.pi * (math.pi ** 2 * (1 - e2) ** 2 - 16 * e2 * e2) / (eps * s)],
                       [-math.pi * (math.pi ** 2 * (1 - e2) * (1 + 2 * e2) + 32 * e2 * (1 + e2)) / (eps * s),
                        4 * (math.pi ** 2 * (1 + 2 * e2) + 32 * e2 * (1 + e2) / (1 - e2))]])
    buv = -8 * (math.pi ** 2 * (1 + 2 * e2) - 16 * e2)
    b = h0 * np.array([[2 * math.pi * s * (math.pi ** 2 * (1 + 2 * e2) - 16 * e2) / eps, buv],
                       [buv, 2 * math.pi * (math.pi ** 2 * (1 - e2) ** 2 + 48 * e2) / (eps * s)]])
    return a, b


def lund_equivalent(K: np.ndarray, C: np.ndarray) -> tuple[float, float]:
    """(K_eq, nu^2): the bearing's real equivalent stiffness and the squared whirl frequency at
    neutral stability (Lund 1965), from any consistent K (N/m) and C (N s/m)."""
    keq = (K[0, 0] * C[1, 1] + K[1, 1] * C[0, 0] - K[0, 1] * C[1, 0] - K[1, 0] * C[0, 1]) / (C[0, 0] + C[1, 1])
    nu2 = ((K[0, 0] - keq) * (K[1, 1] - keq) - K[0, 1] * K[1, 0]) / (C[0, 0] * C[1, 1] - C[0, 1] * C[1, 0])
    return keq, nu2


def jeffcott_short_threshold(m: float, m_j: float, k_s: float, W: float, mu: float, R: float, L: float, c: float,
                             lo: float, hi: float, n: int = 400) -> tuple[float, float]:
    """(threshold speed, whirl frequency) in rad/s of the disc m on the massless shaft k_s with journals
    m_j on two short bearings each carrying W: the first root in [lo, hi] of
    K_eq(omega) - m_j nu^2 - (k_s/2) m nu^2 / (k_s - m nu^2)."""
    def g(w):
        eps = short_eccentricity(W, mu, w, R, L, c)
        a, b = short_coefficients(eps)
        keq, nu2 = lund_equivalent(a * W / c, b * W / (c * w))
        return keq - m_j * nu2 - 0.5 * k_s * m * nu2 / (k_s - m * nu2), math.sqrt(nu2)

    ws = np.linspace(lo, hi, n)
    vals = [g(w)[0] for w in ws]
    i = next(i for i in range(n - 1) if vals[i] * vals[i + 1] <= 0)
    root = brentq(lambda w: g(w)[0], ws[i], ws[i + 1], xtol=1e-13, rtol=1e-15)
    return root, g(root)[1]


def damper_cco_forces(eps: float, film: str) -> tuple[float, float]:
    """(F_r, F_t) / (mu R L^3 w / c^2) of a squeeze-film damper on a circular centred orbit
    (F_r outward, F_t along the whirl)."""
    if film == "pi":
        return -2 * eps ** 2 / (1 - eps ** 2) ** 2, -math.pi * eps / (2 * (1 - eps ** 2) ** 1.5)
    return 0.0, -math.pi * eps / (1 - eps ** 2) ** 1.5


def sjovall(eps: float, n: float) -> float:
    """J_r(eps) of the radial load zone (load-deflection exponent n)."""
    if eps <= 0:
        return 0.0
    psi_l = math.pi if eps >= 1 else math.acos(max(-1.0, 1 - 2 * eps))
    return quad(lambda p: (1 - (1 - math.cos(p)) / (2 * eps)) ** n * math.cos(p), -psi_l, psi_l,
                epsabs=0, epsrel=1e-13)[0] / (2 * math.pi)


def brewe_hamrock(Rx: float, Ry: float) -> tuple[float, float, float]:
    """(kappa, E, K) of a point contact by the Brewe-Hamrock approximations (R_x < R_y)."""
    ar = Ry / Rx
    return 1.0339 * ar ** 0.636, 1.0003 + 0.5968 / ar, 1.5277 + 0.6023 * math.log(ar)
