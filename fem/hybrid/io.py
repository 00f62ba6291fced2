"""CSV export and plots of a :class:`HybridResult` (they take a result, never recompute it)."""
from __future__ import annotations

import csv
import pathlib

import numpy as np


def write_csv(result, path) -> pathlib.Path:
    """Columns ``t`` and one per FE DOF (``<field>@x=<x>``) of the sampled field history,
    then the lumped bodies' displacement and velocity (if any)."""
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    sys_ = result.fe.system
    comp = result.compiled
    bodies = [i for i in range(comp.n_fe, comp.system.n_dofs)]
    solver = result.solver
    # body histories at the sampled times (the sample indices are the nearest recorded instants)
    idx = np.searchsorted(solver.t, result.t).clip(0, solver.t.size - 1)
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        head = ["t"] + sys_.labels() + [f"{comp.system.dof_name[i]}.{c}" for i in bodies for c in ("x", "v")]
        w.writerow(head)
        for k in range(result.t.size):
            row = [repr(float(result.t[k]))] + [repr(float(v)) for v in result.field_history[k]]
            for i in bodies:
                row += [repr(float(solver.x[i, idx[k]])), repr(float(solver.v[i, idx[k]]))]
            w.writerow(row)
    return path


def plot_result(result, out_dir) -> list[pathlib.Path]:
    """``field.png`` (space-time map of the primary field), ``coupling.png`` (history of the DOFs
    where elements act, events marked), ``energy.png`` (E - E0 against the integrated work)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    fe = result.fe
    prim = fe.model.fields[0]
    xs, _ = fe.nodal_values(result.field_history[0], prim)
    Z = np.array([fe.nodal_values(q, prim)[1] for q in result.field_history])
    fig, ax = plt.subplots(figsize=(8, 4.5))
    im = ax.pcolormesh(xs, result.t, Z, shading="nearest", cmap="RdBu_r")
    fig.colorbar(im, ax=ax, label=prim)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("t (s)")
    ax.set_title(f"{result.compiled.system.title or 'hybrid model'}: {prim}(x, t)")
    p = out / "field.png"
    fig.savefig(p, dpi=110, bbox_inches="tight")
    plt.close(fig)
    paths.append(p)
    fig, ax = plt.subplots(figsize=(8, 4))
    sys_ = fe.system
    shown = 0
    for j in [int(j) for j in result.compiled.coupling][:6]:
        ax.plot(result.t, result.field_history[:, j], lw=1, label=sys_.label(j))
        shown += 1
    if not shown:
        tip = int(np.argmax(np.where(sys_.dof_field == prim, sys_.dof_x, -np.inf)))
        ax.plot(result.t, result.field_history[:, tip], lw=1, label=sys_.label(tip))
    ev = np.array([e.t for e in result.events])
    if ev.size and ev.size < 2000:
        ax.plot(ev, 0 * ev, "k|", ms=8, label="events")
    ax.set_xlabel("t (s)")
    ax.legend(fontsize=7)
    p = out / "coupling.png"
    fig.savefig(p, dpi=110, bbox_inches="tight")
    plt.close(fig)
    paths.append(p)
    s = result.solver
    fig, ax = plt.subplots(figsize=(8, 3.5))
    ax.plot(s.t, s.energy - s.energy[0], lw=1, label="E - E0")
    ax.plot(s.t, s.work, "--", lw=1, label="work of non-conservative forces")
    ax.set_xlabel("t (s)")
    ax.set_title(f"energy balance: error {result.energy_error:.2e}")
    ax.legend(fontsize=8)
    p = out / "energy.png"
    fig.savefig(p, dpi=110, bbox_inches="tight")
    plt.close(fig)
    paths.append(p)
    return paths
