"""Lumped (discrete) drive models and the solvers that integrate them.

Depends on numpy and scipy only.  The common currency between ``fem`` and
``discrete`` is :class:`discrete.linear_system.LinearSystem`.  It is imported on first use
(``discrete.LinearSystem``, ``from discrete import LinearSystem``), so that importing a light
module such as :mod:`discrete.errors` does not load scipy.
"""
from .errors import ModelError

__all__ = ["ModelError", "LinearSystem"]


def __getattr__(name):
    if name == "LinearSystem":
        from .linear_system import LinearSystem
        return LinearSystem
    raise AttributeError(f"module 'discrete' has no attribute {name!r}")
