"""A plain journal bearing computed from its geometry: operating point, 8 coefficients, film force.

The film (:mod:`.reynolds`: finite length by scikit-fem with Reynolds' or Guembel's cavitation;
:mod:`.short_film`: Ocvirk's short-bearing closed form) gives the force on the journal

    F = (mu R^4 / c^2) f(X, Y, a, b),    a = -6 omega X + 12 Y',  b = 6 omega Y + 12 X',

(X, Y) = (y, z) / c the journal centre relative to the bearing centre, X' = y'/c.  f is
homogeneous of degree 1 in (a, b), so every operating point is a function of the Sommerfeld
number S = mu N L D (R / c)^2 / W (N = omega / 2 pi in rev/s, W the static load) alone:

* **equilibrium**: the journal position where the film carries the static load W (direction
  ``load_angle``): F(X, Y) = -W (cos, sin)(load_angle), by Newton's method with the film's exact
  Jacobian (steps limited to stay inside the clearance);
* **coefficients**: K = -dF/d(y, z), C = -dF/d(y', z') at that position, from the film's
  derivatives (:meth:`ReynoldsFilm.derivatives`: the discrete solution's exact derivatives; the
  short film: central differences of its closed form);
* **as a bearing**: :class:`JournalBearing` is a :class:`~fem.rotor.model.Bearing` whose 8
  coefficients are this table over ``speeds`` (pchip), so modal, Campbell, unbalance response and
  stability use it like a typed-in table; in a run-up (:mod:`fem.rotor.runup`) its nonlinear film
  force acts instead (:meth:`JournalBearing.planar_law`).

The static load is ``load`` (N) along ``load_angle`` (the force the shaft puts on the bearing,
from +y towards +z; default -90 deg: gravity along -z), or, when ``load`` is None, the rotor's
weight on rigid supports at its bearings (:mod:`.static_load`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from discrete import checks
from discrete.errors import ModelError, SolverError

from ..model import BEARING_COEFFICIENTS, Bearing
from .reynolds import CAVITATION, ReynoldsFilm
from .short_film import ShortFilm

FILM_MODELS = ("reynolds", "short")
MAX_ECCENTRICITY = 0.98
_TABLES: dict = {}
"""Operating points per (speeds, load, geometry, film): computed once per process (at most 32 kept)."""


@dataclass
class JournalState:
    """One operating point: ``speed`` (rad/s), ``eccentricity`` ratio e/c, ``attitude_deg`` (the
    angle from the load line to the line of centres, in the direction of rotation),
    ``position`` (y, z) of the journal centre (m), ``sommerfeld`` number, ``min_film`` (m), the
    coefficients ``K`` (N/m) and ``C`` (N s/m) as 2 x 2 (rows: force y, z), ``iterations``."""

    speed: float
    eccentricity: float
    attitude_deg: float
    position: np.ndarray
    sommerfeld: float
    min_film: float
    K: np.ndarray
    C: np.ndarray
    iterations: int

    def to_dict(self) -> dict:
        return {"speed_rad_s": self.speed, "eccentricity": self.eccentricity, "attitude_deg": self.attitude_deg,
                "position_m": self.position.tolist(), "sommerfeld": self.sommerfeld, "min_film_m": self.min_film,
                "K": self.K.tolist(), "C": self.C.tolist()}


def _angle(where: str, key: str, value) -> float:
    return checks.number(where, key, value, "an angle in rad")


@dataclass
class JournalBearing(Bearing):
    """A plain (cylindrical) journal bearing at ``x`` computed from its geometry.

    ``diameter`` D and ``length`` L of the journal (m), radial ``clearance`` c (m), lubricant
    ``viscosity`` mu (Pa s, isoviscous); ``load`` (N) the static load it carries along
    ``load_angle`` (rad, from +y towards +z; default -pi/2) or None (the rotor's weight share);
    ``film`` "reynolds" (finite length, scikit-fem, ``cavitation`` "reynolds" or "gumbel",
    ``mesh`` = (elements around, elements along the half length)) or "short" (Ocvirk's closed
    form, Guembel's pi film); ``grooves`` ((centre, width), ...) in rad: axial supply grooves at
    ambient pressure (finite film only); ``speeds`` (rad/s, > 0, increasing): the grid of the
    coefficient table the linear analyses interpolate (``interpolation``, default pchip)."""

    diameter: float = 0.0
    length: float = 0.0
    clearance: float = 0.0
    viscosity: float = 0.0
    load: float | None = None
    load_angle: float = -0.5 * math.pi
    film: str = "reynolds"
    cavitation: str = "reynolds"
    grooves: tuple = ()
    mesh: tuple = (144, 16)
    interpolation: str = "pchip"
    _static_load: np.ndarray | None = field(default=None, repr=False, compare=False)
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    kind = "journal_bearing"
    nonlinear = True
    """Runs with a nonlinear law in time runs (:meth:`planar_law`)."""

    # ---------------------------------------------------------------- checks
    def check(self, where: str) -> None:
        checks.number(where, "x", self.x, "a position in m")
        for key in ("diameter", "length", "clearance", "viscosity"):
            checks.positive(where, key, getattr(self, key))
        if not self.clearance < 0.05 * self.diameter:
            raise ModelError(where, "clearance", self.clearance, f"a radial clearance well below the radius "
                             f"(< 0.05 D = {0.05 * self.diameter:g} m; typically 1e-3 D)")
        if self.load is not None:
            checks.positive(where, "load", self.load, "N (or leave it out: the rotor's weight share)")
        _angle(where, "load_angle", self.load_angle)
        checks.choice(where, "film", self.film, FILM_MODELS)
        checks.choice(where, "cavitation", self.cavitation, CAVITATION)
        checks.choice(where, "interpolation", self.interpolation, ("linear", "pchip"))
        if self.speeds is None:
            raise ModelError(where, "speeds", None,
                             "the speeds of the coefficient table (rad/s, >= 2, increasing, > 0)")
        grid = self.speed_grid
        if grid.size < 2 or not np.all(np.isfinite(grid)) or np.any(np.diff(grid) <= 0) or grid[0] <= 0:
            raise ModelError(where, "speeds", list(grid), "at least two increasing speeds > 0 (rad/s): the film "
                             "carries no load at rest")
        mesh = tuple(self.mesh)
        if len(mesh) != 2 or any(isinstance(m, bool) or not isinstance(m, (int, np.integer)) for m in mesh) \
                or mesh[0] < 12 or mesh[1] < 2:
            raise ModelError(where, "mesh", list(mesh),
                             "[elements around (>= 12), elements along the half length (>= 2)]")
        for i, g in enumerate(self.grooves):
            if np.size(g) != 2:
                raise ModelError(where, "grooves", list(map(list, self.grooves)), "[[centre, width], ...] in rad")
            _angle(where, f"grooves[{i}] centre", g[0])
            w = checks.bounded(where, f"grooves[{i}] width", g[1], (">", 0.0), ("<", math.pi), "rad")
            del w
        if self.grooves and self.film == "short":
            raise ModelError(where, "grooves", list(map(list, self.grooves)), "no grooves with film = 'short' "
                             "(the closed form has none; use film = 'reynolds')")
        for key in ("k_axial", "c_axial"):
            checks.non_negative(where, key, getattr(self, key))
        for key in BEARING_COEFFICIENTS:
            if getattr(self, key) != 0.0:
                raise ModelError(where, key, getattr(self, key), "no typed-in coefficients: a journal bearing "
                                 "computes them from its geometry")

    # ---------------------------------------------------------------- the film
    @property
    def radius(self) -> float:
        return 0.5 * self.diameter

    @property
    def length_scale(self) -> float:
        """The law's length (the clearance, m): the integrators' absolute tolerances."""
        return self.clearance

    @property
    def force_scale(self) -> float:
        """mu R^4 / c^2 (N s): F = force_scale * f."""
        return self.viscosity * self.radius ** 4 / self.clearance ** 2

    def film_model(self):
        """The dimensionless film (built once per geometry)."""
        key = ("film", self.diameter, self.length, self.film, self.cavitation, tuple(map(tuple, self.grooves)),
               tuple(self.mesh))
        if key not in self._cache:
            ld = self.length / self.diameter
            self._cache.clear()
            self._cache[key] = (ShortFilm(ld, "pi") if self.film == "short" else
                                ReynoldsFilm(ld, int(self.mesh[0]), int(self.mesh[1]), self.cavitation,
                                             [tuple(map(float, g)) for g in self.grooves]))
        return self._cache[key]

    def _film_eval(self, X, Y, a, b, jacobian: bool):
        film = self.film_model()
        return film.force_and_jacobian(X, Y, a, b) if jacobian else (film.force(X, Y, a, b), None)

    # ---------------------------------------------------------------- static load
    @property
    def needs_weight_load(self) -> bool:
        return self.load is None

    def set_weight_load(self, force_yz) -> None:
        """The static load from the rotor's weight (called by the assembly, :mod:`.static_load`)."""
        self._static_load = np.asarray(force_yz, dtype=float)

    def static_load(self) -> np.ndarray:
        """(W_y, W_z): the force the shaft puts on the bearing, N."""
        if self.load is not None:
            return self.load * np.array([math.cos(self.load_angle), math.sin(self.load_angle)])
        if self._static_load is None:
            raise ModelError(f"journal bearing at x = {self.x!r}", "load", None, "a static load (N), or a bearing "
                             "assembled with its rotor (its weight share)")
        if not np.hypot(*self._static_load) > 0:
            raise ModelError(f"journal bearing at x = {self.x!r}", "load", 0.0, "a bearing that carries some of "
                             "the rotor's weight (give `load` explicitly)")
        return self._static_load

    # ---------------------------------------------------------------- operating points
    def sommerfeld(self, speed: float, load: float | None = None) -> float:
        """S = mu N L D (R/c)^2 / W (N in rev/s)."""
        W = float(np.hypot(*self.static_load())) if load is None else float(load)
        N = speed / (2 * math.pi)
        return self.viscosity * N * self.length * self.diameter * (self.radius / self.clearance) ** 2 / W

    def operating_point(self, speed: float, start=None) -> JournalState:
        """Equilibrium, Sommerfeld number and coefficients at ``speed`` (rad/s, > 0)."""
        speed = checks.positive(f"journal bearing at x = {self.x!r}", "speed", speed, "rad/s")
        Wv = self.static_load()
        k = self.force_scale * speed
        target = -Wv / k                                  # f(X, Y; a = -6X, b = 6Y) at unit speed
        X = self._start(target) if start is None else np.asarray(start, dtype=float)
        it = 0
        for it in range(1, 101):
            f, J = self._film_eval(X[0], X[1], -6 * X[0], 6 * X[1], True)
            r = f - target
            if np.linalg.norm(r) <= 1e-11 * np.linalg.norm(target):
                break
            Jt = J[:, :2] + J[:, 2:] @ np.array([[-6.0, 0.0], [0.0, 6.0]])
            step = -np.linalg.solve(Jt, r)
            lam = 1.0
            while np.hypot(*(X + lam * step)) > MAX_ECCENTRICITY + 0.015 and lam > 1e-4:
                lam *= 0.5
            X = X + lam * step
        else:
            raise SolverError(f"journal bearing at x = {self.x:g} m: no equilibrium found at {speed:.6g} rad/s")
        e = float(np.hypot(*X))
        if e > MAX_ECCENTRICITY:
            raise ModelError(f"journal bearing at x = {self.x!r}", "speeds", speed,
                             f"speeds where the film carries the load with an eccentricity ratio <= {MAX_ECCENTRICITY} "
                             f"(at {speed:.6g} rad/s it is {e:.4f}, Sommerfeld number {self.sommerfeld(speed):.4g}): "
                             "raise the table's lowest speed")
        f, J = self._film_eval(X[0], X[1], -6 * X[0], 6 * X[1], True)
        c, s = self.clearance, self.force_scale
        Jt = J[:, :2] + J[:, 2:] @ np.array([[-6.0, 0.0], [0.0, 6.0]])
        K = -s * speed * Jt / c                        # -dF/d(y, z)
        C = -s * 12.0 / c * J[:, [3, 2]]               # dF/dy' through b, dF/dz' through a
        load_dir = Wv / np.linalg.norm(Wv)
        cross = load_dir[0] * X[1] - load_dir[1] * X[0]
        att = math.degrees(math.atan2(cross, load_dir @ X))
        return JournalState(speed=float(speed), eccentricity=e, attitude_deg=float(att), position=X * c,
                            sommerfeld=self.sommerfeld(speed), min_film=(1 - e) * c, K=K, C=C, iterations=it)

    def _start(self, target) -> np.ndarray:
        """A first guess: the short-bearing equilibrium of the same load (magnitude and attitude)."""
        short = ShortFilm(self.length / self.diameter)
        mag = np.linalg.norm(target)
        lo, hi = 1e-6, 0.995
        for _ in range(60):
            e = 0.5 * (lo + hi)
            if np.linalg.norm(short.force(e, 0.0, -6 * e, 0.0)) < mag:
                lo = e
            else:
                hi = e
        e = min(0.5 * (lo + hi), 0.9)
        f = short.force(e, 0.0, -6 * e, 0.0)
        rot = math.atan2(target[1], target[0]) - math.atan2(f[1], f[0])
        return e * np.array([math.cos(rot), math.sin(rot)])

    def states(self, speeds=None) -> list[JournalState]:
        """Operating points over ``speeds`` (default: the table's), each Newton started from the last."""
        grid = self.speed_grid if speeds is None else np.asarray(speeds, dtype=float)
        key = ("states", tuple(grid), tuple(self.static_load()), self.viscosity, self.clearance, self.diameter,
               self.length, self.film, self.cavitation, tuple(map(tuple, self.grooves)), tuple(self.mesh))
        if key not in _TABLES:                     # shared by identical bearings (the two ends of a rotor)
            out, start = [], None
            for s in grid:
                st = self.operating_point(float(s), start)
                start = st.position / self.clearance
                out.append(st)
            if len(_TABLES) >= 32:
                _TABLES.pop(next(iter(_TABLES)))
            _TABLES[key] = out
        return _TABLES[key]

    def table(self) -> dict[str, np.ndarray]:
        """The 8 coefficients over ``speeds`` (computed at the operating point of every speed)."""
        st = self.states()
        K = np.array([s.K for s in st])
        C = np.array([s.C for s in st])
        return {"kyy": K[:, 0, 0], "kyz": K[:, 0, 1], "kzy": K[:, 1, 0], "kzz": K[:, 1, 1],
                "cyy": C[:, 0, 0], "cyz": C[:, 0, 1], "czy": C[:, 1, 0], "czz": C[:, 1, 1]}

    # ---------------------------------------------------------------- time runs
    def planar_law(self):
        """The nonlinear film force for time runs: law(y, z, y', z', speed, angle) -> (F_y, F_z), N."""
        return FilmLaw(self)


class FilmLaw:
    """The journal film's force on the shaft at a state (relative to the bearing), for time runs.
    ``cost``: the finite film solves a (warm-started) cavitation problem per evaluation."""

    work = "bearings"

    def __init__(self, bearing: JournalBearing):
        self.bearing = bearing
        self.film = bearing.film_model()
        self.c = bearing.clearance
        self.k = bearing.force_scale

    def __call__(self, y, z, yd, zd, speed, angle=0.0):
        X, Y, Xd, Yd = y / self.c, z / self.c, yd / self.c, zd / self.c
        if X * X + Y * Y >= 1.0:          # the film has closed: no force (an integrator rejects the step)
            return math.nan, math.nan
        a = -6.0 * speed * X + 12.0 * Yd
        b = 6.0 * speed * Y + 12.0 * Xd
        f = self.film.force(X, Y, a, b)
        return self.k * f[0], self.k * f[1]
