"""Lumped (discrete) drive models and the solvers that integrate them.

Depends on numpy and scipy only.  The common currency between ``fem`` and
``discrete`` is :class:`discrete.linear_system.LinearSystem`.
"""
from .errors import ModelError
from .linear_system import LinearSystem

__all__ = ["ModelError", "LinearSystem"]
