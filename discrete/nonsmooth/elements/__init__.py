"""The nonlinear elements, one module each (see :mod:`.base` for the protocol every element follows).

Every module of this package is imported here; its :class:`~.base.Element` subclasses are the
element types the solvers accept (``ELEMENT_TYPES``).  Adding an element is adding a module."""
import importlib
import inspect
import pkgutil

from .base import Element


def _discover() -> dict:
    types = {}
    for mod in pkgutil.iter_modules(__path__):
        module = importlib.import_module(f"{__name__}.{mod.name}")
        for obj in vars(module).values():
            if inspect.isclass(obj) and issubclass(obj, Element) and obj is not Element:
                types[obj.__name__] = obj
    return types


ELEMENT_TYPES = _discover()
"""{class name: element class} of every element module."""
globals().update(ELEMENT_TYPES)

__all__ = ["Element", "ELEMENT_TYPES", *ELEMENT_TYPES]
