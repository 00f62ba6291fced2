"""Matplotlib figures of results (never recomputes anything): mode shapes and FRFs."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .save import save_figure  # noqa: E402

from .quantities import FIELD, common_label, output_quantity  # noqa: E402


def _wrap(text: str, width: int = 95) -> str:
    import textwrap

    return "\n".join(textwrap.wrap(text, width)) if text else text


def _save(fig, path) -> Path:
    return save_figure(fig, path, tight=False)


def plot_mode_shapes(fe, modal, path: str | Path, n: int | None = None, title: str | None = None) -> Path:
    """The first ``n`` modes of an FE model, one panel each (the primary field normalised to its
    largest value, the mode's frequency in the panel's title), above a side view of the shaft with
    its segments, supports and point attachments (:mod:`fem.output.figures.shaft`); faint lines
    at the supports and attachments run through every panel."""
    from .shaft import draw_shaft, legend_handles

    model = fe.model
    field = model.fields[0]
    quantity, _ = FIELD.get(field, (field, "-"))
    n = modal.omega_rad_s.size if n is None else min(n, modal.omega_rad_s.size)
    n = max(n, 1)
    handles = legend_handles(model)
    fig, axes = plt.subplots(n + 1, 1, figsize=(8.0, 1.25 * n + 2.1 + 0.12 * len(handles)), sharex=True,
                             gridspec_kw={"height_ratios": [1.0] * n + [0.55]})
    marks = [s.x for s in model.supports] + [p.x for p in model.points if p.mass > 0 or p.inertia > 0]
    short = quantity.split()[-1]
    for r, ax in enumerate(axes[:n]):
        x, v = fe.nodal_values(modal.shapes[:, r], field)
        scale = v[np.argmax(np.abs(v))] if v.size and np.max(np.abs(v)) > 0 else 1.0
        ax.plot(x, v / scale, color="tab:blue", lw=1.6)
        ax.axhline(0, color="0.6", lw=0.7)
        for xm in marks:
            ax.axvline(xm, color="0.75", lw=0.7, ls=":")
        ax.set_ylim(-1.25, 1.25)
        ax.set_yticks([-1, 0, 1])
        ax.set_ylabel(f"{short} [-]", fontsize=8)
        f = modal.frequencies_hz[r]
        note = "" if modal.reliable[r] else " (not reliable in double precision)"
        rigid = bool(getattr(modal, "rigid", np.zeros(n, bool))[r])
        ax.set_title(f"mode {r + 1}: " + ("rigid-body motion" if rigid else f"{f:.4g} Hz") + note,
                     fontsize=8.5, loc="left", pad=2)
    strip = axes[n]
    draw_shaft(strip, model)
    strip.set_xlabel("x along the shaft [m]")
    head = title if title is not None else (model.title or f"{model.physics} modes")
    fig.suptitle(_wrap(head, 95) + f"\n{model.physics} modes: {quantity} normalised to its largest value",
                 fontsize=9.5)
    rows = (len(handles) + 1) // 2
    bottom = (0.22 * rows + 0.08) / fig.get_figheight() if handles else 0.0
    if handles:
        fig.legend(handles=handles, loc="lower center", bbox_to_anchor=(0.5, 0.01), ncol=min(len(handles), 2),
                   fontsize=7.5, frameon=False)
    fig.tight_layout(rect=(0, bottom, 1, 1))
    return _save(fig, path)


def _frf_arrays(result):
    """(f, amplitude, lag, output names) of a harmonic or a drive forced response (n_freq x n_out)."""
    if hasattr(result, "theta"):          # drive of regular structure: shaft stations and mechanism outputs
        Z = np.concatenate([result.theta, result.y], axis=1)
        n = result.theta.shape[1]
        names = [f"theta{j + 1}" for j in range(n)] + [f"y{j + 1}" for j in range(n)]
        return result.frequencies_hz, Z, names, "drive"
    return result.frequencies_hz, result.response, list(result.outputs), None


def _with_gaps(x, lag_deg):
    x = np.asarray(x, float)
    lag = np.asarray(lag_deg, float)
    if lag.size > 1:
        idx = np.flatnonzero(np.abs(np.diff(lag)) > 180.0) + 1
        return np.insert(x, idx, np.nan), np.insert(lag, idx, np.nan)
    return x, lag


def plot_frf(result, path: str | Path, title: str = "", max_outputs: int = 12) -> Path:
    """Amplitude (log, one panel per unit: shaft angles apart from displacements) and phase lag
    (unwrapped along a sweep; for a few frequencies wrapped to [0, 360) and never joined across a
    wrap) of a harmonic response against frequency [Hz];
    the outputs named as in the model file (FE: quantity and position); markers on every
    computed frequency when there are few."""
    f, Z, names, kind = _frf_arrays(result)
    amp = np.abs(Z)
    lag = np.mod(-np.degrees(np.angle(Z)), 360.0)
    shown = list(range(min(len(names), max_outputs)))
    info = [output_quantity(names[j], kind) for j in shown]
    units = []
    for _, _, u in info:
        if u not in units:
            units.append(u)
    fig, axes = plt.subplots(len(units) + 1, 1, figsize=(8.6, 2.6 * len(units) + 3.0), sharex=True, squeeze=False)
    axes = axes[:, 0]
    colours = plt.get_cmap("tab20").colors if len(shown) > 10 else plt.get_cmap("tab10").colors
    dense = f.size > 40
    span = (0.0, 180.0)
    style = "o" if f.size <= 15 else ("o-" if f.size <= 40 else "-")      # few frequencies: the points only
    for k, j in enumerate(shown):
        legend, q, u = info[k]
        a = axes[units.index(u)]
        c = colours[k % len(colours)]
        a.semilogy(f, np.where(amp[:, j] > 0, amp[:, j], np.nan), style, ms=3.5, lw=1.3, color=c, label=legend)
        if dense:                   # a sweep: the lag unwrapped along it
            un = np.rad2deg(np.unwrap(np.deg2rad(lag[:, j])))
            span = (min(span[0], float(np.nanmin(un))), max(span[1], float(np.nanmax(un))))
            axes[-1].plot(f, un, style, lw=1.3, color=c)
        else:                       # a few frequencies: wrapped, never joined across a wrap
            xs, ls = _with_gaps(f, lag[:, j])
            axes[-1].plot(xs, ls, style, ms=3.5, lw=1.3, color=c)
    for a, u in zip(axes[:-1], units):
        qs = [(q, uu) for (_, q, uu) in info if uu == u]
        a.set_ylabel(common_label(qs, "amplitude of "), fontsize=8.5)
        a.grid(alpha=0.3, which="both")
        a.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, frameon=False)
    axes[-1].set_ylabel("phase lag [deg]")
    lo, hi = (90 * np.floor(span[0] / 90 + 1e-9), 90 * np.ceil(span[1] / 90 - 1e-9)) if dense else (0, 360)
    axes[-1].set_yticks(np.arange(lo, hi + 1, 90 if hi - lo <= 720 else 180))
    axes[-1].set_ylim(lo - 0.03 * (hi - lo), hi + 0.03 * (hi - lo))
    axes[-1].grid(alpha=0.3)
    axes[-1].set_xlabel("frequency f [Hz]")
    if f.size > 1 and f.min() > 0 and f.max() / f.min() > 30:
        axes[-1].set_xscale("log")
    extra = f" ({len(names) - len(shown)} more outputs in the JSON and CSV)" if len(names) > len(shown) else ""
    damping = getattr(result, "damping", None)
    sub = "harmonic response" + (f", damping: {damping}" if damping else "") + extra
    axes[0].set_title(_wrap(title, 100) + "\n" + sub if title else sub, fontsize=9)
    fig.tight_layout()
    return _save(fig, path)
