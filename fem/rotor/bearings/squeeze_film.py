"""A squeeze-film damper: a non-rotating journal (the bearing's outer race) in an oil film, centred by a
spring (squirrel cage).

The film is the short-bearing closed form of :mod:`.short_film` at omega = 0 (the damper journal
does not spin, only whirls): F = (mu R^4 / c^2) f(X, Y, 12 Y', 12 X') with the film extent
``film``: ``"pi"`` (cavitated: Guembel's condition, only the half of the film that the journal's
velocity pressurises carries pressure; the usual design assumption for a damper fed at low
pressure) or ``"2pi"`` (uncavitated: a high supply pressure or a sealed damper).  For a circular
centred orbit of radius e = eps c at the whirl speed w these are the classic forces (Vance,
*Rotordynamics of Turbomachinery* (1988) ch. 6; San Andres, *Squeeze film dampers* (2010)):
pi film F_r = -2 mu R L^3 eps^2 w / (c^2 (1 - eps^2)^2), F_t = -pi mu R L^3 eps w / (2 c^2 (1 - eps^2)^1.5);
2 pi film F_r = 0, F_t twice the pi film's (checked in the validation case).

The centring spring ``centering_stiffness`` k_s acts in y and z; the static load (``load`` along
``load_angle``; default none: the damper centred) sits the journal at r_s = W / k_s.

* **Linear analyses**: K = k_s I, C = -dF/dr' at r_s.  The pi film's force is not differentiable in
  the velocity at rest (the pressurised half turns with the velocity); its coefficients are the
  mean of the two one-sided derivatives, which is exactly half the 2 pi film's damping (the two
  halves add up to the whole film).
* **Time runs**: the film force plus the spring (:meth:`SqueezeFilmDamper.planar_law`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from discrete import checks
from discrete.errors import ModelError

from ..model import BEARING_COEFFICIENTS, Bearing
from .short_film import FILMS, ShortFilm


@dataclass
class SqueezeFilmDamper(Bearing):
    """A squeeze-film damper at ``x``: journal ``diameter`` D and ``length`` L (m), radial
    ``clearance`` c (m), ``viscosity`` mu (Pa s), ``film`` "pi" or "2pi", ``centering_stiffness``
    k_s (N/m), static ``load`` (N, default 0) along ``load_angle`` (rad)."""

    diameter: float = 0.0
    length: float = 0.0
    clearance: float = 0.0
    viscosity: float = 0.0
    film: str = "pi"
    centering_stiffness: float = 0.0
    load: float = 0.0
    load_angle: float = -0.5 * math.pi
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    kind = "squeeze_film_damper"
    nonlinear = True
    needs_weight_load = False

    def check(self, where: str) -> None:
        checks.number(where, "x", self.x, "a position in m")
        for key in ("diameter", "length", "clearance", "viscosity"):
            checks.positive(where, key, getattr(self, key))
        checks.choice(where, "film", self.film, FILMS)
        checks.non_negative(where, "centering_stiffness", self.centering_stiffness, "N/m")
        checks.non_negative(where, "load", self.load, "N")
        checks.number(where, "load_angle", self.load_angle, "an angle in rad")
        if self.load > 0 and self.centering_stiffness == 0:
            raise ModelError(where, "load", self.load, "0 without a centering spring (the film alone carries no "
                             "static load: give centering_stiffness)")
        if self.load > 0 and not self.load / self.centering_stiffness < 0.9 * self.clearance:
            raise ModelError(where, "load", self.load, f"a load the centering spring holds within 0.9 of the "
                             f"clearance (< {0.9 * self.clearance * self.centering_stiffness:g} N)")
        for key in ("k_axial", "c_axial"):
            checks.non_negative(where, key, getattr(self, key))
        for key in BEARING_COEFFICIENTS:
            if getattr(self, key) != 0.0:
                raise ModelError(where, key, getattr(self, key), "no typed-in coefficients: a squeeze-film damper "
                                 "computes them from its geometry")
        if self.speeds is not None:
            raise ModelError(where, "speeds", self.speeds, "no speeds: a damper's journal does not spin")

    @property
    def force_scale(self) -> float:
        return self.viscosity * (0.5 * self.diameter) ** 4 / self.clearance ** 2

    @property
    def length_scale(self) -> float:
        return self.clearance

    def film_model(self) -> ShortFilm:
        return ShortFilm(self.length / self.diameter, self.film)

    def static_load(self) -> np.ndarray:
        return self.load * np.array([math.cos(self.load_angle), math.sin(self.load_angle)])

    def film_force(self, y, z, yd, zd) -> np.ndarray:
        """The film's force on the journal (N) at the position and velocity (m, m/s)."""
        c = self.clearance
        return self.force_scale * self.film_model().force(y / c, z / c, 12.0 * zd / c, 12.0 * yd / c)

    def damping_matrix(self) -> np.ndarray:
        """-dF/dr' at the static position (mean of the one-sided derivatives; see the module notes)."""
        key = ("C", self.diameter, self.length, self.clearance, self.viscosity, self.film, self.load,
               self.load_angle, self.centering_stiffness)
        if key not in self._cache:
            r = self.static_load() / self.centering_stiffness if self.load else np.zeros(2)
            h = 1e-6 * self.clearance
            C = np.zeros((2, 2))
            for j in range(2):
                dv = np.zeros(2)
                dv[j] = h
                C[:, j] = -(self.film_force(*r, *dv) - self.film_force(*r, *(-dv))) / (2 * h)
            self._cache[key] = C
        return self._cache[key]

    def table(self) -> dict[str, np.ndarray]:
        C = self.damping_matrix()
        k = float(self.centering_stiffness)
        return {"kyy": np.array([k]), "kyz": np.zeros(1), "kzy": np.zeros(1), "kzz": np.array([k]),
                "cyy": np.array([C[0, 0]]), "cyz": np.array([C[0, 1]]), "czy": np.array([C[1, 0]]),
                "czz": np.array([C[1, 1]])}

    def planar_law(self):
        return DamperLaw(self)


class DamperLaw:
    """The damper's film and centring spring on the shaft at a state."""

    work = "bearings"

    def __init__(self, damper: SqueezeFilmDamper):
        self.d = damper
        self.film = damper.film_model()
        self.c = damper.clearance
        self.k = damper.force_scale
        self.ks = float(damper.centering_stiffness)

    def __call__(self, y, z, yd, zd, speed, angle=0.0):
        X, Y = y / self.c, z / self.c
        if X * X + Y * Y >= 1.0:
            return math.nan, math.nan
        f = self.film.force(X, Y, 12.0 * zd / self.c, 12.0 * yd / self.c)
        return self.k * f[0] - self.ks * y, self.k * f[1] - self.ks * z
