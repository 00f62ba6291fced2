"""The ``drivefem`` command line (design.md §5)."""
from __future__ import annotations

import argparse
import csv
import json
import sys
import tomllib
import warnings
from pathlib import Path

import numpy as np

from discrete.errors import ModelError, SolverError

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _write_json(data: dict, path: str | None) -> None:
    if path:
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        with open(path, "w") as fh:
            json.dump(data, fh, indent=2, default=_json_default)


def _json_default(o):
    if isinstance(o, (complex, np.complexfloating)):
        return [float(o.real), float(o.imag)]
    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


# ---------------------------------------------------------------- modal
def modal_report(mf, n_modes: int | None = None, shift: float | None = None):
    from discrete.linear.modal import modal_analysis

    an = mf.analysis
    if an.get("type", "modal") != "modal" and n_modes is None:
        n_modes = int(an.get("modes", 6))
    n = n_modes if n_modes is not None else an.get("modes", 6)
    tol = an.get("tolerance", 1e-5)
    sys_ = mf.linear_system()
    res = modal_analysis(sys_, n, shift=shift if shift is not None else an.get("shift"), tolerance=tol)
    return sys_, res


def print_modal(mf, sys_, res, out=sys.stdout) -> None:
    title = mf.title
    if mf.kind == "fe":
        m = mf.model
        head = f"{m.physics}" + (f" ({m.theory})" if m.physics == "bending" else "") + \
            f", {m.element_name}, {m.mass} mass, {mf.fe_model().mesh.n_elements} elements"
    else:
        head = f"lumped drive, {len(mf.model.bodies)} bodies"
    print(f"{title}\n{head}; {res.n_dofs} free DOFs; solver: {res.method}", file=out)
    print(f"{'mode':>4} {'f [Hz]':>14} {'omega [rad/s]':>14} {'residual':>9} {'RQ mism.':>9}  note", file=out)
    for r in range(res.omega_rad_s.size):
        note = "rigid-body" if res.rigid[r] else ("" if res.reliable[r] else "NOT RELIABLE (see warnings)")
        if res.reliable[r] or res.rigid[r]:
            f, w = f"{res.frequencies_hz[r]:14.6f}", f"{res.omega_rad_s[r]:14.6f}"
        else:
            f = w = f"{'--':>14}"
        print(f"{r + 1:4d} {f} {w} {res.residuals[r]:9.1e} {res.rayleigh_rel_diff[r]:9.1e}  {note}".rstrip(), file=out)
    if mf.kind == "lumped":
        bound = _dunkerley(mf)
        if bound is not None:
            print(f"Dunkerley's lower bound (4.40) of the first frequency: {bound:.6f} rad/s "
                  f"({100 * (bound / res.omega_rad_s[0] - 1):+.2f} %)", file=out)
    for wmsg in res.warnings:
        print(f"warning: {wmsg}", file=out)


def modal_json(mf, res) -> dict:
    d = res.to_dict()
    rel = res.reliable | res.rigid
    d["omega_rad_s"] = [v if ok else None for v, ok in zip(res.omega_rad_s.tolist(), rel)]
    d["frequencies_hz"] = [v if ok else None for v, ok in zip(res.frequencies_hz.tolist(), rel)]
    d["omega_rad_s_unverified"] = res.omega_rad_s.tolist()
    d["title"] = mf.title
    d["kind"] = mf.kind
    if mf.kind == "fe":
        fe = mf.fe_model()
        d["physics"] = fe.system.physics
        d["element"] = fe.model.element_name
        d["n_elements"] = fe.mesh.n_elements
        shapes = {}
        for fld in fe.model.fields:
            xs = None
            vals = []
            for r in range(res.omega_rad_s.size):
                xs, v = fe.nodal_values(res.shapes[:, r], fld)
                vals.append(v.tolist())
            shapes[fld] = {"x": xs.tolist(), "modes": vals}
        d["mode_shapes"] = shapes
    else:
        d["mode_shapes"] = {"dofs": mf.linear_system().labels(), "modes": res.shapes.T.tolist()}
        bound = _dunkerley(mf)
        if bound is not None:
            d["dunkerley_lower_bound_rad_s"] = bound
    return d


def _dunkerley(mf) -> float | None:
    """Dunkerley's lower bound (4.40) of the first frequency for grounded lumped models."""
    from discrete.dunkerley import dunkerley_bound

    sys_ = mf.linear_system()
    if sys_.rigid_modes is not None and sys_.rigid_modes.shape[1]:
        return None
    return dunkerley_bound(sys_)


def _drive_doc(path: str) -> dict | None:
    """The parsed file if it describes a drive of regular structure ([drive] table), else None."""
    from .drives import is_drive

    p = Path(path)
    if not p.is_file():
        return None
    try:
        with open(p, "rb") as fh:
            doc = tomllib.load(fh)
    except tomllib.TOMLDecodeError:
        return None
    return doc if is_drive(doc) else None


def cmd_modal(args) -> int:
    from .modelfile import load_model_file

    doc = _drive_doc(args.model)
    if doc is not None:
        from .drives import cli as drives_cli

        return drives_cli.run("modal", doc, modes=args.modes, json_path=args.json)
    mf = load_model_file(args.model)
    sys_, res = modal_report(mf, args.modes)
    print_modal(mf, sys_, res)
    _write_json(modal_json(mf, res), args.json)
    if args.vtu:
        from .export import write_modes

        print(f"wrote {write_modes(mf.fe_model(), res, args.vtu)}")
    if args.png:
        from .render import RenderUnavailable, render_modes

        try:
            for p in render_modes(mf.fe_model(), res, args.png):
                print(f"wrote {p}")
        except RenderUnavailable as exc:
            print(f"warning: no images: {exc}", file=sys.stderr)
            return 5
    if args.plot and mf.kind == "fe":
        from .plots import plot_mode_shapes

        Path(args.plot).parent.mkdir(parents=True, exist_ok=True)
        print(f"wrote {plot_mode_shapes(mf.fe_model(), res, args.plot)}")
    return 0 if (res.reliable | res.rigid).all() else 3


# --------------------------------------------------------------- forced
def forced_run(mf):
    from discrete.linear.harmonic import harmonic_response
    from .modelfile import parse_damping, parse_forced

    sys_ = mf.linear_system()
    spec = parse_forced(mf, sys_)
    return harmonic_response(sys_, spec.omegas, force=spec.force, base_motion=spec.base_motion,
                             damping=parse_damping(mf.doc), outputs=spec.outputs, method=spec.method,
                             n_modes=spec.n_modes)


def cmd_forced(args) -> int:
    from .modelfile import load_model_file

    doc = _drive_doc(args.model)
    if doc is not None:
        from .drives import cli as drives_cli

        return drives_cli.run("forced", doc, json_path=args.json, csv_path=args.csv)
    from discrete import steady

    doc = _read_toml(args.model)
    if steady.is_nonlinear_forced(doc):
        res = steady.run_forced(doc)
        print((doc.get("title", "") + "\n" if doc.get("title") else "") + res.table())
        _write_json(res.to_dict() | {"title": doc.get("title", "")}, args.json)
        if args.csv:
            steady.write_csv(res, args.csv)
            print(f"wrote {args.csv}")
        if args.plot:
            steady.plot_afc(res, args.plot)
            print(f"wrote {args.plot}")
        if not str(res.reason).startswith("reached"):
            print(f"continuation stopped early: {res.reason} (the partial branch is kept)", file=sys.stderr)
            return 1
        return 0
    mf = load_model_file(args.model)
    if mf.analysis.get("type") != "forced":
        raise ModelError("[analysis]", "type", mf.analysis.get("type"), "'forced' for drivefem forced")
    res = forced_run(mf)
    print(f"{mf.title}\nharmonic response: {res.method}; damping: {res.damping}")
    hdr = "".join(f" | {o:>24}" for o in res.outputs)
    print(f"{'f [Hz]':>12}{hdr}\n{'':>12}" + "".join(f" | {'amplitude':>12}{'lag [deg]':>12}" for _ in res.outputs))
    idx = np.arange(res.omega_rad_s.size)
    if idx.size > 40 and not args.all:
        idx = np.unique(np.linspace(0, idx.size - 1, 40).astype(int))
    for j in idx:
        row = "".join(f" | {res.amplitude[j, k]:12.5e}{res.phase_lag_deg[j, k]:12.3f}" for k in range(len(res.outputs)))
        print(f"{res.frequencies_hz[j]:12.5f}{row}")
    if idx.size < res.omega_rad_s.size:
        print(f"({res.omega_rad_s.size} frequencies; every {res.omega_rad_s.size // idx.size}th shown, --all for all)")
    _write_json(res.to_dict() | {"title": mf.title}, args.json)
    if args.csv:
        write_harmonic_csv(res, args.csv)
    if args.plot:
        from .plots import plot_frf

        print(f"wrote {plot_frf(res, args.plot, mf.title)}")
    return 0


def write_harmonic_csv(res, path) -> None:
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["f_hz", "omega_rad_s"] + [f"{o} {q}" for o in res.outputs for q in ("amplitude", "lag_deg", "re", "im")])
        for j in range(res.omega_rad_s.size):
            row = [res.frequencies_hz[j], res.omega_rad_s[j]]
            for k in range(len(res.outputs)):
                z = res.response[j, k]
                row += [abs(z), res.phase_lag_deg[j, k], z.real, z.imag]
            w.writerow(row)


def cmd_compare(args) -> int:
    from .drives import cli as drives_cli

    doc = _drive_doc(args.model)
    if doc is None:
        raise ModelError(str(args.model), "drive", None, "a model file with a [drive] table (drive of regular structure)")
    return drives_cli.run("compare", doc, json_path=args.json)


# ------------------------------------------------------------- simulate
def cmd_simulate(args) -> int:
    from .modelfile import load_model_file

    doc = _read_toml(args.model)
    from . import hybrid

    if hybrid.is_hybrid(doc):
        result = hybrid.run_model_file(doc)
        d = result.to_dict()
        _print_simulation(doc.get("title", ""), d)
        _write_json(d, args.json)
        if args.csv:
            print(f"wrote {hybrid.write_csv(result, args.csv)}")
        if args.png:
            for p in hybrid.plot_result(result, args.png):
                print(f"wrote {p}")
        return 1 if d.get("stopped_early") else 0
    mf = load_model_file(args.model)
    try:
        from discrete import nonsmooth
    except ImportError as exc:  # pragma: no cover - present once the nonsmooth solver lands
        raise SolverError("time simulation is not available in this build") from exc
    result = nonsmooth.run_model_file(mf.doc)
    d = result.to_dict()
    _print_simulation(mf.title, d)
    _write_json(d, args.json)
    if args.csv:
        nonsmooth.write_csv(result, args.csv)
    if args.png:
        for p in nonsmooth.plot_result(result, args.png):
            print(f"wrote {p}")
    return 1 if d.get("stopped_early") else 0


def _read_toml(path: str) -> dict:
    p = Path(path)
    if not p.is_file():
        raise ModelError("", "model file", str(p), "an existing TOML file")
    try:
        with open(p, "rb") as fh:
            return tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise ModelError(str(p), "TOML", str(exc), "valid TOML syntax") from exc


def _print_simulation(title: str, d: dict) -> None:
    counts = ", ".join(f"{n} {k}" for k, n in sorted(d.get("event_counts", {}).items()))
    print(f"{title}\nsimulated to t = {d.get('t_end')} ({d.get('method', '')}); {len(d.get('events', []))} events"
          + (f" ({counts})" if counts else "") + f"; period = {d.get('period')}; energy error = {d.get('energy_error')}")
    red = d.get("reduction")
    if red:
        print(f"reduction: {red.get('method')}, {red.get('retained_modes')} modes, highest retained frequency "
              f"{red.get('highest_frequency_hz', float('nan')):.6g} Hz, suggested time step "
              f"{red.get('suggested_time_step_s', float('nan')):.3g} s; restitution at coupling DOFs: "
              + ", ".join(f"{c} {100 * r:.1f} %" for c, r in zip(red.get("coupling_dofs", []), red.get("restitution", []))))
    for wmsg in d.get("warnings", []):
        print(f"warning: {wmsg}")
    if d.get("stopped_early"):
        print(f"stopped early: {d.get('reason')}")


# ---------------------------------------------------------------- sweep
def cmd_sweep(args) -> int:
    from .sweep import run_sweep

    return run_sweep(args.model, scheduler=args.scheduler, resume=args.resume, out=args.out,
                     json_path=args.json, workers=args.workers)


# ------------------------------------------------------------- validate
def cmd_validate(args) -> int:
    from validation.report import print_table, run_validation, write_report

    outcomes = run_validation(args.case or None, include_slow=not args.fast, progress=not args.quiet)
    print_table(outcomes)
    data = {"cases": [c.to_dict() | {"case": o.case.name} for o in outcomes for c in o.checks],
            "errors": {o.case.name: o.error for o in outcomes if o.error},
            "passed": all(o.passed for o in outcomes)}
    _write_json(data, args.json)
    if args.report:
        print(f"wrote {write_report(outcomes, args.report)}")
    return 0 if data["passed"] else 1


# --------------------------------------------------------------- render
def cmd_render(args) -> int:
    from .render import render_model_file

    modes = [int(m) for m in args.mode] if args.mode else None
    rep = render_model_file(args.model, args.out, n_modes=args.modes, gif=args.gif, modes=modes)
    for p in rep.data_files + rep.images:
        print(f"wrote {p}")
    print(rep.message)
    return 0 if rep.rendered else 5


# ----------------------------------------------------------------- demo
def cmd_demo(args) -> int:
    from .demo import run_demo

    return run_demo(Path(args.out))


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="drivefem", description="FE and lumped models of machine drives: modal, "
                                "forced and nonsmooth time analyses, validated against the textbook.")
    sub = p.add_subparsers(dest="command", required=True)
    m = sub.add_parser("modal", help="natural frequencies and mode shapes")
    m.add_argument("model")
    m.add_argument("--modes", type=int, default=None, help="number of modes (default: [analysis] modes or 6)")
    m.add_argument("--json", help="write the JSON result here")
    m.add_argument("--plot", help="write a PNG line plot of the mode shapes here (FE models)")
    m.add_argument("--vtu", help="write the mode shapes to this VTU or XDMF file (FE models)")
    m.add_argument("--png", help="render one PNG per mode off-screen into this directory (FE models)")
    m.set_defaults(func=cmd_modal)
    r = sub.add_parser("render", help="off-screen PNG (and GIF) pictures of the mode shapes, plus VTU/CSV/JSON data")
    r.add_argument("model")
    r.add_argument("--modes", type=int, default=None, help="number of modes (default: [analysis] modes or 6)")
    r.add_argument("--mode", action="append", help="render only this mode number (repeatable)")
    r.add_argument("--out", required=True, help="output directory")
    r.add_argument("--gif", action="store_true", help="also write an animated GIF per mode")
    r.set_defaults(func=cmd_render)
    f = sub.add_parser("forced", help="harmonic response / FRF ([analysis] type = 'forced')")
    f.add_argument("model")
    f.add_argument("--json")
    f.add_argument("--csv")
    f.add_argument("--plot", help="write a PNG of amplitude and phase here")
    f.add_argument("--all", action="store_true", help="print every frequency")
    f.set_defaults(func=cmd_forced)
    c = sub.add_parser("compare", help="a [drive] model by the discrete, transfer-matrix and continuum methods")
    c.add_argument("model")
    c.add_argument("--json")
    c.set_defaults(func=cmd_compare)
    s = sub.add_parser("simulate", help="time simulation of a drive with nonsmooth elements")
    s.add_argument("model")
    s.add_argument("--json")
    s.add_argument("--csv")
    s.add_argument("--png", help="directory for time plots and phase portraits")
    s.set_defaults(func=cmd_simulate)
    w = sub.add_parser("sweep", help="evaluate a grid of parameter points ([sweep] table) on Dask")
    w.add_argument("model")
    w.add_argument("--scheduler", help="address of an existing dask.distributed scheduler (default: local cluster)")
    w.add_argument("--resume", help="directory of a previous sweep: points already done are not recomputed")
    w.add_argument("--out", help="directory for the per-point results (default: next to --json or ./sweep-<model>)")
    w.add_argument("--json", help="write the collected results here")
    w.add_argument("--workers", type=int, default=None, help="local workers (0: serial, no Dask)")
    w.set_defaults(func=cmd_sweep)
    v = sub.add_parser("validate", help="run the validation catalogue")
    v.add_argument("--case", action="append", help="case or group name (repeatable)")
    v.add_argument("--report", help="directory for the report (markdown, JSON, plots)")
    v.add_argument("--json")
    v.add_argument("--fast", action="store_true", help="skip the slow cases")
    v.add_argument("--quiet", action="store_true", help="no progress bar")
    v.set_defaults(func=cmd_validate)
    d = sub.add_parser("demo", help="run representative examples end to end into ./drivefem-demo/")
    d.add_argument("--out", default="drivefem-demo")
    d.set_defaults(func=cmd_demo)
    return p


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("default")
            return args.func(args)
    except ModelError as exc:
        print(f"drivefem: error: {exc}", file=sys.stderr)
        return 2
    except SolverError as exc:
        print(f"drivefem: solver failure: {exc}", file=sys.stderr)
        return 4
    except BrokenPipeError:  # output piped into head & co.
        sys.stderr.close()
        return 0


if __name__ == "__main__":
    sys.exit(main())
