"""Description of a shaft / rod / beam model: segments, supports and point attachments.

A :class:`ShaftModel` is what a TOML model file with ``[[segment]]`` tables describes; Python
users build it directly.  Checks happen here so that both routes give the same messages.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from discrete.errors import ModelError

from .sections import Material, Section

PHYSICS = ("torsion", "axial", "bending")
THEORIES = ("euler-bernoulli", "timoshenko")
MASS_KINDS = ("consistent", "lumped")
SUPPORT_TYPES = {"torsion": ("clamped", "spring"), "axial": ("clamped", "spring"),
                 "bending": ("clamped", "pinned", "spring")}

#: DOF field names per physics / theory.  ``w_x`` is the Hermite slope, ``phi`` the
#: Timoshenko section rotation.
FIELDS = {("torsion", None): ("theta",), ("axial", None): ("u",),
          ("bending", "euler-bernoulli"): ("w", "w_x"), ("bending", "timoshenko"): ("w", "phi")}


@dataclass
class Segment:
    """A uniform piece of shaft.  ``rho_extra``: extra distributed inertia per length
    (torsion: kg m^2/m as in (4.56), where J includes attached parts; axial/bending: kg/m).
    ``psi``: the textbook's dissipation coefficient of the material (hysteretic damping)."""

    length: float
    elements: int
    section: Section
    material: Material
    rho_extra: float = 0.0
    psi: float = 0.0


@dataclass
class Support:
    """``clamped`` (all DOFs of the node), ``pinned`` (bending: w only) or ``spring``
    (``k``: translational / axial / torsional stiffness, ``kr``: rotational, bending only)."""

    x: float
    type: str = "clamped"
    k: float = 0.0
    kr: float = 0.0


@dataclass
class PointAttachment:
    """Lumped attachment at a node: mass (kg), inertia (kg m^2; polar for torsion,
    diametral for bending rotation), springs to ground k (per physics) and kr (rotational)."""

    x: float
    mass: float = 0.0
    inertia: float = 0.0
    k: float = 0.0
    kr: float = 0.0


@dataclass
class ShaftModel:
    physics: str
    segments: list[Segment]
    supports: list[Support] = field(default_factory=list)
    points: list[PointAttachment] = field(default_factory=list)
    theory: str = "euler-bernoulli"
    mass: str = "consistent"
    order: int = 2
    shear_coefficient: float | None = None
    title: str = ""

    def __post_init__(self):
        where = "[model]"
        if self.physics not in PHYSICS:
            raise ModelError(where, "physics", self.physics, " | ".join(map(repr, PHYSICS)))
        if self.theory not in THEORIES:
            raise ModelError(where, "theory", self.theory, " | ".join(map(repr, THEORIES)))
        if self.mass not in MASS_KINDS:
            raise ModelError(where, "mass", self.mass, " | ".join(map(repr, MASS_KINDS)))
        if self.order not in (1, 2):
            raise ModelError(where, "order", self.order, "1 (linear Lagrange) or 2 (quadratic Lagrange)")
        if not self.segments:
            raise ModelError("", "segment", [], "at least one [[segment]] table")
        for i, s in enumerate(self.segments, 1):
            w = f"[[segment]] #{i}"
            if not s.length > 0:
                raise ModelError(w, "length", s.length, "a length > 0 (m)")
            if isinstance(s.elements, bool) or not isinstance(s.elements, (int, np.integer)) or s.elements < 1:
                raise ModelError(w, "elements", s.elements, "an integer >= 1")
            if s.rho_extra < 0:
                raise ModelError(w, "rho_extra", s.rho_extra, "a number >= 0")
            if s.psi < 0:
                raise ModelError(w, "psi", s.psi, "a dissipation coefficient >= 0")
        L = self.length
        allowed = SUPPORT_TYPES[self.physics]
        for i, s in enumerate(self.supports, 1):
            w = f"[[support]] #{i}"
            if not -1e-12 * L <= s.x <= L * (1 + 1e-12):
                raise ModelError(w, "x", s.x, f"a position on the shaft, 0 <= x <= {L:g}")
            if s.type not in allowed:
                raise ModelError(w, "type", s.type, " | ".join(map(repr, allowed)) + f" for {self.physics}")
            if s.k < 0 or s.kr < 0:
                raise ModelError(w, "k" if s.k < 0 else "kr", min(s.k, s.kr), "a stiffness >= 0")
            if s.kr and self.physics != "bending":
                raise ModelError(w, "kr", s.kr, "kr (rotational stiffness) only for physics = 'bending'")
            if s.type == "spring" and s.k == 0 and s.kr == 0:
                raise ModelError(w, "k", 0.0, "a stiffness > 0 for type = 'spring' (k and/or kr)")
        for i, p in enumerate(self.points, 1):
            w = f"[[point]] #{i}"
            if not -1e-12 * L <= p.x <= L * (1 + 1e-12):
                raise ModelError(w, "x", p.x, f"a position on the shaft, 0 <= x <= {L:g}")
            for key in ("mass", "inertia", "k", "kr"):
                if getattr(p, key) < 0:
                    raise ModelError(w, key, getattr(p, key), "a number >= 0")
            if self.physics == "torsion" and p.mass:
                raise ModelError(w, "mass", p.mass, "inertia (kg m^2) for torsion; mass is for axial/bending")
            if self.physics == "axial" and p.inertia:
                raise ModelError(w, "inertia", p.inertia, "mass (kg) for axial; inertia is for torsion/bending")
            if self.physics != "bending" and p.kr:
                raise ModelError(w, "kr", p.kr, "kr (rotational spring) only for physics = 'bending'")

    @property
    def length(self) -> float:
        return float(sum(s.length for s in self.segments))

    @property
    def fields(self) -> tuple[str, ...]:
        return FIELDS[(self.physics, self.theory if self.physics == "bending" else None)]

    @property
    def element_name(self) -> str:
        if self.physics != "bending":
            return f"Lagrange P{self.order}"
        if self.theory == "euler-bernoulli":
            return "Hermite cubic (Euler-Bernoulli)"
        return f"Timoshenko P{self.order}/P{self.order}, reduced shear integration"
