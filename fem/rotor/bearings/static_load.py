"""The static load each bearing carries: given, or the rotor's weight on rigid supports at the bearings.

A bearing computed from its geometry needs the static load it runs at (the operating point of a
fluid film, the preload of rolling elements).  When it is not given, it is the reaction of the
rotor's weight with every bearing replaced by a rigid support of (v, w) at its node (pedestals
carry the same reaction).  For two bearings the rotor is statically determinate and the
reactions are exact whatever the bearings' stiffness; with three or more they are the reactions
of rigid supports (a compliant film shares the load differently: give ``load`` explicitly then).
"""
from __future__ import annotations

import numpy as np
import scipy.sparse.linalg as spla

from discrete.errors import ModelError

GRAVITY = (0.0, 0.0, -9.81)
"""Default acceleration of gravity (g_x, g_y, g_z), m/s^2: -z is down (as in static_deflection)."""


def weight_reactions(rotor, assemble, gravity=GRAVITY) -> list[np.ndarray]:
    """(F_y, F_z) the shaft presses on each bearing of ``rotor`` (in ``rotor.bearings`` order), N,
    from its weight under ``gravity`` with rigid supports at the bearings.  ``assemble``: the rotor
    assembler (:func:`fem.rotor.assembly.assemble_rotor`, which calls this while it assembles a rotor
    whose bearings draw their load from the weight; passed in, so this module does not import it)."""
    from dataclasses import replace

    from ..model import Support

    if not rotor.bearings:
        return []
    xs = sorted({float(b.x) for b in rotor.bearings})
    rigid = replace(rotor, bearings=[], pedestals=[],
                    supports=list(rotor.supports) + [Support(x, ("v", "w")) for x in xs])
    rs = assemble(rigid)
    f = rs.gravity_load(gravity)
    K = rs.K0.tocsc()
    held = np.zeros(rs.n_dofs, dtype=bool)
    held[rs.constrained] = True
    free = np.flatnonzero(~held)
    q = np.zeros(rs.n_dofs)
    try:
        q[free] = spla.spsolve(K[free][:, free], f[free])
    except RuntimeError:
        q[free] = np.nan
    if not np.all(np.isfinite(q)):
        raise ModelError("[[rotor.journal_bearing]]", "load", None, "a static load, or a rotor that its bearings hold "
                         "(the weight's reactions on rigid supports at the bearings are undefined)")
    reaction = K @ q - f                       # ground on the shaft at the held DOFs
    out = []
    for b in rotor.bearings:
        node = rs.node(b.x)
        iv, iw = rs.node_dofs["v"][node], rs.node_dofs["w"][node]
        share = sum(1 for c in rotor.bearings if abs(c.x - b.x) <= 1e-12 * max(rotor.length, 1.0))
        out.append(-np.array([reaction[iv], reaction[iw]]) / share)     # the shaft on the bearing
    return out
