"""Lumped (discrete) drive models and the solvers that integrate them.

Depends on numpy and scipy only.  The common currency between ``fem`` and
``discrete`` is :class:`discrete.linear_system.LinearSystem`.  It is imported on first use
(``discrete.LinearSystem``, ``from discrete import LinearSystem``), so that importing a light
module such as :mod:`discrete.errors` does not load scipy.
"""
from .errors import ModelError

__all__ = ["ModelError", "LinearSystem"]


def __getattr__(name):
    import importlib

    if name == "LinearSystem":
        from .linear_system import LinearSystem
        globals()[name] = LinearSystem
        return LinearSystem
    if name.startswith("__"):
        raise AttributeError(f"module 'discrete' has no attribute {name!r}")
    try:                                           # a submodule, as ``import discrete`` used to provide some
        return importlib.import_module(f"{__name__}.{name}")
    except ModuleNotFoundError as exc:
        if exc.name != f"{__name__}.{name}":
            raise
        raise AttributeError(f"module 'discrete' has no attribute {name!r}") from None


def __dir__():
    return sorted(set(globals()) | {"LinearSystem"})
