"""Figure of ``drivefem stability``: the log decrement of the tracked modes against speed with the
stability threshold, and the API Level I screening (log decrement of the first forward mode
against the applied cross-coupling, Q_A, Q_0 and the criteria).  Draws results only."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .plots import MODE_COLOURS, RPM, WHIRL_LINE, _dominant, _layout, _wrap, mode_tags, plt


def plot_stability(threshold, path, *, level1=None, title: str = "", operating_range=None) -> Path:
    """Top: log decrement [-] of every tracked mode of the threshold's scan against speed [rev/min],
    the threshold marked (or the top of the scan when the rotor stays stable), the operating range
    shaded.  Bottom (with ``level1``, a :class:`fem.rotor.api_level1.LevelIResult`): the first
    forward mode's log decrement against the applied cross-coupling [MN/m], Q_A and Q_0 marked,
    the criterion delta = 0.1 dashed, the verdict in the title."""
    rows = 2 if level1 is not None else 1
    fig, axes = plt.subplots(rows, 1, figsize=(8.8, 7.6 if rows == 2 else 4.6), squeeze=False)
    ax = axes[0, 0]
    scan = threshold.scan
    s = scan.speeds_rad_s * RPM
    ld = np.where(np.isfinite(scan.log_decrement), scan.log_decrement, np.nan)
    tags = mode_tags(scan)
    colours = [MODE_COLOURS[j % len(MODE_COLOURS)] for j in range(scan.n_modes)]
    for j in range(scan.n_modes):
        if scan.kind[j] == "rigid":
            continue
        w = _dominant([row[j] for row in scan.whirl])
        ax.plot(s, ld[:, j], color=colours[j], ls=WHIRL_LINE.get(w, "-"), lw=1.4, label=f"mode {tags[j]}: {w} whirl")
    ax.axhline(0.0, color="k", lw=0.9)
    if operating_range is not None:
        lo, hi = (v * RPM for v in operating_range)
        ax.axvspan(lo, hi, color="tab:green", alpha=0.13, lw=0, label=f"operating range {lo:.0f}-{hi:.0f} rev/min")
    th = threshold.threshold_rad_s
    if th is not None:
        ax.axvline(th * RPM, color="tab:red", lw=1.2,
                   label=f"stability threshold {th * RPM:.0f} rev/min ({threshold.whirl} whirl, "
                         f"{threshold.frequency_rad_s / (2 * np.pi):.4g} Hz)")
        head = f"stability threshold {th * RPM:.0f} rev/min"
    else:
        head = f"stable up to {s[-1]:.0f} rev/min (no log decrement crosses zero)"
    ax.set_xlim(s[0], s[-1])
    ax.set_xlabel("speed [rev/min]")
    ax.set_ylabel("log decrement [-]")
    ax.set_title(_wrap(f"Stability: {title}: {head}" if title else f"Stability: {head}", 85), fontsize=10)
    ax.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, frameon=False)
    ax.grid(alpha=0.3)
    a2 = None
    if level1 is not None:
        a2 = axes[1, 0]
        scale, unit = (1e-6, "MN/m") if level1.cross_coupling[-1] >= 1e6 else (1e-3, "kN/m")
        Q = level1.cross_coupling * scale
        a2.plot(Q, level1.log_decrement, "o-", color="tab:blue", ms=3, lw=1.4, label="first forward mode")
        a2.axhline(0.1, color="tab:orange", ls="--", lw=1.0, label="criterion: log decrement at QA >= 0.1")
        a2.axhline(0.0, color="k", lw=0.9)
        a2.axvline(level1.q_a * scale, color="tab:green", lw=1.2, label=f"QA = {level1.q_a * scale:.4g} {unit} (Wachel)")
        if level1.q0 is not None and level1.q0 * scale <= Q[-1] * 1.0001:
            a2.axvline(level1.q0 * scale, color="tab:red", lw=1.2, label=f"Q0 = {level1.q0 * scale:.4g} {unit}")
        r = level1.ratio
        verdict = "passes Level I" if level1.passed else "Level II analysis required"
        ratio = "Q0/QA > 1000" if r is None else f"Q0/QA = {r:.3g}"
        a2.set_title(_wrap(f"API Level I screening at {level1.speed_rad_s * RPM:.0f} rev/min "
                           f"(Q at {level1.placement}): log dec at QA {level1.log_decrement_a:.3g}, {ratio}: {verdict}",
                           85), fontsize=9.5)
        a2.set_xlabel(f"applied cross-coupled stiffness Q [{unit}]")
        a2.set_ylabel("log decrement [-]")
        a2.set_xlim(0, Q[-1])
        a2.grid(alpha=0.3)
        a2.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, frameon=False)
    fig.tight_layout()
    fig.canvas.draw()
    return _layout(fig, path)
