"""The condensed linear operator of :mod:`discrete.steady.condense` at one frequency, compiled by numba
(``DRIVEFEM_JIT=0`` runs the same source as plain Python): for k = 0 .. H, with ``s = i k Om`` and
``Z = K + s C + s^2 M``,

    X = Z_ll^-1 Z_lc,  w = Z_ll^-1 f_l,  Y = Z_cl Z_ll^-1,
    S = Z_cc - Z_cl X,                  dS = dZ_cc - dZ_cl X - Y dZ_lc + Y dZ_ll X,
    f~ = f_c - Z_cl w,                  df~ = df_c - dZ_cl w - Y df_l + Y dZ_ll w,

``dZ = (C + 2 s M) i k / nu`` the derivative in omega.  The same algebra as the batched numpy version in
``CondensedHB.operator`` (which checks it, tests/test_steady_condense.py): one small LU per harmonic,
without the ~30 numpy calls per frequency that dominate it for a few DOFs.
"""
from __future__ import annotations

import numpy as np

from ..jit import JIT, njit  # noqa: F401  (JIT: whether numba compiles this module)


@njit(cache=True)
def _lu(A):
    """In-place LU with partial pivoting of a small complex matrix; returns the pivots (-1: singular)."""
    n = A.shape[0]
    piv = np.arange(n)
    for j in range(n):
        p = j
        best = abs(A[j, j])
        for i in range(j + 1, n):
            if abs(A[i, j]) > best:
                best = abs(A[i, j])
                p = i
        if best == 0.0:
            piv[0] = -1
            return piv
        if p != j:
            for q in range(n):
                A[j, q], A[p, q] = A[p, q], A[j, q]
            piv[j], piv[p] = piv[p], piv[j]
        for i in range(j + 1, n):
            A[i, j] /= A[j, j]
            f = A[i, j]
            for q in range(j + 1, n):
                A[i, q] -= f * A[j, q]
    return piv


@njit(cache=True)
def _solve(LU, piv, B):
    """Z^-1 B for the LU of Z (pivots ``piv``); B (n, m) complex."""
    n, m = B.shape
    X = np.empty_like(B)
    for i in range(n):
        for q in range(m):
            X[i, q] = B[piv[i], q]
    for i in range(n):
        for j in range(i):
            for q in range(m):
                X[i, q] -= LU[i, j] * X[j, q]
    for i in range(n - 1, -1, -1):
        for j in range(i + 1, n):
            for q in range(m):
                X[i, q] -= LU[i, j] * X[j, q]
        for q in range(m):
            X[i, q] /= LU[i, i]
    return X


@njit(cache=True)
def _solve_t(LU, piv, B):
    """Z^-T B for the LU of Z: Z^T = U^T L^T P, so solve U^T y = B, L^T z = y, then un-pivot."""
    n, m = B.shape
    Y = B.copy()
    for i in range(n):
        for j in range(i):
            for q in range(m):
                Y[i, q] -= LU[j, i] * Y[j, q]
        for q in range(m):
            Y[i, q] /= LU[i, i]
    for i in range(n - 1, -1, -1):
        for j in range(i + 1, n):
            for q in range(m):
                Y[i, q] -= LU[j, i] * Y[j, q]
    X = np.empty_like(B)
    for i in range(n):
        for q in range(m):
            X[piv[i], q] = Y[i, q]
    return X


@njit(cache=True)
def _mm(A, B, out, sign):
    """out += sign * A @ B for small complex matrices (explicit loops: no BLAS call per product)."""
    n, m = A.shape
    q = B.shape[1]
    for i in range(n):
        for j in range(q):
            acc = 0j
            for r in range(m):
                acc += A[i, r] * B[r, j]
            out[i, j] += sign * acc


@njit(cache=True)
def operator(M, C, K, c, l, F, omega, nu, symmetric):
    """(S, dS, f~, df~, X, w, ok) for k = 0 .. H (module docstring); ``F`` (4, H+1, n) the forcing's
    complex harmonics by powers of omega (f = F0 + F1 / omega + omega F2 + omega^2 F3); ok False when a
    Z_ll is singular."""
    H1 = F.shape[1]
    nc, nl = c.size, l.size
    n = M.shape[0]
    S = np.empty((H1, nc, nc), np.complex128)
    dS = np.empty((H1, nc, nc), np.complex128)
    ft = np.empty((H1, nc), np.complex128)
    dft = np.empty((H1, nc), np.complex128)
    Xo = np.empty((H1, nl, nc), np.complex128)
    wo = np.empty((H1, nl), np.complex128)
    Z = np.empty((n, n), np.complex128)
    dZ = np.empty((n, n), np.complex128)
    f = np.empty(n, np.complex128)
    df = np.empty(n, np.complex128)
    LU = np.empty((nl, nl), np.complex128)
    RHS = np.empty((nl, nc + 1), np.complex128)
    Zcl = np.empty((nc, nl), np.complex128)
    Y = np.empty((nc, nl), np.complex128)
    YdZll = np.empty((nc, nl), np.complex128)
    dZll = np.empty((nl, nl), np.complex128)
    dZlc = np.empty((nl, nc), np.complex128)
    dZcl = np.empty((nc, nl), np.complex128)
    Om = omega / nu
    for k in range(H1):
        s = 1j * k * Om
        ds = 1j * k / nu
        for i in range(n):
            f[i] = F[0, k, i] + F[1, k, i] / omega + omega * F[2, k, i] + omega * omega * F[3, k, i]
            df[i] = -F[1, k, i] / (omega * omega) + F[2, k, i] + 2.0 * omega * F[3, k, i]
            for j in range(n):
                Z[i, j] = K[i, j] + s * C[i, j] + s * s * M[i, j]
                dZ[i, j] = (C[i, j] + 2.0 * s * M[i, j]) * ds
        for i in range(nc):
            ft[k, i] = f[c[i]]
            dft[k, i] = df[c[i]]
            for j in range(nc):
                S[k, i, j] = Z[c[i], c[j]]
                dS[k, i, j] = dZ[c[i], c[j]]
        if nl == 0:
            continue
        for i in range(nl):
            for j in range(nl):
                LU[i, j] = Z[l[i], l[j]]
                dZll[i, j] = dZ[l[i], l[j]]
            for j in range(nc):
                RHS[i, j] = Z[l[i], c[j]]
                dZlc[i, j] = dZ[l[i], c[j]]
                Zcl[j, i] = Z[c[j], l[i]]
                dZcl[j, i] = dZ[c[j], l[i]]
            RHS[i, nc] = f[l[i]]
        piv = _lu(LU)
        if piv[0] < 0:
            return S, dS, ft, dft, Xo, wo, False
        sol = _solve(LU, piv, RHS)
        X = np.ascontiguousarray(sol[:, :nc])
        w = sol[:, nc].copy()
        if symmetric:
            for i in range(nc):
                for j in range(nl):
                    Y[i, j] = X[j, i]
        else:
            Yt = _solve_t(LU, piv, np.ascontiguousarray(Zcl.T))
            for i in range(nc):
                for j in range(nl):
                    Y[i, j] = Yt[j, i]
        YdZll[:, :] = 0.0
        _mm(Y, dZll, YdZll, 1.0)
        _mm(Zcl, X, S[k], -1.0)
        _mm(dZcl, X, dS[k], -1.0)
        _mm(Y, dZlc, dS[k], -1.0)
        _mm(YdZll, X, dS[k], 1.0)
        for i in range(nc):
            for j in range(nl):
                ft[k, i] -= Zcl[i, j] * w[j]
                dft[k, i] += -dZcl[i, j] * w[j] - Y[i, j] * df[l[j]] + YdZll[i, j] * w[j]
        Xo[k] = X
        wo[k] = w
    return S, dS, ft, dft, Xo, wo, True


@njit(cache=True)
def real_jacobian(S):
    """The real (nc m)^2 Jacobian of Re/-Im (S_k z_k) in the coefficients [a0, a1, b1, ...] per DOF
    (CondensedHB._real_jacobian): blocks [[Sr, Si], [-Si, Sr]] of harmonic k >= 1, Sr of k = 0; and
    whether S is finite."""
    H1, nc, _ = S.shape
    m = 2 * H1 - 1
    J = np.zeros((nc * m, nc * m))
    finite = True
    for i in range(nc):
        for j in range(nc):
            z = S[0, i, j]
            if not (np.isfinite(z.real) and np.isfinite(z.imag)):
                finite = False
            J[i * m, j * m] = z.real
            for k in range(1, H1):
                z = S[k, i, j]
                if not (np.isfinite(z.real) and np.isfinite(z.imag)):
                    finite = False
                a, b = i * m + 2 * k - 1, j * m + 2 * k - 1
                J[a, b] = z.real
                J[a, b + 1] = z.imag
                J[a + 1, b] = -z.imag
                J[a + 1, b + 1] = z.real
    return J, finite


@njit(cache=True)
def linear_residual(S, f, Q):
    """The real layout (nc m,) of ``S_k z_k - f_k`` (z_k = a_k - i b_k the complex coefficients of Q (nc, m))
    -- the condensed linear part of the residual, or of its omega derivative with dS, df."""
    H1, nc, _ = S.shape
    m = 2 * H1 - 1
    out = np.empty(nc * m)
    for i in range(nc):
        for k in range(H1):
            acc = -f[k, i]
            for j in range(nc):
                z = Q[j, 0] + 0j if k == 0 else Q[j, 2 * k - 1] - 1j * Q[j, 2 * k]
                acc += S[k, i, j] * z
            if k == 0:
                out[i * m] = acc.real
            else:
                out[i * m + 2 * k - 1] = acc.real
                out[i * m + 2 * k] = -acc.imag
    return out


@njit(cache=True)
def expand(Qc, c, l, X, wf):
    """Full coefficients (n, m) of the condensed ones Qc (nc, m): z_l = wf - X z_c per harmonic."""
    nc, m = Qc.shape
    H1 = (m + 1) // 2
    n = nc + l.size
    Q = np.empty((n, m))
    for i in range(nc):
        for q in range(m):
            Q[c[i], q] = Qc[i, q]
    for r in range(l.size):
        for k in range(H1):
            acc = wf[k, r]
            for j in range(nc):
                z = Qc[j, 0] + 0j if k == 0 else Qc[j, 2 * k - 1] - 1j * Qc[j, 2 * k]
                acc -= X[k, r, j] * z
            if k == 0:
                Q[l[r], 0] = acc.real
            else:
                Q[l[r], 2 * k - 1] = acc.real
                Q[l[r], 2 * k] = -acc.imag
    return Q
