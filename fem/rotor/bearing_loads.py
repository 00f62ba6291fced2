"""Bearing reactions of a rotor: the force each bearing (or seal) exerts on the shaft,
f = -K(Omega) d - C(Omega) d' with d the shaft node's lateral displacement relative to its pedestal
(or the ground) -- the law of :class:`fem.rotor.model.Bearing`, its tabulated coefficients interpolated
at the speed as the assembly does.  For a run-up (time histories, the speed of each sample) and for the
unbalance response (complex amplitudes, d' = i Omega d)."""
from __future__ import annotations

import numpy as np

from .model import BEARING_COEFFICIENTS


def bearing_name(b, index: int) -> str:
    """The bearing's name in the outputs: its ``name``, else ``bearing[<index>] x=<x>``."""
    return b.name or f"bearing[{index}] x={b.x:g}"


def _coefficients(rs, index: int, speeds: np.ndarray) -> dict:
    """{coefficient: (n_speeds,) values} of bearing number ``index`` at the speeds (the assembly's tables)."""
    from ..loads.reactions import _bearing_coefficients

    vals = _bearing_coefficients(rs, speeds)[index - 1]
    return {k: vals[:, j] for j, k in enumerate(BEARING_COEFFICIENTS)}


def bearing_forces(rs, speeds, disp, vel=None, linear_only: bool = False) -> dict:
    """{bearing name: (F_y, F_z)} of every bearing: ``disp(dofs)`` gives the displacements of those DOFs
    at the samples ((n_samples, len(dofs)), real, or complex amplitudes), ``vel(dofs)`` their rates
    (None: i Omega times the displacements, a synchronous response); ``speeds`` (n_samples,) rad/s.
    ``linear_only``: leave out the bearings that run with their own nonlinear law (a run-up)."""
    speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
    ped = {p.name: i for i, p in enumerate(rs.rotor.pedestals)}
    n_shaft = rs.n_dofs - 2 * len(ped)
    out = {}
    for k, b in enumerate(rs.rotor.bearings, 1):
        if linear_only and getattr(b, "nonlinear", False):
            continue
        idx = [rs.dof(b.x, "v", f"bearing {k}"), rs.dof(b.x, "w", f"bearing {k}")]
        if b.pedestal is not None:
            idx += [n_shaft + 2 * ped[b.pedestal], n_shaft + 2 * ped[b.pedestal] + 1]
        q = np.asarray(disp(idx))
        qd = 1j * speeds[:, None] * q if vel is None else np.asarray(vel(idx))
        d, dd = q[:, :2].T, qd[:, :2].T
        if b.pedestal is not None:
            d, dd = d - q[:, 2:].T, dd - qd[:, 2:].T
        c = _coefficients(rs, k, speeds)
        fy = -(c["kyy"] * d[0] + c["kyz"] * d[1]) - (c["cyy"] * dd[0] + c["cyz"] * dd[1])
        fz = -(c["kzy"] * d[0] + c["kzz"] * d[1]) - (c["czy"] * dd[0] + c["czz"] * dd[1])
        out[bearing_name(b, k)] = (fy, fz)
    return out
