"""Reading a model file: once, with every way a file can be unreadable turned into a clear error
(missing file, a directory, binary or non-UTF-8 content, broken TOML, absurd size or nesting)."""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

from discrete.errors import ModelError

MAX_BYTES = 16 * 1024 * 1024
"""Largest model file read (a model file is a description, not data)."""
MAX_DEPTH = 24
"""Deepest nesting of tables and arrays in a model file."""
MAX_MAGNITUDE = 1e100
"""Largest magnitude of a number in a model file (and 1 / it the smallest nonzero one): beyond any
physical scale in SI units, and products of two such numbers (stiffness x displacement, omega^2 x
mass, ...) overflow or underflow double precision inside the solvers."""


def read_toml(path: str | Path) -> dict:
    """The parsed TOML document of ``path``."""
    p = Path(path)
    if p.is_dir():
        raise ModelError("", "model file", str(p), "a TOML file (this is a directory)")
    if not p.is_file():
        raise ModelError("", "model file", str(p), "an existing TOML file")
    try:
        size = p.stat().st_size
        if size > MAX_BYTES:
            raise ModelError(str(p), "model file", f"{size} bytes", f"a model file of at most {MAX_BYTES} bytes")
        data = p.read_bytes()
    except OSError as exc:
        raise ModelError("", "model file", str(p), f"a readable file ({exc.strerror})") from None
    return parse_toml(data, str(p))


def parse_toml(data: bytes, name: str = "model file") -> dict:
    """Parse TOML bytes: UTF-8 text without NUL bytes, valid syntax, bounded nesting."""
    nul = data.find(b"\x00")
    if nul >= 0:
        raise ModelError(name, "model file", f"binary data (NUL byte at offset {nul})",
                         "a UTF-8 TOML text file")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ModelError(name, "model file", f"byte 0x{data[exc.start]:02x} at offset {exc.start} is not UTF-8",
                         "a UTF-8 TOML text file") from None
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ModelError(name, "TOML", str(exc), "valid TOML syntax") from None
    except RecursionError:
        doc = None
    depth = _depth(doc) if doc is not None else MAX_DEPTH + 1
    if depth > MAX_DEPTH:
        raise ModelError(name, "nesting", ">" + str(MAX_DEPTH) if doc is None else depth,
                         f"tables and arrays nested at most {MAX_DEPTH} deep")
    _check_magnitudes(doc, [])
    return doc


def _check_magnitudes(obj, path: list) -> None:
    """Every finite float within [1/MAX_MAGNITUDE, MAX_MAGNITUDE] in magnitude, or zero (NaN and
    infinity are left to the schema, which names them)."""
    if isinstance(obj, dict):
        for k, v in obj.items():
            _check_magnitudes(v, path + [str(k)])
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            _check_magnitudes(v, path + [i])
    elif isinstance(obj, float) and math.isfinite(obj) and obj != 0.0 \
            and not (1.0 / MAX_MAGNITUDE <= abs(obj) <= MAX_MAGNITUDE):
        n_idx = _tail_ints(path)                  # indices of the value inside an array
        head = path[:len(path) - n_idx]
        key = (str(head[-1]) if head else "value") + "".join(f"[{p}]" for p in path[len(head):])
        where, table = "", head[:-1]
        for p in table:
            where += f" #{p + 1}" if isinstance(p, int) else ("." if where else "") + p
        where = f"[{where}]" if where else "model file"
        raise ModelError(where, key, obj, f"a number of magnitude between {1 / MAX_MAGNITUDE:g} and "
                         f"{MAX_MAGNITUDE:g}, or 0 (beyond any physical scale: the solvers would overflow)")


def _tail_ints(path: list) -> int:
    n = 0
    for p in reversed(path):
        if not isinstance(p, int):
            break
        n += 1
    return n


def _depth(obj, level: int = 0) -> int:
    """Nesting depth of tables and arrays (stops counting past MAX_DEPTH)."""
    if level > MAX_DEPTH or not isinstance(obj, (dict, list)):
        return level
    items = obj.values() if isinstance(obj, dict) else obj
    return max((_depth(v, level + 1) for v in items), default=level + 1)
