"""Other sources of named columns for :class:`fem.loads.analyses.NamedOutputs`: the FE section loads of a
shaft (torque, axial force, bending moments, shear forces along x; ``section_loads(fe_model, q, ...)``
returns ``SectionLoads(x, quantities: {name: array}, units)``) become one column per quantity and station,
named ``<where>.<quantity>@x=<x>`` (e.g. ``shaft.torque@x=0.25``), so the JSON, CSV, --h5 and plots take
them like the element loads (docs/outputs.md)."""
from __future__ import annotations

import numpy as np

from discrete.loads import Channel

_FORCE_LIKE = ("torque", "axial_force", "bending_moment", "shear_force", "bending_moment_y", "bending_moment_z",
               "shear_force_y", "shear_force_z")


def section_columns(section, where: str = "shaft", m: int | None = None) -> tuple[list, np.ndarray]:
    """(channels, values (n_columns, m)) of a section-loads object: ``section.x`` (n_x stations),
    ``section.quantities`` {name: (n_x,) or (n_x, m) array}, ``section.units`` ({name: unit} or one unit).
    ``m``: the length of the analysis axis (instants, modes, frequencies); a (n_x,) array is one column of
    length 1 (m = 1)."""
    xs = np.asarray(section.x, dtype=float).ravel()
    units = section.units
    chans, rows = [], []
    for q, arr in section.quantities.items():
        a = np.asarray(arr)
        a = a.reshape(xs.size, -1)
        unit = units.get(q, "") if isinstance(units, dict) else str(units)
        word = "torque" if q == "torque" else ("moment" if "moment" in q else "force")
        for i, x in enumerate(xs):
            chans.append(Channel(f"{where}.{q}@x={x:g}", word if q in _FORCE_LIKE else q, unit, "section", where,
                                 info={"x": float(x), "section_quantity": q}))
            rows.append(a[i])
    values = np.array(rows) if rows else np.zeros((0, m or 1))
    if m is not None and values.shape[1] != m:
        raise ValueError(f"section loads with {values.shape[1]} values per station for an axis of {m}")
    return chans, values
