"""The nonlinear amplitude-frequency curve (an AFCResult): stable parts solid, unstable dashed, folds marked."""
from __future__ import annotations

from pathlib import Path

import numpy as np


def plot_afc(result, path, ax=None, label=None) -> None:
    """PNG of the curve: stable parts solid, unstable parts dashed red, folds marked."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    own = ax is None
    if own:
        fig, ax = plt.subplots(figsize=(7, 4.5))
    x = result.z if result.omega_ref else result.omega
    y = result.response
    st = np.asarray(result.stable, bool)
    ys = np.where(st, y, np.nan)
    yu = np.where(~st, y, np.nan)
    # extend unstable segments by one point on each side so the curve is continuous
    for i in range(1, len(st)):
        if st[i] != st[i - 1]:
            yu[i - 1 if st[i - 1] else i] = y[i - 1 if st[i - 1] else i]
    line, = ax.plot(x, ys, "-", lw=1.6, label=label or f"{result.method} (stable)")
    ax.plot(x, yu, "--", color=line.get_color(), lw=1.2, alpha=0.9,
            label=None if label else "unstable")
    for f in result.folds:
        fx = f["omega"] / result.omega_ref if result.omega_ref else f["omega"]
        ax.plot([fx], [f["response"]], "o", ms=4, color=line.get_color(), mfc="none")
    bb = (result.extra or {}).get("backbone")
    if bb and bb.get("response"):
        bx = np.asarray(bb["omega_rad_s"]) / (result.omega_ref or 1.0)
        ax.plot(bx, bb["response"], "-.", color="0.35", lw=1.2,
                label=f"backbone: nonlinear mode ({bb['method'].split(' (')[0]})")
    if own:
        ax.set_xlabel("z = omega / omega_ref" if result.omega_ref else "omega, rad/s")
        ax.set_ylabel(result.response_label)
        ax.grid(alpha=0.3)
        ax.legend()
        fig.tight_layout()
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=120)
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
