"""The one CSV writer: a header row and rows of numbers written with ``repr`` (round-trip exact)."""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np


def _cell(v):
    if isinstance(v, (float, np.floating)):
        return repr(float(v))
    if isinstance(v, (bool, np.bool_)):
        return int(bool(v))
    if isinstance(v, (int, np.integer)):
        return int(v)
    return "" if v is None else v


def write_csv(path, header: list[str], rows) -> Path:
    """Write ``header`` and ``rows`` (iterables of numbers/strings) to ``path``."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        for row in rows:
            w.writerow([_cell(v) for v in row])
    return path


def write_columns(columns: dict, path) -> Path:
    """Write equal-length columns as CSV (``.csv``: header row, full precision) or JSON (``.json``:
    an object of lists, through the one JSON serialiser)."""
    from discrete.errors import ModelError

    from .jsonio import write_json

    path = Path(path)
    if path.suffix.lower() not in (".csv", ".json"):
        raise ModelError("table export", "path", str(path), "a .csv or .json file")
    cols = {k: np.asarray(v).ravel() for k, v in columns.items()}
    lengths = {k: v.size for k, v in cols.items()}
    if len(set(lengths.values())) > 1:
        raise ModelError("table export", "columns", lengths, "columns of equal length")
    if path.suffix.lower() == ".json":
        return write_json(path, cols)
    return write_csv(path, list(cols), zip(*cols.values()))


def read_columns(path) -> dict:
    """Read a table written by :func:`write_columns` (numeric columns as float arrays)."""
    import json

    path = Path(path)
    if path.suffix.lower() == ".json":
        return {k: np.asarray(v) for k, v in json.loads(path.read_text()).items()}
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    head, body = rows[0], rows[1:]
    out = {}
    for j, name in enumerate(head):
        col = [r[j] for r in body]
        try:
            out[name] = np.array([float(v) for v in col])
        except ValueError:
            out[name] = np.array(col, dtype=object)
    return out


def modal_table(modal) -> dict:
    """Columns of a modal result: mode number, f [Hz], omega [rad/s], residual, reliable."""
    n = modal.omega_rad_s.size
    cols = {"mode": np.arange(1, n + 1), "f_hz": modal.frequencies_hz, "omega_rad_s": modal.omega_rad_s,
            "residual": modal.residuals, "reliable": modal.reliable.astype(int)}
    kinds = getattr(modal, "kinds", None)
    if kinds is not None:
        cols["kind"] = np.asarray(kinds, dtype=object)
    return cols


def write_modal_table(modal, path) -> Path:
    """The frequency table of ``modal`` as CSV or JSON."""
    return write_columns(modal_table(modal), path)
