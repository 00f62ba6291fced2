"""The named outputs of a train's time simulation (docs/outputs.md, docs/geared.md): one
:class:`fem.loads.analyses.NamedOutputs` over time with

* every connection's force by its own law (:meth:`fem.train.simulate.TrainSimulation.connection_forces`):
  ``<mesh>.force`` along its line of action (N, compression of the drive flank positive), a coupling's
  ``<coupling>.torque`` (N m), ``.force_y|z|x`` (N), ``.moment_y|z`` (N m) per direction;
* every bearing's reaction on the shaft, ``<bearing>.force_y``, ``.force_z`` (``.force_x`` where the
  bearing is axial), N.

Their derived quantities (peak, rms, mean, dynamic load factor = peak / |mean|) are those of every time
history (:func:`fem.loads.analyses.derived`).  The other analyses of a train report their mesh forces,
load factors and bearing forces in their own keys (docs/geared.md) and have no named outputs here (None)."""
from __future__ import annotations

import numpy as np

from discrete.loads import Channel


def outputs(study, result):
    """Named outputs of ``result`` (an analysis of the train ``study``): a time simulation's, else None."""
    from .simulate import TrainSimulation

    if isinstance(result, TrainSimulation):
        return simulation_outputs(result)
    return None


SUFFIX = {"torsion": ("torque", "N*m"), "lateral y": ("force_y", "N"), "lateral z": ("force_z", "N"),
          "angular y": ("moment_y", "N*m"), "angular z": ("moment_z", "N*m"), "axial": ("force_x", "N")}
"""A coupling direction's output: name suffix and unit (docs/outputs.md's names)."""


def _connection_channel(key: str, connections: dict) -> Channel:
    name, _, label = key.partition(":")
    if hasattr(connections[name], "mesh_force"):
        return Channel(f"{name}.force", "force", "N", "mesh", name,
                       info={"along": "line of action, drive flank compression +"})
    suffix, unit = SUFFIX[label]
    return Channel(f"{name}.{suffix}", suffix.split("_")[0], unit, "coupling", name, info={"direction": label})


def simulation_outputs(sim):
    """:class:`NamedOutputs` over the simulation's samples: connection forces, then bearing reactions."""
    from ..loads.analyses import NamedOutputs, derived

    t = np.asarray(sim.result.t, dtype=float)
    connections = {c.name: c for c in sim.compiled.ts.train.connections}
    channels, rows = [], []
    for key, F in sim.connection_forces().items():
        channels.append(_connection_channel(key, connections))
        rows.append(np.asarray(F, dtype=float))
    for label, F in sim.bearing_forces().items():
        F = np.asarray(F, dtype=float)
        for k, axis in enumerate(("y", "z", "x")):
            if axis == "x" and not np.any(F[2]):
                continue                                   # a bearing without axial stiffness
            channels.append(Channel(f"{label}.force_{axis}", "reaction", "N", "bearing", label,
                                    info={"component": axis, "on": "shaft"}))
            rows.append(F[k])
    values = np.vstack(rows) if rows else np.zeros((0, t.size))
    out = NamedOutputs("t", t, channels, values)
    out.summaries = derived("t", t, channels, values)
    out.notes = ["train: connection forces by each connection's own law, bearing reactions on the shaft "
                 "(docs/geared.md); section loads per shaft: TrainSimulation.section_loads"]
    return out
