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
    if own:
        ax.set_xlabel("z = omega / omega_ref" if result.omega_ref else "omega, rad/s")
        ax.set_ylabel(result.response_label)
        ax.grid(alpha=0.3)
        ax.legend()
        fig.tight_layout()
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=120)
        plt.close(fig)
