"""The motor as a model element: the dynamic characteristic (5.54), (3.15) with the torque as a state
(textbook §5.10, §10.6)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import ModelError
from .base import Element, Linearisation


@dataclass
class Motor(Element):
    """Motor torque ``M`` along s (the rotor's angle): ``T M' + M = (1 - s'/omega0)/nu``.

    ``omega0``: ideal no-load speed (rad/s), ``nu``: slope of the static characteristic
    (1/(N m)), ``T``: electromagnetic time constant (s); see
    :class:`discrete.motion.motor.DynamicMotor` (catalogue data, (5.55)-(5.58)).  With T > 0 the
    torque is one internal state of the exact pieces (``M' = ((1 - s'/omega0)/nu - M)/T``, affine
    in (s', M, e0)), starting from ``torque0`` (default 0: the motor switched on at t = 0); with
    T = 0 the static characteristic ``M = (1 - s'/omega0)/nu`` is an affine force (no state).
    Its power ``M s'`` is the work category ``motor`` of the energy balance.  No modes, no events.
    """

    omega0: float = 0.0
    nu: float = 0.0
    T: float = 0.0
    torque0: float = 0.0

    kind = "motor"
    work = "motor"
    event_driven = False
    smooth_law = False

    def __post_init__(self):
        super().__post_init__()
        where = f"[[motor]] {self.name!r}"
        for key in ("omega0", "nu"):
            v = getattr(self, key)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v > 0):
                raise ModelError(where, key, v, "a finite number > 0")
        if isinstance(self.T, bool) or not isinstance(self.T, (int, float)) or not (math.isfinite(self.T) and self.T >= 0):
            raise ModelError(where, "T", self.T, "a finite time constant >= 0 (0: the static characteristic)")
        if not math.isfinite(self.torque0):
            raise ModelError(where, "torque0", self.torque0, "a finite torque")
        if self.T == 0 and self.torque0 != 0:
            raise ModelError(where, "torque0", self.torque0, "0 with T = 0 (the static characteristic has no "
                             "torque state: M follows the speed)")

    @property
    def n_states(self) -> int:
        return 1 if self.T > 0 else 0

    def initial_states(self) -> list:
        return [float(self.torque0)] if self.T > 0 else []

    def static_torque(self, sd, e0):
        """(1 - s'/omega0)/nu, with the constant written e0 (affine in the exogenous state)."""
        return (e0 - sd / self.omega0) / self.nu

    # ------------------------------------------------------------ event-driven solver
    def force(self, mode, s, sd, e0, t):
        return self.static_torque(sd, e0)

    def state_force(self, mode, s, sd, w, e0, t):
        return w[0] if self.T > 0 else self.static_torque(sd, e0)

    def state_rates(self, mode, s, sd, w, e0, t):
        if self.T == 0:
            return np.zeros((0, np.size(s)))
        return ((self.static_torque(sd, e0) - w[0]) / self.T)[None, :]

    def state_scale(self) -> float:
        return 1.0 / self.nu

    # ------------------------------------------------------------ outputs and linear analyses
    outputs = ("force", "velocity")          # the motor torque and the rotor's speed

    linear_states = ("characteristic",)

    def linearised(self, state=None):
        """The dynamic characteristic about a steady speed: torque -Z(omega) s with the complex stiffness
        Z = i omega b / (1 + i omega T), b = 1/(nu omega0) (the Maxwell element of (10.65)); it adds
        damping, not stiffness or inertia, so the undamped modes do not see it."""
        b = 1.0 / (self.nu * self.omega0)
        T = self.T
        return Linearisation(state or self.linear_state, note=f"its dynamic characteristic: complex stiffness "
                             f"i omega b/(1 + i omega T), b = {b:g}, T = {T:g} (forced response; the undamped "
                             "modes do not see it)", Z=lambda w: 1j * np.asarray(w) * b / (1 + 1j * np.asarray(w) * T))

    def velocity_scale(self) -> float:
        return self.omega0

    def rate(self, mass: float) -> float:
        """With T > 0 the largest |root| of T s^2 + s + 1/(nu omega0 mass) = 0 (the torque state coupled to the
        rotor, the roots of §5.10); with T = 0 the damping rate 1/(nu omega0 mass) of the static characteristic."""
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            b = float(np.float64(1.0) / (np.float64(self.nu) * self.omega0 * mass))
            if self.T == 0 or not math.isfinite(b):
                return b if math.isfinite(b) else math.inf
            disc = 1.0 - 4.0 * self.T * b
            rate = (1.0 + math.sqrt(disc)) / (2.0 * self.T) if disc >= 0 else math.sqrt(b / self.T)
        return rate if math.isfinite(rate) else math.inf

    # ------------------------------------------------------------ other solvers
    def smooth_force(self, s, sd, eps):
        raise ModelError(f"element {self.name!r}", "kind", "motor", "the event-driven time simulation "
                         "(a motor has no periodic steady state of its own: the rotor angle drifts)")

    def regularised_force(self, s, sd, t, memory, settings):
        if self.T > 0:
            raise ModelError(f"element {self.name!r}", "T", self.T, "0 for method = 'regularised' (its torque state "
                             "is integrated by the event-driven solver only: method = 'event')")
        return float(self.static_torque(sd, 1.0)), ()
