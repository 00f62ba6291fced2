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
