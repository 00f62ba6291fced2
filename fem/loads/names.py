"""The names of the things of a model file in every output (docs/outputs.md, "Names"): the ``name`` key
where the table has one; otherwise

* springs, dampers, gears, forces: ``<table>[<index>] <a>-<b>`` (the ends of ``between``; a body for a
  force), e.g. ``spring[2] motor-pinion``, ``gear[1] gear1-gear2``, ``force[1] disk``;
* nonsmooth elements: ``<table><index>`` (e.g. ``gap1``: the names their events always had);
* hybrid FE nodes: ``x=<x>`` (with the DOF when not the primary field, ``x=0.5 w_x``); supports and
  drivers of hybrid files: ``support[<index>] x=<x>``, ``driver[<index>] x=<x>``.

The index is the table's 1-based position in the file (the ``#i`` of error messages), so a name does
not change when other tables are added after it."""
from __future__ import annotations


def end_name(end) -> str:
    """A ``between`` end: a body/driver name, "ground", or an FE node { x, dof }."""
    if isinstance(end, str):
        return end
    return f"x={end.x:g}" + (f" {end.dof}" if getattr(end, "dof", None) else "")


def link_name(table: str, index: int, t) -> str:
    if getattr(t, "name", None):
        return t.name
    return f"{table}[{index}] " + "-".join(end_name(e) for e in t.between)


def force_name(index: int, t) -> str:
    if t.name:
        return t.name
    if t.body is not None:
        return f"force[{index}] {t.body}"
    if t.x is not None:
        return f"force[{index}] x={t.x:g}" + (f" {t.dof}" if t.dof else "")
    return f"force[{index}] " + "-".join(end_name(e) for e in t.between)


def node_name(kind: str, index: int, x: float, dof: str | None = None) -> str:
    return f"{kind}[{index}] x={x:g}" + (f" {dof}" if dof else "")
