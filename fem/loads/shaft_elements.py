"""The :class:`~fem.loads.elements.ElementSet` of an assembled shaft, rod or beam (:class:`fem.FEModel`).

The element matrices are scikit-fem's elemental matrices of the very forms and coefficients that
:func:`fem.assembly.assemble` sums (``BilinearForm.elemental``), so that sum_e K_e plus the
point attachments and spring supports is the assembled K (tests check K, M and H).  Lumped mass
(``mass = "lumped"``) belongs to the nodes: the elements then carry no inertia of their own.
"""
from __future__ import annotations

import numpy as np
from skfem import Basis, ElementLineHermite, ElementLineP1, ElementLineP2

from .. import forms
from ..assembly import FEModel, _gauss_line, _hysteretic_weight, _per_element, _segment_property
from .elements import FORCE, MOMENT, ElementSet, LineTerm, hermite, lagrange

#: section-load quantities per physics: name -> (kind, axis) (plane bending: the x-y plane)
QUANTITIES = {"torsion": {"torque": (MOMENT, 0)}, "axial": {"axial_force": (FORCE, 0)},
              "bending": {"bending_moment": (MOMENT, 2), "shear_force": (FORCE, 1)}}
ROLES = {"theta": (MOMENT, 0), "u": (FORCE, 0), "w": (FORCE, 1), "w_x": (MOMENT, 2), "phi": (MOMENT, 2)}


def _elemental(form, basis: Basis, **coefficients) -> np.ndarray:
    """(E, nb, nb) element matrices A_e[i, j] = a(phi_j, phi_i) of ``form`` (rows: test functions)."""
    data = form.elemental(basis, **coefficients)
    nu, nv = data.local_shape[1], data.local_shape[0]
    return np.asarray(data.data).reshape(nu, nv, basis.nelems).transpose(2, 1, 0)


def shaft_elements(fe: FEModel) -> ElementSet:
    """The elements of ``fe`` with their matrices, DOF roles and distributed inertia."""
    model, mesh, sys_ = fe.model, fe.mesh, fe.system
    m = mesh.skfem
    loss = _hysteretic_weight(model, mesh)
    lumped = model.mass == "lumped"
    if model.physics in ("torsion", "axial"):
        basis = Basis(m, ElementLineP1() if model.order == 1 else ElementLineP2(), intorder=2 * model.order)
        if model.physics == "torsion":
            stiff = _segment_property(model, mesh, lambda s, i: s.material.G * s.section.need("J", f"[[segment]] #{i}", "torsion"))
            inert = _segment_property(model, mesh, lambda s, i: s.material.rho * s.section.need("Ip", f"[[segment]] #{i}", "torsion") + s.rho_extra)
        else:
            stiff = _segment_property(model, mesh, lambda s, i: s.material.E * s.section.need("A", f"[[segment]] #{i}", "axial"))
            inert = _segment_property(model, mesh, lambda s, i: s.material.rho * s.section.A + s.rho_extra)
        K = _elemental(forms.rod_stiffness, basis, stiffness=_per_element(stiff, basis))
        M = _elemental(forms.rod_mass, basis, inertia=_per_element(inert, basis))
        dist = [(model.fields[0], inert)]
    elif model.theory == "euler-bernoulli":
        basis = Basis(m, ElementLineHermite(), intorder=6)
        stiff_basis = Basis(m, ElementLineHermite(), intorder=2)
        EI = _segment_property(model, mesh, lambda s, i: s.material.E * s.section.need("I", f"[[segment]] #{i}", "bending"))
        rhoA = _segment_property(model, mesh, lambda s, i: s.material.rho * s.section.need("A", f"[[segment]] #{i}", "bending") + s.rho_extra)
        K = _elemental(forms.euler_bernoulli_stiffness, stiff_basis, EI=_per_element(EI, stiff_basis))
        M = _elemental(forms.euler_bernoulli_mass, basis, rhoA=_per_element(rhoA, basis))
        dist = [("w", rhoA)]
    else:
        p = model.order
        elem = ElementLineP1() if p == 1 else ElementLineP2()
        basis = Basis(m, elem * elem, intorder=2 * p)
        reduced = Basis(m, elem * elem, quadrature=_gauss_line(p))
        kappa = np.asarray([model.shear_coefficient or s.section.shear_coefficient(s.material.nu)
                            for s in model.segments])[mesh.elem_segment]
        EI = _segment_property(model, mesh, lambda s, i: s.material.E * s.section.need("I", f"[[segment]] #{i}", "bending"))
        GA = _segment_property(model, mesh, lambda s, i: s.material.G * s.section.need("A", f"[[segment]] #{i}", "bending"))
        rhoA = _segment_property(model, mesh, lambda s, i: s.material.rho * s.section.A + s.rho_extra)
        rhoI = _segment_property(model, mesh, lambda s, i: s.material.rho * s.section.I)
        K = (_elemental(forms.timoshenko_bending, basis, EI=_per_element(EI, basis))
             + _elemental(forms.timoshenko_shear, reduced, kGA=_per_element(kappa * GA, reduced)))
        M = _elemental(forms.timoshenko_mass, basis, rhoA=_per_element(rhoA, basis), rhoI=_per_element(rhoI, basis))
        dist = [("w", rhoA), ("phi", rhoI)]
    dofs = np.asarray(basis.element_dofs).T                       # (E, nb)
    x0, x1 = mesh.nodes[:-1], mesh.nodes[1:]
    h = x1 - x0
    fields = sys_.dof_field[dofs[0]]
    xi = np.round((sys_.dof_x[dofs[0]] - x0[0]) / h[0], 12)
    roles = [ROLES[f] for f in fields]
    terms = [] if lumped else [_term(fields, xi, fld, coef, model.theory == "euler-bernoulli" and model.physics == "bending",
                                     h) for fld, coef in dist]
    H = loss[:, None, None] * K if np.any(loss) else None
    return ElementSet(x0=x0, x1=x1, dofs=dofs, K=K, M=None if lumped else M, H=H, roles=roles, xi=xi, terms=terms,
                      quantities=dict(QUANTITIES[model.physics]), n_dofs=sys_.n_dofs,
                      description=f"{model.element_name}, {mesh.n_elements} elements, {model.mass} mass")


def _term(fields, xi, field_name, coef, hermite_elements: bool, h) -> LineTerm:
    """The density coef * (interpolation of ``field_name``) @ u_e on the elements."""
    kind, axis = ROLES[field_name]
    if hermite_elements:                 # w and its slope w_x interpolate w
        slots = [(k, fields[k] == "w", xi[k] > 0.5) for k in range(len(fields))]

        def shape(el, t):
            out = np.zeros(t.shape + (len(fields),))
            hh = h[el][:, None]
            for k, is_value, right in slots:
                out[..., k] = hermite(is_value, right, t, hh)
            return out
    else:
        own = [k for k in range(len(fields)) if fields[k] == field_name]
        nodes = xi[own]

        def shape(el, t):
            out = np.zeros(t.shape + (len(fields),))
            for j, k in enumerate(own):
                out[..., k] = lagrange(nodes, j, t)
            return out

    def weight(el, t):
        return np.repeat(coef[el][:, None], t.shape[1], axis=1)

    return LineTerm(kind=kind, axis=axis, weight=weight, shape=shape)
