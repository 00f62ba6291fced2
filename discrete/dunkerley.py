"""Dunkerley's lower bound of the fundamental frequency (4.37)-(4.40)."""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .errors import ModelError
from .linear_system import LinearSystem


def dunkerley_bound(system: LinearSystem) -> float:
    """k_1 >= 1 / sqrt(trace(e m)) with e = K^-1 the flexibility matrix (4.40).

    By Vieta (4.38) trace(K^-1 M) = sum_r k_r^-2, so the bound holds for any grounded
    system (lumped or consistent mass); it needs a non-singular K on the free DOFs.
    """
    K = sp.csc_matrix(system.free_block(system.K))
    M = sp.csc_matrix(system.free_block(system.M))
    if system.rigid_modes is not None and system.rigid_modes.shape[1]:
        raise ModelError("", "supports", "none", "a grounded system (Dunkerley's estimate needs K^-1)")
    try:
        lu = spla.splu(K)
    except RuntimeError as exc:
        raise ModelError("", "supports", "none", "a grounded system (K is singular)") from exc
    Md = M.toarray() if M.shape[0] <= 2000 else None
    if Md is None:
        raise ModelError("", "n_dofs", M.shape[0], "at most 2000 free DOFs for the Dunkerley estimate")
    trace = float(np.trace(lu.solve(Md)))
    return 1.0 / np.sqrt(trace)
