"""More matplotlib figures from result objects (files only, no display): convergence,
Campbell-style frequency-vs-parameter, amplitude-frequency curves, phase portraits and
time histories.  Nothing here computes a result; each function takes one and draws it.

Result objects are used through their documented attributes: a :class:`ModalResult`
(``frequencies_hz``), a :class:`discrete.linear.harmonic.HarmonicResult` (``frequencies_hz``,
``amplitude``, ``outputs``), a nonsmooth ``SimulationResult`` (``t``, ``x``, ``v``,
``names``, ``events``, ``period``); plain arrays work where a function says so.
"""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def _save(fig, path) -> Path:
    from ..mesh import ensure_directory

    path = Path(path)
    ensure_directory(path.parent)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_convergence(n_elements, errors: dict, path, orders=(2, 4), title: str = "mesh convergence") -> Path:
    """Relative error against element count (log-log) for each series in ``errors``
    ({label: errors}); dashed lines show the slopes ``orders`` for reference."""
    n = np.asarray(n_elements, float)
    fig, ax = plt.subplots(figsize=(6, 4.5))
    floor = np.inf
    for label, e in errors.items():
        e = np.abs(np.asarray(e, float))
        ax.loglog(n, np.maximum(e, 1e-17), "o-", label=label)
        floor = min(floor, np.min(e[e > 0])) if np.any(e > 0) else floor
    top = max(np.max(np.abs(np.asarray(e, float))) for e in errors.values())
    for p in orders:
        ax.loglog(n, top * (n / n[0]) ** (-p), "k--", lw=0.8, alpha=0.6)
        ax.text(n[-1], top * (n[-1] / n[0]) ** (-p), f" O(h^{p})", fontsize=8, va="center")
    ax.set_xticks(n, [f"{v:g}" for v in n])
    ax.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
    ax.set_xlabel("number of elements [-]")
    ax.set_ylabel("relative error [-]")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    return _save(fig, path)


def plot_campbell(parameter, results, path, xlabel: str = "speed [rpm]", orders=(1.0, 2.0),
                  per_minute: bool = True, kinds=None, title: str = "Campbell diagram") -> Path:
    """Frequencies of a parameter study: ``results`` is a list of ModalResult (one per
    parameter value) or an array (n_param, n_modes) in Hz.  With ``per_minute`` the
    excitation lines f = k * parameter / 60 (orders k) are drawn; crossings are marked."""
    p = np.asarray(parameter, float)
    F = np.array([r.frequencies_hz for r in results]) if not isinstance(results, np.ndarray) else np.asarray(results)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for m in range(F.shape[1]):
        lab = f"mode {m + 1}" + (f" ({kinds[m]})" if kinds is not None else "")
        ax.plot(p, F[:, m], "-", lw=1.5, label=lab)
    if per_minute:
        for k in orders:
            line = k * p / 60.0
            ax.plot(p, line, "k--", lw=0.8)
            ax.text(p[-1], line[-1], f" {k:g}x", fontsize=8)
            for m in range(F.shape[1]):
                d = F[:, m] - line
                for i in np.flatnonzero(np.sign(d[:-1]) != np.sign(d[1:])):
                    t = d[i] / (d[i] - d[i + 1])
                    ax.plot(p[i] + t * (p[i + 1] - p[i]), F[i, m] + t * (F[i + 1, m] - F[i, m]), "ro", ms=5)
    ax.set_ylim(0, F.max() * 1.1)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("frequency f [Hz]")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return _save(fig, path)


def plot_amplitude_curve(result, path, log: bool = False, stable=None, title: str = "amplitude-frequency curve",
                         ylabel: str = "amplitude [m | rad]") -> Path:
    """Amplitude-frequency curves of a harmonic result (each output), or of any object with
    ``frequencies_hz`` and ``amplitude`` (n_freq[, n_out]); ``stable`` (bool per point)
    draws unstable points dashed (continuation results)."""
    f = np.asarray(result.frequencies_hz, float)
    A = np.asarray(result.amplitude, float)
    A = A[:, None] if A.ndim == 1 else A
    names = getattr(result, "outputs", None) or [f"output {j + 1}" for j in range(A.shape[1])]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for j in range(A.shape[1]):
        if stable is None:
            ax.plot(f, A[:, j], "-", label=names[j])
        else:
            st = np.asarray(stable, bool)
            ax.plot(np.where(st, f, np.nan), np.where(st, A[:, j], np.nan), "-", label=f"{names[j]} stable")
            ax.plot(np.where(~st, f, np.nan), np.where(~st, A[:, j], np.nan), "--", label=f"{names[j]} unstable")
    if log:
        ax.set_yscale("log")
    ax.set_xlabel("frequency f [Hz]")
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return _save(fig, path)


def _series(result, name):
    if hasattr(result, "series"):
        return result.series(name)
    i = list(result.names).index(name)
    return np.asarray(result.x)[i], np.asarray(result.v)[i]


def plot_phase_portrait(result, path, names=None, last_fraction: float = 1.0, title: str = "phase portrait") -> Path:
    """v against x for the named DOFs of a simulation result (default: all, up to 4);
    ``last_fraction`` keeps only the end of the run (the steady regime); event instants
    are marked."""
    names = list(names or list(result.names)[:4])
    t = np.asarray(result.t)
    keep = t >= t[0] + (1 - last_fraction) * (t[-1] - t[0])
    fig, ax = plt.subplots(figsize=(6, 5))
    for n in names:
        x, v = _series(result, n)
        ax.plot(np.asarray(x)[keep], np.asarray(v)[keep], lw=1, label=n)
    ev = [e for e in getattr(result, "events", []) if e.t >= t[keep][0]]
    for n in names:
        pts = [(e.state[n]["x"], e.state[n]["v"]) for e in ev if n in e.state]
        if pts:
            ax.plot(*np.array(pts).T, "k.", ms=3)
    ax.set_xlabel("displacement or angle x [m | rad]")
    ax.set_ylabel("velocity v [m/s | rad/s]")
    ax.set_title(title + (f"  (period {result.period:.4g})" if getattr(result, "period", None) else ""), fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return _save(fig, path)


def plot_time_series(result, path, names=None, velocity: bool = True, title: str = "time history") -> Path:
    """x(t) (and v(t)) of the named DOFs of a simulation result, events as ticks."""
    names = list(names or list(result.names)[:4])
    t = np.asarray(result.t)
    fig, axes = plt.subplots(2 if velocity else 1, 1, figsize=(8, 5 if velocity else 3), sharex=True, squeeze=False)
    for n in names:
        x, v = _series(result, n)
        axes[0, 0].plot(t, x, lw=1, label=n)
        if velocity:
            axes[1, 0].plot(t, v, lw=1, label=n)
    for e in getattr(result, "events", [])[:2000]:
        axes[-1, 0].axvline(e.t, color="0.8", lw=0.4, zorder=0)
    axes[0, 0].set_ylabel("x [m | rad]")
    if velocity:
        axes[1, 0].set_ylabel("v [m/s | rad/s]")
    axes[-1, 0].set_xlabel("t [s]")
    axes[0, 0].set_title(title, fontsize=9)
    axes[0, 0].legend(fontsize=8)
    return _save(fig, path)


def plot_solid_vs_beam(solid_modal, beam: dict, path, title: str = "3D solid vs 1D models") -> Path:
    """Frequencies of a classified 3D result (``frequencies_hz``, ``kinds``) next to 1D
    model frequencies ``beam`` ({label: (kind, frequencies)}), one column per kind."""
    fig, ax = plt.subplots(figsize=(7, 4.5))
    kinds = ["bending", "torsion", "axial"]
    for i, k in enumerate(kinds):
        f = np.asarray(solid_modal.frequencies_hz)[np.array(solid_modal.kinds) == k]
        ax.plot(np.full(f.size, i), f, "o", ms=9, mfc="none", mec="k", label="3D solid" if i == 0 else None)
    markers = iter("sD^v<>")
    for label, (k, f) in beam.items():
        ax.plot(np.full(len(f), kinds.index(k)) + 0.12, f, next(markers), ms=6, label=label)
    ax.set_xticks(range(3), kinds)
    ax.set_xlabel("mode family")
    ax.set_yscale("log")
    ax.set_ylabel("frequency f [Hz]")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    return _save(fig, path)
