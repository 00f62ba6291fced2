"""The Reynolds equation of a finite-length journal bearing film, solved with scikit-fem.

On the unwrapped bearing surface (theta: the angle from +y towards +z, the direction in which the
shaft surface moves for a spin about +x; zeta = z / R along the axis) the isoviscous, incompressible
Reynolds equation with the film thickness h = c H, H = 1 - X cos(theta) - Y sin(theta) (journal
centre at (y, z) = c (X, Y) relative to the bearing centre) reads

    d/dtheta (H^3 dP/dtheta) + d/dzeta (H^3 dP/dzeta) = 6 omega dH/dtheta + 12 dH/dt,
    p = (mu R^2 / c^2) P,

(Hamrock, Schmid & Jacobson, *Fundamentals of Machine Elements*, or Frene et al., *Hydrodynamic
Lubrication* (1997) ch. 5), whose right-hand side is g = a sin(theta) + b cos(theta) with
a = -6 omega X + 12 Y', b = 6 omega Y + 12 X' (X' = y'/c in 1/s).  The film covers theta in
[0, 2 pi) (periodic) and, by the symmetry of an aligned journal, the half length zeta in [0, L/D]:
no flux through the mid-plane, P = 0 at the bearing end (ambient), and P = 0 over axial supply
grooves (supply at ambient pressure).

Weak form (P1 triangles on a right-angled tensor mesh: the stiffness is an M-matrix for any
aspect ratio, so the discrete cavitation problem below is monotone):

    int H^3 grad P . grad v = int g v    for every v vanishing on the Dirichlet nodes.

**Cavitation.**  ``"reynolds"`` (Swift-Stieber): the film ruptures where the pressure would fall
below ambient, with P = 0 and zero pressure gradient on the free boundary.  It is the obstacle
problem P >= 0, A P - r >= 0, P (A P - r) = 0 (Kinderlehrer & Stampacchia 1980; Bayada &
Chambat 1983 for the Reynolds condition as its variational inequality), solved exactly (to the
linear solver's round-off) by the primal-dual active-set method (Hintermueller, Ito & Kunisch,
SIAM J. Optim. 13 (2003)), which terminates in finitely many steps on an M-matrix.  It is the
condition of the published finite-bearing tables (Lund & Thomsen 1978; Someya 1989), hence the
default: the validation is like for like.  A mass-conserving model (Elrod / JFO) moves the
reformation boundary, which for a fully flooded bearing with supply grooves lies at the groove
and hardly changes the steady film; it is not implemented.  ``"gumbel"`` (half-Sommerfeld): the
full-film solution with its negative part discarded; the closed forms of Ocvirk and Sommerfeld
use it, so it serves their limits.

**Perturbation.**  The film force is F = -(mu R^4 / c^2) * 2 int P (cos, sin) dtheta dzeta.  Its
derivatives with respect to X, Y (through A(H) and g) and to X', Y' (through g) are the exact
derivatives of the discrete solution with the cavitated set held: on the free boundary of the
Reynolds condition P and grad P vanish, so its first-order movement changes neither the pressure
nor the force (Lund & Thomsen 1978 use the same argument); with Guembel's condition the force's
integrand vanishes on the boundary.  Four solves with the factorised film matrix give the eight
linear coefficients.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import Basis, BilinearForm, ElementTriP1, LinearForm, MeshTri

from discrete.errors import ModelError, SolverError

CAVITATION = ("reynolds", "gumbel")


@BilinearForm
def film_flow(u, v, w):
    """H^3 grad u . grad v (the Poiseuille flow of the film, H^3 given at the quadrature points)."""
    return w["h3"] * (u.grad[0] * v.grad[0] + u.grad[1] * v.grad[1])


@LinearForm
def cosine_load(v, w):
    """cos(theta) v: the Couette/squeeze source's cosine part, and the force's y-component."""
    return np.cos(w.x[0]) * v


@LinearForm
def sine_load(v, w):
    """sin(theta) v."""
    return np.sin(w.x[0]) * v


@dataclass
class FilmSolution:
    """A solved film: ``P`` on the free nodes, ``wet`` the nodes where the film carries pressure
    (the inactive set of the cavitation problem), ``force`` the dimensionless force on the journal
    f = -2 int P (cos, sin) (F = mu R^4 / c^2 f), ``iterations`` of the active-set method."""

    X: float
    Y: float
    a: float
    b: float
    P: np.ndarray
    wet: np.ndarray
    force: np.ndarray
    iterations: int


class ReynoldsFilm:
    """The discretised film of one bearing geometry (see the module notes).

    ``length_ratio`` L/D; ``n_theta`` elements around, ``n_axial`` along the half length;
    ``cavitation`` "reynolds" or "gumbel"; ``grooves`` ((centre, width), ...) in radians, the
    centre measured like theta (from +y towards +z)."""

    def __init__(self, length_ratio: float, n_theta: int = 144, n_axial: int = 16, cavitation: str = "reynolds",
                 grooves=()):
        if cavitation not in CAVITATION:
            raise ModelError("journal bearing", "cavitation", cavitation, " | ".join(map(repr, CAVITATION)))
        self.length_ratio = float(length_ratio)
        self.cavitation = cavitation
        theta = np.linspace(0.0, 2 * np.pi, int(n_theta) + 1)
        zeta = np.linspace(0.0, self.length_ratio, int(n_axial) + 1)
        self.mesh = MeshTri.init_tensor(theta, zeta)
        self.basis = Basis(self.mesh, ElementTriP1(), intorder=4)
        x = np.asarray(self.basis.global_coordinates())
        self._cos_q, self._sin_q = np.cos(x[0]), np.sin(x[0])
        # periodic identification theta = 2 pi -> theta = 0 (same zeta)
        p = self.mesh.p
        n = p.shape[1]
        right = np.flatnonzero(np.isclose(p[0], 2 * np.pi))
        left = np.flatnonzero(np.isclose(p[0], 0.0))
        target = np.arange(n)
        li = left[np.argsort(p[1, left])]
        ri = right[np.argsort(p[1, right])]
        target[ri] = li
        keep = np.setdiff1d(np.arange(n), ri)
        index = np.full(n, -1)
        index[keep] = np.arange(keep.size)
        self._map = index[target]                                   # full node -> reduced node
        self._Pmap = sp.csr_matrix((np.ones(n), (np.arange(n), self._map)), shape=(n, keep.size))
        th, ze = p[0, keep], p[1, keep]
        fixed = np.isclose(ze, self.length_ratio)
        for centre, width in grooves:
            d = np.angle(np.exp(1j * (th - centre)))               # signed distance around the circle
            fixed |= np.abs(d) <= 0.5 * width + 1e-9
        self.free = np.flatnonzero(~fixed)
        self.theta, self.zeta = th[self.free], ze[self.free]
        self._load_c = self._reduce_vec(cosine_load.assemble(self.basis))[self.free]
        self._load_s = self._reduce_vec(sine_load.assemble(self.basis))[self.free]
        self._wet_prev = None

    # ---------------------------------------------------------------- assembly
    def _reduce_vec(self, f: np.ndarray) -> np.ndarray:
        return self._Pmap.T @ f

    def _reduce(self, A: sp.spmatrix) -> sp.csr_matrix:
        R = (self._Pmap.T @ A @ self._Pmap).tocsr()
        return R[self.free][:, self.free].tocsr()

    def film_thickness(self, X: float, Y: float):
        """H = 1 - X cos(theta) - Y sin(theta) at the quadrature points; an error at contact (H <= 0)."""
        H = 1.0 - X * self._cos_q - Y * self._sin_q
        if H.min() <= 0:
            raise SolverError(f"journal at eccentricity ratio {np.hypot(X, Y):.6g} >= 1: the film has closed")
        return H

    def matrix(self, X: float, Y: float, weight=None) -> sp.csr_matrix:
        """The film matrix int w grad u . grad v on the free nodes (w = H^3 by default)."""
        H = self.film_thickness(X, Y)
        w = H ** 3 if weight is None else weight(H)
        return self._reduce(film_flow.assemble(self.basis, h3=w))

    def source(self, a: float, b: float) -> np.ndarray:
        """r = int (a sin + b cos) v on the free nodes."""
        return a * self._load_s + b * self._load_c

    def force_of(self, P: np.ndarray) -> np.ndarray:
        """f = -2 int P_h (cos, sin) over the half domain (the whole film by symmetry)."""
        return -2.0 * np.array([self._load_c @ P, self._load_s @ P])

    # ---------------------------------------------------------------- solve
    def solve(self, X: float, Y: float, a: float, b: float, wet=None) -> FilmSolution:
        """The film at the journal position (X, Y) with the source coefficients (a, b); ``wet``:
        a starting guess of the pressurised nodes (the last solution's by default)."""
        A = self.matrix(X, Y)
        r = self.source(a, b)
        if self.cavitation == "gumbel":
            P = spla.spsolve(A.tocsc(), r)
            wet = P > 0
            sol = FilmSolution(X, Y, a, b, P, wet, self.force_of(np.where(wet, P, 0.0)), 0)
        else:
            sol = self._obstacle(A, r, X, Y, a, b, self._wet_prev if wet is None else wet)
        self._wet_prev = sol.wet
        return sol

    def _obstacle(self, A, r, X, Y, a, b, wet) -> FilmSolution:
        """Primal-dual active set: P >= 0, A P - r >= 0, complementary (see the module notes)."""
        n = r.size
        if wet is None or np.size(wet) != n:
            P0 = spla.spsolve(A.tocsc(), r)
            wet = P0 > 0
        wet = np.asarray(wet, dtype=bool).copy()
        scale = np.abs(r).max() + 1e-300
        for it in range(1, 201):
            P = np.zeros(n)
            if wet.any():
                P[wet] = spla.spsolve(A[wet][:, wet].tocsc(), r[wet])
            lam = A @ P - r
            new = np.where(wet, P >= -1e-13 * scale, lam < -1e-13 * scale)
            if np.array_equal(new, wet):
                P[~wet] = 0.0
                return FilmSolution(X, Y, a, b, np.maximum(P, 0.0), wet, self.force_of(np.maximum(P, 0.0)), it)
            wet = new
        raise SolverError("the cavitation (obstacle) problem of the journal film did not settle in 200 active-set "
                          "steps")

    def force(self, X: float, Y: float, a: float, b: float) -> np.ndarray:
        """The dimensionless force f on the journal (F = mu R^4 / c^2 f)."""
        return self.solve(X, Y, a, b).force

    def force_and_jacobian(self, X: float, Y: float, a: float, b: float):
        """(f, df/d(X, Y, a, b)) from one solve."""
        sol = self.solve(X, Y, a, b)
        return sol.force, self.derivatives(sol)

    def derivatives(self, sol: FilmSolution) -> np.ndarray:
        """(2, 4) derivatives of the dimensionless force with respect to (X, Y, a, b) at ``sol``,
        the wet set held (see the module notes)."""
        gumbel = self.cavitation == "gumbel"
        wet = sol.wet
        out = np.zeros((2, 4))
        if not wet.any():
            return out
        rows = np.ones(wet.size, dtype=bool) if gumbel else wet     # the unknowns of the solved system
        A = self.matrix(sol.X, sol.Y)[rows][:, rows].tocsc()
        lu = spla.splu(A)
        dA_dX = self.matrix(sol.X, sol.Y, weight=lambda H: -3 * H * H * self._cos_q)[rows][:, rows]
        dA_dY = self.matrix(sol.X, sol.Y, weight=lambda H: -3 * H * H * self._sin_q)[rows][:, rows]
        Pr = sol.P[rows]
        rhs = np.column_stack([-(dA_dX @ Pr), -(dA_dY @ Pr), self._load_s[rows], self._load_c[rows]])
        dP = np.zeros((wet.size, 4))
        dP[rows] = lu.solve(rhs)
        out[0] = -2.0 * self._load_c[wet] @ dP[wet]
        out[1] = -2.0 * self._load_s[wet] @ dP[wet]
        return out
