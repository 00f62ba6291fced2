"""The linear analyses' tables -> solver inputs: frequencies of ``[analysis]``, the
:class:`~discrete.linear.Damping` of ``[damping]``, and the located ``[[load]]``,
``[[base_motion]]`` and ``[[response]]`` DOFs of a forced analysis."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from discrete.errors import ModelError
from discrete.motion.waveforms import unit_waveform
from discrete.linear import Damping
from discrete.linear_system import LinearSystem


def frequencies(an) -> np.ndarray:
    """Angular frequencies (rad/s) of a forced ``[analysis]``."""
    if an.sweep_hz is not None:
        sw = an.sweep_hz
        f = np.geomspace(sw.start, sw.stop, sw.points) if sw.spacing == "log" else np.linspace(sw.start, sw.stop,
                                                                                              sw.points)
        return 2 * np.pi * f
    if an.frequencies_hz is not None:
        return 2 * np.pi * np.array(an.frequencies_hz, dtype=float)
    return np.array(an.omega_rad_s, dtype=float)


def damping(table) -> Damping:
    """The harmonic analysis' damping model of a ``[damping]`` table (None: the model's own)."""
    if table is None:
        return Damping()
    return Damping(type=table.kind, alpha=table.alpha, beta=table.beta, zeta=table.zeta, psi=table.psi)


@dataclass
class ForcedSpec:
    omegas: np.ndarray
    method: str
    n_modes: int | None
    force: np.ndarray
    base_motion: dict
    outputs: list[int]
    period: float | None = None                        # periodic loads: the period, s
    harmonics: int = 0
    waveforms: list = field(default_factory=list)      # [(DOF, amplitude, phase fraction, unit shape w(s))]
    force_w2: np.ndarray | None = None                 # complex amplitudes of the loads ~ omega^2


def _locate(system: LinearSystem, t, where: str, lumped_key: str) -> int:
    """DOF of a load/response/base-motion table: FE by x and dof, lumped by body/driver name."""
    if system.physics == "lumped":
        name = getattr(t, lumped_key)
        if getattr(t, "x", None) is not None:
            raise ModelError(where, "x", t.x, f"{lumped_key} = .. (a lumped model has no FE nodes)")
        if name is None:
            raise ModelError(where, lumped_key, None, f"the name of a {lumped_key} (required key missing)")
        return system.dof_index(name=name, where=where)
    if getattr(t, lumped_key) is not None:
        raise ModelError(where, lumped_key, getattr(t, lumped_key), "x = .. (and dof) in an FE model")
    if t.x is None:
        raise ModelError(where, "x", None, "the node position x = .. (required key missing)")
    return system.dof_index(field=t.dof or system.dof_field[0], x=t.x, where=where)


def forced_spec(doc, system: LinearSystem) -> ForcedSpec:
    """Frequencies, excitation and outputs of a linear forced analysis."""
    an = doc.analysis
    force = np.zeros(system.n_dofs, dtype=complex)
    force_w2 = np.zeros(system.n_dofs, dtype=complex)          # loads amplitude * omega^2 (unbalance)
    held = set(system.constrained.tolist())
    waves = []
    for i, t in enumerate(doc.load, 1):
        w = f"[[load]] #{i}"
        dof = _locate(system, t, w, "body")
        if dof in held:
            raise ModelError(w, "x", t.x if t.x is not None else t.body, "a free DOF (this one is held by a support/driver)")
        if t.waveform is not None:
            wf = t.waveform
            waves.append((dof, t.amplitude, t.phase_deg / 360.0,
                          unit_waveform(wf.kind, duty=wf.duty, s_points=wf.t, values=wf.value)))
            continue
        target = force_w2 if t.scaling == "omega2" else force
        target[dof] += t.amplitude * np.exp(1j * math.radians(t.phase_deg))
    base = {}
    for i, t in enumerate(doc.base_motion, 1):
        w = f"[[base_motion]] #{i}"
        dof = _locate(system, t, w, "driver")
        if dof not in held:
            raise ModelError(w, "x" if system.physics != "lumped" else "driver", t.x if t.x is not None else t.driver,
                             "a held DOF: a clamped/pinned support (FE) or a driver (lumped)")
        base[dof] = t.amplitude * np.exp(1j * math.radians(t.phase_deg))
    outputs = [_locate(system, t, f"[[response]] #{i}", "body") for i, t in enumerate(doc.response, 1)]
    if not outputs:
        outputs = sorted(set(np.flatnonzero(force).tolist()) | set(np.flatnonzero(force_w2).tolist())
                         | {w[0] for w in waves})
    if not outputs:  # base motion only: every body, or the free end of the primary field
        if system.physics == "lumped":
            outputs = system.free.tolist()
        else:
            prim = system.free[system.dof_field[system.free] == system.dof_field[0]]
            outputs = [int(prim[np.argmax(np.abs(system.dof_x[prim] - system.dof_x[system.constrained].mean()))])]
    if an.period is not None:
        if np.any(force_w2):
            raise ModelError("[[load]]", "scaling", "omega2", '"constant" with [analysis] period (a load ~ omega^2 has '
                             "no single periodic shape)")
        return ForcedSpec(omegas=np.zeros(0), method=an.method, n_modes=an.modes, force=force, base_motion=base,
                          outputs=outputs, period=float(an.period), harmonics=int(an.harmonics), waveforms=waves)
    return ForcedSpec(omegas=frequencies(an), method=an.method, n_modes=an.modes, force=force, base_motion=base,
                      outputs=outputs, force_w2=force_w2)
