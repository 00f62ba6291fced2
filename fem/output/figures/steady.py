"""The nonlinear amplitude-frequency curve (an AFCResult): stable parts solid, unstable dashed, folds marked."""
from __future__ import annotations

from pathlib import Path

import numpy as np


def plot_afc(result, path, ax=None, label=None, title: str = "") -> None:
    """PNG of the curve: stable branch solid, unstable branch dashed in the same colour, folds as
    open circles, the backbone (nonlinear mode) dash-dotted.  The legend says it in words
    ("harmonic balance, 7 harmonics: stable branch"); the axes carry quantity and unit (the
    excitation frequency in rad/s, or as omega / omega_ref when the file gives omega_ref)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .quantities import measure_label, method_text

    own = ax is None
    if own:
        fig, ax = plt.subplots(figsize=(7.8, 4.8))
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
    line, = ax.plot(x, ys, "-", lw=1.6, label=f"{name}: stable branch" if not label else label)
    if np.any(~st):
        ax.plot(x, yu, "--", color=line.get_color(), lw=1.2, alpha=0.9,
                label=f"{name}: unstable branch" if not label else "_nolegend_")
    for k, f in enumerate(result.folds):
        fx = f["omega"] / result.omega_ref if result.omega_ref else f["omega"]
        ax.plot([fx], [f["response"]], "o", ms=4, color=line.get_color(), mfc="none",
                label="fold (turning point)" if k == 0 and not label else "_nolegend_")
    bb = (result.extra or {}).get("backbone")
    if bb and bb.get("response"):
        bx = np.asarray(bb["omega_rad_s"]) / (result.omega_ref or 1.0)
        ax.plot(bx, bb["response"], "-.", color="0.35", lw=1.2,
                label=f"backbone: {method_text(bb['method'])}")
    if own:
        ref = result.omega_ref
        ax.set_xlabel(f"excitation frequency omega / omega_ref [-] (omega_ref = {ref:.6g} rad/s)" if ref
                      else "excitation frequency omega [rad/s]")
        q, u = measure_label(result.response_label)
        ax.set_ylabel(f"{q} [{u}]", fontsize=8.5)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)   # off the curves
        sub = "amplitude-frequency curve (continuation)" + ("" if getattr(result, "completed", True) else
                                                              ": stopped early, partial branch")
        ax.set_title((title + "\n" if title else "") + sub, fontsize=9)
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
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper right")
    for ax in axes.ravel()[n:]:
        ax.set_visible(False)
    fig.tight_layout()
    fig.savefig(Path(path), dpi=110)
    plt.close(fig)


def plot_orbit_overlay(curves, path, title: str = "", xlabel: str = "t [s]") -> None:
    """PNG of several time series on one axis: ``curves`` = [(t, y, label, style)]."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4.2))
    for t, y, label, style in curves:
        ax.plot(t, y, style, lw=1.3, label=label)
    ax.set_xlabel(xlabel)
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(Path(path), dpi=110)
    plt.close(fig)
