"""Parametric excitation of a train by the mesh-stiffness variation: Floquet stability chart over the
reference speed and the depth of the variation.

The mean train (meshes at their mean stiffness, the linear state) with its free rotation eliminated
(:mod:`.compile`) and, optionally, Craig-Bampton per shaft, pulsates by the chosen mesh's variation

    K(t) = K + eps k sum_h (a_h cos(h w_m t) + b_h sin(h w_m t)) g g^T,    w_m = z_a |ratio_a| Omega,

(eps = 1: the declared variation) -- in the terms of :mod:`discrete.linear.parametric` one
:class:`Modulation` per harmonic, depth sqrt(a_h^2 + b_h^2), phase atan2(a_h, b_h) + pi (its sign
convention K0 - eps d P sin(h W t + phi)).  The chart's excitation frequency is the tooth-pass frequency,
reported also as the reference speed Omega = w_m / (z_a |ratio_a|).  The gyroscopic and bearing terms are
those at the [train] operating speed (a stiffness-pulsation chart, not a run-up).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from discrete.errors import ModelError
from discrete.linear.parametric import Modulation, stability_chart

from .assembly import TrainSystem
from .compile import ReductionSpec, compile_train


@dataclass
class TrainParametricResult:
    """The chart (:class:`discrete.linear.parametric.StabilityChart`) and the speed axis."""

    chart: object
    mesh: str
    pass_per_speed: float           # w_m / Omega = z_a |ratio_a|
    warnings: list = field(default_factory=list)

    @property
    def speeds_rad_s(self) -> np.ndarray:
        return self.chart.omega_rad_s / self.pass_per_speed

    def to_dict(self) -> dict:
        d = self.chart.to_dict()
        d.update({"mesh": self.mesh, "tooth_pass_per_speed": self.pass_per_speed,
                  "speeds_rad_s": self.speeds_rad_s.tolist(), "speeds_rpm": (self.speeds_rad_s * 30 / math.pi).tolist()})
        d["warnings"] = list(d.get("warnings", [])) + list(self.warnings)
        return d


def mesh_modulations(comp, mesh) -> list[Modulation]:
    """The variation of ``mesh`` as modulations of the compiled (linear) system's stiffness."""
    probe = [p for p in comp.probes if p[0] is mesh and p[1] == "line of action"]
    if not probe:
        raise ModelError(mesh.where, "linear_state", mesh.linear_state, "'closed' for a Floquet analysis of its "
                         "stiffness variation")
    g = probe[0][2]
    if comp.Tr is not None:
        g = comp.Tr.T @ g
    P = mesh.stiffness * np.outer(g, g)
    out = []
    for h, a, b in mesh.variation:
        A = math.hypot(a, b)
        if A == 0:
            continue
        out.append(Modulation(target="stiffness", depth=A, harmonic=int(h), phase=math.atan2(a, b) + math.pi,
                              part=P, label=f"{mesh.name} h{h}"))
    return out


def train_parametric(ts: TrainSystem, *, speed: float, speed_min: float, speed_max: float, n_speed: int,
                     depth_min: float, depth_max: float, n_depth: int, mesh: str | None = None,
                     boundaries_at=(), modes: int | None = None, tolerance: float = 1e-10,
                     reduction: ReductionSpec | None = None) -> TrainParametricResult:
    """Floquet chart of the mesh ``mesh`` (default: the one mesh with a variation) over reference speeds
    [speed_min, speed_max] and depths [depth_min, depth_max] (see the module docstring)."""
    meshes = [c for c in ts.train.connections if getattr(c, "variation", ())]
    if mesh is not None:
        meshes = [c for c in meshes if c.name == mesh]
        if not meshes:
            raise ModelError("[parametric]", "mesh", mesh, "a [[mesh]] with a [mesh.variation] table")
    if len(meshes) != 1:
        raise ModelError("[parametric]", "mesh", [c.name for c in meshes] or None,
                         "exactly one [[mesh]] with a [mesh.variation] (name it with mesh = .. when several have one)")
    m = meshes[0]
    comp = compile_train(ts, speed, reduction=reduction, eliminate_rigid=True, linear=True)
    mods = mesh_modulations(comp, m)
    z = m.teeth[0] * abs(ts.ratio_of(m.ports[0]))
    chart = stability_chart(comp.system, mods, omega_min=z * speed_min, omega_max=z * speed_max, n_omega=n_speed,
                            depth_min=depth_min, depth_max=depth_max, n_depth=n_depth,
                            boundaries_at=list(boundaries_at), modes=modes, tolerance=tolerance)
    return TrainParametricResult(chart=chart, mesh=m.name, pass_per_speed=z, warnings=list(comp.warnings))
