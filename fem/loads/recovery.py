"""Section loads from the element equations (docs/loads.md).

Element end forces -- the generalised forces the nodes exert on element e:

    f_e = K_e q_e + (i H_e q_e) + C_e q_e' + Omega G_e q_e' + M_e q_e'' - (applied element loads)

with C_e = alpha M_e + beta K_e (+ H_e / omega_ref in the time domain).  At a node the end forces
of all elements there, the node's own inertia, springs and dampers balance the applied nodal load
and the support reaction exactly (assembled, they are the rows of M q'' + C q' + K q = f + r), so
section loads taken from the two elements meeting at a free node agree to round-off, and they jump
by exactly the point load / point inertia / spring force at an attachment.

Section load on the face with outward normal +x (the material right of x acting on the material left
of it): at an element's left end it is -f_e, at its right end +f_e of the DOF with that role.
Inside an element it follows from the equilibrium of the part [x_a, x] with the distributed inertia
of the element's own interpolation (the identity that makes both ends agree is the element's exact
rigid-body equilibrium: K_e annihilates rigid motions, M_e and G_e are integrals of the densities):

    F(x) = int_a^x r_F ds - sum_{x_k < x} f_k,
    M(x) = int_a^x (r_M + sign (s - x) r_F') ds - sum_{x_k < x} (f_k^M + sign (x_k - x) f_k^F')

(r: the densities of :class:`~fem.loads.elements.LineTerm`, F' the force component whose lever arm
gives M, sign from :data:`~fem.loads.elements.ARM`).
"""
from __future__ import annotations

import numpy as np

from .elements import ARM, FORCE, MOMENT, ElementSet, gauss
from .motion import ElementDamping, Motion


def _mul(A: np.ndarray, u: np.ndarray) -> np.ndarray:
    return np.einsum("eij,ejt->eit", A, u)


def element_loss(es: ElementSet, damping: ElementDamping) -> np.ndarray | None:
    """H_e of the elements under ``damping`` (material psi scaled, plus a global hysteretic psi)."""
    H = None if es.H is None or damping.loss_scale == 0 else damping.loss_scale * es.H
    if damping.added_loss:
        H = damping.added_loss * es.K + (0 if H is None else H)
    return H


def end_forces(es: ElementSet, mo: Motion, damping: ElementDamping, *, speed: float = 0.0,
               load: np.ndarray | None = None, elements: np.ndarray | None = None) -> np.ndarray:
    """f_e (E, nb, n_t) of the module notes, for every element or the ``elements`` given (in that order);
    ``load`` (3,): factors of the element load terms (gravity)."""
    sel = slice(None) if elements is None else np.asarray(elements, dtype=int)
    d = es.dofs[sel]
    q, qd, qdd = mo.q[d], mo.qd[d], mo.qdd[d]
    K = es.K[sel]
    f = _mul(K, q)
    H = element_loss(es, damping)
    H = None if H is None else H[sel]
    M = None if es.M is None else es.M[sel]
    if H is not None and mo.loss:
        f = f + mo.loss * _mul(H, q)
    if mo.kind != "static":
        C = 0.0
        if damping.beta:
            C = damping.beta * K
        if damping.alpha and M is not None:
            C = C + damping.alpha * M
        if H is not None and damping.viscous_loss_omega and not mo.loss:
            C = C + H / damping.viscous_loss_omega
        if not np.isscalar(C):
            f = f + _mul(C, qd)
        spin = np.broadcast_to(np.asarray(speed, dtype=float), (f.shape[2],))
        if es.G is not None and np.any(spin):
            f = f + _mul(es.G[sel], qd) * spin
        if M is not None:
            f = f + _mul(M, qdd)
    if load is not None and es.applied is not None:
        f = f - (es.applied[sel] @ np.asarray(load, float))[:, :, None]
    return f


def station_values(es: ElementSet, f: np.ndarray, mo: Motion, damping: ElementDamping, element: np.ndarray,
                   xi: np.ndarray, side: np.ndarray, *, speed: float = 0.0, load: np.ndarray | None = None,
                   rows: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Every quantity of ``es`` at the stations (element, xi, side) -> {name: (n_x, n_t)}; ``rows``: the row
    of ``f`` that holds each station's element (default: the element index itself)."""
    element = np.asarray(element, dtype=int)
    rows = element if rows is None else np.asarray(rows, dtype=int)
    xi = np.asarray(xi, dtype=float)
    n_t = f.shape[2]
    out = {name: np.zeros((element.size, n_t), dtype=f.dtype) for name in es.quantities}
    left, right = xi == 0.0, xi == 1.0
    for name, (kind, axis) in es.quantities.items():
        for k in es.local(kind, axis):
            at = (left & (es.xi[k] == 0.0)) | (right & (es.xi[k] == 1.0))
            sgn = np.where(left, -1.0, 1.0)
            out[name][at] = sgn[at, None] * f[rows[at], k]
    inside = np.flatnonzero(~left & ~right)
    if inside.size:
        vals = _inside(es, f[rows[inside]], mo, damping, element[inside], xi[inside], np.asarray(side)[inside], speed,
                       load)
        for name in out:
            out[name][inside] = vals[name]
    return out


def _inside(es, fe, mo, damping, el, xi, side, speed, load) -> dict[str, np.ndarray]:
    """Equilibrium of the part [x_a, x] of each element (module notes); ``fe`` (S, nb, T): the end forces of
    the elements ``el`` of the stations."""
    g, w = gauss(8)
    h = es.length[el]
    t = xi[:, None] * g[None, :]                         # (S, n) points in [0, xi]
    ds = (xi * h)[:, None] * w[None, :]
    arm = (t - xi[:, None]) * h[:, None]                 # s - x
    d = es.dofs[el]
    source = {"inertia": mo.qdd[d] + (damping.alpha * mo.qd[d] if damping.alpha and mo.kind != "static" else 0.0),
              "gyroscopic": mo.qd[d] * np.broadcast_to(np.asarray(speed, dtype=float), (mo.q.shape[1],))}
    if mo.kind == "static":
        source = {"inertia": 0.0 * mo.q[d], "gyroscopic": 0.0 * mo.q[d]}
    density = {}                                          # (kind, axis) -> (S, n, T)
    for term in es.terms:
        r = np.einsum("sn,snb,sbt->snt", term.weight(el, t), term.shape(el, t), source[term.source])
        key = (term.kind, term.axis)
        density[key] = density.get(key, 0.0) + r
    if load is not None:
        for term in es.load_terms:
            key = (term.kind, term.axis)
            r = -load[term.axis] * term.weight(el, t)[:, :, None]
            density[key] = density.get(key, 0.0) + r
    xk = es.xi[None, :]
    passed = (xk < xi[:, None]) | ((side == "right")[:, None] & (xk == xi[:, None]))   # (S, nb)
    out = {}
    for name, (kind, axis) in es.quantities.items():
        val = 0.0
        if (kind, axis) in density:
            val = val + np.einsum("sn,snt->st", ds, density[(kind, axis)])
        for k in es.local(kind, axis):
            val = val - passed[:, k, None] * fe[:, k]
        if kind == MOMENT and axis in ARM:
            faxis, sign = ARM[axis]
            if (FORCE, faxis) in density:
                val = val + sign * np.einsum("sn,snt->st", ds * arm, density[(FORCE, faxis)])
            for k in es.local(FORCE, faxis):
                lever = (es.xi[k] - xi) * h
                val = val - sign * (passed[:, k] * lever)[:, None] * fe[:, k]
        out[name] = val if not np.isscalar(val) else np.zeros((el.size, fe.shape[2]), dtype=fe.dtype)
    return out


def element_end_stations(es: ElementSet) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Both ends of every element in order along x: (element, xi, side)."""
    order = np.argsort(es.x0, kind="stable")
    element = np.repeat(order, 2)
    xi = np.tile([0.0, 1.0], order.size)
    side = np.tile(np.array(["right", "left"], dtype=object), order.size)
    return element, xi, side


def node_stations(es: ElementSet, jumps: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One station per node, two (both sides) where a section load may jump: at nodes whose DOFs are in
    ``jumps`` (point attachments, supports, springs, loads) and where consecutive elements do not share
    their node (a coupling).  Returns (element, xi, side)."""
    order = np.argsort(es.x0, kind="stable")
    jumps = set(np.asarray(jumps, dtype=int).tolist())
    node_cols = es.xi == 0.0
    right_cols = es.xi == 1.0
    element, xi, side = [int(order[0])], [0.0], ["right"]
    for a, b in zip(order[:-1], order[1:]):
        end_dofs = set(es.dofs[a][right_cols].tolist())
        start_dofs = set(es.dofs[b][node_cols].tolist())
        if end_dofs == start_dofs and not (end_dofs & jumps):
            element.append(int(b)), xi.append(0.0), side.append("right")
        else:
            element += [int(a), int(b)]
            xi += [1.0, 0.0]
            side += ["left", "right"]
    element.append(int(order[-1])), xi.append(1.0), side.append("left")
    return np.asarray(element), np.asarray(xi), np.asarray(side, dtype=object)
