"""One-call runner used by the ``drivefem`` CLI for model files with a ``[drive]`` table
(``drivefem modal | forced | compare``): prints the table, writes JSON/CSV, returns the exit code."""
from __future__ import annotations

import json
import sys

from discrete.errors import ModelError

from . import compare, drive_forced, drive_modal

COMMANDS = ("modal", "forced", "compare")


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
        from ..cli import _json_default

        with open(json_path, "w") as fh:
            json.dump(res.to_dict() | {"title": title}, fh, indent=2, default=_json_default)
    return rc
