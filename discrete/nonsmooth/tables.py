"""The element tables ``[[friction]]``, ``[[one_sided]]``, ``[[gap]]`` and ``[[impact]]``, shared by the
lumped (:mod:`discrete.nonsmooth.model`) and hybrid (:mod:`fem.hybrid.modelfile`) model files.

The two files differ in how an element's coordinate s is given (body names or FE nodes), which
:func:`element_tables` takes as functions, and in a few defaults, which are its keyword arguments.
Each table function validates the element parameters and returns (element class, keyword arguments)
without the name and the coordinate.
"""
from __future__ import annotations

from collections.abc import Callable, Iterator

from ..errors import ModelError
from ..schema import check_keys, choice, number, require
from .elements import Friction, Gap, Impact, OneSided

KEYS = {"friction": {"name", "kinetic", "static", "viscous", "quadratic", "cubic", "surface_velocity", "restick"},
        "one_sided": {"name", "k", "preload", "side"},
        "gap": {"name", "k", "delta", "lower", "upper", "law", "L"},
        "impact": {"name", "stop", "side", "restitution", "v_rest"}}
SIDES = {"tension": 1, "compression": -1}


def simulation_table(doc: dict, keys: set, methods: tuple, numeric: dict) -> dict:
    """The required ``[simulation]`` table: t_end, method (first of ``methods`` by default), the
    optional ``numeric`` settings (name -> keyword arguments of :func:`number`) and energy."""
    sim = doc.get("simulation")
    if not isinstance(sim, dict):
        raise ModelError("model file", "simulation", sim, "a table [simulation] with t_end = .. (required)")
    check_keys(sim, keys, "[simulation]")
    settings = {"t_end": number(require(sim, "t_end", "[simulation]", "the end time in s"), "t_end", "[simulation]",
                                positive=True),
                "method": choice(sim.get("method", methods[0]), "method", "[simulation]", methods)}
    for k, kw in numeric.items():
        if k in sim:
            settings[k] = number(sim[k], k, "[simulation]", **kw)
    if "energy" in sim:
        if not isinstance(sim["energy"], bool):
            raise ModelError("[simulation]", "energy", sim["energy"], "true | false")
        settings["energy"] = sim["energy"]
    return settings


def unique_name(t: dict, where: str, default: str, used: set) -> str:
    """The element name (``default`` if not given), a non-empty string not in ``used``; adds it to ``used``."""
    name = t.get("name", default)
    if not isinstance(name, str) or not name:
        raise ModelError(where, "name", name, "a non-empty string")
    if name in used:
        raise ModelError(where, "name", name, "a name not used by another element")
    used.add(name)
    return name


def _stiffness(t: dict, where: str, what: str) -> float:
    return number(require(t, "k", where, what), "k", where, positive=True)


def friction(t: dict, where: str, levels: dict | None = None) -> tuple[type, dict]:
    """``[[friction]]``; ``levels`` (kinetic, static, ...) replaces the table's kinetic/static when given."""
    if levels is None:
        kinetic = number(require(t, "kinetic", where, "the kinetic friction level (force or torque)"), "kinetic",
                         where, nonnegative=True)
        static = number(t.get("static", kinetic), "static", where)
        if static < kinetic:
            raise ModelError(where, "static", static, f"a number >= the kinetic level {kinetic!r}")
        levels = dict(kinetic=kinetic, static=static)
    return Friction, dict(levels, viscous=number(t.get("viscous", 0.0), "viscous", where),
                          quadratic=number(t.get("quadratic", 0.0), "quadratic", where),
                          cubic=number(t.get("cubic", 0.0), "cubic", where),
                          surface_velocity=number(t.get("surface_velocity", 0.0), "surface_velocity", where),
                          restick=choice(t.get("restick", "static"), "restick", where, ("static", "kinetic")))


def one_sided(t: dict, where: str, default_side: str) -> tuple[type, dict]:
    """``[[one_sided]]``; ``default_side`` ("tension" | "compression") when the table gives no side."""
    k = _stiffness(t, where, "the stiffness")
    side = SIDES[choice(t.get("side", default_side), "side", where, SIDES)]
    preload = number(t.get("preload", 0.0), "preload", where)
    return OneSided, dict(k=k, s_open=-side * preload / k, side=side)


def _clearance(t: dict, where: str, single_bound: bool) -> tuple[float, float]:
    """(lower, upper) from delta or lower and upper."""
    if "delta" in t:
        if "lower" in t or "upper" in t:
            raise ModelError(where, "delta", t["delta"], "either delta (symmetric) or lower/upper")
        d = number(t["delta"], "delta", where, nonnegative=True)
        return -d, d
    if single_bound and "lower" not in t and "upper" not in t:
        raise ModelError(where, "delta", None, "delta = .. or lower = .. / upper = .. (the clearance)")
    lower = number(require(t, "lower", where, "the lower clearance bound (or delta)"), "lower", where)
    upper = number(require(t, "upper", where, "the upper clearance bound (or delta)"), "upper", where)
    if lower > upper:
        raise ModelError(where, "lower", lower, f"a number <= upper = {upper!r}")
    return lower, upper


def _stop(t: dict, where: str, k: float) -> dict:
    """A single lower or upper bound: the one-sided spring k engaged beyond it (exact potential)."""
    if "law" in t or "L" in t:
        raise ModelError(where, "law", t.get("law", t.get("L")), "lower and upper (or delta) for law/L")
    side, key = (1, "upper") if "upper" in t else (-1, "lower")
    return dict(k=k, s_open=number(t[key], key, where), side=side)


def gap(t: dict, where: str, single_bound: bool) -> tuple[type, dict]:
    """``[[gap]]``; with ``single_bound`` a lone lower or upper gives a :class:`OneSided` stop."""
    k = _stiffness(t, where, "the contact stiffness")
    if single_bound and "delta" not in t and ("lower" in t) != ("upper" in t):
        return OneSided, _stop(t, where, k)
    lower, upper = _clearance(t, where, single_bound)
    return Gap, dict(k=k, lower=lower, upper=upper, law=choice(t.get("law", "exact"), "law", where, ("exact", "arctan")),
                     L=number(t.get("L", 1e3), "L", where, positive=True))


def impact(t: dict, where: str) -> tuple[type, dict, bool]:
    """``[[impact]]``; also whether the caller negates the coordinate (side = "upper": s <= stop <=> -s >= -stop)."""
    e = number(require(t, "restitution", where, "the restitution coefficient"), "restitution", where)
    if not 0 <= e <= 1:
        raise ModelError(where, "restitution", e, "a number in [0, 1]")
    stop = number(t.get("stop", 0.0), "stop", where)
    upper = choice(t.get("side", "lower"), "side", where, ("lower", "upper")) == "upper"
    v_rest = number(t["v_rest"], "v_rest", where, positive=True) if "v_rest" in t else None
    return Impact, dict(s_min=-stop if upper else stop, restitution=e, v_rest=v_rest), upper


def element_tables(doc: dict, used: set, coordinate: Callable, negate: Callable, coord_keys: set, *,
                   one_sided_side: str, single_bound_gap: bool, friction_levels: Callable | None = None,
                   friction_keys: set = frozenset()) -> Iterator[tuple[type, dict, object]]:
    """Yield (class, keyword arguments with the name, coordinate) of each element table, in file order.

    ``coordinate(t, where)`` resolves the coordinate from the keys ``coord_keys``, ``negate`` flips it;
    ``friction_levels(t, where)`` gives the levels of :func:`friction` from ``friction_keys`` (or None).
    """
    for kind in KEYS:
        for i, t in enumerate(doc.get(kind, []), 1):
            where = f"[[{kind}]] #{i}"
            check_keys(t, coord_keys | KEYS[kind] | (friction_keys if kind == "friction" else set()), where)
            s = coordinate(t, where)
            name = unique_name(t, where, f"{kind}{i}", used)
            if kind == "friction":
                cls, kw = friction(t, where, friction_levels(t, where) if friction_levels else None)
            elif kind == "one_sided":
                cls, kw = one_sided(t, where, one_sided_side)
            elif kind == "gap":
                cls, kw = gap(t, where, single_bound_gap)
            else:
                cls, kw, flip = impact(t, where)
                s = negate(s) if flip else s
            yield cls, dict(name=name, **kw), s
