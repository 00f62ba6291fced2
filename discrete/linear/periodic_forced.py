"""Steady response of a :class:`LinearSystem` to periodic non-harmonic loads by Fourier superposition.

Each periodic load is a fixed spatial vector times a scalar periodic function given by its Fourier
series (:class:`discrete.motion.fourier.FourierSeries`, (5.41)-(5.42)); a periodic prescribed motion of
a constrained DOF (a cam-driven driver, §6.2) is given the same way.  By superposition (textbook §5.8,
(5.44)-(5.45)) the steady state is

    q(t) = Re sum_{j=0}^{H} Q_j e^{i j w t},   Q_j = c_j H(j w) f   (c_j = F_jc - i F_js, c_0 = F_0),

where the receptances H(j w) f are computed by :func:`discrete.linear.harmonic.harmonic_response`
(one call per load over the frequencies j w: direct sparse LU or modal superposition).

Accuracy: exact for the truncated series; the error is the response to the discarded harmonics.
For a load with a jump (F_j ~ 1/j) it decays like 1/H^2 in q and 1/H in q' (the book's remark that
harmonic analysis suits smooth excitations, §5.8); the series' own truncation and aliasing errors
are reported with the result.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import ModelError
from ..linear_system import LinearSystem
from ..motion.fourier import FourierSeries
from .harmonic import Damping, HarmonicResult, harmonic_response, reliability_warnings

WHERE = "periodic load"
BLOCK = 1 << 21          # entries of one block of the matrix of exponentials (instants x harmonics)


@dataclass
class PeriodicLoad:
    """Force vector(t) = vector * F(t), F given by its Fourier series."""

    vector: np.ndarray
    series: FourierSeries


@dataclass
class PeriodicResponse:
    omega_rad_s: float                  # fundamental 2 pi / tau
    amplitudes: np.ndarray              # (H + 1, n_outputs) complex Q_j, j = 0..H
    outputs: list[str]
    method: str
    damping: str
    series_errors: list[dict] = field(default_factory=list)   # truncation / aliasing of each input series
    warnings: list[str] = field(default_factory=list)
    error_estimate: np.ndarray | None = None  # (H + 1,) relative error of each harmonic's response (harmonic_response)

    @property
    def period(self) -> float:
        return 2 * math.pi / self.omega_rad_s

    @property
    def harmonics(self) -> int:
        return self.amplitudes.shape[0] - 1

    def __call__(self, t, derivative: int = 0) -> np.ndarray:
        """q^(derivative)(t) at the outputs, shape (len(t), n_outputs); evaluated in blocks of instants, so that
        the matrix of exponentials stays below :data:`BLOCK` entries whatever the number of harmonics."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        j = np.arange(self.harmonics + 1)
        w = j * self.omega_rad_s
        fac = (1j * w) ** derivative
        out = np.empty((t.size, self.amplitudes.shape[1]))
        rows = max(1, BLOCK // w.size)
        for a in range(0, t.size, rows):
            E = np.exp(1j * np.multiply.outer(t[a:a + rows], w)) * fac
            out[a:a + rows] = (E @ self.amplitudes).real
        return out

    def peak(self, samples: int = 4096, derivative: int = 0) -> np.ndarray:
        """max |q^(m)| over one period per output, on ``samples`` equally spaced instants: the sum
        sum_j Q_j (i j w)^m e^{2 pi i j k / samples} is an inverse FFT (O(samples log samples) per output, exact
        for samples > harmonics; the instants k period / samples of the direct sum)."""
        H = self.harmonics
        if samples <= H:
            t = np.linspace(0.0, self.period, samples, endpoint=False)
            return np.max(np.abs(self(t, derivative)), axis=0)
        w = np.arange(H + 1) * self.omega_rad_s
        spec = np.zeros((samples, self.amplitudes.shape[1]), dtype=complex)
        spec[:H + 1] = self.amplitudes * ((1j * w) ** derivative)[:, None]
        q = (samples * np.fft.ifft(spec, axis=0)).real
        return np.max(np.abs(q), axis=0)

    def to_dict(self) -> dict:
        return {"omega_rad_s": self.omega_rad_s, "period": self.period, "harmonics": self.harmonics,
                "outputs": list(self.outputs), "method": self.method, "damping": self.damping,
                "real": self.amplitudes.real.T.tolist(), "imag": self.amplitudes.imag.T.tolist(),
                "peak": self.peak().tolist(), "series_errors": list(self.series_errors), "warnings": list(self.warnings)}


def _fundamental(series: list[FourierSeries]) -> float:
    periods = np.array([s.period for s in series])
    if np.any(np.abs(periods - periods[0]) > 1e-12 * periods[0]):
        raise ModelError(WHERE, "period", periods.tolist(), "the same period for every periodic load and motion")
    return 2 * math.pi / periods[0]


def periodic_response(system: LinearSystem, *, loads: list[PeriodicLoad] | tuple = (),
                      base_motion: dict[int, FourierSeries] | None = None, damping: Damping | None = None,
                      outputs: list[int] | None = None, method: str = "direct", n_modes: int | None = None,
                      harmonics: int | None = None) -> PeriodicResponse:
    """Fourier superposition of harmonic responses (see the module docstring).

    ``loads``: periodic forces; ``base_motion``: {constrained DOF: periodic prescribed motion};
    ``harmonics``: use at most this many harmonics of each series (default: all of them).
    """
    base_motion = dict(base_motion or {})
    if not loads and not base_motion:
        raise ModelError(WHERE, "loads", [], "at least one periodic load or base motion")
    for i, ld in enumerate(loads):
        if not isinstance(ld, PeriodicLoad):
            raise ModelError(WHERE, f"loads[{i}]", type(ld).__name__, "a PeriodicLoad(vector, series)")
        if np.shape(ld.vector) != (system.n_dofs,):
            raise ModelError(WHERE, f"loads[{i}].vector", list(np.shape(ld.vector)), f"a vector of {system.n_dofs} entries")
    for dof, s in base_motion.items():
        if not isinstance(s, FourierSeries):
            raise ModelError(WHERE, f"base_motion[{dof}]", type(s).__name__, "a FourierSeries")
    series = [ld.series for ld in loads] + list(base_motion.values())
    w0 = _fundamental(series)
    H = max(s.harmonics for s in series)
    if harmonics is not None:
        if isinstance(harmonics, bool) or not isinstance(harmonics, (int, np.integer)) or harmonics < 1:
            raise ModelError(WHERE, "harmonics", harmonics, "an integer >= 1")
        H = min(H, int(harmonics))
    outputs = list(range(system.n_dofs)) if outputs is None else [int(i) for i in outputs]
    n_rigid = 0 if system.rigid_modes is None else system.rigid_modes.shape[1]
    Q = np.zeros((H + 1, len(outputs)), dtype=complex)
    err = np.zeros(H + 1)
    method_name, damp_name = "", ""

    def add(coeffs: np.ndarray, **kw):
        nonlocal method_name, damp_name
        c = np.zeros(H + 1, dtype=complex)
        m = min(H + 1, coeffs.size)
        c[:m] = coeffs[:m]
        js = np.flatnonzero(c != 0)
        if js.size == 0:
            return
        if js[0] == 0 and n_rigid:
            raise ModelError(WHERE, "mean", float(c[0].real), "0 for a system with rigid-body modes (a constant "
                             "load would accelerate it without bound; give the load a zero mean)")
        res = harmonic_response(system, js * w0, damping=damping, outputs=outputs, method=method, n_modes=n_modes, **kw)
        Q[js] += res.response * c[js, None]
        if res.error_estimate is not None:
            err[js] = np.maximum(err[js], res.error_estimate)
        method_name, damp_name = res.method, res.damping

    for ld in loads:
        add(ld.series.complex_amplitudes, force=np.asarray(ld.vector, dtype=complex))
    for dof, s in base_motion.items():
        add(s.complex_amplitudes, base_motion={int(dof): 1.0})
    errs = [{"input": f"load {i}" if i < len(loads) else f"base motion of DOF {list(base_motion)[i - len(loads)]}",
             "harmonics": s.harmonics, "max_error": s.max_error, "rms_error": s.rms_error,
             "aliasing_error": s.aliasing_error, "scale": s.scale} for i, s in enumerate(series)]
    return PeriodicResponse(omega_rad_s=w0, amplitudes=Q, outputs=[system.label(i) for i in outputs],
                            method=f"Fourier superposition of {H} harmonics; {method_name}", damping=damp_name,
                            series_errors=errs, error_estimate=err,
                            warnings=reliability_warnings(np.arange(H + 1) * w0, err))


@dataclass
class PeriodicForcedResult(HarmonicResult):
    """The steady state under periodic loads in the shape of a harmonic result: ``omega_rad_s`` are the
    harmonics j w (j = 0..H) and ``response`` their complex amplitudes Q_j at the outputs, so that
    q(t) = Re sum_j Q_j e^{i j w t}; plus the period, one period of samples and the peak |q|."""

    period: float = 0.0
    t: np.ndarray | None = None            # one period of samples
    q: np.ndarray | None = None            # (samples, outputs)
    peak: np.ndarray | None = None         # max |q| over a period per output (dense: max(8192, 32 H) instants)
    series_errors: list = field(default_factory=list)

    def to_dict(self) -> dict:
        d = super().to_dict()
        d["periodic"] = {"period": self.period, "harmonics": int(self.omega_rad_s.size - 1),
                         "peak": self.peak.tolist(), "t": self.t.tolist(), "q": self.q.T.tolist(),
                         "series_errors": list(self.series_errors)}
        return d


def _harmonic_series(c: complex, period: float, harmonics: int) -> FourierSeries:
    """The series of Re(c e^{i w t}) (w = 2 pi / period): one harmonic, exact."""
    cos, sin = np.zeros(harmonics), np.zeros(harmonics)
    cos[0], sin[0] = c.real, -c.imag
    return FourierSeries(period=period, mean=0.0, cos=cos, sin=sin, samples=0, max_error=0.0, rms_error=0.0,
                         aliasing_error=0.0, scale=abs(c))


def periodic_forced(system: LinearSystem, period: float, harmonics: int, *, shaped=(), force=None,
                    base_motion: dict | None = None, damping: Damping | None = None, outputs: list[int] | None = None,
                    method: str = "direct", n_modes: int | None = None, samples: int = 512) -> PeriodicForcedResult:
    """Steady state under periodic loads of ``period``: ``shaped`` = [(DOF, amplitude, shift, w)] loads
    amplitude * w(t/period + shift) (:class:`discrete.motion.waveforms.Waveform`: exact series), ``force`` complex
    amplitudes of harmonic loads at the fundamental, ``base_motion`` {held DOF: complex amplitude} at the
    fundamental; Fourier superposition of ``harmonics`` harmonics (:func:`periodic_response`)."""
    loads = []
    n = system.n_dofs
    for dof, amp, shift, wave in shaped:
        vec = np.zeros(n)
        vec[int(dof)] = 1.0
        loads.append(PeriodicLoad(vec, wave.series(period, int(harmonics), amp, shift)))
    if force is not None:
        for dof in np.flatnonzero(force):
            vec = np.zeros(n)
            vec[dof] = 1.0
            loads.append(PeriodicLoad(vec, _harmonic_series(complex(force[dof]), period, int(harmonics))))
    base = {int(d): _harmonic_series(complex(c), period, int(harmonics)) for d, c in (base_motion or {}).items()}
    res = periodic_response(system, loads=loads, base_motion=base, damping=damping, outputs=outputs, method=method,
                            n_modes=n_modes, harmonics=int(harmonics))
    t = period * np.arange(samples) / samples
    H = res.harmonics
    return PeriodicForcedResult(omega_rad_s=np.arange(H + 1) * res.omega_rad_s, response=res.amplitudes,
                                outputs=res.outputs, method=res.method, damping=res.damping,
                                warnings=list(res.warnings), error_estimate=res.error_estimate,
                                period=float(period), t=t, q=res(t),
                                peak=res.peak(samples=max(8192, 32 * H)), series_errors=res.series_errors)
