"""Lumped linear drives: bodies, drivers, springs, dampers and gear (transmission) constraints.

The textbook's discrete models of §4.4–4.9: each body has one generalised coordinate x
(displacement or angle) and an inertia a (mass or moment of inertia).  A spring or damper
between bodies a and b acts on the deformation  r_b x_b - r_a x_a  (``ratios = [r_a, r_b]``,
e.g. radii of a belt, default 1), so its energy is 0.5 k (r_b x_b - r_a x_a)^2.  ``ground``
is the fixed frame.  A gear makes one body's coordinate proportional to another's,
x_b = u x_a (the rigid gear pair of (3.1)); it is eliminated exactly (reduction J u^2, c u^2
of §2.2).  A driver is a body whose motion is prescribed (held in modal analysis, moved
in forced analysis).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from . import checks
from .errors import ModelError
from .linear_system import LinearSystem, check_finite

GROUND = "ground"


def rigid_motions(G: np.ndarray) -> np.ndarray:
    """An orthonormal basis of the rigid-body motions: the motions x that no spring resists, G x = 0, where the
    rows of ``G`` are the deformation gradients g (r_b x_b - r_a x_a = g . x) of the springs with k > 0.
    K = G^T diag(k) G has the same null space, but deciding it from K's eigenvalues ties the answer to the
    spread of the stiffnesses and masses (a spring k = 1 beside k = 1e10 is a mode, not a rigid motion); G
    holds only the geometry (the ratios), scaled here to unit rows and columns before the SVD."""
    n = G.shape[1]
    if G.shape[0] == 0:
        return np.eye(n)
    rows = np.linalg.norm(G, axis=1)
    G = G[rows > 0] / rows[rows > 0, None]
    cols = np.linalg.norm(G, axis=0)
    d = np.where(cols > 0, 1.0 / np.where(cols > 0, cols, 1.0), 1.0)
    ns = sla.null_space(G * d[None, :]) if G.shape[0] else np.eye(n)
    return sla.orth(ns * d[:, None]) if ns.shape[1] else np.zeros((n, 0))


@dataclass
class Body:
    name: str
    inertia: float
    inertia_rate: float = 0.0
    reactive: float = 0.0
    x0: float = 0.0
    v0: float = 0.0

    def __post_init__(self):
        where = f"[[body]] {self.name!r}"
        if not isinstance(self.name, str) or not self.name:
            raise ModelError("[[body]]", "name", self.name, "a non-empty name other than 'ground'")
        self.inertia = checks.positive(where, "inertia", self.inertia, "mass (kg) or moment of inertia (kg m^2)")
        for key in ("inertia_rate", "x0", "v0"):
            setattr(self, key, checks.finite(where, key, getattr(self, key)))
        self.reactive = checks.bounded(where, "reactive", self.reactive, (">=", 0.0), ("<=", 1.0),
                                       "reactive coefficient eps: 0 a mass change at zero relative velocity, 1 the "
                                       "momentum form")


@dataclass
class Driver:
    """Prescribed motion x(t) = offset + velocity t + amplitude sin(omega t + phase)."""

    name: str
    velocity: float | None = None
    amplitude: float = 0.0
    omega: float = 0.0
    phase: float = 0.0
    inertia: float = 0.0
    offset: float = 0.0

    def __post_init__(self):
        where = f"[[driver]] {self.name!r}"
        if not isinstance(self.name, str) or not self.name:
            raise ModelError("[[driver]]", "name", self.name, "a non-empty name other than 'ground'")
        self.velocity = checks.optional(checks.finite, where, "velocity", self.velocity, "m/s or rad/s")
        for key in ("amplitude", "phase", "offset"):
            setattr(self, key, checks.finite(where, key, getattr(self, key)))
        self.omega = checks.non_negative(where, "omega", self.omega, "angular frequency of the harmonic part, rad/s")
        self.inertia = checks.non_negative(where, "inertia", self.inertia, "inertia of the driven coordinate")
        if self.amplitude != 0 and self.omega == 0:
            raise ModelError(where, "omega", self.omega, "a number > 0 with amplitude")

    def position(self, t):
        return self.offset + (self.velocity or 0.0) * t + self.amplitude * np.sin(self.omega * t + self.phase)

    def velocity_at(self, t):
        return (self.velocity or 0.0) + self.amplitude * self.omega * np.cos(self.omega * t + self.phase)

    def acceleration(self, t):
        return -self.amplitude * self.omega**2 * np.sin(self.omega * t + self.phase)


@dataclass
class Link:
    """A spring (``value`` = k) or damper (``value`` = c) acting on r_b x_b - r_a x_a."""

    between: tuple[str, str]
    value: float
    ratios: tuple[float, float] = (1.0, 1.0)
    psi: float = 0.0

    def __post_init__(self):
        where = f"link {self.between!r}"
        self.between = _pair(where, self.between)
        self.value = checks.non_negative(where, "value", self.value, "stiffness k of a spring or coefficient c "
                                         "of a damper")
        if isinstance(self.ratios, (str, bytes)) or np.ndim(self.ratios) != 1 or len(self.ratios) != 2:
            raise ModelError(where, "ratios", self.ratios, "[r_a, r_b]: a list of 2 finite numbers")
        self.ratios = tuple(checks.finite(where, "ratios", r, "[r_a, r_b]: a list of 2 finite numbers")
                            for r in self.ratios)
        self.psi = checks.non_negative(where, "psi", self.psi, "dissipation coefficient of the spring")


def _pair(where: str, between) -> tuple:
    if isinstance(between, (str, bytes)) or not hasattr(between, "__len__") or len(between) != 2 \
            or not all(isinstance(n, str) for n in between):
        raise ModelError(where, "between", between, "[a, b]: two names (bodies, drivers or 'ground')")
    return tuple(between)


@dataclass
class Gear:
    """Rigid transmission x_b = ratio * x_a."""

    between: tuple[str, str]
    ratio: float

    def __post_init__(self):
        where = f"[[gear]] {self.between!r}"
        self.between = _pair(where, self.between)
        self.ratio = checks.finite(where, "ratio", self.ratio, "the transmission ratio, non-zero")
        if self.ratio == 0:
            raise ModelError(where, "ratio", self.ratio, "a finite non-zero number")


@dataclass
class LumpedModel:
    bodies: list[Body]
    drivers: list[Driver] = field(default_factory=list)
    springs: list[Link] = field(default_factory=list)
    dampers: list[Link] = field(default_factory=list)
    gears: list[Gear] = field(default_factory=list)
    title: str = ""

    def __post_init__(self):
        for key, cls in (("bodies", Body), ("drivers", Driver), ("springs", Link), ("dampers", Link),
                         ("gears", Gear)):
            items = getattr(self, key)
            if isinstance(items, (str, bytes)) or not hasattr(items, "__iter__"):
                raise ModelError("lumped model", key, items, f"a list of discrete.lumped.{cls.__name__}")
            items = list(items)
            for i, it in enumerate(items, 1):
                if not isinstance(it, cls):
                    raise ModelError(f"{key} #{i}", key, it, f"a discrete.lumped.{cls.__name__}")
            setattr(self, key, items)
        names = [b.name for b in self.bodies] + [d.name for d in self.drivers]
        seen = set()
        for i, n in enumerate(names):
            if n == GROUND or n in seen or not isinstance(n, str) or not n:
                raise ModelError(f"body/driver #{i + 1}", "name", n,
                                 "a unique non-empty name other than 'ground'")
            seen.add(n)
        for i, b in enumerate(self.bodies, 1):
            if not b.inertia > 0:
                raise ModelError(f"[[body]] #{i} ({b.name})", "inertia", b.inertia, "a number > 0 (kg or kg m^2)")
        allowed = set(names) | {GROUND}
        for kind, items in (("spring", self.springs), ("damper", self.dampers), ("gear", self.gears)):
            for i, it in enumerate(items, 1):
                where = f"[[{kind}]] #{i}"
                if len(it.between) != 2 or it.between[0] == it.between[1]:
                    raise ModelError(where, "between", list(it.between), "two different names")
                for n in it.between:
                    if n not in allowed:
                        raise ModelError(where, "between", n, "one of " + ", ".join(map(repr, sorted(allowed))))
                if kind != "gear":
                    checks.non_negative(where, "k" if kind == "spring" else "c", it.value)
        for i, g in enumerate(self.gears, 1):
            where = f"[[gear]] #{i}"
            if GROUND in g.between:
                raise ModelError(where, "between", list(g.between), "two bodies (a gear to ground is a clamp)")
            if g.between[1] in [d.name for d in self.drivers]:
                raise ModelError(where, "between", list(g.between),
                                 "[driving, driven] with the driven one a body (not a driver)")
            if not g.ratio != 0 or not math.isfinite(g.ratio):
                raise ModelError(where, "ratio", g.ratio, "a finite non-zero number")

    # ----------------------------------------------------------- coordinates
    @property
    def names(self) -> list[str]:
        return [b.name for b in self.bodies] + [d.name for d in self.drivers]

    def transformation(self) -> tuple[list[str], np.ndarray]:
        """Independent coordinates and T with x_all = T x_independent (gears eliminated)."""
        names = self.names
        idx = {n: i for i, n in enumerate(names)}
        dependent = {}
        for i, g in enumerate(self.gears, 1):
            a, b = g.between
            if b in dependent:
                raise ModelError(f"[[gear]] #{i}", "between", list(g.between),
                                 f"a body driven by one gear only ({b!r} is already driven)")
            dependent[b] = (a, g.ratio)
        indep = [n for n in names if n not in dependent]
        col = {n: j for j, n in enumerate(indep)}
        T = np.zeros((len(names), len(indep)))

        def row(n, depth=0):
            if depth > len(names):
                raise ModelError("[[gear]]", "between", n, "gear chains without loops")
            if n in col:
                r = np.zeros(len(indep))
                r[col[n]] = 1.0
                return r
            a, u = dependent[n]
            return u * row(a, depth + 1)

        for n in names:
            T[idx[n]] = row(n)
        return indep, T

    def _gradient(self, ln: Link) -> np.ndarray:
        """g with r_b x_b - r_a x_a = g . x over all bodies and drivers."""
        idx = {n: i for i, n in enumerate(self.names)}
        g = np.zeros(len(idx))
        (a, b), (ra, rb) = ln.between, ln.ratios
        if a != GROUND:
            g[idx[a]] -= ra
        if b != GROUND:
            g[idx[b]] += rb
        return g

    def _link_matrix(self, links: list[Link], use_psi: bool = False) -> np.ndarray:
        names = self.names
        A = np.zeros((len(names), len(names)))
        for ln in links:
            g = self._gradient(ln)
            coef = ln.value * (2 * ln.psi / (4 * math.pi) if use_psi else 1.0)
            A += coef * np.outer(g, g)
        return A

    def linear_system(self) -> LinearSystem:
        """The linear system in the independent coordinates; drivers are constrained DOFs."""
        indep, T = self.transformation()
        inert = np.array([b.inertia for b in self.bodies] + [d.inertia for d in self.drivers])
        M = T.T @ np.diag(inert) @ T
        K = T.T @ self._link_matrix(self.springs) @ T
        C = T.T @ self._link_matrix(self.dampers) @ T
        H = T.T @ self._link_matrix(self.springs, use_psi=True) @ T
        check_finite(self.title or "lumped model", M=M, K=K, C=C, H=H)
        drivers = {d.name for d in self.drivers}
        constrained = [j for j, n in enumerate(indep) if n in drivers]
        free = [j for j in range(len(indep)) if j not in set(constrained)]
        rigid = np.zeros((len(indep), 0))
        if free:
            G = np.array([self._gradient(ln) for ln in self.springs if ln.value > 0]).reshape(-1, len(self.names))
            ns = rigid_motions((G @ T)[:, free])
            rigid = np.zeros((len(indep), ns.shape[1]))
            rigid[free] = ns
        return LinearSystem(M=sp.csr_matrix(M), K=sp.csr_matrix(K), C=sp.csr_matrix(C), H=sp.csr_matrix(H),
                            dof_field=np.full(len(indep), "x", dtype=object),
                            dof_name=np.array(indep, dtype=object), constrained=np.array(constrained, dtype=int),
                            rigid_modes=rigid, title=self.title, physics="lumped")

    def driver(self, name: str) -> Driver:
        for d in self.drivers:
            if d.name == name:
                return d
        raise KeyError(name)
