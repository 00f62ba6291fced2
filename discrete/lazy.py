"""Lazy package attributes (PEP 562) for ``fem`` and ``discrete``: their public names are imported
on first use and their submodules on demand, so that a light module (``discrete.errors``, the
command line's start) does not load scipy and scikit-fem."""
from __future__ import annotations

import importlib


def lazy_exports(package: str, exports: dict[str, str], namespace: dict):
    """``(__getattr__, __dir__)`` for the package ``package``: ``exports`` maps a public name to the
    module that defines it (imported, then kept in ``namespace``, the package's globals); any other
    name is tried as a submodule, as a plain ``import package`` used to provide them."""

    def __getattr__(name):
        where = exports.get(name)
        if where is None:
            if name.startswith("__"):
                raise AttributeError(f"module {package!r} has no attribute {name!r}")
            try:
                return importlib.import_module(f"{package}.{name}")
            except ModuleNotFoundError as exc:
                if exc.name != f"{package}.{name}":
                    raise
                raise AttributeError(f"module {package!r} has no attribute {name!r}") from None
        value = getattr(importlib.import_module(where), name)
        namespace[name] = value
        return value

    def __dir__():
        return sorted(set(namespace) | set(exports))

    return __getattr__, __dir__


def lazy_module(name: str):
    """The module ``name``, loaded on its first attribute access (``importlib.util.LazyLoader``): a
    module-level ``from x import y as m`` that costs start-up in code paths that never use ``m``."""
    import sys
    import importlib.util

    mod = sys.modules.get(name)
    if mod is not None:
        return mod
    spec = importlib.util.find_spec(name)
    if spec is None:
        raise ModuleNotFoundError(f"No module named {name!r}", name=name)
    loader = importlib.util.LazyLoader(spec.loader)
    spec.loader = loader
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    loader.exec_module(mod)
    return mod
