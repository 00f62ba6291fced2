"""Radial clearance between a spinning shaft and a stator ring: rotor-stator rub, bearing clearance.

A *planar* element: it acts on the lateral displacement r = (y, z) of one shaft section
(y = g_y . x, z = g_z . x) and its direction of action turns with r, so it is not a law along one
fixed coordinate s = g . x like the elements of :mod:`discrete.nonsmooth.elements.base`; it owns
its law in the two forms the rotor's transient solvers use (:mod:`fem.rotor.transient`):

* **compliant contact** (``stiffness`` k > 0): with rho = |r - c| (c: the stator centre), the
  outward normal n = (r - c)/rho and the tangent t = (-n_z, n_y) (the direction in which the
  surface of a shaft spinning about +x at Omega > 0 moves at the contact point), the contact
  presses the shaft back with N = k (rho - delta) + c_n rho' while rho > delta and N > 0
  (Kelvin-Voigt), and Coulomb friction opposes the slip of the shaft surface on the stator,
  v_s = t . r' + Omega R:  F = -N n - mu N sign(v_s) t.  The friction also brakes the spin with
  the torque mu N R (the drive supplies that work: :meth:`drive_power`).
* **rigid contact** (``stiffness`` None): Newton's impact law with restitution e and Coulomb's
  law at the contact point, for one Moreau-Jean step: :meth:`impulse` solves the 2 x 2 local
  problem exactly (no contact, stick, slip forward, slip backward: the one consistent case).

A bearing clearance is the same law with the bearing's stiffness (and mu = 0): the bearing
carries the shaft only when the journal has crossed its clearance.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ... import checks
from ...errors import ModelError


@dataclass
class RadialClearance:
    """A stator ring of radial clearance ``clearance`` (m) around the shaft section whose lateral
    displacements are y = g_y . x and z = g_z . x.

    ``stiffness`` (N/m; None: rigid contact with Newton's ``restitution`` e in [0, 1]),
    ``damping`` c_n (N s/m, compliant contact only), ``friction`` mu >= 0 (Coulomb), ``radius`` R
    of the shaft at the contact (m: the surface speed Omega R), ``centre`` (c_y, c_z): offset of
    the stator centre from the undeformed shaft axis (m; |c| < clearance)."""

    name: str
    g_y: np.ndarray
    g_z: np.ndarray
    clearance: float
    stiffness: float | None = None
    damping: float = 0.0
    restitution: float = 0.5
    friction: float = 0.0
    radius: float = 0.0
    centre: tuple[float, float] = (0.0, 0.0)

    kind = "rub"

    def __post_init__(self):
        where = f"[[{self.kind}]] {self.name!r}"
        self.clearance = checks.positive(where, "clearance", self.clearance)
        if self.stiffness is not None:
            self.stiffness = checks.positive(where, "stiffness", self.stiffness, "or leave it out for a rigid contact")
        self.damping = checks.non_negative(where, "damping", self.damping)
        self.restitution = checks.bounded(where, "restitution", self.restitution, (">=", 0.0), ("<=", 1.0))
        self.friction = checks.non_negative(where, "friction", self.friction)
        self.radius = checks.non_negative(where, "radius", self.radius)
        cy, cz = (float(v) for v in checks.vector(where, "centre", self.centre, 2, "(c_y, c_z) in m"))
        if math.hypot(cy, cz) >= self.clearance:
            raise ModelError(where, "centre", [cy, cz], f"a stator centre offset smaller than the clearance "
                             f"{self.clearance:g} m (the undeformed shaft must be free)")
        self.centre = (cy, cz)
        if self.friction > 0 and self.radius == 0:
            raise ModelError(where, "radius", 0.0, "the shaft radius at the contact (> 0 m) when friction > 0: "
                             "the slip velocity is Omega R + t . r'")
        self.g_y = np.asarray(self.g_y, dtype=float)
        self.g_z = np.asarray(self.g_z, dtype=float)

    @property
    def rigid(self) -> bool:
        return self.stiffness is None

    # ------------------------------------------------------------ kinematics
    def relative(self, y, z):
        """(dy, dz, rho): position relative to the stator centre and its length."""
        dy, dz = y - self.centre[0], z - self.centre[1]
        return dy, dz, np.hypot(dy, dz)

    def gap(self, y, z):
        """delta - rho (>= 0: free)."""
        return self.clearance - self.relative(y, z)[2]

    def frame(self, y, z):
        """(n_y, n_z, t_y, t_z): outward normal and spin tangent at the contact point."""
        dy, dz, rho = self.relative(y, z)
        rho = np.where(rho > 0, rho, 1.0)
        ny, nz = dy / rho, dz / rho
        return ny, nz, -nz, ny

    def slip_velocity(self, y, z, yd, zd, speed):
        """v_s = t . r' + Omega R: the shaft surface's velocity on the stator at the contact point."""
        _, _, ty, tz = self.frame(y, z)
        return ty * yd + tz * zd + speed * self.radius

    # ------------------------------------------------------------ compliant law
    def normal_force(self, y, z, yd, zd):
        """Unclipped N = k (rho - delta) + c_n rho' (the contact holds while rho > delta and N > 0)."""
        ny, nz, _, _ = self.frame(y, z)
        rho = self.relative(y, z)[2]
        return self.stiffness * (rho - self.clearance) + self.damping * (ny * yd + nz * zd)

    def force(self, y, z, yd, zd, speed, sign):
        """(F_y, F_z, N, v_s) in contact: F = -N n - mu N sign t, ``sign`` the slip direction held
        over the contact phase (+1 forward slip)."""
        ny, nz, ty, tz = self.frame(y, z)
        N = self.normal_force(y, z, yd, zd)
        Ft = -self.friction * N * sign
        return -N * ny + Ft * ty, -N * nz + Ft * tz, N, ty * yd + tz * zd + speed * self.radius

    def potential(self, y, z):
        """Energy stored in the compliant contact, k (rho - delta)_+^2 / 2."""
        if self.rigid:
            return 0.0 * np.asarray(y, dtype=float)
        pen = np.maximum(self.relative(y, z)[2] - self.clearance, 0.0)
        return 0.5 * self.stiffness * pen * pen

    # ------------------------------------------------------------ rigid law (one Moreau-Jean step)
    def impulse(self, W: np.ndarray, U_free: np.ndarray, un_before: float) -> tuple[np.ndarray, str]:
        """The contact impulse P = (P_n, P_t) of one step: P_n >= 0 presses the shaft inward (along
        -n), P_t acts along t.  ``W`` (2 x 2) maps P to the change of the local velocities U =
        (U_n, U_t) (U_n = -n . r': separating velocity, U_t = v_s: slip), ``U_free`` the local
        velocities without impulse, ``un_before`` the separating velocity at the step's start.

        Newton's law 0 <= P_n  _|_  U_n + e min(un_before, 0) >= 0 and Coulomb's |P_t| <= mu P_n with
        P_t = -mu P_n sign(U_t) when U_t != 0, solved exactly: no impulse, stick, slip +, slip -
        (the first consistent case).  Returns (P, case)."""
        target = -self.restitution * min(un_before, 0.0)       # U_n after the step must be >= target
        if U_free[0] >= target:
            return np.zeros(2), "free"
        mu = self.friction
        rhs = np.array([target - U_free[0], -U_free[1]])
        tol = 1e-12 * (abs(target) + abs(U_free[0]) + abs(U_free[1]) + 1e-300)
        if mu > 0:
            try:
                P = np.linalg.solve(W, rhs)
            except np.linalg.LinAlgError:
                P = None
            if P is not None and P[0] >= 0 and abs(P[1]) <= mu * P[0] * (1 + 1e-12):
                return P, "stick"
        for s in (1.0, -1.0) if mu > 0 else (0.0,):
            d = W[0, 0] - s * mu * W[0, 1]
            if d <= 0:
                continue
            pn = rhs[0] / d
            ut = U_free[1] + (W[1, 0] - s * mu * W[1, 1]) * pn
            if pn >= 0 and (s == 0 or s * ut >= -tol):
                return np.array([pn, -s * mu * pn]), "slip"
        # no consistent case (a Painleve-type paradox of the 2 x 2 problem): slip against the free slip
        s = 1.0 if U_free[1] >= 0 else -1.0
        d = max(W[0, 0] - s * mu * W[0, 1], W[0, 0])
        pn = max(rhs[0] / d, 0.0)
        return np.array([pn, -s * mu * pn]), "paradox"
