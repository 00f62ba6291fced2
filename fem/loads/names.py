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


# ------------------------------------------------------------------ FE shafts and rotors
SHAFT = "shaft"
"""The ``where`` of the section loads of the FE shaft of an FE, hybrid or rotor file."""


def section_name(quantity: str, x: float, side: str | None = None, where: str = SHAFT) -> str:
    """``shaft.<quantity>@x=<x>``; a station reported on both sides of a jump (or asked for one side)
    carries ``-`` (just left of x) or ``+`` (just right), e.g. ``shaft.shear_force@x=0.6-``."""
    mark = {"left": "-", "right": "+"}.get(side, "")
    return f"{where}.{quantity}@x={x:g}{mark}"


def support_name(index: int, t, field: str | None = None) -> str:
    """An FE ``[[support]]`` (#index): its ``name``, else ``support[<index>] x=<x>``; ``field``: the DOF, for
    a support that holds several (``support[1] x=0 w_x``)."""
    base = getattr(t, "name", None) or f"support[{index}] x={t.x:g}"
    return base + (f" {field}" if field else "")


def bearing_names(rotor) -> list[str]:
    """The names of a rotor's bearings in its order: ``name``, else ``<table>[<number>] x=<x>`` numbered
    per model-file table (``bearing[1] x=0``, ``journal_bearing[2] x=1.2``), as its error messages do."""
    numbers: dict = {}
    out = []
    for b in rotor.bearings:
        table = getattr(b, "kind", "bearing")
        numbers[table] = numbers.get(table, 0) + 1
        out.append(b.name or f"{table}[{numbers[table]}] x={b.x:g}")
    return out
