"""Loads proportional to omega^2: rotating unbalance and inertia of moving links (§5.12, §6.4 model 2).

A mass-eccentricity product m e (kg m) on a DOF gives the harmonic load F(omega) = m e omega^2 e^{i phase}
(one component of the rotating force).  :func:`unbalance_spectrum` produces that spectrum;
:func:`unbalance_response` scales the receptance of :func:`discrete.linear.harmonic.harmonic_response`
frequency by frequency (linearity), so every harmonic solver option applies unchanged.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import ModelError
from ..linear.harmonic import Damping, HarmonicResult, harmonic_response
from ..linear_system import LinearSystem


def unbalance_spectrum(omegas, mass_eccentricity: float, phase: float = 0.0) -> np.ndarray:
    """Complex amplitudes m e omega^2 e^{i phase} at the angular frequencies ``omegas``."""
    w = np.atleast_1d(np.asarray(omegas, dtype=float))
    if np.any(w < 0) or not np.all(np.isfinite(w)):
        raise ModelError("unbalance", "omegas", w.tolist(), "angular frequencies >= 0")
    if isinstance(mass_eccentricity, bool) or not isinstance(mass_eccentricity, (int, float, np.floating)) \
            or not math.isfinite(mass_eccentricity):
        raise ModelError("unbalance", "mass_eccentricity", mass_eccentricity, "a finite number (kg m)")
    return mass_eccentricity * w**2 * np.exp(1j * phase)


def unbalance_response(system: LinearSystem, omegas, dof: int, mass_eccentricity: float, *, phase: float = 0.0,
                       damping: Damping | None = None, outputs: list[int] | None = None, method: str = "direct",
                       n_modes: int | None = None) -> tuple[HarmonicResult, np.ndarray]:
    """Harmonic response to the unbalance load m e omega^2 on DOF ``dof``; returns (result, force spectrum)."""
    if isinstance(dof, bool) or not isinstance(dof, (int, np.integer)) or not 0 <= dof < system.n_dofs:
        raise ModelError("unbalance", "dof", dof, f"a DOF index in [0, {system.n_dofs - 1}]")
    spec = unbalance_spectrum(omegas, mass_eccentricity, phase)
    unit = np.zeros(system.n_dofs, dtype=complex)
    unit[dof] = 1.0                  # response to omega^2 x a unit unbalance, scaled by m e e^{i phase}
    res = harmonic_response(system, omegas, force_omega2=unit, damping=damping, outputs=outputs, method=method,
                            n_modes=n_modes)
    res.response = res.response * (mass_eccentricity * np.exp(1j * phase))
    return res, spec
