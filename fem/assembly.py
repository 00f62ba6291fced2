"""Assemble a :class:`ShaftModel` with scikit-fem into a :class:`LinearSystem`."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
from skfem import Basis, ElementLineHermite, ElementLineP1, ElementLineP2, asm

from discrete.errors import ModelError, SolverError
from discrete.linear_system import LinearSystem

from . import forms
from .mesh import LineMesh, build_line_mesh
from .model import ShaftModel


@dataclass
class FEModel:
    """An assembled FE model: the description, its mesh and basis, and the linear system."""

    model: ShaftModel
    mesh: LineMesh
    basis: Basis
    system: LinearSystem

    def nodal_values(self, q: np.ndarray, field: str) -> tuple[np.ndarray, np.ndarray]:
        """(x, value) of ``field`` at the mesh nodes (vertices) for a full-length DOF vector ``q``."""
        sys = self.system
        idx = np.flatnonzero(sys.dof_field == field)
        x = sys.dof_x[idx]
        vertex = np.isin(np.round(x / max(self.model.length, 1e-300), 12),
                         np.round(self.mesh.nodes / max(self.model.length, 1e-300), 12))
        idx, x = idx[vertex], x[vertex]
        order = np.argsort(x)
        return x[order], np.asarray(q)[idx[order]]


def _diagonal(entries: dict, n: int) -> sp.csr_matrix:
    idx = np.fromiter(entries.keys(), dtype=int, count=len(entries))
    val = np.fromiter(entries.values(), dtype=float, count=len(entries))
    return sp.csr_matrix((val, (idx, idx)), shape=(n, n))


def _rigid_modes(fields, dof_x, model_fields, held) -> np.ndarray:
    """Rigid-body motions allowed by the supports and springs: rods a uniform u/theta,
    beams the translation w = 1 and the rotation w = x (slope 1), restricted to the
    combinations that vanish at every held or spring-loaded DOF."""
    primary = fields == model_fields[0]
    cands = [np.where(primary, 1.0, 0.0)]
    if len(model_fields) > 1:
        cands.append(np.where(primary, dof_x, 1.0))
    R = np.column_stack(cands)
    held = np.unique(np.asarray(held, dtype=int))
    if held.size:
        R = R @ sla.null_space(R[held], rcond=1e-12)
    return R


def _per_element(values: np.ndarray, basis: Basis) -> np.ndarray:
    """Broadcast one value per element to the (elements, quadrature points) layout of ``basis``."""
    return np.repeat(np.asarray(values, float)[:, None], basis.X.shape[-1], axis=1)


def _segment_property(model: ShaftModel, mesh: LineMesh, fn) -> np.ndarray:
    vals = np.array([fn(s, i) for i, s in enumerate(model.segments, 1)], dtype=float)
    return vals[mesh.elem_segment]


def _hysteretic_weight(model: ShaftModel, mesh: LineMesh) -> np.ndarray:
    """2 delta per element with delta = psi / (4 pi): complex stiffness c (1 + 2 i delta)."""
    return _segment_property(model, mesh, lambda s, i: 2.0 * s.psi / (4.0 * math.pi))


#: eps * (X / h)^3 above which a Hermite mesh is refused (see :func:`hermite_mesh_check`)
HERMITE_ROUNDING_LIMIT = 1e-3


def hermite_max_ratio() -> float:
    """Largest X / h allowed for Hermite elements: (HERMITE_ROUNDING_LIMIT / eps)^(1/3) = 16 510."""
    return (HERMITE_ROUNDING_LIMIT / np.finfo(float).eps) ** (1.0 / 3.0)


def hermite_mesh_check(model: ShaftModel, mesh: LineMesh) -> None:
    """Refuse a Hermite (Euler-Bernoulli) mesh too fine for double precision, before assembling.

    scikit-fem's ``ElementLineHermite`` is an ``ElementGlobal``: per element it inverts the 4 x 4
    matrix of the cubic monomials 1, x, x^2, x^3 and their slopes at the two end nodes, in *global*
    coordinates.  Its determinant is h^4 while its entries are of size X^3 (X = the larger |x| of the
    element's nodes), so the inverse -- hence every shape function and element matrix -- carries a
    relative rounding error of about c eps (X / h)^3, whatever the units.  Measured on uniform
    cantilevers (lengths 1e-3 ... 1e3 m, the last element's stiffness against the exact 12 EI / h^3 and
    4 EI / h): c = 4 ... 9 up to 50 000 elements (2e-4 at 5 000 elements, 5e-3 at 17 000, 0.12 at
    50 000), larger beyond; ``LinAlgError: Singular matrix`` from 75 000 elements on (always at
    90 000).  The mesh is refused when eps (X / h)^3 exceeds :data:`HERMITE_ROUNDING_LIMIT` = 1e-3
    (X / h > 16 510: element matrices wrong by ~1 %, no result can be trusted), a factor of 5 in
    element count below the first measured crash.  Finer meshes below the limit (5 000 ... 16 510
    elements) assemble, and modal analysis flags their modes as not reliable in double precision.
    """
    if model.physics != "bending" or model.theory != "euler-bernoulli":
        return
    nodes = mesh.nodes
    h = np.diff(nodes)
    X = np.maximum(np.abs(nodes[:-1]), np.abs(nodes[1:]))
    ratio = X / h
    worst = int(np.argmax(ratio))
    limit = hermite_max_ratio()
    if ratio[worst] > limit:
        raise ModelError("[[segment]] elements", "elements", mesh.n_elements, _hermite_advice(model, mesh, ratio[worst]))


def _hermite_advice(model: ShaftModel, mesh: LineMesh, ratio: float) -> str:
    limit = hermite_max_ratio()
    span = float(np.max(np.abs(mesh.nodes)))
    carry = int(math.floor(limit * model.length / span))
    return (f"at most about {carry} Euler-Bernoulli (Hermite) elements for this model (uniformly spread): "
            f"scikit-fem's Hermite element inverts a cubic Vandermonde matrix in global coordinates whose rounding "
            f"error grows like eps (x / h)^3 (here x / h = {ratio:.4g}, eps (x / h)^3 = "
            f"{np.finfo(float).eps * ratio**3:.1e} > {HERMITE_ROUNDING_LIMIT:g}, the element matrices would be "
            f"wrong by about 1 % or more); use fewer elements (Hermite cubics converge fast: 50-200 elements "
            f"suffice for the low modes) or theory = 'timoshenko'")


def assemble(model: ShaftModel) -> FEModel:
    """Assemble stiffness, mass (consistent or lumped), hysteretic loss stiffness, point
    attachments and supports of ``model``.  A Hermite mesh too fine for double precision is refused
    before assembling (:func:`hermite_mesh_check`)."""
    if not isinstance(model, ShaftModel):
        raise ModelError("fem.assemble", "model", type(model).__name__,
                         "a fem.ShaftModel (segments, supports, points); lumped chains and drives have their own builders")
    mesh = build_line_mesh(model)
    hermite_mesh_check(model, mesh)
    m = mesh.skfem
    loss = _hysteretic_weight(model, mesh)
    if model.physics in ("torsion", "axial"):
        basis, K, M, H, fields = _assemble_rod(model, mesh, m, loss)
    elif model.theory == "euler-bernoulli":
        try:
            basis, K, M, H, fields = _assemble_euler_bernoulli(model, mesh, m, loss)
        except np.linalg.LinAlgError as exc:      # second line of defence: skfem's Vandermonde inverse
            h = np.diff(mesh.nodes)
            ratio = float(np.max(np.maximum(np.abs(mesh.nodes[:-1]), np.abs(mesh.nodes[1:])) / h))
            raise SolverError(f"Hermite assembly failed in scikit-fem ({exc}): "
                              + _hermite_advice(model, mesh, ratio)) from None
    else:
        basis, K, M, H, fields = _assemble_timoshenko(model, mesh, m, loss)
    dof_x = basis.doflocs[0].copy()
    add_M, add_K = {}, {}      # diagonal additions of point attachments and spring supports

    def add(table: dict, i: int, value: float) -> None:
        if value:
            table[i] = table.get(i, 0.0) + value

    primary, rotation = model.fields[0], (model.fields[1] if len(model.fields) > 1 else None)

    def at(x: float, field: str) -> int:
        hit = np.flatnonzero((fields == field) & np.isclose(dof_x, x, rtol=0, atol=1e-9 * model.length))
        return int(hit[0])

    for p in model.points:
        i = at(p.x, primary)
        add(add_M, i, p.mass if model.physics != "torsion" else p.inertia)
        add(add_K, i, p.k)
        if rotation is not None:
            j = at(p.x, rotation)
            add(add_M, j, p.inertia)
            add(add_K, j, p.kr)
    constrained, sprung = [], []
    for p in model.points:
        sprung += [at(p.x, primary)] * bool(p.k) + ([at(p.x, rotation)] * bool(p.kr) if rotation else [])
    for s in model.supports:
        if s.type == "clamped":
            constrained += [at(s.x, f) for f in model.fields]
        elif s.type == "pinned":
            constrained.append(at(s.x, "w"))
        else:
            i = at(s.x, primary)
            add(add_K, i, s.k)
            sprung += [i] * bool(s.k)
            if rotation is not None:
                j = at(s.x, rotation)
                add(add_K, j, s.kr)
                sprung += [j] * bool(s.kr)
    rigid = _rigid_modes(fields, dof_x, model.fields, constrained + sprung)
    M = sp.csr_matrix(M) + _diagonal(add_M, basis.N)
    K = sp.csr_matrix(K) + _diagonal(add_K, basis.N)
    system = LinearSystem(M=M, K=K, H=H, dof_field=fields, dof_x=dof_x,
                          constrained=np.array(constrained, dtype=int), rigid_modes=rigid, title=model.title,
                          physics=model.physics if model.physics != "bending" else f"bending ({model.theory})")
    return FEModel(model=model, mesh=mesh, basis=basis, system=system)


def _assemble_rod(model, mesh, m, loss):
    elem = ElementLineP1() if model.order == 1 else ElementLineP2()
    basis = Basis(m, elem, intorder=2 * model.order)
    if model.physics == "torsion":
        stiff = _segment_property(model, mesh, lambda s, i: s.material.G * s.section.need("J", f"[[segment]] #{i}", "torsion"))
        inert = _segment_property(model, mesh, lambda s, i: s.material.rho * s.section.need("Ip", f"[[segment]] #{i}", "torsion") + s.rho_extra)
    else:
        stiff = _segment_property(model, mesh, lambda s, i: s.material.E * s.section.need("A", f"[[segment]] #{i}", "axial"))
        inert = _segment_property(model, mesh, lambda s, i: s.material.rho * s.section.A + s.rho_extra)
    K = asm(forms.rod_stiffness, basis, stiffness=_per_element(stiff, basis))
    H = asm(forms.rod_stiffness, basis, stiffness=_per_element(stiff * loss, basis))
    M = asm(forms.rod_mass, basis, inertia=_per_element(inert, basis))
    if model.mass == "lumped":
        M = sp.diags(np.asarray(M.sum(axis=1)).ravel())
    fields = np.full(basis.N, model.fields[0], dtype=object)
    return basis, K, M, H, fields


def _assemble_euler_bernoulli(model, mesh, m, loss):
    basis = Basis(m, ElementLineHermite(), intorder=6)        # mass: cubic x cubic
    stiff_basis = Basis(m, ElementLineHermite(), intorder=2)
    EI = _segment_property(model, mesh, lambda s, i: s.material.E * s.section.need("I", f"[[segment]] #{i}", "bending"))
    rhoA = _segment_property(model, mesh, lambda s, i: s.material.rho * s.section.need("A", f"[[segment]] #{i}", "bending") + s.rho_extra)
    K = asm(forms.euler_bernoulli_stiffness, stiff_basis, EI=_per_element(EI, stiff_basis))
    H = asm(forms.euler_bernoulli_stiffness, stiff_basis, EI=_per_element(EI * loss, stiff_basis))
    M = asm(forms.euler_bernoulli_mass, basis, rhoA=_per_element(rhoA, basis))
    fields = np.empty(basis.N, dtype=object)
    fields[basis.nodal_dofs[0]] = "w"
    fields[basis.nodal_dofs[1]] = "w_x"
    if model.mass == "lumped":
        M = _hrz_lumped_hermite(M, basis, fields, mesh, rhoA)
    return basis, K, M, H, fields


def _hrz_lumped_hermite(M, basis, fields, mesh, rhoA):
    """Hinton-Rock-Zienkiewicz lumping: m_e/2 per node translation, m_e h^2/78 per rotation."""
    diag = np.zeros(basis.N)
    w = fields == "w"
    Mw = M.tocsr()[w][:, w]
    diag[w] = np.asarray(Mw.sum(axis=1)).ravel()
    h = np.diff(mesh.nodes)
    rot = rhoA * h**3 / 78.0
    t = basis.mesh.t
    np.add.at(diag, basis.nodal_dofs[1][t[0]], rot)
    np.add.at(diag, basis.nodal_dofs[1][t[1]], rot)
    return sp.diags(diag)


def _gauss_line(n: int) -> tuple[np.ndarray, np.ndarray]:
    """n-point Gauss rule on the reference interval [0, 1] (skfem's line rules have >= 2 points)."""
    xi, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (xi + 1.0)[None, :], 0.5 * w


def _assemble_timoshenko(model, mesh, m, loss):
    p = model.order
    elem = (ElementLineP1() if p == 1 else ElementLineP2())
    full = Basis(m, elem * elem, intorder=2 * p)
    reduced = Basis(m, elem * elem, quadrature=_gauss_line(p))
    nu_kappa = []
    for i, s in enumerate(model.segments, 1):
        kappa = model.shear_coefficient or s.section.shear_coefficient(s.material.nu)
        if kappa is None:
            raise ModelError(f"[[segment]] #{i} section", "kappa", None,
                             "a shear coefficient for an explicit section in a Timoshenko model "
                             "(or [model] shear_coefficient)")
        nu_kappa.append(kappa)
    kappa = np.asarray(nu_kappa)[mesh.elem_segment]
    EI = _segment_property(model, mesh, lambda s, i: s.material.E * s.section.need("I", f"[[segment]] #{i}", "bending"))
    GA = _segment_property(model, mesh, lambda s, i: s.material.G * s.section.need("A", f"[[segment]] #{i}", "bending"))
    rhoA = _segment_property(model, mesh, lambda s, i: s.material.rho * s.section.A + s.rho_extra)
    rhoI = _segment_property(model, mesh, lambda s, i: s.material.rho * s.section.I)
    Kb = asm(forms.timoshenko_bending, full, EI=_per_element(EI, full))
    Ks = asm(forms.timoshenko_shear, reduced, kGA=_per_element(kappa * GA, reduced))
    Hb = asm(forms.timoshenko_bending, full, EI=_per_element(EI * loss, full))
    Hs = asm(forms.timoshenko_shear, reduced, kGA=_per_element(kappa * GA * loss, reduced))
    M = asm(forms.timoshenko_mass, full, rhoA=_per_element(rhoA, full), rhoI=_per_element(rhoI, full))
    fields = np.empty(full.N, dtype=object)
    iw, iphi = full.split_indices()
    fields[iw], fields[iphi] = "w", "phi"
    if model.mass == "lumped":
        M = sp.diags(np.asarray(M.sum(axis=1)).ravel())
    return full, Kb + Ks, M, Hb + Hs, fields
