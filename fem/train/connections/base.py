"""The connection protocol: what a connection element of a train (gear mesh, coupling) provides.

A connection joins two ports (shaft nodes, bodies or the ground) and owns its law in every form the
analyses need; the assembly and the compilers loop over the connections and call these methods,
never looking at their type:

* ``speed_ratio()``: omega_b / omega_a imposed by it (None: no kinematic relation);
* ``coordinates(ts)``: its coordinates s_j = g_j . q (sparse vectors over the train's DOFs), each with
  the stiffness and damping of its linear law and a role;
* ``linear_part(ts)``: the (g, k, c) terms of its linearisation in the declared ``linear_state``
  (K += k g g^T, C += c g g^T);
* ``nonsmooth(ts)``: its linear remainder and its elements of the scalar nonsmooth protocol
  (:mod:`discrete.nonsmooth.elements`) for the time simulation and the nonlinear steady states;
* ``modulations(ts)``: the periodic part of its stiffness (parametric excitation);
* ``excitations(ts)``: prescribed displacements along its coordinates (static transmission error);
* ``force(coordinate values)``: its force along each coordinate (mesh force, coupling torque) from
  the states, for the loads.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from discrete.errors import ModelError

LINEAR_STATES = ("closed", "open")


@dataclass
class Coord:
    """A coordinate s = g . q of a connection over the train's DOFs (``idx``, ``val``: sparse g),
    with its linear stiffness ``k`` and damping ``c`` and a ``label`` (e.g. "line of action")."""

    idx: np.ndarray
    val: np.ndarray
    label: str = ""
    k: float = 0.0
    c: float = 0.0

    def dense(self, n: int) -> np.ndarray:
        g = np.zeros(n)
        np.add.at(g, self.idx, self.val)
        return g

    def outer(self, n: int, scale: float) -> sp.csr_matrix:
        """scale g g^T as a sparse n x n matrix."""
        r = np.repeat(self.idx, self.idx.size)
        c = np.tile(self.idx, self.idx.size)
        v = scale * np.outer(self.val, self.val).ravel()
        return sp.csr_matrix((v, (r, c)), shape=(n, n))

    def of(self, q: np.ndarray) -> np.ndarray:
        """s for DOF vectors q (n,) or (n, m)."""
        q = np.asarray(q)
        return self.val @ q[self.idx]


def coord(parts, label="", k=0.0, c=0.0) -> Coord:
    """A :class:`Coord` from [(dof index, coefficient), ...] (repeated indices add)."""
    parts = [(int(i), float(v)) for i, v in parts if v != 0.0]
    if not parts:
        return Coord(np.zeros(0, dtype=int), np.zeros(0), label, k, c)
    idx = np.array([p[0] for p in parts], dtype=int)
    val = np.array([p[1] for p in parts])
    u, inv = np.unique(idx, return_inverse=True)
    acc = np.zeros(u.size)
    np.add.at(acc, inv, val)
    keep = acc != 0.0
    return Coord(u[keep], acc[keep], label, k, c)


@dataclass
class ElementPart:
    """A nonsmooth element of a connection before the DOF basis is known: its class, keyword
    arguments (without name and g) and its coordinate; ``extra``: coefficients on exogenous
    coordinates (the transmission error's prescribed DOFs) by their key."""

    cls: type
    name: str
    kwargs: dict
    coord: Coord
    extra: dict = field(default_factory=dict)


@dataclass
class Excitation:
    """A prescribed displacement ``amplitude sin(harmonic w_m t + phase)`` entering the coordinate
    ``coord`` with coefficient -1 (s = g . q - e(t)): the static transmission error of a mesh."""

    key: str
    coord: Coord
    harmonic: int
    amplitude: float
    phase: float
    omega: float                   # the base frequency (tooth-pass) at the train's speed, rad/s
    stiffness: float
    damping: float


@dataclass
class Connection:
    """Base of the connection elements (see the module docstring for the protocol)."""

    name: str
    ports: tuple
    linear_state: str = "closed"

    table = "connection"

    @property
    def where(self) -> str:
        return f"[[{self.table}]] {self.name!r}"

    def check(self, train) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ModelError(f"[[{self.table}]]", "name", self.name, "a non-empty name")
        if len(self.ports) != 2:
            raise ModelError(self.where, "between", self.ports, "two ends")
        for p in self.ports:
            p.check(self.where)
            train.member(p, self.where)
        if self.linear_state not in LINEAR_STATES:
            raise ModelError(self.where, "linear_state", self.linear_state, " | ".join(map(repr, LINEAR_STATES)))

    # ------------------------------------------------------------------ protocol
    def speed_ratio(self) -> float | None:
        return None

    def coordinates(self, ts) -> list[Coord]:
        raise NotImplementedError

    def linear_part(self, ts) -> list[Coord]:
        """Coordinates with the (k, c) of the declared linear state."""
        return [] if self.linear_state == "open" else self.coordinates(ts)

    def nonsmooth(self, ts, speed: float = 0.0) -> tuple[list[Coord], list[ElementPart], dict]:
        """(linear remainder, elements, exogenous keys) for the time simulation and the steady states."""
        return self.coordinates(ts), [], {}

    def isotropic(self, ts) -> bool:
        """Whether the connection's lateral stiffness and damping are rotationally symmetric about x (then
        forward and backward whirl stay apart, :func:`fem.rotor.campbell.isotropic_supports`)."""
        return True

    def modulations(self, ts) -> list:
        return []

    def excitations(self, ts, speed: float) -> list[Excitation]:
        return []

    def force_history(self, ts, q: np.ndarray, v: np.ndarray, t: np.ndarray, speed: float) -> dict:
        """{coordinate label: force along it} for DOF histories q, v (n, m) at times t, by the
        connection's own law (for the loads)."""
        out = {}
        for cd in self.coordinates(ts):
            out[cd.label] = -cd.k * cd.of(q) - cd.c * cd.of(v)
        return out
