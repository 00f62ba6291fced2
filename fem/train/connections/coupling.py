"""Shaft coupling: torsional (and, where both ends have them, lateral, angular and axial) springs and
dampers between two ports, optionally with a torsional backlash or a slip torque.

Coordinates (relative motion b - a of the train-frame motions): torsion theta_x,b - theta_x,a; lateral
u_y and u_z; angular theta_y and theta_z; axial u_x.  A port may be the ground (a spring to ground).
The torsional law is one of: a linear spring and damper (``k_torsion``, ``c_torsion``); a spring with a
total clearance ``backlash`` (rad): the gap law (11.1) by :class:`MeshContact`; a slipping joint
(``slip_torque``, ``slip_torque_static``): Coulomb friction (stick is a constraint of the event
solver), rigid until it slips -- so without a torsional spring.  Linear analyses see the
``linear_state``: "closed" (the spring, the backlash closed) or "open" (no torsional connection; a slip
coupling has no linear stiffness, so "open" is its only linear state).
"""
from __future__ import annotations

from dataclasses import dataclass

from discrete import checks
from discrete.errors import ModelError
from discrete.nonsmooth.elements import Friction, MeshContact

from .base import Connection, Coord, ElementPart, coord

#: (motion, stiffness key, damping key, label)
DIRECTIONS = (("rx", "k_torsion", "c_torsion", "torsion"), ("uy", "k_lateral", "c_lateral", "lateral y"),
              ("uz", "k_lateral", "c_lateral", "lateral z"), ("ry", "k_angular", "c_angular", "angular y"),
              ("rz", "k_angular", "c_angular", "angular z"), ("ux", "k_axial", "c_axial", "axial"))


@dataclass
class ShaftCoupling(Connection):
    """Springs (N/m, N m/rad) and dampers (N s/m, N m s/rad) between ports a and b; ``backlash``
    (rad, total) and ``slip_torque`` (N m) act on the torsion."""

    k_torsion: float = 0.0
    c_torsion: float = 0.0
    k_lateral: float = 0.0
    c_lateral: float = 0.0
    k_angular: float = 0.0
    c_angular: float = 0.0
    k_axial: float = 0.0
    c_axial: float = 0.0
    backlash: float = 0.0
    slip_torque: float | None = None
    slip_torque_static: float | None = None

    table = "coupling"

    def check(self, train) -> None:
        if self.slip_torque is not None and self.linear_state == "closed" and not self.given_state:
            self.linear_state = "open"
        super().check(train)
        w = self.where
        for _, kk, ck, _ in DIRECTIONS:
            setattr(self, kk, checks.non_negative(w, kk, getattr(self, kk)))
            setattr(self, ck, checks.non_negative(w, ck, getattr(self, ck)))
        self.backlash = checks.non_negative(w, "backlash", self.backlash, "total torsional backlash, rad")
        if self.backlash > 0 and not self.k_torsion > 0:
            raise ModelError(w, "k_torsion", self.k_torsion, "a torsional stiffness > 0 with a backlash (N m/rad)")
        if self.slip_torque is not None:
            self.slip_torque = checks.positive(w, "slip_torque", self.slip_torque, "kinetic slip torque, N m")
            if self.slip_torque_static is not None:
                self.slip_torque_static = checks.bounded(w, "slip_torque_static", self.slip_torque_static,
                                                         (">=", self.slip_torque), note="breakaway torque, N m")
            if self.k_torsion or self.backlash:
                raise ModelError(w, "k_torsion" if self.k_torsion else "backlash", self.k_torsion or self.backlash,
                                 "no torsional spring or backlash with slip_torque (a slip coupling is rigid until "
                                 "it slips; model a flexible part as a shaft)")
            if self.linear_state == "closed":
                raise ModelError(w, "linear_state", "closed", "'open' for a slip coupling (it has no linear "
                                 "torsional stiffness)")
        elif self.slip_torque_static is not None:
            raise ModelError(w, "slip_torque_static", self.slip_torque_static, "only with slip_torque")
        if not any(getattr(self, k) for _, k, c, _ in DIRECTIONS for k in (k, c)) and self.slip_torque is None:
            raise ModelError(w, "k_torsion", 0.0, "some stiffness, damping or a slip torque")

    given_state: bool = False
    """Whether ``linear_state`` was given explicitly (a slip coupling defaults to "open")."""

    def speed_ratio(self) -> float:
        return 1.0

    def _coord(self, ts, motion, label, k, c) -> Coord | None:
        parts = []
        missing = []
        for port, sign in ((self.ports[0], -1.0), (self.ports[1], 1.0)):
            if port.is_ground:
                continue
            m = ts.port(port).motions.get(motion)
            if not m:
                missing.append(port.describe())
            for dof, factor in m or ():
                parts.append((dof, sign * factor))
        if missing:
            if k or c:
                raise ModelError(self.where, label.split()[0] if label != "torsion" else "k_torsion", k or c,
                                 f"ends that have the {label} motion ({', '.join(missing)} has none)")
            return None
        return coord(parts, label, k, c)

    def coordinates(self, ts) -> list[Coord]:
        out = []
        for motion, kk, ck, label in DIRECTIONS:
            k, c = getattr(self, kk), getattr(self, ck)
            if motion == "rx" and (self.backlash or self.slip_torque is not None):
                k = self.k_torsion
            if k or c:
                cd = self._coord(ts, motion, label, k, c)
                if cd is not None:
                    out.append(cd)
        return out

    def torsion(self, ts) -> Coord:
        cd = self._coord(ts, "rx", "torsion", 1.0, 0.0)
        if cd is None:  # pragma: no cover - checked by _coord
            raise ModelError(self.where, "between", [p.describe() for p in self.ports], "ends with a rotation")
        return cd

    def linear_part(self, ts) -> list[Coord]:
        if self.linear_state == "open":
            return [cd for cd in self.coordinates(ts) if cd.label != "torsion"]
        return self.coordinates(ts)

    def nonsmooth(self, ts, speed: float = 0.0):
        lin = [cd for cd in self.coordinates(ts)]
        if self.slip_torque is not None:
            tor = self.torsion(ts)
            lin = [cd for cd in lin if cd.label != "torsion"]
            static = self.slip_torque if self.slip_torque_static is None else self.slip_torque_static
            return lin, [ElementPart(Friction, self.name, dict(kinetic=self.slip_torque, static=static), tor)], {}
        if self.backlash:
            tor = [cd for cd in lin if cd.label == "torsion"][0]
            lin = [cd for cd in lin if cd.label != "torsion"]
            if tor.c:
                lin.append(Coord(tor.idx, tor.val, tor.label, 0.0, tor.c))
            half = 0.5 * self.backlash
            return lin, [ElementPart(MeshContact, self.name, dict(k=self.k_torsion, lower=-half, upper=half, table="coupling"), tor)], {}
        return lin, [], {}
