"""The :class:`~fem.loads.elements.ElementSet` of an assembled rotor (:class:`fem.rotor.RotorSystem`).

The shaft elements of :mod:`fem.rotor.elements` (Nelson's Timoshenko interpolation, two bending
planes, gyroscopic coupling; with ``dofs = "full"`` also the axial and torsion rods), recomputed
with the functions and per-element arrays that :func:`fem.rotor.assemble_rotor` uses.  Element DOFs:
(v1, theta_z1, v2, theta_z2, w1, theta_y1, w2, theta_y2[, u1, u2, theta_x1, theta_x2]).  Discs,
couplings, bearings, pedestals and supports act at nodes.

Plane x-y carries (v, theta_z) as it is: v = N_d q_y, theta_z = N_r q_y; plane x-z carries
(w, theta_y) through S: w = N_d S q_z, theta_y = -N_r S q_z.  Gyroscopic moment densities (the
slice form of Euler's equations in :func:`fem.rotor.elements.lateral_matrices`):
m_y = rho I_p Omega theta_z',  m_z = -rho I_p Omega theta_y'.
"""
from __future__ import annotations

import numpy as np

from ..rotor import elements as el
from ..rotor.assembly import RotorSystem, _segment_arrays
from .elements import FORCE, MOMENT, ElementSet, LineTerm

LATERAL_QUANTITIES = {"bending_moment_y": (MOMENT, 1), "bending_moment_z": (MOMENT, 2),
                      "shear_force_y": (FORCE, 1), "shear_force_z": (FORCE, 2)}
FULL_QUANTITIES = {"torque": (MOMENT, 0), "axial_force": (FORCE, 0)}


def rotor_elements(rs: RotorSystem) -> ElementSet:
    """The shaft elements of ``rs`` (module notes) with gravity as a load term per unit g component."""
    a = _segment_arrays(rs.rotor)
    L = a["L"]
    Kp, MT, MR, P, phi = el.plane_matrices(L, a["E"], a["G"], a["rho"], a["kappa"], a["d0"], a["d1"],
                                           a["di0"], a["di1"], a["mx"])
    Kl, Ml, Gl = el.lateral_matrices(Kp, MT, MR, P)
    nodes = rs.element_nodes
    nd = rs.node_dofs
    n0, n1 = nodes[:, 0], nodes[:, 1]
    lateral = [nd["v"][n0], nd["theta_z"][n0], nd["v"][n1], nd["theta_z"][n1],
               nd["w"][n0], nd["theta_y"][n0], nd["w"][n1], nd["theta_y"][n1]]
    roles = [(FORCE, 1), (MOMENT, 2)] * 2 + [(FORCE, 2), (MOMENT, 1)] * 2
    xi = [0.0, 0.0, 1.0, 1.0] * 2
    full = rs.rotor.dofs == "full"
    E = L.size
    nb = 12 if full else 8
    K = np.zeros((E, nb, nb))
    M = np.zeros((E, nb, nb))
    G = np.zeros((E, nb, nb))
    K[:, :8, :8], M[:, :8, :8], G[:, :8, :8] = Kl, Ml, Gl
    applied = np.zeros((E, nb, 3))          # consistent loads per unit g_x, g_y, g_z
    fe = rs.element_load
    applied[:, :4, 1] = fe
    applied[:, 4:8, 2] = fe * np.array([1.0, -1.0, 1.0, -1.0])
    if full:
        A_g, _, Ip_g = el.section_at(a["d0"], a["d1"], a["di0"], a["di1"], el.XI)
        line = a["rho"][:, None] * A_g + a["mx"][:, None]
        Ka, Ma = el.rod_matrices(L, a["E"][:, None] * A_g, line)
        Kt, Mt = el.rod_matrices(L, a["G"][:, None] * Ip_g, a["rho"][:, None] * Ip_g)
        K[:, 8:10, 8:10], M[:, 8:10, 8:10] = Ka, Ma
        K[:, 10:, 10:], M[:, 10:, 10:] = Kt, Mt
        lateral += [nd["u"][n0], nd["u"][n1], nd["theta_x"][n0], nd["theta_x"][n1]]
        roles += [(FORCE, 0), (FORCE, 0), (MOMENT, 0), (MOMENT, 0)]
        xi += [0.0, 1.0, 0.0, 1.0]
        applied[:, 8:10, 0] = rs.axial_load
    S = np.diag([1.0, -1.0, 1.0, -1.0])

    def section(e, t):
        return el.section_at(a["d0"][e], a["d1"][e], a["di0"][e], a["di1"][e], t)

    def line_mass(e, t):
        return a["rho"][e][:, None] * _rows(section, e, t, 0) + a["mx"][e][:, None]

    def rho_I(e, t):
        return a["rho"][e][:, None] * _rows(section, e, t, 1)

    def rho_Ip(e, t):
        return a["rho"][e][:, None] * _rows(section, e, t, 2)

    def plane(which, z_sign=None):
        """(S, n, nb) with N_d or N_r (``which``) of the elements placed in plane y (z_sign None) or z."""
        def shape(e, t):
            out = np.zeros(t.shape + (nb,))
            N = _nelson(L[e], phi[e], t)[which]
            if z_sign is None:
                out[..., :4] = N
            else:
                out[..., 4:8] = z_sign * (N @ S)
            return out
        return shape

    def rod(first):
        def shape(e, t):
            out = np.zeros(t.shape + (nb,))
            out[..., first], out[..., first + 1] = 1.0 - t, t
            return out
        return shape

    terms = [LineTerm(FORCE, 1, line_mass, plane(0)), LineTerm(MOMENT, 2, rho_I, plane(1)),
             LineTerm(FORCE, 2, line_mass, plane(0, 1.0)), LineTerm(MOMENT, 1, rho_I, plane(1, -1.0)),
             # gyroscopic: m_y = rho Ip Omega theta_z',  m_z = -rho Ip Omega theta_y' = rho Ip Omega N_r S q_z'
             LineTerm(MOMENT, 1, rho_Ip, plane(1), source="gyroscopic", row=plane(1, -1.0)),
             LineTerm(MOMENT, 2, rho_Ip, plane(1, 1.0), source="gyroscopic", row=plane(1))]
    load_terms = [LineTerm(FORCE, 1, line_mass, None, source="load"), LineTerm(FORCE, 2, line_mass, None, source="load")]
    quantities = dict(LATERAL_QUANTITIES)
    if full:
        terms += [LineTerm(FORCE, 0, line_mass, rod(8)), LineTerm(MOMENT, 0, rho_Ip, rod(10))]
        load_terms.append(LineTerm(FORCE, 0, line_mass, None, source="load"))
        quantities.update(FULL_QUANTITIES)
    x = rs.node_x
    return ElementSet(x0=x[n0], x1=x[n1], dofs=np.stack(lateral, axis=1), K=K, M=M, H=None, roles=roles,
                      xi=np.asarray(xi), terms=terms, quantities=quantities, n_dofs=rs.n_dofs, G=G,
                      load_terms=load_terms, applied=applied,
                      description=f"Timoshenko rotor elements (Nelson), {E} elements, dofs = {rs.rotor.dofs!r}")


def _rows(section, e, t, k):
    """Section property k (A, I, Ip) at the points t (S, n) of the elements e (S,)."""
    out = np.empty(t.shape)
    for j in range(t.shape[0]):          # section_at takes one xi row for a set of elements
        out[j] = section(e[j:j + 1], t[j])[k][0]
    return out


def _nelson(L, phi, t):
    """N_d, N_r (S, n, 4) at the points t (S, n) of elements with lengths L and shear parameters phi (S,)."""
    Nd = np.empty(t.shape + (4,))
    Nr = np.empty(t.shape + (4,))
    for j in range(t.shape[0]):
        d, _, r, _ = el.shape_functions(L[j:j + 1], phi[j:j + 1], t[j])
        Nd[j], Nr[j] = d[0], r[0]
    return Nd, Nr
