"""The harmonic bases of harmonic balance, shared by the numpy path (:mod:`.hb`) and the compiled kernel
(:mod:`.hb_kernel`): the real trigonometric basis at sample phases, and the index and sign maps of the
Galerkin products (cos a cos b = (cos(a - b) + cos(a + b)) / 2, ...)."""
from __future__ import annotations

from dataclasses import dataclass
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


def block_maps(H: int, W, D):
    """Gather maps of :meth:`.hb.HBModel.element_blocks`: with U = [C(cs), S(cs), Om C(cv), Om S(cv)]
    (the DFT sums of the two functions), ``B.flat = sum_r U[idx[r]] coef[r]`` -- the Galerkin matrix
    T(cs) of :func:`galerkin_maps` plus T(cv) D^T, whose column l is column p(l) of T(cv) times
    D[l, p(l)] (D has one entry per row)."""
    m = 2 * H + 1
    i1, i2, c1, c2 = galerkin_maps(H)
    half = (0.5 * np.asarray(W))[:, None]
    # column l of D^T: l = 2k - 1 (cos k) takes column 2k (sin k) times -k; l = 2k takes 2k - 1 times k
    p = np.zeros(m, int)
    dl = np.zeros(m)
    for k in range(1, H + 1):
        p[2 * k - 1], dl[2 * k - 1] = 2 * k, -k
        p[2 * k], dl[2 * k] = 2 * k - 1, k
    off = 2 * m
    idx = np.stack([i1, i2, off + i1[:, p], off + i2[:, p]]).reshape(4, -1)
    coef = np.stack([half * c1, half * c2, half * c1[:, p] * dl[None, :], half * c2[:, p] * dl[None, :]]).reshape(4, -1)
    return idx, coef


@dataclass(frozen=True)
class GridTables:
    """What a harmonic-balance model of H harmonics needs of its AFT grid of N phases: the phases theta,
    the basis G (2H+1, N) and its derivatives DG, DDG (d/dtheta: ``Q @ D``), D and D^2, the weights W
    and the projection Pm = G^T W (N, 2H+1), the Galerkin maps and the sparse map of the Jacobian's element
    blocks (:func:`block_maps`)."""

    theta: np.ndarray
    G: np.ndarray
    D: np.ndarray
    DD: np.ndarray
    DG: np.ndarray
    DDG: np.ndarray
    W: np.ndarray
    Pm: np.ndarray
    galerkin_maps: tuple
    block_map: object


@lru_cache(maxsize=32)
def grid_tables(H: int, N: int) -> GridTables:
    """The :class:`GridTables` of (H, N), computed once and shared read-only by every model on the grid."""
    from scipy.sparse import csr_matrix

    m = 2 * H + 1
    th = 2 * np.pi * np.arange(N) / N
    G = uniform_basis(H, N)
    D = np.zeros((m, m))
    for k in range(1, H + 1):
        D[2 * k, 2 * k - 1] = k       # d/dtheta: a_k' = k b_k, b_k' = -k a_k   (Qd = Q @ D)
        D[2 * k - 1, 2 * k] = -k
    W = np.full(m, 2.0 / N)
    W[0] = 1.0 / N
    idx, coef = block_maps(H, W, D)
    cols = np.repeat(np.arange(m * m)[None, :], 4, axis=0)
    block_map = csr_matrix((coef.ravel(), (cols.ravel(), idx.ravel())), shape=(m * m, 4 * m))
    arrays = dict(theta=th, G=G, D=D, DD=D @ D, DG=D @ G, DDG=D @ D @ G, W=W, Pm=G.T * W)
    for a in arrays.values():
        a.flags.writeable = False
    maps = galerkin_maps(H)
    for a in maps:
        a.flags.writeable = False
    return GridTables(**arrays, galerkin_maps=maps, block_map=block_map)
