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


def encode(obj, path: str = "$"):
    """``obj`` as plain JSON data; raises :class:`SolverError` at the first non-finite number."""
    if obj is None or isinstance(obj, (bool, str)):
        return obj
    if isinstance(obj, (np.bool_,)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        x = float(obj)
        if not math.isfinite(x):
            raise SolverError(f"the result is not finite at {path} ({x}): the computation lost its meaning there "
                              "(check the model's parameters, or the solver's warnings above)")
        return x
    if isinstance(obj, (complex, np.complexfloating)):
        return {"re": encode(obj.real, path + ".re"), "im": encode(obj.imag, path + ".im")}
    if isinstance(obj, np.ndarray):
        if obj.dtype.kind in "fc" and obj.size and not np.all(np.isfinite(obj)):
            bad = np.argwhere(~np.isfinite(obj))[0]
            raise SolverError(f"the result is not finite at {path}[{']['.join(map(str, bad))}]: the computation lost "
                              "its meaning there (check the model's parameters, or the solver's warnings above)")
        return encode(obj.tolist(), path)
    if isinstance(obj, dict):
        return {str(k): encode(v, f"{path}.{k}") for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [encode(v, f"{path}[{i}]") for i, v in enumerate(obj)]
    if isinstance(obj, Path):
        return str(obj)
    raise TypeError(f"not JSON serialisable at {path}: {type(obj).__name__}")


def check_finite(data) -> dict:
    """Encode ``data`` (raising at the first non-finite number) and return the JSON-ready dict."""
    return encode(data)


def write_json(path, data) -> Path:
    """Write ``data`` (already encoded or not) atomically to ``path``."""
    path = Path(path)
    text = json.dumps(encode(data), indent=2, allow_nan=False) + "\n"
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(text)
    os.replace(tmp, path)
    return path
