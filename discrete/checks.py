"""Argument checks of the public Python API, worded like the model file's rules.

Each function checks one value and returns it normalised (a Python float, an int, a float array)
or raises :class:`~discrete.errors.ModelError` ``(where, key, value, allowed)`` -- the message form
of the model file, whose schema (``fem/modelfile/schema``) words the same ranges the same way:
"a number > 0", "a number >= 0", "an integer >= 1", "a number > 0 and <= 1.5".  A bool is never
a number, a complex value is never real, NaN and infinity are refused unless a check says so.

These run in constructors and entry points, never in a solver's inner loop.  numpy only.
"""
from __future__ import annotations

import numbers
import operator

import numpy as np

from .errors import ModelError

_OPS = {">": operator.gt, ">=": operator.ge, "<": operator.lt, "<=": operator.le}


def _with(allowed: str, note: str | None) -> str:
    return f"{allowed} ({note})" if note else allowed


def number(where: str, key: str, value, allowed: str = "a finite number", *, allow_inf: bool = False) -> float:
    """A real, finite number (``allow_inf``: +-inf allowed, NaN never) as a Python float."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        if isinstance(value, numbers.Complex) and not isinstance(value, (bool, np.bool_)):
            raise ModelError(where, key, value, allowed + " (real, not complex)")
        raise ModelError(where, key, value, allowed)
    v = float(value)
    if np.isnan(v) or (np.isinf(v) and not allow_inf):
        raise ModelError(where, key, value, allowed)
    return v


def bounded(where: str, key: str, value, lower: tuple[str, float] | None = None,
            upper: tuple[str, float] | None = None, note: str | None = None, *, allow_inf: bool = False) -> float:
    """A finite number satisfying ``lower`` = (">" or ">=", bound) and ``upper`` = ("<" or "<=", bound);
    the allowed text reads "a number > 0 and <= 1.5 (note)" as the model file's."""
    bounds = [f"{op} {b:g}" for op, b in filter(None, (lower, upper))]
    allowed = _with("a number" + (" " + " and ".join(bounds) if bounds else ""), note)
    v = number(where, key, value, allowed, allow_inf=allow_inf)
    for op, b in filter(None, (lower, upper)):
        if not _OPS[op](v, b):
            raise ModelError(where, key, value, allowed)
    return v


def positive(where: str, key: str, value, note: str | None = None) -> float:
    """A finite number > 0."""
    return bounded(where, key, value, (">", 0.0), note=note)


def non_negative(where: str, key: str, value, note: str | None = None) -> float:
    """A finite number >= 0."""
    return bounded(where, key, value, (">=", 0.0), note=note)


def finite(where: str, key: str, value, note: str | None = None) -> float:
    """Any finite real number."""
    return number(where, key, value, _with("a finite number", note))


def optional(check, where: str, key: str, value, *args, **kw):
    """``check(where, key, value, ...)`` unless value is None (kept None)."""
    return None if value is None else check(where, key, value, *args, **kw)


def integer(where: str, key: str, value, minimum: int | None = None, note: str | None = None) -> int:
    """An integer (not a bool, not a float) >= ``minimum``."""
    allowed = _with("an integer" + (f" >= {minimum}" if minimum is not None else ""), note)
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise ModelError(where, key, value, allowed)
    if minimum is not None and value < minimum:
        raise ModelError(where, key, value, allowed)
    return int(value)


def index(where: str, key: str, value, n: int, what: str = "DOF") -> int:
    """An integer index into ``n`` items: 0 <= value < n."""
    allowed = f"an integer {what} index in [0, {n - 1}]" if n > 0 else f"no {what} index (there are none)"
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral) or not 0 <= value < n:
        raise ModelError(where, key, value, allowed)
    return int(value)


def choice(where: str, key: str, value, options) -> object:
    """One of ``options`` (the message lists them as the model file does: 'a' | 'b')."""
    try:
        ok = value in options
    except TypeError:
        ok = False
    if not ok:
        raise ModelError(where, key, value, " | ".join(repr(o) for o in options))
    return value


def _short(a: np.ndarray):
    return a.tolist() if a.size <= 8 else f"array of shape {a.shape}"


def vector(where: str, key: str, value, n: int | None = None, note: str | None = None) -> np.ndarray:
    """A real, finite 1-D float array (of length ``n`` when given): a copy."""
    allowed = _with(f"a vector of {n} finite real numbers" if n is not None else "a vector of finite real numbers",
                    note)
    try:
        a = np.asarray(value)
    except Exception:                       # a ragged or foreign object
        raise ModelError(where, key, type(value).__name__, allowed) from None
    if a.dtype == object or a.dtype.kind not in "biuf" or a.dtype.kind == "b":
        raise ModelError(where, key, _short(a) if a.dtype.kind in "cO" and a.size <= 8 else str(a.dtype), allowed
                         + (" (real, not complex)" if a.dtype.kind == "c" else ""))
    if a.ndim != 1 or (n is not None and a.shape != (n,)):
        raise ModelError(where, key, f"shape {a.shape}", allowed)
    a = a.astype(float)
    if not np.all(np.isfinite(a)):
        raise ModelError(where, key, _short(a), allowed)
    return a


def real_matrix(where: str, key: str, A, shape: tuple[int, int] | None = None, note: str | None = None):
    """A real (not complex), 2-D matrix (dense or sparse) of ``shape`` when given; returned unchanged.
    Finiteness is checked by :func:`discrete.linear_system.check_finite` on the assembled form."""
    allowed = _with("a real square matrix" + (f" of shape {shape}" if shape else ""), note)
    dtype = getattr(A, "dtype", None)
    if dtype is None:
        try:
            dtype = np.asarray(A).dtype
        except Exception:
            raise ModelError(where, key, type(A).__name__, allowed) from None
    if np.dtype(dtype).kind == "c":
        raise ModelError(where, key, "complex entries", allowed + " (real, not complex)")
    if np.dtype(dtype).kind not in "biuf":
        raise ModelError(where, key, str(dtype), allowed)
    s = getattr(A, "shape", None)
    if s is None or len(s) != 2 or (shape is not None and tuple(s) != tuple(shape)) or s[0] != s[1]:
        raise ModelError(where, key, f"shape {s}", allowed)
    return A
