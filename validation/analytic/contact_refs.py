"""References of the contact with stiffness and damping switched on at closure (Kelvin-Voigt)."""
from __future__ import annotations

import math


def kelvin_voigt_impact(k: float, c: float, m: float, v: float) -> dict:
    """A mass m at speed v into a spring k parallel to a dashpot c, released when the penetration is
    back to zero (geometric switching): the penetration is the damped half-sine
    x(t) = v/omega_d e^(-zeta omega_0 t) sin(omega_d t), so the contact lasts pi/omega_d and the mass
    leaves at e v, e = exp(-pi zeta / sqrt(1 - zeta^2)) (zeta = c / (2 sqrt(k m)) < 1); the largest
    penetration is at tan(omega_d t) = sqrt(1 - zeta^2)/zeta."""
    w0 = math.sqrt(k / m)
    zeta = c / (2 * math.sqrt(k * m))
    wd = w0 * math.sqrt(1 - zeta ** 2)
    tmax = math.atan2(math.sqrt(1 - zeta ** 2), zeta) / wd
    return {"duration": math.pi / wd, "restitution": math.exp(-math.pi * zeta / math.sqrt(1 - zeta ** 2)),
            "max_penetration": v / wd * math.exp(-zeta * w0 * tmax) * math.sin(wd * tmax)}


#: textbook §11.2, Fig. 11.2-11.3 in the digest's reading of (11.4): N = 30, delta = 0.03, s = 1e-3;
#: the digest's steady-state simulation (DOP853, rtol 1e-10, exact switching): contact angles mod 2 pi
#: and extremes as printed (4 decimals; max|q''| 2 digits, max|q| 3 digits)
SEC_11_2 = {"N": 30.0, "delta": 0.03, "gap": 1e-3,
            "opens": ("1.6056", "1.8958", "4.7472", "5.0374"), "closes": ("1.7508", "1.9447", "4.8923", "5.0863"),
            "max_acceleration": "0.46", "max_displacement": "1.78e-3", "flight_estimate": "0.18171"}
