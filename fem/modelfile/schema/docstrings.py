"""The field descriptions of the schema's tables (the string under each field), attached on demand.

Pydantic's ``use_attribute_docstrings`` finds each class's source through the interpreter's frames and
parses it once per class when the class is created: ~0.18 s of every command's start-up for the ~80
tables, though only an error message, the JSON Schema and the reference page read the descriptions.
:func:`attach` does the same extraction (same rule: an annotated field followed by a string; inherited
fields keep the description of the class that declares them) by parsing each schema module once, and
rebuilds the tables' validators so that the JSON Schema carries them -- at the first use."""

import ast
import inspect
import sys
from typing import get_args

from pydantic import BaseModel

_attached = False


def _module_docstrings(module) -> dict[str, dict[str, str]]:
    """{class name: {field: docstring}} of every class defined in a module's source."""
    tree = ast.parse(inspect.getsource(module))
    out: dict[str, dict[str, str]] = {}
    for node in ast.walk(tree):
        if not isinstance(node, ast.ClassDef):
            continue
        docs, target = {}, None
        for stmt in node.body:
            if isinstance(stmt, ast.AnnAssign) and isinstance(stmt.target, ast.Name):
                target = stmt.target.id
                continue
            if (target and isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Constant)
                    and isinstance(stmt.value.value, str)):
                docs[target] = inspect.cleandoc(stmt.value.value)
            target = None
        out.setdefault(node.name, docs)
    return out


def _models(root: type) -> list[type]:
    """Every subclass of ``root`` (recursively)."""
    seen, todo = [], [root]
    while todo:
        cls = todo.pop()
        for sub in cls.__subclasses__():
            if sub not in seen:
                seen.append(sub)
                todo.append(sub)
    return seen


def _nested(ann) -> list[type]:
    """The model classes an annotation refers to (lists, unions, Annotated)."""
    if isinstance(ann, type) and issubclass(ann, BaseModel):
        return [ann]
    return [m for a in get_args(ann) for m in _nested(a)]


def attach() -> None:
    """Set every table field's description from its docstring (once) and rebuild the validators."""
    global _attached
    if _attached:
        return
    from . import base, document  # noqa: F401  (every table defined)

    models = [base.Table] + _models(base.Table) + [m for m in _models(BaseModel)
                                                   if m.__module__.startswith(__package__) and m not in _models(base.Table)]
    per_module: dict[str, dict] = {}
    for cls in models:
        mod = sys.modules.get(cls.__module__)
        if mod is None or not mod.__name__.startswith(__package__):
            continue
        if mod.__name__ not in per_module:
            per_module[mod.__name__] = _module_docstrings(mod)
    for cls in models:
        for name, field in cls.model_fields.items():
            if field.description is not None:
                continue
            owner = next((k for k in cls.__mro__ if name in k.__dict__.get("__annotations__", {})), None)
            if owner is None:
                continue
            doc = per_module.get(owner.__module__, {}).get(owner.__name__, {}).get(name)
            if doc is not None:
                field.description = doc
    done: set = set()

    def rebuild(cls):
        if cls in done:
            return
        done.add(cls)
        for field in cls.model_fields.values():
            for sub in _nested(field.annotation):
                rebuild(sub)
        cls.model_rebuild(force=True)

    for cls in models:
        if issubclass(cls, BaseModel) and cls.__module__.startswith(__package__):
            rebuild(cls)
    _attached = True
