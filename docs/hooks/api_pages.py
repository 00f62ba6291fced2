"""MkDocs hook: the API reference pages list what the packages really export.

A page of ``docs/api/`` holds a marker ``<!-- api: PACKAGE -->``; at build time the marker is
replaced by one mkdocstrings directive (``::: module.name``) per name of ``PACKAGE.__all__``,
each resolved by importing the package, so that lazy re-exports (``fem``, ``discrete``,
``fem.rotor``'s bearings: PEP 562 ``__getattr__``, invisible to static analysis) are documented
where they are defined.  A name of ``__all__`` that does not import is a build error, never a
silently missing entry.  The home page includes README.md (``<!-- include: README.md -->``),
its links to ``docs/...`` made relative to the docs folder, so the landing page is written once.
"""
from __future__ import annotations

import importlib
import inspect
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
API_MARKER = re.compile(r"^<!-- api: (?P<package>[\w.]+) -->$", re.M)
INCLUDE_MARKER = re.compile(r"^<!-- include: (?P<path>[\w./-]+) -->$", re.M)


def directive(package: str, name: str) -> str:
    """The mkdocstrings identifier of ``package.name``: where the object is defined when it is a
    class or function (lazy re-exports), else the package attribute itself (griffe follows the
    explicit import)."""
    mod = importlib.import_module(package)
    try:
        obj = getattr(mod, name)
    except AttributeError:     # a submodule named in __all__ (imported by ``from package import *``)
        obj = importlib.import_module(f"{package}.{name}")
    if inspect.ismodule(obj):
        return obj.__name__
    module, qualname = getattr(obj, "__module__", None), getattr(obj, "__qualname__", None)
    if (inspect.isclass(obj) or inspect.isfunction(obj)) and module and qualname and "<" not in qualname:
        return f"{module}.{qualname}"
    return f"{package}.{name}"


def exports(package: str) -> list[tuple[str, str]]:
    """``(name, identifier)`` for every name of ``package.__all__``."""
    names = getattr(importlib.import_module(package), "__all__", None)
    if not names:
        raise ValueError(f"docs: <!-- api: {package} -->: the package has no __all__")
    return [(name, directive(package, name)) for name in names]


def home_pages(packages: list[str]) -> dict[str, str]:
    """identifier -> the package whose page documents it: an object exported by several packages
    (``fem.ModalResult`` is ``discrete.linear``'s) is documented once, on the page of the exporting
    package that is the longest prefix of its identifier (the first page otherwise); the other
    pages link to it."""
    exporters: dict[str, list[str]] = {}
    for package in packages:
        for _, ident in exports(package):
            exporters.setdefault(ident, []).append(package)
    home = {}
    for ident, pkgs in exporters.items():
        prefixes = [p for p in pkgs if ident.startswith(p + ".")]
        home[ident] = max(prefixes, key=len) if prefixes else pkgs[0]
    return home


HOME: dict[str, str] = {}


def api_section(package: str) -> str:
    documented, linked = [], []
    for name, ident in exports(package):
        if HOME.get(ident, package) == package:
            documented.append(f"::: {ident}\n"
                              "    options:\n"
                              "      heading_level: 3\n"
                              "      show_root_full_path: false\n")
        else:
            linked.append(f"| `{name}` | [`{ident}`][{ident}] | `{HOME[ident]}` |")
    text = "\n".join(documented)
    if linked:
        text = ("Re-exported here and documented with the package that defines them:\n\n"
                "| name | object | documented with |\n| --- | --- | --- |\n" + "\n".join(linked)
                + "\n\n" + text)
    return text


def readme_for_docs(path: Path) -> str:
    """README.md as a page of the docs folder: ``docs/x`` links become ``x``."""
    text = path.read_text(encoding="utf-8")
    return re.sub(r"\]\(docs/", "](", text)


def on_config(config, **kwargs):
    if str(ROOT) not in sys.path:
        sys.path.insert(0, str(ROOT))
    return config


def on_files(files, config, **kwargs):
    packages = []
    for file in files.documentation_pages():
        if file.src_uri.startswith("api/"):
            packages += API_MARKER.findall(Path(file.abs_src_path).read_text(encoding="utf-8"))
    HOME.clear()
    HOME.update(home_pages(packages))
    return files


def on_page_markdown(markdown, page, config, files, **kwargs):
    markdown = INCLUDE_MARKER.sub(lambda m: readme_for_docs(ROOT / m["path"]), markdown)
    return API_MARKER.sub(lambda m: api_section(m["package"]), markdown)
