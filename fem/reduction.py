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

The reduced system is again a :class:`LinearSystem`: boundary DOFs keep their labels,
modal coordinates are labelled ``eta1``, ``eta2``, ...  ``expand`` maps reduced coordinates
back to the full DOF vector (field histories for rendering and export).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from discrete.errors import ModelError
from discrete.linear_system import LinearSystem

from .modal import modal_analysis


@dataclass
class ReducedModel:
    system: LinearSystem                 # the reduced system
    T: np.ndarray                        # full DOFs = T @ reduced DOFs (n_full x n_red)
    coupling: np.ndarray                 # coupling DOFs (full indices)
    coupling_reduced: np.ndarray         # the same DOFs in the reduced system
    restitution: np.ndarray              # restored share of the static flexibility per coupling DOF
    highest_frequency_hz: float          # highest natural frequency of the reduced system
    retained_modes: int
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


def _static_flexibility(K_ff: sp.spmatrix, rows: np.ndarray) -> np.ndarray:
    lu = spla.splu(sp.csc_matrix(K_ff))
    E = np.zeros((K_ff.shape[0], rows.size))
    E[rows, np.arange(rows.size)] = 1.0
    return np.einsum("ij,ij->j", E, lu.solve(E))


def reduce(system: LinearSystem, coupling, n_modes: int, *, static_correction: bool = True,
           threshold: float = 0.95) -> ReducedModel:
    """Reduce ``system`` keeping ``coupling`` DOFs (full indices) for nonlinear elements."""
    coupling = np.unique(np.asarray(coupling, dtype=int))
    constrained = set(system.constrained.tolist())
    for j in coupling:
        if j in constrained:
            raise ModelError("[reduction]", "coupling DOF", system.label(int(j)),
                             "a free DOF (this one is held by a support or driver)")
    n_free = system.n_free
    if isinstance(n_modes, bool) or not isinstance(n_modes, (int, np.integer)) or n_modes < 1:
        raise ModelError("[reduction]", "modes", n_modes, "an integer >= 1")
    f, c = system.free, system.constrained
    pos = {int(d): k for k, d in enumerate(f)}
    K, M, C, H = (system.K.tocsr(), system.M.tocsr(), system.C.tocsr(), system.H.tocsr())
    warnings = []
    if static_correction:
        interior = np.array([d for d in f if d not in set(coupling.tolist())], dtype=int)
        boundary = np.concatenate([c, coupling])
        if n_modes > interior.size - 1:
            raise ModelError("[reduction]", "modes", n_modes,
                             f"at most {interior.size - 1} (interior DOFs left after the coupling DOFs)")
        Kii = sp.csc_matrix(K[interior][:, interior])
        Kib = K[interior][:, boundary]
        lu = spla.splu(Kii)
        Psi = -lu.solve(Kib.toarray())
        sub = LinearSystem(M=M[interior][:, interior], K=Kii, dof_field=system.dof_field[interior])
        fixed = modal_analysis(sub, n_modes)
        Phi = fixed.shapes
        nb = boundary.size
        T = np.zeros((system.n_dofs, nb + n_modes))
        T[boundary, np.arange(nb)] = 1.0
        T[np.ix_(interior, np.arange(nb))] = Psi
        T[np.ix_(interior, nb + np.arange(n_modes))] = Phi
        labels_field = np.concatenate([system.dof_field[boundary], np.full(n_modes, "eta", dtype=object)])
        labels_x = np.concatenate([system.dof_x[boundary], np.full(n_modes, np.nan)])
        labels_name = np.concatenate([system.dof_name[boundary], [f"eta{r + 1}" for r in range(n_modes)]])
        red_constrained = np.arange(c.size)
        red_coupling = c.size + np.arange(coupling.size)
    else:
        if n_modes > n_free - 1:
            raise ModelError("[reduction]", "modes", n_modes, f"at most {n_free - 1} (free DOFs minus one)")
        modes = modal_analysis(system, n_modes)
        Phi = modes.shapes
        # constrained DOFs stay physical with their quasi-static shapes (zero if fixed)
        if c.size:
            Kff = sp.csc_matrix(K[f][:, f])
            Psi = -spla.splu(Kff).solve(K[f][:, c].toarray())
        T = np.zeros((system.n_dofs, c.size + n_modes))
        T[c, np.arange(c.size)] = 1.0
        if c.size:
            T[np.ix_(f, np.arange(c.size))] = Psi
        T[:, c.size:] = Phi
        labels_field = np.concatenate([system.dof_field[c], np.full(n_modes, "eta", dtype=object)])
        labels_x = np.concatenate([system.dof_x[c], np.full(n_modes, np.nan)])
        labels_name = np.concatenate([system.dof_name[c], [f"eta{r + 1}" for r in range(n_modes)]])
        red_constrained = np.arange(c.size)
        red_coupling = np.array([], dtype=int)
    Tm = sp.csr_matrix(T)
    proj = {name: (Tm.T @ A @ Tm).toarray() for name, A in (("M", M), ("K", K), ("C", C), ("H", H))}
    for name in proj:
        proj[name] = 0.5 * (proj[name] + proj[name].T)
    reduced = LinearSystem(M=proj["M"], K=proj["K"], C=proj["C"], H=proj["H"], dof_field=labels_field,
                           dof_x=labels_x, dof_name=labels_name, constrained=red_constrained,
                           title=system.title, physics=f"{system.physics} (reduced)")
    # restitution of the static flexibility at the coupling DOFs
    full_flex = _static_flexibility(K[f][:, f], np.array([pos[int(j)] for j in coupling], dtype=int)) \
        if coupling.size else np.zeros(0)
    rf = reduced.free
    Kr = reduced.free_block(reduced.K).toarray()
    G = T[np.ix_(coupling, rf)]
    red_flex = np.einsum("ij,ji->i", G, sla.solve(Kr, G.T, assume_a="sym")) if coupling.size else np.zeros(0)
    restitution = red_flex / full_flex if coupling.size else np.zeros(0)
    for j, r in zip(coupling, restitution):
        if r < threshold:
            warnings.append(f"the reduced basis restores only {100 * r:.1f} % of the static flexibility at "
                            f"{system.label(int(j))} (threshold {100 * threshold:.0f} %): add modes or use "
                            "static_correction = true")
    lam = sla.eigh(Kr, reduced.free_block(reduced.M).toarray(), eigvals_only=True)
    top = float(np.sqrt(max(lam.max(), 0.0)) / (2 * np.pi))
    return ReducedModel(system=reduced, T=T, coupling=coupling,
                        coupling_reduced=red_coupling if static_correction else np.array([], dtype=int),
                        restitution=restitution, highest_frequency_hz=top, retained_modes=n_modes,
                        static_correction=static_correction, threshold=threshold, warnings=warnings)
