"""The element tables of lumped and hybrid files, in the order the solvers list the elements (the
registry of :mod:`fem.modelfile.schema.elements`); each table builds its element itself
(``element()``), the caller resolves the coordinate (body names or FE nodes)."""
from __future__ import annotations

from discrete.errors import ModelError

from ..schema.elements import ELEMENT_TABLES


def element_tables(doc):
    """(table name, 1-based index, table, element name) of every element of the file."""
    used: set[str] = set()
    for table in ELEMENT_TABLES:
        for i, t in enumerate(getattr(doc, table), 1):
            where = f"[[{table}]] #{i}"
            name = t.name or f"{table}{i}"
            if name in used:
                raise ModelError(where, "name", name, "a name not used by another element")
            used.add(name)
            yield table, i, t, name
