"""Speed tables of bearing coefficients: interpolation inside the table, the declared extrapolation outside.

Inside ``[speeds[0], speeds[-1]]`` a coefficient is interpolated: ``linear``, ``pchip``
(Fritsch-Carlson shape-preserving cubic), ``spline`` (the cubic spline through the points with
not-a-knot ends, scipy's ``CubicSpline``) or ``smoothing-spline``: ROSS's convention (ROSS 2.3.0,
``BearingElement._process_coefficient``): per coefficient scipy's ``UnivariateSpline(speeds,
values)`` with its defaults -- a cubic *smoothing* spline with smoothing s = the number of points,
in the coefficient's own units -- and, for 2 or 3 points, where FITPACK cannot fit a cubic, the
line or the parabola through them (``interp1d(kind=n-1)``, here the same B-spline by
``make_interp_spline``).  It is not an interpolant: it misses the table points (ROSS's compressor
example: by up to 4.5e-4 of a seal's damping), and it is what ROSS computes with.
Outside, ``extrapolate`` decides:

* ``refuse`` (default): a :class:`~discrete.errors.ModelError` naming the bearing, the speed and the
  table's range;
* ``hold``: the interpolant's end values (a flat continuation);
* ``linear``: the tangent line of the interpolant at the table's end, c(s) = c(s_end) + c'(s_end)
  (s - s_end): for linear interpolation the end segment's line, for the cubics their end
  slopes (a C^1 continuation);
* ``continue``: the interpolant's end pieces continued (its own polynomial beyond the end): for
  ``smoothing-spline`` ROSS's extrapolation (``UnivariateSpline``'s ext = 0, ``interp1d``'s
  fill_value = "extrapolate"); for linear interpolation the same as ``linear``; for the cubics
  their end cubic, which bends away from the tangent line quadratically.

An extrapolation warns once per bearing and side (again when a later call reaches further out),
naming the bearing and the speeds outside its table.  Extrapolated damping, and the smoothing
spline's damping anywhere (it does not pass through the checked table values), must stay
dissipative (the symmetric part of C positive semidefinite, as the table itself: see
:class:`fem.rotor.model.Bearing`); stiffness may change sign (a seal's, ROSS's extrapolated
compressor seals reach kyy = -22034 N/m at rest).
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import CubicSpline, PchipInterpolator, PPoly, UnivariateSpline, make_interp_spline

from discrete.errors import ModelError

from .model import BEARING_COEFFICIENTS, DAMPING_RULE, damping_not_dissipative


@dataclass
class SpeedTable:
    """A speed-dependent bearing: ``grid`` (n,) rad/s, ``values`` (8, n) in BEARING_COEFFICIENTS order."""

    index: int                      # 1-based bearing number (for messages)
    grid: np.ndarray
    values: np.ndarray
    interpolation: str = "linear"
    extrapolate: str = "refuse"
    name: str = ""
    table: str = "rotor.bearing"    # the model-file table the bearing is written in (for messages)
    x: float = 0.0
    _curve: object = field(default=None, repr=False)
    _slopes: tuple | None = field(default=None, repr=False)
    _warned: list = field(default_factory=lambda: [np.inf, -np.inf], repr=False)

    @property
    def where(self) -> str:
        return f"[[{self.table}]] #{self.index}"

    @property
    def label(self) -> str:
        """The bearing as a warning names it: number, name, position."""
        name = f" {self.name!r}" if self.name else ""
        return f"[[{self.table}]] #{self.index}{name} at x = {self.x:g} m"

    def _interpolant(self):
        if self._curve is None:
            if self.interpolation == "pchip":
                self._curve = PchipInterpolator(self.grid, self.values, axis=1)
            elif self.interpolation == "spline":
                # not-a-knot needs 4 points; with 2 or 3 CubicSpline's not-a-knot is the line or parabola
                self._curve = CubicSpline(self.grid, self.values, axis=1, bc_type="not-a-knot")
            elif self.interpolation == "smoothing-spline":
                self._curve = SmoothingSplines(self.grid, self.values, self.where)
            else:
                self._curve = None
        return self._curve

    def _inside(self, s: np.ndarray) -> np.ndarray:
        """(8, len(s)) interpolated values at speeds inside the grid."""
        curve = self._interpolant()
        if curve is not None:
            return curve(s)
        return np.stack([np.interp(s, self.grid, v) for v in self.values])

    def end_slopes(self) -> tuple[np.ndarray, np.ndarray]:
        """dc/dOmega (8,) of the interpolant at the first and the last speed of the table (computed
        once: a table does not change)."""
        if self._slopes is None:
            curve = self._interpolant()
            g, v = self.grid, self.values
            if curve is None:
                self._slopes = ((v[:, 1] - v[:, 0]) / (g[1] - g[0]), (v[:, -1] - v[:, -2]) / (g[-1] - g[-2]))
            else:
                d = curve.derivative()
                self._slopes = (d(g[0]), d(g[-1]))
        return self._slopes

    def values_at(self, speeds) -> np.ndarray:
        """(n_speeds, 8) coefficients with the declared extrapolation, unchecked (``refuse`` clips;
        :meth:`at` is the checked entry)."""
        s = np.atleast_1d(np.asarray(speeds, dtype=float))
        lo, hi = self.grid[0], self.grid[-1]
        continued = self.extrapolate == "continue" and self._interpolant() is not None
        out = self._inside(s if continued else np.clip(s, lo, hi))
        if self.extrapolate == "linear" or (self.extrapolate == "continue" and not continued):
            below, above = s < lo, s > hi
            if below.any() or above.any():
                d_lo, d_hi = self.end_slopes()
                out[:, below] += d_lo[:, None] * (s[below] - lo)[None, :]
                out[:, above] += d_hi[:, None] * (s[above] - hi)[None, :]
        return out.T

    def at(self, speeds, check: bool = True) -> np.ndarray:
        """(n_speeds, 8) coefficients at ``speeds``; outside the table as ``extrapolate`` says (an
        error for ``refuse``, a warning otherwise; extrapolated damping checked, and the smoothing
        spline's everywhere -- ``check`` False leaves the damping check to the caller, see
        :meth:`needs_damping_check`)."""
        s = np.atleast_1d(np.asarray(speeds, dtype=float))
        lo, hi = self.grid[0], self.grid[-1]
        outside = s[(s < lo * (1 - 1e-12)) | (s > hi * (1 + 1e-12))]
        if not outside.size:
            vals = self._inside(np.clip(s, lo, hi)).T
            if check and self.interpolation == "smoothing-spline":
                self._check_damping(vals, s, "at the speed {:g} rad/s (the smoothing spline does not pass through "
                                    "the table's values): use another interpolation")
            return vals
        if self.extrapolate == "refuse":
            raise ModelError(self.where, "speed", float(outside[0]),
                             f"a speed inside the bearing table's range [{lo:g}, {hi:g}] rad/s (extrapolate = "
                             "'refuse': extend its `speeds`, or declare extrapolate = 'hold', 'linear' or 'continue')")
        self._warn(outside, lo, hi)
        vals = self.values_at(s)
        if check:
            self._check_damping(vals, s, f"at the extrapolated speed {{:g}} rad/s (extrapolate = {self.extrapolate!r} "
                                f"outside [{lo:g}, {hi:g}] rad/s): use 'hold' or extend the table")
        return vals

    def needs_damping_check(self, speeds: np.ndarray) -> bool:
        """Whether :meth:`at` checks the damping at these speeds (values that are not the checked
        table values: extrapolated ones, and the smoothing spline's)."""
        lo, hi = self.grid[0], self.grid[-1]
        return self.interpolation == "smoothing-spline" or bool(np.any((speeds < lo * (1 - 1e-12))
                                                                        | (speeds > hi * (1 + 1e-12))))

    def _check_damping(self, vals: np.ndarray, s: np.ndarray, where: str) -> None:
        bad = damping_not_dissipative(vals.T)
        if bad is not None:
            j, key = bad
            raise ModelError(self.where, key, float(vals[j, BEARING_COEFFICIENTS.index(key)]),
                             f"{DAMPING_RULE} {where.format(s[j])}")

    def _warn(self, outside: np.ndarray, lo: float, hi: float) -> None:
        if outside.min() >= self._warned[0] and outside.max() <= self._warned[1]:
            return                                   # warned already as far out
        below, above = outside[outside < lo], outside[outside > hi]
        parts = []
        if below.size and below.min() < self._warned[0]:
            self._warned[0] = float(below.min())
            parts.append(f"{below.min():g} ... {lo:g} rad/s below")
        if above.size and above.max() > self._warned[1]:
            self._warned[1] = float(above.max())
            parts.append(f"{hi:g} ... {above.max():g} rad/s above")
        if parts:
            how = {"hold": "held at the end values", "linear": "extrapolated linearly",
                   "continue": "extrapolated along the smoothing spline's end cubics (ROSS's convention)"
                   if self.interpolation == "smoothing-spline" else "extrapolated along the interpolant's end pieces"
                   }[self.extrapolate]
            warnings.warn(f"{self.label}: speeds {' and '.join(parts)} its table [{lo:g}, {hi:g}] rad/s: "
                          f"coefficients {how} (extrapolate = {self.extrapolate!r})", stacklevel=3)


class SmoothingSplines:
    """ROSS's interpolation of a bearing table, row by row (ROSS 2.3.0,
    ``BearingElement._process_coefficient``): ``UnivariateSpline(speeds, row)`` with scipy's
    defaults (k = 3, smoothing s = number of points, ext = 0: the end cubics continue outside);
    for 2 or 3 points, where FITPACK cannot fit a cubic, the B-spline of degree n - 1 through them
    (what ROSS's ``interp1d(kind=n-1, fill_value="extrapolate")`` evaluates).  FITPACK's warnings
    about its smoothing iteration are silenced, as ROSS does; the spline is the same function.

    For speed the rows (each with its own knots: the smoothing spline places them) are re-expanded
    once into one piecewise cubic on the union of their knots (Taylor coefficients from FITPACK's
    derivatives at each knot, right-hand pieces), so a table is evaluated in one call; the end
    pieces continue outside as FITPACK's do.  Equal to FITPACK's evaluation of the row splines to
    round-off (ROSS's compressor tables: 8e-16 of a row's largest value inside the tables, 1e-14
    extrapolated to rest); one call per table instead of one per coefficient (0.15 instead of
    0.7 ms per speed for the compressor's 14 tables)."""

    def __init__(self, grid: np.ndarray, values: np.ndarray, where: str = ""):
        from math import factorial

        rows = []
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for row in values:
                if grid.size >= 4:
                    try:
                        rows.append(UnivariateSpline(grid, row))
                        continue
                    except Exception as exc:          # FITPACK's error type is not public (ROSS: a bare except)
                        raise ModelError(where, "speeds", grid.tolist(), "speeds FITPACK can fit a smoothing "
                                         f"spline to ({exc})") from None
                rows.append(make_interp_spline(grid, row, k=grid.size - 1))
        knots = [r.get_knots() if isinstance(r, UnivariateSpline) else r.t[r.k:r.t.size - r.k] for r in rows]
        breaks = np.unique(np.concatenate(knots))
        coef = np.zeros((4, breaks.size - 1, len(rows)))
        for j, r in enumerate(rows):
            for m in range(4 if isinstance(r, UnivariateSpline) else r.k + 1):
                d = r.derivative(m) if m else r
                coef[3 - m, :, j] = np.asarray(d(breaks[:-1]), dtype=float).ravel() / factorial(m)
        self.rows = rows
        self.piecewise = PPoly(coef, breaks, extrapolate=True)

    def __call__(self, s) -> np.ndarray:
        """(8, len(s)) values, (8,) at a scalar speed (extrapolated outside the table, as ROSS does)."""
        x = np.asarray(s, dtype=float)
        out = self.piecewise(np.atleast_1d(x)).T
        return out[:, 0] if x.ndim == 0 else out

    def derivative(self):
        d = self.piecewise.derivative()
        return lambda s: (lambda x, v: v[:, 0] if x.ndim == 0 else v)(np.asarray(s, dtype=float),
                                                                      d(np.atleast_1d(np.asarray(s, float))).T)
