"""The harmonic bases of harmonic balance, shared by the numpy path (:mod:`.hb`) and the compiled kernel
(:mod:`.hb_kernel`): the real trigonometric basis at sample phases, and the index and sign maps of the
Galerkin products (cos a cos b = (cos(a - b) + cos(a + b)) / 2, ...)."""
from __future__ import annotations

from functools import lru_cache

import numpy as np


def basis(H: int, th) -> np.ndarray:
    """[1, cos th, sin th, ..., cos H th, sin H th] at the phases th: (2H+1, len(th))."""
    G = np.ones((2 * H + 1, np.size(th)))
    for k in range(1, H + 1):
        G[2 * k - 1] = np.cos(k * th)
        G[2 * k] = np.sin(k * th)
    return G


@lru_cache(maxsize=32)
def uniform_basis(H: int, N: int) -> np.ndarray:
    """:func:`basis` at the N equidistant phases 2 pi n / N (the AFT grid), computed once per (H, N) and
    shared read-only by every model on that grid (the same values as ``basis``)."""
    G = basis(H, 2 * np.pi * np.arange(N) / N)
    G.flags.writeable = False
    return G


@lru_cache(maxsize=32)
def uniform_dft_table(J: int, N: int) -> tuple[np.ndarray, np.ndarray]:
    """cos(j th_n), sin(j th_n) (J + 1, N) for j = 0..J at th_n = 2 pi n / N (the compiled kernel's DFT
    sums), computed once per (J, N) and shared read-only."""
    arg = np.multiply.outer(np.arange(J + 1), 2 * np.pi * np.arange(N) / N)
    C, S = np.cos(arg), np.sin(arg)
    C.flags.writeable = S.flags.writeable = False
    return C, S


def galerkin_maps(H: int):
    """Index and sign maps of :meth:`.hb.HBModel.galerkin`: with V = [C_0..C_2H, S_0..S_2H] (the sums of
    c cos(j th), c sin(j th)), T[k, l] = W_k / 2 (c1 V[i1] + c2 V[i2])."""
    m = 2 * H + 1
    freq = np.array([0] + [k for k in range(1, H + 1) for _ in (0, 1)])
    sine = np.array([False] + [s for _ in range(1, H + 1) for s in (False, True)])
    a, b = freq[:, None], freq[None, :]
    sk, sl = sine[:, None], sine[None, :]
    d, p = np.abs(a - b), a + b
    sgn = np.sign(a - b)
    off = 2 * H + 1
    same = sk == sl
    # cos-cos: C_d + C_p;  sin-sin: C_d - C_p;  cos(k) sin(l): S_p - sgn S_d;  sin(k) cos(l): S_p + sgn S_d
    i1 = np.where(same, d, off + p)
    i2 = np.where(same, p, off + d)
    c1 = np.ones((m, m))
    c2 = np.where(same, np.where(sk, -1.0, 1.0), np.where(sk, sgn, -sgn)).astype(float)
    return i1, i2, c1, c2
