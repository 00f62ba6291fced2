"""Model-file tables of the nonsmooth elements and ``[simulation]`` (see docs/discrete.md).

Builds on :class:`discrete.lumped.LumpedModel` (bodies, drivers, springs, dampers, gears) and
adds ``[[friction]]``, ``[[one_sided]]``, ``[[gap]]``, ``[[impact]]``, ``[[force]]``,
``[constants]`` and ``[simulation]``.  Element coordinates are given by ``body = "name"`` (s = x)
or ``between = ["a", "b"]`` with optional ``ratios = [r_a, r_b]`` (s = r_b x_b - r_a x_a, as
springs); gears are eliminated the same way as in the linear part.
"""
from __future__ import annotations


import numpy as np

from ..errors import ModelError
from ..lumped import GROUND, LumpedModel
from ..schema import check_keys, choice, number, require
from .elements import Friction, Gap, Impact, OneSided
from .problem import ExternalForce, MotionLaw, Problem

LUMPED_KEYS = {"title", "body", "driver", "spring", "damper", "gear"}
TOP_LEVEL_KEYS = {"friction", "one_sided", "gap", "impact", "force", "simulation", "constants"}
SIM_KEYS = {"t_end", "method", "max_events", "max_step", "steps_per_period", "rtol", "rest_tol", "energy",
            "regularisation", "penalty", "memory_time", "output_step"}
REG_METHODS = ("event", "regularised")


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


def _name(t, where, default):
    n = t.get("name", default)
    if not isinstance(n, str) or not n:
        raise ModelError(where, "name", n, "a non-empty string")
    return n


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
    sim = doc.get("simulation")
    if not isinstance(sim, dict):
        raise ModelError("model file", "simulation", sim, "a table [simulation] with t_end = .. (required)")
    check_keys(sim, SIM_KEYS, "[simulation]")
    t_end = number(require(sim, "t_end", "[simulation]", "the end time in s"), "t_end", "[simulation]", positive=True)
    settings = {"t_end": t_end, "method": choice(sim.get("method", "event"), "method", "[simulation]", REG_METHODS)}
    for k, kw in (("max_events", dict(positive=True, integer=True)), ("max_step", dict(positive=True)),
                  ("steps_per_period", dict(positive=True, integer=True)), ("rtol", dict(positive=True)),
                  ("rest_tol", dict(positive=True)), ("regularisation", dict(positive=True)),
                  ("penalty", dict(positive=True)), ("memory_time", dict(positive=True)),
                  ("output_step", dict(positive=True))):
        if k in sim:
            settings[k] = number(sim[k], k, "[simulation]", **kw)
    if "energy" in sim:
        if not isinstance(sim["energy"], bool):
            raise ModelError("[simulation]", "energy", sim["energy"], "true | false")
        settings["energy"] = sim["energy"]

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

    elements, used = [], set()

    def uniq(n, where):
        if n in used:
            raise ModelError(where, "name", n, "a name not used by another element")
        used.add(n)
        return n

    for i, t in enumerate(doc.get("friction", []), 1):
        w = f"[[friction]] #{i}"
        check_keys(t, {"name", "body", "between", "ratios", "kinetic", "static", "mu", "mu_static", "normal",
                       "viscous", "quadratic", "cubic", "surface_velocity", "restick"}, w)
        g = _coordinate(t, w, lm, names_all, T)
        name = uniq(_name(t, w, f"friction{i}"), w)
        normal = choice(t.get("normal", "given"), "normal", w, ("given", "weight"))
        mass0 = rate = None
        if normal == "weight":
            for k in ("kinetic", "static"):
                if k in t:
                    raise ModelError(w, k, t[k], "not with normal = \"weight\" (give mu and mu_static)")
            if "body" not in t:
                raise ModelError(w, "body", None, "the body whose weight presses the contact (normal = \"weight\")")
            b = bodies.get(t["body"])
            if b is None:
                raise ModelError(w, "body", t["body"], "a body (not a driver) for normal = \"weight\"")
            mu = number(require(t, "mu", w, "the friction coefficient"), "mu", w, nonnegative=True)
            mus = number(t.get("mu_static", mu), "mu_static", w, nonnegative=True)
            if mus < mu:
                raise ModelError(w, "mu_static", mus, f"a number >= mu = {mu!r}")
            kinetic, static = mu * grav * b.inertia, mus * grav * b.inertia
            mass0, rate = b.inertia, b.inertia_rate
        else:
            for k in ("mu", "mu_static"):
                if k in t:
                    raise ModelError(w, k, t[k], "only with normal = \"weight\"")
            kinetic = number(require(t, "kinetic", w, "the kinetic friction level (force or torque)"), "kinetic", w)
            static = number(t["static"], "static", w) if "static" in t else None
            if kinetic < 0:
                raise ModelError(w, "kinetic", kinetic, "a number >= 0")
            if static is not None and static < kinetic:
                raise ModelError(w, "static", static, f"a number >= the kinetic level {kinetic!r}")
        el = Friction(name=name, g=g, kinetic=kinetic, static=static,
                      viscous=number(t.get("viscous", 0.0), "viscous", w),
                      quadratic=number(t.get("quadratic", 0.0), "quadratic", w),
                      cubic=number(t.get("cubic", 0.0), "cubic", w),
                      surface_velocity=number(t.get("surface_velocity", 0.0), "surface_velocity", w),
                      restick=choice(t.get("restick", "static"), "restick", w, ("static", "kinetic")),
                      mass0=mass0, mass_rate=rate or 0.0)
        elements.append(el)

    for i, t in enumerate(doc.get("one_sided", []), 1):
        w = f"[[one_sided]] #{i}"
        check_keys(t, {"name", "body", "between", "ratios", "k", "preload", "side"}, w)
        g = _coordinate(t, w, lm, names_all, T)
        name = uniq(_name(t, w, f"one_sided{i}"), w)
        k = number(require(t, "k", w, "the stiffness"), "k", w)
        if not k > 0:
            raise ModelError(w, "k", k, "a number > 0")
        side = {"tension": 1, "compression": -1}[choice(t.get("side", "tension"), "side", w, ("tension", "compression"))]
        pre = number(t.get("preload", 0.0), "preload", w)
        elements.append(OneSided(name=name, g=g, k=k, s_open=-side * pre / k, side=side))

    for i, t in enumerate(doc.get("gap", []), 1):
        w = f"[[gap]] #{i}"
        check_keys(t, {"name", "body", "between", "ratios", "k", "delta", "lower", "upper", "law", "L"}, w)
        g = _coordinate(t, w, lm, names_all, T)
        name = uniq(_name(t, w, f"gap{i}"), w)
        k = number(require(t, "k", w, "the contact stiffness"), "k", w)
        if not k > 0:
            raise ModelError(w, "k", k, "a number > 0")
        if "delta" in t:
            for kk in ("lower", "upper"):
                if kk in t:
                    raise ModelError(w, kk, t[kk], "not together with delta (symmetric gap)")
            d = number(t["delta"], "delta", w, nonnegative=True)
            lo, up = -d, d
        else:
            lo = number(require(t, "lower", w, "the lower clearance bound (or delta)"), "lower", w)
            up = number(require(t, "upper", w, "the upper clearance bound (or delta)"), "upper", w)
            if lo > up:
                raise ModelError(w, "lower", lo, f"a number <= upper = {up!r}")
        elements.append(Gap(name=name, g=g, k=k, lower=lo, upper=up,
                            law=choice(t.get("law", "exact"), "law", w, ("exact", "arctan")),
                            L=number(t.get("L", 1e3), "L", w, positive=True)))

    for i, t in enumerate(doc.get("impact", []), 1):
        w = f"[[impact]] #{i}"
        check_keys(t, {"name", "body", "between", "ratios", "stop", "side", "restitution", "v_rest"}, w)
        g = _coordinate(t, w, lm, names_all, T)
        name = uniq(_name(t, w, f"impact{i}"), w)
        e = number(require(t, "restitution", w, "the restitution coefficient"), "restitution", w)
        if not 0 <= e <= 1:
            raise ModelError(w, "restitution", e, "a number in [0, 1]")
        stop = number(t.get("stop", 0.0), "stop", w)
        side = choice(t.get("side", "lower"), "side", w, ("lower", "upper"))
        if side == "upper":       # s <= stop  <=>  (-s) >= -stop
            g, stop = -g, -stop
        vr = number(t["v_rest"], "v_rest", w, positive=True) if "v_rest" in t else None
        elements.append(Impact(name=name, g=g, s_min=stop, restitution=e, v_rest=vr))

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
