"""One function per ``drivefem`` command: load the model once, run the analysis of its kind, write
the outputs through the output layer, return the exit code (documented in docs/cli.md):

0 done; 1 done but incomplete (a run or continuation stopped early, a sweep point failed, a
validation case failed); 2 bad input (model, options, paths); 3 modes not reliable in double
precision; 4 solver failure (including a result that became non-finite); 5 pictures not rendered
(no off-screen OpenGL); 130 interrupted (Ctrl-C; what was written is kept)."""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from discrete.errors import ModelError

from ..output import columns, contract, tables, write_json
from ..output.jsonio import encode
from ..study import Study
from .exit_codes import EXIT_INTERRUPTED
from .progress import count_bar, progress_bar


def count_option(args, attr: str, low: int, high: int, what: str) -> None:
    """An integer option (``--modes``, ``--mode``, ``--workers``; a list for a repeatable one) in [low, high]
    before any work starts: ModelError naming the option otherwise."""
    values = getattr(args, attr, None)
    for v in values if isinstance(values, list) else [values]:
        if v is not None and not low <= v <= high:
            raise ModelError("command line", "--" + attr, v, f"an integer from {low} to {high:.0f} ({what})")


def max_workers() -> int:
    """The most local sweep workers (processes) allowed: four per CPU."""
    import os

    return 4 * (os.cpu_count() or 1)


def _outputs(args, command: str, **kinds) -> dict:
    """Everything checked before any work starts (:func:`fem.app.options.prepare`): old spellings,
    ``--quiet``, every output path (``attr=kind``), plotly for ``--html``."""
    from .options import prepare

    return prepare(args, command, **kinds)


def _emit(args, command: str, study, data: dict) -> dict:
    """Encode (refusing non-finite numbers) and write the JSON document; returns it."""
    doc = encode(contract.payload(command, study, data))
    if getattr(args, "json", None):
        write_json(args.json, doc, encoded=True)
    return doc


# ---------------------------------------------------------------- modal
def modal(args) -> int:
    _outputs(args, "modal", json="json", plot="plot", vtu="mesh", render="dir", csv="csv")
    count_option(args, "modes", 1, max_modes(), "the number of modes")
    study = Study.load(args.model)
    if (args.vtu or args.render or args.plot) and study.kind != "fe":
        opt = "--vtu" if args.vtu else ("--render" if args.render else "--plot")
        raise ModelError("command line", opt, getattr(args, opt[2:]), "an FE or rotor model file (mode-shape files "
                         f"and pictures are drawn for [[segment]] and [rotor] models; this is a {study.kind} model)")
    res = study.modal(args.modes)
    data = contract.modal_data(study, res)
    if study.kind in ("lumped", "hybrid"):
        data["linearisation"] = contract.linearisation_data(study)
    shapes = study.outputs(res)
    contract.with_outputs(data, shapes)
    if study.kind == "lumped":
        bound = _dunkerley(study)
        if bound is not None:
            data["dunkerley_lower_bound_rad_s"] = bound
    _emit(args, "modal", study, data)
    tables.modal_table(study, res)
    tables.linearisation_lines(data.get("linearisation"))
    tables.outputs_lines(data)
    if getattr(args, "csv", None):
        columns.write(args.csv, columns.modal(res, shapes))
        print(f"wrote {args.csv}")
    if study.kind == "lumped" and data.get("dunkerley_lower_bound_rad_s") is not None:
        print(tables.dunkerley_line(data["dunkerley_lower_bound_rad_s"], res.omega_rad_s[0]))
    if study.kind == "drive":
        return 0 if res.ok else 3
    if args.vtu:
        from ..output.mesh import write_modes

        print(f"wrote {write_modes(study.fe_model, res, args.vtu)}")
    if args.plot:
        from ..output.figures import plot_mode_shapes

        print(f"wrote {plot_mode_shapes(study.fe_model, res, args.plot, title=study.title)}")
    if args.render:
        from ..render import RenderUnavailable, render_modes

        try:
            with count_bar("render", "images") as update:
                written = render_modes(study.fe_model, res, args.render, progress=update)
            for p in written:
                print(f"wrote {p}")
        except RenderUnavailable as exc:
            print(f"warning: no images: {exc}", file=sys.stderr)
            return 5
    return 0 if (res.reliable | res.rigid).all() else 3


def max_modes() -> int:
    from ..modelfile import budget

    return int(budget.MAX_MODES * budget.scale())


def _dunkerley(study) -> float | None:
    """Dunkerley's lower bound (4.40) of the first frequency of a grounded lumped model."""
    from discrete.dunkerley import dunkerley_bound

    sys_ = study.linear_model.system
    if sys_.rigid_modes is not None and sys_.rigid_modes.shape[1]:
        return None
    return dunkerley_bound(sys_)


# --------------------------------------------------------------- forced
def forced(args) -> int:
    given = _outputs(args, "forced", json="json", csv="csv", plot="plot", html="html")
    study = Study.load(args.model)
    if study.is_steady():
        w0, w1 = study.doc.steady.range
        with progress_bar(w0, w1, "continuation", "rad/s") as update:
            res = study.forced(progress=update)
    else:
        res = study.forced()
    data = contract.forced_data(study, res)
    if study.kind in ("lumped", "hybrid"):
        data["linearisation"] = contract.linearisation_data(study) if not data["steady"] else None
    loads = study.outputs(res)
    contract.with_outputs(data, loads)
    _emit(args, "forced", study, data)
    tables.forced_table(study, res, all_rows=args.all)
    tables.linearisation_lines(data.get("linearisation"))
    tables.outputs_lines(data)
    if "periodic" in data:
        per = data["periodic"]
        print(f"periodic load, period {per['period']:g} s, {per['harmonics']} harmonics: peak |q| over a period "
              + ", ".join(f"{o} {p:.6g}" for o, p in zip(data["outputs"], per["peak"])))
    steady = data["steady"]
    if args.csv:
        table = columns.afc(res, loads) if steady else (columns.drive_forced(res) if study.kind == "drive"
                                                        else columns.harmonic(res, loads))
        columns.write(args.csv, table)
        print(f"wrote {args.csv}")
    if args.plot:
        from ..output.figures import plot_afc, plot_frf, plot_output_amplitudes

        one, folder = given["plot"]
        if folder is not None:
            folder.mkdir(parents=True, exist_ok=True)
        main = one or folder / ("afc.png" if steady else "frf.png")
        if steady:
            plot_afc(res, main, title=study.title or None)
            print(f"wrote {main}")
        else:
            print(f"wrote {plot_frf(res, main, study.title)}")
        if folder is not None and loads is not None and not isinstance(loads, dict) and loads.channels:
            print(f"wrote {plot_output_amplitudes(loads, folder / 'loads.png', study.title)}")
    if args.html:
        from ..output.html import afc_html, frf_html

        print(f"wrote {(afc_html if steady else frf_html)(res, args.html, title=study.title)}")
    if steady and res.stop_cause == "interrupted":
        print(f"continuation {res.reason}", file=sys.stderr)
        return EXIT_INTERRUPTED
    if steady and not res.completed:
        print(f"continuation stopped early: {res.reason} (the partial branch is kept)", file=sys.stderr)
        return 1
    if not steady and not np.all(data.get("reliable", True)):
        return 3                 # a response not reliable in double precision (flagged in the table and the JSON)
    return 0


# ------------------------------------------------------------- compare
def compare(args) -> int:
    _outputs(args, "compare", json="json")
    study = Study.load(args.model)
    if study.kind != "drive":
        raise ModelError(str(args.model), "drive", None, "a model file with a [drive] table (drive of regular structure)")
    res = study.compare()
    _emit(args, "compare", study, res.to_dict())
    print((study.title + "\n" if study.title else "") + res.table())
    return 0


# ------------------------------------------------------------- simulate
def simulate(args) -> int:
    _outputs(args, "simulate", json="json", csv="csv", plot="plot", h5="h5", html="html")
    study = Study.load(args.model)
    if study.kind not in ("lumped", "hybrid"):
        raise ModelError(str(args.model), "simulation", None, "a lumped or hybrid model file with a [simulation] table "
                         f"(this is a {study.kind} model)")
    with progress_bar(0.0, study.simulation_settings()["t_end"], "simulate", "s") as update:
        res = study.simulate(progress=update)
    outs = study.outputs(res)
    solver = res.solver if study.kind == "hybrid" else res
    every = study.doc.simulation.record_every
    idx = None
    if every > 1:
        from ..loads.analyses import decimate

        idx = decimate(solver.t, every, [e.t for e in solver.events])
    history = None
    if getattr(args, "h5", None):
        history = {"file": str(args.h5), "samples": int(solver.t.size if idx is None else idx.size),
                   "record_every": int(every)}
    d = _emit(args, "simulate", study, contract.simulate_data(study, res, outs, history))
    tables.simulation_summary(study.title, d)
    tables.outputs_lines(d)
    if args.csv:
        if getattr(study.doc, "output", None):
            table = columns.selected_outputs(solver.t, outs, idx)
        elif study.kind == "hybrid":
            table = columns.hybrid(res, outs)
        else:
            table = columns.time_history(res, outs, idx)
        columns.write(args.csv, table)
        print(f"wrote {args.csv}")
    if getattr(args, "h5", None):
        from ..output.history import write_history

        sel = np.arange(solver.t.size) if idx is None else idx
        has_e = solver.energy.size == solver.t.size
        names, X, V = _solved_states(study, solver)
        write_history(args.h5, command="simulate", title=study.title, kind=study.kind, t=solver.t[sel],
                      outputs=outs.take(sel), states=(names, X[:, sel], V[:, sel]),
                      energy=(solver.energy[sel], solver.work[sel]) if has_e else None, events=solver.events,
                      record_every=every, n_recorded=solver.t.size)
        print(f"wrote {args.h5}")
    if args.plot:
        from ..output.figures import plot_hybrid, plot_time_history

        if study.kind == "hybrid":
            paths = plot_hybrid(res, args.plot, outputs=outs, title=study.title)
        else:
            paths = plot_time_history(res, args.plot, outputs=outs, title=study.title)
        for p in paths:
            print(f"wrote {p}")
    if args.html:
        from ..output.html import simulation_html

        print(f"wrote {simulation_html(res, outs, args.html, title=study.title)}")
    if str(d.get("reason", "")).startswith("interrupted"):
        return EXIT_INTERRUPTED
    return 1 if d.get("stopped_early") else 0


def _solved_states(study, solver):
    """(names, x, v) of the solved coordinates of a run (drivers included)."""
    return list(solver.names), solver.x, solver.v


# ---------------------------------------------------------------- sweep
def sweep(args) -> int:
    from .sweep import run_sweep

    _outputs(args, "sweep", json="json", out="dir", resume="dir")
    count_option(args, "workers", 0, max_workers(), "local worker processes; 0: serial, without Dask")
    return run_sweep(args.model, scheduler=args.scheduler, resume=args.resume, out=args.out, json_path=args.json,
                     workers=args.workers)


# ------------------------------------------------------------- validate
def validate(args) -> int:
    from validation.report import print_table, run_validation, write_report

    _outputs(args, "validate", json="json", report="dir")
    with count_bar("validation", "cases") as update:
        outcomes = run_validation(args.case or None, include_slow=not args.fast, progress=update)
    print_table(outcomes)
    data = {"cases": [c.to_dict() | {"case": o.case.name} for o in outcomes for c in o.checks],
            "errors": {o.case.name: o.error for o in outcomes if o.error},
            "passed": all(o.passed for o in outcomes)}
    if args.json:
        write_json(args.json, contract.payload("validate", None, data))
    if args.report:
        print(f"wrote {write_report(outcomes, args.report)}")
    return 0 if data["passed"] else 1


# --------------------------------------------------------------- render
def render(args) -> int:
    from ..render import render_study

    _outputs(args, "render", render="dir")
    count_option(args, "modes", 1, max_modes(), "the number of modes")
    count_option(args, "mode", 1, max_modes(), "a mode number")
    if args.render is None:
        raise ModelError("command line", "--render", None, "a directory for the pictures and their data files "
                         "(drivefem render MODEL --render DIR)")
    study = Study.load(args.model)
    modes = [int(m) for m in args.mode] if args.mode else None
    with count_bar("render", "images") as update:
        rep = render_study(study, args.render, n_modes=args.modes, gif=args.gif, modes=modes, progress=update)
    for p in rep.data_files + rep.images:
        print(f"wrote {p}")
    print(rep.message)
    return 0 if rep.rendered else 5


# --------------------------------------------------------------- schema
def schema(args) -> int:
    from ..modelfile.load import dumps_schema

    _outputs(args, "schema", out="json")
    text = dumps_schema(args.kind)
    if args.out:
        Path(args.out).write_text(text)
        print(f"wrote {args.out}")
    else:
        sys.stdout.write(text)
    return 0


# ----------------------------------------------------------------- demo
def demo(args, run_command) -> int:
    """``drivefem demo``: ``run_command`` is the command line's ``main`` (each example runs through it)."""
    from .demo import run_demo

    _outputs(args, "demo", out="dir", gallery="dir")
    return run_demo(Path(args.out), run_command, gallery=Path(args.gallery) if args.gallery else None,
                    quiet=args.quiet)
