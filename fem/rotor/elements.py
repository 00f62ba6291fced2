"""Element matrices of the rotating Timoshenko shaft (Nelson & McVaugh 1976, Nelson 1980), discs and rods.

One bending plane, DOFs (displacement, rotation) at the two nodes, q = (d1, r1, d2, r2) with the
rotation r = slope for a slender shaft.  The interpolation is the one that solves the static
Timoshenko beam exactly (Przemieniecki; Nelson 1980, eq. 11), with the shear parameter
Phi = 12 E I / (kappa G A L^2) of the element and xi = x / L:

    N_d = [1 - 3xi^2 + 2xi^3 + Phi (1 - xi),  L (xi - 2xi^2 + xi^3 + Phi (xi - xi^2)/2),
           3xi^2 - 2xi^3 + Phi xi,            L (-xi^2 + xi^3 - Phi (xi - xi^2)/2)] / (1 + Phi)
    N_r = [6 (xi^2 - xi)/L,  1 - 4xi + 3xi^2 + Phi (1 - xi),  6 (xi - xi^2)/L,  -2xi + 3xi^2 + Phi xi] / (1 + Phi)

so that the shear strain N_d' - N_r is constant in the element.  The matrices are the integrals

    K   = int E I N_r'^T N_r' + kappa G A (N_d' - N_r)^T (N_d' - N_r) dx      (bending + shear)
    M_T = int (rho A + m_extra) N_d^T N_d dx,   R = int N_r^T N_r dx           (translation, rotation)

with the rotary inertia rho I R and, with the polar second moment I_p, the gyroscopic
coupling of the two planes (see :func:`lateral_matrices`).  They are integrated by 6-point
Gauss quadrature, exact for uniform elements (degree <= 6) and for linearly tapered ones
(A quadratic, I quartic in x: degree <= 10).  For Phi = 0 they are the Euler-Bernoulli Hermite
matrices (tests compare with scikit-fem's assembly of the Hermite element).

Why not a scikit-fem basis: the interpolation depends on each element's own Phi (it is not one
reference element mapped to every cell), and the matrices need no mesh machinery beyond a
line of nodes, so they are integrated here directly, vectorised over the elements.
"""
from __future__ import annotations

import numpy as np

_XI, _WG = np.polynomial.legendre.leggauss(6)
XI = 0.5 * (_XI + 1.0)          # Gauss points on [0, 1]
WG = 0.5 * _WG


def section_at(d0, d1, di0, di1, xi):
    """Area, second moment and polar second moment (m^2, m^4, m^4) of linearly tapered circular
    sections at the points xi (rows: elements given by arrays d0, d1, di0, di1 of shape (E,))."""
    d = d0[:, None] + (d1 - d0)[:, None] * xi[None, :]
    di = di0[:, None] + (di1 - di0)[:, None] * xi[None, :]
    A = np.pi * (d**2 - di**2) / 4.0
    I = np.pi * (d**4 - di**4) / 64.0
    return A, I, 2.0 * I


def shape_functions(L: np.ndarray, phi: np.ndarray, xi: np.ndarray = XI):
    """N_d, N_d', N_r, N_r' of shape (E, Q, 4) for element lengths ``L`` and shear parameters ``phi`` (E,)."""
    L = L[:, None]
    p = phi[:, None]
    x = xi[None, :]
    c = 1.0 / (1.0 + p)
    Nd = np.stack([1 - 3 * x**2 + 2 * x**3 + p * (1 - x),
                   L * (x - 2 * x**2 + x**3 + p * (x - x**2) / 2),
                   3 * x**2 - 2 * x**3 + p * x,
                   L * (-x**2 + x**3 - p * (x - x**2) / 2)], axis=-1) * c[..., None]
    dNd = np.stack([(-6 * x + 6 * x**2 - p) / L,
                    1 - 4 * x + 3 * x**2 + p * (1 - 2 * x) / 2,
                    (6 * x - 6 * x**2 + p) / L,
                    -2 * x + 3 * x**2 - p * (1 - 2 * x) / 2], axis=-1) * c[..., None]
    Nr = np.stack([6 * (x**2 - x) / L,
                   1 - 4 * x + 3 * x**2 + p * (1 - x),
                   6 * (x - x**2) / L,
                   -2 * x + 3 * x**2 + p * x], axis=-1) * c[..., None]
    dNr = np.stack([6 * (2 * x - 1) / L**2,
                    (-4 + 6 * x - p) / L,
                    6 * (1 - 2 * x) / L**2,
                    (-2 + 6 * x + p) / L], axis=-1) * c[..., None]
    return Nd, dNd, Nr, dNr


def _integrate(weight: np.ndarray, A: np.ndarray, B: np.ndarray, L: np.ndarray) -> np.ndarray:
    """int_0^L weight A^T B dx for (E, Q) weights and (E, Q, 4) functions -> (E, 4, 4)."""
    return np.einsum("eq,eqi,eqj->eij", weight * (WG[None, :] * L[:, None]), A, B, optimize=True)


def plane_matrices(L, E, G, rho, kappa, d0, d1, di0, di1, m_extra):
    """Per-element bending-plane matrices (E, 4, 4): stiffness K, translational mass M_T, the
    rotation Gram matrix R = int N_r^T N_r dx weighted by rho I (rotary inertia M_R) and by
    rho I_p (gyroscopic weight P); and the shear parameter Phi of each element (computed with
    the section at the element's middle, as in Nelson 1980 for tapered elements)."""
    A_mid, I_mid, _ = section_at(d0, d1, di0, di1, np.array([0.5]))
    phi = 12.0 * E * I_mid[:, 0] / (kappa * G * A_mid[:, 0] * L**2)
    A, I, Ip = section_at(d0, d1, di0, di1, XI)
    Nd, dNd, Nr, dNr = shape_functions(L, phi)
    gamma = dNd - Nr
    K = _integrate(E[:, None] * I, dNr, dNr, L) + _integrate(kappa[:, None] * G[:, None] * A, gamma, gamma, L)
    MT = _integrate(rho[:, None] * A + m_extra[:, None], Nd, Nd, L)
    MR = _integrate(rho[:, None] * I, Nr, Nr, L)
    P = _integrate(rho[:, None] * Ip, Nr, Nr, L)
    return K, MT, MR, P, phi


#: the x-z plane uses (w, psi) with psi = dw/dx = -theta_y: S maps (w, theta_y) to (w, psi)
S = np.diag([1.0, -1.0, 1.0, -1.0])


def lateral_matrices(K, MT, MR, P):
    """8 x 8 element matrices over (v1, theta_z1, v2, theta_z2, w1, theta_y1, w2, theta_y2).

    Plane x-y uses (v, theta_z) as it is; plane x-z uses S (w, theta_y).  Gyroscopic matrix:
    a slice of polar inertia rho I_p dx obeys the disc equations (Euler's equations, small tilt)
    rho I dx theta_y'' + rho I_p dx Omega theta_z' = m_y,  rho I dx theta_z'' - rho I_p dx Omega theta_y' = m_z,
    so G[theta_y rows, theta_z cols] = +int rho I_p N_{theta_y}^T N_{theta_z} dx with
    theta_z = N_r q_y and theta_y = -N_r S q_z:  G_zy = -S P,  G_yz = P S (G skew-symmetric)."""
    E = K.shape[0]
    Kl = np.zeros((E, 8, 8))
    Ml = np.zeros((E, 8, 8))
    Gl = np.zeros((E, 8, 8))
    Kl[:, :4, :4], Kl[:, 4:, 4:] = K, S @ K @ S
    Mp = MT + MR
    Ml[:, :4, :4], Ml[:, 4:, 4:] = Mp, S @ Mp @ S
    Gl[:, :4, 4:] = P @ S
    Gl[:, 4:, :4] = -S @ P
    return Kl, Ml, Gl


def rod_matrices(L, stiffness, inertia):
    """Linear (two-node) rod elements for axial (E A, rho A) or torsion (G J, rho I_p) with the
    properties varying along the element (values at the Gauss points, shape (E, Q)):
    K = int s N'^T N' dx, M = int m N^T N dx, N = (1 - xi, xi)."""
    N = np.stack([1 - XI, XI], axis=-1)[None, :, :].repeat(L.size, axis=0)
    dN = np.stack([-np.ones_like(XI), np.ones_like(XI)], axis=-1)[None, :, :] / L[:, None, None]
    w = WG[None, :] * L[:, None]
    K = np.einsum("eq,eqi,eqj->eij", stiffness * w, dN, dN)
    M = np.einsum("eq,eqi,eqj->eij", inertia * w, N, N)
    return K, M
