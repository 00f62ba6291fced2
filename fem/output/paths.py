"""Output paths are checked before any work starts: a run never computes for minutes to fail on an
unwritable file, and never writes two outputs into one file.

:func:`check_outputs` is the one check every command runs on its output options (``--json``, ``--csv``,
``--plot``, ``--png``, ``--vtu``, ``--h5``, ``--html``, ``--out``, ``--report``): each path is non-empty, its names fit the
file system (``NAME_MAX`` per component, counting the ``.tmp`` of the atomic write, ``PATH_MAX`` in
all), a file ends in a suffix its writer produces (:data:`SUFFIXES`), a file is not a directory, a
device or a FIFO (files are written by replacing them), a directory is not a file, the location is
writable, and no two options name the same path."""
from __future__ import annotations

import os
import stat
from pathlib import Path

from discrete.errors import ModelError

#: File suffixes each kind of output is written in (lower case): JSON documents, CSV tables,
#: matplotlib figures (formats that need no LaTeX or optional plugins), mode-shape meshes (meshio).
SUFFIXES = {
    "json": (".json",),
    "csv": (".csv", ".txt"),
    "figure": (".png", ".pdf", ".svg", ".svgz", ".eps", ".ps", ".jpg", ".jpeg", ".tif", ".tiff", ".webp"),
    "mesh": (".vtu", ".xdmf"),
    "h5": (".h5", ".hdf5"),
    "html": (".html", ".htm"),
    "toml": (".toml",),
}
#: Kinds of output: a file kind of :data:`SUFFIXES`, a directory (created if missing), or ``figure|dir``:
#: a figure file when the path has a suffix, else a directory of figures (rotor ``forced --plot``).
KINDS = tuple(SUFFIXES) + ("dir", "figure|dir")
_TMP = ".tmp"          # files are written as NAME.tmp, then renamed (fem.output.jsonio.write_json)
WHERE = "command line"


def _limit(probe: Path, name: str, default: int) -> int:
    try:
        return int(os.pathconf(probe, name))
    except (OSError, ValueError):
        return default


def _existing_ancestor(p: Path) -> Path:
    probe = p.absolute()
    while True:
        try:
            if probe.exists() or probe == probe.parent:
                return probe
        except OSError:
            pass
        probe = probe.parent


def _check_names(p: Path, option: str, directory: bool) -> None:
    """Every component within NAME_MAX (a file's own name with the temporary suffix), the whole path within PATH_MAX."""
    shown = str(p)
    probe = _existing_ancestor(p)
    if not probe.is_dir():
        probe = probe.parent
    name_max = _limit(probe, "PC_NAME_MAX", 255)
    path_max = _limit(probe, "PC_PATH_MAX", 4096)
    absolute = str(p.absolute())
    if len(os.fsencode(absolute)) >= path_max:
        raise ModelError(WHERE, option, _short(shown), f"a path shorter than {path_max} bytes (this one has "
                         f"{len(os.fsencode(absolute))} as an absolute path)")
    parts = p.parts
    for k, part in enumerate(parts):
        n = len(os.fsencode(part)) + (len(_TMP) if (k == len(parts) - 1 and not directory) else 0)
        if n > name_max:
            room = name_max - (len(_TMP) if (k == len(parts) - 1 and not directory) else 0)
            raise ModelError(WHERE, option, _short(shown), f"names of at most {room} bytes per path component "
                             f"(the file system allows {name_max}" + (f", and the file is written through a temporary "
                             f"name with {_TMP!r} added" if room < name_max else "") + f"; {_short(part)!r} has "
                             f"{len(os.fsencode(part))})")


def _short(s: str, n: int = 60) -> str:
    return s if len(s) <= n else s[:n - 3] + "..."


def check_output_path(path, option: str, directory: bool = False, kind: str | None = None) -> Path:
    """``path`` can be written: a file (of ``kind``, whose suffixes :data:`SUFFIXES` lists; None: any
    suffix), or with ``directory`` a directory that may be created.  ModelError naming ``option`` otherwise."""
    if path is None or str(path) == "":
        raise ModelError(WHERE, option, "" if path is not None else None,
                         "a non-empty path" + (" of a directory" if directory else " of a file"))
    if "\x00" in str(path):
        raise ModelError(WHERE, option, _short(repr(str(path))), "a path without NUL characters")
    p = Path(path)
    _check_names(p, option, directory)
    if not directory and kind is not None:
        allowed = SUFFIXES[kind]
        if p.suffix.lower() not in allowed:
            raise ModelError(WHERE, option, _short(str(p)), "a file name ending in " + ", ".join(allowed)
                             + (f" (not {p.suffix!r})" if p.suffix else " (it has no suffix)"))
    try:
        st = p.stat() if p.exists() else None
    except OSError as exc:
        raise ModelError(WHERE, option, _short(str(p)), f"a path that can be examined ({exc.strerror or exc})") from None
    if st is not None:
        if directory and not stat.S_ISDIR(st.st_mode):
            raise ModelError(WHERE, option, str(p), "a directory (this is a file)")
        if not directory and stat.S_ISDIR(st.st_mode):
            raise ModelError(WHERE, option, str(p), "a file path (this is a directory)")
        if not directory and not stat.S_ISREG(st.st_mode):
            raise ModelError(WHERE, option, str(p), "a regular file path (this is a device, FIFO or socket; "
                             "outputs are written to a temporary file that then replaces the target)")
        if not os.access(p, os.W_OK):
            raise ModelError(WHERE, option, str(p), "a writable path (permission denied)")
        return p
    probe = _existing_ancestor(p if directory else p.parent)
    if not probe.is_dir():
        raise ModelError(WHERE, option, str(p), f"a path under a directory ({probe} is a file)")
    if not os.access(probe, os.W_OK | os.X_OK):
        raise ModelError(WHERE, option, str(p), f"a writable location ({probe} is not writable)")
    return p


def _identity(p: Path) -> str:
    """The path a name refers to (symbolic links and '..' resolved as far as the path exists)."""
    return os.path.realpath(os.path.abspath(p))


def check_outputs(values: dict[str, tuple[object, str]]) -> dict[str, Path]:
    """Check the output options ``{option: (value, kind)}`` (``kind`` one of :data:`KINDS`; options whose value
    is None are not given) with :func:`check_output_path`, then refuse two options naming the same path."""
    seen: dict[str, str] = {}
    out = {}
    for option, (value, kind) in values.items():
        if value is None:
            continue
        if kind not in KINDS:
            raise ValueError(f"unknown output kind {kind!r}")
        if kind == "figure|dir":
            suffix = Path(str(value)).suffix
            if suffix and suffix.lower() not in SUFFIXES["figure"]:
                raise ModelError(WHERE, option, _short(str(value)), "a .png file (one figure) or a directory "
                                 "without a suffix (every figure of the command); figure files end in "
                                 + ", ".join(SUFFIXES["figure"]) + f" (not {suffix!r})")
            kind = "figure" if suffix else "dir"
        p = check_output_path(value, option, directory=kind == "dir", kind=None if kind == "dir" else kind)
        ident = _identity(p)
        if ident in seen:
            raise ModelError(WHERE, option, str(value), f"a path of its own ({seen[ident]} writes to the same path: "
                             "each output needs its own file or directory)")
        seen[ident] = option
        out[option] = p
    return out


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
