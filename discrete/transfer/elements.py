"""Transfer-matrix elements of single-connected chains (textbook §10.1, §10.6).

State of a section: (a, Q), a = (signed, or complex) displacement amplitude, Q = internal
force/torque transmitted through the section with the sign rule of §10.1 (tension positive
for a spring).  An element maps the state at its input to the state at its output,
[a_j; Q_j] = Gamma_j [a_{j-1}; Q_{j-1}] (10.1)-(10.2), det Gamma_j = 1 (10.4).

Element kinds used by the chain solver (:mod:`discrete.transfer.chain`), all vectorised over
an array of frequencies ``p`` (rad/s):

* members between two nodes: :class:`Spring` (10.3), :class:`Damper` (10.64), the complex
  spring c(1 + 2 i delta) (10.63) via ``Spring(c, delta)``, :class:`Shaft` (a continuous
  torsion segment, exact);
* shunts at a node: :class:`Inertia` (10.3), :class:`Ground` (spring to the frame),
  :class:`Load` (external force amplitude), :class:`Branch` (a sub-chain hanging off the node,
  condensed to its dynamic stiffness, e.g. the mechanism Pi-c-m giving J*(p) of (10.16));
* the ideal mechanism / gear :class:`Ratio` (A = Pi', D = 1/Pi', (10.3)).

Members and shunts also give their clamped-end eigenvalue counts (Wittrick-Williams J0)
so that roots can be counted below any trial frequency.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import ModelError


def _arr(p):
    return np.asarray(p, dtype=float)


# ----------------------------------------------------------------- 2x2 primitives
def spring_matrix(c) -> np.ndarray:
    """(10.3) spring: A = 1, B = 1/c, C = 0, D = 1 (c may be complex, (10.63))."""
    return np.array([[1.0, 1.0 / c], [0.0, 1.0]], dtype=complex if np.iscomplexobj(c) else float)


def inertia_matrix(J, p) -> np.ndarray:
    """(10.3) inertia: A = 1, B = 0, C = -J p^2, D = 1."""
    return np.array([[1.0, 0.0], [-J * p**2, 1.0]])


def mechanism_matrix(ratio) -> np.ndarray:
    """(10.3) ideal mechanism: A = Pi', B = 0, C = 0, D = 1/Pi'."""
    if ratio == 0 or not np.isfinite(ratio):
        raise ModelError("mechanism", "ratio", ratio, "a finite non-zero transfer function Pi'")
    return np.array([[ratio, 0.0], [0.0, 1.0 / ratio]])


def damper_matrix(b, omega) -> np.ndarray:
    """(10.64) viscous damper R = -b q': A = 1, B = 1/(i b omega), C = 0, D = 1."""
    return np.array([[1.0, 1.0 / (1j * b * omega)], [0.0, 1.0]])


def chain_product(mats) -> np.ndarray:
    """(10.6) Gamma = Gamma_n ... Gamma_1 for ``mats`` listed input -> output."""
    out = np.eye(2, dtype=np.result_type(*mats))
    for G in mats:
        out = G @ out
    return out


def parallel(mats) -> np.ndarray:
    """(10.9) parallel connection of branches between the same two sections.
    Every branch needs B != 0 (a pure inertia branch is not admissible)."""
    B = np.array([G[0, 1] for G in mats])
    if np.any(B == 0):
        raise ModelError("parallel", "B", B.tolist(), "branches with B != 0 (an elastic element in each branch)")
    g1 = sum(G[0, 0] / G[0, 1] for G in mats)
    g2 = sum(1.0 / G[0, 1] for G in mats)
    g3 = sum(G[1, 1] / G[0, 1] for G in mats)
    return np.array([[g1 / g2, 1.0 / g2], [(g1 * g3 - g2**2) / g2, g3 / g2]])


_PRIMITIVE = {"c": lambda p, c, J, r: spring_matrix(c), "J": lambda p, c, J, r: inertia_matrix(J, p),
              "Pi": lambda p, c, J, r: mechanism_matrix(r)}


def connection(name: str, p: float, c: float, J: float, ratio: float) -> np.ndarray:
    """Transfer matrix of a Table 10.1 connection such as ``"c-J-Pi"`` (order along the chain,
    input -> output), built as the product of the primitives in reverse order (10.6)."""
    parts = name.split("-")
    if sorted(parts) not in (["J", "Pi", "c"], ["c"], ["J"], ["Pi"], ["J", "c"]) or len(set(parts)) != len(parts):
        raise ModelError("connection", "name", name, "a sequence of 'c', 'J', 'Pi' joined by '-' (each once)")
    return chain_product([_PRIMITIVE[k](p, c, J, ratio) for k in parts])


# ----------------------------------------------------------------- chain elements
class Member:
    """A two-section member with a 2x2 transfer matrix ``T(p)`` (spring, damper, shaft, parallel
    connection), as opposed to the shunts (inertia, ground, load, branch) and ratios."""


@dataclass(frozen=True)
class Spring(Member):
    """Member of stiffness c; ``delta`` gives the complex stiffness c (1 + 2 i delta) (10.63)."""

    c: float
    delta: float = 0.0

    def __post_init__(self):
        if not self.c > 0 or not np.isfinite(self.c):
            raise ModelError("spring", "c", self.c, "a finite stiffness > 0")
        if self.delta < 0:
            raise ModelError("spring", "delta", self.delta, "a loss factor >= 0")

    @property
    def real(self) -> bool:
        return self.delta == 0

    def cval(self):
        return self.c * (1 + 2j * self.delta) if self.delta else self.c

    def T(self, p):
        p = _arr(p)
        c = self.cval()
        one = np.ones_like(p)
        return one, one / c, 0 * one, one

    def stiffness(self, p):
        one = np.ones_like(_arr(p))
        c = self.cval()
        return c * one, -c * one, c * one

    def det_stiffness(self, p):
        """s11 s22 - s12^2 (exactly 0 for a spring)."""
        return np.zeros(_arr(p).shape)

    def count(self, p):
        return np.zeros(_arr(p).shape, dtype=int)


@dataclass(frozen=True)
class Damper(Member):
    """Viscous damper (10.64): member with B = 1/(i b omega) (forced response only)."""

    b: float
    real = False

    def __post_init__(self):
        if not self.b > 0:
            raise ModelError("damper", "b", self.b, "a damping coefficient > 0")

    def T(self, p):
        p = _arr(p)
        one = np.ones_like(p, dtype=complex)
        return one, 1.0 / (1j * self.b * p), 0 * one, one

    def stiffness(self, p):
        s = 1j * self.b * _arr(p)
        return s, -s, s


@dataclass(frozen=True)
class Shaft(Member):
    """Continuous uniform torsion segment (exact): length l, stiffness GI, inertia per length rho.
    beta = p sqrt(rho/GI); A = D = cos(beta l), B = sin(beta l)/(GI beta), C = -GI beta sin(beta l)."""

    length: float
    GI: float
    rho: float
    delta: float = 0.0   # hysteretic loss: GI (1 + 2 i delta) (10.63)

    def __post_init__(self):
        for k in ("length", "GI"):
            if not getattr(self, k) > 0:
                raise ModelError("shaft segment", k, getattr(self, k), "a number > 0")
        if self.rho < 0:
            raise ModelError("shaft segment", "rho", self.rho, "a number >= 0")

    @property
    def real(self) -> bool:
        return self.delta == 0

    def _gi(self):
        return self.GI * (1 + 2j * self.delta) if self.delta else self.GI

    def _bl(self, p):
        return _arr(p) * self.length * np.sqrt(self.rho / self._gi())

    def T(self, p):
        bl = self._bl(p)
        c0 = self._gi() / self.length
        cs = np.cos(bl)
        if self.delta:
            with np.errstate(divide="ignore", invalid="ignore"):
                sinc = np.where(np.abs(bl) > 1e-8, np.sin(bl) / np.where(bl == 0, 1, bl), 1.0)
        else:
            sinc = np.sinc(bl / np.pi)
        return cs, sinc / c0, -c0 * bl * np.sin(bl), cs

    def stiffness(self, p):
        bl = self._bl(p)
        c0 = self.GI / self.length
        with np.errstate(divide="ignore", invalid="ignore"):
            s11 = np.where(bl > 1e-6, c0 * bl / np.tan(bl), c0 * (1 - bl**2 / 3))
            s12 = np.where(bl > 1e-6, -c0 * bl / np.sin(bl), -c0 * (1 + bl**2 / 6))
        return s11, s12, s11

    def det_stiffness(self, p):
        """s11 s22 - s12^2 = -(GI beta)^2 exactly (cot^2 - csc^2 = -1)."""
        return -(self.GI / self.length * self._bl(p)) ** 2

    def count(self, p):
        return np.floor(self._bl(p) / np.pi).astype(int)


@dataclass(frozen=True)
class Inertia:
    """Shunt inertia J (mass m): Q_out = Q_in - J p^2 a (10.3)."""

    J: float
    real = True

    def __post_init__(self):
        if self.J < 0:
            raise ModelError("inertia", "J", self.J, "a number >= 0")

    def shunt(self, p):
        return -self.J * _arr(p) ** 2


@dataclass(frozen=True)
class Ground:
    """Shunt spring k to the frame (complex allowed through delta)."""

    k: float
    delta: float = 0.0

    @property
    def real(self) -> bool:
        return self.delta == 0

    def shunt(self, p):
        return (self.k * (1 + 2j * self.delta) if self.delta else self.k) * np.ones_like(_arr(p))


@dataclass(frozen=True)
class Load:
    """External force/torque amplitude M applied at a node (Q_out = Q_in - M)."""

    M: complex
    real = True


@dataclass(frozen=True)
class Ratio:
    """Ideal mechanism or gear: a_out = Pi' a_in, Q_out = Q_in / Pi' (10.3)."""

    ratio: float
    real = True

    def __post_init__(self):
        if self.ratio == 0 or not np.isfinite(self.ratio):
            raise ModelError("mechanism", "ratio", self.ratio, "a finite non-zero transfer function Pi'")


@dataclass(frozen=True, eq=False)
class Branch:
    """A sub-chain hanging off a node (listed from the node outward), ``end`` = "free" (its
    last section carries no force, or the ``load``) or "grounded" (last section held, the
    output link sprung to the frame, (10.13)).  Condensed to its dynamic stiffness at the
    node; for Pi-c-m with a free output this gives J*(p) = J + m Pi'^2 / (1 - p^2/k^2) (10.16)."""

    elements: tuple = field(default_factory=tuple)
    end: str = "free"
    load: complex = 0.0

    def __post_init__(self):
        if self.end not in ("free", "grounded"):
            raise ModelError("branch", "end", self.end, "'free' | 'grounded'")
        object.__setattr__(self, "elements", tuple(self.elements))
        if not any(isinstance(e, (Spring, Shaft, Damper)) for e in self.elements):
            raise ModelError("branch", "elements", [type(e).__name__ for e in self.elements],
                             "a sub-chain with at least one elastic member (Spring, Shaft or Damper)")

    @property
    def real(self) -> bool:
        return all(getattr(e, "real", True) for e in self.elements)


def mechanism_branch(m: float, c: float, ratio: float, *, end: str = "free", load: complex = 0.0,
                     delta: float = 0.0) -> Branch:
    """The 1-DOF cyclic mechanism of Fig. 10.2: Pi' - c - m (output mass m, force ``load`` on it)."""
    if not m > 0:
        raise ModelError("mechanism", "m", m, "a mass > 0")
    return Branch((Ratio(ratio), Spring(c, delta), Inertia(m)), end=end, load=load)


SHUNTS = (Inertia, Ground, Load, Branch)
