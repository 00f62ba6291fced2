"""Griffe extension: the docstrings' Sphinx roles (``:class:`~a.b.C```, ``:func:`f```) shown as
code in the Markdown API reference (mkdocstrings renders docstrings as Markdown)."""
from __future__ import annotations

import re

import griffe

ROLE = re.compile(r":(?:py:)?(?:class|func|mod|meth|attr|data|obj|exc):`(?P<tilde>~?)(?P<target>[^`]+)`")


def _code(match: re.Match) -> str:
    target = match["target"]
    if match["tilde"]:
        target = target.rsplit(".", 1)[-1]
    return f"`{target}`"


class SphinxRoles(griffe.Extension):
    def _fix(self, obj) -> None:
        if obj.docstring is not None:
            obj.docstring.value = ROLE.sub(_code, obj.docstring.value)

    def on_instance(self, *, obj, **kwargs) -> None:
        self._fix(obj)
