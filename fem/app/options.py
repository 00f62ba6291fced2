"""The output options every ``drivefem`` command shares (docs/cli.md, "One convention"):

``--json FILE.json``  the result (schema ``drivefem.<command>``);
``--csv FILE.csv``    the result's table;
``--plot PATH``       the figures (matplotlib): a file (``.png``, ``.svg``, ``.pdf``, ...) where the command
                      draws one figure, a directory where it draws several (:data:`FIGURES` per command);
``--render DIR``      3D pictures (pyvista, off screen): PNG and GIF files in a directory;
``--html FILE.html``  the interactive figure (plotly, optional extra ``drivefem[html]``);
``--quiet``           no progress bar.

A path that does not fit its option is bad input (exit 2) before any work: a figure file name where a
directory is needed (``modal --render modes.png``, ``simulate --plot run.png``), a directory where a
file is needed, a suffix the writer does not produce.  Nothing creates a directory named like a file.

Old spellings (``modal --png DIR``, ``campbell --png FILE``, ``render --out DIR``, ...) are aliases of
the new options that print one line on stderr naming the new spelling; giving both is bad input.
"""
from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from discrete.errors import ModelError

#: ``--plot`` forms
FILE, DIRECTORY, EITHER = "file", "directory", "file or directory"
#: suffixes of files drivefem writes: a directory option never takes one of them
FILE_SUFFIXES = (".png", ".svg", ".svgz", ".pdf", ".eps", ".ps", ".jpg", ".jpeg", ".tif", ".tiff", ".webp", ".gif",
                 ".json", ".csv", ".txt", ".html", ".htm", ".vtu", ".xdmf", ".h5", ".hdf5", ".toml", ".md")
FIGURE_SUFFIXES = (".png", ".svg", ".svgz", ".pdf", ".eps", ".ps", ".jpg", ".jpeg", ".tif", ".tiff", ".webp")

#: what ``--plot`` writes, per command: (form, the figures)
FIGURES = {
    "modal": (FILE, "the mode shapes (FE files: one panel per mode above a side view of the shaft with its supports "
                    "and discs; rotor files: the orbits of the first lateral mode)"),
    "forced": (EITHER, "the response (FRF, nonlinear amplitude-frequency curve of [steady], or a rotor's Bode plot); "
                       "a directory gets every figure: frf.png, afc.png or bode.png, loads.png where the model has "
                       "named outputs, and a rotor's polar_<k>_<probe>.png per probe"),
    "simulate": (DIRECTORY, "the time histories (named outputs: twist, speeds, loads), phase portraits and energy "
                            "balance (rotor run-ups: orbit radius, rub forces, orbits, run-up Bode plot, cascade)"),
    "campbell": (FILE, "the Campbell diagram with the log decrements"),
    "parametric": (FILE, "the stability chart"),
    "static": (FILE, "the static sag and the bearing loads"),
    "critical-map": (FILE, "the undamped critical speed map with the model's bearings"),
    "stability": (FILE, "the log decrements against speed and the API Level I plot"),
}


class Deprecated(argparse.Action):
    """An old spelling of an option: stores its value for the new option (resolved by
    :func:`check_outputs`) and says once on stderr which spelling replaces it."""

    def __init__(self, option_strings, dest, new: str = "", **kw):
        self.new = new
        super().__init__(option_strings, dest, **kw)

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"drivefem: warning: {option_string} is deprecated; use {self.new} (same meaning; the old spelling "
              "will be removed)", file=sys.stderr)
        setattr(namespace, self.dest, values)
        given = getattr(namespace, "_old_given", None) or {}
        given[self.dest] = (option_string, self.new.split()[0])
        namespace._old_given = given


def add_outputs(p, command: str, *, json: str | None = "the result", csv: str | None = None, plot: bool = False,
                render: str | None = None, html: str | None = None, quiet: bool = True,
                old: dict | None = None) -> None:
    """Register the shared output options of ``command`` on its parser ``p`` (texts from this
    module, so that every command says the same thing); ``old``: {old spelling: new option}."""
    if json:
        p.add_argument("--json", metavar="FILE.json", help=f"write {json} here (JSON)")
    if csv:
        p.add_argument("--csv", metavar="FILE.csv", help=f"write {csv} here (CSV)")
    if plot:
        form, what = FIGURES[command]
        metavar = {FILE: "FILE.png", DIRECTORY: "DIR", EITHER: "FILE.png|DIR"}[form]
        text = {FILE: f"write {what} here (.png, .svg, .pdf)", DIRECTORY: f"write the figures into this directory: {what}",
                EITHER: f"a file: write {what} there (.png, .svg, .pdf)"}[form]
        p.add_argument("--plot", metavar=metavar, help=text)
    if render:
        p.add_argument("--render", metavar="DIR", help=f"render {render} off screen into this directory (PNG)")
    if html:
        p.add_argument("--html", metavar="FILE.html", help=f"write {html} as a self-contained interactive HTML file "
                       "(needs plotly: pip install 'drivefem[html]')")
    if quiet:
        p.add_argument("--quiet", action="store_true", help="no progress bar (bars show only on a terminal, after 2 s)")
    for spelling, new in (old or {}).items():
        p.add_argument(spelling, dest="_old_" + spelling.lstrip("-").replace("-", "_"), action=Deprecated,
                       new=new, help=argparse.SUPPRESS)


def resolve_old(args) -> None:
    """Move the values of old spellings to their new options; both given is bad input."""
    for dest, (spelling, new) in (getattr(args, "_old_given", None) or {}).items():
        attr = new.lstrip("-").replace("-", "_")
        if getattr(args, attr, None) is not None:
            raise ModelError("command line", spelling, getattr(args, dest), f"one of {spelling} (old spelling) and "
                             f"{new}, not both")
        setattr(args, attr, getattr(args, dest))
        setattr(args, dest, None)
        spelled = getattr(args, "_spelled", None) or {}
        spelled[attr] = spelling
        args._spelled = spelled
    args._old_given = {}


def figure_form(command: str) -> str:
    return FIGURES[command][0]



def _is_dir(p: Path) -> bool:
    """``p.is_dir()``, False where the system cannot even look the name up (too long, a loop): the
    output-path check that follows names the reason."""
    try:
        return p.is_dir()
    except OSError:
        return False


def _exists(p: Path) -> bool:
    try:
        return p.exists()
    except OSError:
        return False


def plot_target(path, command: str, form: str | None = None, option: str = "--plot") -> tuple[Path | None, Path | None]:
    """(file, None) or (None, directory) that ``--plot path`` names for ``command`` (``form``:
    the command's form for this kind of model, default :data:`FIGURES`); ModelError when it does
    not fit.  Nothing is created."""
    form = form or figure_form(command)
    p = Path(path)
    suffix = p.suffix.lower()
    what = FIGURES[command][1] if command in FIGURES else "the figures"
    if form == FILE:
        if _is_dir(p):
            raise ModelError("command line", option, str(path), f"a figure file name such as {command}.png "
                             f"(drivefem {command} draws one figure: {what}; this is a directory)")
        if suffix not in FIGURE_SUFFIXES:
            raise ModelError("command line", option, str(path), "a figure file name ending in .png, .svg or .pdf "
                             f"(drivefem {command} draws one figure: {what})")
        return p, None
    if form == DIRECTORY:
        if suffix in FILE_SUFFIXES or (_exists(p) and not _is_dir(p)):
            raise ModelError("command line", option, str(path), f"a directory (drivefem {command} draws several "
                             f"figures: {what}; e.g. {option} {p.with_suffix('').name or 'figures'}/)")
        return None, p
    if suffix in FIGURE_SUFFIXES and not _is_dir(p):
        return p, None
    if (suffix and not _is_dir(p)) or (_exists(p) and not _is_dir(p)):   # out.xyz: neither a figure nor a folder name
        raise ModelError("command line", option, str(path), "a figure file (.png, .svg, .pdf: the main figure) or a "
                         f"directory (every figure) for drivefem {command}"
                         + (f"; {suffix!r} is not a figure format (a new directory takes a name without a suffix)"
                            if suffix and suffix not in FILE_SUFFIXES else ""))
    return None, p


def directory_target(path, option: str, what: str) -> Path:
    """A directory option (``--render``, ``--out``, ``--report``): never a name with a file suffix."""
    p = Path(path)
    if p.suffix.lower() in FILE_SUFFIXES or (_exists(p) and not _is_dir(p)):
        raise ModelError("command line", option, str(path), f"a directory for {what} (this names a file; "
                         f"e.g. {option} {p.with_suffix('').name or 'pictures'}/)")
    return p


def need_plotly(args) -> None:
    """``--html`` given: plotly must import, checked before any work (exit 2 naming the extra)."""
    if getattr(args, "html", None):
        from ..output.html import require_plotly

        require_plotly("--html")


def prepare(args, command: str, **kinds) -> dict:
    """Everything a command checks before any work: old spellings resolved (:func:`resolve_old`),
    ``--quiet`` applied to every progress bar, each output path checked (``attr=kind``: ``"plot"``
    in the command's form of :data:`FIGURES`, ``"dir"`` a directory, else a file), and plotly
    present when ``--html`` is given; two outputs on one path are bad input.  Returns
    {attr: (file, directory)} of the paths given."""
    from ..output.paths import SUFFIXES, check_output_path
    from .progress import set_quiet

    resolve_old(args)
    set_quiet(getattr(args, "quiet", False))
    out, seen, checks = {}, {}, []
    for attr, kind in kinds.items():
        value = getattr(args, attr, None)
        if value is None:
            continue
        option = (getattr(args, "_spelled", None) or {}).get(attr) or "--" + attr.replace("_", "-")
        if str(value) == "":
            raise ModelError("command line", option, "", "a non-empty path")
        if kind == "plot":
            file, folder = plot_target(value, command, option=option)
        elif kind == "dir":
            file, folder = None, directory_target(value, option, DIRECTORY_WHAT.get(attr, "the outputs"))
        else:
            file, folder = Path(value), None
        if "\x00" in str(value):
            raise ModelError("command line", option, repr(str(value))[:60], "a path without NUL characters")
        target = Path(os.path.realpath(os.path.abspath(file or folder)))   # one file under two names too
        if target in seen:
            raise ModelError("command line", option, str(value), f"a path other than that of {seen[target]} "
                             "(two outputs would overwrite each other)")
        seen[target] = option
        out[attr] = (file, folder)
        checks.append((file or folder, option, folder is not None, kind))
    for path, option, directory, kind in checks:     # after the pairs: a shared path is named as such
        check_output_path(path, option, directory=directory,
                          kind=kind if not directory and kind in SUFFIXES else None)   # .json for --json, ...
    need_plotly(args)
    return out


#: what a directory option holds (for the message when a file name is given)
DIRECTORY_WHAT = {"render": "the 3D pictures (PNG, GIF) and their data files", "out": "the outputs",
                  "report": "the validation report", "resume": "the sweep's point files", "gallery": "the gallery"}
