"""The discrete FE/lumped representation of a drive: a :class:`LinearSystem` with the shaft's
DOFs (lumped discs, or a scikit-fem torsion mesh with nodes at the stations) plus one DOF y_j
per mechanism output.  Mechanism j adds the potential 1/2 c (y_j - Pi' theta(x_j))^2 and the
kinetic energy 1/2 m y_j'^2, i.e. K += c [[Pi'^2, -Pi'], [-Pi', 1]] on (theta_j, y_j) and
M += m on y_j; a grounded output holds y_j = 0 (the spring then acts as c Pi'^2 to ground)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from discrete.linear_system import LinearSystem

from .model import DistributedShaft, DriveModel


@dataclass
class DiscreteDrive:
    system: LinearSystem
    theta: np.ndarray      # DOF index of theta at each station
    y: np.ndarray          # DOF index of each mechanism output
    fe: object = None      # FEModel of a distributed shaft (None for a lumped shaft)


def _lumped_shaft(model: DriveModel):
    """Discs at the stations, segments c0 between them (and to the clamps)."""
    n, c0, J0 = model.n, model.shaft.c0, model.shaft.J0
    rows, cols, vals = [], [], []

    def add(i, j, v):
        rows.append(i), cols.append(j), vals.append(v)

    for j in range(n - 1):       # springs between consecutive discs
        add(j, j, c0), add(j + 1, j + 1, c0), add(j, j + 1, -c0), add(j + 1, j, -c0)
    if model.start == "clamped":
        add(0, 0, c0)
    if model.end == "clamped":
        add(n - 1, n - 1, c0)
    K = sp.coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsr()
    M = sp.diags(np.full(n, J0)).tocsr()
    if model.mechanism.rigid:
        M = M + sp.diags(np.full(n, model.mechanism.m * model.mechanism.ratio**2))
    return K, M, np.arange(n), model.stations(), []


def _distributed_shaft(model: DriveModel):
    from fem import Material, PointAttachment, Section, Segment, ShaftModel, Support, assemble

    sh: DistributedShaft = model.shaft
    mat = Material(E=sh.GI, G=sh.GI, rho=sh.rho)
    sec = Section(A=1.0, I=1.0, J=1.0, Ip=1.0)
    h = model.segment_length
    segs = [Segment(h, sh.elements, sec, mat) for _ in range(model.n_segments)]
    sups = []
    if model.start == "clamped":
        sups.append(Support(0.0, "clamped"))
    if model.end == "clamped":
        sups.append(Support(model.length, "clamped"))
    me = model.mechanism
    J = sh.J0 + (me.m * me.ratio**2 if me.rigid else 0.0)
    pts = [PointAttachment(x=float(x), inertia=J) for x in model.stations()] if J else []
    fe = assemble(ShaftModel(physics="torsion", segments=segs, supports=sups, points=pts, order=sh.order,
                             mass=sh.mass, title=model.title))
    s = fe.system
    theta = np.array([s.dof_index(field="theta", x=float(x), where="[drive]") for x in model.stations()])
    return s.K, s.M, theta, s.dof_x, list(s.constrained), fe


def build_discrete(model: DriveModel, *, delta: float = 0.0) -> DiscreteDrive:
    """Assemble the drive; ``delta`` (hysteretic, psi/(4 pi)) puts H = 2 delta K for forced response."""
    fe = None
    if isinstance(model.shaft, DistributedShaft):
        Ks, Ms, theta, xs, constrained, fe = _distributed_shaft(model)
        fields = list(fe.system.dof_field)
    else:
        Ks, Ms, theta, xs, constrained = _lumped_shaft(model)
        fields = ["theta"] * model.n
    ns, n = Ks.shape[0], model.n
    me = model.mechanism
    if me.rigid:
        sys_ = LinearSystem(M=Ms, K=Ks, H=2 * delta * Ks if delta else None, dof_field=np.array(fields, dtype=object),
                            dof_x=np.asarray(xs, float), constrained=np.array(constrained, dtype=int),
                            rigid_modes=_rigid(model, ns, theta, np.zeros(0, int), ns, fe), title=model.title,
                            physics="torsion")
        return DiscreteDrive(system=sys_, theta=theta, y=np.zeros(0, dtype=int), fe=fe)
    y = ns + np.arange(n)
    P = me.ratio
    rows = np.concatenate([theta, theta, y, y])
    cols = np.concatenate([theta, y, theta, y])
    vals = np.concatenate([np.full(n, me.c * P * P), np.full(n, -me.c * P), np.full(n, -me.c * P), np.full(n, me.c)])
    N = ns + n
    K = sp.block_diag([Ks, sp.csr_matrix((n, n))]).tocsr() + sp.coo_matrix((vals, (rows, cols)), shape=(N, N)).tocsr()
    M = sp.block_diag([Ms, sp.diags(np.full(n, me.m))]).tocsr()
    if me.output == "grounded":
        constrained = list(constrained) + list(y)
    dof_x = np.concatenate([np.asarray(xs, float), model.stations()])
    names = np.array([""] * ns + [f"mechanism{j + 1}" for j in range(n)], dtype=object)
    field = np.array(fields + ["y"] * n, dtype=object)
    sys_ = LinearSystem(M=M, K=K, H=2 * delta * K if delta else None, dof_field=field, dof_x=dof_x, dof_name=names,
                        constrained=np.array(constrained, dtype=int),
                        rigid_modes=_rigid(model, N, theta, y, ns, fe), title=model.title, physics="torsion")
    return DiscreteDrive(system=sys_, theta=theta, y=y, fe=fe)


def _rigid(model, N, theta, y, ns, fe):
    """Free-free drive: one rigid rotation (theta = 1 everywhere, y = Pi')."""
    if model.boundary != "free-free" or model.mechanism.output == "grounded":
        return np.zeros((N, 0))
    r = np.zeros((N, 1))
    r[:ns, 0] = 1.0
    r[y, 0] = model.mechanism.ratio
    return r
