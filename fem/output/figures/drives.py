"""Plots of drive results (they take computed results, never recompute them)."""
from __future__ import annotations

from pathlib import Path

import numpy as np


def plot_spectrum_vs_n(sweep, path, title: str | None = None):
    """Natural frequencies vs the number of mechanisms n: dots per n, the pass bands |xi| <= 1
    of the block (below k and above p_*), the stop band (k, p_*) of J*(p), and the continuum
    (pseudo-medium) roots (10.50) as the n -> inf limit."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 5.5), dpi=130)
    ax.fill_between(sweep.n, sweep.upper_band[:, 0], sweep.upper_band[:, 1], color="tab:blue", alpha=0.12,
                    label="pass bands $|\\xi(p)| \\leq 1$ (10.32)")
    ax.fill_between(sweep.n, np.full(sweep.n.size, 1.0), sweep.lower_band[:, 1], color="tab:blue", alpha=0.12)
    ax.axhspan(*sweep.stop_band, color="tab:red", alpha=0.15, label="stop band $(k, p_*)$: $J^*(p) < 0$")
    for i, (n, w) in enumerate(zip(sweep.n, sweep.roots)):
        lower, upper = w[w < sweep.k], w[w > sweep.k]
        ax.plot(np.full(lower.size, n), lower, ".", ms=3, color="tab:green", label="$p_{r1}$ (in phase)" if i == 0 else None)
        ax.plot(np.full(upper.size, n), upper, ".", ms=3, color="tab:blue", label="$p_{r2}$ (antiphase)" if i == 0 else None)
    for r, (lo, hi) in enumerate(zip(sweep.continuum_lower, sweep.continuum_upper)):
        ax.axhline(hi, color="k", lw=0.8, ls="--", label="continuum limit (10.50)" if r == 0 else None)
        ax.axhline(lo, color="k", lw=0.6, ls=":")
    ax.axhline(sweep.k, color="tab:red", lw=0.8)
    ax.set_yscale("log")
    ax.set_xlabel("number of identical mechanisms n [-] (totals fixed)")
    ax.set_ylabel("natural frequency p [rad/s]")
    ax.set_ylim(0.5 * min(w.min() for w in sweep.roots), 1.3 * sweep.upper_band.max())
    ax.set_title(title or "Spectrum of a regular drive vs n")
    ax.legend(fontsize=7, loc="upper left")
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    plt.close(fig)
    return Path(path)
