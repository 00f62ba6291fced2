"""Named loads and motions as linear functionals of a drive's motion: one :class:`LoadMap` gives every
output of every analysis from the same few signals.

A lumped or hybrid drive is solved in its own coordinates q (``n`` of them: independent bodies, the
drivers, the reduced FE part).  Every quantity an engineer reads -- the deflection and the force of a
spring, a damper, a gear pair or a nonsmooth element, a driver's reaction, a body's displacement,
velocity or acceleration -- is, at every instant or frequency, a linear combination

    y = X q + V q' + A q'' + Fe f_el + Fa f_app + c

of the coordinates, their rates, the element forces ``f_el`` (the force along s of each nonsmooth
element, its law's value or its Lagrange multiplier in stick / persistent contact) and the applied
loads ``f_app`` (one value per source: a ``[[force]]`` table, a harmonic load).  A :class:`LoadMap`
holds these rows, one per :class:`Channel`; :meth:`LoadMap.values` evaluates them for a whole time
history (real arrays) or a frequency response (complex amplitudes, ``q' = i omega Q``) at once.

Sign convention (docs/outputs.md): the ``force`` of an element is the generalised force it exerts on
its second end (``b`` of ``between = [a, b]``, or its ``body``) per unit of that end's ratio: the end
``b`` receives ``r_b F``, the end ``a`` receives ``-r_a F`` (the element's force ``F`` of
:mod:`discrete.nonsmooth.elements.base`).  A drive written from the motor (``a``) to the load (``b``)
transmits a positive torque.  A linear spring of stiffness k then carries ``F = -k s`` with the
deflection ``s = r_b x_b - r_a x_a``.  A reaction is the force the driver or support exerts on the
drive (the torque a driver must supply).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import ModelError

#: the quantity words of outputs, and their kind (a motion of a coordinate, or a force)
MOTIONS = ("displacement", "velocity", "acceleration", "deflection", "twist", "slip_velocity")
FORCES = ("force", "torque", "moment", "reaction", "impulse")
QUANTITIES = MOTIONS + FORCES

_UNITS = {
    # quantity: (generalised coordinate (m or rad), translational, rotational)
    "displacement": ("m | rad", "m", "rad"),
    "deflection": ("m | rad", "m", "rad"),
    "twist": ("rad", "rad", "rad"),
    "velocity": ("m/s | rad/s", "m/s", "rad/s"),
    "slip_velocity": ("m/s | rad/s", "m/s", "rad/s"),
    "acceleration": ("m/s^2 | rad/s^2", "m/s^2", "rad/s^2"),
    "force": ("N | N m", "N", "N m"),
    "reaction": ("N | N m", "N", "N m"),
    "torque": ("N m", "N m", "N m"),
    "moment": ("N m", "N m", "N m"),
    "impulse": ("N s | N m s", "N s", "N m s"),
}


def unit_of(quantity: str, motion: str | None = None) -> str:
    """The SI unit of ``quantity`` for a coordinate of kind ``motion``: "translation", "rotation" or None
    (a lumped coordinate, whose kind the model file does not state: ``"m | rad"``, ``"N | N m"``)."""
    generic, trans, rot = _UNITS[quantity]
    return {"translation": trans, "rotation": rot}.get(motion, generic)


@dataclass
class Channel:
    """One named output: ``name`` (the column of the CSV, the key of the JSON, the legend of a plot),
    the ``quantity`` word and its ``unit``, the ``source`` (the model-file table of the thing it
    measures: spring, damper, gear, driver, body, support, force, or the element's table) and ``where``
    (that thing's name).  ``acts_on`` ({coordinate name: coefficient}) says, for a force, which
    generalised force it puts on each named coordinate per unit of its value (the balance of every
    body sums them); ``info`` holds what a reader needs to interpret it (ratios, ends, kind)."""

    name: str
    quantity: str
    unit: str
    source: str
    where: str
    acts_on: dict = field(default_factory=dict)
    info: dict = field(default_factory=dict)

    @property
    def is_force(self) -> bool:
        return self.quantity in FORCES

    def describe(self) -> dict:
        d = {"quantity": self.quantity, "unit": self.unit, "source": self.source, "where": self.where}
        d.update(self.info)
        return d


@dataclass
class LoadMap:
    """Rows ``X``, ``V``, ``A`` (n_channels x n), ``Fe`` (n_channels x n_elements), ``Fa``
    (n_channels x n_sources) and ``offset`` (n_channels) of the channels: see the module docstring.
    Rows may be complex (a hysteretic loss stiffness in a frequency response)."""

    channels: list[Channel]
    X: np.ndarray
    V: np.ndarray
    A: np.ndarray
    Fe: np.ndarray
    Fa: np.ndarray
    offset: np.ndarray
    At: np.ndarray | None = None
    """Rows of t q'' (a variable inertia M0 + t Mdot, seed 004): None when no channel has one."""

    @classmethod
    def empty(cls, n: int, n_el: int, n_src: int) -> "LoadMap":
        z = np.zeros((0, n))
        return cls([], z, z.copy(), z.copy(), np.zeros((0, n_el)), np.zeros((0, n_src)), np.zeros(0))

    @property
    def names(self) -> list[str]:
        return [c.name for c in self.channels]

    def __len__(self) -> int:
        return len(self.channels)

    def add(self, channel: Channel, X=None, V=None, A=None, Fe=None, Fa=None, offset=0.0, At=None, **_) -> None:
        """Append a channel with its rows (None: zeros)."""
        if channel.name in self.names:
            raise ModelError("outputs", "name", channel.name, "a name used by one output only")

        def row(M, r):
            r = np.zeros(M.shape[1]) if r is None else np.asarray(r).reshape(M.shape[1])
            return np.vstack([M.astype(np.result_type(M, r)), r[None, :]])

        if At is not None or self.At is not None:
            self.At = row(np.zeros((len(self), self.X.shape[1])) if self.At is None else self.At, At)
        self.X, self.V, self.A = row(self.X, X), row(self.V, V), row(self.A, A)
        self.Fe, self.Fa = row(self.Fe, Fe), row(self.Fa, Fa)
        self.offset = np.append(self.offset, offset)
        self.channels.append(channel)

    def rows(self, name: str) -> dict:
        """The rows X, V, A, Fe, Fa and offset of the channel ``name``."""
        i = self.names.index(name)
        out = {"X": self.X[i], "V": self.V[i], "A": self.A[i], "Fe": self.Fe[i], "Fa": self.Fa[i],
               "offset": self.offset[i]}
        if self.At is not None:
            out["At"] = self.At[i]
        return out

    def take(self, names) -> "LoadMap":
        """The channels ``names`` in that order."""
        idx = [self.names.index(n) for n in names]
        return LoadMap([self.channels[i] for i in idx], self.X[idx], self.V[idx], self.A[idx], self.Fe[idx],
                       self.Fa[idx], self.offset[idx], None if self.At is None else self.At[idx])

    def substituted(self, Lx, Lv, La, Lf) -> "LoadMap":
        """The map with the element forces written as ``f_el = Lx q + Lv q' + La q'' + Lf f_app`` (a
        linear analysis: each nonsmooth element replaced by its declared linearisation)."""
        F = self.Fe
        return LoadMap(self.channels, self.X + F @ Lx, self.V + F @ Lv, self.A + F @ La, np.zeros((len(self), 0)),
                       self.Fa + F @ Lf, self.offset.copy(), self.At)

    def values(self, x, v, a, f_el=None, f_app=None, t=None) -> np.ndarray:
        """(n_channels, m) values for states with one column per instant (or frequency); ``t``: the
        instants (needed only with a variable inertia, ``At``)."""
        x = np.asarray(x)
        m = x.shape[1] if x.ndim == 2 else 1
        out = self.X @ x.reshape(-1, m)
        if self.At is not None and np.any(self.At):
            out = out + self.At @ (np.asarray(a).reshape(-1, m) * np.asarray(t, dtype=float).reshape(1, m))
        for R, s in ((self.V, v), (self.A, a), (self.Fe, f_el), (self.Fa, f_app)):
            if R.size and s is not None and np.any(R):
                out = out + R @ np.asarray(s).reshape(R.shape[1], m)
        if np.any(self.offset):
            out = out + self.offset[:, None]
        return out


# --------------------------------------------------------------------- derived quantities
def time_mean(t: np.ndarray, y: np.ndarray) -> float:
    """Time average of samples y(t) (trapezoid on the recorded instants: event-dense sampling is
    weighted by the time it covers; several samples at one instant add nothing)."""
    return float(time_means(t, np.asarray(y, dtype=float)[None])[0]) if np.size(y) else 0.0


def time_means(t: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """:func:`time_mean` along the last axis of Y (histories over the instants t: one row (N,) for all, or
    one row per history broadcasting against Y's leading axes, e.g. t (P, N) for Y (k, P, N))."""
    t = np.asarray(t, dtype=float)
    if Y.shape[-1] == 0:
        return np.zeros(Y.shape[:-1])
    span = t[..., -1] - t[..., 0]
    trap = np.sum(0.5 * (Y[..., 1:] + Y[..., :-1]) * np.diff(t, axis=-1), axis=-1)
    flat = span <= 0                      # no time covered: the plain mean of the samples
    if np.all(flat):
        return np.mean(Y, axis=-1)
    if not np.any(flat):
        return trap / span
    return np.where(flat, np.mean(Y, axis=-1), trap / np.where(flat, 1.0, span))


def history_quantities(t: np.ndarray, Y: np.ndarray) -> dict:
    """{peak (max |y|), max, min, mean, rms} along the last axis of Y (t as in :func:`time_means`), arrays
    over Y's leading axes."""
    Y = np.asarray(Y, dtype=float)
    return {"peak": np.max(np.abs(Y), axis=-1), "max": np.max(Y, axis=-1), "min": np.min(Y, axis=-1),
            "mean": time_means(t, Y), "rms": np.sqrt(np.maximum(time_means(t, Y * Y), 0.0))}


def load_factor(peak: float, mean: float):
    """The dynamic load factor peak / |mean| of a force (None where the mean is zero to round-off)."""
    return peak / abs(mean) if abs(mean) > 1e-12 * max(peak, 1e-300) else None


def summaries(t: np.ndarray, Y: np.ndarray, force_like) -> list[dict]:
    """:func:`summary` of every row of Y (one history per row over the instants t; ``force_like``: one
    flag per row), in a few whole-array operations."""
    Y = np.asarray(Y, dtype=float)
    if Y.shape[1] == 0:
        return [summary(t, y, f) for y, f in zip(Y, force_like)]
    q = history_quantities(t, Y)
    out = []
    for k, f in enumerate(force_like):
        d = {"peak": float(q["peak"][k]), "max": float(q["max"][k]), "min": float(q["min"][k]),
             "mean": float(q["mean"][k]), "rms": float(q["rms"][k]), "peak_to_peak": float(q["max"][k] - q["min"][k])}
        if f:
            d["dynamic_load_factor"] = load_factor(d["peak"], d["mean"])
        out.append(d)
    return out


def summary(t: np.ndarray, y: np.ndarray, force_like: bool) -> dict:
    """Derived quantities of one time history: peak (max |y|), max, min, mean and rms (time averages),
    peak_to_peak, and for a force the dynamic load factor = peak / |mean| (peak over the mean
    transmitted load; None where the mean is zero to round-off)."""
    y = np.asarray(y, dtype=float)
    if y.size == 0:
        return {"peak": None, "max": None, "min": None, "mean": None, "rms": None, "peak_to_peak": None,
                "dynamic_load_factor": None}
    return summaries(t, y[None], [force_like])[0]


def amplitude_summary(z: np.ndarray) -> dict:
    """Derived quantities of complex amplitudes over frequencies: the largest amplitude and where."""
    amp = np.abs(np.asarray(z))
    if amp.size == 0:
        return {"peak": None, "peak_index": None}
    k = int(np.argmax(amp))
    return {"peak": float(amp[k]), "peak_index": k}
