"""Response measures of periodic orbits, computed exactly where the orbit is known in closed form.

* HB orbits are trigonometric series in theta = (omega / nu) t.  ``h1`` (the amplitude at the forcing
  frequency omega) of a body's coordinate is the modulus of its harmonic nu, read off the coefficients
  (no quadrature; on a 1/nu subharmonic the omega/nu component does not enter it).  Of an element force
  it is the periodic (rectangle) quadrature of the sampled force over a whole period -- exact for
  trigonometric polynomials of degree < samples, O(samples^-2) at a kink of |F|.
* The extremes (``amplitude`` = half peak-to-peak, ``max``, ``min``, ``peak``) of a body's coordinate:
  the extreme samples of a grid, then Newton on y'(theta) = 0 with y''(theta) from the series (quadratic
  convergence to rounding); of an element force: golden-section search on the exactly evaluated
  force around the extreme sample (the law may have kinks; no derivative is needed).
* Time series (shooting: the event-driven integrator's dense output) are non-uniform: ``h1`` is the
  trapezoidal rule over the whole period including its closing point, and an extreme sample is refined
  by the vertex of the parabola through it and its two neighbours.
"""
from __future__ import annotations

import numpy as np

GOLDEN = 0.5 * (np.sqrt(5.0) - 1.0)


def series_values(C, theta, deriv: int = 0):
    """Values (or theta-derivatives 1, 2) of real series C (k, 2H+1) at phases theta (k,) or (k, p)."""
    C = np.atleast_2d(np.asarray(C, float))
    H = (C.shape[-1] - 1) // 2
    th = np.asarray(theta, float)
    squeeze = th.ndim == 1
    th = th.reshape(C.shape[0], -1)
    k = np.arange(1, H + 1)
    kt = th[..., None] * k
    c, s = np.cos(kt), np.sin(kt)
    a, b = C[:, None, 1::2], C[:, None, 2::2]
    if deriv == 0:
        v = C[:, :1] + np.sum(c * a + s * b, axis=-1)
    elif deriv == 1:
        v = np.sum(k * (c * b - s * a), axis=-1)
    else:
        v = -np.sum(k * k * (c * a + s * b), axis=-1)
    return v[:, 0] if squeeze else v


def series_extremes(C, points: int | None = None, iterations: int = 6, compiled: bool = False):
    """(max, min) of each real series C (k, 2H+1): grid extremes refined by Newton on y' = 0
    (``compiled``: by hb_kernel.series_extremes, the same steps -- the HB curve asks for it when its model
    is evaluated by the kernel)."""
    C = np.atleast_2d(np.asarray(C, float))
    H = (C.shape[-1] - 1) // 2
    P = points or max(64, 16 * H)
    if compiled:
        from .hb_kernel import series_extremes as kernel

        return kernel(np.ascontiguousarray(C), int(P), int(iterations))
    th = 2 * np.pi * np.arange(P) / P
    kt = np.multiply.outer(th, np.arange(1, H + 1))
    Y = C[:, :1] + C[:, 1::2] @ np.cos(kt).T + C[:, 2::2] @ np.sin(kt).T      # (k, P)
    out = []
    h = 2 * np.pi / P
    for arg, better in ((np.argmax(Y, axis=1), np.greater), (np.argmin(Y, axis=1), np.less)):
        t0 = th[arg]
        t = t0.copy()
        for _ in range(iterations):
            d1, d2 = series_values(C, t, 1), series_values(C, t, 2)
            ok = d2 != 0
            t = np.where(ok, t - d1 / np.where(ok, d2, 1.0), t)
            t = np.clip(t, t0 - h, t0 + h)
        y = series_values(C, t)
        y0 = Y[np.arange(C.shape[0]), arg]
        out.append(np.where(better(y, y0), y, y0))
    return out[0], out[1]


def golden_extremes(f, k: int, points: int, iterations: int = 60):
    """(max, min) over theta of the vectorised periodic function f(theta (k, p)) -> (k, p): grid extremes,
    then golden-section search in the two neighbouring intervals (bracket shrunk by 0.618^iterations)."""
    P = points
    th = np.broadcast_to(2 * np.pi * np.arange(P) / P, (k, P))
    Y = f(th)
    h = 2 * np.pi / P
    out = []
    for sign in (1.0, -1.0):
        arg = np.argmax(sign * Y, axis=1)
        best = sign * Y[np.arange(k), arg]
        a = th[np.arange(k), arg] - h
        b = a + 2 * h
        c = b - GOLDEN * (b - a)
        d = a + GOLDEN * (b - a)
        fc = sign * f(c[:, None])[:, 0]
        fd = sign * f(d[:, None])[:, 0]
        for _ in range(iterations):            # maximise g = sign f on [a, b]
            left = fc > fd                         # the maximum lies in [a, d]
            b = np.where(left, d, b)
            a = np.where(left, a, c)
            c_new = np.where(left, b - GOLDEN * (b - a), d)
            d_new = np.where(left, c, a + GOLDEN * (b - a))
            fnew = sign * f(np.where(left, c_new, d_new)[:, None])[:, 0]
            fc, fd = np.where(left, fnew, fd), np.where(left, fc, fnew)
            c, d = c_new, d_new
        best = np.maximum(best, np.maximum(fc, fd))
        out.append(sign * best)
    return out[0], out[1]


def from_extremes(measure: str, ymax, ymin):
    """The extreme-based measures from (max, min)."""
    return {"amplitude": 0.5 * (ymax - ymin), "max": ymax, "min": ymin,
            "peak": np.maximum(np.abs(ymax), np.abs(ymin))}[measure]


def series_h1(C, nu: int):
    """Amplitude of harmonic nu of the real series C (k, 2H+1) (0 if nu > H)."""
    C = np.atleast_2d(np.asarray(C, float))
    H = (C.shape[-1] - 1) // 2
    if nu > H:
        return np.zeros(C.shape[0])
    return np.hypot(C[:, 2 * nu - 1], C[:, 2 * nu])


def periodic_h1(y, omega, nu: int):
    """h1 of samples y (k, P) at P equidistant phases of a period nu 2 pi / omega (the forcing component
    is harmonic nu of the phase grid): rectangle rule = trapezoid over the closed period."""
    y = np.atleast_2d(np.asarray(y, float))
    P = y.shape[-1]
    th = 2 * np.pi * np.arange(P) / P * nu
    a = 2.0 / P * (y @ np.cos(th))
    b = 2.0 / P * (y @ np.sin(th))
    return np.hypot(a, b)


def series_h1_time(t, y, omega, period):
    """h1 of a non-uniform time series over one period [t0, t0 + period] (trapezoid including the closing
    point; if the series stops short of it, the closing value is taken equal to the first: periodic)."""
    t = np.asarray(t, float) - t[0]
    y = np.asarray(y, float)
    sel = t <= period * (1 + 1e-12)
    t, y = t[sel], y[sel]
    if period - t[-1] > 1e-12 * period:
        t, y = np.append(t, period), np.append(y, y[0])
    a = 2 / period * np.trapezoid(y * np.cos(omega * t), t)
    b = 2 / period * np.trapezoid(y * np.sin(omega * t), t)
    return float(np.hypot(a, b))


def refined_sample_extremes(t, y, events=None):
    """(max, min) of a sampled series refined by the vertex of the parabola through the extreme sample
    and its nearest neighbours at distinct times (dense output repeats the instants where pieces join);
    the neighbours spaced alike (ratio <= 2: where one lies much closer than the other -- a marching step
    or an event record next to the extreme on an output grid -- the next sample on that side is taken);
    kept only if no event (a switch of the law: the series is only C^1 there, e.g. a slip reversal at the
    extreme) lies between them, and the vertex lies between them."""
    t, y = np.asarray(t, float), np.asarray(y, float)
    ev = np.asarray([] if events is None else events, float)
    tiny = 1e-12 * max(abs(t[-1] - t[0]), 1e-300)
    out = []
    for sign in (1.0, -1.0):
        i = int(np.argmax(sign * y))
        v = y[i]
        lo, hi = i - 1, i + 1
        while lo >= 0 and t[i] - t[lo] <= tiny:
            lo -= 1
        while hi < y.size and t[hi] - t[i] <= tiny:
            hi += 1
        if lo >= 0 and hi < y.size:
            h0, h1 = t[i] - t[lo], t[hi] - t[i]
            while h0 > 2.0 * h1 and hi + 1 < y.size:       # a sample much closer on the right: skip it
                hi += 1
                h1 = t[hi] - t[i]
            while h1 > 2.0 * h0 and lo - 1 >= 0:           # ... on the left
                lo -= 1
                h0 = t[i] - t[lo]
            if 0.5 <= h0 / h1 <= 2.0 and not np.any((ev >= t[lo] - tiny) & (ev <= t[hi] + tiny)):
                # the parabola through (-h0, y_lo), (0, y_i), (h1, y_hi): slope b and curvature 2 c at 0
                d0, d1 = (y[i] - y[lo]) / h0, (y[hi] - y[i]) / h1
                c = (d1 - d0) / (h0 + h1)
                b = d0 + c * h0
                if c != 0:
                    tv = -b / (2 * c)
                    if -h0 < tv < h1:
                        yv = float(y[i] + b * tv + c * tv * tv)
                        if sign * yv > sign * v:
                            v = yv
        out.append(float(v))
    return out[0], out[1]
