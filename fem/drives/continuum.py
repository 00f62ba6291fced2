"""Continuum pseudo-medium model of a regular drive (§10.5) as a two-field scikit-fem model.

Fields theta(x) (P1 or P2) and y(x) (same element) on one mesh of [0, L]; theta is clamped at
the clamped ends, y is free (or held everywhere for a grounded mechanism output).  Eliminating
y gives the shaft equation with the frequency-dependent inertia
rho(p) = rho0 + m_bar Pi'^2 / (1 - p^2/k^2) of (10.48), whose roots are (10.50); the
stop band (k, p_*) of (10.54) contains no eigenvalue, and the y-dominated eigenvalues
accumulate at k from below (one per y DOF).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import Basis, ElementLineP1, ElementLineP2, MeshLine, asm

from discrete.linear_system import LinearSystem

from . import forms
from .model import DriveModel


@dataclass
class ContinuumDrive:
    system: LinearSystem
    basis: Basis
    i_theta: np.ndarray
    i_y: np.ndarray
    params: dict
    load: np.ndarray | None = None     # consistent load vector of f_bar = n F / L on y

    def values_at(self, q: np.ndarray, x, field: str = "theta") -> np.ndarray:
        """theta(x) or y(x) of a DOF vector (or (n_dofs, k) array), interpolated by the FE basis."""
        parts = self.basis.split(np.zeros(self.basis.N))
        b = parts[0][1] if field == "theta" else parts[1][1]
        idx = self.i_theta if field == "theta" else self.i_y
        P = b.probes(np.atleast_2d(np.asarray(x, dtype=float)))
        return P @ np.asarray(q)[idx]


def build_continuum(model: DriveModel, *, elements: int | None = None, order: int | None = None,
                    delta: float = 0.0) -> ContinuumDrive:
    """Assemble the pseudo-medium of ``model`` (smeared parameters from :meth:`DriveModel.smeared`)."""
    prm = model.smeared()
    ne = int(elements or model.continuum_elements)
    p = int(order or model.continuum_order)
    L = prm["L"]
    mesh = MeshLine(np.linspace(0.0, L, ne + 1))
    e = ElementLineP1() if p == 1 else ElementLineP2()
    basis = Basis(mesh, e * e, intorder=2 * p)
    rigid = prm["rigid"]
    c_bar = 0.0 if rigid else prm["c_bar"]
    rho = prm["rho"] + (prm["m_bar"] * prm["ratio"] ** 2 if rigid else 0.0)   # (10.51): y = Pi' theta
    K = asm(forms.pseudo_medium_stiffness, basis, GI=prm["GI"], c_bar=c_bar, ratio=prm["ratio"])
    M = asm(forms.pseudo_medium_mass, basis, rho=rho, m_bar=prm["m_bar"])
    f = asm(forms.smeared_output_force, basis, f_bar=model.n * model.force / L) if model.force else None
    i_th, i_y = (np.asarray(i) for i in basis.split_indices())
    x = basis.doflocs[0]
    constrained = []
    if model.start == "clamped":
        constrained += list(i_th[np.isclose(x[i_th], 0.0, atol=1e-12 * L)])
    if model.end == "clamped":
        constrained += list(i_th[np.isclose(x[i_th], L, atol=1e-12 * L)])
    if model.mechanism.output == "grounded" or rigid:
        constrained += list(i_y)
    field = np.empty(basis.N, dtype=object)
    field[i_th], field[i_y] = "theta", "y"
    rmodes = np.zeros((basis.N, 0))
    if model.boundary == "free-free" and model.mechanism.output == "free":
        rmodes = np.zeros((basis.N, 1))
        rmodes[i_th, 0], rmodes[i_y, 0] = 1.0, 0.0 if rigid else prm["ratio"]
    sys_ = LinearSystem(M=M, K=K, H=2 * delta * K if delta else None, dof_field=field, dof_x=x,
                        constrained=np.array(constrained, dtype=int), rigid_modes=rmodes,
                        title=model.title, physics="torsion")
    return ContinuumDrive(system=sys_, basis=basis, i_theta=i_th, i_y=i_y, params=prm, load=f)
