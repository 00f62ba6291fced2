"""Figures of named outputs (PNG, matplotlib Agg): time histories (:func:`plot_loads`) and the amplitudes
of a frequency response (:func:`plot_output_amplitudes`), legends with the names of the model file."""
from __future__ import annotations

import pathlib

import numpy as np

MARKS = {"stick": "v", "slip": "^", "reversal": "x", "impact": "o", "contact_open": "s", "contact_close": "D"}


def _panels(outputs, max_lines: int, max_panels: int = 6) -> list[list[int]]:
    """One panel per unit (motions first, forces last; the section loads of a shaft apart from element
    forces and reactions) with at most ``max_lines`` outputs each: those of the largest peak, in the
    outputs' order."""
    groups: dict = {}
    for k, c in sorted(enumerate(outputs.channels), key=lambda kc: (kc[1].is_force, kc[1].source == "section")):
        groups.setdefault((c.unit, c.source == "section"), []).append(k)
    out = []
    for ks in list(groups.values())[:max_panels]:
        if len(ks) > max_lines:
            peak = np.array([np.max(np.abs(outputs.values[k])) if np.size(outputs.values[k]) else 0.0 for k in ks])
            ks = sorted(np.asarray(ks)[np.argsort(-peak, kind="stable")[:max_lines]].tolist())
        out.append(ks)
    return out


def _axis_label(channels) -> str:
    """'quantity [unit]' of the channels on one axis (their common words, else 'values')."""
    qs = sorted({c.quantity for c in channels})
    us = sorted({c.unit for c in channels})
    return f"{' / '.join(qs)} [{', '.join(us)}]"


def plot_loads(outputs, path, title: str = "", events=None, max_lines: int = 8) -> pathlib.Path:
    """``path``: the named outputs over time, motions (deflection, twist, slip velocity, ...) on the upper
    axis and forces (element forces, gear forces, reactions) on the lower one, events marked; legends with
    the names of the model file."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = outputs.axis_values
    panels = _panels(outputs, max_lines)
    fig, axes = plt.subplots(len(panels) or 1, 1, figsize=(8, 2.8 * max(len(panels), 1) + 0.6), sharex=True,
                             squeeze=False)
    for ax, ks in zip(axes[:, 0], panels):
        for k in ks:
            ax.plot(t, outputs.values[k], lw=1, label=outputs.channels[k].name)
        ax.set_ylabel(_axis_label([outputs.channels[k] for k in ks]), fontsize=8)
        ax.legend(fontsize=7, loc="best")
    if events is not None:
        ax = axes[-1, 0]
        for kind, mk in MARKS.items():
            tt = np.array([e.t for e in events if e.kind == kind])
            if tt.size and tt.size < 2000:
                ax.plot(tt, 0 * tt, mk, ms=4, ls="none", label=kind)
        ax.legend(fontsize=7, loc="best", ncol=3)
    axes[-1, 0].set_xlabel("time t [s]")
    axes[0, 0].set_title(title or "element loads", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return pathlib.Path(path)




def plot_output_amplitudes(outputs, path, title: str = "", max_lines: int = 8) -> pathlib.Path:
    """``path``: the amplitude of the named outputs of a frequency response (or an unbalance response over
    its speeds) against the frequency, one panel per unit, logarithmic."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    w = np.asarray(outputs.axis_values, dtype=float)
    panels = _panels(outputs, max_lines)
    fig, axes = plt.subplots(len(panels) or 1, 1, figsize=(8, 2.8 * max(len(panels), 1) + 0.6), sharex=True,
                             squeeze=False)
    for ax, ks in zip(axes[:, 0], panels):
        for k in ks:
            amp = np.abs(outputs.values[k])
            ax.semilogy(w, np.where(amp > 0, amp, np.nan), lw=1, label=outputs.channels[k].name)
        ax.set_ylabel("amplitude of " + _axis_label([outputs.channels[k] for k in ks]), fontsize=8)
        ax.legend(fontsize=7, loc="best")
    axes[-1, 0].set_xlabel("angular frequency omega [rad/s]")
    axes[0, 0].set_title((title + ": " if title else "") + "named outputs (loads, reactions)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return pathlib.Path(path)
