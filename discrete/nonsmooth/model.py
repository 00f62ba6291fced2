"""Model-file tables of the nonsmooth elements and ``[simulation]`` (see docs/discrete.md).

Builds on :class:`discrete.lumped.LumpedModel` (bodies, drivers, springs, dampers, gears) and
adds ``[[friction]]``, ``[[one_sided]]``, ``[[gap]]``, ``[[impact]]``, ``[[force]]``,
``[constants]`` and ``[simulation]``.  Element coordinates are given by ``body = "name"`` (s = x)
or ``between = ["a", "b"]`` with optional ``ratios = [r_a, r_b]`` (s = r_b x_b - r_a x_a, as
springs); gears are eliminated the same way as in the linear part.
"""
from __future__ import annotations

from functools import partial

import numpy as np

from ..errors import ModelError
from ..lumped import GROUND, LumpedModel
from ..schema import check_keys, choice, number, require
from .problem import ExternalForce, MotionLaw, Problem
from .tables import element_tables, simulation_table

LUMPED_KEYS = {"title", "body", "driver", "spring", "damper", "gear"}
TOP_LEVEL_KEYS = {"friction", "one_sided", "gap", "impact", "force", "simulation", "constants"}
SIM_KEYS = {"t_end", "method", "max_events", "max_step", "steps_per_period", "rtol", "rest_tol", "energy",
            "regularisation", "penalty", "memory_time", "output_step"}
REG_METHODS = ("event", "regularised")
BODY_KEYS = {"body", "between", "ratios"}      # element coordinate s (see _coordinate)
WEIGHT_KEYS = {"mu", "mu_static", "normal"}    # [[friction]] normal = "weight"


def _coordinate(t: dict, where: str, lm: LumpedModel, names_all: list[str], T: np.ndarray) -> np.ndarray:
    """Gradient g (independent coordinates) of s = x_body or s = r_b x_b - r_a x_a."""
    allowed = names_all + [GROUND]
    g_all = np.zeros(len(names_all))
    if "body" in t and "between" in t:
        raise ModelError(where, "between", t["between"], "either body = .. or between = [..], not both")
    if "body" in t:
        b = t["body"]
        if b not in names_all:
            raise ModelError(where, "body", b, "one of " + ", ".join(map(repr, names_all)))
        g_all[names_all.index(b)] = 1.0
    elif "between" in t:
        pair = t["between"]
        if not isinstance(pair, list) or len(pair) != 2 or not all(isinstance(s, str) for s in pair) \
                or pair[0] == pair[1]:
            raise ModelError(where, "between", pair, "a list of two different names, e.g. [\"ground\", \"disk\"]")
        ratios = t.get("ratios", [1.0, 1.0])
        if not isinstance(ratios, list) or len(ratios) != 2:
            raise ModelError(where, "ratios", ratios, "a list [r_a, r_b] of two numbers")
        ra, rb = (number(r, "ratios", where) for r in ratios)
        for n in pair:
            if n not in allowed:
                raise ModelError(where, "between", n, "one of " + ", ".join(map(repr, allowed)))
        if pair[0] != GROUND:
            g_all[names_all.index(pair[0])] -= ra
        if pair[1] != GROUND:
            g_all[names_all.index(pair[1])] += rb
    else:
        raise ModelError(where, "body", None, "body = \"name\" or between = [\"a\", \"b\"] (required)")
    return g_all @ T


def _weight_levels(t: dict, where: str, bodies: dict, grav: float) -> dict | None:
    """Friction levels mu g m(t), mu_static g m(t) of normal = "weight" (None for normal = "given")."""
    if choice(t.get("normal", "given"), "normal", where, ("given", "weight")) == "given":
        for k in ("mu", "mu_static"):
            if k in t:
                raise ModelError(where, k, t[k], "only with normal = \"weight\"")
        return None
    for k in ("kinetic", "static"):
        if k in t:
            raise ModelError(where, k, t[k], "not with normal = \"weight\" (give mu and mu_static)")
    if "body" not in t:
        raise ModelError(where, "body", None, "the body whose weight presses the contact (normal = \"weight\")")
    b = bodies.get(t["body"])
    if b is None:
        raise ModelError(where, "body", t["body"], "a body (not a driver) for normal = \"weight\"")
    mu = number(require(t, "mu", where, "the friction coefficient"), "mu", where, nonnegative=True)
    mus = number(t.get("mu_static", mu), "mu_static", where, nonnegative=True)
    if mus < mu:
        raise ModelError(where, "mu_static", mus, f"a number >= mu = {mu!r}")
    return dict(kinetic=mu * grav * b.inertia, static=mus * grav * b.inertia, mass0=b.inertia,
                mass_rate=b.inertia_rate or 0.0)


def build_problem(doc: dict):
    """Parse a model dict into (Problem, simulation settings dict)."""
    hints = {k: ("a table of the modal/forced analyses, not used by the time simulation "
                 "(use [[damper]], [[force]] and [[driver]] tables)") for k in ("damping", "load", "base_motion", "response")}
    # [analysis] selects the analysis of other commands; the time simulation is set by [simulation]
    check_keys(doc, LUMPED_KEYS | TOP_LEVEL_KEYS | {"analysis"}, "model file", hints=hints)
    for key in TOP_LEVEL_KEYS - {"simulation", "constants"}:
        if key in doc and not isinstance(doc[key], list):
            raise ModelError("model file", key, doc[key], f"an array of tables [[{key}]]")
    lm = LumpedModel.from_dict(doc)
    if not lm.bodies:
        raise ModelError("model file", "body", None, "at least one [[body]] table")
    consts = doc.get("constants", {})
    if not isinstance(consts, dict):
        raise ModelError("model file", "constants", consts, "a table [constants]")
    check_keys(consts, {"g"}, "[constants]")
    grav = number(consts.get("g", 9.81), "g", "[constants]", positive=True)
    pos, count = dict(positive=True), dict(positive=True, integer=True)
    settings = simulation_table(doc, SIM_KEYS, REG_METHODS, {
        "max_events": count, "max_step": pos, "steps_per_period": count, "rtol": pos, "rest_tol": pos,
        "regularisation": pos, "penalty": pos, "memory_time": pos, "output_step": pos})
    t_end = settings["t_end"]

    names_all = lm.names
    indep, T = lm.transformation()
    ls = lm.linear_system()
    bodies = {b.name: b for b in lm.bodies}
    # variable mass (seed 004 (1)): Mdot and the reactive damping epsilon * Mdot, reduced by T
    rates = np.array([bodies[n].inertia_rate if n in bodies else 0.0 for n in names_all])
    react = np.array([bodies[n].reactive * bodies[n].inertia_rate if n in bodies else 0.0 for n in names_all])
    for n, b in bodies.items():
        if b.inertia_rate < 0:
            t0 = -b.inertia / b.inertia_rate
            if t0 <= t_end:
                raise ModelError(f"[[body]] {n!r}", "inertia_rate", b.inertia_rate,
                                 f"a rate keeping the inertia positive up to t_end = {t_end!r} "
                                 f"(the inertia would vanish at t = {t0:.6g})")
    Mdot = T.T @ np.diag(rates) @ T
    Creact = T.T @ np.diag(react) @ T

    coordinate = partial(_coordinate, lm=lm, names_all=names_all, T=T)
    elements = [cls(g=g, **kw) for cls, kw, g in element_tables(
        doc, set(), coordinate, np.negative, BODY_KEYS, one_sided_side="tension", single_bound_gap=False,
        friction_levels=partial(_weight_levels, bodies=bodies, grav=grav), friction_keys=WEIGHT_KEYS)]

    forces = []
    for i, t in enumerate(doc.get("force", []), 1):
        w = f"[[force]] #{i}"
        check_keys(t, {"body", "between", "ratios", "value", "amplitude", "omega", "phase", "gravity"}, w)
        g = _coordinate(t, w, lm, names_all, T)
        value = number(t.get("value", 0.0), "value", w)
        if "gravity" in t:
            if not isinstance(t["gravity"], bool):
                raise ModelError(w, "gravity", t["gravity"], "true | false")
            if t["gravity"]:
                b = bodies.get(t.get("body"))
                if b is None:
                    raise ModelError(w, "body", t.get("body"), "a body for gravity = true")
                if b.inertia_rate != 0:
                    raise ModelError(w, "gravity", True, "a body of constant inertia (inertia_rate = 0)")
                value -= grav * b.inertia
        amp = number(t.get("amplitude", 0.0), "amplitude", w)
        om = number(t.get("omega", 0.0), "omega", w, nonnegative=True)
        if amp != 0 and om == 0:
            raise ModelError(w, "omega", om, "a number > 0 with amplitude")
        forces.append(ExternalForce(g=g, value=value, amplitude=amp, omega=om,
                                    phase=number(t.get("phase", 0.0), "phase", w)))

    drivers = {}
    for d in lm.drivers:
        j = indep.index(d.name) if d.name in indep else None
        if j is None:
            continue
        drivers[j] = MotionLaw(velocity=d.velocity or 0.0, amplitude=d.amplitude, omega=d.omega, phase=d.phase)
    for n, b in bodies.items():
        if n not in indep and (b.x0 != 0 or b.v0 != 0):
            raise ModelError(f"[[body]] {n!r}", "x0" if b.x0 != 0 else "v0", b.x0 if b.x0 != 0 else b.v0,
                             "0 for a body driven by a [[gear]] (give the initial state of the driving body)")
    x0 = np.zeros(len(indep))
    v0 = np.zeros(len(indep))
    for j, n in enumerate(indep):
        if n in bodies:
            x0[j], v0[j] = bodies[n].x0, bodies[n].v0
    prob = Problem(ls, elements, drivers=drivers, forces=forces, mass_rate=Mdot, reactive=Creact, x0=x0, v0=v0)
    return prob, settings


def run_model_file(doc: dict):
    """Simulate a parsed model file; returns a :class:`SimulationResult` (contract of design.md §5)."""
    from .regularised import simulate_regularised
    from .solver import Options, simulate

    prob, st = build_problem(doc)
    if st["method"] == "regularised":
        kw = {k: st[k] for k in ("regularisation", "penalty", "memory_time", "rtol", "max_step") if k in st}
        return simulate_regularised(prob, st["t_end"], **kw)
    opts = Options(**{k: st[k] for k in ("max_events", "max_step", "steps_per_period", "rtol", "rest_tol", "energy",
                                         "output_step") if k in st})
    return simulate(prob, st["t_end"], opts)
