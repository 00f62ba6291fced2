"""The commands on geared train files (kind ``train``: ``[[shaft]]``, ``[[mesh]]``, ``[[coupling]]`` or
``[train]`` at the top level; docs/geared.md):

* ``drivefem modal TRAIN [--modes N] [--json F]``: complex modes at the ``[analysis]`` speed (meshes in
  their linear state), kind of each mode by its kinetic energy, whirl of every rotor shaft;
* ``drivefem campbell TRAIN [--modes N] [--json F] [--png F] [--csv F]``: Campbell diagram of
  ``[campbell]`` over the reference speed (each shaft at its own speed), critical speeds;
* ``drivefem forced TRAIN``: ``[forced]`` (linear response over speed: mesh forces, dynamic load factors,
  bearing reactions) or ``[steady]`` (the nonlinear amplitude-frequency curve by HB or shooting);
* ``drivefem simulate TRAIN``: ``[simulation]`` with exact backlash and slip events;
* ``drivefem parametric TRAIN``: ``[parametric]`` Floquet chart of the mesh-stiffness variation.

:func:`add_parser` routes a train file here and every other file to the command it had before.  Exit
codes as for every command."""
from __future__ import annotations

import sys

import numpy as np

from discrete.errors import ModelError

from ..output import contract, write_csv
from .commands import _emit, count_option, max_modes
from .commands import _outputs as _check_outputs

RPM = 30.0 / np.pi


def add_parser(subparsers) -> None:
    """Route ``modal``, ``campbell`` of train files here (the other commands follow as they are built)."""
    for name, command in (("modal", modal), ("campbell", campbell), ("parametric", parametric), ("forced", forced),
                          ("simulate", simulate)):
        sp = subparsers.choices[name]
        sp.set_defaults(func=_routed(sp.get_default("func"), command))


def _routed(other, train_command):
    def run(args) -> int:
        return train_command(args) if is_train_file(args.model) else other(args)

    run.__doc__ = other.__doc__
    return run


def is_train_file(path) -> bool:
    """Whether the file has a top-level table of a train file (read as TOML only; validated by the command)."""
    from ..modelfile.schema.document import TRAIN_MARKERS
    from ..modelfile.source import read_toml

    try:
        doc = read_toml(path)
    except ModelError:
        return False            # the other command reports the unreadable file
    return any(k in doc for k in TRAIN_MARKERS)


def _load(path):
    from ..study import Study

    return Study.load(path)


# ---------------------------------------------------------------- modal
def modal(args) -> int:
    _check_outputs(args, "modal", json="json")
    count_option(args, "modes", 1, max_modes(), "the number of modes")
    for opt in ("vtu", "png", "plot", "csv"):
        if getattr(args, opt, None):
            raise ModelError("command line", "--" + opt, getattr(args, opt), "--json for a train model file (the "
                             "figures of a train are drawn by the Python API: fem.train.plots)")
    study = _load(args.model)
    res = study.modal(args.modes)
    _emit(args, "modal", study, contract.modal_data(study, res))
    modal_table(study, res)
    return 0 if (res.reliable | res.rigid).all() else 3


def modal_table(study, res, out=None) -> None:
    out = sys.stdout if out is None else out
    ts = study.train
    speeds = ", ".join(f"{m} {r * res.speed_rad_s * RPM:.6g}" for m, r in ts.ratios.items())
    print(f"{study.title}\ntrain: {len(ts.blocks)} shafts, {len(ts.train.bodies)} bodies, "
          f"{len(ts.train.connections)} connections, {ts.n_dofs - ts.constrained.size} free DOFs; reference speed "
          f"{res.speed_rad_s:.6g} rad/s; speeds [rev/min]: {speeds}; solver: {res.method}", file=out)
    print(f"{'mode':>4} {'omega_d [rad/s]':>15} {'f_d [Hz]':>12} {'zeta':>10} {'kind':>8} {'torsion':>8} "
          f"{'lateral':>8} {'axial':>8} {'whirl':>9} {'residual':>9}  note", file=out)
    for r in range(res.n_modes):
        note = "rigid-body" if res.rigid[r] else ("" if res.reliable[r] else "NOT RELIABLE (see warnings)")
        if res.reliable[r] or res.rigid[r]:
            w, f = f"{res.omega_damped_rad_s[r]:15.6f}", f"{res.frequencies_hz[r]:12.6f}"
        else:
            w, f = f"{'--':>15}", f"{'--':>12}"
        sh = res.energy_share[r]
        print(f"{r + 1:4d} {w} {f} {res.damping_ratio[r]:10.5f} {res.kind[r]:>8} {sh[0]:8.3f} {sh[1]:8.3f} "
              f"{sh[2]:8.3f} {res.whirl[r]:>9} {res.residuals[r]:9.1e}  {note}".rstrip(), file=out)
    for w in res.warnings:
        print(f"warning: {w}", file=out)


# ------------------------------------------------------------- campbell
def campbell(args) -> int:
    from .rotor import campbell_columns, campbell_table

    _check_outputs(args, "campbell", json="json", plot="plot", csv="csv", html="html")
    count_option(args, "modes", 1, max_modes(), "the number of modes")
    from .progress import count_bar

    study = _load(args.model)
    with count_bar("campbell", "solves", quiet=getattr(args, "quiet", False)) as update:
        camp = study.campbell(args.modes, progress=update)
    _emit(args, "campbell", study, contract.campbell_data(study, camp))
    campbell_table(study, camp)
    print("speed ratios: " + ", ".join(f"{m} {r:.6g}" for m, r in study.train.ratios.items()))
    if args.csv:
        write_csv(args.csv, *campbell_columns(camp))
        print(f"wrote {args.csv}")
    figure = getattr(args, "plot", None)
    if figure:
        from ..train.plots import plot_train_campbell

        ts = study.train
        lines = {f"tooth pass {m.name}": m.teeth[0] * abs(ts.ratio_of(m.ports[0])) / (2 * np.pi)
                 for m in ts.train.connections if getattr(m, "teeth", None)}
        print(f"wrote {plot_train_campbell(camp, figure, title=study.title, ratios=ts.ratios, lines=lines, reference=ts.train.reference)}")
    if getattr(args, "html", None):
        from ..output.html import campbell_html

        print(f"wrote {campbell_html(camp, args.html, title=study.title)}")
    for w in camp.warnings:
        print(f"drivefem: warning: {w}", file=sys.stderr)
    return 0


# ------------------------------------------------------------- parametric
def parametric(args) -> int:
    from ..modelfile.build.train import parametric as run

    _check_outputs(args, "parametric", json="json", plot="plot", csv="csv")
    study = _load(args.model)
    res = run(study)
    d = res.to_dict()
    chart = res.chart
    d["omega_ratio"] = (chart.omega_rad_s / chart.natural_omega_rad_s[0]).tolist()
    _emit(args, "parametric", study, d)
    if args.json:
        print(f"wrote {args.json}")
    parametric_table(study, res)
    if args.csv:
        head = ["depth", "speed_rad_s", "tooth_pass_rad_s", "rho_max", "stable"]
        rows = [[e, w / res.pass_per_speed, w, chart.rho_max[i, j], bool(chart.stable[i, j])]
                for i, e in enumerate(chart.depth) for j, w in enumerate(chart.omega_rad_s)]
        write_csv(args.csv, head, rows)
        print(f"wrote {args.csv}")
    if getattr(args, "plot", None):
        from ..train.plots import plot_train_parametric

        print(f"wrote {plot_train_parametric(res, args.plot, title=study.title)}")
    for w in d["warnings"]:
        print(f"drivefem: warning: {w}", file=sys.stderr)
    return 0


def parametric_table(study, res, out=None) -> None:
    out = sys.stdout if out is None else out
    c = res.chart
    z = res.pass_per_speed
    print(f"{study.title}\nmesh-stiffness variation of {res.mesh!r}: tooth-pass frequency = {z:.6g} x the reference "
          f"speed; {c.n_dofs} {'modes (projected)' if c.projected else 'DOFs'}; grid {c.depth.size} depths x "
          f"{c.omega_rad_s.size} speeds [{c.omega_rad_s[0] / z:.6g}, {c.omega_rad_s[-1] / z:.6g}] rad/s; unstable points "
          f"{int(np.sum(~c.stable))}", file=out)
    print("natural frequencies of the mean train [rad/s]: " + ", ".join(f"{v:.6g}" for v in c.natural_omega_rad_s[:6]),
          file=out)
    for b in c.boundaries:
        print(f"instability intervals at depth {b.depth:g}:", file=out)
        if not len(b.omega_low_rad_s):
            print("  none in the range", file=out)
        for lo, hi, cen, k in zip(b.omega_low_rad_s, b.omega_high_rad_s, b.centre, b.crossing):
            print(f"  {cen:>10}  speed ({lo / z:.6g}, {hi / z:.6g}) rad/s = ({lo / z * RPM:.6g}, {hi / z * RPM:.6g}) "
                  f"rev/min; tooth-pass ({lo:.6g}, {hi:.6g}) rad/s; multiplier through {k}", file=out)


# ---------------------------------------------------------------- forced
def forced(args) -> int:
    from ..output import columns, tables
    from .progress import progress_bar

    _check_outputs(args, "forced", json="json", csv="csv", plot="plot")
    if getattr(args, "html", None):
        raise ModelError("command line", "--html", args.html, "a rotor model file (the interactive Bode plot of the "
                         "unbalance response); for a train file use --plot")
    study = _load(args.model)
    if study.is_steady():
        w0, w1 = study.doc.steady.range
        with progress_bar(w0, w1, "continuation", "rad/s") as update:
            res = study.forced(progress=update)
        _emit(args, "forced", study, contract.forced_data(study, res))
        tables.forced_table(study, res, all_rows=args.all, out=sys.stdout)
        if args.csv:
            columns.write(args.csv, columns.afc(res))
            print(f"wrote {args.csv}")
        if args.plot:
            from ..output.figures import plot_afc

            plot_afc(res, args.plot)
            print(f"wrote {args.plot}")
        if res.stop_cause == "interrupted":
            print(f"continuation {res.reason}", file=sys.stderr)
            from .exit_codes import EXIT_INTERRUPTED

            return EXIT_INTERRUPTED
        return 0 if res.completed else 1
    res = study.forced()
    _emit(args, "forced", study, contract.forced_data(study, res))
    forced_table(study, res, all_rows=args.all)
    if args.csv:
        head = ["speed_rad_s", "speed_rpm"] + [f"{c.connection}:{c.coordinate} {q}" for c in res.connections
                                               for q in ("peak", "dynamic_factor")] + \
            [f"{k} peak_radial" for k in res.bearings]
        rows = []
        for j, sp_ in enumerate(res.speeds_rad_s):
            row = [sp_, sp_ * RPM]
            for c in res.connections:
                row += [c.peak[j], c.dynamic_factor[j] if np.isfinite(c.dynamic_factor[j]) else ""]
            row += [v["peak_radial"][j] for v in res.bearings.values()]
            rows.append(row)
        write_csv(args.csv, head, rows)
        print(f"wrote {args.csv}")
    if args.plot:
        from ..train.plots import plot_train_forced

        print(f"wrote {plot_train_forced(res, args.plot, title=study.title)}")
    return 0


def forced_table(study, res, all_rows: bool = False, out=None) -> None:
    out = sys.stdout if out is None else out
    print(f"{study.title}\nlinear response over speed: harmonics " + ", ".join(res.harmonics) +
          f"; force balance of every shaft: max residual {res.balance_max:.1e}", file=out)
    for c in res.connections:
        print(f"  {c.connection}:{c.coordinate}: static {c.static:.6g}", file=out)
    cols = [(f"{c.connection} DLF", c.dynamic_factor) for c in res.connections if c.coordinate == "line of action"]
    cols += [(f"{c.connection} peak", c.peak) for c in res.connections]
    print(f"{'rev/min':>10} {'rad/s':>10}" + "".join(f" | {name[:22]:>22}" for name, _ in cols), file=out)
    s = res.speeds_rad_s
    idx = np.arange(s.size)
    if idx.size > 40 and not all_rows:
        idx = np.unique(np.linspace(0, idx.size - 1, 40).astype(int))
    for j in idx:
        print(f"{s[j] * RPM:10.2f} {s[j]:10.4f}" + "".join(f" | {v[j]:22.6g}" for _, v in cols), file=out)
    if idx.size < s.size:
        print(f"({s.size} speeds; every {s.size // idx.size}th shown, --all for all)", file=out)
    for w in res.warnings:
        print(f"warning: {w}", file=out)


# ---------------------------------------------------------------- simulate
def simulate(args) -> int:
    from ..output import tables
    from .progress import progress_bar

    _check_outputs(args, "simulate", json="json", csv="csv", plot="plot", h5="h5")
    study = _load(args.model)
    with progress_bar(0.0, study.simulation_settings()["t_end"], "simulate", "s") as update:
        res = study.simulate(progress=update)
    r = res.result
    outs = study.outputs(res)            # connection forces and bearing reactions (fem.train.outputs)
    every = study.doc.simulation.record_every if study.doc.simulation is not None else 1
    idx = None
    if every > 1:
        from ..loads.analyses import decimate

        idx = decimate(r.t, every, [e.t for e in r.events])
    data = contract.with_outputs(res.to_dict(), outs)
    if getattr(args, "h5", None):
        data["history"] = {"file": str(args.h5), "samples": int(r.t.size if idx is None else idx.size),
                           "record_every": int(every)}
    d = _emit(args, "simulate", study, data)
    tables.simulation_summary(study.title, d, out=sys.stdout)
    print(f"force balance of every shaft and body at every sample: max residual {d['force_balance']['max_residual']:.1e}")
    for k, v in d["connection_forces"].items():
        print(f"  {k}: force min {v['min']:.6g}, max {v['max']:.6g}, mean {v['mean']:.6g}")
    for k, v in d["bearing_forces"].items():
        print(f"  {k}: max radial force {v['max_radial']:.6g} N")
    sel = np.arange(r.t.size) if idx is None else idx
    if args.csv:
        head = ["t"] + [f"{n}.x" for n in r.names] + [f"{n}.v" for n in r.names] + outs.names
        cols = [r.t[sel]] + list(np.asarray(r.x)[:, sel]) + list(np.asarray(r.v)[:, sel]) + list(outs.values[:, sel])
        write_csv(args.csv, head, np.column_stack(cols).tolist())
        print(f"wrote {args.csv}")
    if getattr(args, "h5", None):
        from ..output.history import write_history

        has_e = np.size(r.energy) == r.t.size
        write_history(args.h5, command="simulate", title=study.title, kind=study.kind, t=r.t[sel],
                      outputs=outs.take(sel), states=(list(r.names), np.asarray(r.x)[:, sel], np.asarray(r.v)[:, sel]),
                      energy=(np.asarray(r.energy)[sel], np.asarray(r.work)[sel]) if has_e else None, events=r.events,
                      record_every=every, n_recorded=r.t.size)
        print(f"wrote {args.h5}")
    if getattr(args, "plot", None):
        from ..train.plots import plot_train_simulation

        for p in plot_train_simulation(res, args.plot, title=study.title):
            print(f"wrote {p}")
    if str(d.get("reason", "")).startswith("interrupted"):
        from .exit_codes import EXIT_INTERRUPTED

        return EXIT_INTERRUPTED
    return 1 if d.get("stopped_early") else 0
