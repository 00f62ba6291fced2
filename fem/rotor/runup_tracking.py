"""The synchronous (1x) response of a run-up, as a tracking filter on the shaft angle gives it: the
data of a run-up Bode plot.

With the shaft angle phi(t) = int Omega dt (the unbalance's phase reference: the forcing is
m e Omega^2 e^{i (phi + beta)}), the orbit r = y + i z of a probe at constant speed is
r = F e^{i phi} + B e^{-i phi} (forward and backward circles, :mod:`fem.rotor.whirl`).  Along the run
F and B are estimated at each output speed as Hann-weighted means over a window of
``revolutions`` shaft revolutions in the angle,

    F = sum r_j e^{-i phi_j} w_j dphi_j / sum w_j dphi_j,     B = the same with e^{+i phi_j},

which rejects every component that is not synchronous (sub-synchronous whirl, harmonics of a rub)
to the Hann window's leakage.  The 1x orbit's semi-major axis is |F| + |B| and its phase lag
-arg F, the conventions of :func:`fem.rotor.unbalance_response` (a slow run-up converges to the
steady unbalance response; tests/test_rotor_cli_figures.py checks it)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from discrete.errors import ModelError


@dataclass
class SynchronousResponse:
    """1x components at ``speed_rad_s`` (n,) for each probe at ``probe_x``: ``forward``, ``backward``
    (n, n_probes) complex, m; ``amplitude`` = |F| + |B| (the 1x orbit's semi-major axis), ``phase_lag_deg``
    of F in [0, 360)."""

    probe_x: np.ndarray
    speed_rad_s: np.ndarray
    forward: np.ndarray
    backward: np.ndarray
    revolutions: float

    @property
    def amplitude(self) -> np.ndarray:
        return np.abs(self.forward) + np.abs(self.backward)

    @property
    def phase_lag_deg(self) -> np.ndarray:
        return np.mod(-np.degrees(np.angle(self.forward)), 360.0)

    def to_dict(self) -> dict:
        return {"probe_x": self.probe_x.tolist(), "speed_rad_s": self.speed_rad_s.tolist(),
                "amplitude_m": self.amplitude.T.tolist(), "phase_lag_deg": self.phase_lag_deg.T.tolist(),
                "revolutions": self.revolutions}


def synchronous_response(res, revolutions: float = 4.0, points: int = 300) -> SynchronousResponse:
    """The 1x response of a :class:`~fem.rotor.RunUpResult` at ``points`` speeds (module notes)."""
    t, w = np.asarray(res.t, float), np.asarray(res.speed, float)
    if t.size < 16:
        raise ModelError("run-up Bode plot", "samples", t.size, "a run with at least 16 output samples")
    phi = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(t))])    # exact for a linear ramp
    if phi[-1] < 2 * np.pi * revolutions:
        raise ModelError("run-up Bode plot", "revolutions", float(phi[-1] / (2 * np.pi)),
                         f"a run of more than {revolutions:g} shaft revolutions")
    dphi = np.gradient(phi)
    half = np.pi * revolutions
    centres = np.linspace(phi[0] + half, phi[-1] - half, int(points))
    r = res.orbit_y + 1j * res.orbit_z                              # (n_samples, n_probes)
    F = np.zeros((centres.size, r.shape[1]), complex)
    B = np.zeros_like(F)
    speeds = np.zeros(centres.size)
    lo = np.searchsorted(phi, centres - half)
    hi = np.searchsorted(phi, centres + half, side="right")
    for k, (c, a, b) in enumerate(zip(centres, lo, hi)):
        u = (phi[a:b] - c) / half                                   # -1 ... 1 over the window
        wgt = (0.5 + 0.5 * np.cos(np.pi * u)) * dphi[a:b]
        e = np.exp(-1j * phi[a:b])
        F[k] = (wgt * e) @ r[a:b] / wgt.sum()
        B[k] = (wgt * np.conj(e)) @ r[a:b] / wgt.sum()
        speeds[k] = np.interp(c, phi, w)
    return SynchronousResponse(probe_x=np.asarray(res.probe_x, float), speed_rad_s=speeds, forward=F, backward=B,
                               revolutions=float(revolutions))
