"""Independent references for the amplitude-frequency curves of hybrid FE models (case ``hybrid_afc``).

* :func:`den_hartog_damped` -- the exact symmetric steady state of the oscillator with combined
  Coulomb and viscous friction (Den Hartog 1931, "Forced vibrations with combined Coulomb and viscous
  friction", Trans. ASME APM-53-9)

      m x'' + c x' + k x + F sign x' = P0 cos(w t + phi)

  with two stops per period and no sticking.  On the half period 0 < t < pi/w (x' > 0) the motion is
  linear with the constant force -F; the symmetric orbit satisfies x(0) = -X, x'(0) = 0,
  x(pi/w) = X, x'(pi/w) = 0.  With the free response e^(-sigma t) (A cos w_d t + B sin w_d t) and the
  forced part Re(D e^(i(w t + phi))), D = P0 / (k - m w^2 + i c w), the four conditions are *linear*
  in u = (A, B, X, cos phi, sin phi); their one-parameter solution family u_p + tau n meets
  cos^2 + sin^2 = 1 at the roots of a quadratic in tau.  The root kept is the one whose velocity stays
  positive inside the half period (no stop: the formula's own validity condition); NaN when none does
  (the motion then sticks, outside Den Hartog's regime).  For c = 0 it reduces to the classical
  ``den_hartog_amplitude`` of :mod:`validation.analytic.steady_refs` (checked in the case).
* :func:`first_mode_sdof` -- the one-mode (Rayleigh-Ritz) oscillator of a linear system referred to
  one DOF j: m1 = 1 / phi1_j^2 (mass-normalised phi1), k1 = omega1^2 m1, c1 = (phi1^T C phi1) m1, and the
  share of the static flexibility at j that mode 1 carries, (phi1_j^2 / omega1^2) / (K^-1)_jj.  The rest
  (1 - share) is the flexibility of the higher modes that any one-mode estimate leaves out.
* :func:`residual_receptance` -- what the higher modes add at DOF j per unit force at DOF i and frequency
  w: the exact damped receptance of the system minus mode 1's (the part every one-mode estimate drops).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def den_hartog_damped(m: float, k: float, c: float, F: float, P0: float, omega: float,
                      check_points: int = 2001) -> float:
    """Amplitude X (half peak-to-peak) of the exact symmetric two-stop steady state of
    m x'' + c x' + k x + F sign x' = P0 cos(omega t + phi); NaN where that motion does not exist."""
    w0 = np.sqrt(k / m)
    zeta = c / (2.0 * np.sqrt(k * m))
    if not zeta < 1.0:
        raise ValueError("den_hartog_damped: underdamped oscillators only (zeta < 1)")
    sig = zeta * w0
    wd = w0 * np.sqrt(1.0 - zeta * zeta)
    D = P0 / (k - m * omega * omega + 1j * c * omega)
    Dr, Di = D.real, D.imag
    tau = np.pi / omega

    def basis(t):
        """Rows [h1, h2, pc, ps] and their time derivatives at t (x = A h1 + B h2 - F/k + c pc + s ps)."""
        e = np.exp(-sig * t)
        co, si = np.cos(wd * t), np.sin(wd * t)
        cw, sw = np.cos(omega * t), np.sin(omega * t)
        val = np.array([e * co, e * si, Dr * cw - Di * sw, -Dr * sw - Di * cw])
        der = np.array([e * (-sig * co - wd * si), e * (-sig * si + wd * co),
                        omega * (-Dr * sw - Di * cw), omega * (-Dr * cw + Di * sw)])
        return val, der

    v0, d0 = basis(0.0)
    v1, d1 = basis(tau)
    # unknowns u = [A, B, X, cos phi, sin phi]
    Amat = np.array([[v0[0], v0[1], 1.0, v0[2], v0[3]],
                     [d0[0], d0[1], 0.0, d0[2], d0[3]],
                     [v1[0], v1[1], -1.0, v1[2], v1[3]],
                     [d1[0], d1[1], 0.0, d1[2], d1[3]]])
    rhs = np.array([F / k, 0.0, F / k, 0.0])
    up = np.linalg.lstsq(Amat, rhs, rcond=None)[0]
    n = np.linalg.svd(Amat)[2][-1]
    a = n[3] ** 2 + n[4] ** 2
    b = 2.0 * (up[3] * n[3] + up[4] * n[4])
    c0 = up[3] ** 2 + up[4] ** 2 - 1.0
    disc = b * b - 4.0 * a * c0
    if disc < 0:
        return float("nan")
    t_in = np.linspace(0.0, tau, check_points)[1:-1]
    e = np.exp(-sig * t_in)
    cw, sw = np.cos(omega * t_in), np.sin(omega * t_in)
    h1d = e * (-sig * np.cos(wd * t_in) - wd * np.sin(wd * t_in))
    h2d = e * (-sig * np.sin(wd * t_in) + wd * np.cos(wd * t_in))
    pcd = omega * (-Dr * sw - Di * cw)
    psd = omega * (-Dr * cw + Di * sw)
    best = float("nan")
    for root in ((-b + np.sqrt(disc)) / (2 * a), (-b - np.sqrt(disc)) / (2 * a)):
        u = up + root * n
        if not u[2] > 0:
            continue
        v = u[0] * h1d + u[1] * h2d + u[3] * pcd + u[4] * psd
        if np.all(v > 0):                  # moving up through the whole half period: no stop, no stick
            best = float(u[2])
    return best


@dataclass
class ModeSDOF:
    """The first mode of a linear system referred to one DOF j (see :func:`first_mode_sdof`)."""

    j: int                 # the DOF it is referred to
    omega1: float          # rad/s
    m1: float              # modal mass referred to DOF j, 1 / phi1_j^2
    k1: float              # modal stiffness referred to DOF j, omega1^2 m1
    c1: float              # modal damping referred to DOF j, (phi1^T C phi1) m1
    static_flexibility: float    # (K^-1)_jj of the system
    share: float           # mode 1's share of it, (1 / k1) / (K^-1)_jj
    phi: np.ndarray        # mass-normalised mode 1 over all DOFs of the system (zero at held DOFs)

    def ratio(self, i: int) -> float:
        """phi1_i / phi1_j: a force at DOF i acts on the referred coordinate multiplied by this."""
        return float(self.phi[i] / self.phi[self.j])

    def receptance(self, omega: float) -> complex:
        """Mode 1's own receptance at DOF j, 1 / (k1 - m1 omega^2 + i c1 omega)."""
        return 1.0 / (self.k1 - self.m1 * omega * omega + 1j * self.c1 * omega)


def _dense_free(system):
    f = system.free
    return (f, system.free_block(system.M).toarray(), system.free_block(system.K).toarray(),
            system.free_block(system.C).toarray())


def first_mode_sdof(system, j: int, modal_result) -> ModeSDOF:
    """Mode 1 of ``modal_result`` (mass-normalised, full DOF vector) of ``system`` referred to DOF ``j``.
    Exact for Rayleigh damping (the modes decouple); otherwise c1 is mode 1's diagonal term."""
    w1 = float(modal_result.omega_rad_s[0])
    phi = np.asarray(modal_result.shapes[:, 0], float)
    f, M, K, C = _dense_free(system)
    pf = phi[f]
    if abs(pf @ M @ pf - 1.0) > 1e-8:
        raise ValueError("first_mode_sdof: mode 1 is not mass-normalised")
    m1 = 1.0 / phi[j] ** 2
    k1 = w1 * w1 * m1
    jf = list(f).index(j)
    fs = float(np.linalg.solve(K, np.eye(len(f))[jf])[jf])
    return ModeSDOF(j=j, omega1=w1, m1=m1, k1=k1, c1=float(pf @ C @ pf) * m1, static_flexibility=fs,
                    share=(1.0 / k1) / fs, phi=phi)


def residual_receptance(system, mode: ModeSDOF, i: int, omega: float) -> complex:
    """What the higher modes add to the displacement of DOF ``mode.j`` per unit force at DOF ``i`` at
    frequency ``omega``: the exact damped receptance of the (small, dense) system minus mode 1's term,
    ``[K - w^2 M + i w C]^-1_ji - phi1_j phi1_i / (omega1^2 - w^2 + i w c_modal)``."""
    f, M, K, C = _dense_free(system)
    fl = list(f)
    Z = K - omega * omega * M + 1j * omega * C
    e = np.zeros(len(f), complex)
    e[fl.index(i)] = 1.0
    full = np.linalg.solve(Z, e)[fl.index(mode.j)]
    return complex(full - mode.ratio(i) * mode.receptance(omega))
