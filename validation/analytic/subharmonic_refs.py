"""Independent time integration of the forced cubic oscillator for the 1/3 subharmonic test of the
digest (textbook §8.4 checks): q'' + 2 n0 q' + k0^2 q (1 + xi q^2) = F3 cos(Omega t), written here
directly on scipy's DOP853 (no package code), all initial phases integrated at once."""
from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp


def subharmonic_amplitudes(F3: float, psi: float, *, k0: float = 1.0, xi: float = 0.5, omega: float = 1.2,
                           A1: float, phases: int = 12, periods: int = 300, samples: int = 256) -> np.ndarray:
    """The digest's procedure: damping 2 n0 = psi k0 / (2 pi); initial state q = A1 cos(phi) + F3 / (k0^2 -
    Omega^2), q' = -A1 omega sin(phi) for ``phases`` phases phi = 2 pi j / phases; ``periods`` periods
    2 pi / omega (Omega = 3 omega) integrated (rtol 1e-10); returns, per phase, the amplitude of the
    omega-component (the subharmonic) over the last period."""
    W = 3.0 * omega
    c = psi * k0 / (2.0 * np.pi)
    ph = 2.0 * np.pi * np.arange(phases) / phases
    y0 = np.concatenate([A1 * np.cos(ph) + F3 / (k0 ** 2 - W ** 2), -A1 * omega * np.sin(ph)])

    def rhs(t, y):
        q, v = y[:phases], y[phases:]
        return np.concatenate([v, F3 * np.cos(W * t) - c * v - k0 ** 2 * q * (1.0 + xi * q * q)])

    T = 2.0 * np.pi / omega
    t1 = (periods - 1) * T
    a = solve_ivp(rhs, (0.0, t1), y0, method="DOP853", rtol=1e-10, atol=1e-12)
    te = t1 + T * np.arange(samples) / samples
    b = solve_ivp(rhs, (t1, t1 + T), a.y[:, -1], method="DOP853", rtol=1e-11, atol=1e-13, t_eval=te)
    q = b.y[:phases]
    return 2.0 / samples * np.abs(q @ np.exp(-1j * omega * te))
