"""Modal reduction of a :class:`LinearSystem` for coupling with lumped nonlinear elements.

Two bases, both reported with how much of the static flexibility they restore at every
coupling DOF (the DOFs where nonlinear elements act):

* ``static_correction = True`` (Craig-Bampton): the coupling DOFs and the constrained DOFs
  (supports, drivers) stay physical ("boundary" B); the interior I is spanned by the
  constraint modes Psi = -K_II^-1 K_IB (exact static response to boundary motion) and the
  lowest fixed-interface modes of (K_II, M_II).  The static flexibility at the coupling DOFs
  is restored exactly.
* ``static_correction = False``: the lowest free-interface modes only; the restored share of
  the static flexibility at coupling DOF j is sum_r phi_jr^2 / lambda_r divided by (K^-1)_jj,
  and a warning is issued below ``threshold``.

Floating structures (rigid-body modes R = ``LinearSystem.rigid_modes``, K_ff singular) are reduced
with inertia relief: R is kept in the basis (free-interface: on top of the ``n_modes`` elastic
modes; Craig-Bampton: through the boundary motions, and rigid motions that leave the boundary at
rest as zero-frequency fixed-interface modes on top of ``n_modes``); static shapes of a floating
part are its elastic response, mass-orthogonal to R; and the restitution compares elastic
flexibilities, sum over elastic modes of phi_j^2 / lambda (the response to a load balanced by the
rigid-body inertia forces), on both sides.  Craig-Bampton then restores less than 1: the interior
inertia-relief loads are carried by the retained fixed-interface modes only (for a free-free bar
coupled at one end, 96/pi^4 sum_{k<=n} (2k-1)^-4: 98.6 % with one mode).

The reduced system is again a :class:`LinearSystem`: boundary DOFs keep their labels,
modal coordinates are labelled ``eta1``, ``eta2``, ... (rigid-body ones first, and passed on as
its ``rigid_modes``).  ``expand`` maps reduced coordinates back to the full DOF vector (field
histories for rendering and export).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import ModelError, SolverError
from ..linear_system import LinearSystem

from .modal import EPS, _factor, as_linear_system, modal_analysis


@dataclass
class ReducedModel:
    system: LinearSystem                 # the reduced system
    T: np.ndarray                        # full DOFs = T @ reduced DOFs (n_full x n_red)
    coupling: np.ndarray                 # coupling DOFs (full indices)
    coupling_reduced: np.ndarray         # the same DOFs in the reduced system
    restitution: np.ndarray              # restored share of the (floating: elastic) static flexibility per coupling DOF
    highest_frequency_hz: float          # highest natural frequency of the reduced system
    retained_modes: int                  # modal coordinates (a floating structure's rigid modes included)
    static_correction: bool
    threshold: float
    warnings: list[str] = field(default_factory=list)

    @property
    def suggested_time_step(self) -> float:
        """A twentieth of the shortest retained period (explicit/implicit steppers)."""
        return 1.0 / (20.0 * self.highest_frequency_hz)

    def project(self, g_full: np.ndarray) -> np.ndarray:
        """An element's DOF coefficients in reduced coordinates: g_red = T^T g (g . q = g_red . z)."""
        return self.T.T @ np.asarray(g_full, dtype=float)

    def expand(self, z: np.ndarray) -> np.ndarray:
        """Full DOF vector(s) from reduced coordinates; ``z`` is (n_red,) or (n_times, n_red)."""
        return np.asarray(z) @ self.T.T

    def report(self) -> dict:
        return {"method": "Craig-Bampton (static correction)" if self.static_correction else "free-interface modes",
                "retained_modes": self.retained_modes, "n_reduced_dofs": self.system.n_dofs,
                "coupling_dofs": [self.system.label(int(i)) for i in self.coupling_reduced],
                "restitution": self.restitution.tolist(), "threshold": self.threshold,
                "highest_frequency_hz": self.highest_frequency_hz,
                "suggested_time_step_s": self.suggested_time_step, "warnings": list(self.warnings)}


def elastic_flexibility(K, M, R: np.ndarray | None, rows: np.ndarray) -> np.ndarray:
    """Diagonal of the static flexibility at ``rows`` (indices of the given matrices): K^-1, or for a
    floating structure (rigid modes R on these DOFs) the elastic flexibility with inertia relief,
    sum over the elastic modes of phi_j^2 / lambda (see :func:`_solve`)."""
    E = np.zeros((K.shape[0], rows.size))
    E[rows, np.arange(rows.size)] = 1.0
    return _flexibility(K, M, np.zeros((K.shape[0], 0)) if R is None else R, E)


def _flexibility(K, M, R: np.ndarray, G: np.ndarray) -> np.ndarray:
    """g_k^T F g_k for the columns g_k of G, F the (elastic) flexibility of :func:`_solve`."""
    return np.einsum("ij,ij->j", G, _solve(K, M, R, G))


def _solve(K, M, R: np.ndarray, F: np.ndarray) -> np.ndarray:
    """Static response X to the loads F: K^-1 F, or, for a floating structure (rigid modes R, K R = 0),
    the inertia-relief response (Geradin & Rixen, Mechanical Vibrations, free structures): the load
    balanced by the rigid-body inertia forces, P F with P = I - M R (R^T M R)^-1 R^T, and the elastic
    response measured from the mean axes, R^T M X = 0 -- the bordered system
    [K, M R; R^T M, 0] [X; mu] = [F; 0].  Sparse K: sparse LU; dense K: symmetric solver."""
    nr = R.shape[1]
    if nr:
        MR = np.asarray(M @ _mass_normalised(R, M))
        MR *= abs(K).max() / abs(MR).max()               # the border scaled like K (X is unchanged)
        Z = np.zeros((nr, nr))
        K = sp.bmat([[K, MR], [MR.T, Z]], format="csc") if sp.issparse(K) else np.block([[K, MR], [MR.T, Z]])
        F = np.vstack([F, np.zeros((nr, F.shape[1]))])
    X = spla.splu(sp.csc_matrix(K)).solve(F) if sp.issparse(K) else sla.solve(K, F, assume_a="sym")
    return X[: X.shape[0] - nr]


def _mass_normalised(R: np.ndarray, M) -> np.ndarray:
    """Columns spanning R with R^T M R = I."""
    return R @ np.linalg.inv(np.linalg.cholesky(R.T @ np.asarray(M @ R))).T


def _rigid_free(system: LinearSystem, tol: float = 1e-9) -> np.ndarray:
    """Rigid-body motions of the free DOFs (rows ``system.free``): the columns of ``system.rigid_modes``
    that K_ff does not strain.  Unknown rigid modes (None): K_ff must be regular."""
    Kf = system.free_block(system.K)
    if system.rigid_modes is None:
        lu = _factor(Kf)
        ratio = 0.0 if lu is None else lu.pivot_ratio
        if lu is None or ratio <= 1e3 * EPS:
            raise SolverError(f"reduction: K_ff is singular (smallest/largest LU pivot {ratio:.1e}): the structure "
                              "floats, but its rigid-body modes are unknown (LinearSystem.rigid_modes = None); give "
                              "them so that the reduction can use inertia relief")
        return np.zeros((system.n_free, 0))
    R = system.rigid_modes[system.free]
    scale = max(1.0, abs(Kf).max())
    keep = [k for k in range(R.shape[1])
            if 0 < np.linalg.norm(R[:, k]) and np.linalg.norm(Kf @ R[:, k]) <= tol * scale * np.linalg.norm(R[:, k])]
    return R[:, keep]


def _modes(system: LinearSystem, n_modes: int, R: np.ndarray) -> np.ndarray:
    """The rigid-body modes R (rows ``system.free``, mass-normalised) followed by the lowest ``n_modes``
    elastic modes of ``system``, as full-length columns."""
    nr = R.shape[1]
    shapes = modal_analysis(system, n_modes + nr).shapes
    if not nr:
        return shapes
    return np.hstack([system.expand(_mass_normalised(R, system.free_block(system.M))), shapes[:, nr:]])


def _craig_bampton(system: LinearSystem, coupling: np.ndarray, n_modes: int, R: np.ndarray):
    """Craig & Bampton (1968): boundary B = constrained + coupling DOFs kept; the interior I spanned by
    the constraint modes Psi (static response to unit boundary motion, K_II Psi = -K_IB) and the lowest
    fixed-interface modes of (K_II, M_II).  A floating interior (rigid motions R0 that leave B at rest)
    keeps R0 among the fixed-interface modes, on top of ``n_modes``, and Psi is its elastic solution
    (the loads K_IB do no work on R0: K R = 0 and R0 = 0 on B).  Returns (B, I, Psi, Phi_I)."""
    f, c = system.free, system.constrained
    interior = np.setdiff1d(f, coupling)
    boundary = np.concatenate([c, coupling])
    R0 = R[np.searchsorted(f, interior)]
    if R.shape[1] and coupling.size:
        R0 = R0 @ sla.null_space(R[np.searchsorted(f, coupling)], rcond=1e-12)
    if n_modes + R0.shape[1] > interior.size - 1:
        raise ModelError("[reduction]", "modes", n_modes,
                         f"at most {interior.size - 1 - R0.shape[1]} (interior DOFs left after the {coupling.size} "
                         f"coupling DOFs, minus one{_minus_rigid(R0.shape[1])})")
    K, M = system.K.tocsr(), system.M.tocsr()
    Kii, Mii = sp.csc_matrix(K[interior][:, interior]), M[interior][:, interior]
    Psi = _solve(Kii, Mii, R0, -K[interior][:, boundary].toarray())
    sub = LinearSystem(M=Mii, K=Kii, dof_field=system.dof_field[interior], rigid_modes=R0 if R0.shape[1] else None)
    return boundary, interior, Psi, _modes(sub, n_modes, R0)


def _free_interface(system: LinearSystem, n_modes: int, R: np.ndarray):
    """The rigid-body modes R and the lowest ``n_modes`` elastic modes of the whole system; constrained
    DOFs stay physical with their quasi-static (for a floating structure: elastic) shapes.
    Returns (B, I, Psi, Phi_I) as :func:`_craig_bampton` with B = constrained DOFs, I = free DOFs."""
    f, c = system.free, system.constrained
    if n_modes + R.shape[1] > f.size - 1:
        raise ModelError("[reduction]", "modes", n_modes,
                         f"at most {f.size - 1 - R.shape[1]} (free DOFs minus one{_minus_rigid(R.shape[1])})")
    Psi = np.zeros((f.size, 0))
    if c.size:
        K = system.K.tocsr()
        Psi = _solve(sp.csc_matrix(K[f][:, f]), system.free_block(system.M), R, -K[f][:, c].toarray())
    return c, f, Psi, _modes(system, n_modes, R)[f]


def _minus_rigid(nr: int) -> str:
    return f", minus the {nr} rigid-body mode(s) kept on top" if nr else ""


def _check(system: LinearSystem, coupling: np.ndarray, n_modes, threshold) -> None:
    if isinstance(n_modes, bool) or not isinstance(n_modes, (int, np.integer)) or n_modes < 1:
        raise ModelError("[reduction]", "modes", n_modes, "an integer >= 1")
    if not 0 < threshold <= 1:
        raise ModelError("[reduction]", "threshold", threshold, "a share in (0, 1]")
    constrained = set(system.constrained.tolist())
    for j in coupling:
        if not 0 <= j < system.n_dofs:
            raise ModelError("[reduction]", "coupling DOF", int(j), f"a DOF index from 0 to {system.n_dofs - 1}")
        if j in constrained:
            raise ModelError("[reduction]", "coupling DOF", system.label(int(j)),
                             "a free DOF (this one is held by a support or driver)")


def reduce(system: LinearSystem, coupling, n_modes: int, *, static_correction: bool = True,
           threshold: float = 0.95) -> ReducedModel:
    """Reduce ``system`` keeping ``coupling`` DOFs (full indices) for nonlinear elements; ``n_modes``
    elastic modes (a floating structure's rigid-body modes come on top)."""
    system = as_linear_system(system, "reduce")
    raw = np.atleast_1d(np.asarray(coupling))
    if raw.ndim != 1 or (raw.size and raw.dtype.kind not in "iu"):
        raise ModelError("[reduction]", "coupling", coupling, f"a list of integer DOF indices from 0 to {system.n_dofs - 1}")
    coupling = np.unique(raw.astype(int))
    if isinstance(threshold, bool) or not isinstance(threshold, (int, float, np.integer, np.floating)):
        raise ModelError("[reduction]", "threshold", threshold, "a share in (0, 1]")
    _check(system, coupling, n_modes, threshold)
    R = _rigid_free(system)
    if static_correction:
        boundary, rest, Psi, Phi = _craig_bampton(system, coupling, n_modes, R)
    else:
        boundary, rest, Psi, Phi = _free_interface(system, n_modes, R)
    nb, nm = boundary.size, Phi.shape[1]
    T = np.zeros((system.n_dofs, nb + nm))
    T[boundary, np.arange(nb)] = 1.0
    T[np.ix_(rest, np.arange(nb))] = Psi
    T[np.ix_(rest, nb + np.arange(nm))] = Phi
    nc = system.constrained.size
    red_coupling = nc + np.arange(coupling.size) if static_correction else np.array([], dtype=int)
    reduced = _project(system, T, boundary, nc, R)
    restitution = _restitution(system, reduced, T, coupling, R)
    warnings = _warnings(system, reduced, T, coupling, restitution, R, static_correction, threshold)
    lam = sla.eigh(reduced.free_block(reduced.K).toarray(), reduced.free_block(reduced.M).toarray(),
                   eigvals_only=True)
    top = float(np.sqrt(max(lam.max(), 0.0)) / (2 * np.pi))
    return ReducedModel(system=reduced, T=T, coupling=coupling, coupling_reduced=red_coupling,
                        restitution=restitution, highest_frequency_hz=top, retained_modes=nm,
                        static_correction=static_correction, threshold=threshold, warnings=warnings)


def _project(system: LinearSystem, T: np.ndarray, boundary: np.ndarray, nc: int, R: np.ndarray) -> LinearSystem:
    """The reduced system T^T A T (symmetrised); boundary DOFs keep their labels, modal ones are ``eta1``, ...;
    a floating structure's rigid modes are passed on in reduced coordinates."""
    nm = T.shape[1] - boundary.size
    Tm = sp.csr_matrix(T)
    proj = {}
    for name in ("M", "K", "C", "H"):
        A = (Tm.T @ getattr(system, name).tocsr() @ Tm).toarray()
        proj[name] = 0.5 * (A + A.T)
    Rr = None
    if R.shape[1]:
        Rr = np.zeros((T.shape[1], R.shape[1]))
        Rr[nc:] = np.linalg.lstsq(T[np.ix_(system.free, np.arange(nc, T.shape[1]))], R, rcond=None)[0]
    return LinearSystem(M=proj["M"], K=proj["K"], C=proj["C"], H=proj["H"],
                        dof_field=np.concatenate([system.dof_field[boundary], np.full(nm, "eta", dtype=object)]),
                        dof_x=np.concatenate([system.dof_x[boundary], np.full(nm, np.nan)]),
                        dof_name=np.concatenate([system.dof_name[boundary], [f"eta{r + 1}" for r in range(nm)]]),
                        constrained=np.arange(nc), rigid_modes=Rr, title=system.title,
                        physics=f"{system.physics} (reduced)")


def _restitution(system: LinearSystem, reduced: LinearSystem, T: np.ndarray, coupling: np.ndarray,
                 R: np.ndarray) -> np.ndarray:
    """Restored share of the full model's (elastic) static flexibility at each coupling DOF j:
    g^T F_r g / F_jj with g = T^T e_j (Ritz: F_r is the flexibility of the Galerkin projection, so the
    share is in (0, 1]; 1 when the basis contains the static response F e_j)."""
    if not coupling.size:
        return np.zeros(0)
    f, rf = system.free, reduced.free
    full = elastic_flexibility(system.free_block(system.K), system.free_block(system.M), R,
                               np.searchsorted(f, coupling))
    Rr = np.zeros((rf.size, 0)) if reduced.rigid_modes is None else reduced.rigid_modes[rf]
    G = T[np.ix_(coupling, rf)].T
    red = _flexibility(reduced.free_block(reduced.K).toarray(), reduced.free_block(reduced.M).toarray(), Rr, G)
    return red / full


def _warnings(system: LinearSystem, reduced: LinearSystem, T: np.ndarray, coupling: np.ndarray,
              restitution: np.ndarray, R: np.ndarray, static_correction: bool, threshold: float) -> list[str]:
    """Low restitution at a coupling DOF; rigid-body modes not reproduced by the basis (rounding)."""
    out = []
    kind = "(elastic, inertia-relief) static flexibility" if R.shape[1] else "static flexibility"
    advice = "add modes" if static_correction else "add modes or use static_correction = true"
    for j, r in zip(coupling, restitution):
        if r < threshold:
            out.append(f"the reduced basis restores only {100 * r:.1f} % of the {kind} at {system.label(int(j))} "
                       f"(threshold {100 * threshold:.0f} %): {advice}")
    if R.shape[1]:
        miss = np.linalg.norm(T[system.free] @ reduced.rigid_modes - R) / np.linalg.norm(R)
        if miss > 1e-8:
            out.append(f"the reduced basis reproduces the rigid-body modes only to {miss:.1e} (relative residual): "
                       "the stiffness matrix is too ill-conditioned for double precision (use fewer elements)")
    return out
