"""The outputs of a lumped or hybrid file: its ``[[output]]`` tables resolved against the drive's load map
(:func:`outputs_map`), or, without any, the defaults -- every link's and element's deflection and force
(a friction's force and slip velocity, a motor's torque and speed), every gear pair's force, every
driver's and support's reaction, every applied load (docs/outputs.md)."""
from __future__ import annotations

import numpy as np

from discrete.errors import ModelError
from discrete.loads import Channel, LoadMap, unit_of

from .names import end_name

_FORCE_WORDS = ("force", "torque", "moment")
SECTION_WORDS = ("torque", "moment", "force", "shear")      # at x: the section loads of fem.loads.shaft


def outputs_map(tables, loads, order: dict | None = None) -> LoadMap:
    """The channels of the file's ``[[output]]`` tables (``tables`` empty: the default channels);
    ``order`` gets {channel name: table index}.  Tables asking for a section load of a hybrid file's FE
    shaft (x with torque | moment | force | shear) are :mod:`fem.loads.shaft`'s."""
    if not tables:
        return loads.map
    out = LoadMap.empty(loads.coords.n, loads.map.Fe.shape[1], loads.map.Fa.shape[1])
    for i, t in enumerate(tables, 1):
        if getattr(t, "x", None) is not None and t.quantity in SECTION_WORDS:
            continue
        for channel, rows in _resolve(t, i, loads):
            out.add(channel, **rows)
            if order is not None:
                order[channel.name] = i
    return out


def _motion_rows(quantity: str, X) -> dict:
    """Rows of a displacement / deflection (X) turned into the asked motion quantity."""
    if quantity in ("displacement", "deflection", "twist"):
        return {"X": X}
    if quantity in ("velocity", "slip_velocity"):
        return {"V": X}
    return {"A": X}


def _channel_like(base: Channel, name: str, quantity: str, where_key: str, where) -> Channel:
    """An [[output]] of a default channel under the user's name and quantity word: torque, moment and
    twist say the coordinate is an angle (N m, rad); force, reaction and the motions keep the channel's
    unit (or the generic one)."""
    if quantity in ("torque", "moment", "twist"):
        unit = unit_of(quantity, "rotation")
    elif quantity in ("force", "reaction", base.quantity):
        unit = base.unit
    else:
        unit = unit_of(quantity, None)
    return Channel(name, quantity, unit, base.source, base.where, acts_on=dict(base.acts_on),
                   info={**base.info, "output": {where_key: where}})


def _resolve(t, i: int, loads):
    where_key = next(k for k in ("element", "body", "between", "support", "x") if getattr(t, k) is not None)
    q = t.quantity
    lm = loads.map
    table = f"[[output]] #{i}"
    if where_key == "element":
        el = t.element
        have = [c for c in lm.channels if c.where == el and c.source not in ("driver", "support", "force", "damping")]
        if not have:
            known = sorted({c.where for c in lm.channels if c.source not in ("driver", "support", "force", "damping")})
            raise ModelError(table, "element", el, "one of " + ", ".join(map(repr, known)))
        base_q = "force" if q in _FORCE_WORDS else ("slip_velocity" if q == "slip_velocity" else "deflection")
        base = next((c for c in have if c.quantity == base_q), None)
        if base is None:
            raise ModelError(table, "quantity", q, "one of " + ", ".join(sorted({c.quantity for c in have}))
                             + f" for {el!r}")
        name = t.name or f"{el}.{q}"
        rows = lm.rows(base.name)
        if base_q == "deflection" and q in ("velocity", "acceleration"):
            rows = _motion_rows(q, rows["X"])
        yield _channel_like(base, name, q, "element", el), rows
        return
    if where_key in ("support",) or (where_key == "body" and q == "reaction") or (where_key == "x" and q == "reaction"):
        who = t.support if where_key == "support" else (t.body if where_key == "body" else _node_reaction(t, loads))
        base = next((c for c in lm.channels if c.quantity == "reaction" and c.where == who), None)
        if base is None:
            known = [c.where for c in lm.channels if c.quantity == "reaction"]
            raise ModelError(table, where_key, who if where_key != "x" else t.x,
                             "a driver or support: one of " + ", ".join(map(repr, known)) if known else
                             "a driver or support (this model has none)")
        name = t.name or f"{who}.{q}"
        yield _channel_like(base, name, q, where_key, who), lm.rows(base.name)
        return
    T = loads.coords.T
    if where_key == "body":
        g = loads.named_vector(t.body)
        where = t.body
    elif where_key == "between":
        ra, rb = t.ratios if t.ratios is not None else (1.0, 1.0)
        a, b = t.between
        g = rb * loads.named_vector(b) - ra * loads.named_vector(a)
        where = "-".join(end_name(e) for e in t.between)
    else:                                   # x: an FE node, one output per component
        comps = t.components or [t.dof]
        for comp in comps:
            from ..modelfile.schema.lumped import NodeEnd

            end = NodeEnd(x=t.x, dof=comp)
            g = loads.named_vector(end)
            where = end_name(end)
            name = (t.name + (f".{comp}" if t.components else "")) if t.name else f"{where}.{q}"
            motion = loads.motion_of_ends([end]) or loads.coords.motion_of(g)
            yield Channel(name, q, unit_of(q, motion), "node", where, info={"output": {"x": t.x, "dof": comp}}), \
                _motion_rows(q, g @ T)
        return
    if not np.any(g):
        raise ModelError(table, where_key, t.body if where_key == "body" else t.between,
                         "a place that moves (not the ground alone)")
    ends = [t.body] if where_key == "body" else list(t.between)
    motion = loads.motion_of_ends(ends) or loads.coords.motion_of(g)
    q_unit = "rotation" if q == "twist" else motion
    name = t.name or f"{where}.{q}"
    yield Channel(name, q, unit_of(q, q_unit), where_key, where, info={"output": {where_key: where}}), \
        _motion_rows(q, g @ T)


def _node_reaction(t, loads) -> str:
    """The held coordinate (support or driver) at the FE node of ``t`` (hybrid files)."""
    from ..modelfile.schema.lumped import NodeEnd

    g = loads.named_vector(NodeEnd(x=t.x, dof=t.dof))
    for name, _, h in loads.coords.held:
        if g[h] != 0:
            return name
    return f"x={t.x:g}"
