"""``[damping]`` in the time domain (simulations, shooting, harmonic balance of nonlinear models).

One meaning in every kind of file: "rayleigh" adds alpha M + beta K, "none" removes every damper and
every psi, "hysteretic" puts psi on every stiffness, "viscous" keeps the model's own dampers; "modal"
(damping ratios) is a model of the harmonic analysis and refused here.  Every psi -- of [damping],
springs and segments, the loss stiffness H -- then becomes a viscous matrix by (9.3) or (9.14)-(9.18)
(:func:`discrete.linear.dissipation.time_domain_psi`): honoured or refused, never dropped."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from discrete.errors import ModelError


def linear_damping(system, table):
    """The system with the linear part of ``[damping]`` applied (no psi conversion yet)."""
    kind = "viscous" if table is None else table.kind
    if kind == "modal":
        raise ModelError("[damping]", "type", "modal", "'rayleigh', 'hysteretic', 'viscous' or 'none' in a time "
                         "simulation or steady state (modal damping ratios are a model of the harmonic analysis)")
    if kind == "rayleigh":
        return replace(system, C=system.C + table.alpha * system.M + table.beta * system.K)
    if kind == "none":
        return replace(system, C=0 * system.C, H=0 * system.H)
    if kind == "hysteretic":
        return replace(system, H=system.H + table.psi / (2 * np.pi) * system.K)
    return system


def psi_viscous(system, table, forcing_omegas=()):
    """(system with the viscous equivalent of its psi added to C, report or None)."""
    from discrete.linear.dissipation import time_domain_psi

    if system.H.nnz == 0 or not np.any(system.H.data):
        return system, None
    method = getattr(table, "psi_time", None)
    if method is None:                  # the book's (9.3) at the one forcing frequency, else the modal form
        method = "equivalent" if len(set(forcing_omegas)) == 1 else "modal"
    omega_ref = getattr(table, "omega_ref", None)
    C_psi, report = time_domain_psi(system, method, omega_ref if omega_ref is not None else
                                    ("forcing" if method == "equivalent" else None),
                                    getattr(table, "psi_modes", None), forcing_omegas=tuple(forcing_omegas),
                                    completion=getattr(table, "psi_completion", "stiffness"))
    return replace(system, C=system.C + C_psi), report


def time_domain_damping(system, table, forcing_omegas=()):
    """Both steps: (system, psi report or None)."""
    return psi_viscous(linear_damping(system, table), table, forcing_omegas)
