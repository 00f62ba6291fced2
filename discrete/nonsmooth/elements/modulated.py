"""The pulsating part of a spring of periodically varying stiffness (textbook (7.1), §7.3)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import ModelError
from .base import Element, Linearisation


@dataclass
class ModulatedSpring(Element):
    """A spring of stiffness ``c(t) = k (1 - depth sin(omega t + phase))`` on s, the sign of the
    book's (7.1) ``c(t) = c0 - dc sin(Omega t)`` and of :mod:`discrete.linear.parametric` (a phase
    of pi gives ``c0 (1 + depth sin omega t)``).  The constant part k belongs to the linear system
    (the [[spring]]); this element is the pulsating part, force along s
    ``F = k depth sin(omega t + phase) s`` and potential ``V = -k depth sin(omega t + phase) s^2/2``
    (so the spring's whole energy is ``c(t) s^2/2``).  The law depends on t explicitly: its pieces
    are integrated numerically (DOP853 at the solver's rtol), and the explicit derivative
    ``dV/dt = -k depth omega cos(omega t + phase) s^2/2`` (the work of the pulsation) is the
    category ``modulation`` of the energy balance."""

    k: float = 0.0
    depth: float = 0.0
    omega: float = 0.0
    phase: float = 0.0

    kind = "modulated_spring"
    work = "conservative"
    event_driven = False
    time_dependent = True
    smooth_law = False

    def __post_init__(self):
        super().__post_init__()
        where = f"[[spring]] {self.name!r} modulation"
        if not (math.isfinite(self.k) and self.k > 0):
            raise ModelError(where, "k", self.k, "a stiffness > 0 (the spring that pulsates)")
        if not (math.isfinite(self.depth) and 0 <= self.depth < 1):
            raise ModelError(where, "depth", self.depth, "a number in [0, 1) (the stiffness stays positive)")
        if not (math.isfinite(self.omega) and self.omega > 0):
            raise ModelError(where, "omega", self.omega, "a pulsation frequency > 0 (rad/s)")
        if not math.isfinite(self.phase):
            raise ModelError(where, "phase", self.phase, "a finite phase (rad)")

    @property
    def affine(self) -> bool:
        return False

    def pulsation(self, t):
        """k depth sin(omega t + phase): the stiffness removed from k at time t."""
        return self.k * self.depth * np.sin(self.omega * np.asarray(t, dtype=float) + self.phase)

    def force(self, mode, s, sd, e0, t):
        return self.pulsation(t) * s

    def potential(self, s, mode):
        return self.potential_at(s, mode, 0.0)

    def potential_at(self, s, mode, t):
        return -0.5 * self.pulsation(t) * s * s

    def explicit_power(self, s, mode, t):
        return -0.5 * self.k * self.depth * self.omega * np.cos(self.omega * np.asarray(t, dtype=float) + self.phase) * s * s

    linear_states = ("mean",)

    def linearised(self, state=None):
        return Linearisation(state or self.linear_state, note="its mean stiffness, the k of its [[spring]] (the "
                             "pulsation: drivefem simulate and [analysis] type = 'parametric')")

    def stiffness(self) -> float:
        return self.k * self.depth

    def frequency(self) -> float:
        return self.omega

    def smooth_force(self, s, sd, eps):
        raise ModelError(f"element {self.name!r}", "modulation", "a time-dependent stiffness",
                         "the time simulation (harmonic balance needs time-invariant laws; the stability of the "
                         "linear system is [analysis] type = 'parametric')")

    def regularised_force(self, s, sd, t, memory, settings):
        return float(self.pulsation(t) * s), ()
