"""The common currency of the package: a linear second-order system with sparse matrices.

    M q'' + (C + Omega G) q' + (K + i H) q = f(t) + sum of nonlinear element forces

``H`` is the hysteretic (loss) stiffness used in harmonic analysis: an element with the
textbook's dissipation coefficient psi contributes ``2 delta K_e`` with
``delta = psi / (4 pi)`` (complex stiffness ``c (1 + 2 i delta)``).

Every DOF carries a label: its field name (``theta``, ``u``, ``w``, ``w_x``, ``phi`` for FE
models, ``x`` for lumped bodies), a coordinate ``x`` along the shaft (NaN for lumped
bodies) and an optional name (the body name in lumped models).  Constrained DOFs are held
at zero in modal analysis; in forced analysis they may carry a prescribed (base) motion.

``rigid_modes`` (full-length columns), when the builder knows them, span the motions that
satisfy the constraints without straining anything (the null space of K on the free DOFs);
``None`` means unknown, and modal analysis then detects them numerically.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from . import checks
from .errors import ModelError


def check_finite(where: str, **matrices) -> None:
    """Refuse matrices with infinite or NaN entries (a model whose assembly overflows double
    precision, e.g. stiffnesses near 1e308): every later number would be meaningless."""
    for name, A in matrices.items():
        data = A.data if sp.issparse(A) else np.asarray(A)
        if data.size and not np.all(np.isfinite(data)):
            raise ModelError(where, name, "inf/NaN entries", "model values whose assembled matrices stay finite in "
                             "double precision (|entries| < 1.8e308): scale the units or check the inputs")


def _csr(a, n: int) -> sp.csr_matrix:
    if a is None:
        return sp.csr_matrix((n, n))
    return sp.csr_matrix(a, dtype=float)


@dataclass
class LinearSystem:
    """Linear second-order system with DOF labels and constraints."""

    M: sp.csr_matrix
    K: sp.csr_matrix
    dof_field: np.ndarray
    dof_x: np.ndarray | None = None
    dof_name: np.ndarray | None = None
    C: sp.csr_matrix | None = None
    H: sp.csr_matrix | None = None
    G: sp.csr_matrix | None = None
    constrained: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    rigid_modes: np.ndarray | None = None
    title: str = ""
    physics: str = ""
    mass_proof: tuple | None = field(default=None, repr=False, compare=False)
    """``(reason, M)``: why this M is positive semi-definite by construction, with the very matrix
    object it was proven for (set by :meth:`prove_mass_semidefinite`; a system whose M is another
    object -- replaced, rebuilt, converted -- has no proof)."""

    def __post_init__(self):
        where = f"LinearSystem {self.title!r}" if self.title else "LinearSystem"
        checks.real_matrix(where, "M", self.M, note="mass matrix")
        n = self.M.shape[0]
        for name in ("K", "C", "H", "G"):
            if getattr(self, name) is not None:
                checks.real_matrix(where, name, getattr(self, name), (n, n),
                                   note="K + i H: give the loss stiffness as the real matrix H" if name in "KH"
                                   else None)
        self.M = _csr(self.M, n)
        self.K = _csr(self.K, n)
        self.C = _csr(self.C, n)
        self.H = _csr(self.H, n)
        self.G = _csr(self.G, n)
        check_finite(self.title or "model", M=self.M, K=self.K, C=self.C, H=self.H, G=self.G)
        self.dof_field = np.asarray(self.dof_field, dtype=object)
        if self.dof_field.shape != (n,):
            raise ModelError(where, "dof_field", f"{self.dof_field.size} labels", f"one label per DOF ({n})")
        for key in ("dof_x", "dof_name"):
            val = getattr(self, key)
            if val is not None and np.shape(val) != (n,):
                raise ModelError(where, key, f"shape {np.shape(val)}", f"one value per DOF ({n}) or None")
        self.dof_x = np.full(n, np.nan) if self.dof_x is None else np.asarray(self.dof_x, dtype=float)
        self.dof_name = (np.full(n, "", dtype=object) if self.dof_name is None
                         else np.asarray(self.dof_name, dtype=object))
        con = np.asarray(self.constrained)
        if con.size and (con.ndim != 1 or con.dtype.kind not in "iu" or con.min() < 0 or con.max() >= n):
            raise ModelError(where, "constrained", con.tolist() if con.size <= 8 else f"array of shape {con.shape}",
                             f"a list of integer DOF indices in [0, {n - 1}]")
        self.constrained = np.unique(con.astype(int))
        if self.rigid_modes is not None:
            R = np.asarray(self.rigid_modes)
            if R.dtype.kind not in "iuf" or R.shape[:1] != (n,) or R.ndim > 2:
                raise ModelError(where, "rigid_modes", f"shape {R.shape}",
                                 f"real columns of length {n} (one per rigid-body mode) or None")
            self.rigid_modes = R.astype(float).reshape(n, -1)

    # ------------------------------------------------------------------ DOFs
    def prove_mass_semidefinite(self, reason: str) -> None:
        """Record that M, as it is now, is positive semi-definite by construction -- e.g. an FE mass
        matrix ``sum_q rho_q dx_q phi_q phi_q^T`` with densities and quadrature weights >= 0 -- so
        that :func:`~discrete.linear.modal.modal_analysis` need not prove it by a factorisation.
        The assembler calls this after checking the conditions that ``reason`` states.  The proof
        follows the matrix object, so a replaced or rebuilt M has none; M must not be changed in
        place afterwards (nothing detects that)."""
        self.mass_proof = (str(reason), self.M)

    @property
    def mass_semidefinite_reason(self) -> str | None:
        """The reason of :meth:`prove_mass_semidefinite` while M is the matrix it was given for."""
        proof = self.mass_proof
        return proof[0] if proof is not None and proof[1] is self.M else None

    @property
    def n_dofs(self) -> int:
        return self.M.shape[0]

    @property
    def free(self) -> np.ndarray:
        mask = np.ones(self.n_dofs, dtype=bool)
        mask[self.constrained] = False
        return np.flatnonzero(mask)

    @property
    def n_free(self) -> int:
        return self.n_dofs - self.constrained.size

    def label(self, i: int) -> str:
        name = self.dof_name[i]
        if name:
            return f"{name}.{self.dof_field[i]}"
        return f"{self.dof_field[i]}@x={self.dof_x[i]:.6g}"

    def labels(self) -> list[str]:
        return [self.label(i) for i in range(self.n_dofs)]

    def fields(self) -> list[str]:
        return sorted(set(self.dof_field.tolist()))

    def dof_index(self, *, field: str | None = None, x: float | None = None, name: str | None = None,
                  where: str = "") -> int:
        """Index of the DOF with the given field at coordinate ``x`` (FE) or body ``name`` (lumped)."""
        fields = self.fields()
        if field is not None and field not in fields:
            raise ModelError(where, "dof", field, "one of " + ", ".join(repr(f) for f in fields)
                             + f" (the DOFs of this {self.physics or 'model'})")
        candidates = np.arange(self.n_dofs)
        if field is not None:
            candidates = candidates[self.dof_field[candidates] == field]
        if name is not None:
            names = sorted(set(n for n in self.dof_name.tolist() if n))
            hit = candidates[self.dof_name[candidates] == name]
            if hit.size == 0:
                raise ModelError(where, "body", name, "one of " + ", ".join(repr(n) for n in names))
            return int(hit[0])
        if x is not None:
            xs = self.dof_x[candidates]
            span = np.nanmax(self.dof_x) - np.nanmin(self.dof_x) if np.isfinite(self.dof_x).any() else 1.0
            dist = np.abs(xs - x)
            k = int(np.nanargmin(dist))
            if not dist[k] <= 1e-9 * max(span, 1e-300):
                lo, hi = np.nanmin(self.dof_x), np.nanmax(self.dof_x)
                raise ModelError(where, "x", x, f"a node position in [{lo:.6g}, {hi:.6g}] "
                                 f"(nearest node at x = {xs[k]:.6g})")
            return int(candidates[k])
        if candidates.size != 1:
            raise ModelError(where, "dof", field, "a DOF selected by x (FE) or body (lumped)")
        return int(candidates[0])

    # ------------------------------------------------------------ matrices
    def free_block(self, A: sp.spmatrix) -> sp.csr_matrix:
        """Rows and columns of the free DOFs (A itself, not a copy, when nothing is
        constrained: treat the result as read-only)."""
        if self.constrained.size == 0:
            return sp.csr_matrix(A)
        f = self.free
        return sp.csr_matrix(A[f][:, f])

    def coupling_block(self, A: sp.spmatrix) -> sp.csr_matrix:
        """Rows of free DOFs, columns of constrained DOFs (for prescribed support motion)."""
        return sp.csr_matrix(A[self.free][:, self.constrained])

    def expand(self, q_free: np.ndarray, q_constrained: np.ndarray | None = None) -> np.ndarray:
        """Full-length vector(s) from values on the free DOFs (constrained ones zero unless given)."""
        q_free = np.asarray(q_free)
        if self.constrained.size == 0 and q_constrained is None:
            return q_free.copy()
        shape = (self.n_dofs,) + q_free.shape[1:]
        out = np.zeros(shape, dtype=q_free.dtype if q_constrained is None else np.result_type(q_free, q_constrained))
        out[self.free] = q_free
        if q_constrained is not None:
            out[self.constrained] = q_constrained
        return out

    def with_damping(self, C: sp.spmatrix | None = None, H: sp.spmatrix | None = None) -> "LinearSystem":
        """A copy with extra viscous ``C`` and/or hysteretic ``H`` added."""
        return LinearSystem(M=self.M, K=self.K, dof_field=self.dof_field, dof_x=self.dof_x,
                            dof_name=self.dof_name, C=self.C + (0 if C is None else C),
                            H=self.H + (0 if H is None else H), G=self.G, constrained=self.constrained,
                            rigid_modes=self.rigid_modes, title=self.title, physics=self.physics)
