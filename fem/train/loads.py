"""Loads of a train: the force of every connection by its own law, the reaction of every bearing and
support, and the force balance of every shaft.

Bearing reaction (force of the bearing on the shaft, N): f = -K_b d - C_b d' with d = (v, w) of the shaft
node relative to its pedestal (rotor bearings, K_b and C_b at the shaft's own speed), and the thrust
f_x = -k_axial u - c_axial u'.  Support reaction: the force a held DOF needs, the row of the held DOF
in the equations of motion, R_c = (M a + (C + Omega G) v + K q)_c - f_c.

Force balance of a shaft (or body) in a direction d (torsion about x, y, z, axial x): with r_d the rigid
motion of that shaft in that direction (unit translation of every node, or unit rotation about x),
r_d^T (M a + C_int v + K_int q) = r_d^T (f_applied + f_bearings + f_supports + f_connections): the
shaft's internal forces do no work on a rigid motion (r_d^T K_int = 0).  The residual of this sum,
relative to its largest term, is the check that every force is accounted for (round-off).
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import scipy.sparse as sp

from ..rotor.assembly import assemble_rotor
from ..rotor.model import BEARING_COEFFICIENTS
from .assembly import TrainSystem, _place


@dataclass
class BearingTerm:
    """One rotor bearing placed in the train: its label, shaft DOFs (v, w), pedestal DOFs (or None),
    thrust DOF (u or None) and coefficients at the shaft's speed."""

    label: str
    shaft: str
    x: float
    shaft_dofs: tuple
    pedestal_dofs: tuple | None
    K: np.ndarray
    C: np.ndarray
    axial_dof: int | None
    k_axial: float
    c_axial: float

    def force(self, q, v):
        """(F_y, F_z[, F_x]) on the shaft: arrays (3, m) for DOF histories q, v (n, m) (real or complex)."""
        q, v = np.atleast_2d(np.asarray(q).T).T, np.atleast_2d(np.asarray(v).T).T
        d = q[list(self.shaft_dofs)]
        dd = v[list(self.shaft_dofs)]
        if self.pedestal_dofs is not None:
            d = d - q[list(self.pedestal_dofs)]
            dd = dd - v[list(self.pedestal_dofs)]
        f = -(self.K @ d + self.C @ dd)
        fx = np.zeros((1, f.shape[1]), dtype=f.dtype)
        if self.axial_dof is not None:
            fx = -(self.k_axial * q[[self.axial_dof]] + self.c_axial * v[[self.axial_dof]])
        return np.vstack([f, fx])


def bearing_terms(ts: TrainSystem, speed: float) -> list[BearingTerm]:
    """Every bearing of every rotor shaft, with its coefficients at the shaft's speed |ratio| * speed."""
    out = []
    for b in ts.blocks:
        if b.rs is None:
            continue
        rs = b.rs
        s = abs(b.ratio) * float(speed)
        tables = {t.index: t for t in rs.tables}
        for no, br in enumerate(rs.rotor.bearings, 1):
            if no in tables:
                c = tables[no].at(s)[0]
            else:
                tab = br.table()
                c = np.array([tab[k][0] for k in BEARING_COEFFICIENTS])
            node = rs.node(br.x)
            sd = (b.offset + int(rs.node_dofs["v"][node]), b.offset + int(rs.node_dofs["w"][node]))
            ped = None
            if br.pedestal is not None:
                iv = np.flatnonzero((rs.dof_field == "pedestal_v") & (rs.dof_name == br.pedestal))[0]
                iw = np.flatnonzero((rs.dof_field == "pedestal_w") & (rs.dof_name == br.pedestal))[0]
                ped = (b.offset + int(iv), b.offset + int(iw))
            iu = b.offset + int(rs.node_dofs["u"][node]) if "u" in rs.node_dofs else None
            label = f"{b.name}:{br.name or f'bearing{no}'}@x={br.x:g}"
            out.append(BearingTerm(label, b.name, float(br.x), sd, ped, np.array([[c[0], c[1]], [c[2], c[3]]]),
                                   np.array([[c[4], c[5]], [c[6], c[7]]]), iu, float(br.k_axial), float(br.c_axial)))
    return out


def internal_matrices(ts: TrainSystem) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """(K, C) of the shafts without their bearings, pedestals and springs to ground (the shafts' internal
    forces), placed in the train."""
    n = ts.n_dofs
    K = sp.csr_matrix((n, n))
    C = sp.csr_matrix((n, n))
    for b in ts.blocks:
        if b.rs is not None:
            bare = replace(b.rs.rotor, bearings=[], pedestals=[])
            rs0 = assemble_rotor(bare) if (b.rs.rotor.bearings or b.rs.rotor.pedestals) else b.rs
            K = K + _place(_pad(rs0.K0, b.n), b.offset, n)
            C = C + _place(_pad(rs0.C0, b.n), b.offset, n)
        else:
            K = K + _place(b.fe.system.K, b.offset, n)
            C = C + _place(b.fe.system.C, b.offset, n)
    return sp.csr_matrix(K - point_springs(ts)), sp.csr_matrix(C)


def _pad(A, n):
    A = sp.coo_matrix(A)
    return sp.csr_matrix((A.data, (A.row, A.col)), shape=(n, n))


def point_springs(ts: TrainSystem) -> sp.csr_matrix:
    """The [[point]] springs to ground of FE shafts (diagonal), placed in the train."""
    n = ts.n_dofs
    rows, vals = [], []
    for b in ts.blocks:
        if b.fe is None:
            continue
        m = b.fe.model
        prim, rot = m.fields[0], (m.fields[1] if len(m.fields) > 1 else None)
        for p in list(m.points) + [s for s in m.supports if s.type == "spring"]:
            if p.k:
                rows.append(b.offset + b.local_dof(p.x, prim, ""))
                vals.append(p.k)
            if getattr(p, "kr", 0.0) and rot is not None:
                rows.append(b.offset + b.local_dof(p.x, rot, ""))
                vals.append(p.kr)
    return sp.csr_matrix((vals, (rows, rows)), shape=(n, n))


@dataclass
class Direction:
    """A rigid motion of one member (shaft or body): ``label`` ("torsion", "y", "z", "axial") and its
    vector over the train DOFs."""

    member: str
    label: str
    r: np.ndarray


def rigid_directions(ts: TrainSystem) -> list[Direction]:
    """Unit rigid motions of every member in the directions its DOFs have."""
    n = ts.n_dofs
    out = []
    for b in ts.blocks:
        sl = np.arange(b.offset, b.offset + b.n)
        f = ts.dof_field[sl]
        for label, fields in (("torsion", ("theta_x", "theta")), ("y", ("v",)), ("z", ("w",)), ("axial", ("u",))):
            if b.fe is not None and b.kind == "bending":
                fields = {"y": ("w",) if b.plane == "y" else (), "z": ("w",) if b.plane == "z" else ()}.get(label, ())
            mask = np.isin(f, fields)
            if mask.any():
                r = np.zeros(n)
                r[sl[mask]] = 1.0
                out.append(Direction(b.name, label, r))
    for i, bd in enumerate(ts.train.bodies):
        r = np.zeros(n)
        r[ts.body_offset + i] = 1.0
        out.append(Direction(bd.name, "torsion", r))
    return out


@dataclass
class Balance:
    """Force balance per member and direction (see the module docstring): the terms (summed over the
    samples' absolute values for scale) and the largest relative residual over the samples."""

    rows: list = field(default_factory=list)      # dicts: member, direction, residual, terms {name: max |term|}

    @property
    def max_residual(self) -> float:
        return max((r["residual"] for r in self.rows), default=0.0)

    def to_dict(self) -> dict:
        return {"max_residual": self.max_residual, "rows": self.rows}


def balance(ts: TrainSystem, dirs: list[Direction], terms: dict) -> Balance:
    """Balance of every direction: ``terms`` {name: force vectors (n, m)} whose sum must vanish (inertia
    and damping with their signs: -M a, -C v, applied, bearings, supports, each connection).  The residual
    of a direction is relative to the largest sum of the magnitudes of its terms over the samples (a
    direction without forces: relative to the largest force of the train)."""
    out = Balance()
    glob = max((float(np.max(np.abs(F))) for F in terms.values() if np.size(F)), default=0.0)
    for d in dirs:
        proj = {k: d.r @ np.asarray(F) for k, F in terms.items()}
        total = sum(proj.values())
        scale = float(np.max(sum(np.abs(p) for p in proj.values()))) if np.size(total) else 0.0
        # a direction that carries (almost) no force is measured against the largest force of the train
        denom = scale if scale > 1e-9 * glob else max(glob, 1e-300)
        res = float(np.max(np.abs(total)) / denom) if np.size(total) else 0.0
        out.rows.append({"member": d.member, "direction": d.label, "residual": res,
                         "terms": {k: float(np.max(np.abs(p))) for k, p in proj.items()}})
    return out


def shaft_section_loads(ts: TrainSystem, shaft: str, q, *, qd=None, qdd=None, omega=None, speed: float = 0.0,
                        x=None):
    """Section loads (torque, axial force, bending moments, shear forces) along one shaft of the train by
    :mod:`fem.loads` (the recovery from the element equations with inertia, damping and gyroscopic terms)
    for the train DOF vector(s) ``q`` (static; harmonic with ``omega``; time history with ``qd``, ``qdd``);
    ``speed``: the reference speed (a rotor shaft spins at |ratio| speed)."""
    from ..loads import section_loads

    b = ts.block(shaft, "section loads")
    sl = slice(b.offset, b.offset + b.n)
    q = np.asarray(q)[sl]
    qd = None if qd is None else np.asarray(qd)[sl]
    qdd = None if qdd is None else np.asarray(qdd)[sl]
    if b.rs is not None:
        spin = abs(b.ratio) * float(speed)
        return section_loads(b.rs, q, qd=qd, qdd=qdd, omega=omega, x=x, speed=spin)
    return section_loads(b.fe, q, qd=qd, qdd=qdd, omega=omega, x=x)
