"""Smooth cubic spring (textbook (8.20)): an element with a smooth force only."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .base import Element


@dataclass
class Cubic(Element):
    """Cubic spring on s = g . x: force along s ``F = -k3 s^3`` (hardening for k3 > 0)."""

    k3: float = 0.0

    kind = "cubic"
    event_driven = False
    work = "conservative"

    @property
    def affine(self) -> bool:
        return False

    def force(self, mode, s, sd, e0, t):
        return -self.k3 * s ** 3

    def potential(self, s, mode):
        return 0.25 * self.k3 * s ** 4

    def smooth_force(self, s, sd, eps):
        return -self.k3 * s ** 3, -3 * self.k3 * s ** 2, np.zeros_like(s)

    def regularised_force(self, s, sd, t, memory, settings):
        return -self.k3 * s ** 3, ()
