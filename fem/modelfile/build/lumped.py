"""Lumped model files -> :class:`discrete.lumped.LumpedModel` (linear part) and the nonsmooth
:class:`discrete.nonsmooth.Problem` (elements, drivers, forces, variable mass) of the time and
steady-state analyses.  Time-domain-only data -- a spring's ``modulation`` (an element of
pulsating stiffness), a driver's ``programme`` (a cam law), ``[[motor]]`` -- enter the Problem only;
the linear part keeps the constant stiffness k and the driver's constant/harmonic law."""
from __future__ import annotations

import numpy as np

from discrete.errors import ModelError
from discrete.lumped import GROUND, Body, Driver, Gear, Link, LumpedModel
from discrete.motion import cam_laws
from discrete.motion.piecewise import PiecewiseLaw
from discrete.nonsmooth import ExternalForce, MotionLaw
from discrete.nonsmooth.elements import ModulatedSpring
from discrete.nonsmooth.problem import ProblemSpec, ProgrammeMotion

from ...loads.names import force_name
from .damping import time_domain_damping
from .elements import element_tables


def _names(pair, where: str) -> tuple[str, str]:
    for end in pair:
        if not isinstance(end, str):
            raise ModelError(where, "between", end.model_dump(), "a body or driver name, or \"ground\" "
                             "(FE nodes { x = .. } only in hybrid models)")
    return pair[0], pair[1]


def lumped_model(doc) -> LumpedModel:
    """The linear part of a lumped model file: bodies, drivers, springs, dampers, gears."""
    if not doc.body:        # every analysis needs a free coordinate (modal and forced as well as simulate)
        raise ModelError("model file", "body", None, "at least one [[body]] table")
    drivers = []
    for i, t in enumerate(doc.driver, 1):
        w = f"[[driver]] #{i}"
        if t.x is not None or t.dof is not None:
            raise ModelError(w, "x" if t.x is not None else "dof", t.x if t.x is not None else t.dof,
                             "name = .. (a lumped driver; FE nodes only in hybrid models)")
        if t.name is None:
            raise ModelError(w, "name", None, "the driver's name (required key missing)")
        drivers.append(Driver(name=t.name, velocity=t.velocity if t.given("velocity") else None,
                              amplitude=t.amplitude, omega=t.omega, phase=t.phase, inertia=t.inertia,
                              offset=t.offset))
    springs, dampers = [], []
    for i, t in enumerate(doc.spring, 1):
        pair = _names(t.between, f"[[spring]] #{i}")
        springs.append(Link(between=pair, value=t.k, ratios=tuple(t.ratios), psi=t.psi))
        if t.c:
            dampers.append((i, Link(between=pair, value=t.c, ratios=tuple(t.ratios))))
    damper_links = [Link(between=_names(t.between, f"[[damper]] #{i}"), value=t.c, ratios=tuple(t.ratios))
                    for i, t in enumerate(doc.damper, 1)] + [ln for _, ln in dampers]
    return LumpedModel(bodies=[Body(name=b.name, inertia=b.inertia, inertia_rate=b.inertia_rate, reactive=b.reactive,
                                    x0=b.x0, v0=b.v0) for b in doc.body],
                       drivers=drivers, springs=springs, dampers=damper_links,
                       gears=[Gear(between=tuple(g.between), ratio=g.ratio) for g in doc.gear], title=doc.title)


def forcing_omegas(doc) -> list[float]:
    """The frequencies of the harmonic drivers and forces: the reference of psi's equivalent viscous
    damping (9.3) in a simulation; none in a file with a [steady] table, whose forcing frequency is
    continued (psi then goes by the modal form unless omega_ref is a number)."""
    if getattr(doc, "steady", None) is not None:
        return []
    return [d.omega for d in doc.driver if d.amplitude] + [f.omega for f in doc.force if f.amplitude]


def programme_law(prog, where: str, t_end: float | None = None) -> PiecewiseLaw:
    """The time law x(t) of a driver's ``programme`` table: a dwell-rise-dwell-return cycle of a
    standard cam law or a C2 spline table, in the cam angle phi = cam_speed (t - start) (a table's
    first angle at t = start).  A non-periodic table must cover the run [0, t_end]."""
    if prog.law == "table" and not prog.periodic:
        if prog.start > 0:
            raise ModelError(f"{where} programme", "start", prog.start, "a time <= 0 for a non-periodic table "
                             "(the law is defined from its first angle on; the run starts at t = 0)")
        end = prog.start + (prog.phi[-1] - prog.phi[0]) / prog.cam_speed
        if t_end is not None and end < t_end:
            raise ModelError(f"{where} programme", "phi", [prog.phi[0], prog.phi[-1]],
                             f"a non-periodic table covering the run: its end t = {end:.6g} s is before t_end = "
                             f"{t_end!r} (extend the table or set periodic = true)")
    try:
        if prog.law == "table":
            law = PiecewiseLaw.tabulated(prog.phi, prog.x, periodic=prog.periodic, name="table")
        else:
            law = cam_laws.dwell_rise_dwell_return(prog.stroke, prog.rise, prog.top_dwell, prog.return_,
                                                   law=prog.law, return_law=prog.return_law, cycle=prog.cycle)
        return law.in_time(prog.cam_speed, prog.start)
    except ModelError as exc:
        raise ModelError(f"{where} programme", exc.key, exc.value, exc.allowed) from None


def _time_domain_only(doc) -> list[tuple[str, str, object]]:
    """(where, key, value) of the tables only the time simulation integrates."""
    out = [(f"[[spring]] #{i}", "modulation", t.modulation.model_dump()) for i, t in enumerate(doc.spring, 1)
           if t.modulation is not None]
    out += [(f"[[driver]] #{i}", "programme", t.programme.law) for i, t in enumerate(doc.driver, 1)
            if t.programme is not None]
    out += [(f"[[motor]] #{i}", "kind", "motor") for i, _ in enumerate(getattr(doc, "motor", ()), 1)]
    return out


def _refuse_outside_event_solver(doc) -> None:
    """Modulated springs, programme laws and motors are integrated by the event (or regularised)
    solver: a clear error for a [steady] table or the Moreau-Jean stepper, which would not see them."""
    found = _time_domain_only(doc)
    if not found:
        return
    where, key, value = found[0]
    if getattr(doc, "steady", None) is not None:
        raise ModelError(where, key, value, "a time simulation ([simulation], method = 'event'): a [steady] "
                         "periodic state of a model with a modulated spring, a programme law or a motor is not "
                         "available (the stability of a pulsating linear system: [analysis] type = 'parametric')")
    sim = getattr(doc, "simulation", None)
    if sim is not None and sim.method == "moreau":
        raise ModelError(where, key, value, "[simulation] method = 'event' (the Moreau-Jean stepper does not "
                         "integrate modulated springs, programme laws or motors)")


def problem_spec(doc, t_end: float | None = None, refuse: bool = True) -> ProblemSpec:
    """The nonsmooth problem of a lumped model file (elements, drivers, forces, variable mass);
    ``refuse``: the tables only the event solver integrates are an error with [steady] or Moreau-Jean
    (False: the linear analyses' view, which only reads the elements)."""
    if refuse:
        _refuse_outside_event_solver(doc)
    lm = lumped_model(doc)
    if not lm.bodies:
        raise ModelError("model file", "body", None, "at least one [[body]] table")
    grav = doc.constants.g
    names_all = lm.names
    indep, T = lm.transformation()
    omegas = forcing_omegas(doc)
    ls, psi_report = time_domain_damping(lm.linear_system(), doc.damping, omegas)
    bodies = {b.name: b for b in lm.bodies}
    rates = np.array([bodies[n].inertia_rate if n in bodies else 0.0 for n in names_all])
    react = np.array([bodies[n].reactive * bodies[n].inertia_rate if n in bodies else 0.0 for n in names_all])
    if t_end is not None:
        for n, b in bodies.items():
            if b.inertia_rate < 0:
                t0 = -b.inertia / b.inertia_rate
                if t0 <= t_end:
                    raise ModelError(f"[[body]] {n!r}", "inertia_rate", b.inertia_rate,
                                     f"a rate keeping the inertia positive up to t_end = {t_end!r} "
                                     f"(the inertia would vanish at t = {t0:.6g})")
    Mdot = T.T @ np.diag(rates) @ T
    Creact = T.T @ np.diag(react) @ T

    def coordinate(t, where: str) -> np.ndarray:
        """Gradient g (independent coordinates) of s = ratio x_body or s = r_b x_b - r_a x_a."""
        return named(t, where) @ T

    def named(t, where: str) -> np.ndarray:
        """Gradient g over every body and driver (gear-driven bodies included)."""
        allowed = names_all + [GROUND]
        g_all = np.zeros(len(names_all))
        if t.x is not None:
            raise ModelError(where, "x", t.x, "body = .. or between = [..] (FE nodes only in hybrid models)")
        if t.body is not None:
            if t.body not in names_all:
                raise ModelError(where, "body", t.body, "one of " + ", ".join(map(repr, names_all)))
            g_all[names_all.index(t.body)] = 1.0 if t.ratio is None else t.ratio
        elif t.between is not None:
            a, b = _names(t.between, where)
            if a == b:
                raise ModelError(where, "between", [a, b], "two different names, e.g. [\"ground\", \"disk\"]")
            ra, rb = t.ratios if t.ratios is not None else (1.0, 1.0)
            for n in (a, b):
                if n not in allowed:
                    raise ModelError(where, "between", n, "one of " + ", ".join(map(repr, allowed)))
            if a != GROUND:
                g_all[names_all.index(a)] -= ra
            if b != GROUND:
                g_all[names_all.index(b)] += rb
        return g_all

    def weight(t, where):
        b = bodies.get(t.body)
        if b is None:
            raise ModelError(where, "body", t.body, "a body (not a driver) for normal = \"weight\"")
        return grav * b.inertia, b.inertia, b.inertia_rate or 0.0

    elements, layout = [], {"elements": [], "forces": [], "force_names": []}
    for table, i, t, name in element_tables(doc):
        where = f"[[{table}]] #{i}"
        g = named(t, where)
        cls, kw, flip = t.element(where, "lumped", weight)
        if t.linearise is not None:
            kw.setdefault("linearise", t.linearise)
        g = np.negative(g) if flip else g
        elements.append(cls(name=name, g=g @ T, **kw))
        layout["elements"].append((table, g))
    used = {el.name for el in elements}
    for i, t in enumerate(doc.spring, 1):
        if t.modulation is None:
            continue
        where = f"[[spring]] #{i}"
        name = f"spring{i}.modulation"
        if name in used:
            raise ModelError(where, "modulation", name, "an element name not used by another element")
        g = named(_SpringCoordinate(t.between, t.ratios), where)
        m = t.modulation
        elements.append(ModulatedSpring(name=name, g=g @ T, k=t.k, depth=m.depth, omega=m.omega, phase=m.phase))
        layout["elements"].append(("spring", g))

    forces = []
    for i, t in enumerate(doc.force, 1):
        w = f"[[force]] #{i}"
        g_named = named(t, w)
        g = g_named @ T
        layout["forces"].append(g_named)
        layout["force_names"].append(force_name(i, t))
        value = t.value
        if t.gravity:
            b = bodies.get(t.body)
            if b is None:
                raise ModelError(w, "body", t.body, "a body for gravity = true")
            if b.inertia_rate != 0:
                raise ModelError(w, "gravity", True, "a body of constant inertia (inertia_rate = 0)")
            value -= grav * b.inertia
        forces.append(ExternalForce(g=g, value=value, amplitude=t.amplitude, omega=t.omega, phase=t.phase))

    drivers = {}
    programmes = {t.name: (i, t.programme) for i, t in enumerate(doc.driver, 1) if t.programme is not None}
    for d in lm.drivers:
        if d.name in indep:
            base = dict(offset=d.offset, velocity=d.velocity or 0.0, amplitude=d.amplitude, omega=d.omega,
                        phase=d.phase)
            if d.name in programmes:
                i, prog = programmes[d.name]
                drivers[indep.index(d.name)] = ProgrammeMotion(law=programme_law(prog, f"[[driver]] #{i}", t_end),
                                                                 **base)
            else:
                drivers[indep.index(d.name)] = MotionLaw(**base)
    for n, b in bodies.items():
        if n not in indep and (b.x0 != 0 or b.v0 != 0):
            raise ModelError(f"[[body]] {n!r}", "x0" if b.x0 != 0 else "v0", b.x0 if b.x0 != 0 else b.v0,
                             "0 for a body driven by a [[gear]] (give the initial state of the driving body)")
    x0 = np.zeros(len(indep))
    v0 = np.zeros(len(indep))
    for j, n in enumerate(indep):
        if n in bodies:
            x0[j], v0[j] = bodies[n].x0, bodies[n].v0
    return ProblemSpec(system=ls, elements=elements, drivers=drivers, forces=forces, mass_rate=Mdot,
                       reactive=Creact, x0=x0, v0=v0, damping_report=psi_report, layout=layout)


class _SpringCoordinate:
    """The coordinate keys of a [[spring]] (s = r_b x_b - r_a x_a) in the form ``coordinate`` reads."""

    def __init__(self, between, ratios):
        self.between, self.ratios = between, tuple(ratios)
        self.body = self.x = self.ratio = None
