"""Speed tables of bearing coefficients: interpolation inside the table, the declared extrapolation outside.

Inside ``[speeds[0], speeds[-1]]`` a coefficient is interpolated: ``linear``, ``pchip``
(Fritsch-Carlson shape-preserving cubic) or ``spline`` (the cubic spline through the points with
not-a-knot ends, scipy's ``CubicSpline``; FITPACK's interpolating spline is the same function, and
ROSS's ``UnivariateSpline`` with its default smoothing tends to it as the smoothing vanishes).
Outside, ``extrapolate`` decides:

* ``refuse`` (default): a :class:`~discrete.errors.ModelError` naming the bearing, the speed and the
  table's range;
* ``hold``: the end values (a flat continuation);
* ``linear``: the tangent line of the interpolant at the table's end, c(s) = c(s_end) + c'(s_end)
  (s - s_end): for linear interpolation the end segment's line, for pchip and spline their end
  slopes (a C^1 continuation).

An extrapolation warns once per bearing and side (again when a later call reaches further out),
naming the bearing and the speeds outside its table.  Extrapolated damping must stay dissipative
(the symmetric part of C positive semidefinite, as the table itself: see
:class:`fem.rotor.model.Bearing`); stiffness may change sign (a seal's, ROSS's extrapolated
compressor seals reach kyy = -22034 N/m at rest).
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import CubicSpline, PchipInterpolator

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
        """dc/dOmega (8,) of the interpolant at the first and the last speed of the table."""
        curve = self._interpolant()
        g, v = self.grid, self.values
        if curve is None:
            return (v[:, 1] - v[:, 0]) / (g[1] - g[0]), (v[:, -1] - v[:, -2]) / (g[-1] - g[-2])
        d = curve.derivative()
        return d(g[0]), d(g[-1])

    def values_at(self, speeds) -> np.ndarray:
        """(n_speeds, 8) coefficients with the declared extrapolation, unchecked (``refuse`` clips;
        :meth:`at` is the checked entry)."""
        s = np.atleast_1d(np.asarray(speeds, dtype=float))
        lo, hi = self.grid[0], self.grid[-1]
        out = self._inside(np.clip(s, lo, hi))
        if self.extrapolate == "linear":
            below, above = s < lo, s > hi
            if below.any() or above.any():
                d_lo, d_hi = self.end_slopes()
                out[:, below] += d_lo[:, None] * (s[below] - lo)[None, :]
                out[:, above] += d_hi[:, None] * (s[above] - hi)[None, :]
        return out.T

    def at(self, speeds) -> np.ndarray:
        """(n_speeds, 8) coefficients at ``speeds``; outside the table as ``extrapolate`` says (an
        error for ``refuse``, a warning otherwise; extrapolated damping checked)."""
        s = np.atleast_1d(np.asarray(speeds, dtype=float))
        lo, hi = self.grid[0], self.grid[-1]
        outside = s[(s < lo * (1 - 1e-12)) | (s > hi * (1 + 1e-12))]
        if not outside.size:
            return self._inside(np.clip(s, lo, hi)).T
        if self.extrapolate == "refuse":
            raise ModelError(self.where, "speed", float(outside[0]),
                             f"a speed inside the bearing table's range [{lo:g}, {hi:g}] rad/s (extrapolate = "
                             "'refuse': extend its `speeds`, or declare extrapolate = 'hold' or 'linear')")
        self._warn(outside, lo, hi)
        vals = self.values_at(s)
        bad = damping_not_dissipative(vals.T)
        if bad is not None:
            j, key = bad
            raise ModelError(self.where, key, float(vals[j, BEARING_COEFFICIENTS.index(key)]),
                             f"{DAMPING_RULE} at the extrapolated speed {s[j]:g} rad/s (extrapolate = "
                             f"{self.extrapolate!r} outside [{lo:g}, {hi:g}] rad/s): use 'hold' or extend the table")
        return vals

    def _warn(self, outside: np.ndarray, lo: float, hi: float) -> None:
        below, above = outside[outside < lo], outside[outside > hi]
        parts = []
        if below.size and below.min() < self._warned[0]:
            self._warned[0] = float(below.min())
            parts.append(f"{below.min():g} ... {lo:g} rad/s below")
        if above.size and above.max() > self._warned[1]:
            self._warned[1] = float(above.max())
            parts.append(f"{hi:g} ... {above.max():g} rad/s above")
        if parts:
            how = "held at the end values" if self.extrapolate == "hold" else "extrapolated linearly"
            warnings.warn(f"{self.label}: speeds {' and '.join(parts)} its table [{lo:g}, {hi:g}] rad/s: "
                          f"coefficients {how} (extrapolate = {self.extrapolate!r})", stacklevel=3)
