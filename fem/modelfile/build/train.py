"""A ``train`` model file -> :class:`fem.train.Train` and the settings of its analyses.

Each ``[[shaft]]`` is built by the builder of its own kind (:func:`.fe.shaft_model` on the shaft table,
which has the FE file's keys, or :func:`.rotor.rotor_model` on its ``[shaft.rotor]``); meshes and
couplings become :class:`~fem.train.connections.GearMesh` and :class:`~fem.train.connections.ShaftCoupling`
(degrees -> rad, rev/min -> rad/s), which check everything that involves the shafts (nodes, DOFs).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from discrete.errors import ModelError

from ...train.connections import GearMesh, ShaftCoupling
from ...train.connections.mesh import rectangular_variation
from ...train.model import Port, Train, TrainBody, TrainShaft
from .. import budget
from ..schema.train import ShaftNode
from . import fe as build_fe
from . import rotor as build_rotor

RPM = math.pi / 30.0
DEG = math.pi / 180.0


class _RotorDoc:
    """What :func:`.rotor.rotor_model` reads from a document: ``rotor`` and ``title``."""

    def __init__(self, rotor, title):
        self.rotor, self.title = rotor, title


def port(end, where: str) -> Port:
    """A connection end of the file as a :class:`Port`."""
    if isinstance(end, ShaftNode):
        if end.dof is not None:
            raise ModelError(where, "dof", end.dof, "no dof for a connection end (the connection acts on every DOF "
                             "of the node it needs)")
        return Port(shaft=end.shaft, x=end.x)
    return Port(body=end)


def train_model(doc) -> Train:
    """The :class:`Train` a file describes."""
    n_dofs = 0
    shafts = []
    for i, t in enumerate(doc.shaft, 1):
        where = f"[[shaft]] #{i} {t.name!r}"
        try:
            if t.rotor is not None:
                model = build_rotor.rotor_model(_RotorDoc(t.rotor, t.name))
                n_dofs += (model.n_elements + 1) * len(model.fields)
            else:
                model = build_fe.shaft_model(t)
                n_dofs += sum(s.elements for s in t.segment) * (2 if t.model.physics != "bending" else 3)
        except ModelError as exc:
            raise ModelError(f"{where} {exc.where}".strip(), exc.key, exc.value, exc.allowed) from None
        shafts.append(TrainShaft(name=t.name, model=model, position=tuple(t.position), x0=t.x0, plane=t.plane,
                                 speed_ratio=t.speed_ratio))
    budget.check_count("[[shaft]]", "elements", n_dofs, budget.MAX_FE_DOFS, "train DOFs",
                       [len(t.segment) or len(t.rotor.segment) for t in doc.shaft])
    bodies = [TrainBody(name=b.name, inertia=b.inertia, x0=b.x0, v0=b.v0, speed_ratio=b.speed_ratio)
              for b in doc.body]
    conns = []
    for i, m in enumerate(doc.mesh, 1):
        name = m.name or f"mesh{i}"
        where = f"[[mesh]] #{i} {name!r}"
        var = ()
        if m.variation is not None:
            v = m.variation
            var = (tuple((int(r[0]), r[1], r[2]) for r in v.fourier) if v.fourier is not None
                   else rectangular_variation(v.contact_ratio, v.depth, v.harmonics))
        conns.append(GearMesh(name=name, ports=tuple(port(e, where) for e in m.between), stiffness=m.stiffness,
                              damping=m.damping, base_radius=None if m.base_radius is None else tuple(m.base_radius),
                              teeth=None if m.teeth is None else tuple(m.teeth), module=m.module,
                              pressure_angle=m.pressure_angle_deg * DEG, helix_angle=m.helix_angle_deg * DEG,
                              hand=1 if m.hand == "right" else -1, internal=m.internal,
                              flank=1 if m.flank == "positive" else -1,
                              line_of_centres=None if m.line_of_centres_deg is None else m.line_of_centres_deg * DEG,
                              backlash=m.backlash, damping_in_contact=m.damping_in_contact, variation=var,
                              transmission_error=tuple((t.harmonic, t.amplitude, t.phase_deg * DEG)
                                                       for t in m.transmission_error),
                              linear_state=m.linear_state))
    for i, c in enumerate(doc.coupling, 1):
        name = c.name or f"coupling{i}"
        where = f"[[coupling]] #{i} {name!r}"
        ends = []
        for e in c.between:
            ends.append(Port.ground() if e == "ground" else port(e, where))
        conns.append(ShaftCoupling(name=name, ports=tuple(ends), k_torsion=c.k_torsion, c_torsion=c.c_torsion,
                                   k_lateral=c.k_lateral, c_lateral=c.c_lateral, k_angular=c.k_angular,
                                   c_angular=c.c_angular, k_axial=c.k_axial, c_axial=c.c_axial, backlash=c.backlash,
                                   slip_torque=c.slip_torque, slip_torque_static=c.slip_torque_static,
                                   linear_state=c.linear_state or "closed", given_state=c.linear_state is not None))
    return Train(shafts=shafts, bodies=bodies, connections=conns, reference=doc.train.reference, title=doc.title)


def operating_speed(doc) -> float:
    """[train] speed in rad/s (0 when not given)."""
    t = doc.train
    if t.speed_rpm is not None:
        return t.speed_rpm * RPM
    return t.speed or 0.0


def modal_speed(doc) -> float:
    an = doc.analysis
    if an is None:
        return operating_speed(doc)
    if an.speed_rpm is not None:
        return an.speed_rpm * RPM
    if an.speed is not None:
        return an.speed
    return operating_speed(doc)


def modes_count(doc, table=None, n_modes: int | None = None) -> int:
    if n_modes is not None:
        return n_modes
    if table is not None and getattr(table, "modes", None) is not None:
        return table.modes
    if doc.analysis is not None and doc.analysis.modes is not None:
        return doc.analysis.modes
    return 6


def speeds(table, where: str) -> np.ndarray:
    """Speeds of [campbell] / [forced] (rad/s)."""
    return build_rotor.speed_grid(table, where)


@dataclass
class EndRef:
    """A driver's or force's place: a body, or a DOF at a shaft node."""

    member: str
    field: str | None
    x: float | None


def end_ref(ts, end, where: str) -> int:
    """The train DOF of a driver's or force's ``at``."""
    if isinstance(end, ShaftNode):
        b = ts.block(end.shaft, where)
        field = end.dof
        if field is None:
            field = "theta_x" if b.rs is not None else ("theta" if b.kind == "torsion" else None)
            if field is None:
                raise ModelError(where, "dof", None, f"the DOF at the node of shaft {end.shaft!r} (physics "
                                 f"{b.kind!r} has no torsion DOF)")
        return ts.dof(end.shaft, field, end.x, where)
    if end == "ground":
        raise ModelError(where, "at", end, "a body or a shaft node")
    return ts.body_dof(end, where)


def loads(ts, doc) -> list:
    """The [[force]] tables as :class:`fem.train.forced.TrainLoad` (order: of the member's speed)."""
    from ...train.forced import TrainLoad

    out = []
    for i, f in enumerate(doc.force, 1):
        where = f"[[force]] #{i}"
        j = end_ref(ts, f.at, where)
        member = ts.dof_member[j]
        label = f"force{i}@{ts.label(j)}"
        out.append(TrainLoad(dof=j, value=f.value, amplitude=f.amplitude, omega=f.omega, order=f.order,
                             member=member, phase=f.phase, label=label))
    return out


def drivers(ts, doc) -> list:
    """The [[driver]] tables as :class:`fem.train.compile.TrainDriver`."""
    from discrete.nonsmooth import MotionLaw

    from ...train.compile import TrainDriver

    out = []
    for i, d in enumerate(doc.driver, 1):
        where = f"[[driver]] #{i}"
        j = end_ref(ts, d.at, where)
        if d.amplitude != 0 and d.omega == 0:
            raise ModelError(where, "omega", d.omega, "a number > 0 with amplitude")
        out.append(TrainDriver(dof=j, law=MotionLaw(offset=d.offset, velocity=d.velocity, amplitude=d.amplitude,
                                                    omega=d.omega, phase=d.phase)))
    return out


def reduction(doc):
    """[reduction] as :class:`fem.train.compile.ReductionSpec` (None: the full shafts)."""
    from ...train.compile import ReductionSpec

    r = doc.reduction
    if r is None:
        return None
    return ReductionSpec(modes=r.modes, shaft_modes=dict(r.shaft_modes), static_correction=r.static_correction,
                         threshold=r.threshold)


def parametric(study):
    """[parametric] -> :func:`fem.train.parametric.train_parametric` on the study's train."""
    from ...train.parametric import train_parametric

    doc = study.doc
    t = doc.parametric
    if t is None:
        raise ModelError("model file (train)", "parametric", None, "a table [parametric] with speeds (or speeds_rpm) "
                         "= { start, stop, points } and depth = { stop, .. } (required for drivefem parametric)")
    grid, scale = (t.speeds, 1.0) if t.speeds is not None else (t.speeds_rpm, RPM)
    budget.check_count("[parametric]", "points", grid.points * t.depth.points, 400_000, "Floquet grid points",
                       [grid.points, t.depth.points])
    if t.depth.stop < t.depth.start:
        raise ModelError("[parametric]", "depth", [t.depth.start, t.depth.stop], "start <= stop")
    if t.depth.points > 1 and t.depth.stop == t.depth.start:
        raise ModelError("[parametric]", "depth.points", t.depth.points, "1 when start == stop")
    for d in t.boundaries_at:
        if d > t.depth.stop:
            raise ModelError("[parametric]", "boundaries_at", t.boundaries_at, f"depths <= depth.stop = {t.depth.stop}")
    return train_parametric(study.train, speed=operating_speed(doc), speed_min=grid.start * scale,
                            speed_max=grid.stop * scale, n_speed=grid.points, depth_min=t.depth.start,
                            depth_max=t.depth.stop, n_depth=t.depth.points, mesh=t.mesh,
                            boundaries_at=list(t.boundaries_at), modes=t.modes, tolerance=t.tolerance,
                            reduction=reduction(doc))
