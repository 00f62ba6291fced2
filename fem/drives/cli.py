"""One-call runner for the ``drivefem`` CLI (and ``python -m fem.drives``): prints the table,
writes JSON/CSV, returns the exit code.  The lead's CLI routes a model file with a ``[drive]``
table here: ``if drives.is_drive(doc): return drives.cli.run(cmd, doc, modes=.., json_path=..)``."""
from __future__ import annotations

import argparse
import json
import sys
import tomllib

import numpy as np

from discrete.errors import ModelError, SolverError

from . import compare, drive_forced, drive_modal

COMMANDS = ("modal", "forced", "compare")


def load(path) -> dict:
    with open(path, "rb") as fh:
        return tomllib.load(fh)


def _default(o):
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, (np.floating, np.integer)):
        return o.item()
    if isinstance(o, complex):
        return [o.real, o.imag]
    raise TypeError(type(o).__name__)


def run(command: str, doc: dict, *, modes: int | None = None, json_path=None, csv_path=None, out=None) -> int:
    """Run ``command`` ("modal" | "forced" | "compare") on a parsed drive model file."""
    out = out or sys.stdout
    rc = 0
    if command == "modal":
        res = drive_modal(doc, modes)
        rc = 0 if res.ok else 3
    elif command == "forced":
        if doc.get("analysis", {}).get("type", "forced") != "forced":
            raise ModelError("[analysis]", "type", doc["analysis"]["type"], "'forced' for drivefem forced")
        res = drive_forced(doc)
        if csv_path:
            res.write_csv(csv_path)
    elif command == "compare":
        res = compare(doc)
    else:
        raise ModelError("drivefem", "command", command, " | ".join(COMMANDS))
    title = doc.get("title", "")
    print((title + "\n" if title else "") + res.table(), file=out)
    if json_path:
        with open(json_path, "w") as fh:
            json.dump(res.to_dict() | {"title": title}, fh, indent=2, default=_default)
    return rc


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m fem.drives", description="drives of regular structure (ch. 10)")
    ap.add_argument("command", choices=COMMANDS)
    ap.add_argument("model")
    ap.add_argument("--modes", type=int)
    ap.add_argument("--json")
    ap.add_argument("--csv")
    a = ap.parse_args(argv)
    try:
        return run(a.command, load(a.model), modes=a.modes, json_path=a.json, csv_path=a.csv)
    except ModelError as exc:
        print(f"drivefem: error: {exc}", file=sys.stderr)
        return 2
    except SolverError as exc:
        print(f"drivefem: solver failure: {exc}", file=sys.stderr)
        return 4
