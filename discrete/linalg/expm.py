"""Matrix exponential of small dense matrices (the exact pieces of the event-driven solver)."""
from __future__ import annotations

import numpy as np

_PADE6 = (1.0, 1.0 / 2, 5.0 / 44, 1.0 / 66, 1.0 / 792, 1.0 / 15840, 1.0 / 665280)


def expm_small(M: np.ndarray) -> np.ndarray:
    """Matrix exponential of a small matrix: diagonal [6/6] Pade approximant with scaling to a
    1-norm <= 1/2 (truncation ~1e-20) and squaring, using only numpy matmul/solve.  scipy's expm
    is equally accurate and fast single-threaded, but its kernel can be slowed 10-100x by BLAS
    thread contention on a loaded machine."""
    n = M.shape[0]
    n1 = float(np.max(np.sum(np.abs(M), axis=0))) if M.size else 0.0
    I = np.eye(n)
    if n1 == 0.0:
        return I
    s = 0
    if n1 > 0.5:
        s = int(np.ceil(np.log2(n1 / 0.5)))
        M = M / (2.0 ** s)
    b = _PADE6
    M2 = M @ M
    M4 = M2 @ M2
    M6 = M4 @ M2
    U = M @ (b[1] * I + b[3] * M2 + b[5] * M4)
    V = b[0] * I + b[2] * M2 + b[4] * M4 + b[6] * M6
    E = np.linalg.solve(V - U, V + U)
    for _ in range(s):
        E = E @ E
    return E


def expm_batch(X: np.ndarray) -> np.ndarray:
    """exp of a batch (P, m, m): the diagonal [6/6] Pade approximant after scaling each matrix to a
    1-norm <= 1/2 (truncation ~1e-20) and squaring back -- the scheme of
    :func:`expm_small`, vectorised over the batch.  scipy.linalg.expm accepts
    batches but loops over the matrices in Python (~15 us each): measured 3-10x slower here."""
    m = X.shape[-1]
    norm = np.abs(X).sum(axis=-2).max(axis=-1)
    s = np.maximum(0, np.ceil(np.log2(np.maximum(norm, 1e-300) / 0.5))).astype(int)
    Y = X / (2.0 ** s)[:, None, None]
    b = _PADE6
    I = np.eye(m)
    Y2 = Y @ Y
    Y4 = Y2 @ Y2
    U = Y @ (b[1] * I + b[3] * Y2 + b[5] * Y4)
    V = b[0] * I + b[2] * Y2 + b[4] * Y4 + b[6] * (Y4 @ Y2)
    E = np.linalg.solve(V - U, V + U)
    for k in range(int(s.max()) if s.size else 0):
        sq = s > k
        E[sq] = E[sq] @ E[sq]
    return E
