"""Smooth planar elements: a force law on the lateral motion r = (y, z) of one shaft section.

The planar family (see :mod:`.radial` for the contacts and docs/architecture.md) acts on
y = g_y . x and z = g_z . x (for a bearing on a pedestal, g is the shaft's row minus the
pedestal's: the law acts on the relative motion and its reaction on the pedestal).  A *smooth*
planar element has no modes and no events: its force F(y, z, y', z', Omega, phi) (phi the shaft's
angle, for laws that turn with it, e.g. a rolling-element cage) is evaluated at every state, and
its power F . r' is counted in the work category ``work`` of the energy balance.  Fluid films
(journal bearings, squeeze-film dampers) and the clearance law of rolling-element bearings are
such laws (:mod:`fem.rotor.bearings`); the element only carries the law and the kinematics, so the
rotor's integrators treat every law alike.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ... import checks


@dataclass
class SmoothPlanarElement:
    """A smooth planar law ``law(y, z, y', z', speed, angle) -> (F_y, F_z)`` (N, on the shaft) acting
    on y = g_y . x, z = g_z . x; ``scale`` a length of the law (m: the clearance), for the
    integrators' absolute tolerances."""

    name: str
    g_y: np.ndarray
    g_z: np.ndarray
    law: object
    scale: float

    kind = "bearing"
    event_driven = False
    """No modes, no guards: the force is evaluated at every state."""

    def __post_init__(self):
        self.scale = checks.positive(f"[[{self.kind}]] {self.name!r}", "scale", self.scale, "m")
        self.g_y = np.asarray(self.g_y, dtype=float)
        self.g_z = np.asarray(self.g_z, dtype=float)

    @property
    def work(self) -> str:
        return getattr(self.law, "work", "bearings")

    def force(self, y, z, yd, zd, speed, angle):
        """(F_y, F_z) on the shaft."""
        return self.law(y, z, yd, zd, speed, angle)
