"""Figures of named outputs (PNG, matplotlib Agg): time histories (:func:`plot_loads`) and the amplitudes
of a frequency response (:func:`plot_output_amplitudes`), legends with the names of the model file."""
from __future__ import annotations

import pathlib
import textwrap

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


def _same(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    scale = max(float(np.max(np.abs(a), initial=0.0)), float(np.max(np.abs(b), initial=0.0)), 1e-300)
    return a.shape == b.shape and bool(np.all(np.abs(a - b) <= 1e-9 * scale))


def _curves(names, values, ks) -> list[tuple[str, int]]:
    """(legend, index) of the curves of one panel: outputs with identical values drawn once, named
    together ('spring.force = top.reaction'), so that no curve hides another."""
    out: list[list] = []
    for k in ks:
        for entry in out:
            if _same(values[entry[1]], values[k]):
                entry[0] += f" = {names[k]}"
                break
        else:
            out.append([names[k], k])
    return [(a, b) for a, b in out]


def _event_strip(ax, events) -> None:
    """The events as ticks on their own rows (one per kind, named), under the time histories."""
    kinds = [k for k in MARKS if any(e.kind == k for e in events)]
    kinds += sorted({e.kind for e in events} - set(kinds))
    for row, kind in enumerate(kinds):
        tt = np.array([e.t for e in events if e.kind == kind])
        ax.plot(tt, np.full(tt.size, row), "|", ms=9, mew=1.2, color=f"C{row % 10}")
    ax.set_yticks(range(len(kinds)), [k.replace("_", " ") for k in kinds], fontsize=7.5)
    ax.set_ylim(-0.7, len(kinds) - 0.3)
    ax.set_ylabel("events", fontsize=8)
    ax.grid(axis="x", alpha=0.3)


def plot_loads(outputs, path, title: str = "", events=None, max_lines: int = 8, speeds=None) -> pathlib.Path:
    """``path``: the named outputs over time, motions (deflection, twist, slip velocity, ...) above and
    forces (element forces, gear forces, reactions) below, one panel per unit, legends with the names
    of the model file (identical curves named together, drawn once); ``speeds`` [(name, v(t))]: the
    velocities of the bodies and drivers on a panel of their own after the motions; events (stick,
    slip, impacts, ...) as ticks on a strip of their own at the bottom."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = outputs.axis_values
    panels = [("outputs", ks) for ks in _panels(outputs, max_lines)]
    if speeds:
        at = next((i for i, (_, ks) in enumerate(panels) if outputs.channels[ks[0]].is_force), len(panels))
        panels.insert(at, ("speeds", list(range(len(speeds)))))
    evs = [e for e in (events or [])]
    strip = bool(evs) and len(evs) < 20000
    heights = [1.0] * len(panels) + ([0.32 + 0.08 * len({e.kind for e in evs})] if strip else [])
    fig, axes = plt.subplots(len(heights) or 1, 1, figsize=(8.6, 2.5 * len(panels) + (0.9 if strip else 0) + 0.7),
                             sharex=True, squeeze=False, gridspec_kw={"height_ratios": heights or [1.0]})
    names = [c.name for c in outputs.channels]
    for ax, (what, ks) in zip(axes[:, 0], panels):
        if what == "speeds":
            for name, v in (speeds[k] for k in ks):
                ax.plot(t if len(v) == len(t) else np.arange(len(v)), v, lw=1, label=name)
            ax.set_ylabel("speed of the bodies and drivers\nvelocity [m/s | rad/s]", fontsize=8)
        else:
            for legend, k in _curves(names, outputs.values, ks):
                ax.plot(t, outputs.values[k], lw=1, label=legend)
            ax.set_ylabel(_axis_label([outputs.channels[k] for k in ks]), fontsize=8)
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, frameon=False)
        ax.grid(alpha=0.3)
    if strip:
        _event_strip(axes[-1, 0], evs)
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
    axes[0, 0].set_title(textwrap.fill((title + ": " if title else "") + "named outputs (loads, reactions)", 110,
                                       break_on_hyphens=False),
                         fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return pathlib.Path(path)
