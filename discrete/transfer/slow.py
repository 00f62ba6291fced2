"""Slowly varying parameters (10.20): a mode whose frequency p(t) changes slowly (cyclic
mechanisms, Pi'(phi0)) keeps its adiabatic invariant, so its amplitude follows
a(t) = a0 sqrt(p(0)/p(t)) and its phase is the integral of p.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import cumulative_trapezoid

from ..errors import ModelError


@dataclass
class AdiabaticResponse:
    t: np.ndarray
    p: np.ndarray            # instantaneous frequency p(t) (rad/s)
    amplitude: np.ndarray    # a0 sqrt(p(0)/p(t))   (non-stationary shape coefficient of (10.20))
    phase: np.ndarray        # int_0^t p(u) du + alpha
    q: np.ndarray            # amplitude cos(phase)


def adiabatic_response(p, t, a0: float = 1.0, alpha: float = 0.0, refine: int = 8) -> AdiabaticResponse:
    """(10.20) for one mode: ``p`` a callable p(t) (or an array on ``t``); the phase integral is
    computed on a grid ``refine`` times finer than ``t`` (trapezoid, error O(dt^2 p''))."""
    t = np.asarray(t, dtype=float)
    if t.ndim != 1 or t.size < 2 or np.any(np.diff(t) <= 0):
        raise ModelError("adiabatic_response", "t", "t", "an increasing 1D array of at least 2 times")
    if callable(p):
        tf = np.linspace(t[0], t[-1], (t.size - 1) * refine + 1)
        pf = np.asarray(p(tf), dtype=float)
        ph = np.interp(t, tf, cumulative_trapezoid(pf, tf, initial=0.0))
        pt = np.asarray(p(t), dtype=float)
    else:
        pt = np.asarray(p, dtype=float)
        ph = cumulative_trapezoid(pt, t, initial=0.0)
    if np.any(pt <= 0):
        raise ModelError("adiabatic_response", "p", float(pt.min()), "a frequency p(t) > 0")
    amp = a0 * np.sqrt(pt[0] / pt)
    return AdiabaticResponse(t=t, p=pt, amplitude=amp, phase=ph + alpha, q=amp * np.cos(ph + alpha))
