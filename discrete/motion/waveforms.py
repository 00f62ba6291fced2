"""Unit periodic load shapes for Fourier superposition (textbook §5.8, (5.41)-(5.42)): w(s) on one period,
s = t/T in [0, 1).

``square`` (+1 for s < duty, -1 after), ``sawtooth`` (2 s - 1), ``triangle`` (1 - 4 |s - 1/2|) and
``table`` (piecewise linear through (s_k, v_k), s from 0 to 1, v_0 = v_end).  All are piecewise linear, so
their Fourier coefficients are exact closed forms (:meth:`Waveform.series`) -- no sampling, no aliasing,
and a jump anywhere in the period (not only on a sample) is represented exactly.  At a jump the value is
the midpoint of the two sides, which is what the series converges to."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..checks import bounded, choice, vector
from ..errors import ModelError
from .fourier import FourierSeries

KINDS = ("square", "sawtooth", "triangle", "table")


@dataclass(frozen=True)
class Waveform:
    """A periodic piecewise-linear shape: segment k runs from s[k] to s[k+1] linearly from left[k]
    (its value just after s[k]) to right[k] (just before s[k+1]); s[0] = 0, s[-1] = 1."""

    s: np.ndarray
    left: np.ndarray
    right: np.ndarray
    name: str = ""

    def __call__(self, s):
        x = np.mod(np.asarray(s, float), 1.0)
        k = np.clip(np.searchsorted(self.s, x, side="right") - 1, 0, self.left.size - 1)
        h = self.s[k + 1] - self.s[k]
        val = self.left[k] + (self.right[k] - self.left[k]) * (x - self.s[k]) / h
        # at a knot: the midpoint of the two one-sided values
        prev = np.where(k > 0, self.right[k - 1], self.right[-1])
        at = np.isclose(x, self.s[k], rtol=0, atol=1e-13)
        return np.where(at, 0.5 * (self.left[k] + prev), val)

    def coefficients(self, harmonics: int) -> tuple[float, np.ndarray]:
        """(mean, c_j) with w(s) = mean + Re sum_{j=1}^{H} c_j e^{2 pi i j s}: exact integrals over the
        linear segments, c_j = 2 int_0^1 w e^{-2 pi i j s} ds."""
        j = np.arange(1, int(harmonics) + 1)
        om = -2j * math.pi * j                       # d/ds of the exponent
        c = np.zeros(j.size, dtype=complex)
        mean = 0.0
        for s0, s1, a, b in zip(self.s[:-1], self.s[1:], self.left, self.right):
            h = s1 - s0
            mean += 0.5 * (a + b) * h
            E0, E1 = np.exp(om * s0), np.exp(om * s1)
            beta = (b - a) / h
            c += a * (E1 - E0) / om + beta * (h * E1 / om - (E1 - E0) / om ** 2)
        return float(mean), 2.0 * c

    def series(self, period: float, harmonics: int, amplitude: float = 1.0, shift: float = 0.0,
               check_points: int | None = None) -> FourierSeries:
        """The exact series of amplitude * w(t/period + shift) truncated at ``harmonics``; its truncation error
        (max and rms over a fine grid plus the knots) is reported in the series, as the sampled series do."""
        H = int(harmonics)
        mean, c = self.coefficients(H)
        c = amplitude * c * np.exp(2j * math.pi * np.arange(1, H + 1) * shift)
        fs = FourierSeries(period=float(period), mean=amplitude * mean, cos=c.real.copy(), sin=-c.imag.copy(),
                           samples=0, max_error=0.0, rms_error=0.0, aliasing_error=0.0,
                           scale=abs(amplitude) * float(max(np.max(np.abs(self.left)), np.max(np.abs(self.right)))))
        N = check_points or max(4096, 16 * H)
        grid = np.arange(N) / N
        knots = np.mod(self.s[:-1] - shift, 1.0)
        if N > 2 * H:        # the series on the equally spaced instants k/N: an inverse FFT, O(N log N)
            spec = np.zeros(N // 2 + 1, dtype=complex)
            spec[0] = fs.mean * N
            spec[1:H + 1] = 0.5 * N * (fs.cos - 1j * fs.sin)
            on_grid = np.fft.irfft(spec, n=N)
        else:
            on_grid = fs(grid * period)
        err = np.concatenate([on_grid - amplitude * self(grid + shift), fs(knots * period) - amplitude * self(knots + shift)])
        return FourierSeries(period=fs.period, mean=fs.mean, cos=fs.cos, sin=fs.sin, samples=0,
                             max_error=float(np.max(np.abs(err))), rms_error=float(np.sqrt(np.mean(err ** 2))),
                             aliasing_error=0.0, scale=fs.scale)


def unit_waveform(kind: str, *, duty: float | None = None, s_points=None, values=None) -> Waveform:
    """The unit shape of ``kind`` (see the module docstring)."""
    where = "waveform"
    choice(where, "kind", kind, KINDS)
    if duty is not None and kind != "square":
        raise ModelError(where, "duty", duty, "only with kind = 'square'")
    if kind == "square":
        d = 0.5 if duty is None else bounded(where, "duty", duty, (">", 0.0), ("<", 1.0))
        return Waveform(np.array([0.0, d, 1.0]), np.array([1.0, -1.0]), np.array([1.0, -1.0]), "square")
    if kind == "sawtooth":
        return Waveform(np.array([0.0, 1.0]), np.array([-1.0]), np.array([1.0]), "sawtooth")
    if kind == "triangle":
        return Waveform(np.array([0.0, 0.5, 1.0]), np.array([-1.0, 1.0]), np.array([1.0, -1.0]), "triangle")
    sp = vector(where, "t", s_points)
    v = vector(where, "value", values, sp.size)
    if sp.size < 2 or sp[0] != 0.0 or sp[-1] != 1.0 or np.any(np.diff(sp) <= 0):
        raise ModelError(where, "t", sp.tolist() if sp.size <= 8 else f"{sp.size} points",
                         "at least 2 increasing fractions of the period from 0 to 1")
    if abs(v[0] - v[-1]) > 1e-12 * max(1.0, float(np.max(np.abs(v)))):
        raise ModelError(where, "value", [float(v[0]), float(v[-1])], "value[0] == value[-1] (one period of a "
                         "periodic load)")
    return Waveform(sp, v[:-1].copy(), v[1:].copy(), "table")
