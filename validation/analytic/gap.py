"""Piecewise-linear oscillator with clearance (textbook §11.1, law (11.1)): exact free-vibration period.

q'' + k0^2 (q - Delta sign q) u(|q| - Delta) = 0 from q = A > Delta at rest: contact half-cycles of
the harmonic motion of amplitude A - Delta (total 2 pi / k0 per period) plus two free flights across
the gap at speed k0 (A - Delta).  For an asymmetric clearance [lower, upper] started at q = A > upper
the contact amplitude is a = A - upper on both sides (energy conservation).
"""
from __future__ import annotations

import math


def period(k0: float, A: float, lower: float, upper: float) -> float:
    """Exact period 2 pi/k0 + 2 (upper - lower) / (k0 (A - upper))."""
    a = A - upper
    return 2 * math.pi / k0 + 2 * (upper - lower) / (k0 * a)


def frequency_ratio(delta_over_A: float) -> float:
    """Symmetric gap: k/k0 = 1 / (1 + 2 Delta / (pi (A - Delta)))."""
    d = delta_over_A
    return 1.0 / (1.0 + 2 * d / (math.pi * (1 - d)))
