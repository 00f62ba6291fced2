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


#: the log-decrement panel of a Campbell diagram is cut here (heavily damped modes would flatten it)
LOG_DEC_SHOWN = 4.0


def plot_campbell(camp, path, *, title: str = "", log_decrement: bool = True) -> Path:
    """Damped natural frequencies (Hz) of the tracked modes against speed (rev/min), coloured by
    whirl (forward solid, backward dashed), the excitation lines k x speed, and the critical
    speeds as circles; below, the log decrement of each mode.  A mode is drawn where it
    oscillates: not at speeds where its eigenvalue is real (omega_d = 0: overdamped, or rigid)."""
    s = camp.speeds_rad_s * RPM
    fig, axes = plt.subplots(2 if log_decrement else 1, 1, figsize=(7.5, 7 if log_decrement else 4.8), sharex=True,
                             gridspec_kw={"height_ratios": [3, 1.3]} if log_decrement else None)
    ax = axes[0] if log_decrement else axes
    f = np.where(camp.omega_damped_rad_s > 0, camp.omega_damped_rad_s, np.nan) / (2 * np.pi)
    seen = set()
    for j in range(camp.n_modes):
        w = _dominant([row[j] for row in camp.whirl])
        colour, ls = WHIRL_STYLE.get(w, ("k", "-"))
        ax.plot(s, f[:, j], color=colour, ls=ls, lw=1.6, label=None if w in seen else f"{w} whirl")
        seen.add(w)
    top = float(np.nanmax(f)) * 1.05 if np.any(np.isfinite(f)) else 1.0
    for k in camp.orders:
        ax.plot(s, k * camp.speeds_rad_s / (2 * np.pi), color="0.3", lw=1.0, ls="-")
        xe = min(s[-1], top * 2 * np.pi / k * RPM)
        ax.text(xe, k * xe / RPM / (2 * np.pi), f" {k:g}x", fontsize=8, va="bottom", ha="right", color="0.3")
    crit = camp.critical_speeds
    if crit:
        ax.plot([c.speed_rpm for c in crit], [c.frequency_rad_s / (2 * np.pi) for c in crit], "o", mfc="none",
                mec="k", ms=8, label="critical speeds")
        last = -np.inf
        for c in sorted(crit, key=lambda c: c.speed_rpm):
            if c.order == 1 and c.speed_rpm - last > 0.04 * (s[-1] - s[0]):     # labels that would overlap: the first
                ax.annotate(f"{c.speed_rpm:.0f}", (c.speed_rpm, c.frequency_rad_s / (2 * np.pi)), fontsize=7,
                            xytext=(4, -10), textcoords="offset points")
                last = c.speed_rpm
    ax.set_ylim(0, top)
    ax.set_ylabel("damped natural frequency [Hz]")
    ax.set_title(title or "Campbell diagram", fontsize=10)
    ax.legend(fontsize=8, loc="upper left")
    ax.grid(alpha=0.3)
    if log_decrement:
        a2 = axes[1]
        ld = np.where(np.isfinite(camp.log_decrement), camp.log_decrement, np.nan)
        for j in range(camp.n_modes):
            w = _dominant([row[j] for row in camp.whirl])
            colour, ls = WHIRL_STYLE.get(w, ("k", "-"))
            a2.plot(s, ld[:, j], color=colour, ls=ls, lw=1.2)
        a2.axhline(0.0, color="k", lw=0.8)
        hi = float(np.nanmax(ld)) if np.any(np.isfinite(ld)) else 1.0
        if hi > LOG_DEC_SHOWN:           # modes just past overdamped: log dec -> inf; the stability margin is near 0
            lo = float(np.nanmin(ld))
            a2.set_ylim(min(lo, 0.0) - 0.05 * LOG_DEC_SHOWN, LOG_DEC_SHOWN)
            a2.set_ylabel(f"log decrement\n(shown up to {LOG_DEC_SHOWN:g})")
        else:
            a2.set_ylabel("log decrement")
        a2.grid(alpha=0.3)
        a2.set_xlabel("speed [rev/min]")
    else:
        ax.set_xlabel("speed [rev/min]")
    return _save(fig, path)


def plot_bode(resp, path, *, probes=None, title: str = "", log: bool = True) -> Path:
    """Amplitude and phase lag of the probes against speed, peaks marked with their half-power
    band, the operating range shaded."""
    s = resp.speeds_rad_s * RPM
    idx = range(len(resp.probes)) if probes is None else probes
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7.5, 6.5), sharex=True)
    for j in idx:
        p = resp.probes[j]
        label = f"x = {p.x:g} m ({p.direction})"
        (a1.semilogy if log else a1.plot)(s, np.maximum(p.amplitude, 1e-300) * 1e6, label=label)
        a2.plot(s, p.phase_lag_deg, label=label)
    annotated = set()
    for pk in resp.peaks:
        if pk.probe in idx:
            a1.plot(pk.speed_rad_s * RPM, pk.amplitude * 1e6, "kv", ms=5)
            if pk.half_power_rad_s is not None:
                lo, hi = pk.half_power_rad_s
                a1.plot([lo * RPM, hi * RPM], [pk.amplitude / np.sqrt(2) * 1e6] * 2, "k-", lw=0.8)
                key = round(pk.speed_rad_s * RPM / 50)          # one label per peak speed
                if key not in annotated:
                    annotated.add(key)
                    a1.annotate(f"AF {pk.amplification_factor:.1f}", (pk.speed_rad_s * RPM, pk.amplitude * 1e6),
                                fontsize=7, xytext=(4, 4), textcoords="offset points")
    if resp.operating_range is not None:
        for a in (a1, a2):
            a.axvspan(resp.operating_range[0] * RPM, resp.operating_range[1] * RPM, color="tab:green", alpha=0.12)
    a1.set_ylabel("amplitude [um]")
    a1.set_title(title or "unbalance response", fontsize=10)
    a1.legend(fontsize=7)
    a1.grid(alpha=0.3, which="both")
    a2.set_ylabel("phase lag [deg]")
    a2.set_ylim(0, 360)
    a2.set_yticks(range(0, 361, 90))
    a2.set_xlabel("speed [rev/min]")
    a2.grid(alpha=0.3)
    return _save(fig, path)


def plot_polar(resp, path, probe: int = 0, *, title: str = "") -> Path:
    """Polar (Nyquist) plot of one probe's complex response over the speed range (um), speeds labelled."""
    p = resp.probes[probe]
    z = p.value * 1e6
    fig, ax = plt.subplots(figsize=(5.5, 5.5))
    ax.plot(z.real, z.imag, "-", color="tab:blue")
    n = max(1, z.size // 8)
    for k in range(0, z.size, n):
        ax.plot(z.real[k], z.imag[k], "o", color="tab:blue", ms=3)
        ax.annotate(f"{resp.speeds_rad_s[k] * RPM:.0f}", (z.real[k], z.imag[k]), fontsize=7)
    ax.axhline(0, color="0.6", lw=0.8)
    ax.axvline(0, color="0.6", lw=0.8)
    ax.set_aspect("equal", "datalim")
    ax.set_xlabel("real [um]")
    ax.set_ylabel("imaginary [um]")
    ax.set_title(title or f"polar plot, x = {p.x:g} m ({p.direction}); labels: rev/min", fontsize=9)
    return _save(fig, path)


def _ellipse(V, W, n: int = 121):
    t = np.linspace(0, 2 * np.pi, n)
    e = np.exp(1j * t)
    return (V * e).real, (W * e).real


def plot_orbits(V, W, node_x, path, *, nodes=None, title: str = "") -> Path:
    """Orbits (ellipses in the y-z plane, looking along -x) of complex amplitudes V, W at the
    shaft nodes (arrays over the nodes), with a dot at t = 0 and the whirl direction."""
    V, W, node_x = np.asarray(V), np.asarray(W), np.asarray(node_x)
    nodes = list(range(V.size)) if nodes is None else list(nodes)
    o = Orbits.of(V, W)
    fig, ax = plt.subplots(figsize=(6, 6))
    cmap = plt.get_cmap("viridis")
    for k, i in enumerate(nodes):
        y, z = _ellipse(V[i], W[i])
        c = cmap(k / max(len(nodes) - 1, 1))
        fwd = o.forward[i] > o.backward[i]
        ax.plot(y, z, color=c, lw=1.2, label=f"x = {node_x[i]:.3g} m ({'fwd' if fwd else 'bwd'})")
        ax.plot(y[0], z[0], "o", color=c, ms=3)
    ax.plot(0, 0, "k+")
    ax.set_aspect("equal", "datalim")
    ax.set_xlabel("y")
    ax.set_ylabel("z")
    ax.set_title(title or "orbits (spin about +x: forward = counter-clockwise)", fontsize=9)
    if len(nodes) <= 12:
        ax.legend(fontsize=7)
    return _save(fig, path)


def plot_mode_orbits(modes, r: int, path, *, nodes=None) -> Path:
    """Orbits of mode ``r`` (0-based) of a :class:`fem.rotor.modal.RotorModes` (from its
    orbit axes: semi-axes, major-axis angle and direction of every shaft node)."""
    major, minor, ang = modes.orbit_major[r], modes.orbit_minor[r], modes.orbit_angle[r]
    fig, ax = plt.subplots(figsize=(6, 6))
    cmap = plt.get_cmap("viridis")
    nodes = list(range(modes.node_x.size)) if nodes is None else list(nodes)
    t = np.linspace(0, 2 * np.pi, 121)
    for k, i in enumerate(nodes):
        a, b, th = major[i], minor[i], ang[i]
        sgn = 1.0 if modes.orbit_forward[r, i] else -1.0
        y = a * np.cos(t) * np.cos(th) - sgn * b * np.sin(t) * np.sin(th)
        z = a * np.cos(t) * np.sin(th) + sgn * b * np.sin(t) * np.cos(th)
        ax.plot(y, z, color=cmap(k / max(len(nodes) - 1, 1)), lw=1.2)
    ax.set_aspect("equal", "datalim")
    ax.set_xlabel("y")
    ax.set_ylabel("z")
    ax.set_title(f"mode {r + 1}: {modes.omega_damped_rad_s[r]:.4g} rad/s, {modes.whirl[r]} whirl "
                 f"at {modes.speed_rad_s * RPM:.0f} rev/min", fontsize=9)
    return _save(fig, path)


def plot_critical_speed_map(cmap_result, path, *, title: str = "") -> Path:
    """Undamped critical speeds against bearing stiffness (log-log), with the bearings' own
    stiffness curves (kyy, kzz against speed) when they are tabulated."""
    k = cmap_result.stiffness
    fig, ax = plt.subplots(figsize=(7, 5))
    S = cmap_result.speeds_rad_s * RPM
    for j in range(S.shape[1]):
        ax.loglog(k, S[:, j], "-", lw=1.5, label=f"critical {j + 1}")
    for c in cmap_result.bearing_curves:
        sp = np.asarray(c["speeds_rad_s"]) * RPM
        ax.loglog(np.asarray(c["kyy"]), sp, "k--", lw=1.0, label=f"bearing {c['bearing']} kyy")
        ax.loglog(np.asarray(c["kzz"]), sp, "k:", lw=1.0, label=f"bearing {c['bearing']} kzz")
    ax.set_xlabel("bearing stiffness [N/m]")
    ax.set_ylabel("critical speed [rev/min]")
    ax.set_title(title or "undamped critical speed map", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    return _save(fig, path)


def plot_static(static, path, *, title: str = "") -> Path:
    """Static deflection v, w along the shaft (um) with the bearing loads annotated."""
    fig, ax = plt.subplots(figsize=(7, 3.8))
    ax.plot(static.node_x, static.v * 1e6, label="v (y)")
    ax.plot(static.node_x, static.w * 1e6, label="w (z)")
    for x, f in zip(static.bearing_x, static.bearing_force):
        ax.axvline(x, color="0.7", lw=0.8)
        ax.annotate(f"{np.hypot(*f):.0f} N", (x, 0), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("deflection [um]")
    ax.set_title(title or "static deflection", fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return _save(fig, path)


def plot_run_up(res, path, *, title: str = "") -> Path:
    """A run-up with rubs: the orbit radius at each probe against speed (rev/min), the rubs' normal
    forces below with the full annular rub intervals shaded; the clearances as dashed lines."""
    s = res.speed * RPM
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(7.5, 6.5), sharex=True, gridspec_kw={"height_ratios": [2, 1.2]})
    for k, x in enumerate(res.probe_x):
        ax.plot(s, 1e3 * np.hypot(res.orbit_y[:, k], res.orbit_z[:, k]), lw=0.8, label=f"x = {x:g} m")
    for r in res.rubs:
        ax.axhline(1e3 * r.clearance, color="k", ls="--", lw=0.8)
        ax2.plot(s, r.normal_force, lw=0.8, label=r.name)
        for t0, t1 in r.full_annular:
            ax2.axvspan(*(np.interp([t0, t1], res.t, s)), color="tab:red", alpha=0.15)
    ax.set_ylabel("orbit radius [mm]")
    ax.legend(fontsize=8)
    ax.set_title(title or f"run-up ({res.method})")
    if res.rubs:
        ax.text(0.01, 0.97, "dashed: rub clearances (about the stator centres)", transform=ax.transAxes, fontsize=8,
                va="top")
    if res.rubs or not res.bearings:
        ax2.set_ylabel("rub normal force [N]" + (" (impulse/step)" if res.method == "moreau" else ""))
    else:                                   # bearings computed from their geometry: the journals' eccentricity
        for b in res.bearings:
            ax2.plot(s, b.eccentricity, lw=0.8, label=b.name)
        ax2.set_ylabel("bearing eccentricity ratio e/c [-]")
        ax.text(0.01, 0.97, "orbit radius about the bearing centres' line (static sag included)", transform=ax.transAxes,
                fontsize=8, va="top")
    ax2.set_xlabel("speed [rev/min]")
    if res.rubs or res.bearings:
        ax2.legend(fontsize=8)
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
    ax.set_title(title or f"whirl at x = {onset.probe_x:g} m: band {onset.band[0] / (2 * np.pi):.0f}-"
                 f"{onset.band[1] / (2 * np.pi):.0f} Hz")
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
    axes[0].set_ylabel("z [mm]")
    fig.suptitle(title or f"orbits at x = {x:g} m (last 3 revolutions)"
                 + (f"; dashed: {brg.name}'s clearance" if brg is not None and rub is None else ""), fontsize=10)
    return _save(fig, path)
