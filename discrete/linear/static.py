"""Static deflection K q = F of a :class:`LinearSystem` (flexibility checks of Table 3.1)."""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import ModelError, SolverError
from ..linear_system import LinearSystem

from .harmonic import load_vector
from .modal import as_linear_system


def static_deflection(system: LinearSystem, force: np.ndarray) -> np.ndarray:
    """Full-length displacement vector for the full-length load ``force`` (constrained DOFs 0).

    An under-constrained model (rigid-body modes) is an error naming the missing supports.
    """
    system = as_linear_system(system, "static_deflection")
    F = load_vector(force, system.n_dofs, "force", complex_ok=False)
    n_rigid = 0 if system.rigid_modes is None else system.rigid_modes.shape[1]
    if n_rigid:
        raise ModelError("[[support]]", "supports", system.constrained.size,
                         f"supports that prevent rigid-body motion: the model has {n_rigid} rigid-body mode(s), "
                         "so the static problem K q = F is singular")
    try:
        lu = spla.splu(sp.csc_matrix(system.free_block(system.K)))
    except RuntimeError as exc:
        raise SolverError("the stiffness matrix is singular (under-constrained model): add supports") from exc
    q = lu.solve(F[system.free])
    return system.expand(q)
