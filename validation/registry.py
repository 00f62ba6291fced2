"""The validation catalogue: one registry of cases, each comparing the package with an
independent reference (closed form, root of a frequency equation, a seed's table, or a
second independent method) under a tolerance justified in the case's docstring.

A case is a function decorated with :func:`case` that returns a list of :class:`Check`.
Modules in ``validation/cases/`` are discovered automatically.
"""
from __future__ import annotations

import importlib
import pkgutil
import time
from dataclasses import asdict, dataclass, field
from typing import Callable

import numpy as np


@dataclass
class Check:
    """One compared quantity (the JSON contract's ``cases`` entries)."""

    name: str
    source: str
    quantity: str
    expected: float
    computed: float
    rel_error: float
    tolerance: float
    passed: bool
    note: str = ""

    def to_dict(self) -> dict:
        d = asdict(self)
        for k in ("expected", "computed", "rel_error", "tolerance"):
            d[k] = None if d[k] is None or not np.isfinite(d[k]) else float(d[k])
        d["passed"] = bool(self.passed)
        return d


def check(name: str, source: str, quantity: str, expected: float, computed: float, tolerance: float,
          *, scale: float | None = None, note: str = "") -> Check:
    """Compare with relative error |computed - expected| / |scale or expected|.

    ``scale`` replaces |expected| in the denominator where the expected value is zero or
    where an absolute tolerance relative to a reference magnitude is meant.
    """
    expected, computed = float(expected), float(computed)
    denom = abs(scale) if scale is not None else abs(expected)
    err = abs(computed - expected) / denom if denom > 0 else abs(computed - expected)
    return Check(name=name, source=source, quantity=quantity, expected=expected, computed=computed,
                 rel_error=err, tolerance=tolerance, passed=bool(err <= tolerance), note=note)


def printed(text: str) -> tuple[float, float]:
    """A number as printed in a source and the relative tolerance of half a unit of its last digit."""
    value = float(text)
    mantissa = text.lower().split("e")[0]
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    exponent = int(text.lower().split("e")[1]) if "e" in text.lower() else 0
    return value, 0.5 * 10.0 ** (exponent - decimals) / abs(value)


def claim(name: str, source: str, quantity: str, holds: bool, note: str = "") -> Check:
    """A yes/no statement (e.g. 'the amplitude decays linearly', 'no eigenvalue in the stop band')."""
    return Check(name=name, source=source, quantity=quantity, expected=1.0, computed=float(bool(holds)),
                 rel_error=0.0 if holds else 1.0, tolerance=0.0, passed=bool(holds), note=note)


@dataclass
class Case:
    name: str
    group: str
    func: Callable[[], list[Check]]
    slow: bool = False
    doc: str = ""


@dataclass
class CaseOutcome:
    case: Case
    checks: list[Check] = field(default_factory=list)
    error: str | None = None
    seconds: float = 0.0

    @property
    def passed(self) -> bool:
        return self.error is None and bool(self.checks) and all(c.passed for c in self.checks)


REGISTRY: dict[str, Case] = {}


def case(name: str, *, group: str, slow: bool = False):
    """Register a validation case (a function returning a list of :class:`Check`)."""

    def deco(func):
        if name in REGISTRY:
            raise ValueError(f"validation case {name!r} registered twice")
        REGISTRY[name] = Case(name=name, group=group, func=func, slow=slow, doc=(func.__doc__ or "").strip())
        return func

    return deco


def load_all() -> dict[str, Case]:
    from . import cases

    for mod in pkgutil.iter_modules(cases.__path__):
        importlib.import_module(f"{cases.__name__}.{mod.name}")
    return REGISTRY


def run_case(c: Case) -> CaseOutcome:
    t0 = time.perf_counter()
    try:
        checks = list(c.func())
        return CaseOutcome(case=c, checks=checks, seconds=time.perf_counter() - t0)
    except Exception as exc:  # a crashing case is a failed case, reported with its error
        return CaseOutcome(case=c, error=f"{type(exc).__name__}: {exc}", seconds=time.perf_counter() - t0)


def select(names: list[str] | None = None, include_slow: bool = True) -> list[Case]:
    reg = load_all()
    if names:
        unknown = [n for n in names if n not in reg and not any(c.group == n for c in reg.values())]
        if unknown:
            from discrete.errors import ModelError

            raise ModelError("drivefem validate", "--case", unknown[0] if len(unknown) == 1 else unknown,
                             "a case name (" + ", ".join(sorted(reg)) + ") or a group ("
                             + ", ".join(sorted({c.group for c in reg.values()})) + ")")
        return [c for c in reg.values() if c.name in names or c.group in names]
    return [c for c in reg.values() if include_slow or not c.slow]
