"""Figures of geared trains (matplotlib, off screen): Campbell diagram with the shafts' and the meshes'
excitation lines, mesh force and dynamic load factor over speed, time histories of the meshes, the Floquet
chart of the mesh-stiffness variation.  They take results, never recompute them."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..output.figures.save import save_figure  # noqa: E402

RPM = 30.0 / np.pi
WHIRL_STYLE = {"forward": ("tab:blue", "-"), "backward": ("tab:red", "--"), "mixed": ("tab:purple", "-."),
               "planar": ("0.4", "-"), "none": ("tab:green", "-"), "axial": ("tab:olive", "-")}


def _save(fig, path) -> Path:
    return save_figure(fig, path, dpi=130)


def _dominant(labels):
    return max(set(labels), key=labels.count)


def plot_train_campbell(camp, path, *, title: str = "", ratios: dict | None = None, lines: dict | None = None,
                        reference: str = "") -> Path:
    """Damped natural frequencies (Hz) of the tracked modes against the reference speed (rev/min), styled by
    whirl and kind (torsion/coupled modes green); the excitation lines: 1x of every shaft's own speed
    (|ratio_i| x) and the ``lines`` given ({label: slope in Hz per rad/s of the reference}, e.g. tooth-pass
    frequencies); the critical speeds of the orders as circles; below, the log decrement."""
    s = camp.speeds_rad_s * RPM
    fig, axes = plt.subplots(2, 1, figsize=(8, 7.2), sharex=True, gridspec_kw={"height_ratios": [3, 1.2]})
    ax = axes[0]
    f = camp.omega_damped_rad_s / (2 * np.pi)
    seen = set()
    for j in range(camp.n_modes):
        if camp.kind[j] == "rigid":
            continue
        w = _dominant([row[j] for row in camp.whirl])
        key = {"torsion": "none", "axial": "axial"}.get(camp.kind[j], w)
        colour, ls = WHIRL_STYLE.get(key, ("k", "-"))
        lab = f"{camp.kind[j]} mode" if key in ("none", "axial") else f"{w} whirl"
        ax.plot(s, f[:, j], color=colour, ls=ls, lw=1.5, label=None if lab in seen else lab)
        seen.add(lab)
    top = float(np.nanmax(f)) * 1.08 if f.size else 1.0
    exc = {}
    for name, r in (ratios or {}).items():
        key = f"1x {name}"
        if any(abs(v - abs(r) / (2 * np.pi)) < 1e-12 for v in exc.values()):
            continue                                   # shafts at the same speed: one line
        exc[key] = abs(r) / (2 * np.pi)
    exc.update(lines or {})
    for k, (lab, slope) in enumerate(sorted(exc.items(), key=lambda kv: kv[1])):
        y = slope * camp.speeds_rad_s
        ax.plot(s, y, color="0.35", lw=0.9, ls=":" if "tooth" in lab else "-")
        xe = min(s[-1], top / max(slope, 1e-300) * RPM / 1.0)
        ax.text(xe, slope * xe / RPM, f" {lab}", fontsize=7, va="bottom", ha="right", color="0.3")
    crit = camp.critical_speeds
    if crit:
        ax.plot([c.speed_rpm for c in crit], [c.frequency_rad_s / (2 * np.pi) for c in crit], "o", mfc="none",
                mec="k", ms=7, label="critical speeds")
    back = getattr(camp, "backward_crossings", [])
    if back:
        ax.plot([c.speed_rpm for c in back], [c.frequency_rad_s / (2 * np.pi) for c in back], "s", mfc="none",
                mec="r", ms=6, label="backward-whirl crossings")
    ax.set_ylim(0, top)
    ax.set_ylabel("damped natural frequency [Hz]")
    ax.set_title(title or "Campbell diagram", fontsize=10)
    ax.legend(fontsize=7, loc="upper right", framealpha=0.9)
    ax.grid(alpha=0.3)
    a2 = axes[1]
    ld = np.where(np.isfinite(camp.log_decrement), camp.log_decrement, np.nan)
    for j in range(camp.n_modes):
        if camp.kind[j] == "rigid":
            continue
        w = _dominant([row[j] for row in camp.whirl])
        colour, ls = WHIRL_STYLE.get({"torsion": "none", "axial": "axial"}.get(camp.kind[j], w), ("k", "-"))
        a2.plot(s, ld[:, j], color=colour, ls=ls, lw=1.0)
    a2.axhline(0.0, color="k", lw=0.8)
    a2.set_ylabel("log decrement [-]")
    a2.set_xlabel(f"speed of {reference or 'the reference'} [rev/min]")
    a2.grid(alpha=0.3)
    return _save(fig, path)


def plot_train_forced(res, path, *, title: str = "") -> Path:
    """Dynamic load factor of every mesh and the peak radial force of every bearing against the reference
    speed (rev/min)."""
    s = res.speeds_rad_s * RPM
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for c in res.connections:
        if c.coordinate == "line of action" and np.any(np.isfinite(c.dynamic_factor)):
            a1.plot(s, c.dynamic_factor, lw=1.5, label=f"{c.connection} (static {abs(c.static):.4g} N)")
    a1.axhline(1.0, color="k", lw=0.8)
    a1.set_ylabel("dynamic load factor [-]")
    a1.set_title(title or "mesh loads", fontsize=10)
    a1.legend(fontsize=7)
    a1.grid(alpha=0.3)
    for k, v in res.bearings.items():
        a2.plot(s, v["peak_radial"], lw=1.2, label=k)
    a2.set_ylabel("peak radial bearing force [N]")
    a2.set_xlabel("speed of the reference [rev/min]")
    a2.legend(fontsize=7)
    a2.grid(alpha=0.3)
    return _save(fig, path)


def plot_train_simulation(sim, out_dir, *, title: str = "") -> list[Path]:
    """``mesh_forces.png``: the force of every connection against time (events marked); ``bearings.png``: the
    radial force of every bearing; ``phase.png``: each mesh's deflection against its rate."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    r = sim.result
    t = np.asarray(r.t)
    paths = []
    cf = sim.connection_forces()
    fig, ax = plt.subplots(figsize=(8, 4.2))
    for k, v in cf.items():
        ax.plot(t, v, lw=1.0, label=k)
    for e in r.events:
        if e.kind in ("contact_open", "contact_close", "stick", "slip"):
            ax.axvline(e.t, color="0.8", lw=0.4, zorder=0)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("connection force [N or N m]")
    ax.set_title((title + "\n" if title else "") + "connection forces (grey: contact and slip events)", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    paths.append(_save(fig, out / "mesh_forces.png"))
    bf = sim.bearing_forces()
    if bf:
        fig, ax = plt.subplots(figsize=(8, 4.2))
        for k, v in bf.items():
            ax.plot(t, np.hypot(v[0], v[1]), lw=1.0, label=k)
        ax.set_xlabel("time t [s]")
        ax.set_ylabel("radial bearing force [N]")
        ax.set_title(title or "bearing forces", fontsize=9)
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
        paths.append(_save(fig, out / "bearings.png"))
    c = sim.compiled
    q, v, _ = sim.field
    meshes = [m for m in c.ts.train.connections if m.table == "mesh"]
    if meshes:
        fig, ax = plt.subplots(figsize=(6, 5))
        for m in meshes:
            cd = m.coordinates(c.ts)[0]
            ax.plot(cd.of(q) * 1e6, cd.of(v), lw=0.7, label=m.name)
            if m.backlash:
                for b in (-0.5 * m.backlash, 0.5 * m.backlash):
                    ax.axvline(b * 1e6, color="0.5", ls="--", lw=0.8)
        ax.set_xlabel("mesh deflection along the line of action [um] (dashed: backlash)")
        ax.set_ylabel("deflection rate [m/s]")
        ax.set_title(title or "phase portrait", fontsize=9)
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
        paths.append(_save(fig, out / "phase.png"))
    return paths


def plot_train_parametric(res, path, *, title: str = "") -> Path:
    """max |Floquet multiplier| over the reference speed (rev/min) and the variation depth: unstable points
    shaded by the growth rate, the edges located by root finding at the depths asked for."""
    chart = res.chart
    x = res.speeds_rad_s * RPM
    y = chart.depth
    fig, ax = plt.subplots(figsize=(8, 5))
    unstable = ~chart.stable
    if y.size > 1 and np.any(unstable):
        rate = np.ma.masked_where(~unstable, chart.growth_rate)
        mesh = ax.pcolormesh(x, y, rate, shading="nearest", cmap="Reds", vmin=0.0)
        fig.colorbar(mesh, ax=ax, label="growth rate ln|rho|max / T [1/s]")
        ax.contour(x, y, chart.rho_max, levels=[1.0 + chart.stability_margin], colors="k", linewidths=0.8)
    first = True
    for b in chart.boundaries:
        for lo, hi, cen in zip(b.omega_low_rad_s, b.omega_high_rad_s, b.centre):
            ax.plot([lo / res.pass_per_speed * RPM, hi / res.pass_per_speed * RPM], [b.depth, b.depth], "-|",
                    color="tab:blue", lw=1.5, ms=8, label="edges (root finding)" if first else None)
            ax.annotate(f"{cen}", (0.5 * (lo + hi) / res.pass_per_speed * RPM, b.depth), fontsize=7,
                        xytext=(0, 5), textcoords="offset points", ha="center")
            first = False
    ax.set_xlabel(f"speed of the reference [rev/min] (tooth-pass frequency = {res.pass_per_speed:g} x speed)")
    ax.set_ylabel("depth of the mesh-stiffness variation [-] (1 = declared)")
    ax.set_title((title + "\n" if title else "") + f"Floquet stability, mesh {res.mesh!r}", fontsize=9)
    if not first:
        ax.legend(fontsize=7, loc="upper right")
    ax.grid(alpha=0.3)
    return _save(fig, path)
