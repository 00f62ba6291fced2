"""Time histories in one binary container (``--h5 OUT.h5``): HDF5 through h5py, one layout, readable
without drivefem (any HDF5 reader: h5py, MATLAB's h5read, pandas via h5py, HDFView).  Layout
``drivefem.history`` version 1 (docs/outputs.md):

    /                 attributes: schema = "drivefem.history", version = 1, command, title, kind,
                      record_every, n_samples_recorded
    /t                (n,) float64, s
    /outputs/values   (n, n_outputs) float64: the named outputs, one column each (as the CSV)
    /outputs/names    (n_outputs,) UTF-8 strings: column names ("spring[1] top-disk.force", ...)
    /outputs/quantity, /outputs/unit, /outputs/source, /outputs/where   (n_outputs,) strings
    /states/x, /states/v   (n, n_dofs) float64: the solved coordinates and their velocities
    /states/names     (n_dofs,) strings
    /energy/energy, /energy/work   (n,) float64 (absent when the run has no energy balance)
    /events/t         (n_events,) float64; /events/kind, /events/element (n_events,) strings;
    /events/impulse   (n_events,) float64: the generalised impulse of the element's event rule (impacts)

Rows are the recorded instants after decimation (``[simulation] record_every``; event instants are
always kept); two rows at one instant are the states just before and after an event."""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np

LAYOUT = "drivefem.history"
VERSION = 1


def _strings(values) -> np.ndarray:
    import h5py

    return np.array([str(v) for v in values], dtype=h5py.string_dtype("utf-8"))


def write_history(path, *, command: str, title: str, kind: str, t, outputs=None, states=None, energy=None,
                  events=(), record_every: int = 1, n_recorded: int | None = None) -> Path:
    """Write the container (atomically: a temporary file renamed).  ``outputs``: a
    :class:`fem.loads.analyses.NamedOutputs` sampled at ``t``; ``states``: (names, x, v) with one row per
    coordinate; ``energy``: (energy, work) or None; ``events``: the run's events."""
    import h5py

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    t = np.asarray(t, dtype=float)
    with h5py.File(tmp, "w") as f:
        f.attrs.update({"schema": LAYOUT, "version": VERSION, "command": command, "title": title, "kind": kind,
                        "record_every": int(record_every),
                        "n_samples_recorded": int(t.size if n_recorded is None else n_recorded)})
        f.create_dataset("t", data=t)
        if outputs is not None:
            g = f.create_group("outputs")
            g.create_dataset("values", data=np.ascontiguousarray(np.asarray(outputs.values, dtype=float).T))
            ch = outputs.channels
            g.create_dataset("names", data=_strings(c.name for c in ch))
            g.create_dataset("quantity", data=_strings(c.quantity for c in ch))
            g.create_dataset("unit", data=_strings(c.unit for c in ch))
            g.create_dataset("source", data=_strings(c.source for c in ch))
            g.create_dataset("where", data=_strings(c.where for c in ch))
        if states is not None:
            names, x, v = states
            g = f.create_group("states")
            g.create_dataset("names", data=_strings(names))
            g.create_dataset("x", data=np.ascontiguousarray(np.asarray(x, dtype=float).T))
            g.create_dataset("v", data=np.ascontiguousarray(np.asarray(v, dtype=float).T))
        if energy is not None:
            g = f.create_group("energy")
            g.create_dataset("energy", data=np.asarray(energy[0], dtype=float))
            g.create_dataset("work", data=np.asarray(energy[1], dtype=float))
        g = f.create_group("events")
        g.create_dataset("t", data=np.array([e.t for e in events], dtype=float))
        g.create_dataset("kind", data=_strings(e.kind for e in events))
        g.create_dataset("element", data=_strings(e.element for e in events))
        g.create_dataset("impulse", data=np.array([float(getattr(e, "impulse", 0.0)) for e in events], dtype=float))
    os.replace(tmp, path)
    return path


def read_history(path) -> dict:
    """The container as plain arrays ({"t", "outputs": {name: column}, "states": {...}, "events": {...},
    "attrs": {...}}): what a reader without drivefem does in a few lines of h5py."""
    import h5py

    out = {}
    with h5py.File(path, "r") as f:
        out["attrs"] = dict(f.attrs)
        out["t"] = f["t"][()]
        if "outputs" in f:
            names = [s.decode() if isinstance(s, bytes) else s for s in f["outputs/names"][()]]
            vals = f["outputs/values"][()]
            out["outputs"] = {n: vals[:, k] for k, n in enumerate(names)}
            out["units"] = dict(zip(names, [s.decode() if isinstance(s, bytes) else s for s in f["outputs/unit"][()]]))
        if "states" in f:
            out["states"] = {k: f[f"states/{k}"][()] for k in ("names", "x", "v")}
        if "energy" in f:
            out["energy"] = {k: f[f"energy/{k}"][()] for k in ("energy", "work")}
        out["events"] = {k: f[f"events/{k}"][()] for k in ("t", "kind", "element", "impulse")}
    return out
