"""The elements of a line model (rod, shaft, beam, rotor) as the load recovery sees them.

An :class:`ElementSet` holds, per element e, its end coordinates, its global DOFs, its element
matrices (stiffness K_e, mass M_e, loss stiffness H_e, gyroscopic G_e per unit speed), what each
element DOF means (``roles``: a force along an axis or a moment about it, at a local position
xi in [0, 1]) and the distributed inertia behind M_e and G_e (``terms``), which the recovery
needs for values inside an element.

Axes: x along the shaft, y and z lateral.  A force role ("F", a) is conjugate to the displacement
along axis a, a moment role ("M", a) to the rotation about axis a, so the generalised end force of
an element DOF is directly a force or a moment component (plane beams use the x-y plane: w is the
displacement along y, its slope the rotation about z).  Each :class:`LineTerm` is a density

    r(s) = weight(s) * shape(s) @ u_e            (component ``kind``/``axis``)

with u_e the element's accelerations (plus alpha times its velocities for mass-proportional
damping; ``source = "inertia"``) or its velocities times the spin speed (``"gyroscopic"``), such
that the element's inertia matrix is  sum over terms of  int row(s)^T weight(s) shape(s) ds  with
``row`` the interpolation of the term's own component (tests check this against M_e and G_e).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import scipy.sparse as sp

FORCE, MOMENT = "F", "M"
AXES = "xyz"
#: lever arms: the moment about axis a of a force along axis b at (s - x) e_x is  sign (s - x) F_b
#: (e_x x e_y = e_z, e_x x e_z = -e_y): M_z <- +F_y, M_y <- -F_z
ARM = {2: (1, 1.0), 1: (2, -1.0)}


@dataclass
class LineTerm:
    """A distributed load density inside the elements (module notes).  ``weight(el, xi)`` -> (S, n)
    and ``shape(el, xi)`` -> (S, n, nb) for element indices ``el`` (S,) and local points ``xi``
    (S, n); ``row`` is the interpolation of the component the density acts on (default: ``shape``)."""

    kind: str
    axis: int
    weight: Callable
    shape: Callable
    source: str = "inertia"            # "inertia" | "gyroscopic" | "load" (weight = load density, no shape)
    row: Callable | None = None

    def row_shape(self, el, xi):
        return (self.row or self.shape)(el, xi)


@dataclass
class ElementSet:
    """Elements of a line model with their matrices and the meaning of their DOFs (module notes)."""

    x0: np.ndarray                     # (E,) left end of every element, m
    x1: np.ndarray                     # (E,) right end, m
    dofs: np.ndarray                   # (E, nb) global DOF indices
    K: np.ndarray                      # (E, nb, nb)
    M: np.ndarray | None               # (E, nb, nb); None: lumped mass (the inertia belongs to the nodes)
    H: np.ndarray | None               # (E, nb, nb) loss stiffness of the material (psi), or None
    roles: list                        # (kind, axis) of every local DOF
    xi: np.ndarray                     # (nb,) local position of every local DOF
    terms: list                        # LineTerm list (empty for lumped mass)
    quantities: dict                   # name -> (kind, axis)
    n_dofs: int                        # DOFs of the whole system
    G: np.ndarray | None = None        # (E, nb, nb) gyroscopic matrix per unit spin speed
    load_terms: list = field(default_factory=list)   # LineTerm(source="load") per unit load factor
    applied: np.ndarray | None = None  # (E, nb) consistent element loads per unit load factor
    description: str = ""

    @property
    def n_elements(self) -> int:
        return int(self.x0.size)

    @property
    def length(self) -> np.ndarray:
        return self.x1 - self.x0

    def assembled(self, A: np.ndarray) -> sp.csr_matrix:
        """sum_e A_e scattered to the global DOFs (to compare with the assembled matrices)."""
        E, nb = self.dofs.shape
        rows = np.repeat(self.dofs, nb, axis=1).ravel()
        cols = np.tile(self.dofs, (1, nb)).ravel()
        return sp.csr_matrix((np.asarray(A).ravel(), (rows, cols)), shape=(self.n_dofs, self.n_dofs))

    def scatter(self, f: np.ndarray) -> np.ndarray:
        """sum_e of element vectors f (E, nb, T) at the global DOFs -> (n_dofs, T)."""
        out = np.zeros((self.n_dofs,) + f.shape[2:], dtype=f.dtype)
        np.add.at(out, self.dofs, f)
        return out

    def local(self, kind: str, axis: int) -> np.ndarray:
        """Local DOF indices with the role (kind, axis)."""
        return np.array([k for k, r in enumerate(self.roles) if r == (kind, axis)], dtype=int)

    def locate(self, x: float, side: str, where: str = "x") -> tuple[int, float]:
        """(element, local xi) of the station x; at a node, the element to the right of x (``side`` =
        "right", the section just right of x) or to the left ("left"), or the only one there is."""
        from discrete.errors import ModelError

        lo, hi = float(self.x0.min()), float(self.x1.max())
        tol = 1e-9 * max(hi - lo, 1e-300)
        if not np.isfinite(x) or x < lo - tol or x > hi + tol:
            raise ModelError("section loads", where, x, f"a station on the shaft, {lo:g} <= x <= {hi:g} m")
        starts = np.flatnonzero(np.abs(self.x0 - x) <= tol)
        ends = np.flatnonzero(np.abs(self.x1 - x) <= tol)
        if side == "right" and starts.size:
            return int(starts[0]), 0.0
        if side == "left" and ends.size:
            return int(ends[-1]), 1.0
        if starts.size:
            return int(starts[0]), 0.0
        if ends.size:
            return int(ends[-1]), 1.0
        e = int(np.flatnonzero((self.x0 < x) & (self.x1 > x))[0])
        return e, float((x - self.x0[e]) / (self.x1[e] - self.x0[e]))


# ---------------------------------------------------------------- shape functions on the reference element
def lagrange(nodes: np.ndarray, k: int, xi: np.ndarray) -> np.ndarray:
    """The Lagrange polynomial of node k over ``nodes`` (local coordinates) at ``xi``."""
    out = np.ones_like(xi, dtype=float)
    for m, xm in enumerate(nodes):
        if m != k:
            out = out * (xi - xm) / (nodes[k] - xm)
    return out


def hermite(value: bool, at_right: bool, xi: np.ndarray, h: np.ndarray) -> np.ndarray:
    """Cubic Hermite function of a value (``value``) or slope DOF at the left/right node; h (S, 1)."""
    if value:
        return 3 * xi**2 - 2 * xi**3 if at_right else 1 - 3 * xi**2 + 2 * xi**3
    return h * (-xi**2 + xi**3) if at_right else h * (xi - 2 * xi**2 + xi**3)


def gauss(n: int = 8) -> tuple[np.ndarray, np.ndarray]:
    """n-point Gauss-Legendre rule on [0, 1]."""
    t, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (t + 1.0), 0.5 * w
