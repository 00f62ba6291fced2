"""Dynamic characteristic of a motor as transfer-matrix elements (§10.6, (5.54), (10.65)-(10.66)).

The static characteristic omega_D = omega_D0 [1 - nu (M + T M')] is a viscous damper
b_D = 1/(nu omega_D0) in series with a spring c_D = 1/(nu omega_D0 T) between the stator
(clamp) and the rotor: Gamma_cb = [[1, 1/c_D - i/(b_D omega)], [0, 1]] (10.66), so the order
of b_D and c_D does not matter.  Speed non-uniformity chi = |nu M_D (1 + i omega T)|
(the book prints (1 + i T), dimensionally wrong; digest errata).

The motor physics (b_D, c_D, partial frequency, catalogue conversion, complex stiffness, the
first-order state law) lives in :class:`discrete.motion.motor.DynamicMotor`; this class only adds
the transfer-matrix elements.
"""
from __future__ import annotations

from dataclasses import dataclass

from ..motion.motor import DynamicMotor
from .elements import Damper, Spring


@dataclass(frozen=True)
class MotorCharacteristic(DynamicMotor):
    """:class:`DynamicMotor` (fields omega0, nu, T) with its transfer-matrix elements."""

    def elements(self) -> tuple:
        """(damper b_D, spring c_D): clamp -> b_D -> c_D -> rotor (10.65)."""
        return Damper(self.b), Spring(self.c)
