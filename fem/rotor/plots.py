"""Matplotlib figures of rotor results (never recomputes anything): Campbell diagram with the
excitation lines and critical speeds, Bode and polar plots, orbits, the critical speed map."""
from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .whirl import Orbits  # noqa: E402

RPM = 30.0 / np.pi
WHIRL_STYLE = {"forward": ("tab:blue", "-"), "backward": ("tab:red", "--"), "mixed": ("tab:purple", "-."),
               "planar": ("0.4", ":"), "none": ("tab:green", "-")}


def _save(fig, path) -> Path:
    path = Path(path)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _dominant(labels) -> str:
    vals = [v for v in labels if v not in ("planar",)] or list(labels)
    return max(set(vals), key=vals.count)


def _wrap(text: str, width: int = 90) -> str:
    import textwrap

    return "\n".join(textwrap.wrap(text, width, break_on_hyphens=False)) if text else text


def _layout(fig, path) -> Path:
    """Save a figure whose layout is already final (labels placed against it): no re-layout."""
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


#: the log-decrement panel of a Campbell diagram is cut here (heavily damped modes would flatten it)
LOG_DEC_SHOWN = 4.0
#: one colour per tracked mode: tab10 without its grey (the excitation lines are grey) ...
MODE_COLOURS = tuple(c for i, c in enumerate(plt.get_cmap("tab10").colors) if i != 7) + \
    tuple(c for i, c in enumerate(plt.get_cmap("tab20b").colors) if i % 4 == 1)    # ... then darker shades
WHIRL_LINE = {"forward": "-", "backward": "--", "mixed": "-.", "planar": ":", "none": "-"}
WHIRL_TAG = {"forward": "F", "backward": "B", "mixed": "M", "planar": "P", "none": ""}


def mode_tags(camp) -> list[str]:
    """Short names of the tracked modes: number and dominant whirl (1B, 2F, 3M; axial/torsion: 5 torsion)."""
    out = []
    for j in range(camp.n_modes):
        w = _dominant([row[j] for row in camp.whirl])
        kind = camp.kind[j]
        out.append(f"{j + 1}{WHIRL_TAG.get(w, '')}" if kind == "lateral" else f"{j + 1} {kind}")
    return out


def plot_campbell(camp, path, *, title: str = "", log_decrement: bool = True, operating_range=None) -> Path:
    """Damped natural frequencies (Hz) of the tracked modes against speed (rev/min): one colour per
    mode, the line style its whirl (forward solid, backward dashed, mixed dash-dot); the excitation
    lines k x speed; the critical speeds (forward crossings) as filled circles and the backward-whirl
    crossings as open squares, listed apart in the legend; the ``operating_range`` (rad/s) shaded;
    below, the log decrement of each mode, labelled at its end.  Labels never overlap
    (:func:`fem.output.figures.labels.place_labels`)."""
    from ..output.figures.labels import RIGHT_OF, place_labels

    s = camp.speeds_rad_s * RPM
    fig, axes = plt.subplots(2 if log_decrement else 1, 1, figsize=(9.5, 7.6 if log_decrement else 5.2), sharex=True,
                             gridspec_kw={"height_ratios": [3, 1.4]} if log_decrement else None)
    ax = axes[0] if log_decrement else axes
    f = np.where(camp.omega_damped_rad_s > 0, camp.omega_damped_rad_s, np.nan) / (2 * np.pi)   # where it oscillates
    tags = mode_tags(camp)
    colours = [MODE_COLOURS[j % len(MODE_COLOURS)] for j in range(camp.n_modes)]
    for j in range(camp.n_modes):
        w = _dominant([row[j] for row in camp.whirl])
        name = f"mode {tags[j]}: {w} whirl" if camp.kind[j] == "lateral" else f"mode {tags[j]}"
        ax.plot(s, f[:, j], color=colours[j], ls=WHIRL_LINE.get(w, "-"), lw=1.6, label=name)
    top = float(np.nanmax(f)) * 1.08 if np.any(np.isfinite(f)) else 1.0
    for k in camp.orders:
        ax.plot(s, k * camp.speeds_rad_s / (2 * np.pi), color="0.3", lw=0.9, ls="-", zorder=1)
        xe = min(s[-1], top * 2 * np.pi / k * RPM)
        ax.text(xe, min(k * xe / RPM / (2 * np.pi), top), f"{k:g}x ", fontsize=8, va="top", ha="right", color="0.3")
    if operating_range is not None:
        lo, hi = (v * RPM for v in operating_range)
        for a in (axes if log_decrement else [ax]):
            a.axvspan(lo, hi, color="tab:green", alpha=0.13, lw=0, zorder=0,
                      label=f"operating range {lo:.0f}-{hi:.0f} rev/min" if a is ax else None)
    crit, back = camp.critical_speeds, camp.backward_crossings
    if crit:
        ax.plot([c.speed_rpm for c in crit], [c.frequency_rad_s / (2 * np.pi) for c in crit], "o", color="k", mec="w",
                ms=7, zorder=5, label="critical speed (forward whirl crossing)")
    if back:
        iso = getattr(camp, "isotropic_supports", None)
        note = ("not excited by unbalance: isotropic supports" if iso else
                "anisotropic supports: may respond weakly" if iso is False else "backward whirl")
        ax.plot([c.speed_rpm for c in back], [c.frequency_rad_s / (2 * np.pi) for c in back], "s", mfc="none",
                mec="tab:red", mew=1.3, ms=7, zorder=5, label=f"backward crossing ({note})")
    ax.set_ylim(0, top)
    ax.set_xlim(s[0], s[-1])
    ax.set_ylabel("damped natural frequency [Hz]")
    ax.set_title(_wrap(f"Campbell diagram: {title}" if title else "Campbell diagram"), fontsize=10)
    ax.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, frameon=False)
    ax.grid(alpha=0.3)
    a2 = None
    if log_decrement:
        a2 = axes[1]
        ld = np.where(np.isfinite(camp.log_decrement), camp.log_decrement, np.nan)
        for j in range(camp.n_modes):
            w = _dominant([row[j] for row in camp.whirl])
            a2.plot(s, ld[:, j], color=colours[j], ls=WHIRL_LINE.get(w, "-"), lw=1.2)
        a2.axhline(0.0, color="k", lw=0.8)
        hi = float(np.nanmax(ld)) if np.any(np.isfinite(ld)) else 1.0
        if hi > LOG_DEC_SHOWN:           # modes just past overdamped: log dec -> inf; the stability margin is near 0
            lo = float(np.nanmin(ld))
            a2.set_ylim(min(lo, 0.0) - 0.05 * LOG_DEC_SHOWN, LOG_DEC_SHOWN)
            a2.set_ylabel(f"log decrement [-]\n(shown up to {LOG_DEC_SHOWN:g})")
        else:
            a2.set_ylabel("log decrement [-]")
        a2.grid(alpha=0.3)
        a2.set_xlabel("speed [rev/min]")
        a2.set_xlim(s[0], s[-1])
    else:
        ax.set_xlabel("speed [rev/min]")
    fig.tight_layout()
    fig.canvas.draw()
    def _crit_text(c):
        return f"{c.speed_rpm:.0f}" + ("" if c.order == 1 else f" ({c.order:g}x)")
    place_labels(ax, [(c.speed_rpm, c.frequency_rad_s / (2 * np.pi)) for c in crit], [_crit_text(c) for c in crit],
                 fontsize=7.5)
    ax_boxes = None
    if back:
        from ..output.figures.labels import existing_boxes

        ax_boxes = existing_boxes(ax, fig.canvas.get_renderer())
        place_labels(ax, [(c.speed_rpm, c.frequency_rad_s / (2 * np.pi)) for c in back], [_crit_text(c) for c in back],
                     avoid=ax_boxes, fontsize=7.5, color="tab:red", style="italic")
    if a2 is not None:
        ends = []
        for j in range(camp.n_modes):
            ok = np.flatnonzero(np.isfinite(ld[:, j]))
            if ok.size:
                ends.append((j, s[ok[-1]], min(ld[ok[-1], j], a2.get_ylim()[1])))
        ends.sort(key=lambda e: -e[2])
        place_labels(a2, [(x, y) for _, x, y in ends], [tags[j] for j, _, _ in ends], offsets=RIGHT_OF, inside=False,
                     colors=[colours[j] for j, _, _ in ends], fontsize=7.5)
    return _layout(fig, path)


def probe_label(p) -> str:
    """A probe's name: its label from the model file when it has one, else position and direction."""
    name = getattr(p, "label", None) or getattr(p, "name", None)
    if getattr(p, "name", None) and not getattr(p, "label", None):
        return f"{p.name} (x = {p.x:g} m, {p.direction})"
    return name or f"x = {p.x:g} m ({p.direction})"


def unwrapped_lag(phase_lag_deg) -> np.ndarray:
    """Phase lag unwrapped along the speeds (degrees): no jump of 360 deg drawn as a vertical line."""
    return np.rad2deg(np.unwrap(np.deg2rad(np.asarray(phase_lag_deg, dtype=float))))


def plot_bode(resp, path, *, probes=None, title: str = "", log: bool = True) -> Path:
    """Amplitude (um, log) and phase lag (deg, unwrapped) of the probes against speed (rev/min),
    peaks marked with their half-power band and amplification factor (labels placed without
    overlaps), the operating range shaded."""
    from ..output.figures.labels import place_labels

    s = resp.speeds_rad_s * RPM
    idx = list(range(len(resp.probes))) if probes is None else list(probes)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8.5, 6.8), sharex=True)
    colours = {}
    for j in idx:
        p = resp.probes[j]
        line, = (a1.semilogy if log else a1.plot)(s, np.maximum(p.amplitude, 1e-300) * 1e6, label=probe_label(p))
        colours[j] = line.get_color()
        a2.plot(s, unwrapped_lag(p.phase_lag_deg), color=colours[j])
    anchors, texts = [], []
    for pk in resp.peaks:
        if pk.probe in idx:
            a1.plot(pk.speed_rad_s * RPM, pk.amplitude * 1e6, "v", color=colours[pk.probe], mec="k", ms=6)
            if pk.half_power_rad_s is not None:
                lo, hi = pk.half_power_rad_s
                a1.plot([lo * RPM, hi * RPM], [pk.amplitude / np.sqrt(2) * 1e6] * 2, "-", color=colours[pk.probe], lw=0.8)
            af = "" if pk.amplification_factor is None else f", AF {pk.amplification_factor:.1f}"
            anchors.append((pk.speed_rad_s * RPM, pk.amplitude * 1e6))
            texts.append(f"{pk.speed_rad_s * RPM:.0f} rev/min{af}")
    if resp.operating_range is not None:
        lo, hi = (v * RPM for v in resp.operating_range)
        for a in (a1, a2):
            a.axvspan(lo, hi, color="tab:green", alpha=0.13, lw=0,
                      label=f"operating range {lo:.0f}-{hi:.0f} rev/min" if a is a1 else None)
    a1.set_ylabel("amplitude [um]")
    a1.set_title(_wrap(f"Unbalance response: {title}" if title else "Unbalance response"), fontsize=10)
    a1.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, frameon=False)
    a1.grid(alpha=0.3, which="both")
    a2.set_ylabel("phase lag [deg]")
    lag = np.concatenate([unwrapped_lag(resp.probes[j].phase_lag_deg) for j in idx]) if idx else np.zeros(1)
    lo_t, hi_t = 90 * np.floor(np.nanmin(lag) / 90), 90 * np.ceil(np.nanmax(lag) / 90)
    a2.set_yticks(np.arange(lo_t, hi_t + 1, 90 if hi_t - lo_t <= 720 else 180))
    a2.set_xlabel("speed [rev/min]")
    a2.set_xlim(s[0], s[-1])
    a2.grid(alpha=0.3)
    fig.tight_layout()
    fig.canvas.draw()
    place_labels(a1, anchors, texts, fontsize=7)
    return _layout(fig, path)


def plot_polar(resp, path, probe: int = 0, *, title: str = "", labels: int = 8) -> Path:
    """Polar (Nyquist) plot of one probe's complex response over the speed range (um): the speeds of
    ``labels`` points equally spaced along the curve written beside them without overlaps (none
    where the curve crowds at the origin), the operating range drawn thick, the peaks marked."""
    from ..output.figures.labels import place_labels

    p = resp.probes[probe]
    z = p.value * 1e6
    sp = resp.speeds_rad_s * RPM
    fig, ax = plt.subplots(figsize=(6.4, 6.0))
    ax.plot(z.real, z.imag, "-", color="tab:blue", lw=1.2, label="response (speed rising along the curve)")
    if resp.operating_range is not None:
        lo, hi = (v * RPM for v in resp.operating_range)
        inside = (sp >= lo) & (sp <= hi)
        if inside.any():
            ax.plot(z.real[inside], z.imag[inside], "-", color="tab:green", lw=4, alpha=0.6,
                    label=f"operating range {lo:.0f}-{hi:.0f} rev/min")
    ax.plot(z.real[0], z.imag[0], "o", color="k", ms=4, label=f"{sp[0]:.0f} rev/min (first speed)")
    size = float(np.abs(z).max()) or 1.0
    arc = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(z)))])       # labels spaced along the curve
    targets = np.linspace(0.0, arc[-1], labels + 2)[1:-1]
    picks = sorted({int(np.argmin(np.abs(arc - a))) for a in targets})
    picks = [k for k in picks if abs(z[k]) > 0.04 * size]              # none in the crowd at the origin
    for k in picks:
        ax.plot(z.real[k], z.imag[k], "o", color="tab:blue", ms=3)
    peaks = [pk for pk in resp.peaks if pk.probe == probe]
    for pk in peaks:
        k = int(np.argmin(np.abs(resp.speeds_rad_s - pk.speed_rad_s)))
        ax.plot(z.real[k], z.imag[k], "v", color="k", ms=6)
    ax.axhline(0, color="0.6", lw=0.8)
    ax.axvline(0, color="0.6", lw=0.8)
    ax.set_aspect("equal", "datalim")
    ax.set_xlabel("real part [um]")
    ax.set_ylabel("imaginary part [um]")
    head = f"Polar plot: {title}" if title else "Polar plot"
    ax.set_title(_wrap(head, 70) + f"\n{probe_label(p)}; labels: speed [rev/min]", fontsize=9)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(0.0, -0.12), frameon=False)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.canvas.draw()
    anchors = [(z.real[k], z.imag[k]) for k in picks]
    texts = [f"{sp[k]:.0f}" for k in picks]
    for pk in peaks:
        k = int(np.argmin(np.abs(resp.speeds_rad_s - pk.speed_rad_s)))
        anchors.append((z.real[k], z.imag[k]))
        texts.append(f"peak {pk.speed_rad_s * RPM:.0f}")
    place_labels(ax, anchors, texts, fontsize=7)
    return _layout(fig, path)


def _ellipse(V, W, n: int = 121):
    t = np.linspace(0, 2 * np.pi, n)
    e = np.exp(1j * t)
    return (V * e).real, (W * e).real


def plot_orbits(V, W, node_x, path, *, nodes=None, title: str = "", unit: str = "m") -> Path:
    """Orbits (ellipses in the y-z plane, looking along -x) of complex amplitudes V, W at the
    shaft nodes (arrays over the nodes), with a dot at t = 0 and the whirl direction."""
    V, W, node_x = np.asarray(V), np.asarray(W), np.asarray(node_x)
    nodes = list(range(V.size)) if nodes is None else list(nodes)
    o = Orbits.of(V, W)
    fig, ax = plt.subplots(figsize=(7.2, 6.2))
    colour = _node_colours(fig, ax, node_x[nodes])
    for i in nodes:
        y, z = _ellipse(V[i], W[i])
        c = colour(node_x[i])
        ax.plot(y, z, color=c, lw=1.2, ls="-" if o.forward[i] > o.backward[i] else "--")
        ax.plot(y[0], z[0], "o", color=c, ms=3)
    ax.plot([], [], "k-", label="forward whirl")
    ax.plot([], [], "k--", label="backward whirl")
    ax.plot(0, 0, "k+")
    ax.set_aspect("equal", "datalim")
    ax.set_xlabel(f"y [{unit}]")
    ax.set_ylabel(f"z [{unit}]")
    ax.set_title(_wrap((title + "\n" if title else "") + "orbits (spin about +x: forward = counter-clockwise)", 70),
                 fontsize=9)
    ax.legend(fontsize=7.5, loc="upper right")
    return _save(fig, path)


def _node_colours(fig, ax, node_x):
    """One colour per shaft node from its position, with the colour bar that says so."""
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize

    xs = np.asarray(node_x, float)
    norm = Normalize(float(xs.min()), float(xs.max()) if xs.max() > xs.min() else float(xs.min()) + 1.0)
    sm = ScalarMappable(norm=norm, cmap="viridis")
    fig.colorbar(sm, ax=ax, shrink=0.8, pad=0.02, label="position of the node along the shaft x [m]")
    return lambda x: sm.to_rgba(x)


def plot_mode_orbits(modes, r: int, path, *, nodes=None, title: str = "") -> Path:
    """Orbits of mode ``r`` (0-based) of a :class:`fem.rotor.modal.RotorModes` (from its
    orbit axes: semi-axes, major-axis angle and direction of every shaft node), normalised to the
    largest semi-axis, coloured by the node's position (colour bar), a dot at t = 0."""
    major, minor, ang = modes.orbit_major[r], modes.orbit_minor[r], modes.orbit_angle[r]
    fig, ax = plt.subplots(figsize=(7.2, 6.2))
    nodes = list(range(modes.node_x.size)) if nodes is None else list(nodes)
    colour = _node_colours(fig, ax, modes.node_x[nodes])
    scale = float(np.max(major[nodes])) or 1.0
    t = np.linspace(0, 2 * np.pi, 121)
    for i in nodes:
        a, b, th = major[i] / scale, minor[i] / scale, ang[i]
        sgn = 1.0 if modes.orbit_forward[r, i] else -1.0
        y = a * np.cos(t) * np.cos(th) - sgn * b * np.sin(t) * np.sin(th)
        z = a * np.cos(t) * np.sin(th) + sgn * b * np.sin(t) * np.cos(th)
        ax.plot(y, z, color=colour(modes.node_x[i]), lw=1.2)
        ax.plot(y[0], z[0], "o", color=colour(modes.node_x[i]), ms=2.5)
    ax.plot(0, 0, "k+")
    ax.set_aspect("equal", "datalim")
    ax.set_xlabel("y / largest semi-axis [-]")
    ax.set_ylabel("z / largest semi-axis [-]")
    ax.set_title(_wrap((title + "\n" if title else "") + f"mode {r + 1}: {modes.omega_damped_rad_s[r]:.4g} rad/s, "
                       f"{modes.whirl[r]} whirl at {modes.speed_rad_s * RPM:.0f} rev/min (looking along -x; forward = "
                       "counter-clockwise)", 70), fontsize=9)
    return _save(fig, path)


def plot_critical_speed_map(cmap_result, path, *, title: str = "", forward=None, overlay=(), intersections=(),
                            operating_range=None, label: str = "forward critical") -> Path:
    """Undamped synchronous critical speeds against bearing stiffness (log-log): the forward ones
    (``forward``: (n_stiffness, n) array, rad/s; default: every column of the map), the model's
    own bearings overlaid (``overlay``: dicts {name, kind "kyy"/"kzz", stiffness N/m, speeds_rad_s
    or None for a constant bearing}: a vertical line for a constant one, its k(speed) curve for a
    tabulated one), their ``intersections`` with the curves (dicts {speed_rad_s, stiffness, name}:
    the critical speeds on those bearings) marked and labelled without overlaps, the operating
    range (rad/s) shaded."""
    from ..output.figures.labels import place_labels

    k = cmap_result.stiffness
    fig, ax = plt.subplots(figsize=(8.6, 5.6))
    S = (cmap_result.speeds_rad_s if forward is None else forward) * RPM
    for j in range(S.shape[1]):
        ax.loglog(k, S[:, j], "-", lw=1.6, color=MODE_COLOURS[j % len(MODE_COLOURS)], label=f"{label} {j + 1}")
    styles = {"kyy": "--", "kzz": ":"}
    for c in overlay:
        ls = styles.get(c["kind"], "-.")
        if c.get("speeds_rad_s") is None:
            ax.axvline(c["stiffness"], color="0.25", ls=ls, lw=1.0, label=f"{c['name']} {c['kind']} = {c['stiffness']:.3g} N/m")
        else:
            ax.loglog(np.asarray(c["stiffness"]), np.asarray(c["speeds_rad_s"]) * RPM, color="0.25", ls=ls, lw=1.2,
                      label=f"{c['name']} {c['kind']}(speed)")
    if operating_range is not None:
        lo, hi = (v * RPM for v in operating_range)
        ax.axhspan(lo, hi, color="tab:green", alpha=0.13, lw=0, label=f"operating range {lo:.0f}-{hi:.0f} rev/min")
    if intersections:
        ax.plot([c["stiffness"] for c in intersections], [c["speed_rad_s"] * RPM for c in intersections], "o", color="k",
                mec="w", ms=6, zorder=5, label="intersection: critical speed on the model's bearing")
    ax.set_xlim(k[0], k[-1])
    finite = S[np.isfinite(S)]
    if finite.size:
        ax.set_ylim(0.7 * finite.min(), 1.4 * finite.max())
    ax.set_xlabel("bearing stiffness [N/m]")
    ax.set_ylabel("undamped critical speed [rev/min]")
    ax.set_title(_wrap(f"Undamped critical speed map: {title}" if title else "Undamped critical speed map", 80),
                 fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, frameon=False)
    fig.tight_layout()
    fig.canvas.draw()
    place_labels(ax, [(c["stiffness"], c["speed_rad_s"] * RPM) for c in intersections],
                 [f"{c['speed_rad_s'] * RPM:.0f}" for c in intersections], fontsize=7.5)
    return _layout(fig, path)


def plot_static(static, path, *, title: str = "", bearing_names=None, discs=()) -> Path:
    """Static deflection along the shaft (um; the components that are loaded), the bearings marked
    with their names and the load each carries, the discs by name (``discs``: [(x, name)])."""
    from ..output.figures.labels import place_labels

    fig, ax = plt.subplots(figsize=(8.2, 4.4))
    x = static.node_x
    comps = [(static.v, "v: deflection along y"), (static.w, "w: deflection along z")]
    shown = [(c, lab) for c, lab in comps if np.any(c != 0)] or comps[1:]
    for c, lab in shown:
        ax.plot(x, c * 1e6, lw=1.6, label=lab)
    ax.axhline(0.0, color="0.5", lw=0.8)
    names = bearing_names or [f"bearing {i + 1}" for i in range(static.bearing_x.size)]
    main = shown[0][0]
    anchors, texts = [], []
    for xb, f, n in zip(static.bearing_x, static.bearing_force, names):
        yb = float(np.interp(xb, x, main)) * 1e6
        ax.plot(xb, yb, "^", color="k", ms=8, zorder=5)
        anchors.append((xb, yb))
        texts.append(f"{n}: {np.hypot(*f):.4g} N")
    for xd, n in discs:
        yd = float(np.interp(xd, x, main)) * 1e6
        ax.plot(xd, yd, "s", color="tab:gray", ms=6, zorder=5)
        anchors.append((xd, yd))
        texts.append(n)
    ax.plot([], [], "^", color="k", label="bearings: load carried")
    if discs:
        ax.plot([], [], "s", color="tab:gray", label="discs")
    ax.set_xlabel("x along the shaft [m]")
    ax.set_ylabel("static deflection [um]")
    ax.set_title(_wrap(f"Static deflection under gravity: {title}" if title else "Static deflection", 80), fontsize=10)
    ax.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, frameon=False)
    ax.grid(alpha=0.3)
    lo, hi = ax.get_ylim()
    ax.set_ylim(lo - 0.15 * (hi - lo), hi + 0.15 * (hi - lo))
    fig.tight_layout()
    fig.canvas.draw()
    place_labels(ax, anchors, texts, fontsize=7.5)
    return _layout(fig, path)


def plot_run_up(res, path, *, title: str = "") -> Path:
    """A run-up with rubs: the orbit radius at each probe against speed (rev/min), the rubs' normal
    forces below with the full annular rub intervals shaded; the clearances as dashed lines."""
    s = res.speed * RPM
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(8.6, 6.5), sharex=True, gridspec_kw={"height_ratios": [2, 1.2]})
    colours = []
    for k, x in enumerate(res.probe_x):
        name = res.probe_names[k] if k < len(getattr(res, "probe_names", [])) else ""
        line, = ax.plot(s, 1e3 * np.hypot(res.orbit_y[:, k], res.orbit_z[:, k]), lw=0.8,
                        label=f"{name} (x = {x:g} m)" if name else f"x = {x:g} m")
        colours.append(line.get_color())
    for r in res.rubs:          # a clearance only on the probe at its position, in that probe's colour
        k = next((i for i, x in enumerate(res.probe_x) if abs(x - r.x) < 1e-12), None)
        off = math.hypot(*r.centre)
        where = f"{r.name}: clearance {1e3 * r.clearance:.3g} mm" + (f" about a stator offset {1e3 * off:.3g} mm"
                                                                     if off else "")
        if k is not None:
            ax.axhline(1e3 * r.clearance, color=colours[k], ls="--", lw=0.9, label=where)
        else:
            ax.plot([], [], " ", label=where + f" (no probe at x = {r.x:g} m)")
        ax2.plot(s, r.normal_force, lw=0.8, label=r.name)
        for t0, t1 in r.full_annular:
            ax2.axvspan(*(np.interp([t0, t1], res.t, s)), color="tab:red", alpha=0.15)
    ax.set_ylabel("orbit radius [mm]")
    ax.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, frameon=False)
    ax.set_title(_wrap((title + "\n" if title else "") + f"run-up ({res.method})", 80), fontsize=9.5)
    if res.rubs or not res.bearings:
        ax2.set_ylabel("rub normal force [N]" + (" (impulse/step)" if res.method == "moreau" else ""))
    else:                                   # bearings computed from their geometry: the journals' eccentricity
        for b in res.bearings:
            ax2.plot(s, b.eccentricity, lw=0.8, label=b.name)
        ax2.set_ylabel("bearing eccentricity ratio e/c [-]")
        ax.set_ylabel("orbit radius about the bearing line [mm]\n(static sag included)")
    ax2.set_xlabel("speed [rev/min]")
    if res.rubs or res.bearings:
        ax2.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, frameon=False)
    return _save(fig, path)


def plot_cascade(cas, path, *, onset=None, title: str = "", slices: int = 40, fmax: float | None = None) -> Path:
    """Waterfall of a run-up: the whirl spectrum of each window (:func:`fem.rotor.whirl_spectrum.cascade`)
    drawn at the height of its speed (rev/min), forward whirl at positive frequencies (Hz), backward at
    negative ones, with the 1x and 0.5x lines and the whirl onset (a :class:`WhirlOnset`) marked."""
    fig, ax = plt.subplots(figsize=(7.5, 6.0))
    f_hz = cas.frequency / (2 * np.pi)
    top = float(cas.speed.max()) / (2 * np.pi)
    fmax = fmax or 1.6 * top
    keep = np.abs(f_hz) <= fmax
    pick = np.unique(np.linspace(0, cas.t.size - 1, min(slices, cas.t.size)).astype(int))
    rpm = cas.speed * RPM
    span = float(rpm.max() - rpm.min()) or 1.0
    amp = cas.amplitude[:, keep]
    scale = 3.0 * span / max(len(pick), 1) / max(float(amp[pick].max()), 1e-300)
    for i in pick[::-1]:
        base = rpm[i]
        y = base + scale * amp[i]
        ax.fill_between(f_hz[keep], base, y, color="white", zorder=2 * (cas.t.size - i))
        ax.plot(f_hz[keep], y, color="tab:blue", lw=0.7, zorder=2 * (cas.t.size - i) + 1)
    ax.plot(rpm / 60.0, rpm, "k--", lw=0.8, label="1x (synchronous)", zorder=10 ** 6)
    ax.plot(0.5 * rpm / 60.0, rpm, ":", color="0.4", lw=0.8, label="0.5x", zorder=10 ** 6)
    if onset is not None and onset.onset_speed is not None:
        ax.axhline(onset.onset_speed * RPM, color="tab:red", lw=0.8,
                   label=f"whirl onset {onset.onset_speed * RPM:.0f} rev/min ({onset.whirl_frequency / (2 * np.pi):.1f} Hz)",
                   zorder=10 ** 6)
    ax.set_xlim(-0.25 * fmax, fmax)
    ax.set_xlabel("whirl frequency [Hz] (negative: backward)")
    ax.set_ylabel("speed [rev/min] (spectra offset by their speed)")
    ax.set_title(title or f"cascade at x = {cas.probe_x:g} m")
    ax.legend(fontsize=8, loc="lower right")
    return _save(fig, path)


def plot_whirl_onset(res, onset, path, *, title: str = "") -> Path:
    """The subsynchronous whirl amplitude (band-passed envelope) against speed, log scale, with the
    onset (its minimum) marked."""
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    s = res.speed * RPM
    ax.semilogy(s, 1e6 * onset.envelope, lw=0.8)
    if onset.onset_speed is not None:
        ax.axvline(onset.onset_speed * RPM, color="tab:red", lw=0.8, label=f"onset {onset.onset_speed * RPM:.0f} rev/min")
        ax.legend(fontsize=8)
    ax.set_xlabel("speed [rev/min]")
    ax.set_ylabel("subsynchronous whirl amplitude [µm]")
    ax.set_title((title + "\n" if title else "") + f"whirl at x = {onset.probe_x:g} m: band "
                 f"{onset.band[0] / (2 * np.pi):.0f}-{onset.band[1] / (2 * np.pi):.0f} Hz", fontsize=9.5)
    return _save(fig, path)


def plot_run_up_orbits(res, path, *, probe: int = 0, windows: int = 4, title: str = "") -> Path:
    """The orbit at one probe over ``windows`` stretches of the run (a few revolutions each, ending
    at equally spaced instants), with the clearance circle of a rub at that position."""
    fig, axes = plt.subplots(1, windows, figsize=(3.2 * windows, 3.4))
    axes = np.atleast_1d(axes)
    n = res.t.size
    ends = np.linspace(n // windows, n - 1, windows).astype(int)
    x = res.probe_x[probe]
    rub = next((r for r in res.rubs if abs(r.x - x) < 1e-12), None)
    brg = next((b for b in getattr(res, "bearings", []) if abs(b.x - x) < 1e-12), None)
    lim = 1e3 * max(np.hypot(res.orbit_y[:, probe], res.orbit_z[:, probe]).max(initial=0.0),
                    rub.clearance + math.hypot(*rub.centre) if rub else 0.0, brg.clearance if brg else 0.0) * 1.1 or 1.0
    for ax, k in zip(axes, ends):
        revs = 3 * 2 * np.pi / max(res.speed[k], 1e-12)
        sel = (res.t > res.t[k] - revs) & (res.t <= res.t[k])
        ax.plot(1e3 * res.orbit_y[sel, probe], 1e3 * res.orbit_z[sel, probe], lw=0.8)
        if rub is not None:
            a = np.linspace(0, 2 * np.pi, 200)
            ax.plot(1e3 * (rub.centre[0] + rub.clearance * np.cos(a)), 1e3 * (rub.centre[1] + rub.clearance * np.sin(a)),
                    "k--", lw=0.8)
        if brg is not None and rub is None:         # the bearing's clearance circle (journal relative to it)
            a = np.linspace(0, 2 * np.pi, 200)
            ax.plot(1e3 * brg.clearance * np.cos(a), 1e3 * brg.clearance * np.sin(a), "k--", lw=0.8)
        ax.set_aspect("equal")
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, lim)
        ax.set_title(f"{res.speed[k] * RPM:.0f} rev/min", fontsize=9)
        ax.set_xlabel("y [mm]")
        ax.set_ylabel("z [mm]")
    name = res.probe_names[probe] if probe < len(getattr(res, "probe_names", [])) else ""
    fig.suptitle((title + "\n" if title else "") + f"orbits at {name + ', ' if name else ''}x = {x:g} m (last 3 "
                 "revolutions)" + (f"; dashed: {rub.name}'s clearance" if rub is not None else "")
                 + (f"; dashed: {brg.name}'s clearance" if brg is not None and rub is None else ""), fontsize=10)
    return _save(fig, path)


def plot_run_up_bode(sync, path, *, title: str = "", steady=None, names=None) -> Path:
    """Run-up Bode plot: the 1x orbit's semi-major axis (um, log) and phase lag (deg, unwrapped) of
    every probe against speed (rev/min) from a run-up's tracking filter
    (:func:`fem.rotor.runup_tracking.synchronous_response`); ``steady``: an
    :class:`UnbalanceResponse` at the same probes (major) drawn dashed for comparison (the linear
    rotor without contact)."""
    s = sync.speed_rad_s * RPM
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8.5, 6.6), sharex=True)
    amp, lag = sync.amplitude, sync.phase_lag_deg
    for k, x in enumerate(sync.probe_x):
        name = names[k] if names else f"x = {x:g} m"
        line, = a1.semilogy(s, np.maximum(amp[:, k], 1e-300) * 1e6, lw=1.4, label=f"{name}: run-up, 1x")
        a2.plot(s, unwrapped_lag(lag[:, k]), lw=1.4, color=line.get_color())
        if steady is not None:
            p = steady.probes[k]
            a1.semilogy(steady.speeds_rad_s * RPM, np.maximum(p.amplitude, 1e-300) * 1e6, "--", lw=1.0,
                        color=line.get_color(), label=f"{name}: steady state (linear, no contact)")
            a2.plot(steady.speeds_rad_s * RPM, unwrapped_lag(p.phase_lag_deg), "--", lw=1.0, color=line.get_color())
    a1.set_ylabel("1x amplitude (orbit semi-major axis) [um]")
    a1.set_title(_wrap(f"Run-up Bode plot: {title}" if title else "Run-up Bode plot", 80)
                 + f"\ntracking filter: {sync.revolutions:g}-revolution Hann window on the shaft angle", fontsize=9.5)
    a1.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, frameon=False)
    a1.grid(alpha=0.3, which="both")
    a2.set_ylabel("1x phase lag [deg]")
    a2.set_xlabel("speed [rev/min]")
    a2.set_xlim(s.min(), s.max())
    a2.grid(alpha=0.3)
    fig.tight_layout()
    return _layout(fig, path)
