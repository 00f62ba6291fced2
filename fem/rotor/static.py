"""Static deflection of a rotor under gravity and point loads, and the bearing loads.

K(Omega) q = f_gravity + f_points (consistent element loads of the shaft's weight, lumped weights
of discs, coupling halves and pedestals); the bearing loads are the forces the shaft puts on
each bearing, K_b (q_shaft - q_pedestal) (the stiffness at ``speed`` for tabulated bearings,
damping plays no part).  The result carries its equilibrium check: the ground reactions
(bearings to ground, pedestal springs, rigid supports) against the applied load.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from discrete.errors import ModelError

from .modal import as_system, check_speed


@dataclass
class PointLoad:
    """A static force at ``x`` (m): ``fy``, ``fz`` (N), and ``fx`` (N, ``dofs = "full"``)."""

    x: float
    fy: float = 0.0
    fz: float = 0.0
    fx: float = 0.0


@dataclass
class StaticResult:
    """Deflection along the shaft (m, rad) and bearing loads (N) at ``speed_rad_s``."""

    node_x: np.ndarray
    v: np.ndarray
    w: np.ndarray
    theta_y: np.ndarray
    theta_z: np.ndarray
    displacement: np.ndarray               # full DOF vector
    bearing_x: np.ndarray
    bearing_force: np.ndarray              # (n_bearings, 2): (F_y, F_z) the shaft puts on each bearing
    applied_force: np.ndarray              # (F_y, F_z) total applied lateral load
    reaction_force: np.ndarray             # (F_y, F_z) total reaction of the ground
    equilibrium_error: float               # |applied + reaction| / |applied|
    speed_rad_s: float
    warnings: list = field(default_factory=list)

    def to_dict(self) -> dict:
        return {"node_x": self.node_x.tolist(), "v": self.v.tolist(), "w": self.w.tolist(),
                "theta_y": self.theta_y.tolist(), "theta_z": self.theta_z.tolist(),
                "bearing_x": self.bearing_x.tolist(), "bearing_force": self.bearing_force.tolist(),
                "applied_force": self.applied_force.tolist(), "reaction_force": self.reaction_force.tolist(),
                "equilibrium_error": self.equilibrium_error, "speed_rad_s": self.speed_rad_s,
                "warnings": list(self.warnings)}


def static_deflection(rotor, *, gravity=(0.0, 0.0, -9.81), loads=(), speed: float = 0.0) -> StaticResult:
    """Deflection of ``rotor`` under ``gravity`` (g_x, g_y, g_z in m/s^2; default -z down) and
    ``loads`` (:class:`PointLoad`), with tabulated bearings taken at ``speed`` (rad/s)."""
    rs = as_system(rotor)
    speed = check_speed(speed)
    g = np.asarray(gravity, dtype=float).ravel()
    if g.shape != (3,) or not np.all(np.isfinite(g)):
        raise ModelError("[analysis]", "gravity", list(np.atleast_1d(gravity)), "three finite numbers (g_x, g_y, g_z), m/s^2")
    f = rs.gravity_load(g)
    for i, p in enumerate(loads, 1):
        where = f"[[load]] #{i}"
        if not isinstance(p, PointLoad):
            raise ModelError(where, "load", p, "a fem.rotor.static.PointLoad(x, fy, fz, fx)")
        for key in ("fy", "fz", "fx"):
            if not np.isfinite(getattr(p, key)):
                raise ModelError(where, key, getattr(p, key), "a finite force (N)")
        f[rs.dof(p.x, "v", where)] += p.fy
        f[rs.dof(p.x, "w", where)] += p.fz
        if p.fx:
            if "u" not in rs.node_dofs:
                raise ModelError(where, "fx", p.fx, "0 for a lateral model (dofs = 'lateral')")
            f[rs.dof(p.x, "u", where)] += p.fx
    K = rs.stiffness(speed)
    free = np.ones(rs.n_dofs, dtype=bool)
    free[rs.constrained] = False
    # axial and torsional motion decouple from the lateral (linear beam): unloaded, they stay at zero,
    # so a 'full' model without axial or torsional restraint still has its sag under lateral loads
    for fld in ("u", "theta_x"):
        idx = np.flatnonzero(rs.dof_field == fld)
        if idx.size and not np.any(f[idx]):
            free[idx] = False
    fi = np.flatnonzero(free)
    Kff = sp.csc_matrix(K[fi][:, fi])
    try:
        lu = spla.splu(Kff)
        piv = np.abs(lu.U.diagonal())
        singular = piv.min() <= 1e3 * np.finfo(float).eps * piv.max()
    except RuntimeError:
        singular = True
    if singular:
        raise ModelError("[[rotor.bearing]]", "supports", len(rs.rotor.bearings) + len(rs.rotor.supports),
                         "bearings or supports that hold the rotor (the stiffness is singular: a free rotor, or "
                         "axial/torsional motion without restraint in a 'full' model) for a static deflection")
    q = np.zeros(rs.n_dofs)
    q[fi] = lu.solve(f[fi])
    resid = np.linalg.norm(Kff @ q[fi] - f[fi]) / max(np.linalg.norm(f[fi]), 1e-300)
    notes = [] if resid < 1e-8 else [f"static solve residual {resid:.1e}"]
    # bearing loads: K_b d with d = q_shaft - q_pedestal (stiffness at the speed)
    bx, bf = [], []
    for b_no, b in enumerate(rs.rotor.bearings):
        if b.speed_dependent:
            t = rs.tables[[tb.index for tb in rs.tables].index(b_no + 1)]
            c = t.at(speed)[0]
            Kb = np.array([[c[0], c[1]], [c[2], c[3]]])
        else:
            tab = b.table()
            Kb = np.array([[tab["kyy"][0], tab["kyz"][0]], [tab["kzy"][0], tab["kzz"][0]]])
        node = rs.node(b.x)
        d = np.array([q[rs.node_dofs["v"][node]], q[rs.node_dofs["w"][node]]])
        if b.pedestal is not None:
            iv = np.flatnonzero((rs.dof_field == "pedestal_v") & (rs.dof_name == b.pedestal))[0]
            iw = np.flatnonzero((rs.dof_field == "pedestal_w") & (rs.dof_name == b.pedestal))[0]
            d = d - np.array([q[iv], q[iw]])
        bx.append(b.x)
        bf.append(Kb @ d)
    # equilibrium: the forces of the ground on the structure (bearings to ground, pedestal
    # springs, rigid supports) must balance the applied load
    reaction = np.zeros(2)
    for b in rs.rotor.bearings:
        if b.pedestal is None:
            reaction -= bf[rs.rotor.bearings.index(b)]
    for p in rs.rotor.pedestals:
        iv = np.flatnonzero((rs.dof_field == "pedestal_v") & (rs.dof_name == p.name))[0]
        iw = np.flatnonzero((rs.dof_field == "pedestal_w") & (rs.dof_name == p.name))[0]
        reaction -= np.array([p.kyy * q[iv], p.kzz * q[iw]])
    if rs.constrained.size:
        r_c = K[rs.constrained] @ q - f[rs.constrained]          # the support's force on the rotor
        fld = rs.dof_field[rs.constrained]
        reaction += np.array([r_c[fld == "v"].sum(), r_c[fld == "w"].sum()])
    lat_v = np.isin(rs.dof_field, ("v", "pedestal_v"))
    lat_w = np.isin(rs.dof_field, ("w", "pedestal_w"))
    applied = np.array([f[lat_v].sum(), f[lat_w].sum()])
    err = float(np.linalg.norm(applied + reaction) / max(np.linalg.norm(applied), 1e-300))
    nd = rs.node_dofs
    return StaticResult(node_x=rs.node_x, v=q[nd["v"]], w=q[nd["w"]], theta_y=q[nd["theta_y"]], theta_z=q[nd["theta_z"]],
                        displacement=q, bearing_x=np.asarray(bx), bearing_force=np.asarray(bf).reshape(-1, 2),
                        applied_force=applied, reaction_force=reaction, equilibrium_error=err, speed_rad_s=speed,
                        warnings=notes)
