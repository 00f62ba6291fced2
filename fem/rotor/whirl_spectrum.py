"""The spectrum of a run-up's orbit against speed (cascade / waterfall) and the onset of oil whirl/whip.

**Cascade.**  The orbit r = y + i z at a probe is cut into windows (Hann, 75 % overlap; zero-padded
4x) and each window's complex spectrum is taken: positive frequencies are forward whirl, negative ones
backward whirl (Muszynska, *Rotordynamics* (2005) §3: the full spectrum).  Each window is labelled
with the speed at its centre, so the cascade shows the synchronous line 1x, its harmonics, and
a subsynchronous line when the rotor whirls at its own frequency.

**Onset.**  Fluid-film whirl is a self-excited forward mode: below the threshold speed its free
vibration decays like exp(sigma t) with sigma(Omega) < 0, above it grows.  Along a slow ramp the
amplitude of the subsynchronous component is a(t) ~ exp(int sigma(Omega(t)) dt), whose minimum lies
where sigma = 0: the linear threshold (for a ramp slow against the growth rates; the synchronous
unbalance response is filtered out).  The component is isolated by a zero-phase band-pass
(Butterworth, ``scipy.signal.sosfiltfilt``) around the dominant subsynchronous frequency of the
last windows, its envelope is the modulus of the analytic signal (Hilbert), and the minimum is
refined by a parabola through log a(t) over the samples around it.  Reported: the onset speed,
the whirl frequency there and at the end of the run (oil whip: it stays near the rotor's first
forward natural frequency, which the films stiffen as the orbit grows, while the speed goes on
rising; on stiff films that is about the first critical speed) and the amplitude growth after the
onset (the envelope is NaN over the filter's edge transients).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import signal

from discrete.errors import ModelError


@dataclass
class Cascade:
    """The cascade of one probe: window centres ``t`` (s) and ``speed`` (rad/s), ``frequency``
    (rad/s, negative: backward whirl), ``amplitude`` (n_windows, n_freq) of the whirl component at
    each frequency (m; a pure circle of radius A at one frequency shows A)."""

    probe_x: float
    t: np.ndarray
    speed: np.ndarray
    frequency: np.ndarray
    amplitude: np.ndarray

    def to_dict(self) -> dict:
        return {"probe_x": self.probe_x, "t": self.t.tolist(), "speed_rad_s": self.speed.tolist(),
                "frequency_rad_s": self.frequency.tolist()}


@dataclass
class WhirlOnset:
    """The subsynchronous whirl of a run-up at a probe: ``onset_speed`` (rad/s; None: the
    subsynchronous amplitude never turns to growth), the ``whirl_frequency`` there and
    ``final_frequency`` at the end (rad/s), their ratios to the speed, the amplitude ``growth``
    (end / minimum), and the envelope (``t``, ``envelope``; NaN at the filter's edges) it was read from."""

    probe_x: float
    onset_speed: float | None
    onset_time: float | None
    whirl_frequency: float
    final_frequency: float
    final_speed: float
    growth: float
    t: np.ndarray
    envelope: np.ndarray
    band: tuple

    @property
    def whirl_ratio(self) -> float | None:
        return None if self.onset_speed is None else self.whirl_frequency / self.onset_speed

    def to_dict(self) -> dict:
        return {"probe_x": self.probe_x, "onset_speed_rad_s": self.onset_speed, "onset_time_s": self.onset_time,
                "onset_speed_rpm": None if self.onset_speed is None else self.onset_speed * 30 / math.pi,
                "whirl_frequency_rad_s": self.whirl_frequency, "whirl_ratio": self.whirl_ratio,
                "final_frequency_rad_s": self.final_frequency, "final_speed_rad_s": self.final_speed,
                "final_ratio": self.final_frequency / self.final_speed if self.final_speed else None,
                "growth": self.growth, "band_rad_s": list(self.band)}


def _probe(result, x: float | None) -> int:
    if x is None:
        return int(np.argmax([np.ptp(result.orbit_y[:, k]) + np.ptp(result.orbit_z[:, k])
                              for k in range(result.probe_x.size)]))
    k = np.flatnonzero(np.isclose(result.probe_x, x, rtol=0, atol=1e-9 * max(1.0, abs(x))))
    if not k.size:
        raise ModelError("whirl analysis", "probe", x, "one of the run's probes: "
                         + ", ".join(f"{p:g}" for p in result.probe_x))
    return int(k[0])


def cascade(result, probe_x: float | None = None, window_revolutions: float = 16.0) -> Cascade:
    """The cascade of a :class:`~fem.rotor.runup.RunUpResult` at ``probe_x`` (default: the probe
    that moves most): windows of ``window_revolutions`` revolutions at the run's mean speed."""
    k = _probe(result, probe_x)
    t = result.t
    if t.size < 64:
        raise ModelError("whirl analysis", "samples", t.size, "a run with at least 64 output samples")
    dt = float(np.median(np.diff(t)))
    w_mean = max(float(np.mean(result.speed)), 1e-9)
    n = int(min(max(64, window_revolutions * 2 * math.pi / w_mean / dt), t.size))
    step = max(1, n // 4)
    r = result.orbit_y[:, k] + 1j * result.orbit_z[:, k]
    win = np.hanning(n)
    nfft = 4 * n                                     # zero-padded 4x: the peaks drawn smoothly (same resolution)
    freq = np.fft.fftshift(np.fft.fftfreq(nfft, dt)) * 2 * math.pi
    rows, tc, sc = [], [], []
    for i0 in range(0, t.size - n + 1, step):
        seg = r[i0:i0 + n]
        seg = seg - seg.mean()                       # the static position (the journal's operating point)
        F = np.fft.fftshift(np.fft.fft(seg * win, nfft)) * 2.0 / win.sum()
        rows.append(np.abs(F))
        tc.append(t[i0 + n // 2])
        sc.append(result.speed[i0 + n // 2])
    return Cascade(probe_x=float(result.probe_x[k]), t=np.array(tc), speed=np.array(sc), frequency=freq,
                   amplitude=np.array(rows))


def whirl_onset(result, probe_x: float | None = None, band: tuple | None = None,
                window_revolutions: float = 16.0) -> WhirlOnset:
    """The onset of subsynchronous whirl in a run-up (see the module notes); ``band`` (rad/s) the
    whirl frequencies to keep (default: +-30 % around the dominant forward subsynchronous peak of
    the last quarter of the run)."""
    k = _probe(result, probe_x)
    cas = cascade(result, float(result.probe_x[k]), window_revolutions)
    last = cas.t >= cas.t[0] + 0.75 * (cas.t[-1] - cas.t[0])
    sub = (cas.frequency > 0.05 * cas.speed.min()) & (cas.frequency < 0.85 * cas.speed.min())
    if not sub.any():
        raise ModelError("whirl analysis", "samples", result.t.size, "a run sampled finely enough to resolve "
                         "frequencies below the speed (a smaller output_step or a longer run)")
    spec = cas.amplitude[last][:, sub].mean(axis=0)
    f_peak = float(cas.frequency[sub][np.argmax(spec)])
    lo, hi = band if band is not None else (0.7 * f_peak, 1.3 * f_peak)
    t = result.t
    dt = float(np.median(np.diff(t)))
    nyq = math.pi / dt
    sos = signal.butter(4, [lo / nyq, min(hi / nyq, 0.99)], btype="bandpass", output="sos")
    r = result.orbit_y[:, k] + 1j * result.orbit_z[:, k]
    # the forward component at positive frequencies: band-pass y and z, then r_f = (r + i H r)/2 ...
    y = signal.sosfiltfilt(sos, result.orbit_y[:, k] - result.orbit_y[:, k].mean())
    z = signal.sosfiltfilt(sos, result.orbit_z[:, k] - result.orbit_z[:, k].mean())
    ya, za = signal.hilbert(y), signal.hilbert(z)
    forward = 0.5 * (ya + 1j * za)                  # e^{i nu t} part of y + i z (analytic signals of y and z)
    env = np.abs(forward)
    # skip the filter's edge transients (two periods of the band's lower edge at each end)
    edge = int(min(4 * math.pi / lo / dt, t.size // 4))
    inner = slice(edge, t.size - edge)
    ti, ei = t[inner], env[inner]
    j = int(np.argmin(ei))
    onset_t = onset_speed = None
    if 0 < j < ei.size - 1 and ei[-1] > 2.0 * ei[j]:
        # parabola through log a over the samples within one e-fold of the minimum
        near = np.flatnonzero(np.log(ei) <= np.log(ei[j]) + 1.0)
        near = near[(near >= max(j - ei.size // 5, 0)) & (near <= min(j + ei.size // 5, ei.size - 1))]
        c2, c1, _ = np.polyfit(ti[near] - ti[j], np.log(ei[near]), 2)
        shift = -c1 / (2 * c2) if c2 > 0 else 0.0
        onset_t = float(ti[j] + shift)
        onset_speed = float(np.interp(onset_t, t, result.speed))
    phase = np.unwrap(np.angle(forward))
    inst = np.gradient(phase, t)
    f_onset = float(np.interp(onset_t, t, inst)) if onset_t is not None else f_peak
    shown = np.full(t.size, np.nan)
    shown[inner] = ei                               # the filter's edge transients are not part of the envelope
    return WhirlOnset(probe_x=float(result.probe_x[k]), onset_speed=onset_speed, onset_time=onset_t,
                      whirl_frequency=f_onset, final_frequency=float(np.median(inst[inner][-max(1, ei.size // 20):])),
                      final_speed=float(result.speed[-1]), growth=float(ei[-1] / ei[j]), t=t, envelope=shown,
                      band=(float(lo), float(hi)))
