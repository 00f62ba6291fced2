"""A ``rotor`` model file -> :class:`fem.rotor.Rotor` and the settings of its analyses.

The tables map field for field onto :mod:`fem.rotor.model` (which checks positions on the shaft,
the bearing tables' signs and sizes); this module resolves materials (segment override over
``[rotor.material]``, G from nu), disc geometry, units (rev/min -> rad/s, degrees -> rad) and speed
grids, and checks the sizes against the budget before anything is assembled.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from discrete.errors import ModelError

from ...rotor.model import (BEARING_COEFFICIENTS, Bearing, Coupling, Disc, Layer, Pedestal, Rotor, ShaftSegment,
                            Support, Unbalance)
from ...rotor.response import Probe
from ...sections import Material
from .. import budget

RPM = math.pi / 30.0
MAX_SPEEDS = 100_000
"""Speeds of one Campbell diagram or unbalance response, before the DRIVEFEM_BUDGET factor."""


def _material(default, override, where: str) -> Material:
    vals = {}
    for src in (default, override):
        if src is not None:
            for key in ("E", "G", "nu", "rho"):
                v = getattr(src, key)
                if v is not None:
                    if key in ("G", "nu"):
                        vals.pop("G", None)
                        vals.pop("nu", None)
                    vals[key] = v
    for key in ("E", "rho"):
        if key not in vals:
            raise ModelError(where, key, None, f"{key} in [rotor.material] or in the segment's material table")
    if "G" not in vals and "nu" not in vals:
        raise ModelError(where, "G", None, "G or nu in [rotor.material] or in the segment's material table")
    G = vals["G"] if "G" in vals else vals["E"] / (2.0 * (1.0 + vals["nu"]))
    return Material(E=vals["E"], G=G, rho=vals["rho"])


def _disc(d, rho_default: float | None, where: str) -> Disc:
    if d.width is None:
        return Disc(x=d.x, mass=d.mass or 0.0, Id=d.Id or 0.0, Ip=d.Ip or 0.0, name=d.name)
    rho = d.rho if d.rho is not None else rho_default
    if not rho:
        raise ModelError(where, "rho", d.rho, "a density > 0 for a disc given by its geometry (or in [rotor.material])")
    return Disc.from_geometry(d.x, d.width, d.d, d.di or 0.0, rho, d.name)


def _bearing(b) -> Bearing:
    speeds = b.speeds if b.speeds_rpm is None else [v * RPM for v in b.speeds_rpm]
    coeff = {k: getattr(b, k) for k in BEARING_COEFFICIENTS}
    return Bearing(x=b.x, speeds=speeds, interpolation=b.interpolation, extrapolate=b.extrapolate,
                   k_axial=b.k_axial, c_axial=b.c_axial,
                   pedestal=b.pedestal, name=b.name, **coeff)


def _journal(b, where: str):
    from ...rotor.bearings.journal import JournalBearing

    if b.speeds is not None:
        speeds = list(b.speeds)
    elif isinstance(b.speeds_rpm, list):
        speeds = [v * RPM for v in b.speeds_rpm]
    else:
        g = b.speeds_rpm
        budget.check_count(where, "speeds_rpm.points", g.points, 2000, "table speeds", g.points)
        speeds = list(np.linspace(g.start, g.stop, g.points) * RPM)
    budget.check_count(where, "speeds", len(speeds), 2000, "table speeds", len(speeds))
    budget.check_count(where, "mesh", b.mesh[0] * b.mesh[1], 400_000, "film elements", b.mesh)
    return JournalBearing(x=b.x, diameter=b.diameter, length=b.length, clearance=b.clearance, viscosity=b.viscosity,
                          load=b.load, load_angle=math.radians(b.load_angle_deg), film=b.film, cavitation=b.cavitation,
                          grooves=tuple((math.radians(c), math.radians(w)) for c, w in b.grooves_deg),
                          mesh=tuple(b.mesh), speeds=speeds, interpolation=b.interpolation, pedestal=b.pedestal,
                          name=b.name)


def _rolling(b):
    from ...rotor.bearings.rolling import RollingBearing

    return RollingBearing(x=b.x, element=b.element, elements=b.elements, element_diameter=b.element_diameter or 0.0,
                          pitch_diameter=b.pitch_diameter or 0.0, contact_angle=math.radians(b.contact_angle_deg),
                          clearance=b.clearance, inner_conformity=b.inner_conformity,
                          outer_conformity=b.outer_conformity, roller_length=b.roller_length, modulus=b.modulus,
                          poisson=b.poisson, contact_stiffness=b.contact_stiffness, damping=b.damping, load=b.load,
                          load_angle=math.radians(b.load_angle_deg), pedestal=b.pedestal, name=b.name)


def _damper(b):
    from ...rotor.bearings.squeeze_film import SqueezeFilmDamper

    return SqueezeFilmDamper(x=b.x, diameter=b.diameter, length=b.length, clearance=b.clearance,
                             viscosity=b.viscosity, film=b.film, centering_stiffness=b.centering_stiffness, load=b.load,
                             load_angle=math.radians(b.load_angle_deg), pedestal=b.pedestal, name=b.name)


def _geometry_bearings(r) -> list:
    """[[rotor.journal_bearing]], [[rotor.rolling_bearing]], [[rotor.squeeze_film_damper]] -> bearings."""
    out = [_journal(b, f"[[rotor.journal_bearing]] #{i}") for i, b in enumerate(r.journal_bearing, 1)]
    out += [_rolling(b) for b in r.rolling_bearing]
    out += [_damper(b) for b in r.squeeze_film_damper]
    return out


def rotor_model(doc) -> Rotor:
    """The :class:`Rotor` a file describes (checked by the dataclasses; sizes checked up front)."""
    r = doc.rotor
    per_node = 6 if r.dofs == "full" else 4
    n_el = sum(s.elements for s in r.segment)
    budget.check_count("[[rotor.segment]]", "elements", (n_el + 1) * per_node, budget.MAX_FE_DOFS, "rotor DOFs",
                       [s.elements for s in r.segment])
    segments = []
    for i, s in enumerate(r.segment, 1):
        where = f"[[rotor.segment]] #{i}"
        segments.append(ShaftSegment(length=s.length, elements=s.elements, d=s.d, d_end=s.d_end, di=s.di,
                                     di_end=s.di_end, material=_material(r.material, s.material, where),
                                     shear_coefficient=s.shear_coefficient,
                                     added_mass_per_length=s.added_mass_per_length,
                                     layers=[Layer(d=q.d, di=q.di, d_end=q.d_end, di_end=q.di_end,
                                                   material=_material(r.material, q.material, f"{where} layer #{j}"),
                                                   shear_coefficient=q.shear_coefficient, mass_only=q.mass_only)
                                             for j, q in enumerate(s.layer, 1)]))
    rho = r.material.rho if r.material is not None else None
    discs = [_disc(d, rho, f"[[rotor.disc]] #{i}") for i, d in enumerate(r.disc, 1)]
    return Rotor(segments=segments, discs=discs, bearings=[_bearing(b) for b in r.bearing] + _geometry_bearings(r),
                 pedestals=[Pedestal(name=p.name, mass=p.mass, kyy=p.kyy, kzz=p.kzz, cyy=p.cyy, czz=p.czz)
                            for p in r.pedestal],
                 couplings=[Coupling(x=c.x, k_lateral=c.k_lateral, k_angular=c.k_angular, k_axial=c.k_axial,
                                     k_torsion=c.k_torsion, c_lateral=c.c_lateral, c_angular=c.c_angular,
                                     mass=c.mass, Id=c.Id, Ip=c.Ip, name=c.name) for c in r.coupling],
                 supports=[Support(x=s.x, dofs=tuple(s.dofs)) for s in r.support], dofs=r.dofs,
                 title=doc.title)


def speed_grid(table, where: str) -> np.ndarray:
    """The speeds of ``[campbell]`` or ``[unbalance_response]`` in rad/s (list or grid, rad/s or rev/min)."""
    raw, scale = (table.speeds, 1.0) if table.speeds is not None else (table.speeds_rpm, RPM)
    key = "speeds" if table.speeds is not None else "speeds_rpm"
    if isinstance(raw, list):
        s = np.asarray(raw, dtype=float)
    else:
        budget.check_count(where, key + ".points", raw.points, MAX_SPEEDS, "speeds", raw.points)
        s = np.linspace(raw.start, raw.stop, raw.points)
    budget.check_count(where, key, s.size, MAX_SPEEDS, "speeds", s.size)
    if np.any(np.diff(s) <= 0):
        raise ModelError(where, key, list(raw), "increasing speeds")
    return s * scale


def modal_speed(doc) -> float:
    """The speed of ``drivefem modal`` (rad/s; 0 without [analysis] speed)."""
    an = doc.analysis
    if an is None:
        return 0.0
    if an.speed_rpm is not None:
        return an.speed_rpm * RPM
    return an.speed or 0.0


def modes_count(doc, table=None, n_modes: int | None = None) -> int:
    """Modes asked for: argument, then the table's modes, then [analysis] modes, then 6."""
    for v in (n_modes, getattr(table, "modes", None), getattr(doc.analysis, "modes", None)):
        if v is not None:
            budget.check_count("[analysis]", "modes", v, budget.MAX_MODES, "modes", v)
            return int(v)
    return 6


def _unbalances(doc) -> list:
    """The [[unbalance]] tables as :class:`fem.rotor.Unbalance` (degrees -> rad)."""
    return [Unbalance(x=u.x, magnitude=u.magnitude, phase=math.radians(u.phase_deg)) for u in doc.unbalance]


def operating_range(doc) -> tuple | None:
    """The operating speed range (rad/s): [campbell]'s, else [unbalance_response]'s, else None."""
    for name in ("campbell", "unbalance_response"):
        t = getattr(doc, name, None)
        if t is None or (t.operating_range is None and t.operating_range_rpm is None):
            continue
        op = t.operating_range if t.operating_range_rpm is None else [v * RPM for v in t.operating_range_rpm]
        if not op[0] <= op[1]:
            raise ModelError(f"[{name}]", "operating_range" if t.operating_range_rpm is None else "operating_range_rpm",
                             list(t.operating_range or t.operating_range_rpm), "[min, max] with min <= max")
        return float(op[0]), float(op[1])
    return None


@dataclass
class ResponseSpec:
    """What ``drivefem forced`` needs: unbalances, speeds (rad/s), probes, operating range."""

    unbalances: list
    speeds: np.ndarray
    probes: list | None
    operating_range: tuple | None
    find_peaks: bool


def response_spec(doc) -> ResponseSpec:
    t = doc.unbalance_response
    if t is None:
        raise ModelError("model file (rotor)", "unbalance_response", None, "a table [unbalance_response] with "
                         "speeds = [..] or speeds_rpm = { start, stop, points } (required for drivefem forced)")
    if not doc.unbalance:
        raise ModelError("model file (rotor)", "unbalance", [], "at least one [[unbalance]] { x, magnitude, "
                         "phase_deg } (required for drivefem forced)")
    speeds = speed_grid(t, "[unbalance_response]")
    if speeds[0] <= 0:
        raise ModelError("[unbalance_response]", "speeds" if t.speeds is not None else "speeds_rpm",
                         float(speeds[0] / (1.0 if t.speeds is not None else RPM)),
                         "speeds > 0 (the unbalance force m e Omega^2 vanishes at rest)")
    op = t.operating_range if t.operating_range_rpm is None else [v * RPM for v in t.operating_range_rpm]
    if op is not None and not op[0] <= op[1]:
        raise ModelError("[unbalance_response]", "operating_range", list(op), "[min, max] with min <= max")
    probes = [Probe(p.x, p.direction, p.name or "") for p in t.probe] or None
    unb = _unbalances(doc)
    return ResponseSpec(unbalances=unb, speeds=speeds, probes=probes,
                        operating_range=None if op is None else (float(op[0]), float(op[1])), find_peaks=t.peaks)


@dataclass
class RunUpSpec:
    """What ``drivefem simulate`` of a rotor file needs: the ramp, the unbalances, the rubs."""

    run: object
    unbalances: list
    rubs: list


def run_up_spec(doc) -> RunUpSpec:
    """``[run_up]``, ``[[unbalance]]`` and ``[[rub]]`` -> :class:`fem.rotor.RunUp`, unbalances, rubs."""
    from ...rotor.runup import Rub, RunUp

    t = doc.run_up
    if t is None:
        raise ModelError("model file (rotor)", "run_up", None, "a table [run_up] with speed_start, speed_end (or "
                         "speed_start_rpm, speed_end_rpm) and duration (required for drivefem simulate)")
    start = t.speed_start if t.speed_start_rpm is None else t.speed_start_rpm * RPM
    end = t.speed_end if t.speed_end_rpm is None else t.speed_end_rpm * RPM
    run = RunUp(speed_start=float(start), speed_end=float(end), duration=t.duration, method=t.method, modes=t.modes,
                time_step=t.time_step, output_step=t.output_step, rtol=t.rtol, start=t.start, max_events=t.max_events,
                integrator=t.integrator)
    if t.method == "moreau":
        h = t.time_step
        if h is not None:
            budget.check_count("[run_up]", "time_step", t.duration / h, budget.MAX_TIME_STEPS,
                               "Moreau-Jean time steps (duration / time_step)", h)
    unb = _unbalances(doc)
    rubs = [Rub(x=r.x, clearance=r.clearance, stiffness=r.stiffness, damping=r.damping, restitution=r.restitution,
                friction=r.friction, radius=r.radius, centre=tuple(r.centre), name=r.name) for r in doc.rub]
    for i, r in enumerate(doc.rub, 1):
        if t.method == "event" and r.stiffness is None:
            raise ModelError(f"[[rub]] #{i}", "stiffness", None, "a contact stiffness for [run_up] method = 'event' "
                             "(or method = 'moreau' for rigid contacts)")
        if t.method == "moreau" and r.stiffness is not None:
            raise ModelError(f"[[rub]] #{i}", "stiffness", r.stiffness, "no stiffness with [run_up] method = 'moreau' "
                             "(rigid contacts with restitution; or method = 'event' for compliant contacts)")
    geometry = doc.rotor.journal_bearing or doc.rotor.rolling_bearing or doc.rotor.squeeze_film_damper
    if not unb and not rubs and not geometry:
        raise ModelError("model file (rotor)", "unbalance", [], "at least one [[unbalance]] or [[rub]] for drivefem "
                         "simulate (without either the rotor stays at rest)")
    return RunUpSpec(run=run, unbalances=unb, rubs=rubs)


def _speed_key(table, default: float | None = None) -> float | None:
    """A table's ``speed`` (rad/s) or ``speed_rpm`` (rev/min -> rad/s), else ``default``."""
    if table is None:
        return default
    if getattr(table, "speed_rpm", None) is not None:
        return table.speed_rpm * RPM
    if getattr(table, "speed", None) is not None:
        return float(table.speed)
    return default


def static_spec(doc) -> dict:
    """``[static]`` (optional) -> keyword arguments of :func:`fem.rotor.static_deflection`."""
    from ...rotor.static import PointLoad

    t = doc.static
    speed = _speed_key(t, _speed_key(doc.analysis, 0.0))
    loads = [PointLoad(x=p.x, fy=p.fy, fz=p.fz, fx=p.fx) for p in (t.load if t is not None else [])]
    gravity = tuple(t.gravity) if t is not None else (0.0, 0.0, -9.81)
    return {"gravity": gravity, "loads": loads, "speed": speed}


def stability_speeds(doc) -> np.ndarray:
    """The speeds scanned by ``drivefem stability`` (rad/s > 0): [stability]'s, else [campbell]'s."""
    t = doc.stability
    if t is not None and (t.speeds is not None or t.speeds_rpm is not None):
        s, where = speed_grid(t, "[stability]"), "[stability]"
    elif doc.campbell is not None:
        s, where = speed_grid(doc.campbell, "[campbell]"), "[campbell]"
    else:
        raise ModelError("model file (rotor)", "stability", None, "a table [stability] with speeds = [..] or "
                         "speeds_rpm = { start, stop, points } (or a [campbell] table) for drivefem stability")
    s = s[s > 0]
    if s.size < 2:
        raise ModelError(where, "speeds", s.tolist(), "at least two speeds > 0 to scan for the stability threshold")
    return s


def level1_spec(doc, op_range) -> dict | None:
    """``[stability.api_level1]`` -> keyword arguments of :func:`fem.rotor.api_level1.api_level1`, or None."""
    from ...rotor.api_level1 import Stage

    t = doc.stability.api_level1 if doc.stability is not None else None
    if t is None:
        return None
    speed = _speed_key(t, None if op_range is None else op_range[1])
    if speed is None:
        raise ModelError("[stability.api_level1]", "speed_rpm", None, "the maximum continuous speed: speed_rpm = .. "
                         "(or speed, rad/s), or an operating range in [campbell] / [unbalance_response]")
    stages = [Stage(x=s.x, power=s.power, diameter=s.diameter, width=s.width, density_ratio=s.density_ratio,
                    name=s.name) for s in t.stage]
    return {"stages": stages, "speed": speed, "machine": t.machine, "placement": t.placement,
            "exclude": tuple(t.exclude), "points": t.points}
