"""Matplotlib figures for vibration protection (files only; the curves are computed by the caller with
:mod:`discrete.protection` / :mod:`discrete.linear`)."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .save import save_figure  # noqa: E402


def _save(fig, path) -> Path:
    return save_figure(fig, path)


def plot_amplitude_curves(x, curves: dict, path, *, xlabel: str = "omega [rad/s]", ylabel: str = "amplitude [m]",
                          marks: dict | None = None, log: bool = True, title: str = "") -> Path:
    """Several amplitude-frequency curves ({label: values}) with vertical marks ({label: x}) -- the absorber
    AFCs of Fig. 6.10, transmissibility families, the quasi-constant platform of Fig. 6.15."""
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for label, vals in curves.items():
        v = np.asarray(vals, dtype=float)
        ax.plot(x, np.maximum(v, 1e-300) if log else v, label=label, lw=1.1)
    for label, xv in (marks or {}).items():
        ax.axvline(xv, color="0.6", ls="--", lw=0.8)
        ax.text(xv, ax.get_ylim()[1], label, rotation=90, va="top", ha="right", fontsize=7, color="0.3")
    if log:
        ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=9)
    return _save(fig, path)


def plot_isolation_region(design, m_range, path, title: str = "isolation design region (Fig. 6.8a)") -> Path:
    """The lines of an :class:`discrete.protection.IsolationDesign` in the (m, c) plane, the feasible band
    shaded and the optimum point N marked."""
    m = np.linspace(m_range[0], m_range[1], 200)
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    upper = np.full_like(m, np.inf)
    lower = np.zeros_like(m)
    for name, line in design.lines.items():
        c = line["slope"] * m + line["offset"]
        ax.plot(m, c, label=f"({name}) {'upper' if line['kind'] == 'upper' else 'lower'} bound")
        if line["kind"] == "upper":
            upper = np.minimum(upper, c)
        else:
            lower = np.maximum(lower, c)
    ok = upper > lower
    if np.any(ok):
        ax.fill_between(m[ok], lower[ok], upper[ok], color="0.85", label="feasible")
    if design.m_opt is not None and m_range[0] <= design.m_opt <= m_range[1]:
        c_n = max((l["slope"] * design.m_opt + l["offset"] for l in design.lines.values() if l["kind"] == "lower"),
                  default=0.0)
        ax.plot([design.m_opt], [c_n], "ko")
        ax.annotate("N", (design.m_opt, c_n), textcoords="offset points", xytext=(5, 5))
    top = np.max(upper[np.isfinite(upper)], initial=np.max(lower)) * 1.15
    ax.set_ylim(0, top if top > 0 else None)
    ax.set_xlabel("m [kg]")
    ax.set_ylabel("c [N/m]")
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=9)
    return _save(fig, path)


def plot_unloading(y_before, R_before, U, path, title: str = "dynamic unloading (Fig. 6.13)") -> Path:
    """R*(y), the spring force U(y) and R1 = R* + U(y) over a cycle."""
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    ax.plot(y_before * 1e3, R_before, label="R* (no unloader)")
    ax.plot(y_before * 1e3, U, label="U = u0 + c0 y")
    ax.plot(y_before * 1e3, R_before + U, label="R1 = R* + U")
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_xlabel("y [mm]")
    ax.set_ylabel("force [N]")
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=9)
    return _save(fig, path)
