"""Periodic-regime detector working on the event list.

A regime is periodic with p events per period when the last ``cycles`` * p events repeat with
period p: same kind and element, the same time interval to the previous event (relative to the
period, ``rtol``) and the same velocities of all DOFs (relative to the largest velocity, ``vtol``).
Positions are not compared because driven systems drift (x = V t); velocities and intervals
determine the regime of a driven relaxation oscillator.  The smallest such p is reported, with
the period averaged over the confirmed cycles and the number of events of each kind per period.
"""
from __future__ import annotations

import numpy as np

from .result import state_velocities


def detect_period(result, rtol: float = 1e-7, vtol: float = 1e-6, cycles: int = 2, max_events: int = 400):
    ev = result.events[-max_events:]
    n = len(ev)
    if n < 2:
        return None
    t = np.array([e.t for e in ev])
    keys = [(e.kind, e.element) for e in ev]
    names = list(ev[0].state)
    V = state_velocities([e.state for e in ev], names)
    vscale = max(float(np.max(np.abs(V))), 1e-300)
    for p in range(1, n // (cycles + 1) + 1):
        need = cycles * p + 1          # events whose predecessor p back also exists
        if need + p > n + 1:
            break
        period = t[-1] - t[-1 - p]
        if not period > 0:
            continue
        ok = True
        for k in range(n - need, n):
            if k - p < 1:
                ok = False
                break
            if keys[k] != keys[k - p]:
                ok = False
                break
            if abs((t[k] - t[k - 1]) - (t[k - p] - t[k - p - 1])) > rtol * period:
                ok = False
                break
            if np.max(np.abs(V[k] - V[k - p])) > vtol * vscale:
                ok = False
                break
        if ok:
            last = ev[-p:]
            counts: dict[str, int] = {}
            for e in last:
                counts[e.kind] = counts.get(e.kind, 0) + 1
            c = (n - 1) // p
            c = min(c, cycles + 1)
            T = (t[-1] - t[-1 - c * p]) / c
            return {"period": float(T), "events_per_period": p, "per_period": counts,
                    "cycles_confirmed": cycles, "t_detected": float(t[-1])}
    return None


def detect_period_smooth(result, rtol: float = 1e-3, cycles: int = 3):
    """Fallback for regimes without events (smooth laws): upward crossings of the velocity of each
    DOF through its mean over the second half of the run, linearly interpolated; periodic when the
    last ``cycles`` intervals agree to ``rtol`` for every moving DOF.  Accuracy is limited by the
    sampling (linear interpolation between recorded steps)."""
    t = result.t
    if t.size < 8:
        return None
    half = t >= t[0] + 0.5 * (t[-1] - t[0])
    periods = []
    for i in range(result.v.shape[0]):
        v = result.v[i, half]
        tt = t[half]
        if np.ptp(v) <= 1e-12 * max(1.0, np.max(np.abs(v))):
            continue
        y = v - 0.5 * (v.max() + v.min())
        k = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
        if k.size < cycles + 1:
            return None
        tc = tt[k] - y[k] * (tt[k + 1] - tt[k]) / (y[k + 1] - y[k])
        d = np.diff(tc)[-cycles:]
        if np.ptp(d) > rtol * np.mean(d):
            return None
        periods.append(float(np.mean(d)))
    if not periods or np.ptp(periods) > rtol * np.mean(periods):
        return None
    return {"period": float(np.mean(periods)), "events_per_period": 0, "per_period": {},
            "cycles_confirmed": cycles, "method": "velocity crossings (no events)"}
