"""The one JSON serialiser.  Numbers are plain JSON numbers; complex numbers are ``{"re": x, "im": y}``;
numpy arrays become (nested) lists; ``None`` is ``null`` (documented "not available" values).  A NaN
or infinity anywhere is an error naming its place: a result that became non-finite is never written."""
from __future__ import annotations

import json
import math
import os
from pathlib import Path

import numpy as np

from discrete.errors import SolverError


class Raw:
    """A piece of JSON text already written and checked by its producer (a long list of records built
    from arrays in one pass, e.g. a simulation's events): :func:`encode` passes it through and
    :func:`write_json` splices it in.  ``n``: its number of items (``len``)."""

    __slots__ = ("text", "n")

    def __init__(self, text: str, n: int = 0):
        self.text, self.n = text, n

    def __len__(self) -> int:
        return self.n


def encode(obj, path="$"):
    """``obj`` as plain JSON data; raises :class:`SolverError` at the first non-finite number.
    ``path`` names the place in error messages; it is built only then (``_where``): below the
    top it is a chain of (parent, separator, key) tuples, cheap for the millions of numbers of a
    long simulation's events."""
    if obj is None or isinstance(obj, (bool, str, Raw)):
        return obj
    if isinstance(obj, (np.bool_,)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        x = float(obj)
        if not math.isfinite(x):
            raise SolverError(f"the result is not finite at {_where(path)} ({x}): the computation lost its meaning "
                              "there (check the model's parameters, or the solver's warnings above)")
        return x
    if isinstance(obj, (complex, np.complexfloating)):
        return {"re": encode(obj.real, (path, ".", "re")), "im": encode(obj.imag, (path, ".", "im"))}
    if isinstance(obj, np.ndarray):
        if obj.dtype.kind in "fc" and obj.size and not np.all(np.isfinite(obj)):
            bad = np.argwhere(~np.isfinite(obj))[0]
            raise SolverError(f"the result is not finite at {_where(path)}[{']['.join(map(str, bad))}]: the "
                              "computation lost its meaning there (check the model's parameters, or the solver's "
                              "warnings above)")
        if obj.dtype.kind in "biu" or (obj.dtype.kind == "f" and obj.dtype.itemsize <= 8):
            return obj.tolist()              # Python bools, ints and floats, all finite: JSON as they are
        return encode(obj.tolist(), path)
    if isinstance(obj, dict):
        return {str(k): encode(v, (path, ".", k)) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [encode(v, (path, "[", i)) for i, v in enumerate(obj)]
    if isinstance(obj, Path):
        return str(obj)
    raise TypeError(f"not JSON serialisable at {_where(path)}: {type(obj).__name__}")


def _where(path) -> str:
    """The place ``$.a.b[3]`` of a path chain of :func:`encode`."""
    keys = []
    while isinstance(path, tuple):
        path, sep, key = path
        keys.append(f".{key}" if sep == "." else f"[{key}]")
    return str(path) + "".join(reversed(keys))


def check_finite(data) -> dict:
    """Encode ``data`` (raising at the first non-finite number) and return the JSON-ready dict."""
    return encode(data)


def write_json(path, data, encoded: bool = False) -> Path:
    """Write ``data`` atomically to ``path``; ``encoded``: it is already the result of
    :func:`encode` (not encoded twice: a long simulation's events take seconds)."""
    path = Path(path)
    raws: list = []

    def placeholder(obj):
        if isinstance(obj, Raw):
            raws.append(obj.text)
            return f"\x00raw{len(raws) - 1}\x00"
        raise TypeError(f"not JSON serialisable: {type(obj).__name__}")

    text = json.dumps(data if encoded else encode(data), indent=2, allow_nan=False, default=placeholder) + "\n"
    for k, raw in enumerate(raws):
        text = text.replace(json.dumps(f"\x00raw{k}\x00"), raw, 1)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(text)
    os.replace(tmp, path)
    return path
