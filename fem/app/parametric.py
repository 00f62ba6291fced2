"""``drivefem parametric MODEL [--json F] [--plot F] [--csv F] [--quiet]``: the parametric stability chart of a model
file with ``[analysis] type = "parametric"`` (textbook ch. 7, Fig. 7.4): max |Floquet multiplier| over the
(eps, Omega) grid, the tongue edges at the depths of ``boundaries_at`` and the damping thresholds eps* of
the principal tongues.  Exit codes as for every command (0 done, 2 bad input, 4 solver failure)."""
from __future__ import annotations

import sys

import numpy as np

from ..output import contract, write_csv, write_json
from ..output.jsonio import encode


def add_parser(subparsers) -> None:
    """Register the command on the ``drivefem`` sub-parsers."""
    p = subparsers.add_parser("parametric", help="parametric stability chart (Floquet multipliers over depth and "
                              "excitation frequency) of [analysis] type = \"parametric\"")
    p.add_argument("model")
    from .options import add_outputs

    add_outputs(p, "parametric", json="the chart (schema drivefem.parametric)",
                csv="the grid, one row per (depth, Omega) point", plot=True, old={"--png": "--plot FILE"})
    p.set_defaults(func=parametric)


def parametric(args) -> int:
    from ..modelfile.build.parametric import run
    from ..study import Study

    from .options import prepare
    from .progress import count_bar

    prepare(args, "parametric", json="json", plot="plot", csv="csv")
    study = Study.load(args.model)
    with count_bar("parametric", "points") as update:
        spec, chart = run(study, progress=update)
    data = contract.parametric_data(study, spec, chart)
    doc = encode(contract.payload("parametric", study, data))
    if args.json:
        write_json(args.json, doc, encoded=True)
        print(f"wrote {args.json}")
    print_summary(study.title, spec, chart)
    if args.csv:
        write_csv(args.csv, *grid_columns(chart))
        print(f"wrote {args.csv}")
    if args.plot:
        from ..output.figures.parametric import plot_stability_chart

        drawn = plot_stability_chart(chart, args.plot, title=_figure_title(study.title, spec),
                                     normalise=spec.omega_unit != "rad/s")
        print(f"wrote {drawn}")
    for w in chart.warnings:
        print(f"drivefem: warning: {w}", file=sys.stderr)
    return 0


def grid_columns(chart) -> tuple[list[str], list]:
    """CSV of the grid: depth, Omega (rad/s), Omega / omega_1, max |rho|, stable, growth rate, error estimate."""
    w1 = float(chart.natural_omega_rad_s[0])
    head = ["depth", "omega_rad_s", "omega_ratio", "rho_max", "stable", "growth_rate_1_s", "error_estimate",
            "liouville_residual"]
    rows = []
    for i, eps in enumerate(chart.depth):
        for j, om in enumerate(chart.omega_rad_s):
            rows.append([eps, om, om / w1, chart.rho_max[i, j], bool(chart.stable[i, j]), chart.growth_rate[i, j],
                         chart.error_estimate[i, j], chart.liouville_residual[i, j]])
    return head, rows


def _figure_title(title: str, spec) -> str:
    parts = "; ".join(spec.parts)
    return (title + "\n" if title else "") + f"pulsating: {parts}"


def print_summary(title: str, spec, chart, out=None) -> None:
    """The chart's headline numbers as a text table (never recomputed)."""
    out = sys.stdout if out is None else out
    w = chart.natural_omega_rad_s
    w1 = float(w[0])
    print(title, file=out)
    print(f"parametric chart: {chart.n_dofs} {'modes (projected)' if chart.projected else 'DOFs'}, "
          f"inertia form {chart.inertia_form}; damping: {chart.damping}", file=out)
    for m, what in zip(chart.modulations, spec.parts):
        print(f"  pulsating {m['target']}: {what}, relative depth {m['depth']:g}, sin({m['harmonic']} Omega t "
              f"+ {m['phase']:g})", file=out)
    print(f"grid: {chart.depth.size} depths in [{chart.depth[0]:g}, {chart.depth[-1]:g}] x {chart.omega_rad_s.size} "
          f"Omega in [{chart.omega_rad_s[0]:.6g}, {chart.omega_rad_s[-1]:.6g}] rad/s; unstable points "
          f"{int(np.sum(~chart.stable))}; max error estimate {float(chart.error_estimate.max()):.2g}, "
          f"max Liouville residual {float(chart.liouville_residual.max()):.2g}", file=out)
    print("natural frequencies of the mean system [rad/s]: " + ", ".join(f"{v:.6g}" for v in w[:8])
          + (" ..." if w.size > 8 else ""), file=out)
    if chart.thresholds:
        print("damping thresholds of the principal tongues (Omega = 2 omega_r):", file=out)
        print(f"{'mode':>4} {'omega_r':>12} {'eps*(2 w_r)':>12} {'eps* tip':>12} {'Omega_tip/w1':>12} "
              f"{'zeta':>10} {'4 zeta/kappa':>12}", file=out)
        for t in chart.thresholds:
            print(f"{t.mode:4d} {t.natural_omega_rad_s:12.6g} {t.depth_at_centre:12.6g} {t.depth_minimum:12.6g} "
                  f"{t.omega_at_minimum_rad_s / w1:12.6g} {t.zeta:10.4g} {t.energy_estimate:12.6g}"
                  + (f"  {t.note}" if t.note else ""), file=out)
    for b in chart.boundaries:
        print(f"instability intervals at eps = {b.depth:g} (edges by root finding):", file=out)
        if not len(b.omega_low_rad_s):
            print("  none in the Omega range", file=out)
        for lo, hi, c, k, cl in zip(b.omega_low_rad_s, b.omega_high_rad_s, b.centre, b.crossing, b.clipped):
            print(f"  {c:>12}  Omega/w1 in ({lo / w1:.6f}, {hi / w1:.6f})  rad/s ({lo:.6g}, {hi:.6g})  "
                  f"multiplier through {k}" + (f"  [runs past the {cl} end of the range]" if cl else ""), file=out)
