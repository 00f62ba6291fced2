"""Small helpers to validate model dictionaries (parsed TOML) with clear messages."""
from __future__ import annotations

import math
from collections.abc import Iterable, Mapping

from .errors import ModelError


def check_keys(table: Mapping, allowed: Iterable[str], where: str, hints: Mapping[str, str] | None = None) -> None:
    """Raise :class:`ModelError` for the first key of ``table`` not in ``allowed``.

    ``hints`` maps keys that are valid elsewhere (e.g. bending-only keys) to an explanation.
    """
    allowed = set(allowed)
    for key in table:
        if key not in allowed:
            if hints and key in hints:
                raise ModelError(where, key, table[key], hints[key])
            raise ModelError(where, key, table[key], "one of " + ", ".join(sorted(allowed)) + " (unknown keys are an error)")


def require(table: Mapping, key: str, where: str, what: str):
    if key not in table:
        raise ModelError(where, key, None, f"{what} (required key missing)")
    return table[key]


def number(value, key: str, where: str, *, positive: bool = False, nonnegative: bool = False,
           integer: bool = False) -> float:
    """Check that ``value`` is a finite real number with the requested sign."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ModelError(where, key, value, "a number")
    if not math.isfinite(value):
        raise ModelError(where, key, value, "a finite number")
    if integer and int(value) != value:
        raise ModelError(where, key, value, "an integer")
    if positive and not value > 0:
        raise ModelError(where, key, value, "a number > 0")
    if nonnegative and not value >= 0:
        raise ModelError(where, key, value, "a number >= 0")
    return int(value) if integer else float(value)


def choice(value, key: str, where: str, options: Iterable[str]) -> str:
    options = list(options)
    if value not in options:
        raise ModelError(where, key, value, " | ".join(repr(o) for o in options))
    return value
