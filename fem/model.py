"""Description of a shaft / rod / beam model: segments, supports and point attachments.

A :class:`ShaftModel` is what a TOML model file with ``[[segment]]`` tables describes; Python
users build it directly.  Checks happen here so that both routes give the same messages.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from discrete import checks
from discrete.errors import ModelError

from .sections import KAPPA, Material, Section

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

    def __post_init__(self):
        self.check("[[segment]]")

    def check(self, where: str) -> None:
        """The rules of a ``[[segment]]`` table (``where`` names it in messages)."""
        self.length = checks.positive(where, "length", self.length, "length, m")
        self.elements = checks.integer(where, "elements", self.elements, 1, "number of finite elements")
        if not isinstance(self.section, Section):
            raise ModelError(where, "section", self.section, "a fem.Section (Section.circle(d), Section.tube(d, di) "
                             "or Section.explicit(A, I, J, Ip))")
        if not isinstance(self.material, Material):
            raise ModelError(where, "material", self.material, "a fem.Material(E, G, rho)")
        self.rho_extra = checks.non_negative(where, "rho_extra", self.rho_extra, "extra distributed inertia per length")
        self.psi = checks.non_negative(where, "psi", self.psi, "dissipation coefficient of the material")


@dataclass
class Support:
    """``clamped`` (all DOFs of the node), ``pinned`` (bending: w only) or ``spring``
    (``k``: translational / axial / torsional stiffness, ``kr``: rotational, bending only)."""

    x: float
    type: str = "clamped"
    k: float = 0.0
    kr: float = 0.0

    def __post_init__(self):
        self.check("[[support]]")

    def check(self, where: str) -> None:
        self.x = checks.finite(where, "x", self.x, "position along the shaft, m")
        checks.choice(where, "type", self.type, ("clamped", "pinned", "spring"))
        self.k = checks.non_negative(where, "k", self.k, "stiffness of a spring support")
        self.kr = checks.non_negative(where, "kr", self.kr, "rotational stiffness of a spring support, N m/rad")


@dataclass
class PointAttachment:
    """Lumped attachment at a node: mass (kg), inertia (kg m^2; polar for torsion,
    diametral for bending rotation), springs to ground k (per physics) and kr (rotational)."""

    x: float
    mass: float = 0.0
    inertia: float = 0.0
    k: float = 0.0
    kr: float = 0.0

    def __post_init__(self):
        self.check("[[point]]")

    def check(self, where: str) -> None:
        self.x = checks.finite(where, "x", self.x, "position along the shaft, m")
        for key, note in (("mass", "mass, kg"), ("inertia", "moment of inertia, kg m^2"),
                          ("k", "spring to ground"), ("kr", "rotational spring to ground, N m/rad")):
            setattr(self, key, checks.non_negative(where, key, getattr(self, key), note))


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
        if isinstance(self.order, (bool, np.bool_)) or not isinstance(self.order, (int, np.integer)) \
                or self.order not in (1, 2):
            raise ModelError(where, "order", self.order, "1 (linear Lagrange) or 2 (quadratic Lagrange)")
        if self.physics != "bending" and self.theory != "euler-bernoulli":
            raise ModelError(where, "theory", self.theory, "theory applies only to physics = 'bending' "
                             f"(this model: physics = {self.physics!r})")
        if self.shear_coefficient is not None:
            if self.physics != "bending" or self.theory != "timoshenko":
                raise ModelError(where, "shear_coefficient", self.shear_coefficient,
                                 "shear_coefficient applies only to Timoshenko bending models (None otherwise)")
            self.shear_coefficient = checks.bounded(where, "shear_coefficient", self.shear_coefficient, *KAPPA,
                                                    "Timoshenko shear coefficient kappa")
        for key, cls, table in (("segments", Segment, "segment"), ("supports", Support, "support"),
                                ("points", PointAttachment, "point")):
            items = getattr(self, key)
            if isinstance(items, (str, bytes)) or not hasattr(items, "__iter__"):
                raise ModelError(where, table, items, f"a list of fem.{cls.__name__}")
            items = list(items)
            for i, it in enumerate(items, 1):
                if not isinstance(it, cls):
                    raise ModelError(f"[[{table}]] #{i}", table, it, f"a fem.{cls.__name__}")
                it.check(f"[[{table}]] #{i}")
            setattr(self, key, items)
        if not self.segments:
            raise ModelError("", "segment", [], "at least one [[segment]] table")
        L = self.length
        allowed = SUPPORT_TYPES[self.physics]
        for i, s in enumerate(self.supports, 1):
            w = f"[[support]] #{i}"
            if not -1e-12 * L <= s.x <= L * (1 + 1e-12):
                raise ModelError(w, "x", s.x, f"a position on the shaft, 0 <= x <= {L:g}")
            if s.type not in allowed:
                raise ModelError(w, "type", s.type, " | ".join(map(repr, allowed)) + f" for {self.physics}")
            if s.kr and self.physics != "bending":
                raise ModelError(w, "kr", s.kr, "kr (rotational stiffness) only for physics = 'bending'")
            if s.type == "spring" and s.k == 0 and s.kr == 0:
                raise ModelError(w, "k", 0.0, "a stiffness > 0 for type = 'spring' (k and/or kr)")
        for i, p in enumerate(self.points, 1):
            w = f"[[point]] #{i}"
            if not -1e-12 * L <= p.x <= L * (1 + 1e-12):
                raise ModelError(w, "x", p.x, f"a position on the shaft, 0 <= x <= {L:g}")
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
