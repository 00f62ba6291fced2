"""Assemble a :class:`~fem.train.model.Train` into one linear system.

The shafts are assembled by the code of their own kind (:func:`fem.assembly.assemble` for FE shafts,
:func:`fem.rotor.assemble_rotor` for rotors) and placed block-diagonally in the order of the file, the
bodies follow (one rotation DOF each).  The connections add their linear parts in the declared state
(K += k g g^T, C += c g g^T through their protocol).  At the train's speed Omega (rad/s, the reference's
speed) each shaft turns at Omega_i = ratio_i Omega, so

    M q'' + (C(Omega) + Omega G) q' + K(Omega) q = f,   G = sum_i ratio_i G_i,

with each rotor's bearing tables evaluated at its own |Omega_i|.  All matrices at every speed are
stored on one sparsity pattern (the rotor's convention), so the quadratic eigensolver splits and
orders them once.  DOF labels: ``<shaft>@x=<x>.<field>`` for shaft DOFs, ``<body>.theta`` for bodies.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from discrete.errors import ModelError
from discrete.linear_system import LinearSystem

from ..assembly import FEModel, assemble
from ..rotor.assembly import RotorSystem, _data_on, assemble_rotor
from ..rotor.model import Rotor
from .model import Port, Train

#: rotor DOF field -> train-frame motion
ROTOR_MOTIONS = {"u": "ux", "v": "uy", "w": "uz", "theta_x": "rx", "theta_y": "ry", "theta_z": "rz"}


@dataclass
class PortKinematics:
    """What a port offers a connection: its member, the shaft (or None), the axis position (y, z),
    its motions {motion: [(train DOF, factor)]} and its speed ratio."""

    member: str
    shaft: str | None
    centre_yz: tuple
    motions: dict
    ratio: float


@dataclass
class ShaftBlock:
    """An assembled shaft placed in the train: DOFs ``offset .. offset + n``."""

    name: str
    kind: str
    offset: int
    n: int
    ratio: float
    fe: FEModel | None = None
    rs: RotorSystem | None = None
    plane: str = "y"
    position: tuple = (0.0, 0.0)
    x0: float = 0.0

    @property
    def system(self) -> LinearSystem:
        return self.fe.system if self.fe is not None else self.rs.system_at(0.0)

    def local_dof(self, x: float, field: str, where: str) -> int:
        if self.rs is not None:
            return int(self.rs.dof(x, field, where))
        return int(self.fe.system.dof_index(field=field, x=x, where=where))

    def motions(self, x: float, where: str) -> dict:
        """{motion: [(train DOF, factor)]} of the node at x."""
        out = {}
        if self.rs is not None:
            for f in self.rs.fields:
                out[ROTOR_MOTIONS[f]] = [(self.offset + self.local_dof(x, f, where), 1.0)]
            return out
        phys = self.kind
        if phys == "torsion":
            out["rx"] = [(self.offset + self.local_dof(x, "theta", where), 1.0)]
        elif phys == "axial":
            out["ux"] = [(self.offset + self.local_dof(x, "u", where), 1.0)]
        else:
            rot = self.fe.model.fields[1]
            iw = self.offset + self.local_dof(x, "w", where)
            ir = self.offset + self.local_dof(x, rot, where)
            if self.plane == "y":           # w = u_y, slope = theta_z
                out["uy"], out["rz"] = [(iw, 1.0)], [(ir, 1.0)]
            else:                           # w = u_z, slope = dw/dx = -theta_y
                out["uz"], out["ry"] = [(iw, 1.0)], [(ir, -1.0)]
        return out


def _place(A, offset: int, n: int) -> sp.csr_matrix:
    A = sp.coo_matrix(A)
    return sp.csr_matrix((A.data, (A.row + offset, A.col + offset)), shape=(n, n))


@dataclass
class TrainSystem:
    """An assembled train (see the module docstring).  ``system_at(speed)`` is the
    :class:`LinearSystem` at the reference speed; ``port(p)`` resolves a connection end."""

    train: Train
    blocks: list
    body_offset: int
    ratios: dict
    M: sp.csr_matrix
    K0: sp.csr_matrix                 # constant stiffness: shafts (constant bearings) + connections
    C0: sp.csr_matrix
    G: sp.csr_matrix                  # sum_i ratio_i G_i
    H: sp.csr_matrix
    dof_field: np.ndarray
    dof_x: np.ndarray
    dof_name: np.ndarray
    dof_member: np.ndarray            # shaft or body name of every DOF
    constrained: np.ndarray
    pattern: sp.csr_matrix
    connection_coords: dict = field(default_factory=dict)   # name -> linear-state coordinates
    warnings: list = field(default_factory=list)
    _workspace: object = None

    # ------------------------------------------------------------------ sizes and lookup
    @property
    def n_dofs(self) -> int:
        return self.M.shape[0]

    @property
    def title(self) -> str:
        return self.train.title

    @property
    def speed_dependent(self) -> bool:
        return any(b.rs is not None and b.rs.tables for b in self.blocks)

    def block(self, name: str, where: str = "") -> ShaftBlock:
        for b in self.blocks:
            if b.name == name:
                return b
        raise ModelError(where, "shaft", name, "one of " + ", ".join(repr(b.name) for b in self.blocks))

    def body_dof(self, name: str, where: str = "") -> int:
        for i, b in enumerate(self.train.bodies):
            if b.name == name:
                return self.body_offset + i
        raise ModelError(where, "body", name, "one of " + ", ".join(repr(b.name) for b in self.train.bodies)
                         if self.train.bodies else "a [[body]] name (this train has no bodies)")

    def port(self, port: Port, where: str = "") -> PortKinematics:
        if port.is_ground:
            return PortKinematics("ground", None, (0.0, 0.0), {}, 0.0)
        if port.body is not None:
            i = self.body_dof(port.body, where)
            return PortKinematics(port.body, None, (0.0, 0.0), {"rx": [(i, 1.0)]}, self.ratios[port.body])
        b = self.block(port.shaft, where)
        return PortKinematics(b.name, b.name, b.position, b.motions(port.x, where), b.ratio)

    def ratio_of(self, port: Port) -> float:
        return 0.0 if port.is_ground else self.ratios[port.body if port.body is not None else port.shaft]

    def dof(self, member: str, field: str | None = None, x: float | None = None, where: str = "") -> int:
        """Train DOF of a body (``member`` its name) or of ``field`` at ``x`` of a shaft."""
        if any(b.name == member for b in self.train.bodies):
            return self.body_dof(member, where)
        b = self.block(member, where)
        if field is None:
            raise ModelError(where, "dof", None, "the DOF name at the shaft node (e.g. 'theta_x', 'v', 'theta')")
        return b.offset + b.local_dof(x, field, where)

    def label(self, i: int) -> str:
        return f"{self.dof_name[i]}.{self.dof_field[i]}"

    # ------------------------------------------------------------------ speed-dependent parts
    def _table_delta(self, which: str, speed: float) -> sp.csr_matrix | None:
        parts = []
        for b in self.blocks:
            if b.rs is not None and b.rs.tables:
                s = abs(b.ratio) * float(speed)
                A = b.rs.stiffness(s) - b.rs.K0 if which == "K" else b.rs.damping(s) - b.rs.C0
                parts.append(_place(A, b.offset, self.n_dofs))
        return sum(parts) if parts else None

    def _on_pattern(self, A) -> sp.csr_matrix:
        P = self.pattern
        return sp.csr_matrix((_data_on(P, A), P.indices, P.indptr), shape=P.shape)

    def stiffness(self, speed: float = 0.0) -> sp.csr_matrix:
        d = self._table_delta("K", speed)
        return self.K0 if d is None else self._on_pattern(self.K0 + d)

    def damping(self, speed: float = 0.0) -> sp.csr_matrix:
        d = self._table_delta("C", speed)
        return self.C0 if d is None else self._on_pattern(self.C0 + d)

    def system_at(self, speed: float = 0.0) -> LinearSystem:
        """M q'' + (C + speed G) q' + K q = f at the reference speed (rad/s)."""
        return LinearSystem(M=self.M, K=self.stiffness(speed), C=self.damping(speed), H=self.H, G=self.G,
                            dof_field=self.dof_field, dof_x=self.dof_x, dof_name=self.dof_name,
                            constrained=self.constrained, title=self.title, physics="train")

    # ------------------------------------------------------------------ for the complex modes
    @property
    def node_x(self) -> np.ndarray:
        return self.dof_x

    @property
    def rotor_nodes(self) -> list:
        """[(shaft name, ratio, v DOFs, w DOFs)] of the rotor shafts (whirl of each)."""
        out = []
        for b in self.blocks:
            if b.rs is not None:
                out.append((b.name, b.ratio, b.offset + b.rs.node_dofs["v"], b.offset + b.rs.node_dofs["w"]))
        return out


def assemble_train(train: Train) -> TrainSystem:
    """Assemble ``train`` (see the module docstring)."""
    if not isinstance(train, Train):
        raise ModelError("fem.train.assemble_train", "train", type(train).__name__, "a fem.train.Train")
    ratios = train.speed_ratios()
    blocks, mats = [], []
    off = 0
    for s in train.shafts:
        if isinstance(s.model, Rotor):
            rs = assemble_rotor(s.model)
            b = ShaftBlock(s.name, "rotor", off, rs.n_dofs, ratios[s.name], rs=rs, position=s.position, x0=s.x0)
            sysb = rs.system_at(_rotor_speed(rs, abs(ratios[s.name])))
            G = rs.G
            fields, xs = rs.dof_field, rs.dof_x
            names = np.array([f"{s.name}@x={x:.6g}" if not nm else f"{s.name}:{nm}"
                              for x, nm in zip(xs, rs.dof_name)], dtype=object)
            K0, C0 = rs.K0, rs.C0
        else:
            fe = assemble(s.model)
            b = ShaftBlock(s.name, s.model.physics, off, fe.system.n_dofs, ratios[s.name], fe=fe, plane=s.plane,
                           position=s.position, x0=s.x0)
            sysb = fe.system
            G = None
            fields, xs = sysb.dof_field, sysb.dof_x
            names = np.array([f"{s.name}@x={x:.6g}" for x in xs], dtype=object)
            K0, C0 = sysb.K, sysb.C
        mats.append((sysb, K0, C0, G, fields, xs, names, s.name))
        blocks.append(b)
        off += b.n
    body_offset = off
    n = off + len(train.bodies)
    M = sp.csr_matrix((n, n))
    K = sp.csr_matrix((n, n))
    C = sp.csr_matrix((n, n))
    G = sp.csr_matrix((n, n))
    H = sp.csr_matrix((n, n))
    dof_field = np.empty(n, dtype=object)
    dof_x = np.full(n, np.nan)
    dof_name = np.empty(n, dtype=object)
    dof_member = np.empty(n, dtype=object)
    constrained = []
    for b, (sysb, K0, C0, Gb, fields, xs, names, nm) in zip(blocks, mats):
        sl = slice(b.offset, b.offset + b.n)
        M = M + _place(sysb.M, b.offset, n)
        K = K + _place(K0, b.offset, n)
        C = C + _place(C0, b.offset, n)
        H = H + _place(sysb.H, b.offset, n)
        if Gb is not None and b.ratio:
            G = G + _place(b.ratio * Gb, b.offset, n)
        dof_field[sl], dof_x[sl], dof_name[sl], dof_member[sl] = fields, xs, names, nm
        constrained += [b.offset + int(j) for j in sysb.constrained]
    for i, bd in enumerate(train.bodies):
        j = body_offset + i
        M = M + sp.csr_matrix(([bd.inertia], ([j], [j])), shape=(n, n))
        dof_field[j], dof_name[j], dof_member[j] = "theta", bd.name, bd.name
    ts = TrainSystem(train=train, blocks=blocks, body_offset=body_offset, ratios=ratios, M=sp.csr_matrix(M),
                     K0=sp.csr_matrix(K), C0=sp.csr_matrix(C), G=sp.csr_matrix(G), H=sp.csr_matrix(H),
                     dof_field=dof_field, dof_x=dof_x, dof_name=dof_name, dof_member=dof_member,
                     constrained=np.array(sorted(set(constrained)), dtype=int), pattern=None,
                     warnings=list(getattr(train, "ratio_warnings", [])))
    for c in train.connections:
        coords = c.linear_part(ts)
        ts.connection_coords[c.name] = coords
        for cd in coords:
            if cd.k:
                K = K + cd.outer(n, cd.k)
            if cd.c:
                C = C + cd.outer(n, cd.c)
    # the common pattern: every matrix at every speed
    pat = abs(M) + abs(K) + abs(C) + abs(G) + abs(H)
    for b in blocks:
        if b.rs is not None and b.rs.tables:
            pat = pat + _place(abs(b.rs.pattern), b.offset, n)
    pat = sp.csr_matrix(pat)
    pat.sum_duplicates()
    pat.sort_indices()
    pat.data[:] = 1.0
    ts.pattern = pat

    def on(A):
        return sp.csr_matrix((_data_on(pat, A), pat.indices.copy(), pat.indptr.copy()), shape=pat.shape)

    ts.M, ts.K0, ts.C0, ts.G, ts.H = on(M), on(K), on(C), on(G), on(H)
    return ts


def _rotor_speed(rs: RotorSystem, speed: float) -> float:
    """A speed at which the rotor's tables are defined (for the block's template only)."""
    if not rs.tables:
        return 0.0
    from ..rotor.modal import _any_speed

    return _any_speed(rs)
