"""A-posteriori estimate of the harmonic truncation error of an HB orbit.

An HB orbit with H harmonics satisfies the equations of motion projected on harmonics 0..H; its time-
domain residual lives in the harmonics above H and is the nonlinear force's content there,
``r_k = -g F_k`` (k = H+1 .. 2H; the linear part and the forcing have none).  The response the truncation
leaves out is, to first order, that force through the dynamic stiffness of the period-averaged
linearisation,

    dq_k = Z_k^{-1} g F_k,   Z_k = K_bar - (k W)^2 M + i k W C_bar,

(W = omega / nu; K_bar = K - sum_e g_e g_e^T <dF_e/ds>, C_bar likewise with <dF_e/ds'>, the period
averages), the one-step correction of the neglected harmonics (the "residual" estimate of adaptive HB:
Jaumouille, Sinou, Petitjean, J. Sound Vib. 329 (2010) 4048; Grolet, Thouverez, Mech. Syst. Signal Process.
27 (2012) 223).  The estimate is its size relative to the response:

    e = sum_k |dr_k| / a,

dr_k the harmonics of the response quantity (a body's coordinate, or the coordinate s of the response
element) and a its half peak-to-peak amplitude on the orbit (sum |dr_k| bounds max_t |dr(t)|).  The
element projections on 0..2H are exact for piecewise-affine laws (:mod:`.piecewise`) and from the DFT
of the N samples otherwise (2H < N/2).  What it does not include is the feedback of the missing
harmonics onto harmonics 0..H; the fold check (:func:`discrete.steady.afc`) re-solves the fold at
more harmonics for that.
"""
from __future__ import annotations

import numpy as np


def estimate(hb, X, omega, direction) -> float:
    """Relative truncation estimate ``e`` (module docstring) of the HB orbit X at omega for the response
    quantity ``direction . q`` (a unit vector for a body, the element's g for an element coordinate)."""
    return estimates(hb, [X], [omega], direction)[0]


def estimates(hb, Xs, omegas, direction) -> np.ndarray:
    """:func:`estimate` of many orbits (the dynamic-stiffness solves batched)."""
    s = hb.s
    n, H, m = s.n, hb.H, hb.m
    g = np.asarray(direction, float)
    P = len(Xs)
    out = np.zeros(P)
    if not len(s.elements) or P == 0:
        return out
    J = 2 * H
    k = np.arange(H + 1, J + 1)
    Q = np.asarray(Xs, float).reshape(P, n, m)
    hi_all, ms, mv = _high_harmonics(hb, Q, np.asarray(omegas, float), J)     # (P, nel, 2H): H+1..2H
    Gf = np.asarray(s.Gf, float)
    f = (hi_all[:, :, 0::2] - 1j * hi_all[:, :, 1::2]).transpose(0, 2, 1) @ Gf   # (P, H, n) amplitudes
    Kb = s.K - (Gf.T * ms[:, None, :]) @ Gf                        # (P, n, n): the period-averaged K, C
    Cb = s.C - (Gf.T * mv[:, None, :]) @ Gf
    W = np.asarray(omegas, float) / hb.nu
    kW = np.multiply.outer(W, k)                                   # (P, H)
    if n == 1:
        Z = Kb[:, :1, 0] - kW ** 2 * s.M[0, 0] + 1j * kW * Cb[:, :1, 0]
        dr = f[..., 0] / Z * g[0]
    else:
        Z = Kb[:, None] - (kW ** 2)[..., None, None] * s.M + 1j * kW[..., None, None] * Cb[:, None]
        dr = np.linalg.solve(Z, f[..., None])[..., 0] @ g          # (P, H)
    r = Q.transpose(0, 2, 1) @ g                                   # (P, m): the response quantity's series
    half = _half_ranges(r)
    amp = np.hypot(r[:, 1::2], r[:, 2::2]).sum(axis=1)
    scale = np.where(half > 0, half, np.maximum(np.maximum(amp, np.abs(r[:, 0])), 1e-300))
    return np.sum(np.abs(dr), axis=1) / scale


def _high_harmonics(hb, Q, omegas, J):
    """Element force projections on harmonics H+1..J (P, nel, 2(J-H)) and the period averages of dF/ds,
    dF/ds' (P, nel) of the orbits Q (P, n, m): the sampled laws of all orbits at once, the exact
    projections orbit by orbit (an orbit whose rough law is not exact on the grid: the dense grid)."""
    s = hb.s
    P = Q.shape[0]
    H, nel = hb.H, len(s.elements)
    out = np.zeros((P, nel, 2 * (J - H)))
    ms = np.zeros((P, nel))
    mv = np.zeros((P, nel))
    A = s.Gf @ Q                                                   # (P, nel, m)
    g = hb._grid
    Om = (omegas / hb.nu)[:, None, None]
    S = A @ hb.G + g.sa + g.sb / omegas[:, None, None]
    # the velocities only for the sampled laws (the exactly integrated ones take their series)
    Sd = Om * (A @ hb.DG) + g.sda + omegas[:, None, None] * g.sdb if hb._sampled else None
    redo = set()
    for e in hb._sampled:
        el = s.elements[e]
        F, dFs, dFv = el.smooth_force(S[:, e], Sd[:, e], s.eps)   # (P, N)
        spec = np.fft.rfft(F, axis=-1)[:, H + 1:J + 1] * (2.0 / hb.N)
        out[:, e, 0::2], out[:, e, 1::2] = spec.real, -spec.imag
        ms[:, e], mv[:, e] = dFs.mean(axis=-1), dFv.mean(axis=-1)
        if e in hb._rough:
            redo |= set(np.flatnonzero(~hb.rough_exact_batch(e, S[:, e], Sd[:, e])).tolist())
    for k, (e, proj, sa, sda, sdb) in enumerate(hb._pw):
        Cs = A[:, e] + sa
        Cv = Om[:, 0] * (A[:, e] @ hb.D) + sda + omegas[:, None] * sdb
        F, ms[:, e], mv[:, e] = hb.pw_projections(k, Cs, Cv, S[:, e], J)
        out[:, e] = F[:, 2 * H + 1:]
    for i in sorted(redo):                                         # the dense grid for these orbits
        Fp, spec_s, spec_v, _, _ = hb.element_projection(Q[i], omegas[i], jac=True, J=J)
        out[i] = Fp[:, 2 * H + 1:]
        ms[i], mv[i] = spec_s[:, 0].real / hb.N, spec_v[:, 0].real / hb.N
    return out, ms, mv


def _half_ranges(r, points: int = 256):
    """Half peak-to-peak of the real series r (P, 2H+1) on a grid (a scale: grid accuracy suffices)."""
    H = (r.shape[1] - 1) // 2
    th = 2 * np.pi * np.arange(points) / points
    kt = np.multiply.outer(np.arange(1, H + 1), th)
    y = r[:, 1::2] @ np.cos(kt) + r[:, 2::2] @ np.sin(kt)
    return 0.5 * (np.max(y, axis=1) - np.min(y, axis=1))


def response_direction(sm) -> np.ndarray:
    """The response quantity of a SteadyModel as a direction on the free DOFs: the body's unit vector or
    the response element's g."""
    s = sm.system
    if sm.resp_el is not None:
        return np.asarray(s.Gf[sm.resp_el], float)
    e = np.zeros(s.n)
    e[sm.resp_dof] = 1.0
    return e
