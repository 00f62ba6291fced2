"""Force and motion transmissibility of a 1-DOF isolator (textbook §5.4-5.5, §6.4).

z = omega/k, delta = n/k (viscous) or the hysteretic delta = psi/(4 pi) of c (1 + 2 i delta):

* dynamic factor (5.20):            alpha(z) = 1/sqrt((1 - z^2)^2 + 4 delta^2 z^2)
* undamped isolation factor (6.17): xi = R_max/F_0 = 1/|1 - z^2| (= alpha at delta = 0)
* transmitted force with viscous damping (the force through spring and damper, c q + b q'):
      T(z) = sqrt(1 + 4 delta^2 z^2)/sqrt((1 - z^2)^2 + 4 delta^2 z^2)
  (the same function is the absolute-motion transmissibility of base excitation)
* hysteretic damping: T(z) = sqrt(1 + 4 delta^2)/sqrt((1 - z^2)^2 + 4 delta^2)
* relative motion under base excitation (5.28): alpha_1(z) = z^2 alpha(z)

Isolation (T < 1) needs z > sqrt(2) for every damping value (T(sqrt 2) = 1 exactly).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import ModelError

DAMPING_MODELS = ("viscous", "hysteretic")


def _z_delta(z, delta):
    z = np.asarray(z, dtype=float)
    if np.any(z < 0) or not np.all(np.isfinite(z)):
        raise ModelError("transmissibility", "z", z.tolist(), "frequency ratios omega/k >= 0")
    if isinstance(delta, bool) or not isinstance(delta, (int, float, np.floating)) or not (math.isfinite(delta) and delta >= 0):
        raise ModelError("transmissibility", "delta", delta, "a damping ratio >= 0")
    return z, float(delta)


def dynamic_factor(z, delta: float = 0.0):
    """alpha(z) (5.20); undamped 1/|1 - z^2| (inf at z = 1)."""
    z, d = _z_delta(z, delta)
    with np.errstate(divide="ignore"):
        return 1.0 / np.sqrt((1 - z**2) ** 2 + 4 * d * d * z**2)


def force_transmissibility(z, delta: float = 0.0, damping: str = "viscous"):
    """|transmitted force| / F_0 (see the module docstring)."""
    z, d = _z_delta(z, delta)
    if damping not in DAMPING_MODELS:
        raise ModelError("transmissibility", "damping", damping, " | ".join(map(repr, DAMPING_MODELS)))
    num = 1 + 4 * d * d * (z**2 if damping == "viscous" else 1.0)
    den = (1 - z**2) ** 2 + 4 * d * d * (z**2 if damping == "viscous" else 1.0)
    with np.errstate(divide="ignore"):
        return np.sqrt(num / den)


def relative_motion_factor(z, delta: float = 0.0):
    """alpha_1(z) = z^2 alpha(z) (5.28): relative motion over base amplitude."""
    z, d = _z_delta(z, delta)
    return z**2 * dynamic_factor(z, d)
