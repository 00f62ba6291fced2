"""Exact periodic steady state of m x'' + c x' + k x = F(t) under a rectangular F (F1 for the fraction duty of
each period T, F2 for the rest): on each constant piece the state z = (x, x') obeys z' = A z + b F, solved
exactly by matrix exponentials; the periodic state is the fixed point z0 = Phi2 Phi1 z0 + (the forced parts),
a 2x2 linear solve.  Independent of the Fourier superposition it checks (no series at all)."""
from __future__ import annotations

import numpy as np
from scipy.linalg import expm


def sdof_rectangular(m: float, c: float, k: float, F1: float, F2: float, duty: float, T: float, t) -> np.ndarray:
    """x(t) of the periodic steady state at the instants t (any real t, taken modulo T)."""
    A = np.array([[0.0, 1.0], [-k / m, -c / m]])
    b = np.array([0.0, 1.0 / m])
    zs = -np.linalg.solve(A, b)                     # static state per unit force: A zs + b = 0

    def piece(z0, F, tau):
        """State after tau on a piece of constant F: z = zs F + e^{A tau} (z0 - zs F)."""
        return zs * F + expm(A * tau) @ (z0 - zs * F)

    t1 = duty * T
    P1, P2 = expm(A * t1), expm(A * (T - t1))
    # z0 = P2 (zs F2 + ... ) : z(T) = zs F2 + P2 (zs F1 + P1 (z0 - zs F1) - zs F2) = z0
    rhs = zs * F2 + P2 @ (zs * F1 - zs * F2) - P2 @ P1 @ (zs * F1)
    z0 = np.linalg.solve(np.eye(2) - P2 @ P1, rhs)
    z1 = piece(z0, F1, t1)
    out = []
    for ti in np.mod(np.atleast_1d(np.asarray(t, float)), T):
        out.append(piece(z0, F1, ti)[0] if ti < t1 else piece(z1, F2, ti - t1)[0])
    return np.array(out)
