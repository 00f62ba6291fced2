"""Hybrid model files: FE tables (``[material]``, ``[model]``, ``[[segment]]``, ``[[support]]``,
``[[point]]``) plus lumped bodies, springs, drivers and nonsmooth elements attached to FE nodes
by ``x`` (and ``dof``), a ``[reduction]`` table and ``[simulation]``.  See docs/hybrid.md.
"""
from __future__ import annotations

from discrete.errors import ModelError
from discrete.nonsmooth import MotionLaw
from discrete.nonsmooth.tables import element_tables, simulation_table, unique_name
from discrete.schema import check_keys, choice, number, require

from ..assembly import assemble
from ..modelfile import parse_shaft
from .build import (Body, DriverSpec, ElementSpec, ForceSpec, HybridModel, NodeRef, ReductionSpec, Spring)
from .distributed import distributed_friction

FE_TABLES = {"material", "model", "segment", "support", "point"}
HYBRID_TABLES = {"damping", "body", "spring", "driver", "friction", "one_sided", "gap", "impact", "force",
                 "distributed_friction", "reduction", "simulation", "constants", "initial"}
ALLOWED = FE_TABLES | HYBRID_TABLES | {"title", "analysis"}
ELEMENT_TABLES = ("friction", "one_sided", "gap", "impact", "distributed_friction")
SIM_KEYS = {"t_end", "method", "dt", "theta", "max_events", "max_step", "steps_per_period", "rest_tol", "energy",
            "samples", "tol", "max_iter"}
METHODS = ("event", "moreau")
REF_KEYS = {"x", "dof", "body"}


def is_hybrid(doc: dict) -> bool:
    """An FE model file (``[[segment]]``) with nonsmooth elements, bodies, drivers, forces or a
    ``[reduction]`` table: run by :func:`fem.hybrid.run_model_file`."""
    return isinstance(doc, dict) and "segment" in doc and any(k in doc for k in HYBRID_TABLES - {"constants", "damping"})


def _ref(t: dict, where: str) -> NodeRef:
    if "body" in t and "x" in t:
        raise ModelError(where, "body", t["body"], "either body = .. (a lumped body) or x = .. (an FE node), not both")
    if "body" in t:
        if not isinstance(t["body"], str):
            raise ModelError(where, "body", t["body"], "a body name")
        return NodeRef(body=t["body"])
    if "x" not in t:
        raise ModelError(where, "x", None, "the node position x = .. (with dof = ..) or body = \"name\" (required)")
    dof = t.get("dof")
    if dof is not None and not isinstance(dof, str):
        raise ModelError(where, "dof", dof, "a DOF name such as \"theta\", \"u\", \"w\", \"w_x\", \"phi\"")
    return NodeRef(x=number(t["x"], "x", where), dof=dof)


def _terms(t: dict, where: str) -> list:
    """Coordinate s of an element: x/dof or body (s = that DOF) or between = [a, b] with ratios."""
    if "between" in t:
        if "x" in t or "body" in t:
            raise ModelError(where, "between", t["between"], "either between = [..] or x/body, not both")
        pair = t["between"]
        if not isinstance(pair, list) or len(pair) != 2:
            raise ModelError(where, "between", pair, "a list of two ends: body names, \"ground\" or {x = .., dof = ..}")
        ratios = t.get("ratios", [1.0, 1.0])
        if not isinstance(ratios, list) or len(ratios) != 2:
            raise ModelError(where, "ratios", ratios, "a list [r_a, r_b] of two numbers")
        ra, rb = (number(r, "ratios", where) for r in ratios)
        out = []
        for end, r in zip(pair, (-ra, rb)):
            if end == "ground":
                continue
            if isinstance(end, str):
                out.append((NodeRef(body=end), r))
            elif isinstance(end, dict):
                check_keys(end, {"x", "dof"}, f"{where} between")
                out.append((_ref(end, f"{where} between"), r))
            else:
                raise ModelError(where, "between", end, "a body name, \"ground\" or {x = .., dof = ..}")
        if not out:
            raise ModelError(where, "between", pair, "at least one end that is not the ground")
        return out
    ratio = number(t.get("ratio", 1.0), "ratio", where)
    return [(_ref(t, where), ratio)]


def _negated(terms: list) -> list:
    """The terms of -s."""
    return [(ref, -ratio) for ref, ratio in terms]


COORD = {"x", "dof", "body", "between", "ratios", "ratio"}


def parse_hybrid(doc: dict) -> tuple[HybridModel, dict]:
    """Parse a hybrid model dict into (:class:`HybridModel`, simulation settings)."""
    check_keys(doc, ALLOWED, "model file (hybrid)")
    for key in ("body", "spring", "driver", "force") + ELEMENT_TABLES:
        if key in doc and not isinstance(doc[key], list):
            raise ModelError("model file", key, doc[key], f"an array of tables [[{key}]]")
    fe_doc = {k: doc[k] for k in FE_TABLES | {"title"} if k in doc}
    seen = {}
    for i, t in enumerate(doc.get("support", []) if isinstance(doc.get("support"), list) else [], 1):
        x = t.get("x") if isinstance(t, dict) else None
        if isinstance(x, (int, float)) and x in seen:
            raise ModelError(f"[[support]] #{i}", "x", x, f"a position without another support (contradictory "
                             f"supports: [[support]] #{seen[x]} is already at x = {x})")
        seen[x] = i
    fe = assemble(parse_shaft(fe_doc))
    consts = doc.get("constants", {})
    check_keys(consts, {"g"}, "[constants]")
    grav = number(consts.get("g", 9.81), "g", "[constants]", positive=True)
    model = HybridModel(fe=fe, title=doc.get("title", ""))
    for i, t in enumerate(doc.get("body", []), 1):
        w = f"[[body]] #{i}"
        check_keys(t, {"name", "inertia", "x0", "v0"}, w)
        name = require(t, "name", w, "the body name")
        if not isinstance(name, str) or not name or name == "ground":
            raise ModelError(w, "name", name, "a non-empty string other than \"ground\"")
        model.bodies.append(Body(name=name, inertia=number(require(t, "inertia", w, "mass or moment of inertia"),
                                                           "inertia", w, positive=True),
                                 x0=number(t.get("x0", 0.0), "x0", w), v0=number(t.get("v0", 0.0), "v0", w)))
    for i, t in enumerate(doc.get("spring", []), 1):
        w = f"[[spring]] #{i}"
        check_keys(t, {"between", "ratios", "k", "c"}, w)
        terms = _terms({k: t[k] for k in ("between", "ratios") if k in t} or {"between": None}, w)
        k = number(t.get("k", 0.0), "k", w, nonnegative=True)
        cc = number(t.get("c", 0.0), "c", w, nonnegative=True)
        if k == 0 and cc == 0:
            raise ModelError(w, "k", 0.0, "a stiffness k > 0 and/or a damping c > 0")
        a = terms[0][0] if len(terms) == 2 else None
        b = terms[-1][0]
        # ratios are folded into the references by scaling: keep only unit ratios for springs
        if any(abs(abs(r) - 1.0) > 0 for _, r in terms):
            raise ModelError(w, "ratios", t.get("ratios"), "[1, 1] for springs (use a [[gear]]-free model)")
        model.springs.append(Spring(a=a, b=b, k=k, c=cc))
    for i, t in enumerate(doc.get("driver", []), 1):
        w = f"[[driver]] #{i}"
        check_keys(t, {"x", "dof", "name", "offset", "velocity", "amplitude", "omega", "phase"}, w)
        if "body" in t:
            raise ModelError(w, "body", t["body"], "an FE node x = .. (drivers prescribe FE DOFs)")
        amp = number(t.get("amplitude", 0.0), "amplitude", w)
        om = number(t.get("omega", 0.0), "omega", w, nonnegative=True)
        if amp and not om:
            raise ModelError(w, "omega", om, "a number > 0 with amplitude")
        model.drivers.append(DriverSpec(ref=_ref(t, w), law=MotionLaw(
            offset=number(t.get("offset", 0.0), "offset", w), velocity=number(t.get("velocity", 0.0), "velocity", w),
            amplitude=amp, omega=om, phase=number(t.get("phase", 0.0), "phase", w))))
    names: set[str] = set()
    model.elements += [ElementSpec(cls, kw, terms) for cls, kw, terms in element_tables(
        doc, names, _terms, _negated, COORD, one_sided_side="compression", single_bound_gap=True)]
    for i, t in enumerate(doc.get("force", []), 1):
        w = f"[[force]] #{i}"
        check_keys(t, {"x", "dof", "body", "value", "amplitude", "omega", "phase"}, w)
        amp = number(t.get("amplitude", 0.0), "amplitude", w)
        om = number(t.get("omega", 0.0), "omega", w, nonnegative=True)
        if amp and not om:
            raise ModelError(w, "omega", om, "a number > 0 with amplitude")
        model.forces.append(ForceSpec(ref=_ref(t, w), value=number(t.get("value", 0.0), "value", w), amplitude=amp,
                                      omega=om, phase=number(t.get("phase", 0.0), "phase", w)))
    for i, t in enumerate(doc.get("distributed_friction", []), 1):
        w = f"[[distributed_friction]] #{i}"
        check_keys(t, {"name", "dof", "from", "to", "intensity", "static_intensity", "mu", "radius"}, w)
        name = unique_name(t, w, f"distributed{i}", names)
        if ("intensity" in t) == ("mu" in t):
            raise ModelError(w, "intensity", t.get("intensity"),
                             "either intensity = .. (force or torque per length, e.g. f P / l of seed 003) "
                             "or mu = .. (friction coefficient on the model's own weight per length)")
        specs = distributed_friction(
            fe, name=name, dof=t.get("dof"),
            x_from=number(t.get("from", 0.0), "from", w), x_to=number(t.get("to", fe.model.length), "to", w),
            intensity=number(t["intensity"], "intensity", w, nonnegative=True) if "intensity" in t else None,
            static_intensity=number(t["static_intensity"], "static_intensity", w, nonnegative=True)
            if "static_intensity" in t else None,
            mu=number(t["mu"], "mu", w, nonnegative=True) if "mu" in t else None,
            radius=number(t["radius"], "radius", w, positive=True) if "radius" in t else None, g=grav, where=w)
        for s in specs:
            names.add(s.kwargs["name"])
        model.elements += specs
    red = doc.get("reduction")
    if red is not None:
        w = "[reduction]"
        check_keys(red, {"modes", "static_correction", "threshold"}, w)
        modes = require(red, "modes", w, "the number of retained modes")
        if isinstance(modes, bool) or not isinstance(modes, int) or modes < 1:
            raise ModelError(w, "modes", modes, "an integer >= 1")
        sc = red.get("static_correction", True)
        if not isinstance(sc, bool):
            raise ModelError(w, "static_correction", sc, "true | false")
        thr = number(red.get("threshold", 0.95), "threshold", w)
        if not 0 < thr <= 1:
            raise ModelError(w, "threshold", thr, "a share in (0, 1]")
        model.reduction = ReductionSpec(modes=modes, static_correction=sc, threshold=thr)
    dmp = doc.get("damping")
    if dmp is not None:
        w = "[damping]"
        check_keys(dmp, {"alpha", "beta"}, w, hints={k: "modal/forced damping keys; the time simulation takes "
                                                      "Rayleigh alpha (mass) and beta (stiffness) proportional damping"
                                                      for k in ("type", "zeta", "psi")})
        model.rayleigh = (number(dmp.get("alpha", 0.0), "alpha", w, nonnegative=True),
                          number(dmp.get("beta", 0.0), "beta", w, nonnegative=True))
    ini = doc.get("initial", {})
    check_keys(ini, {"velocity", "state"}, "[initial]")
    model.initial_velocity = number(ini.get("velocity", 0.0), "velocity", "[initial]")
    state = choice(ini.get("state", "rest"), "state", "[initial]", ("rest", "linear_steady_state"))
    model.initial_harmonic = state == "linear_steady_state"
    pos, count = dict(positive=True), dict(positive=True, integer=True)
    st = simulation_table(doc, SIM_KEYS, METHODS, {
        "dt": pos, "theta": {}, "max_events": count, "max_step": pos, "steps_per_period": count, "rest_tol": pos,
        "samples": count, "tol": pos, "max_iter": count})
    if st["method"] == "moreau" and "dt" not in st:
        raise ModelError("[simulation]", "dt", None, "a time step dt = .. for method = \"moreau\"")
    if st["method"] == "event":
        for k in ("dt", "theta", "tol", "max_iter"):
            if k in st:
                raise ModelError("[simulation]", k, st[k], "only with method = \"moreau\"")
    if not model.elements and not model.forces and not model.drivers and not model.initial_velocity:
        raise ModelError("model file", "friction", None,
                         "at least one nonsmooth element, [[force]], [[driver]] or [initial] velocity for a simulation")
    return model, st
