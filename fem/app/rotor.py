"""The commands on rotor model files (kind ``rotor``, a ``[rotor]`` table):

* ``drivefem modal ROTOR [--modes N] [--json F] [--plot F] [--png DIR]``: complex modes at the speed of
  ``[analysis]`` (damped frequencies, log decrement, whirl); ``--plot`` the orbits of the first
  flexible mode, ``--png`` an off-screen 3D whirl picture per lateral mode;
* ``drivefem forced ROTOR [--json F] [--csv F] [--plot F|DIR] [--html F] [--all]``: unbalance response of
  ``[unbalance_response]`` and ``[[unbalance]]`` (peaks with AF and separation margins); ``--plot
  bode.png`` the Bode plot, ``--plot DIR`` the Bode plot and a polar plot per probe;
* ``drivefem campbell ROTOR [--modes N] [--json F] [--plot F] [--csv F] [--html F]``: Campbell diagram
  of ``[campbell]``: critical speeds (forward crossings) and backward crossings apart;
* ``drivefem simulate ROTOR [--json F] [--csv F] [--png DIR]``: the run-up of ``[run_up]`` with the
  ``[[rub]]`` clearances and ``[[unbalance]]`` (orbits, rub forces and regimes, events, energy
  balance); exit 1 when the run stopped early (the reason is printed).

``modal`` and ``forced`` keep their meaning for the other kinds: :func:`add_parser` routes a file
with a ``[rotor]`` table here and every other file to :mod:`fem.app.commands`.  Exit codes as for
every command (0 done, 2 bad input, 3 modes not reliable, 4 solver failure, 5 no off-screen
pictures)."""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from discrete.errors import ModelError

from ..output import columns, contract, tables, write_csv
from .commands import _emit, count_option, max_modes
from .commands import _outputs as _check_outputs

RPM = 30.0 / np.pi


def add_parser(subparsers) -> None:
    """Register ``drivefem campbell`` and route ``modal``/``forced``/``simulate`` of rotor files here."""
    p = subparsers.add_parser("campbell", help="Campbell diagram and critical speeds of a [rotor] model file")
    p.add_argument("model")
    p.add_argument("--modes", type=int, default=None, help="tracked modes (default: [campbell] modes, "
                   "[analysis] modes or 6)")
    from .options import add_outputs

    add_outputs(p, "campbell", json="the diagram (schema drivefem.campbell)", csv="the diagram, one row per speed",
                plot=True, html="the diagram", old={"--png": "--plot FILE"})
    p.set_defaults(func=campbell)
    for name, rotor_command in (("modal", modal), ("forced", forced), ("simulate", simulate)):
        sp = subparsers.choices[name]
        sp.set_defaults(func=_routed(sp.get_default("func"), rotor_command))


def _routed(other, rotor_command):
    def run(args) -> int:
        return rotor_command(args) if is_rotor_file(args.model) else other(args)

    run.__doc__ = other.__doc__
    return run


def is_rotor_file(path) -> bool:
    """Whether the file has a top-level [rotor] table (read as TOML only; validated by the command)."""
    from ..modelfile.source import read_toml

    try:
        return "rotor" in read_toml(path)
    except ModelError:
        return False            # the other command reports the unreadable file


def _load(path):
    from ..study import Study

    return Study.load(path)


def _linear_note(study) -> None:
    """Linear analyses see the rotor free of contact: say so when the file has [[rub]] clearances."""
    if getattr(study.doc, "rub", None):
        print(f"note: the {len(study.doc.rub)} [[rub]] clearance(s) act only in drivefem simulate; this linear "
              "analysis sees the rotor free of contact", file=sys.stderr)


def _rub_records(study) -> list | None:
    """The linearisation record of the [[rub]] clearances (open: the linear analyses see no contact)."""
    rubs = getattr(study.doc, "rub", None) or []
    return [{"element": r.name or f"rub {i} at x = {r.x:g} m", "kind": "rub", "state": "open", "declared": False,
             "note": "open: no contact (the clearance acts only in drivefem simulate)"}
            for i, r in enumerate(rubs, 1)] or None


# ---------------------------------------------------------------- modal
def modal(args) -> int:
    _check_outputs(args, "modal", json="json", plot="plot", render="dir", csv="csv", vtu="mesh")
    count_option(args, "modes", 1, max_modes(), "the number of modes")
    if getattr(args, "vtu", None):
        raise ModelError("command line", "--vtu", args.vtu, "--json, --csv, --plot (orbits) or --render (3D whirl "
                         "pictures) for a rotor model file")
    study = _load(args.model)
    _linear_note(study)
    res = study.modal(args.modes)
    shapes = study.outputs(res)
    data = contract.with_outputs(contract.modal_data(study, res) | {"linearisation": _rub_records(study)}, shapes)
    _emit(args, "modal", study, data)
    modal_table(study, res)
    tables.outputs_lines(data)
    if getattr(args, "csv", None):
        columns.write(args.csv, columns.modal(res, shapes))
        print(f"wrote {args.csv}")
    if args.plot:
        from ..rotor.plots import plot_mode_orbits

        flexible = [r for r in range(res.n_modes) if not res.rigid[r] and res.kind[r] == "lateral"]
        if flexible:
            print(f"wrote {plot_mode_orbits(res, flexible[0], args.plot, title=study.title)}")
        else:
            print("warning: no lateral flexible mode: no orbit plot", file=sys.stderr)
    if args.render:
        from pathlib import Path

        from ..render import RenderUnavailable
        from ..rotor.render import render_whirl
        from .progress import count_bar

        out = Path(args.render)
        out.mkdir(parents=True, exist_ok=True)
        picks = [r for r in range(res.n_modes) if not res.rigid[r] and res.kind[r] == "lateral"]  # whirl to draw
        try:
            with count_bar("render", "images") as update:
                for k, r in enumerate(picks):
                    print(f"wrote {render_whirl(study.rotor, res, r, out / f'mode_{r + 1}_{res.whirl[r]}.png', title=study.title)}")
                    update(k + 1, len(picks))
        except RenderUnavailable as exc:
            print(f"warning: no images: {exc}", file=sys.stderr)
            return 5
    return 0 if (res.reliable | res.rigid).all() else 3


def modal_table(study, res, out=None) -> None:
    out = sys.stdout if out is None else out
    rs = study.rotor
    print(f"{study.title}\nrotor: {rs.rotor.n_elements} Timoshenko elements, {rs.n_dofs - rs.constrained.size} free DOFs "
          f"({rs.rotor.dofs}); speed {res.speed_rad_s:.6g} rad/s = {res.speed_rad_s * RPM:.6g} rev/min; "
          f"solver: {res.method}", file=out)
    print(f"{'mode':>4} {'omega_d [rad/s]':>15} {'f_d [Hz]':>12} {'zeta':>10} {'log dec':>10} {'kind':>8} "
          f"{'whirl':>9} {'residual':>9}  note", file=out)
    ld = res.log_decrement
    for r in range(res.n_modes):
        note = "rigid-body" if res.rigid[r] else ("" if res.reliable[r] else "NOT RELIABLE (see warnings)")
        if not res.rigid[r] and res.eigenvalues[r].imag == 0:
            note = (note + "; " if note else "") + f"overdamped (real eigenvalue {res.eigenvalues[r].real:.6g} 1/s)"
        if res.reliable[r] or res.rigid[r]:
            w, f = f"{res.omega_damped_rad_s[r]:15.6f}", f"{res.frequencies_hz[r]:12.6f}"
        else:
            w, f = f"{'--':>15}", f"{'--':>12}"
        lds = f"{ld[r]:10.5f}" if np.isfinite(ld[r]) else f"{'overdamped':>10}"
        print(f"{r + 1:4d} {w} {f} {res.damping_ratio[r]:10.5f} {lds} {res.kind[r]:>8} {res.whirl[r]:>9} "
              f"{res.residuals[r]:9.1e}  {note}".rstrip(), file=out)
    for w in res.warnings:
        print(f"warning: {w}", file=out)


# --------------------------------------------------------------- forced
def _file_name(text: str) -> str:
    import re

    return re.sub(r"[^A-Za-z0-9.-]+", "_", text).strip("_") or "probe"


def forced(args) -> int:
    given = _check_outputs(args, "forced", json="json", csv="csv", plot="plot", html="html")
    study = _load(args.model)
    _linear_note(study)
    res = study.forced()
    loads = study.outputs(res)
    data = contract.with_outputs(contract.forced_data(study, res) | {"linearisation": _rub_records(study)}, loads)
    _emit(args, "forced", study, data)
    forced_table(study, res, all_rows=args.all)
    tables.outputs_lines(data)
    if args.csv:
        write_csv(args.csv, *response_columns(res, loads))
        print(f"wrote {args.csv}")
    if args.plot:
        from ..rotor.plots import plot_bode, plot_polar, probe_label

        one, folder = given["plot"]
        if folder is not None:
            folder.mkdir(parents=True, exist_ok=True)
        if one is not None:
            print(f"wrote {plot_bode(res, one, title=study.title)}")
        else:
            print(f"wrote {plot_bode(res, folder / 'bode.png', title=study.title)}")
            for j, p in enumerate(res.probes):
                name = _file_name(probe_label(p))
                print(f"wrote {plot_polar(res, folder / f'polar_{j + 1}_{name}.png', j, title=study.title)}")
        if loads is not None and loads.channels:
            from ..output.figures import plot_output_amplitudes

            path = (one.with_name(one.stem + "_loads" + (one.suffix or ".png")) if one is not None
                    else folder / "loads.png")
            print(f"wrote {plot_output_amplitudes(loads, path, study.title)}")
    if getattr(args, "html", None):
        from ..output.html import bode_html

        print(f"wrote {bode_html(res, args.html, title=study.title)}")
    return 0 if all(p.resolved for p in res.peaks) else 3      # an undamped peak: not a property of the rotor


def forced_table(study, res, all_rows: bool = False, out=None) -> None:
    out = sys.stdout if out is None else out
    print(f"{study.title}\nunbalance response: {res.method}", file=out)
    hdr = "".join(f" | {p.label[:22]:>22}" for p in res.probes)
    print(f"{'rev/min':>10} {'rad/s':>10}{hdr}\n{'':>21}" + "".join(f" | {'amp [m]':>11}{'lag':>11}" for _ in res.probes),
          file=out)
    s = res.speeds_rad_s
    idx = np.arange(s.size)
    if idx.size > 40 and not all_rows:
        idx = np.unique(np.linspace(0, idx.size - 1, 40).astype(int))
    for j in idx:
        row = "".join(f" | {p.amplitude[j]:11.4e}{p.phase_lag_deg[j]:11.2f}" for p in res.probes)
        print(f"{s[j] * RPM:10.2f} {s[j]:10.4f}{row}", file=out)
    if idx.size < s.size:
        print(f"({s.size} speeds; every {s.size // idx.size}th shown, --all for all)", file=out)
    for pk in res.peaks:
        p = res.probes[pk.probe]
        af = "n/a" if pk.amplification_factor is None else f"{pk.amplification_factor:.2f}"
        sm = "" if pk.separation_margin is None else f", separation margin {pk.separation_margin:.1f} %"
        req = "" if pk.required_margin is None else f" (required {pk.required_margin:.1f} %: " + \
            ("ok" if pk.passes else "FAILS") + ")"
        print(f"peak at {pk.speed_rad_s * RPM:.2f} rev/min ({pk.speed_rad_s:.4f} rad/s), {p.label}: "
              f"{pk.amplitude:.4e} m, AF {af}{sm}{req}" + (f"; {pk.note}" if pk.note else ""), file=out)
    for w in res.warnings:
        print(f"warning: {w}", file=out)


def response_columns(res, loads=None) -> tuple[list[str], list]:
    """CSV: speed (rev/min, rad/s), then amplitude, lag, Re, Im of every probe and of every named output
    (bearing reactions, section loads: ``loads``, :class:`fem.loads.analyses.NamedOutputs`)."""
    head = ["speed_rpm", "speed_rad_s"] + [f"{p.label} {q}" for p in res.probes
                                           for q in ("amplitude", "lag_deg", "re", "im")]
    names = loads.names if loads is not None else []
    head += [f"{n} {q}" for n in names for q in ("amplitude", "lag_deg", "re", "im")]
    rows = []
    for j, s in enumerate(res.speeds_rad_s):
        row = [s * RPM, s]
        for p in res.probes:
            row += [p.amplitude[j], p.phase_lag_deg[j], p.value[j].real, p.value[j].imag]
        for k in range(len(names)):
            z = complex(loads.values[k, j])
            row += [abs(z), float(np.mod(-np.degrees(np.angle(z)), 360.0)), z.real, z.imag]
        rows.append(row)
    return head, rows


# ------------------------------------------------------------- campbell
def campbell(args) -> int:
    _check_outputs(args, "campbell", json="json", plot="plot", csv="csv", html="html")
    count_option(args, "modes", 1, max_modes(), "the number of tracked modes")
    study = _load(args.model)
    if study.kind != "rotor":
        raise ModelError(str(args.model), "rotor", None, f"a model file with a [rotor] table (this is a {study.kind} "
                         "model)")
    _linear_note(study)
    from ..modelfile.build.rotor import operating_range
    from .progress import count_bar

    op = operating_range(study.doc)
    with count_bar("campbell", "solves") as update:
        camp = study.campbell(args.modes, progress=update)
    loads = study.outputs(camp)
    data = contract.with_outputs(contract.campbell_data(study, camp) | {"linearisation": _rub_records(study)}, loads)
    data["operating_range_rad_s"] = None if op is None else list(op)
    _emit(args, "campbell", study, data)
    campbell_table(study, camp)
    tables.outputs_lines(data)
    if args.csv:
        write_csv(args.csv, *campbell_columns(camp, loads))
        print(f"wrote {args.csv}")
    figure = args.plot
    if figure:
        from ..rotor.plots import plot_campbell

        print(f"wrote {plot_campbell(camp, figure, title=study.title, operating_range=op)}")
    if getattr(args, "html", None):
        from ..output.html import campbell_html

        print(f"wrote {campbell_html(camp, args.html, title=study.title, operating_range=op)}")
    for w in camp.warnings:
        print(f"drivefem: warning: {w}", file=sys.stderr)
    return 0


def _crossing_line(c, label: str) -> str:
    ld = "n/a" if not np.isfinite(c.log_decrement) else f"{c.log_decrement:.4f}"
    return (f"{label} (order {c.order:g}): {c.speed_rpm:.3f} rev/min = {c.speed_rad_s:.5f} rad/s, mode "
            f"{c.mode + 1} ({c.kind}, {c.whirl} whirl), log dec {ld}, MAC {c.mac:.3f}")


def campbell_table(study, camp, out=None) -> None:
    out = sys.stdout if out is None else out
    s = camp.speeds_rad_s
    print(f"{study.title}\nCampbell diagram: {camp.n_modes} tracked modes over {s.size} speeds "
          f"[{s[0] * RPM:.6g}, {s[-1] * RPM:.6g}] rev/min; worst tracking MAC {camp.mac_min.min():.3f}, "
          f"max residual {camp.residual_max.max():.1e}", file=out)
    print(f"{'mode':>4} {'kind':>8} {'whirl':>9} {'f_d at start [Hz]':>18} {'f_d at end [Hz]':>16}", file=out)
    for j in range(camp.n_modes):
        w = max(set(row[j] for row in camp.whirl), key=[row[j] for row in camp.whirl].count)
        print(f"{j + 1:4d} {camp.kind[j]:>8} {w:>9} {camp.omega_damped_rad_s[0, j] / (2 * np.pi):18.5f} "
              f"{camp.omega_damped_rad_s[-1, j] / (2 * np.pi):16.5f}", file=out)
    if not camp.crossings:
        print("no critical speed of orders " + ", ".join(f"{k:g}" for k in camp.orders) + " in the range", file=out)
    for c in camp.critical_speeds:
        print(_crossing_line(c, "critical speed"), file=out)
    back = camp.backward_crossings
    if back:
        iso = camp.isotropic_supports
        print("backward-whirl crossings, not critical speeds: " + (
            "the supports are isotropic, so unbalance (a forward force) does not excite them" if iso else
            "the supports are anisotropic: unbalance can excite them weakly (see drivefem forced)"), file=out)
        for c in back:
            print("  " + _crossing_line(c, "backward crossing"), file=out)


def campbell_columns(camp, loads=None) -> tuple[list[str], list]:
    """CSV: speed (rev/min, rad/s), then damped frequency (rad/s) and log decrement of every tracked mode,
    then the amplitude of every named output (the reactions of each tracked mode: ``loads``)."""
    head = ["speed_rpm", "speed_rad_s"] + [f"mode{j + 1} {q}" for j in range(camp.n_modes)
                                           for q in ("omega_rad_s", "log_decrement", "whirl")]
    names = loads.names if loads is not None else []
    head += [f"{n} amplitude" for n in names]
    rows = []
    for i, s in enumerate(camp.speeds_rad_s):
        row = [s * RPM, s]
        for j in range(camp.n_modes):
            ld = camp.log_decrement[i, j]
            row += [camp.omega_damped_rad_s[i, j], ld if np.isfinite(ld) else "", camp.whirl[i][j]]
        row += [abs(complex(loads.values[k, i])) for k in range(len(names))]
        rows.append(row)
    return head, rows


# ------------------------------------------------------------- simulate (run-up with rubs)
def simulate(args) -> int:
    _check_outputs(args, "simulate", json="json", csv="csv", plot="plot", h5="h5", html="html")
    from .progress import progress_bar

    study = _load(args.model)
    with progress_bar(0.0, 1.0, "run-up", "") as update:
        res = study.run_up(progress=update)
    outs = study.outputs(res)
    data = contract.with_outputs(contract.run_up_data(study, res), outs)
    whirl = _whirl(res)
    if whirl is not None:
        data["whirl"] = whirl[1].to_dict()
    doc = _emit(args, "simulate", study, data)
    run_up_table(study, res)
    tables.outputs_lines(data)
    if whirl is not None:
        whirl_table(whirl[1])
    if args.csv:
        write_csv(args.csv, *run_up_columns(study, res, outs))
        print(f"wrote {args.csv}")
    if getattr(args, "h5", None):
        print(f"wrote {_run_up_h5(study, res, outs, args.h5)}")
    if args.plot:
        from pathlib import Path

        from ..rotor.plots import plot_run_up, plot_run_up_orbits

        out = Path(args.plot)
        out.mkdir(parents=True, exist_ok=True)
        print(f"wrote {plot_run_up(res, out / 'run_up.png', title=study.title)}")
        k = next((i for i, x in enumerate(res.probe_x) if any(abs(r.x - x) < 1e-12 for r in res.rubs)), 0)
        print(f"wrote {plot_run_up_orbits(res, out / 'run_up_orbits.png', probe=k, title=study.title)}")
        if outs.channels:
            from ..output.figures import plot_loads

            loads = [k for k, c in enumerate(outs.channels) if c.source not in ("run_up", "probe")]
            if loads:
                print(f"wrote {plot_loads(outs.subset(loads), out / 'loads.png', study.title)}")
        if whirl is not None:
            from ..rotor.plots import plot_cascade, plot_whirl_onset

            cas, onset = whirl
            print(f"wrote {plot_cascade(cas, out / 'cascade.png', onset=onset, title=study.title)}")
            print(f"wrote {plot_whirl_onset(res, onset, out / 'whirl_onset.png', title=study.title)}")
        for p in _run_up_spectra(study, res, out, cascade_done=whirl is not None):
            print(f"wrote {p}")
    if getattr(args, "html", None):
        from ..output.html import simulation_html

        print(f"wrote {simulation_html(res, outs, args.html, title=study.title)}")
    return 1 if doc.get("stopped") else 0


def _run_up_spectra(study, res, out, cascade_done: bool) -> list:
    """The run-up Bode plot (1x tracking filter, the steady unbalance response of the linear rotor
    dashed) and, unless the whirl analysis drew it, the cascade of the probe that moves most."""
    from ..rotor.plots import plot_cascade, plot_run_up_bode
    from ..rotor.runup_tracking import synchronous_response
    from ..rotor.whirl_spectrum import cascade

    written = []
    if res.t.size < 64 or np.ptp(res.speed) <= 0:
        print("note: no run-up Bode plot or cascade: the speed does not change (or the run is too short)",
              file=sys.stderr)
        return written
    sync = synchronous_response(res)
    steady = None
    lo, hi = max(float(sync.speed_rad_s.min()), 1e-3 * float(sync.speed_rad_s.max())), float(sync.speed_rad_s.max())
    if study.doc.unbalance and hi > lo:
        from ..modelfile.build.rotor import _unbalances
        from ..rotor import Probe, unbalance_response

        steady = unbalance_response(study.rotor, _unbalances(study.doc), np.linspace(lo, hi, 300),
                                    probes=[Probe(float(x), "major") for x in res.probe_x], find_peaks=False)
    written.append(plot_run_up_bode(sync, out / "run_up_bode.png", title=study.title, steady=steady))
    if not cascade_done:
        written.append(plot_cascade(cascade(res), out / "cascade.png", title=study.title))
    return written


def _whirl(res):
    """(cascade, onset) of a run on fluid-film bearings at the probe that moves most, or None."""
    if not any(b.kind == "journal_bearing" for b in res.bearings) or res.stopped:
        return None
    from ..rotor.whirl_spectrum import cascade, whirl_onset

    onset = whirl_onset(res)
    return cascade(res, onset.probe_x), onset


def whirl_table(onset, out=None) -> None:
    out = sys.stdout if out is None else out
    if onset.onset_speed is None:
        print(f"whirl at x = {onset.probe_x:g} m: no onset in the run (the subsynchronous amplitude does not turn to "
              f"growth; {onset.whirl_frequency:.6g} rad/s dominant)", file=out)
        return
    print(f"whirl at x = {onset.probe_x:g} m: onset at {onset.onset_speed:.6g} rad/s ({onset.onset_speed * RPM:.6g} rev/min), "
          f"whirl frequency {onset.whirl_frequency:.6g} rad/s ({onset.whirl_ratio:.4f} x speed); at the end "
          f"{onset.final_frequency:.6g} rad/s ({onset.final_frequency / onset.final_speed:.4f} x speed), amplitude grew "
          f"{onset.growth:.3g} x", file=out)


def run_up_columns(study, res, outs) -> tuple[list[str], list]:
    """CSV of a run-up: t, speed, the orbit (y, z) at every probe, normal force, slip and contact flag of
    every rub, then the other named outputs (bearing reactions, section loads); with [[output]] tables: t
    and those outputs only."""
    extra = [k for k, c in enumerate(outs.channels) if c.source not in ("run_up", "probe", "rub")]
    if getattr(study.doc, "output", None):
        return ["t"] + outs.names, np.column_stack([res.t] + list(outs.values)).tolist()
    head = ["t", "speed_rad_s"] + [_probe_column(res, k, c) for k in range(res.probe_x.size) for c in ("y", "z")] + \
        [f"{q} {r.name}" for r in res.rubs for q in ("normal_force", "slip", "in_contact")] + \
        [outs.channels[k].name for k in extra]
    cols = [res.t, res.speed] + [a[:, k] for k in range(res.probe_x.size) for a in (res.orbit_y, res.orbit_z)] + \
        [a for r in res.rubs for a in (r.normal_force, r.slip, r.in_contact.astype(float))] + \
        [outs.values[k] for k in extra]
    return head, np.column_stack(cols).tolist()


def _run_up_h5(study, res, outs, path):
    """The run-up's time history in the --h5 container (docs/outputs.md): its named outputs (speed, probe
    orbits, rub normal forces, bearing reactions, section loads) and the rub events."""
    from types import SimpleNamespace

    from ..output.history import write_history

    events = [SimpleNamespace(t=e["t"], kind=e["kind"], element=e.get("rub", ""), impulse=0.0) for e in res.events]
    return write_history(path, command="simulate", title=study.title, kind="rotor", t=res.t, outputs=outs,
                         events=events)


def _probe_column(res, k: int, c: str) -> str:
    """The CSV column of probe k's orbit component c: <name>.<c> where a named thing is there, else c@x=<x>."""
    n = res.probe_names[k] if k < len(res.probe_names) else ""
    return f"{n}.{c}" if n else f"{c}@x={res.probe_x[k]:g}"


def _lowest(values) -> str:
    known = [v for v in values if v is not None]
    return f"{min(known):.12f}" if known else ("n/a (free rotor)" if values else "n/a (no rub)")


def run_up_table(study, res, out=None) -> None:
    out = sys.stdout if out is None else out
    red = res.reduction
    print(f"{study.title}\nrun-up {res.speed[0]:.6g} -> {res.speed[-1]:.6g} rad/s "
          f"({res.speed[0] * RPM:.6g} -> {res.speed[-1] * RPM:.6g} rev/min) in {res.t[-1]:.6g} s, method {res.method}, "
          f"{res.steps} steps ({'right-hand sides' if res.method == 'event' else 'time steps'}), {res.wall_time:.3g} s", file=out)
    fc = red["frequency_check"]
    print(f"reduced rotor: {red['basis']} shapes ({red['modes']} modes + {red['attachment_shapes']} attachment), "
          f"highest {red['highest_frequency_rad_s']:.4g} rad/s; static restitution at the "
          f"{'rubs and bearings' if res.bearings else 'rubs'} "
          f"{_lowest(red['restitution'])}; complex eigenvalues vs full rotor at {fc['speed_rad_s']:.4g} rad/s: "
          f"max rel. error {fc['max_relative_error']:.2e}", file=out)
    for k, x in enumerate(res.probe_x):
        r = np.hypot(res.orbit_y[:, k], res.orbit_z[:, k])
        j = int(np.argmax(r))
        name = res.probe_names[k] if k < len(res.probe_names) and res.probe_names[k] else ""
        print(f"  probe {name + ' ' if name else ''}x = {x:g} m: peak orbit radius {r[j]:.4e} m at "
              f"{res.speed[j] * RPM:.1f} rev/min", file=out)
    for r in res.rubs:
        fc = r.first_contact
        first = "never" if fc is None else f"first at t = {fc['t']:.5g} s ({fc['speed_rad_s'] * RPM:.1f} rev/min)"
        full = ", ".join(f"{np.interp(a, res.t, res.speed) * RPM:.0f}-{np.interp(b, res.t, res.speed) * RPM:.0f}"
                         for a, b in r.full_annular) or "none"
        print(f"  rub {r.name!r} (clearance {r.clearance:g} m): contact {first}; {r.contact_phases} contact phases; "
              f"max normal force {r.normal_force.max(initial=0.0):.4g} N; full annular rub at rev/min {full}; "
              f"contact share {100 * r.in_contact.mean():.1f} %"
              + (f"; max penetration {r.max_penetration:.3g} m" if res.method == "moreau" else ""), file=out)
    for b in res.bearings:
        print(f"  {b.kind.replace('_', ' ')} {b.name!r} at x = {b.x:g} m (clearance {b.clearance:g} m): eccentricity "
              f"ratio {b.eccentricity.min():.4g} ... {b.eccentricity.max():.4g}, largest force {b.force.max(initial=0.0):.4g} N",
              file=out)
    w = res.works
    print("energy: start {:.6g} J, end {:.6g} J; works ".format(res.energy_start, res.energy_end)
          + ", ".join(f"{k} {v:.6g}" for k, v in w.items()) + f" J; balance error {res.energy_error:.2e}", file=out)
    for wmsg in res.warnings:
        print(f"warning: {wmsg}", file=out)
