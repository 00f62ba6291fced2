"""Description of a geared multi-shaft drive train: named shafts, rotational bodies and the connections
between them (gear meshes, couplings; :mod:`fem.train.connections`).

Train frame: every shaft axis is parallel to x.  A shaft sits at ``position = (y, z)`` (m) with its own
x = 0 at the train's ``x0``; it is an FE shaft (:class:`fem.model.ShaftModel`: torsion, axial or planar
bending in the plane ``plane``) or a rotor (:class:`fem.rotor.Rotor`: lateral or full DOFs, bearings).
Bodies are rigid rotations about x (inertia in kg m^2): motors, wheels, loads.  Checks happen here
(one :class:`ModelError` naming the table, the key and the value), so the model file and Python users
get the same messages.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from discrete import checks
from discrete.errors import ModelError

from ..model import ShaftModel
from ..rotor.model import Rotor

PLANES = ("y", "z")
GROUND = "ground"


@dataclass
class Port:
    """One end of a connection: a node of a shaft (``shaft``, ``x`` along that shaft, m), a body
    (``body``) or the ground (``Port.ground()``)."""

    shaft: str | None = None
    x: float | None = None
    body: str | None = None

    @classmethod
    def ground(cls) -> "Port":
        return cls(body=GROUND)

    @property
    def is_ground(self) -> bool:
        return self.body == GROUND

    def describe(self) -> str:
        if self.body is not None:
            return self.body
        return f"{self.shaft}@x={self.x:.6g}"

    def check(self, where: str) -> None:
        if (self.body is None) == (self.shaft is None):
            raise ModelError(where, "between", self.describe() if self.body else [self.shaft, self.x],
                             "a body name, \"ground\" or { shaft = \"name\", x = .. } (a shaft node)")
        if self.shaft is not None:
            if not isinstance(self.shaft, str) or not self.shaft:
                raise ModelError(where, "shaft", self.shaft, "a shaft name")
            if self.x is None:
                raise ModelError(where, "x", None, f"the node's position along shaft {self.shaft!r} (m)")
            self.x = checks.finite(where, "x", self.x, "position along the shaft, m")


@dataclass
class TrainShaft:
    """A named shaft of the train: an FE shaft or a rotor, placed at ``position`` (y, z) with its
    x = 0 at ``x0``.  ``plane``: the direction of an FE bending shaft's deflection w ("y" or "z").
    ``speed_ratio``: its speed over the reference speed (signed; None: from the connections)."""

    name: str
    model: ShaftModel | Rotor
    position: tuple = (0.0, 0.0)
    x0: float = 0.0
    plane: str = "y"
    speed_ratio: float | None = None

    def check(self, where: str) -> None:
        if not isinstance(self.name, str) or not self.name or self.name == GROUND:
            raise ModelError(where, "name", self.name, "a shaft name (not empty, not \"ground\")")
        if not isinstance(self.model, (ShaftModel, Rotor)):
            raise ModelError(where, "model", type(self.model).__name__, "a fem.ShaftModel or a fem.rotor.Rotor")
        pos = checks.vector(where, "position", self.position, 2, "[y, z] of the shaft axis, m")
        self.position = (float(pos[0]), float(pos[1]))
        self.x0 = checks.finite(where, "x0", self.x0, "axial position of the shaft's x = 0, m")
        checks.choice(where, "plane", self.plane, PLANES)
        if self.speed_ratio is not None:
            self.speed_ratio = checks.finite(where, "speed_ratio", self.speed_ratio, "speed / reference speed")
            if self.speed_ratio == 0:
                raise ModelError(where, "speed_ratio", 0.0, "a nonzero speed ratio (signed)")

    @property
    def kind(self) -> str:
        """"rotor" or the FE physics ("torsion", "axial", "bending")."""
        return "rotor" if isinstance(self.model, Rotor) else self.model.physics

    @property
    def length(self) -> float:
        return self.model.length


@dataclass
class TrainBody:
    """A rigid body turning about x: ``inertia`` (kg m^2), initial angle ``x0`` (rad) and speed ``v0``
    (rad/s) of its vibration; ``speed_ratio`` as for shafts."""

    name: str
    inertia: float
    x0: float = 0.0
    v0: float = 0.0
    speed_ratio: float | None = None

    def check(self, where: str) -> None:
        if not isinstance(self.name, str) or not self.name or self.name == GROUND:
            raise ModelError(where, "name", self.name, "a body name (not empty, not \"ground\")")
        self.inertia = checks.positive(where, "inertia", self.inertia, "moment of inertia, kg m^2")
        self.x0 = checks.finite(where, "x0", self.x0, "initial angle, rad")
        self.v0 = checks.finite(where, "v0", self.v0, "initial angular velocity, rad/s")
        if self.speed_ratio is not None:
            self.speed_ratio = checks.finite(where, "speed_ratio", self.speed_ratio, "speed / reference speed")
            if self.speed_ratio == 0:
                raise ModelError(where, "speed_ratio", 0.0, "a nonzero speed ratio (signed)")


@dataclass
class Train:
    """Shafts, bodies and connections; ``reference``: the shaft or body whose speed is the train's
    speed Omega (default: the first shaft, else the first body)."""

    shafts: list = field(default_factory=list)
    bodies: list = field(default_factory=list)
    connections: list = field(default_factory=list)
    reference: str | None = None
    title: str = ""

    def __post_init__(self):
        for key, cls, table in (("shafts", TrainShaft, "shaft"), ("bodies", TrainBody, "body")):
            items = getattr(self, key)
            if isinstance(items, (str, bytes)) or not hasattr(items, "__iter__"):
                raise ModelError("train", table, items, f"a list of {cls.__name__}")
            items = list(items)
            for i, it in enumerate(items, 1):
                if not isinstance(it, cls):
                    raise ModelError(f"[[{table}]] #{i}", table, type(it).__name__, f"a fem.train.{cls.__name__}")
                it.check(f"[[{table}]] #{i} {getattr(it, 'name', '')!r}".rstrip())
            setattr(self, key, items)
        if not self.shafts and not self.bodies:
            raise ModelError("train", "shaft", [], "at least one [[shaft]] or [[body]]")
        names = [s.name for s in self.shafts] + [b.name for b in self.bodies]
        seen = set()
        for nm in names:
            if nm in seen:
                raise ModelError("train", "name", nm, "unique names of shafts and bodies")
            seen.add(nm)
        from .connections.base import Connection

        self.connections = list(self.connections)
        cnames = set()
        for i, c in enumerate(self.connections, 1):
            if not isinstance(c, Connection):
                raise ModelError(f"connection #{i}", "type", type(c).__name__, "a fem.train connection "
                                 "(GearMesh, ShaftCoupling)")
            c.check(self)
            if c.name in cnames:
                raise ModelError(c.where, "name", c.name, "a name not used by another connection")
            cnames.add(c.name)
        if self.reference is None:
            self.reference = names[0]
        elif self.reference not in names:
            raise ModelError("[train]", "reference", self.reference, "one of " + ", ".join(map(repr, names)))

    # ------------------------------------------------------------------ lookup
    def shaft(self, name: str, where: str = "") -> TrainShaft:
        for s in self.shafts:
            if s.name == name:
                return s
        raise ModelError(where, "shaft", name, "one of " + ", ".join(repr(s.name) for s in self.shafts)
                         if self.shafts else "a [[shaft]] name (this train has no shafts)")

    def body(self, name: str, where: str = "") -> TrainBody:
        for b in self.bodies:
            if b.name == name:
                return b
        raise ModelError(where, "body", name, "one of " + ", ".join(repr(b.name) for b in self.bodies)
                         if self.bodies else "a [[body]] name (this train has no bodies)")

    def member(self, port: Port, where: str):
        """The shaft or body a port belongs to (None for the ground)."""
        if port.is_ground:
            return None
        if port.body is not None:
            return self.body(port.body, where)
        s = self.shaft(port.shaft, where)
        L = s.length
        if not -1e-12 * L <= port.x <= L * (1 + 1e-12):
            raise ModelError(where, "x", port.x, f"a node of shaft {s.name!r}, 0 <= x <= {L:g} m")
        return s

    # ------------------------------------------------------------------ speeds
    def speed_ratios(self) -> dict:
        """{shaft or body name: Omega_i / Omega}, signed: from the connections' kinematic ratios by a
        walk from the reference; a declared ``speed_ratio`` replaces the kinematic value (a warning in
        :attr:`ratio_warnings` when they differ by more than 1e-9).  Members not reached by a
        kinematic connection turn at the reference speed unless declared."""
        names = [s.name for s in self.shafts] + [b.name for b in self.bodies]
        declared = {m.name: m.speed_ratio for m in (*self.shafts, *self.bodies) if m.speed_ratio is not None}
        adj = {n: [] for n in names}
        for c in self.connections:
            r = c.speed_ratio()
            a, b = c.ports
            if r is None or a.is_ground or b.is_ground:
                continue
            na, nb = (p.body if p.body is not None else p.shaft for p in (a, b))
            if na == nb:
                continue
            adj[na].append((nb, r, c))
            adj[nb].append((na, 1.0 / r, c))
        kin = {}
        warnings = []
        for start in [self.reference] + names:
            if start in kin:
                continue
            kin[start] = declared.get(start, 1.0) if start != self.reference else 1.0
            stack = [start]
            while stack:
                n = stack.pop()
                for m, r, c in adj[n]:
                    val = kin[n] * r
                    if m not in kin:
                        kin[m] = val
                        stack.append(m)
                    elif not math.isclose(kin[m], val, rel_tol=1e-9, abs_tol=0.0):
                        raise ModelError(c.where, "ratio", val, f"a speed ratio consistent with the train's other "
                                         f"connections: {m!r} already turns at {kin[m]:.9g} times the reference "
                                         f"speed (a loop of gears and couplings that does not close)")
        out = {}
        for n in names:
            if n in declared:
                if n == self.reference and declared[n] != 1.0:
                    raise ModelError(f"[[shaft]] {n!r}", "speed_ratio", declared[n],
                                     "1 for the reference (or omit it)")
                if not math.isclose(declared[n], kin[n], rel_tol=1e-9, abs_tol=0.0):
                    warnings.append(f"{n!r}: declared speed_ratio {declared[n]:.12g} differs from the kinematic "
                                    f"ratio of its connections {kin[n]:.12g} (relative {abs(declared[n] / kin[n] - 1):.2e}); "
                                    "the declared value sets its speed")
                out[n] = float(declared[n])
            else:
                out[n] = float(kin[n])
        self.ratio_warnings = warnings
        return out
