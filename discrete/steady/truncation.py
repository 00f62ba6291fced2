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
    """:func:`estimate` of many orbits."""
    s = hb.s
    n, H, m = s.n, hb.H, hb.m
    g = np.asarray(direction, float)
    out = np.zeros(len(Xs))
    if not len(s.elements):
        return out
    J = 2 * H
    k = np.arange(H + 1, J + 1)
    for i, (X, w) in enumerate(zip(Xs, omegas)):
        Q = np.asarray(X, float).reshape(n, m)
        Fp, spec_s, spec_v, _, _ = hb.element_projection(Q, w, jac=True, J=J)
        hi = Fp[:, 2 * H + 1:]                                     # (nel, 2H): harmonics H+1..2H
        f = s.Gf.T @ (hi[:, 0::2] - 1j * hi[:, 1::2])             # (n, H) complex amplitudes
        Kb = s.K - (s.Gf.T * (spec_s[:, 0].real / hb.N)) @ s.Gf
        Cb = s.C - (s.Gf.T * (spec_v[:, 0].real / hb.N)) @ s.Gf
        W = w / hb.nu
        Z = Kb[None] - ((k * W) ** 2)[:, None, None] * s.M[None] + 1j * (k * W)[:, None, None] * Cb[None]
        dq = np.linalg.solve(Z, f.T[..., None])[..., 0]            # (H, n)
        dr = dq @ g
        r = g @ Q
        amp = np.hypot(r[1::2], r[2::2]).sum()                    # bounds the half range; a cheap scale
        half = _half_range(r)
        scale = half if half > 0 else max(amp, abs(r[0]), 1e-300)
        out[i] = float(np.sum(np.abs(dr)) / scale)
    return out


def _half_range(r, points: int = 256) -> float:
    """Half peak-to-peak of the real series r on a grid (a scale: grid accuracy suffices)."""
    H = (r.size - 1) // 2
    th = 2 * np.pi * np.arange(points) / points
    kt = np.multiply.outer(th, np.arange(1, H + 1))
    y = r[0] + np.cos(kt) @ r[1::2] + np.sin(kt) @ r[2::2]
    return 0.5 * float(np.max(y) - np.min(y))


def response_direction(sm) -> np.ndarray:
    """The response quantity of a SteadyModel as a direction on the free DOFs: the body's unit vector or
    the response element's g."""
    s = sm.system
    if sm.resp_el is not None:
        return np.asarray(s.Gf[sm.resp_el], float)
    e = np.zeros(s.n)
    e[sm.resp_dof] = 1.0
    return e
