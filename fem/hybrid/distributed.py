"""Dry friction distributed along a rod, shaft or beam (seed 003: intensity q = f P / l).

The distributed law ``q(x) = -q0 sign(u'(x, t))`` is applied at every node of the primary field
with the *tributary weight* of that node, ``w_i = integral of N_i over the rough range`` (the
consistent load vector of a unit intensity): a Coulomb element of level ``q0 w_i`` at DOF i.
Linear Lagrange: h/2 at the range ends, h inside; quadratic Lagrange: h/6 per vertex and 2h/3
per mid-side node (Simpson); Hermite beams: the translation DOFs w carry h/2 per element end,
the consistent moments +-h^2/12 on the slopes are dropped (their resultant over a uniformly
moving range vanishes; lumping them into the translations keeps every element a scalar Coulomb
law on one velocity).  The weights sum to the rough length, so the total friction force of a
rigid translation is exactly q0 (x_to - x_from).
"""
from __future__ import annotations

import numpy as np
from skfem import LinearForm, asm

from discrete.errors import ModelError
from discrete.nonsmooth import Friction

from ..assembly import FEModel
from .build import ElementSpec, NodeRef


def tributary_weights(fe: FEModel, dof: str, x_from: float, x_to: float) -> tuple[np.ndarray, np.ndarray]:
    """(DOF indices, weights) of the consistent load of a unit intensity on [x_from, x_to] for field ``dof``."""
    L = fe.model.length
    lo, hi = min(x_from, x_to), max(x_from, x_to)
    nodes = fe.mesh.nodes
    tol = 1e-9 * L
    for val in (lo, hi):
        if np.min(np.abs(nodes - val)) > tol:
            raise ModelError("[[distributed_friction]]", "from/to", val, "a mesh node position "
                             "(segment ends; use segments to place range ends on nodes)")

    @LinearForm
    def unit(v, w):
        x = w.x[0]
        return v * ((x >= lo - tol) & (x <= hi + tol))

    sys_ = fe.system
    if fe.model.physics == "bending" and fe.model.theory == "timoshenko":
        raise ModelError("[[distributed_friction]]", "theory", "timoshenko",
                         "euler-bernoulli beams, rods and shafts (distributed friction on mixed Timoshenko "
                         "bases is not implemented)")
    vec = asm(unit, fe.basis)
    vec = np.asarray(vec, float)
    idx = np.flatnonzero((sys_.dof_field == dof) & (np.abs(vec) > 0))
    return idx, vec[idx]


def distributed_friction(fe: FEModel, *, name: str, dof: str | None, x_from: float, x_to: float,
                         intensity: float | None = None, static_intensity: float | None = None,
                         mu: float | None = None, radius: float | None = None, g: float = 9.81,
                         where: str = "[[distributed_friction]]") -> list[ElementSpec]:
    """Coulomb elements at every node of [x_from, x_to] with level intensity * tributary weight.

    ``intensity`` (force or torque per length) or ``mu``: q0 = mu g (rho A + rho_extra) for axial
    and bending, q0 = mu g rho A r for torsion (``radius`` r: the friction acts on the surface)."""
    fld = dof or fe.model.fields[0]
    if fld != fe.model.fields[0]:
        raise ModelError(where, "dof", fld, f"the translation/twist field {fe.model.fields[0]!r} "
                         "(distributed friction acts on the primary field)")
    L = fe.model.length
    for key, val in (("from", x_from), ("to", x_to)):
        if not -1e-12 * L <= val <= L * (1 + 1e-12):
            raise ModelError(where, key, val, f"a position on the model, 0 <= x <= {L:g}")
    if not x_to > x_from:
        raise ModelError(where, "to", x_to, f"a position beyond from = {x_from!r}")
    if mu is not None:
        segs = fe.model.segments
        if len({(s.material.rho, s.section.A, s.rho_extra) for s in segs}) != 1:
            raise ModelError(where, "mu", mu, "intensity = .. for a model with non-uniform segments")
        s = segs[0]
        q = mu * g * (s.material.rho * s.section.A + (s.rho_extra if fe.model.physics != "torsion" else 0.0))
        if fe.model.physics == "torsion":
            if radius is None:
                raise ModelError(where, "radius", None, "the friction radius r (torsion: torque per length mu g rho A r)")
            q *= radius
        intensity = q
    elif radius is not None:
        raise ModelError(where, "radius", radius, "only with mu = ..")
    qs = intensity if static_intensity is None else static_intensity
    if qs < intensity:
        raise ModelError(where, "static_intensity", qs, f"a number >= intensity = {intensity!r}")
    idx, w = tributary_weights(fe, fld, x_from, x_to)
    held = set(fe.system.constrained.tolist())
    out = []
    for j, wj in zip(idx, w):
        if int(j) in held or wj <= 0:
            continue
        x = float(fe.system.dof_x[j])
        out.append(ElementSpec(Friction, dict(name=f"{name}@x={x:.6g}", kinetic=intensity * wj, static=qs * wj),
                               [(NodeRef(x=x, dof=fld), 1.0)]))
    return out
