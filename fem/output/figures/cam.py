"""Matplotlib figures for programme motion and cam laws (files only; nothing is computed here beyond
evaluating a given law on a plotting grid).  Results come from :mod:`discrete.motion`."""
from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .save import save_figure  # noqa: E402


def _save(fig, path) -> Path:
    return save_figure(fig, path)


def plot_cam_law(laws: dict, path, title: str = "cam law and its transfer functions", unit: str = "m") -> Path:
    """Pi, Pi', Pi'', Pi''' against the cam angle (deg) for each {label: PiecewiseLaw} (phase laws:
    the follower's position in ``unit`` and its derivatives with respect to the cam angle in rad);
    knots of the first law dashed."""
    fig, axes = plt.subplots(4, 1, figsize=(7.5, 8), sharex=True)
    names = (f"Pi [{unit}]", f"Pi' [{unit}/rad]", f"Pi'' [{unit}/rad^2]", f"Pi''' [{unit}/rad^3]")
    for label, law in laws.items():
        for m, ax in enumerate(axes):
            phi, val = law.sample(4001, m)          # left limit at the cycle's end
            ax.plot(np.degrees(phi), val, lw=1.2, label=label)
    first = next(iter(laws.values()))
    for ax, nm in zip(axes, names):
        for k in first.knots:
            ax.axvline(math.degrees(k), color="0.8", ls="--", lw=0.7)
        ax.set_ylabel(nm)
        ax.axhline(0, color="0.6", lw=0.6)
    axes[0].legend(fontsize=8)
    axes[0].set_title(title, fontsize=9)
    axes[-1].set_xlabel("cam angle phi [deg]")
    return _save(fig, path)


def plot_follower_cycle(cycles: dict, omega0: float, path, title: str = "follower acceleration over a cycle") -> Path:
    """Programme acceleration x'' and follower acceleration y'' = x'' + q'' (Fig. 6.3 style) against the cam
    angle, for each {label: SteadyState} of an elastic follower; lower panel: dynamic error q."""
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7.5, 6), sharex=True)
    for i, (label, ss) in enumerate(cycles.items()):
        phi = np.degrees(omega0 * (ss.t - ss.t[0]))
        line, = a1.plot(phi, ss.ddy, lw=1.0, label=f"{label}: y''")
        a1.plot(phi, ss.ddx, lw=1.4, ls="--", color=line.get_color(), label=f"{label}: x''")
        a2.plot(phi, ss.q * 1e3, lw=1.0, color=line.get_color(), label=label)
    a1.set_ylabel("acceleration [m/s^2]")
    a2.set_ylabel("dynamic error q [mm]")
    a2.set_xlabel("cam angle phi [deg]")
    a1.legend(fontsize=7, ncol=2)
    a1.set_title(title, fontsize=9)
    return _save(fig, path)


def plot_residual_factor(nu, curves: dict, path, title: str = "equivalent jump of an acceleration ramp (6.8)") -> Path:
    """ae0(nu) curves ({label: values}) against nu = Delta t / T (Fig. 6.4)."""
    fig, ax = plt.subplots(figsize=(7, 4))
    for label, vals in curves.items():
        ax.plot(nu, vals, label=label)
    ax.plot(nu[nu > 0.3], 1 / (math.pi * nu[nu > 0.3]), color="0.6", ls=":", label="1/(pi nu)")
    ax.set_xlabel("ramp duration nu = Delta t / T [-]")
    ax.set_ylabel("equivalent jump ae0 [-]")
    ax.set_ylim(0, 1.1)
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=9)
    return _save(fig, path)


def plot_accumulation(N, curves: dict, path, band=(0.96, 1.04), title: str = "accumulation factor mu (5.53)") -> Path:
    """mu(N) curves ({label: values}) against N = k/omega0 (Fig. 6.6), with the band (0.96, 1.04) shaded."""
    fig, ax = plt.subplots(figsize=(7, 4))
    for label, vals in curves.items():
        ax.plot(N, vals, label=label, lw=1.0)
    if band:
        ax.axhspan(band[0], band[1], color="0.9")
    ax.axhline(1.0, color="0.5", lw=0.6)
    ax.set_xlabel("N = k / omega0 [-]")
    ax.set_ylabel("accumulation factor mu [-]")
    ax.set_yscale("log")
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=9)
    return _save(fig, path)
