"""A rolling-element bearing with radial clearance: Hertzian elements on a turning cage.

Z elements at the angles psi_j = psi_c + 2 pi j / Z (from +y towards +z) carry the shaft (inner
ring) at r = (y, z) relative to the outer ring.  Element j is compressed by
delta_j = y cos psi_j + z sin psi_j - c_r (c_r = ``clearance``, the radial play: half Harris's
diametral clearance P_d; negative: a preload) and pushes the shaft back with K_n delta_j^n
(:mod:`.hertz`: n = 3/2 balls, 10/9 rollers) when delta_j > 0:

    F = -sum_j K_n <delta_j>_+^n (cos psi_j, sin psi_j) - c_b r'

(Harris & Kotzalas, *Rolling Bearing Analysis* 5th ed., vol. 1 ch. 7; the viscous ``damping`` c_b
lumps the lubricant's and the housing's).  The cage turns at Omega_c = Omega (1 - gamma)/2, gamma =
D cos(alpha)/d_m (outer ring fixed; Harris ch. 8), so psi_c = phi (1 - gamma)/2 with phi the
shaft's angle: the stiffness varies at the ball-pass frequency Z Omega_c (varying compliance).

* **Linear analyses**: the static equilibrium under the bearing's load (``load`` along
  ``load_angle``, or the rotor's weight share) and the stiffness -dF/dr there, averaged over the
  cage positions of one element pitch (16 positions): a constant K (no speed table); C = c_b I.
* **Time runs**: the law above, element by element (:meth:`RollingBearing.planar_law`); it is
  continuous (and C^1 for balls), so the integrator's error control resolves the engagements.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from discrete import checks
from discrete.errors import ModelError, SolverError

from ..model import BEARING_COEFFICIENTS, Bearing
from .hertz import ball_contacts, effective_modulus, roller_constant, series_constant

ELEMENTS = {"ball": 1.5, "roller": 10.0 / 9.0}
CAGE_POSITIONS = 16


@dataclass
class RollingBearing(Bearing):
    """A radial rolling-element bearing at ``x``: ``element`` "ball" or "roller", ``elements`` Z,
    ``element_diameter`` D (m), ``pitch_diameter`` d_m (m), ``contact_angle`` alpha (rad),
    radial ``clearance`` c_r (m; < 0: preload); balls: groove conformities ``inner_conformity``,
    ``outer_conformity`` f = r_groove / D (> 0.5); rollers: ``roller_length`` (effective, m);
    ``modulus`` E (Pa) and ``poisson`` nu of rings and elements (steel by default), or
    ``contact_stiffness`` K_n (N/m^n) given directly; ``damping`` c_b (N s/m, y and z);
    ``load`` (N) along ``load_angle`` (rad) or None (the rotor's weight share)."""

    element: str = "ball"
    elements: int = 0
    element_diameter: float = 0.0
    pitch_diameter: float = 0.0
    contact_angle: float = 0.0
    clearance: float = 0.0
    inner_conformity: float = 0.52
    outer_conformity: float = 0.52
    roller_length: float | None = None
    modulus: float = 208e9
    poisson: float = 0.3
    contact_stiffness: float | None = None
    damping: float = 0.0
    load: float | None = None
    load_angle: float = -0.5 * math.pi
    _static_load: np.ndarray | None = field(default=None, repr=False, compare=False)
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    kind = "rolling_bearing"
    nonlinear = True

    # ---------------------------------------------------------------- checks
    def check(self, where: str) -> None:
        checks.number(where, "x", self.x, "a position in m")
        checks.choice(where, "element", self.element, tuple(ELEMENTS))
        checks.integer(where, "elements", self.elements, 3)
        checks.number(where, "clearance", self.clearance, "a radial clearance in m (< 0: preload)")
        checks.non_negative(where, "damping", self.damping, "N s/m")
        checks.number(where, "load_angle", self.load_angle, "an angle in rad")
        if self.load is not None:
            checks.non_negative(where, "load", self.load, "N (or leave it out: the rotor's weight share)")
        if self.contact_stiffness is not None:
            checks.positive(where, "contact_stiffness", self.contact_stiffness, "N/m^n")
        else:
            checks.positive(where, "element_diameter", self.element_diameter, "m")
            checks.positive(where, "pitch_diameter", self.pitch_diameter, "m")
            if not self.element_diameter < self.pitch_diameter:
                raise ModelError(where, "element_diameter", self.element_diameter,
                                 f"an element smaller than the pitch diameter ({self.pitch_diameter:g} m)")
            checks.bounded(where, "contact_angle", self.contact_angle, (">=", 0.0), ("<", 0.5 * math.pi), "rad")
            checks.positive(where, "modulus", self.modulus, "Pa")
            checks.bounded(where, "poisson", self.poisson, (">", -1.0), ("<", 0.5))
            if self.element == "ball":
                for key in ("inner_conformity", "outer_conformity"):
                    checks.bounded(where, key, getattr(self, key), (">", 0.5), ("<", 1.0),
                                   "groove radius / ball diameter (about 0.515-0.53)")
            elif self.roller_length is None:
                raise ModelError(where, "roller_length", None,
                                 "the rollers' effective length (m), or contact_stiffness")
            else:
                checks.positive(where, "roller_length", self.roller_length, "m")
        for key in ("k_axial", "c_axial"):
            checks.non_negative(where, key, getattr(self, key))
        for key in BEARING_COEFFICIENTS:
            if getattr(self, key) != 0.0:
                raise ModelError(where, key, getattr(self, key), "no typed-in coefficients: a rolling-element "
                                 "bearing computes them from its geometry")
        if self.speeds is not None:
            raise ModelError(where, "speeds", self.speeds, "no speeds: the linearised stiffness does not depend on "
                             "speed (the cage position is averaged)")

    # ---------------------------------------------------------------- the law
    @property
    def exponent(self) -> float:
        return ELEMENTS[self.element]

    @property
    def gamma(self) -> float:
        """D cos(alpha) / d_m (0 with contact_stiffness given and no geometry)."""
        if not self.pitch_diameter:
            return 0.0
        return self.element_diameter * math.cos(self.contact_angle) / self.pitch_diameter

    @property
    def cage_ratio(self) -> float:
        """Omega_c / Omega = (1 - gamma) / 2 (outer ring fixed)."""
        return 0.5 * (1.0 - self.gamma)

    def element_constant(self) -> float:
        """K_n of one element between both races (N/m^n)."""
        if self.contact_stiffness is not None:
            return float(self.contact_stiffness)
        if self.element == "ball":
            E = effective_modulus(self.modulus, self.poisson, self.modulus, self.poisson)
            inner, outer = ball_contacts(self.element_diameter, self.pitch_diameter, self.inner_conformity,
                                         self.outer_conformity, self.contact_angle, E)
            return series_constant(inner.K, outer.K, 1.5)
        Kc = roller_constant(self.roller_length)
        return series_constant(Kc, Kc, 10.0 / 9.0)

    def angles(self, cage: float) -> np.ndarray:
        return cage + 2 * math.pi * np.arange(self.elements) / self.elements

    def elastic_force(self, y: float, z: float, cage: float) -> np.ndarray:
        """-sum K_n <delta_j>^n (cos, sin)(psi_j): the elements' force on the shaft (N)."""
        psi = self.angles(cage)
        c, s = np.cos(psi), np.sin(psi)
        d = np.maximum(y * c + z * s - self.clearance, 0.0)
        q = self.element_constant() * d ** self.exponent
        return -np.array([q @ c, q @ s])

    def elastic_stiffness(self, y: float, z: float, cage: float) -> np.ndarray:
        """-dF/dr = sum n K_n <delta_j>^(n-1) e_j e_j^T (2 x 2, N/m)."""
        psi = self.angles(cage)
        c, s = np.cos(psi), np.sin(psi)
        d = np.maximum(y * c + z * s - self.clearance, 0.0)
        k = self.exponent * self.element_constant() * np.where(d > 0, d, 0.0) ** (self.exponent - 1.0)
        k = np.where(d > 0, k, 0.0)
        return np.array([[k @ (c * c), k @ (c * s)], [k @ (c * s), k @ (s * s)]])

    # ---------------------------------------------------------------- static load and linearisation
    @property
    def needs_weight_load(self) -> bool:
        return self.load is None

    def set_weight_load(self, force_yz) -> None:
        self._static_load = np.asarray(force_yz, dtype=float)

    def static_load(self) -> np.ndarray:
        """(W_y, W_z): the force the shaft puts on the bearing, N."""
        if self.load is not None:
            return self.load * np.array([math.cos(self.load_angle), math.sin(self.load_angle)])
        if self._static_load is None:
            raise ModelError(f"rolling-element bearing at x = {self.x!r}", "load", None,
                             "a static load (N), or a bearing assembled with its rotor (its weight share)")
        return self._static_load

    def deflection(self, cage: float = 0.0, load=None) -> np.ndarray:
        """The shaft's position r (m) where the elements carry the static load, -F(r) = W: the
        minimum of the convex potential V(r) = sum K_n <delta_j>^(n+1) / (n + 1) - W . r (trust-region
        Newton with the exact gradient and Hessian; the Hessian is singular while one element alone
        is engaged, which the trust region handles)."""
        from scipy.optimize import minimize

        W = self.static_load() if load is None else np.asarray(load, dtype=float)
        Wn = float(np.hypot(*W))
        if Wn == 0 and self.clearance >= 0:
            return np.zeros(2)
        Kn, n = self.element_constant(), self.exponent
        psi = self.angles(cage)
        c, s = np.cos(psi), np.sin(psi)
        L = max(abs(self.clearance), (4.37 * max(Wn, 1e-300) / (self.elements * Kn)) ** (1.0 / n), 1e-12)

        def V(x):                                   # in units of L (scaled for the optimiser)
            d = np.maximum(L * (x[0] * c + x[1] * s) - self.clearance, 0.0)
            return (Kn * np.sum(d ** (n + 1)) / (n + 1) - L * (W @ x)) / (Wn * L if Wn else Kn * L ** (n + 1))

        def grad(x):
            return (-self.elastic_force(*(L * x), cage) - W) * L / (Wn * L if Wn else Kn * L ** (n + 1))

        def hess(x):
            return self.elastic_stiffness(*(L * x), cage) * L * L / (Wn * L if Wn else Kn * L ** (n + 1))

        u = W / Wn if Wn else np.array([1.0, 0.0])
        x0 = u * (max(self.clearance, 0.0) / L + 1.0)
        res = minimize(V, x0, jac=grad, hess=hess, method="trust-exact", options={"gtol": 1e-13, "maxiter": 500})
        r = L * res.x
        if np.linalg.norm(-self.elastic_force(*r, cage) - W) > 1e-8 * max(Wn, Kn * L ** n):
            raise SolverError(f"rolling-element bearing at x = {self.x:g} m: no static equilibrium under {W} N "
                              f"({res.message})")
        return r

    def linearised_stiffness(self) -> np.ndarray:
        """The stiffness at the static load, averaged over the cage positions of one element pitch."""
        key = ("K", tuple(self.static_load()), self.element_constant(), self.clearance, self.elements, self.exponent)
        if key not in self._cache:
            pitch = 2 * math.pi / self.elements
            cages = pitch * np.arange(CAGE_POSITIONS) / CAGE_POSITIONS
            Ks = [self.elastic_stiffness(*self.deflection(c), c) for c in cages]
            self._cache[key] = np.mean(Ks, axis=0)
        return self._cache[key]

    @property
    def length_scale(self) -> float:
        """A length of the law (m): the clearance or the static deflection, whichever is larger."""
        return max(abs(self.clearance), float(np.hypot(*self.deflection())), 1e-9)

    def table(self) -> dict[str, np.ndarray]:
        K = self.linearised_stiffness()
        c = float(self.damping)
        if not (K[0, 0] > 0 or K[1, 1] > 0 or c > 0):
            raise ModelError(f"[[rotor.rolling_bearing]] at x = {self.x:g} m", "load",
                             float(np.hypot(*self.static_load())),
                             "a static load (or a preload: clearance < 0) that engages some elements, or damping > 0: "
                             "unloaded with clearance, the bearing has no linear stiffness")
        return {"kyy": np.array([K[0, 0]]), "kyz": np.array([K[0, 1]]), "kzy": np.array([K[1, 0]]),
                "kzz": np.array([K[1, 1]]), "cyy": np.array([c]), "cyz": np.zeros(1), "czy": np.zeros(1),
                "czz": np.array([c])}

    # ---------------------------------------------------------------- time runs
    def planar_law(self):
        return RollingLaw(self)


class RollingLaw:
    """The elements' force and the damping on the shaft at a state, the cage at phi (1 - gamma)/2."""

    work = "bearings"

    def __init__(self, bearing: RollingBearing):
        self.b = bearing
        self.Kn = bearing.element_constant()
        self.n = bearing.exponent
        self.ratio = bearing.cage_ratio
        self.offsets = 2 * math.pi * np.arange(bearing.elements) / bearing.elements
        self.cr = bearing.clearance
        self.c = float(bearing.damping)

    def __call__(self, y, z, yd, zd, speed, angle=0.0):
        psi = self.ratio * angle + self.offsets
        c, s = np.cos(psi), np.sin(psi)
        d = y * c + z * s - self.cr
        q = self.Kn * np.maximum(d, 0.0) ** self.n
        return -float(q @ c) - self.c * yd, -float(q @ s) - self.c * zd
