"""The ``drivefem`` command line: argument parsing only; each command is one function of
:mod:`fem.app.commands` (design.md §5, docs/cli.md)."""
from __future__ import annotations

import argparse
import os
import sys
import traceback
import warnings

from discrete.errors import ModelError, SolverError

from .exit_codes import EXIT_INTERNAL, EXIT_INTERRUPTED


def build_parser() -> argparse.ArgumentParser:
    """The parser, each command's function as its ``func`` default (importing the commands loads
    numpy, scipy and scikit-fem: :func:`main` calls this inside its handlers).  The output options
    follow one convention (:mod:`fem.app.options`)."""
    from . import commands
    from .options import add_outputs

    p = argparse.ArgumentParser(prog="drivefem", description="FE and lumped models of machine drives: modal, "
                                "forced and nonsmooth time analyses, validated against the textbook.",
                                epilog="Outputs: --json FILE, --csv FILE, --plot FILE or DIR (figures), --render DIR "
                                "(3D pictures), --html FILE (interactive), --quiet (no progress bar); see docs/cli.md.")
    sub = p.add_subparsers(dest="command", required=True)
    m = sub.add_parser("modal", help="natural frequencies and mode shapes")
    m.add_argument("model")
    m.add_argument("--modes", type=int, default=None, help="number of modes (default: [analysis] modes or 6)")
    add_outputs(m, "modal", json="the modes", csv="the modes (frequency and, for lumped and hybrid files, the load "
                "shape of every output; one row per mode)", plot=True,
                render="one picture per mode (FE files: the deformed shaft; rotor files: the whirl of each lateral mode)",
                old={"--png": "--render DIR"})
    m.add_argument("--vtu", metavar="FILE.vtu", help="write the mode shapes to this VTU or XDMF file (FE models)")
    m.set_defaults(func=commands.modal)
    r = sub.add_parser("render", help="off-screen PNG (and GIF) pictures of the mode shapes, plus VTU/CSV/JSON data; "
                       "rotor files: the whirl of each lateral complex mode at the [analysis] speed")
    r.add_argument("model")
    r.add_argument("--modes", type=int, default=None, help="number of modes (default: [analysis] modes or 6)")
    r.add_argument("--mode", action="append", type=int, help="render only this mode number (repeatable)")
    add_outputs(r, "render", json=None, render="the mode shapes (PNG, with --gif an animation each) and their data "
                "(modes.json, modes.csv, FE files: modes.vtu); required", old={"--out": "--render DIR"})
    r.add_argument("--gif", action="store_true", help="also write an animated GIF per mode")
    r.set_defaults(func=commands.render)
    f = sub.add_parser("forced", help="harmonic response, or the nonlinear amplitude-frequency curve of [steady]")
    f.add_argument("model")
    add_outputs(f, "forced", json="the response", csv="the response, one row per frequency (or speed)", plot=True,
                html="the response (FRF, amplitude-frequency curve of [steady], or a rotor's Bode plot)")
    f.add_argument("--all", action="store_true", help="print every frequency")
    f.set_defaults(func=commands.forced)
    c = sub.add_parser("compare", help="a [drive] model by the discrete, transfer-matrix and continuum methods")
    c.add_argument("model")
    add_outputs(c, "compare", json="the comparison", quiet=False)
    c.set_defaults(func=commands.compare)
    s = sub.add_parser("simulate", help="time simulation of a model with nonsmooth elements (rotor files: the run-up)")
    s.add_argument("model")
    add_outputs(s, "simulate", json="the run's summary (events, period, energy balance, named outputs)",
                csv="the time history", plot=True, html="the time histories", old={"--png": "--plot DIR"})
    s.add_argument("--h5", metavar="FILE.h5", help="write the time history (named outputs, states, events) to this "
                   "HDF5 file (layout drivefem.history: docs/outputs.md)")
    s.set_defaults(func=commands.simulate)
    w = sub.add_parser("sweep", help="evaluate a grid of parameter points ([sweep] table) on Dask")
    w.add_argument("model")
    w.add_argument("--scheduler", help="address of an existing dask.distributed scheduler (default: local cluster)")
    w.add_argument("--resume", metavar="DIR", help="directory of a previous sweep: points already done are not "
                   "recomputed")
    w.add_argument("--out", metavar="DIR", help="directory for the per-point results (default: next to --json or "
                   "./sweep-<model>)")
    add_outputs(w, "sweep", json="the collected results")
    w.add_argument("--workers", type=int, default=None, help="local workers (0: serial, no Dask)")
    w.set_defaults(func=commands.sweep)
    v = sub.add_parser("validate", help="run the validation catalogue")
    v.add_argument("--case", action="append", help="case or group name (repeatable)")
    v.add_argument("--report", metavar="DIR", help="directory for the report (markdown, JSON, plots)")
    add_outputs(v, "validate", json="every check (expected, computed, tolerance)")
    v.add_argument("--fast", action="store_true", help="skip the slow cases")
    v.set_defaults(func=commands.validate)
    k = sub.add_parser("schema", help="print the JSON Schema of model files (for editors: Taplo, Even Better TOML)")
    k.add_argument("kind", nargs="?", choices=["fe", "lumped", "hybrid", "drive", "rotor", "train"],
                   help="one kind of model file (default: any model file)")
    k.add_argument("--out", metavar="FILE.json", help="write the schema to this file")
    k.set_defaults(func=commands.schema)
    d = sub.add_parser("demo", help="run representative examples end to end into ./drivefem-demo/")
    d.add_argument("--out", metavar="DIR", default="drivefem-demo", help="directory for every output of the demo "
                   "(default: ./drivefem-demo)")
    d.add_argument("--gallery", metavar="DOCS_DIR", help="also write the gallery page of the figures drawn "
                   "(DOCS_DIR/gallery.md, images in DOCS_DIR/img/gallery/): `drivefem demo --gallery docs`")
    d.add_argument("--quiet", action="store_true", help="no progress bars")
    d.set_defaults(func=lambda args: commands.demo(args, main))
    from . import parametric as parametric_command

    parametric_command.add_parser(sub)
    from . import rotor as rotor_command

    rotor_command.add_parser(sub)          # drivefem campbell; modal and forced of [rotor] files
    from . import rotor_analyses

    rotor_analyses.add_parser(sub)         # drivefem static | critical-map | stability (rotor files)
    from . import train as train_command

    train_command.add_parser(sub)          # modal, campbell, ... of train files ([[shaft]], [[mesh]])
    from . import convert as convert_command

    convert_command.add_parser(sub)        # drivefem convert: a ROSS rotor file -> a drivefem rotor file
    return p


def _show_warning(message, category, filename, lineno, file=None, line=None):
    print(f"drivefem: warning: {message}", file=sys.stderr)


#: commands that run many analyses in one process (numba's one-off load of the HB kernel pays back there)
LONG_LIVED = ("validate", "sweep", "demo")


def main(argv: list[str] | None = None) -> int:
    """Run a command (:func:`_run`).  Run as the ``drivefem`` program (``argv`` None), a one-shot command
    (not :data:`LONG_LIVED`) ends its process right after its work (:func:`_end_process`)."""
    code, command = _run(argv)
    if argv is None and command is not None and command not in LONG_LIVED:
        _end_process(code)
    return code


def _end_process(code: int) -> None:
    """End the process with ``code`` now: the exit handlers run (atexit, weakref finalizers) and the
    standard streams are flushed before and after them, as at a normal exit -- every file the command
    wrote is closed already (context managers) -- but the interpreter's teardown is skipped: freeing every
    object of numpy, scipy, pydantic and the model took ~65 ms after a ``drivefem forced`` of a one-DOF
    file (0.48 s in all; measured on a quiet machine).  Output that cannot be written (a full disk, an I/O
    error; not a closed pipe) turns a success into exit 120, as Python's own exit does."""
    import atexit

    def flush():
        nonlocal code
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except BrokenPipeError:          # the reader went away (| head): nothing more to say there
                pass
            except (OSError, ValueError):    # output lost: not a success
                code = code or 120

    try:
        flush()
        atexit._run_exitfuncs()
        flush()
    finally:
        os._exit(code)


def _run(argv: list[str] | None) -> tuple[int, str | None]:
    """Parse, then run the command: (exit code, the command's name or None before parsing).  The commands
    (and numpy, scipy, scikit-fem behind them) are imported inside the handlers, so a Ctrl-C during those
    imports (the first ~0.6 s) ends as cleanly as one during a run.  Run as the ``drivefem`` program (``argv`` None), an analysis command is
    one analysis in a fresh process: the compiled HB kernel only for large models (DRIVEFEM_JIT=large unless
    set, which its worker processes inherit; discrete.steady.hb.compiled_evaluation); the long-lived
    commands (:data:`LONG_LIVED`: many analyses in one process) and calls with ``argv`` (tests, a Python
    session) leave the process's setting as it is."""
    command = None
    try:
        args = build_parser().parse_args(argv)
        command = args.command
        if "DRIVEFEM_JIT" in os.environ:          # the user's (or a parent's) setting, checked before any work
            from discrete.steady.hb import jit_setting

            jit_setting()
        elif argv is None and args.command not in LONG_LIVED:
            os.environ["DRIVEFEM_JIT"] = "large"
        with warnings.catch_warnings():
            warnings.simplefilter("default")
            warnings.showwarning = _show_warning
            return args.func(args), command
    except ModelError as exc:
        print(f"drivefem: error: {exc}", file=sys.stderr)
        return 2, command
    except SolverError as exc:
        print(f"drivefem: solver failure: {exc}", file=sys.stderr)
        return 4, command
    except KeyboardInterrupt:
        print("drivefem: interrupted (files already written are kept)", file=sys.stderr)
        return EXIT_INTERRUPTED, command
    except BrokenPipeError:  # output piped into head & co.
        sys.stderr.close()
        return 0, command
    except MemoryError:
        print("drivefem: solver failure: out of memory (reduce elements, harmonics or points)", file=sys.stderr)
        return 4, command
    except Exception as exc:  # a bug: one line for the user, the traceback with DRIVEFEM_DEBUG=1
        if os.environ.get("DRIVEFEM_DEBUG"):
            traceback.print_exc()
        missing = exc.name if isinstance(exc, ImportError) else None
        if missing and missing.split(".")[0] not in ("fem", "discrete", "validation"):
            print(f"drivefem: error: the package {missing!r} is missing or broken ({exc}); the installation is "
                  "incomplete: run `make` again (or `pip install -e .` in the project's environment)", file=sys.stderr)
            return EXIT_INTERNAL, command
        tb = traceback.extract_tb(exc.__traceback__)[-1]
        print(f"drivefem: internal error: {type(exc).__name__}: {exc} (at {os.path.basename(tb.filename)}:{tb.lineno}; "
              "please report it with the model file; DRIVEFEM_DEBUG=1 shows the traceback)", file=sys.stderr)
        return EXIT_INTERNAL, command


if __name__ == "__main__":
    sys.exit(main())
