"""``[analysis] type = "parametric"`` -> the inputs of :func:`discrete.linear.parametric.stability_chart`.

Each ``[[analysis.modulation]]`` names the pulsating part P of K or M (textbook (7.1)-(7.7)):

* lumped files: ``spring = i`` -> k_i g g^T of the i-th ``[[spring]]`` (g: its deformation
  r_b x_b - r_a x_a, gears eliminated as in the model); ``body = "name"`` -> the body's inertia;
* FE files: ``segment = i`` -> the stiffness (or distributed inertia) of the i-th ``[[segment]]``;
  ``point = i`` -> the springs k, kr (or mass and inertia) of the i-th ``[[point]]``;
* no key: the whole K or M.

FE parts are assembled, not approximated: K and M are linear in the segment's moduli (E, G, with
nu = E/2G - 1 and so the Timoshenko shear coefficient unchanged) and in its inertia (rho,
rho_extra), so the part of segment i is K(model with segment i's moduli doubled) - K(model),
exact to round-off; a point likewise.  Hybrid and drive files are refused (the analysis works
on the linear system of an FE or lumped file)."""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp

from discrete.errors import ModelError
from discrete.linear.parametric import Modulation, ParametricProblem
from discrete.linear_system import LinearSystem

from .. import budget
from . import linear as build_linear

WHERE = "[analysis]"
MAX_GRID_POINTS = 400_000
"""Monodromy matrices of one chart (grid points), before the DRIVEFEM_BUDGET factor."""


@dataclass
class ParametricSpec:
    """Everything :func:`discrete.linear.parametric.stability_chart` needs, from the file."""

    problem: ParametricProblem
    omega_min: float                    # rad/s
    omega_max: float
    n_omega: int
    depth_min: float
    depth_max: float
    n_depth: int
    boundaries_at: list[float]
    boundary_samples: int
    thresholds: bool
    tolerance: float
    stability_margin: float
    omega_unit: str                     # "rad/s" or "omega_1": how the file gave the Omega grid
    parts: list[str]                    # what each modulation pulsates, in words

    def chart_kwargs(self) -> dict:
        return dict(omega_min=self.omega_min, omega_max=self.omega_max, n_omega=self.n_omega,
                    depth_min=self.depth_min, depth_max=self.depth_max, n_depth=self.n_depth,
                    boundaries_at=self.boundaries_at, boundary_samples=self.boundary_samples,
                    thresholds=self.thresholds, tolerance=self.tolerance, stability_margin=self.stability_margin)


def _where(i: int) -> str:
    return f"[analysis] modulation #{i}"


def _lumped_part(study, t, i: int) -> tuple[sp.csr_matrix, str]:
    lm = study.lumped
    where = _where(i)
    if t.segment is not None or t.point is not None:
        key = "segment" if t.segment is not None else "point"
        raise ModelError(where, key, getattr(t, key), "spring = .. (a [[spring]] number) or body = .. (a [[body]] "
                         "name) in a lumped model ([[segment]] and [[point]] are FE tables)")
    indep, T = lm.transformation()
    if t.spring is not None:
        n = len(lm.springs)
        if t.spring > n:
            raise ModelError(where, "spring", t.spring, f"a [[spring]] number from 1 to {n}" if n else
                             "a [[spring]] number (this model has no [[spring]] table)")
        link = lm.springs[t.spring - 1]
        if not link.value > 0:
            raise ModelError(where, "spring", t.spring, f"a [[spring]] with a stiffness k > 0 ([[spring]] #{t.spring} "
                             "is a dashpot only)")
        single = replace(lm, springs=[link], dampers=[])
        return sp.csr_matrix(single.linear_system().K), f"[[spring]] #{t.spring} {list(link.between)} stiffness"
    bodies = [b.name for b in lm.bodies]
    if t.body not in bodies:
        raise ModelError(where, "body", t.body, "one of " + ", ".join(map(repr, bodies)) + " (a [[body]] name; "
                         "drivers are held)")
    b = lm.bodies[bodies.index(t.body)]
    row = T[lm.names.index(t.body)]
    return sp.csr_matrix(b.inertia * np.outer(row, row)), f"[[body]] {t.body!r} inertia"


def _fe_part(study, t, i: int, target: str) -> tuple[sp.csr_matrix, str]:
    from ...assembly import assemble

    where = _where(i)
    if t.spring is not None or t.body is not None:
        key = "spring" if t.spring is not None else "body"
        raise ModelError(where, key, getattr(t, key), "segment = .. (a [[segment]] number) or point = .. (a [[point]] "
                         "number) in an FE model ([[spring]] and [[body]] are lumped tables)")
    shaft = study.shaft
    base = study.fe_model.system
    if t.segment is not None:
        n = len(shaft.segments)
        if t.segment > n:
            raise ModelError(where, "segment", t.segment, f"a [[segment]] number from 1 to {n}")
        seg = shaft.segments[t.segment - 1]
        if target == "stiffness":
            mat = replace(seg.material, E=2 * seg.material.E, G=2 * seg.material.G)
            doubled = replace(seg, material=mat)
        else:
            doubled = replace(seg, material=replace(seg.material, rho=2 * seg.material.rho), rho_extra=2 * seg.rho_extra)
        segments = list(shaft.segments)
        segments[t.segment - 1] = doubled
        other = assemble(replace(shaft, segments=segments)).system
        what = f"[[segment]] #{t.segment} " + ("stiffness" if target == "stiffness" else "inertia")
    else:
        n = len(shaft.points)
        if t.point > n:
            raise ModelError(where, "point", t.point, f"a [[point]] number from 1 to {n}" if n else
                             "a [[point]] number (this model has no [[point]] table)")
        p = shaft.points[t.point - 1]
        if target == "stiffness":
            if not (p.k > 0 or p.kr > 0):
                raise ModelError(where, "point", t.point, f"a [[point]] with a spring k or kr > 0 for target = "
                                 f"'stiffness' ([[point]] #{t.point} has none)")
            doubled = replace(p, k=2 * p.k, kr=2 * p.kr)
        else:
            if not (p.mass > 0 or p.inertia > 0):
                raise ModelError(where, "point", t.point, f"a [[point]] with a mass or inertia > 0 for target = "
                                 f"'inertia' ([[point]] #{t.point} has none)")
            doubled = replace(p, mass=2 * p.mass, inertia=2 * p.inertia)
        points = list(shaft.points)
        points[t.point - 1] = doubled
        other = assemble(replace(shaft, points=points)).system
        what = f"[[point]] #{t.point} at x = {p.x:g} " + ("springs" if target == "stiffness" else "inertia")
    A, B = (base.K, other.K) if target == "stiffness" else (base.M, other.M)
    P = sp.csr_matrix(B - A)
    P = 0.5 * (P + P.T)                   # symmetric to round-off by construction
    P.eliminate_zeros()
    return sp.csr_matrix(P), what


def modulations(study, system: LinearSystem) -> tuple[list[Modulation], list[str]]:
    """The :class:`Modulation` of every ``[[analysis.modulation]]`` and what each pulsates."""
    out, parts = [], []
    for i, t in enumerate(study.analysis.modulation, 1):
        key = t.part_key
        if key is None:
            P, what = None, ("whole stiffness matrix K" if t.target == "stiffness" else "whole inertia matrix M")
        elif study.kind == "lumped":
            P, what = _lumped_part(study, t, i)
        else:
            P, what = _fe_part(study, t, i, t.target)
        if P is not None and P.shape != (system.n_dofs, system.n_dofs):
            raise ModelError(_where(i), key, getattr(t, key), "a part of this model's system (internal size mismatch)")
        out.append(Modulation(target=t.target, depth=t.depth, harmonic=t.harmonic, phase=t.phase, part=P,
                              label=t.label or what))
        parts.append(what)
    return out, parts


def parametric_spec(study) -> ParametricSpec:
    """The parametric analysis of an FE or lumped ``study`` (a :class:`fem.study.Study`)."""
    an = study.analysis
    if an is None or getattr(an, "type", None) != "parametric":
        raise ModelError(WHERE, "type", getattr(an, "type", None), "'parametric' for drivefem parametric (an "
                         "[analysis] table with type = \"parametric\" and [[analysis.modulation]] terms)")
    if study.kind not in ("fe", "lumped"):
        raise ModelError(WHERE, "type", "parametric", f"an FE or lumped model file (this is a {study.kind} file: "
                         "the parametric chart works on the linear system of [[segment]] or [[body]] models)")
    grid = an.omega_rad_s if an.omega_rad_s is not None else an.omega_ratio
    budget.check_count("[analysis]", "depth.points", grid.points * an.depth.points, MAX_GRID_POINTS,
                       "monodromy matrices (depth.points x omega points)", an.depth.points)
    system = study.linear_system()
    mods, parts = modulations(study, system)
    problem = ParametricProblem.build(system, mods, damping=build_linear.damping(study.doc.damping),
                                      inertia_form=an.inertia_form, modes=an.modes)
    scale = 1.0 if an.omega_rad_s is not None else float(problem.omega_modes[0])
    return ParametricSpec(problem=problem, omega_min=grid.start * scale, omega_max=grid.stop * scale,
                          n_omega=grid.points, depth_min=an.depth.min, depth_max=an.depth.max,
                          n_depth=an.depth.points, boundaries_at=list(an.boundaries_at),
                          boundary_samples=an.boundary_samples, thresholds=an.thresholds, tolerance=an.tolerance,
                          stability_margin=an.stability_margin,
                          omega_unit="rad/s" if an.omega_rad_s is not None else "omega_1", parts=parts)


def run(study, progress=None):
    """(spec, :class:`~discrete.linear.parametric.StabilityChart`) of the file's parametric analysis;
    ``progress(done, total)`` as the chart is computed."""
    from discrete.linear.parametric import stability_chart

    spec = parametric_spec(study)
    where = "[analysis.depth]"
    for key, value in (("max", spec.depth_max), ("min", spec.depth_min)):
        if not value < spec.problem.depth_limit:
            raise ModelError(where, key, value, f"a depth below {spec.problem.depth_limit:.6g}: at larger depth the "
                             "pulsating K(t) or M(t) is not positive definite during the whole period")
    return spec, stability_chart(spec.problem, **spec.chart_kwargs(), progress=progress)
