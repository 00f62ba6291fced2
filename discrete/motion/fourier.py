"""Fourier series of one period of a periodic function (textbook §5.8, (5.41)-(5.43)).

    F(t) = F_0 + sum_{j=1}^{H} (F_jc cos j w t + F_js sin j w t),   w = 2 pi / tau,

with the coefficients (5.42) computed by the FFT of N equally spaced samples of one period
(``numpy.fft.rfft``).  A :class:`~discrete.motion.piecewise.PiecewiseLaw` is sampled with the mean
of its left and right limits at jumps (the value the series converges to).

Quality figures carried by the result:

* ``max_error``, ``rms_error``: the truncated series against the samples (a jump keeps the Gibbs
  overshoot, about 9 % of the jump, in ``max_error``; ``rms_error`` then decays like H^-1/2);
* ``aliasing_error``: max over j <= H of the change of the coefficients when only every second
  sample is used (the DFT's aliasing estimate; for a jump it is about (pi j / N)^2/3 of F_j).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ModelError
from .piecewise import PiecewiseLaw


BLOCK = 1 << 21          # entries of one block of the phase matrix (instants x harmonics) of an evaluation


@dataclass
class FourierSeries:
    period: float
    mean: float
    cos: np.ndarray          # F_jc, j = 1..H
    sin: np.ndarray          # F_js, j = 1..H
    samples: int
    max_error: float
    rms_error: float
    aliasing_error: float
    scale: float             # max |F| over the samples

    @property
    def omega(self) -> float:
        """Fundamental angular frequency 2 pi / tau [rad/s]."""
        return 2 * math.pi / self.period

    @property
    def harmonics(self) -> int:
        return int(self.cos.size)

    @property
    def complex_amplitudes(self) -> np.ndarray:
        """c_j with F = Re(sum_{j>=0} c_j e^{i j w t}): c_0 = F_0, c_j = F_jc - i F_js."""
        return np.concatenate([[self.mean], self.cos - 1j * self.sin])

    @property
    def amplitude_phase(self) -> tuple[np.ndarray, np.ndarray]:
        """(F_j, alpha_j) of (5.43): F = F_0 + sum F_j sin(j w t + alpha_j)."""
        return np.hypot(self.cos, self.sin), np.arctan2(self.cos, self.sin)

    def __call__(self, t, derivative: int = 0):
        """The series (or its ``derivative``) at the instants ``t``, summed in blocks of instants so that the
        matrix of phases stays below :data:`BLOCK` entries whatever the number of harmonics."""
        t = np.asarray(t, dtype=float)
        j = np.arange(1, self.harmonics + 1)
        fac = (j * self.omega) ** derivative
        shift = derivative * math.pi / 2
        flat = t.reshape(-1)
        val = np.empty(flat.size)
        rows = max(1, BLOCK // max(1, j.size))
        for a in range(0, flat.size, rows):
            ph = np.multiply.outer(flat[a:a + rows], j * self.omega)
            val[a:a + rows] = (np.cos(ph + shift) * (fac * self.cos) + np.sin(ph + shift) * (fac * self.sin)).sum(axis=-1)
        val = val.reshape(t.shape)
        return val + (self.mean if derivative == 0 else 0.0)

    def to_dict(self) -> dict:
        return {"period": self.period, "omega_rad_s": self.omega, "mean": self.mean, "cos": self.cos.tolist(),
                "sin": self.sin.tolist(), "samples": self.samples, "max_error": self.max_error,
                "rms_error": self.rms_error, "aliasing_error": self.aliasing_error, "scale": self.scale}


def _coefficients(values: np.ndarray, H: int) -> tuple[float, np.ndarray, np.ndarray]:
    N = values.size
    c = np.fft.rfft(values) / N
    mean = float(c[0].real)
    cj = c[1:H + 1]
    return mean, 2 * cj.real, -2 * cj.imag


def fourier_series(f, period: float, harmonics: int, *, samples: int | None = None, t0: float = 0.0) -> FourierSeries:
    """Coefficients (5.42) of one period [t0, t0 + period) of ``f`` (a vectorised callable or a
    periodic :class:`PiecewiseLaw`), truncated at ``harmonics`` terms.

    ``samples`` (even, >= 4 harmonics + 2; default max(4096, 32 harmonics) rounded up to a power of 2).
    """
    if isinstance(harmonics, bool) or not isinstance(harmonics, (int, np.integer)) or harmonics < 1:
        raise ModelError("fourier series", "harmonics", harmonics, "an integer >= 1")
    if not (isinstance(period, (int, float)) and math.isfinite(period) and period > 0):
        raise ModelError("fourier series", "period", period, "a finite number > 0")
    H = int(harmonics)
    N = samples if samples is not None else 1 << max(12, math.ceil(math.log2(32 * H)))
    if isinstance(N, bool) or not isinstance(N, (int, np.integer)) or N < 4 * H + 2 or N % 2:
        raise ModelError("fourier series", "samples", samples, f"an even integer >= 4 harmonics + 2 = {4 * H + 2}")
    t = t0 + period * np.arange(N) / N
    if isinstance(f, PiecewiseLaw):
        if not f.periodic:
            raise ModelError("fourier series", "law", f.name or "piecewise law", "a periodic law (periodic = True)")
        if abs(f.span - period) > 1e-9 * period:
            raise ModelError("fourier series", "period", period, f"the law's period {f.span:.12g}")
        values = np.asarray(f.midpoint_value(t), dtype=float)
    elif callable(f):
        values = np.asarray(f(t), dtype=float)
    else:
        raise ModelError("fourier series", "f", type(f).__name__, "a callable f(t) or a periodic PiecewiseLaw")
    if values.shape != t.shape or not np.all(np.isfinite(values)):
        raise ModelError("fourier series", "f", "non-finite or mis-shaped values", f"{N} finite values f(t)")
    mean, a, b = _coefficients(values, H)
    mean2, a2, b2 = _coefficients(values[::2], min(H, N // 4 - 1))
    h2 = a2.size
    alias = float(max(abs(mean - mean2), np.max(np.abs(a[:h2] - a2), initial=0.0), np.max(np.abs(b[:h2] - b2), initial=0.0)))
    series = FourierSeries(period=float(period), mean=mean, cos=a, sin=b, samples=int(N), max_error=0.0,
                           rms_error=0.0, aliasing_error=alias, scale=float(np.max(np.abs(values))))
    # truncation error on the samples: reconstruct the truncated series by the inverse FFT
    spec = np.zeros(N // 2 + 1, dtype=complex)
    spec[0] = mean * N
    spec[1:H + 1] = 0.5 * N * (a - 1j * b)
    err = np.fft.irfft(spec, n=N) - values
    series.max_error = float(np.max(np.abs(err)))
    series.rms_error = float(np.sqrt(np.mean(err**2)))
    return series
