"""Dynamic characteristic of a motor as transfer-matrix elements (§10.6, (5.54), (10.65)-(10.66)).

The static characteristic omega_D = omega_D0 [1 - nu (M + T M')] is a viscous damper
b_D = 1/(nu omega_D0) in series with a spring c_D = 1/(nu omega_D0 T) between the stator
(clamp) and the rotor: Gamma_cb = [[1, 1/c_D - i/(b_D omega)], [0, 1]] (10.66), so the order
of b_D and c_D does not matter.  Speed non-uniformity chi = |nu M_D (1 + i omega T)|
(the book prints (1 + i T), dimensionally wrong; digest errata).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ModelError
from .elements import Damper, Spring


@dataclass(frozen=True)
class MotorCharacteristic:
    omega0: float     # ideal no-load speed (rad/s)
    nu: float         # slope of the static characteristic (1/(N m))
    T: float          # electromagnetic time constant (s)

    def __post_init__(self):
        for key in ("omega0", "nu", "T"):
            if not getattr(self, key) > 0:
                raise ModelError("motor", key, getattr(self, key), "a number > 0")

    @property
    def b(self) -> float:
        return 1.0 / (self.nu * self.omega0)

    @property
    def c(self) -> float:
        return 1.0 / (self.nu * self.omega0 * self.T)

    def elements(self) -> tuple:
        """(damper b_D, spring c_D): clamp -> b_D -> c_D -> rotor (10.65)."""
        return Damper(self.b), Spring(self.c)

    def partial_frequency(self, J: float) -> float:
        """p0 = sqrt(k^2 - n^2), k^2 = c_D/J = 1/(nu T J omega0), n^2 = 1/(4 T^2) (motor with rotor J)."""
        k2, n2 = self.c / J, 0.25 / self.T**2
        return float(np.sqrt(k2 - n2)) if k2 > n2 else float("nan")

    def nonuniformity(self, omega, M_D):
        """chi = |nu M_D (1 + i omega T)| (corrected form of the book's chi_omega)."""
        return np.abs(self.nu * np.asarray(M_D) * (1 + 1j * np.asarray(omega) * self.T))
