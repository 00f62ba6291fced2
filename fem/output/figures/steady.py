"""The nonlinear amplitude-frequency curve (an AFCResult): stable parts solid, unstable dashed, folds marked."""
from __future__ import annotations

from pathlib import Path

import numpy as np


MARKERS = {"fold": ("o", "fold (turning point)"), "branch_point": ("s", "branch point"),
           "period_doubling": ("^", "period doubling"), "neimark_sacker": ("D", "Neimark-Sacker")}


def _curve(ax, result, label=None, color=None):
    """The branch: stable parts solid, unstable dashed in the same colour, its bifurcations marked by
    type; the legend in words ("harmonic balance, 7 harmonics: stable branch").  Returns the colour
    and the bifurcation kinds drawn."""
    from .quantities import method_text

    x = result.z if result.omega_ref else result.omega
    y = result.response
    st = np.asarray(result.stable, bool)
    ys = np.where(st, y, np.nan)
    yu = np.where(~st, y, np.nan)
    # extend unstable segments by one point on each side so the curve is continuous
    for i in range(1, len(st)):
        if st[i] != st[i - 1]:
            yu[i - 1 if st[i - 1] else i] = y[i - 1 if st[i - 1] else i]
    name = label or method_text(result.method)
    line, = ax.plot(x, ys, "-", lw=1.6, label=f"{name}: stable branch" if not label else label, color=color)
    c = line.get_color()
    if np.any(~st):
        ax.plot(x, yu, "--", color=c, lw=1.2, alpha=0.9, label=f"{name}: unstable branch" if not label else "_nolegend_")
    bifs = getattr(result, "bifurcations", None) or [
        type("F", (), {"kind": "fold", "omega": f["omega"], "response": f["response"]}) for f in result.folds]
    for b in bifs:
        bx = b.omega / result.omega_ref if result.omega_ref else b.omega
        ax.plot([bx], [b.response], MARKERS[b.kind][0], ms=5, color=c, mfc="none", mew=1.3)
    return c, {b.kind for b in bifs}


def plot_afc(result, path, ax=None, label=None, title: str | None = None) -> None:
    """PNG of the curve: stable parts solid, unstable parts dashed, bifurcations marked by type (fold o,
    branch point square, period doubling triangle, Neimark-Sacker diamond), secondary (switched) branches
    in their own colours, the backbone (nonlinear mode) dash-dotted; below, the HB truncation estimate
    per point against its tolerance.  The axes carry quantity and unit (the excitation frequency in
    rad/s, or as omega / omega_ref when the file gives omega_ref)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .quantities import measure_label, method_text

    own = ax is None
    est = getattr(result, "truncation", None)
    strip = own and est is not None and np.size(est) > 0
    if own:
        if strip:
            fig, (ax, ax2) = plt.subplots(2, 1, figsize=(10.0, 6.0), sharex=True,
                                          gridspec_kw={"height_ratios": [3.2, 1.0]})
        else:
            fig, ax = plt.subplots(figsize=(7.8, 4.8))
    _, kinds = _curve(ax, result, label)
    for sec in getattr(result, "secondary", []) or []:
        _, k2 = _curve(ax, sec, label=sec.origin.split(", back on")[0].replace(" rad/s", ""), color=None)
        kinds |= k2
    bb = (result.extra or {}).get("backbone")
    if bb and bb.get("response"):
        bx = np.asarray(bb["omega_rad_s"]) / (result.omega_ref or 1.0)
        ax.plot(bx, bb["response"], "-.", color="0.35", lw=1.2,
                label=f"backbone: {method_text(bb['method'])}")
    if not label:
        for kind in ("fold", "branch_point", "period_doubling", "neimark_sacker"):
            if kind in kinds:
                ax.plot([], [], MARKERS[kind][0], color="0.3", mfc="none", label=MARKERS[kind][1])
    if own:
        ref = result.omega_ref
        xlabel = (f"excitation frequency omega / omega_ref [-] (omega_ref = {ref:.6g} rad/s)" if ref
                  else "excitation frequency omega [rad/s]")
        q, u = measure_label(result.response_label)
        ax.set_ylabel(f"{q} [{u}]", fontsize=8.5)
        ax.grid(alpha=0.3)
        sub = "amplitude-frequency curve (continuation)" + ("" if getattr(result, "completed", True) else
                                                              ": stopped early, partial branch")
        ax.set_title((title + "\n" if title else "") + sub, fontsize=9)
        if strip:
            x = result.z if result.omega_ref else result.omega
            e = np.asarray(est, float)
            pos = e[e > 0]
            floor = max(float(pos.min()) / 3 if pos.size else 1e-9, (result.truncation_tol or 1e-3) * 1e-6)
            ax2.semilogy(x, np.maximum(e, floor), ".", ms=3, color="0.25",
                         label="truncation estimate (0 shown at the floor)")
            top = max(float(e.max()) if e.size else 0.0, result.truncation_tol or 0.0)
            ax2.set_ylim(floor / 2, top * 4)
            if result.truncation_tol:
                ax2.axhline(result.truncation_tol, color="tab:red", lw=1.0, ls="--",
                            label=f"tolerance {result.truncation_tol:g}")
            ax2.set_ylabel("truncation estimate [-]", fontsize=8)
            ax2.set_xlabel(xlabel)
            ax2.grid(alpha=0.3, which="both")
            ax2.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)   # off the points
            ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)    # off the curves
        else:
            ax.set_xlabel(xlabel)
            ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)   # off the curves
        fig.tight_layout()
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=120, bbox_inches="tight")
        plt.close(fig)


def plot_phase_portraits(panels, path) -> None:
    """PNG of phase portraits side by side: ``panels`` is a list of dicts with ``title``, ``phi``, ``phidot``
    (one orbit) and ``slack`` (bool per sample: drawn red, the taut parts blue)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from matplotlib.ticker import MaxNLocator

    n = len(panels)
    cols = 2 if n > 1 else 1
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 4.0 * rows), squeeze=False)
    for ax, p in zip(axes.ravel(), panels):
        phi, v, slack = np.asarray(p["phi"]), np.asarray(p["phidot"]), np.asarray(p["slack"], bool)
        ax.plot(phi, np.where(slack, np.nan, v), "-", color="tab:blue", lw=1.2, label="taut")
        if slack.any():
            ax.plot(phi, np.where(slack, v, np.nan), "-", color="tab:red", lw=1.6, label="zero tension")
        ax.axvline(0.0, color="0.6", lw=0.8)
        ax.set_title(p["title"], fontsize=9)
        ax.set_xlabel(p.get("xlabel", "phi [rad]"))
        ax.set_ylabel("phi' [rad/s]")
        ax.xaxis.set_major_locator(MaxNLocator(5))       # long tick labels (-0.015) must not touch
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper right")
    for ax in axes.ravel()[n:]:
        ax.set_visible(False)
    fig.tight_layout()
    fig.savefig(Path(path), dpi=110)
    plt.close(fig)


def plot_orbit_overlay(curves, path, title: str = "", xlabel: str = "t [s]", ylabel: str = "") -> None:
    """PNG of several time series on one axis: ``curves`` = [(t, y, label, style)]; ``ylabel``: the
    quantity and unit of ``y``."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4.2))
    for t, y, label, style in curves:
        ax.plot(t, y, style, lw=1.3, label=label)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(Path(path), dpi=110)
    plt.close(fig)
