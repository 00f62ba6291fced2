"""Figure of a parametric stability chart (textbook Fig. 7.4): the instability tongues in the
(Omega, eps) plane, shaded by growth rate and hatched, with the root-found edges, the damping
threshold eps* and the predicted tongue centres (7.26).  Takes a
:class:`discrete.linear.parametric.StabilityChart`; never recomputes anything."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def _merged_centre_ticks(centres, w1: float, close: float) -> list[tuple[float, str]]:
    """Top-axis ticks of the predicted centres: centres closer than ``close`` (in the plotted unit)
    share one tick at their mean, their labels joined (the rotated labels would overlap)."""
    groups: list[list[tuple[float, str]]] = []
    for c in sorted(centres, key=lambda c: c["omega_rad_s"]):
        xc = c["omega_rad_s"] / w1
        if groups and xc - groups[-1][-1][0] < close:
            groups[-1].append((xc, c["label"]))
        else:
            groups.append([(xc, c["label"])])
    return [(float(np.mean([xc for xc, _ in g])), " ~ ".join(label for _, label in g)) for g in groups]


def plot_stability_chart(chart, path: str | Path, *, title: str = "", normalise: bool = True,
                         max_centre_labels: int = 12) -> Path:
    """Write the chart as PNG.  ``normalise``: Omega / omega_1 on the horizontal axis (as in
    Fig. 7.4; the command asks for it when the file gives ``omega_ratio``), else rad/s (the file
    gives ``omega_rad_s``)."""
    w1 = float(chart.natural_omega_rad_s[0]) if normalise else 1.0
    x = chart.omega_rad_s / w1
    y = chart.depth
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    unstable = ~chart.stable
    if y.size > 1 and np.any(unstable):
        rate = np.ma.masked_where(~unstable, chart.growth_rate)
        mesh = ax.pcolormesh(x, y, rate, shading="nearest", cmap="Reds", vmin=0.0)
        fig.colorbar(mesh, ax=ax, label="growth rate ln|rho|max / T  [1/s]")
        ax.contourf(x, y, unstable.astype(float), levels=[0.5, 1.5], colors="none", hatches=["///"])
        ax.contour(x, y, chart.rho_max, levels=[1.0 + chart.stability_margin], colors="k", linewidths=0.8)
    elif np.any(unstable):
        ax.plot(x[unstable[0]], np.full(int(unstable[0].sum()), y[0]), "s", color="tab:red", ms=3,
                label="unstable grid points")
    first = True
    for b in chart.boundaries:
        for lo, hi in zip(b.omega_low_rad_s, b.omega_high_rad_s):
            ax.plot([lo / w1, hi / w1], [b.depth, b.depth], "-|", color="tab:blue", lw=1.5, ms=8,
                    label="edges (root finding)" if first else None)
            first = False
    first = True
    for t in chart.thresholds:
        if not np.isfinite(t.depth_minimum) or t.depth_minimum <= 0:
            continue
        ax.axhline(t.depth_minimum, color="tab:green", ls="--", lw=1.0,
                   label="damping threshold eps* (principal tongues)" if first else None)
        xt = t.omega_at_minimum_rad_s / w1
        ax.plot(xt, t.depth_minimum, "o", color="tab:green", ms=5)
        right = xt > x[0] + 0.7 * (x[-1] - x[0])
        text = f"eps* = {t.depth_minimum:.5g}"
        if np.isfinite(t.depth_at_centre) and abs(t.depth_at_centre - t.depth_minimum) > 5e-6 * t.depth_minimum:
            text += f" (tip); {t.depth_at_centre:.5g} at 2 w{t.mode}"
        low = y[-1] > y[0] and t.depth_minimum < y[0] + 0.15 * (y[-1] - y[0])     # no room below the line
        ax.annotate(text, (xt, t.depth_minimum), textcoords="offset points", xytext=(-6 if right else 6, 4 if low else -4),
                    ha="right" if right else "left", va="bottom" if low else "top", fontsize=8, color="tab:green")
        first = False
    # predicted centres (7.26) on a top axis: principal 2 w_r/s and combinations (w_r + w_q)/s
    centres = sorted(chart.centres, key=lambda c: (c["s"], c["omega_rad_s"]))[:max_centre_labels]
    top = ax.secondary_xaxis("top")
    ticks = _merged_centre_ticks(centres, w1, 0.02 * (x[-1] - x[0]))
    top.set_xticks([xc for xc, _ in ticks])
    top.set_xticklabels([label for _, label in ticks], rotation=90, fontsize=7)
    top.tick_params(length=3, pad=1)
    for c in centres:
        ax.axvline(c["omega_rad_s"] / w1, color="0.6", ls=":", lw=0.8)
    ax.set_xlim(x[0], x[-1])
    ax.set_ylim(y[0], y[-1] if y[-1] > y[0] else y[0] + 1.0)
    ax.set_xlabel(f"excitation frequency Omega / omega_1 [-] (omega_1 = {w1:.6g} rad/s)" if normalise
                  else "excitation frequency Omega [rad/s]")
    ax.set_ylabel("depth of pulsation eps [-]")
    ax.set_title(title or f"Parametric stability chart ({chart.damping})", fontsize=9, pad=42 if centres else 6)
    handles, labels = ax.get_legend_handles_labels()
    if handles:             # below the axis label, in a strip of its own (not tied to the axes' height)
        fig.legend(handles, labels, fontsize=8, loc="lower center", ncol=2, frameon=False)
        fig.tight_layout(rect=(0, 0.07, 1, 1))
    else:
        fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
