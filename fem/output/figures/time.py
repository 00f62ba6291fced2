"""Time plots and phase portraits of simulations (PNG, matplotlib Agg): lumped (:func:`plot_time_history`)
and hybrid (:func:`plot_hybrid`); they take a result, never recompute it."""
from __future__ import annotations

import pathlib

import numpy as np

from .loads import MARKS, plot_loads


def plot_time_history(result, out_dir, max_dofs: int = 6, outputs=None, title: str = "") -> list[pathlib.Path]:
    """Write ``time.png`` (the named outputs: element deflections and loads, reactions, events marked;
    without outputs: x and v of all DOFs), ``phase_<dof>.png`` per body (not drivers) and ``energy.png``
    (E - E0 and the integrated work).  Returns the written paths."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    names = result.names[:max_dofs]
    head = (title + ": " if title else "") + f"{result.method}" + (f", period {result.period:.6g} s" if result.period else "")
    if outputs is not None and outputs.channels:
        paths.append(plot_loads(outputs, out / "time.png", head, result.events))
    else:
        fig, ax = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
        for i, n in enumerate(names):
            ax[0].plot(result.t, result.x[i], lw=1, label=n)
            ax[1].plot(result.t, result.v[i], lw=1, label=n)
        for kind, mk in MARKS.items():
            tt = result.event_times(kind)
            if tt.size and tt.size < 2000:
                ax[1].plot(tt, 0 * tt, mk, ms=4, ls="none", label=kind)
        ax[0].set_ylabel("displacement x [m | rad]")
        ax[1].set_ylabel("velocity v [m/s | rad/s]")
        ax[1].set_xlabel("time t [s]")
        ax[0].legend(fontsize=7, loc="best")
        ax[1].legend(fontsize=7, loc="best", ncol=3)
        ax[0].set_title(head, fontsize=9)
        fig.tight_layout()
        p = out / "time.png"
        fig.savefig(p, dpi=110)
        plt.close(fig)
        paths.append(p)
    for i, n in enumerate(names):
        if n in result.driven:
            continue                   # prescribed motion: no phase portrait
        fig, a = plt.subplots(figsize=(4.5, 4))
        x, lab = result.x[i], f"{n}: x"
        if result.t.size > 2 and np.ptp(result.t) > 0:
            slope, icpt = np.polyfit(result.t, x, 1)
            T = result.period
            if T and result.t[-1] - result.t[0] > T:       # exact mean velocity over the last period
                t1 = result.t[-1]
                slope = (x[-1] - np.interp(t1 - T, result.t, x)) / T
                icpt = float(np.mean(x - slope * result.t))
            drift = abs(slope) * np.ptp(result.t)
            if drift > 2 * np.ptp(x - slope * result.t):       # a drifting (driven) body: show the cycle
                x, lab = x - (slope * result.t + icpt), f"{n}: x - ({slope:.4g} t + {icpt:.3g})"
        a.plot(x, result.v[i], lw=0.8)
        a.set_xlabel(lab + " [m | rad]")
        a.set_ylabel(f"{n}: v [m/s | rad/s]")
        a.set_title(f"phase portrait of {n}", fontsize=9)
        fig.tight_layout()
        p = out / f"phase_{n}.png"
        fig.savefig(p, dpi=110)
        plt.close(fig)
        paths.append(p)
    if result.energy.size == result.t.size and result.t.size:
        fig, a = plt.subplots(figsize=(7, 3.5))
        a.plot(result.t, result.energy - result.energy[0], lw=1, label="E(t) - E(0)")
        a.plot(result.t, result.work, lw=1, ls="--", label="work of non-conservative forces")
        a.set_xlabel("time t [s]")
        a.set_ylabel("energy [J]")
        a.legend(fontsize=8)
        a.set_title(f"energy balance, relative error {result.energy_error:.2e}", fontsize=9)
        fig.tight_layout()
        p = out / "energy.png"
        fig.savefig(p, dpi=110)
        plt.close(fig)
        paths.append(p)
    return paths


def plot_hybrid(result, out_dir, outputs=None, title: str = "") -> list[pathlib.Path]:
    """``field.png`` (space-time map of the primary field), ``coupling.png`` (history of the DOFs
    where elements act, events marked), ``loads.png`` (the named outputs: element loads, reactions),
    ``energy.png`` (E - E0 against the integrated work)."""
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
    if outputs is not None and outputs.channels:
        paths.append(plot_loads(outputs, out / "loads.png", title or "hybrid model", result.events))
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
