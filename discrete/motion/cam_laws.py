"""Standard cam (programme-motion) laws and dwell-rise-dwell-return cycles (textbook §2.5, §6.2).

A normalised rise s(u) goes from s(0) = 0 to s(1) = 1 over u in [0, 1]:

* ``cycloidal``               s = u - sin(2 pi u)/(2 pi)        (s, s', s'' continuous; jerk jumps at the ends)
* ``harmonic``                s = (1 - cos(pi u))/2             (acceleration jumps at the ends: "soft impacts")
* ``polynomial345``           s = 10 u^3 - 15 u^4 + 6 u^5       (s, s', s'' continuous; jerk jumps at the ends)
* ``constant_acceleration``   s = 2 u^2 (u < 1/2), 1 - 2 (1 - u)^2 (acceleration jumps at 0, 1/2, 1)
* ``constant_velocity``       s = u                             (velocity jumps at the ends: "hard impacts")

A rise of height h over the cam angle beta is x(phi) = h s((phi - phi_a)/beta), so
Pi^(m) = h s^(m) / beta^m (the transfer functions of (2.12)-(2.13)); the return is h (1 - s(.)).
All laws are exact :class:`~discrete.motion.piecewise.PiecewiseLaw` objects (the sinusoidal ones
carry their sine/cosine terms, not a polynomial fit).
"""
from __future__ import annotations

import math

from ..errors import ModelError
from .piecewise import PiecewiseLaw

STANDARD_LAWS = ("cycloidal", "harmonic", "polynomial345", "constant_acceleration", "constant_velocity")


def normalised_rise(name: str) -> PiecewiseLaw:
    """The normalised rise s(u), u in [0, 1], of a standard law (see the module docstring)."""
    if name == "cycloidal":
        return PiecewiseLaw([0.0, 1.0], [[0.0, 1.0]], freq=[[2 * math.pi]], sin=[[-1.0 / (2 * math.pi)]], name=name)
    if name == "harmonic":
        return PiecewiseLaw([0.0, 1.0], [[0.5]], freq=[[math.pi]], cos=[[-0.5]], name=name)
    if name == "polynomial345":
        return PiecewiseLaw([0.0, 1.0], [[0.0, 0.0, 0.0, 10.0, -15.0, 6.0]], name=name)
    if name == "constant_acceleration":
        # second piece in s = u - 1/2: 1 - 2 (1/2 - s)^2 = 1/2 + 2 s - 2 s^2
        return PiecewiseLaw([0.0, 0.5, 1.0], [[0.0, 0.0, 2.0], [0.5, 2.0, -2.0]], name=name)
    if name == "constant_velocity":
        return PiecewiseLaw([0.0, 1.0], [[0.0, 1.0]], name=name)
    raise ModelError("cam law", "law", name, " | ".join(map(repr, STANDARD_LAWS)))


def characteristic_coefficients(name: str) -> dict:
    """Peak |s'|, |s''|, |s'''| of the normalised rise (C_v, C_a, C_j of cam design practice), found
    numerically on the exact law (jerk of a law with acceleration jumps: the finite part only)."""
    s = normalised_rise(name)
    return {"C_v": abs(s.peak(1)[1]), "C_a": abs(s.peak(2)[1]), "C_j": abs(s.peak(3)[1])}


def _angle(value, key: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0:
        raise ModelError("cam law", key, value, "a finite angle >= 0 (rad)")
    return float(value)


def rise(height: float, angle: float, law: str = "cycloidal", start: float = 0.0) -> PiecewiseLaw:
    """Rise 0 -> height over the cam angle ``angle`` [rad] starting at ``start``."""
    if not angle > 0:
        raise ModelError("cam law", "rise", angle, "an angle > 0 (rad)")
    return normalised_rise(law).stretched(start=start, time_scale=angle, value_scale=height)


def fall(height: float, angle: float, law: str = "cycloidal", start: float = 0.0) -> PiecewiseLaw:
    """Return height -> 0 over ``angle``: height (1 - s(u))."""
    if not angle > 0:
        raise ModelError("cam law", "return", angle, "an angle > 0 (rad)")
    return normalised_rise(law).stretched(start=start, time_scale=angle, value_scale=-height, value_offset=height)


def dwell(level: float, angle: float, start: float = 0.0) -> PiecewiseLaw:
    return PiecewiseLaw([start, start + angle], [[level]], name="dwell")


def dwell_rise_dwell_return(height: float, rise_angle: float, top_dwell: float, return_angle: float, *,
                            law: str = "cycloidal", return_law: str | None = None,
                            cycle: float = 2 * math.pi) -> PiecewiseLaw:
    """Periodic cam cycle in the cam angle phi in [0, cycle): rise over ``rise_angle`` from phi = 0,
    dwell at ``height``, return over ``return_angle``, dwell at 0 for the rest of the cycle."""
    if isinstance(height, bool) or not isinstance(height, (int, float)) or not math.isfinite(height) or height == 0:
        raise ModelError("cam law", "height", height, "a finite non-zero stroke")
    b1, b2, b3 = (_angle(rise_angle, "rise"), _angle(top_dwell, "top_dwell"), _angle(return_angle, "return"))
    if not b1 > 0 or not b3 > 0:
        raise ModelError("cam law", "rise" if not b1 > 0 else "return", b1 if not b1 > 0 else b3, "an angle > 0 (rad)")
    bottom = cycle - (b1 + b2 + b3)
    if bottom < -1e-12 * cycle:
        raise ModelError("cam law", "rise + top_dwell + return", b1 + b2 + b3, f"at most the cycle {cycle:.6g} rad")
    parts = [rise(height, b1, law, 0.0)]
    if b2 > 0:
        parts.append(dwell(height, b2, b1))
    parts.append(fall(height, b3, return_law or law, b1 + b2))
    if bottom > 1e-12 * cycle:
        parts.append(dwell(0.0, bottom, b1 + b2 + b3))
    name = f"dwell-rise-dwell-return ({law}/{return_law or law})"
    out = PiecewiseLaw.concatenate(parts, periodic=True, name=name)
    out.knots[-1] = cycle
    return out
