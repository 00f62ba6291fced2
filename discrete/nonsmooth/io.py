"""CSV export of a simulation's time history (one row per recorded instant; events give two rows,
before and after the switch, at the same time)."""
from __future__ import annotations

import csv
import pathlib


def write_csv(result, path) -> pathlib.Path:
    """Write columns t, <dof>.x, <dof>.v for every DOF (drivers included), energy, work."""
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    has_e = result.energy.size == result.t.size
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        head = ["t"] + [f"{n}.{c}" for n in result.names for c in ("x", "v")]
        if has_e:
            head += ["energy", "work"]
        w.writerow(head)
        for k in range(result.t.size):
            row = [repr(float(result.t[k]))]
            for i in range(len(result.names)):
                row += [repr(float(result.x[i, k])), repr(float(result.v[i, k]))]
            if has_e:
                row += [repr(float(result.energy[k])), repr(float(result.work[k]))]
            w.writerow(row)
    return path
