"""Lumped (discrete) drive models and the solvers that integrate them.

Depends on numpy and scipy only.  The common currency between ``fem`` and
``discrete`` is :class:`discrete.linear_system.LinearSystem`.  It is imported on first use
(``discrete.LinearSystem``, ``from discrete import LinearSystem``), so that importing a light
module such as :mod:`discrete.errors` does not load scipy.
"""
from .errors import ModelError
from .lazy import lazy_exports as _lazy_exports

__all__ = ["ModelError", "LinearSystem"]

__getattr__, __dir__ = _lazy_exports(__name__, {"LinearSystem": "discrete.linear_system"}, globals())
