"""Matplotlib figures of results (never recomputes anything): mode shapes and FRFs."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def plot_mode_shapes(fe, modal, path: str | Path, n: int | None = None) -> Path:
    """Line plot of the primary field of the first ``n`` modes of an FE model."""
    field = fe.model.fields[0]
    n = modal.omega_rad_s.size if n is None else min(n, modal.omega_rad_s.size)
    fig, ax = plt.subplots(figsize=(7, 4))
    for r in range(n):
        x, v = fe.nodal_values(modal.shapes[:, r], field)
        scale = np.max(np.abs(v)) or 1.0
        label = f"mode {r + 1}: {modal.frequencies_hz[r]:.4g} Hz" + ("" if modal.reliable[r] else " (unreliable)")
        ax.plot(x, v / scale, label=label)
    ax.axhline(0, color="0.7", lw=0.8)
    ax.set_xlabel("x [m]")
    ax.set_ylabel(f"{field} (normalised)")
    ax.set_title(fe.model.title or f"{fe.model.physics} modes", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _frf_arrays(result):
    """(f, amplitude, lag, output names) of a harmonic or a drive forced response (n_freq x n_out)."""
    if hasattr(result, "theta"):          # drive of regular structure: shaft stations and mechanism outputs
        Z = np.concatenate([result.theta, result.y], axis=1)
        n = result.theta.shape[1]
        names = [f"theta{j + 1}" for j in range(n)] + [f"y{j + 1}" for j in range(n)]
        return result.frequencies_hz, np.abs(Z), np.mod(-np.degrees(np.angle(Z)), 360.0), names
    return result.frequencies_hz, result.amplitude, result.phase_lag_deg, list(result.outputs)


def plot_frf(result, path: str | Path, title: str = "") -> Path:
    """Amplitude (log) and phase lag of a harmonic response (at most 12 outputs drawn)."""
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    f, amp, lag, names = _frf_arrays(result)
    for j, name in enumerate(names[:12]):
        a1.semilogy(f, np.maximum(amp[:, j], 1e-300), label=name)
        a2.plot(f, lag[:, j], label=name)
    a1.set_ylabel("amplitude")
    a2.set_ylabel("phase lag [deg]")
    a2.set_xlabel("f [Hz]")
    if f.size > 1 and f.min() > 0 and f.max() / f.min() > 30:
        a2.set_xscale("log")
    a1.set_title(title or f"harmonic response ({result.damping})", fontsize=8)
    a1.legend(fontsize=8)
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
