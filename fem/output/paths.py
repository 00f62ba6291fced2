"""Output paths are checked before any work starts: a run never computes for minutes to fail on an
unwritable file."""
from __future__ import annotations

import os
from pathlib import Path

from discrete.errors import ModelError


def check_output_path(path, option: str, directory: bool = False) -> Path:
    """``path`` can be written (a file, or with ``directory`` a directory that may be created)."""
    p = Path(path)
    if p.exists():
        if directory and not p.is_dir():
            raise ModelError("command line", option, str(p), "a directory (this is a file)")
        if not directory and p.is_dir():
            raise ModelError("command line", option, str(p), "a file path (this is a directory)")
        if not os.access(p, os.W_OK):
            raise ModelError("command line", option, str(p), "a writable path (permission denied)")
        return p
    parent = p if directory else p.parent
    probe = parent
    while not probe.exists():
        probe = probe.parent
    if not probe.is_dir():
        raise ModelError("command line", option, str(p), f"a path under a directory ({probe} is a file)")
    if not os.access(probe, os.W_OK | os.X_OK):
        raise ModelError("command line", option, str(p), f"a writable location ({probe} is not writable)")
    return p


def try_writing(directory, option: str, shown, what: str = "a writable location") -> None:
    """Create ``directory`` (and parents) and a file in it, then remove the file: permissions can lie (root,
    read-only mounts, full disks), a write cannot.  ModelError naming ``option`` and ``shown`` on failure."""
    d = Path(directory)
    try:
        d.mkdir(parents=True, exist_ok=True)
        probe = d / f".drivefem-probe.{os.getpid()}"
        probe.write_text("")
        probe.unlink()
    except OSError as exc:
        raise ModelError("command line", option, str(shown), f"{what} ({exc.strerror or exc})") from None
