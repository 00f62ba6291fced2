"""The named outputs of each analysis of a lumped or hybrid file, evaluated from the drive's load map:

* :func:`time_outputs`: time histories of a simulation (and of one period of a steady orbit), with the
  derived quantities of each (peak, rms, peak-to-peak, mean, dynamic load factor) and, per element, the
  impacts (count, impulse sum) and the friction work;
* :func:`modal_outputs`: the load shape of each mode (every output for the mode shape as the motion,
  q'' = -omega^2 q);
* :func:`forced_outputs`: the complex amplitude of every output at every frequency.

Each returns a :class:`NamedOutputs`: one table of named columns over an axis (time, mode, frequency),
the one shape the output layer writes (JSON, CSV, --h5, plots).  The section loads and reactions of FE
shafts and rotors (:mod:`fem.loads.shaft`) join a table with :meth:`NamedOutputs.extend`."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from discrete.loads import LoadMap, amplitude_summary, summaries


@dataclass
class NamedOutputs:
    """``values[k]`` is the column ``channels[k]`` over ``axis_values`` (``axis``: "t" (s), "mode" (1, 2,
    ...) or "omega" (rad/s: the frequencies of a forced response, the speeds of an unbalance response));
    ``summaries``: {name: derived quantities}; ``elements``: {element name: impacts, impulse sum, friction
    work} (time histories); ``notes``: what the values leave out or how they are scaled."""

    axis: str
    axis_values: np.ndarray
    channels: list
    values: np.ndarray
    summaries: dict = field(default_factory=dict)
    elements: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)

    @property
    def names(self) -> list[str]:
        return [c.name for c in self.channels]

    def column(self, name: str) -> np.ndarray:
        return self.values[self.names.index(name)]

    def extend(self, channels: list, values: np.ndarray, notes=()) -> None:
        """Add the columns of another source over the same axis (the section loads and reactions of FE
        shafts and rotors: :mod:`fem.loads.shaft`), with their derived quantities."""
        if not channels:
            self.notes += [n for n in notes if n not in self.notes]
            return
        taken = set(self.names)
        clash = next((c.name for c in channels if c.name in taken), None)
        if clash is not None:
            from discrete.errors import ModelError

            raise ModelError("outputs", "name", clash, "a name used by one output only")
        values = np.asarray(values).reshape(len(channels), self.axis_values.size)
        self.channels = list(self.channels) + list(channels)
        self.values = np.vstack([self.values, values]) if self.values.size else values
        self.summaries.update(derived(self.axis, self.axis_values, channels, values))
        self.notes += [n for n in notes if n not in self.notes]

    def take(self, idx) -> "NamedOutputs":
        """The outputs at the samples ``idx`` of the axis (decimation of a time history)."""
        return NamedOutputs(self.axis, self.axis_values[idx], self.channels, self.values[:, idx], self.summaries,
                            self.elements, self.notes)

    def subset(self, idx) -> "NamedOutputs":
        """The columns ``idx`` (indices of channels) over the same axis."""
        idx = list(idx)
        return NamedOutputs(self.axis, self.axis_values, [self.channels[k] for k in idx], self.values[idx],
                            {self.channels[k].name: self.summaries.get(self.channels[k].name, {}) for k in idx},
                            self.elements, self.notes)

    def ordered(self, names: list) -> None:
        """Put the columns in the order of ``names`` (the [[output]] tables' order)."""
        idx = [self.names.index(n) for n in names]
        self.channels = [self.channels[i] for i in idx]
        self.values = self.values[idx] if self.values.size else self.values

    def describe(self) -> dict:
        """{name: channel description + derived quantities} (the JSON ``named_outputs`` of a time history)."""
        return {c.name: {**c.describe(), **self.summaries.get(c.name, {})} for c in self.channels}


def derived(axis: str, axis_values, channels, values) -> dict:
    """{name: derived quantities} of columns over an axis: time histories -- peak, max, min, mean, rms,
    peak-to-peak, dynamic load factor (:func:`discrete.loads.summary`); frequencies (speeds) -- the peak
    amplitude and its frequency (speed); modes -- none."""
    out = {}
    if axis == "t" and len(channels):
        rows = summaries(axis_values, np.real(np.asarray(values)).reshape(len(channels), -1),
                         [c.is_force for c in channels])
        return {c.name: r for c, r in zip(channels, rows)}
    for k, c in enumerate(channels):
        if axis in ("omega", "speed"):
            s = amplitude_summary(values[k])
            k_peak = s.pop("peak_index")
            if k_peak is not None:
                s[f"peak_{axis}_rad_s"] = float(np.asarray(axis_values)[k_peak])
            out[c.name] = s
        else:
            out[c.name] = {}
    return out


# ------------------------------------------------------------------ time histories
def time_outputs(lm: LoadMap, t, x, v, a, f_el, f_app, loads=None, events=()) -> NamedOutputs:
    """Every channel of ``lm`` over a recorded history (columns: instants), its derived quantities, and
    (``loads``: the drive's :class:`discrete.loads.DriveLoads`; ``events``: the run's events) the
    impacts and friction work of each element."""
    t = np.asarray(t, dtype=float)
    Y = lm.values(x, v, a, f_el, f_app, t)
    Y = np.real_if_close(Y)
    out = NamedOutputs("t", t, list(lm.channels), np.asarray(Y, dtype=float))
    out.summaries = derived("t", t, out.channels, out.values)
    if loads is not None:
        out.elements = element_summaries(loads, t, v, f_el, events)
    return out


def element_summaries(loads, t, v, f_el, events) -> dict:
    """Per nonsmooth element: ``impacts`` and ``impulse_sum`` (its impact events and their generalised
    impulses, from the event solver's records) and, for friction, ``friction_work`` = int F s' dt (the
    work it does on the drive: negative when it takes energy) and ``friction_dissipated`` =
    -int F (s' - surface velocity) dt (>= 0), both on the recorded samples (trapezoid)."""
    out = {}
    T = loads.coords.T
    imp: dict = {}
    for e in events:
        if e.kind == "impact":
            n, s = imp.get(e.element, (0, 0.0))
            imp[e.element] = (n + 1, s + float(getattr(e, "impulse", 0.0)))
    t = np.asarray(t, dtype=float)
    dt = np.diff(t)
    for j, es in enumerate(loads.elements):
        el = es.element
        d = {"kind": es.source}
        if el.kind == "impact" or el.name in imp:
            n, s = imp.get(el.name, (0, 0.0))
            d.update({"impacts": n, "impulse_sum": s})
        if el.work == "friction" and f_el is not None and t.size > 1:
            sd = (es.g @ T) @ v
            F = np.asarray(f_el)[j]
            p = F * sd
            w = F * (sd - getattr(el, "surface_velocity", 0.0))
            d["friction_work"] = float(np.sum(0.5 * (p[1:] + p[:-1]) * dt))
            d["friction_dissipated"] = float(-np.sum(0.5 * (w[1:] + w[:-1]) * dt))
        out[el.name] = d
    return out


def decimate(t: np.ndarray, every: int, keep=()) -> np.ndarray:
    """Indices of every ``every``-th sample, the last one, and every sample at an instant in ``keep``
    (the events: both states of an event instant are kept)."""
    n = t.size
    if every <= 1 or n == 0:
        return np.arange(n)
    mask = np.zeros(n, dtype=bool)
    mask[::every] = True
    mask[-1] = True
    if len(keep):
        mask |= np.isin(t, np.asarray(keep, dtype=float))
    return np.flatnonzero(mask)


# ------------------------------------------------------------------ linear analyses
def modal_outputs(lm: LoadMap, omega: np.ndarray, shapes: np.ndarray) -> NamedOutputs:
    """Load shapes: every channel for each mode shape (columns of ``shapes``, the solved coordinates;
    q'' = -omega^2 q, q' = 0), per unit of the mode shape as written in ``mode_shapes``."""
    om = np.asarray(omega, dtype=float)
    Q = np.asarray(shapes)
    Y = lm.values(Q, np.zeros_like(Q), -(om ** 2)[None, :] * Q, None, None)
    Y = np.real_if_close(Y)
    out = NamedOutputs("mode", np.arange(1, om.size + 1), list(lm.channels), np.asarray(Y))
    out.summaries = derived("mode", out.axis_values, out.channels, out.values)
    return out


def forced_outputs(lm_at, omegas: np.ndarray, Q: np.ndarray, loads_at) -> NamedOutputs:
    """Complex amplitudes of every channel: ``lm_at(omega)`` the load map at that frequency (element
    forces substituted), ``Q`` (n_freq x n) the complex response of the solved coordinates,
    ``loads_at(omega)`` the applied load values of the map's sources."""
    om = np.asarray(omegas, dtype=float)
    cols, chans = [], None
    for j, w in enumerate(om):
        lm = lm_at(w)
        chans = lm.channels
        q = np.asarray(Q[j], dtype=complex)[:, None]
        cols.append(lm.values(q, 1j * w * q, -w * w * q, None, loads_at(w))[:, 0])
    Y = np.array(cols).T if cols else np.zeros((0, 0), dtype=complex)
    out = NamedOutputs("omega", om, list(chans or []), Y)
    out.summaries = derived("omega", om, out.channels, Y)
    return out
