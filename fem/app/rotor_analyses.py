"""The rotor analyses beyond modes, Campbell diagram and unbalance response, one command each, with
the outputs every command has (``--json``, ``--csv``, ``--plot``):

* ``drivefem static ROTOR``: sag under gravity (and the point loads of ``[static]``) and the load
  on every bearing, with the equilibrium check;
* ``drivefem critical-map ROTOR``: the undamped critical speed map against bearing stiffness
  (``[critical_map]``), the model's own bearings overlaid and their intersections with the forward
  critical-speed curves (the critical speeds read off the map);
* ``drivefem stability ROTOR``: the stability threshold over the ``[stability]`` (or ``[campbell]``)
  speeds, and the API Level I screening of ``[stability.api_level1]``.

Every table is optional except where a command needs data only the file can give (stages for
Level I).  Exit codes as every command: 0 done, 2 bad input, 4 solver failure; ``stability``
exits 0 also when the rotor is unstable or fails Level I (a result, printed and in the JSON)."""
from __future__ import annotations

import sys

import numpy as np

from discrete.errors import ModelError

from ..output import contract, write_csv
from .rotor import RPM, _check_outputs, _emit, _linear_note, _load


def add_parser(subparsers) -> None:
    for name, helptext, func in (
            ("static", "static sag of a [rotor] file under gravity and the bearing loads ([static])", static),
            ("critical-map", "undamped critical speed map of a [rotor] file with its own bearings overlaid "
                             "([critical_map])", critical_map),
            ("stability", "stability threshold of a [rotor] file and the API Level I screening ([stability])",
             stability)):
        p = subparsers.add_parser(name, help=helptext)
        p.add_argument("model")
        p.add_argument("--json", help="write the JSON result here")
        p.add_argument("--csv", help="write the result's table here")
        p.add_argument("--plot", help="write the PNG figure here")
        if name == "stability":
            p.add_argument("--quiet", action="store_true", help="no progress bar")
        p.set_defaults(func=func)


def _rotor_study(args):
    study = _load(args.model)
    if study.kind != "rotor":
        raise ModelError(str(args.model), "rotor", None, f"a model file with a [rotor] table (this is a {study.kind} "
                         "model)")
    _linear_note(study)
    return study


def _bearing_name(b, i: int) -> str:
    return b.name or f"bearing {i + 1} (x = {b.x:g} m)"


# --------------------------------------------------------------- static
def static(args) -> int:
    from ..modelfile.build.rotor import static_spec
    from ..rotor import static_deflection

    _check_outputs(args, json=False, csv=False, plot=False)
    study = _rotor_study(args)
    spec = static_spec(study.doc)
    res = static_deflection(study.rotor, **spec)
    rotor = study.rotor.rotor
    names = [_bearing_name(b, i) for i, b in enumerate(rotor.bearings)]
    data = res.to_dict() | {"bearing_names": names, "gravity": list(spec["gravity"]),
                            "max_deflection_m": float(np.hypot(res.v, res.w).max(initial=0.0)),
                            "max_deflection_x": float(res.node_x[np.argmax(np.hypot(res.v, res.w))])}
    _emit(args, "static", study, data)
    print(f"{study.title}\nstatic deflection: gravity {tuple(spec['gravity'])} m/s^2, {len(spec['loads'])} point "
          f"load(s), bearings at {res.speed_rad_s * RPM:.6g} rev/min")
    print(f"largest deflection {data['max_deflection_m'] * 1e6:.6g} um at x = {data['max_deflection_x']:g} m "
          f"(v {np.abs(res.v).max() * 1e6:.6g} um, w {np.abs(res.w).max() * 1e6:.6g} um at most)")
    print(f"{'bearing':>28} {'x [m]':>8} {'F_y [N]':>12} {'F_z [N]':>12} {'|F| [N]':>12}")
    for n, x, f in zip(names, res.bearing_x, res.bearing_force):
        print(f"{n[:28]:>28} {x:8.4g} {f[0]:12.6g} {f[1]:12.6g} {np.hypot(*f):12.6g}")
    print(f"applied load ({res.applied_force[0]:.6g}, {res.applied_force[1]:.6g}) N; ground reactions "
          f"({res.reaction_force[0]:.6g}, {res.reaction_force[1]:.6g}) N; equilibrium error {res.equilibrium_error:.1e}")
    for w in res.warnings:
        print(f"warning: {w}", file=sys.stderr)
    if args.csv:
        write_csv(args.csv, ["x_m", "v_m", "w_m", "theta_y_rad", "theta_z_rad"],
                  np.column_stack([res.node_x, res.v, res.w, res.theta_y, res.theta_z]).tolist())
        print(f"wrote {args.csv}")
    if args.plot:
        from ..rotor.plots import plot_static

        discs = [(d.x, d.name or f"disc at x = {d.x:g} m") for d in rotor.discs]
        print(f"wrote {plot_static(res, args.plot, title=study.title, bearing_names=names, discs=discs)}")
    return 0


# --------------------------------------------------------- critical map
def _stiffness_range(rotor, table) -> np.ndarray:
    n = table.points if table is not None else 41
    if table is not None and table.stiffness is not None:
        lo, hi = table.stiffness
        if not lo < hi:
            raise ModelError("[critical_map]", "stiffness", list(table.stiffness), "[lowest, highest] with lowest < highest")
    else:
        ks = [float(v) for b in rotor.bearings for key in ("kyy", "kzz") for v in np.atleast_1d(b.table()[key]) if v > 0]
        if not ks:
            raise ModelError("[critical_map]", "stiffness", None, "[lowest, highest] bearing stiffness (N/m): the "
                             "model's bearings have no positive direct stiffness to centre the map on")
        lo, hi = min(ks) / 100.0, max(ks) * 100.0
    return np.geomspace(lo, hi, n)


def critical_map(args) -> int:
    from ..modelfile.build.rotor import operating_range, speed_grid
    from ..rotor import critical_speed_map
    from ..rotor.critical_map import bearing_overlay, forward_columns, merge_identical

    _check_outputs(args, json=False, csv=False, plot=False)
    study = _rotor_study(args)
    import dataclasses

    t = study.doc.critical_map
    rotor = study.rotor.rotor
    if t is not None and t.bearings is not None:
        names = {b.name for b in rotor.bearings}
        for n in t.bearings:
            if n not in names:
                raise ModelError("[critical_map]", "bearings", n, "names of [[rotor.bearing]]s: "
                                 + ", ".join(repr(x) for x in sorted(names) if x))
        held = [b for b in rotor.bearings if b.name in set(t.bearings)]
    else:
        held = [b for b in rotor.bearings if any(np.any(b.table()[k] > 0) for k in ("kyy", "kzz"))]
    dropped = [_bearing_name(b, i) for i, b in enumerate(rotor.bearings) if b not in held]
    rotor = dataclasses.replace(rotor, bearings=held)
    ks = _stiffness_range(rotor, t)
    n = t.modes if t is not None else 4
    cmap = critical_speed_map(rotor, ks, 2 * n + 2)
    iso_pedestals = all(p.kyy == p.kzz and p.cyy == p.czz for p in rotor.pedestals)
    fwd = forward_columns(cmap, n, backward=not iso_pedestals)
    speeds = speed_grid(study.doc.campbell, "[campbell]") if study.doc.campbell is not None else None
    if speeds is not None and rotor.bearings and any(b.speed_dependent for b in rotor.bearings):
        lo = max(b.speed_grid[0] for b in rotor.bearings if b.speed_dependent and b.extrapolate == "refuse") \
            if any(b.speed_dependent and b.extrapolate == "refuse" for b in rotor.bearings) else speeds[0]
        hi = min(b.speed_grid[-1] for b in rotor.bearings if b.speed_dependent and b.extrapolate == "refuse") \
            if any(b.speed_dependent and b.extrapolate == "refuse" for b in rotor.bearings) else speeds[-1]
        speeds = np.linspace(max(speeds[0], lo), min(speeds[-1], hi), 200)
    overlay, points = merge_identical(*bearing_overlay(rotor, cmap, fwd, speeds))
    op = operating_range(study.doc)
    data = {"stiffness_n_per_m": ks.tolist(),
            "forward_critical_speeds_rad_s": [[None if not np.isfinite(v) else float(v) for v in row] for row in fwd],
            "bearings": [{k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in c.items()} for c in overlay],
            "intersections": points, "left_out": dropped, "backward_included": not iso_pedestals,
            "map": cmap.to_dict()}
    _emit(args, "critical-map", study, data)
    print(f"{study.title}\nundamped critical speed map: {ks.size} bearing stiffnesses {ks[0]:.4g} ... {ks[-1]:.4g} N/m "
          f"(every bearing replaced by an isotropic undamped one), the lowest {n} "
          f"{'forward ' if iso_pedestals else ''}critical speeds")
    if not iso_pedestals:
        print("the pedestals are anisotropic: forward and backward whirl couple, every synchronous crossing is drawn")
    if dropped:
        print("left out of the map (" + ("not in [critical_map] bearings" if t is not None and t.bearings is not None
                                         else "no direct stiffness: seals, dampers") + "): " + ", ".join(dropped))
    print(f"{'k [N/m]':>12} " + " ".join(f"{'crit ' + str(j + 1) + ' [rev/min]':>18}" for j in range(n)))
    for i in np.unique(np.linspace(0, ks.size - 1, min(ks.size, 11)).astype(int)):
        print(f"{ks[i]:12.4g} " + " ".join(f"{v * RPM:18.2f}" if np.isfinite(v) else f"{'--':>18}" for v in fwd[i]))
    if not points:
        print("the model's bearings do not cross the map's curves in its stiffness range")
    for c in sorted(points, key=lambda c: c["speed_rad_s"]):
        print(f"intersection: {c['name']} {c['kind']} = {c['stiffness']:.4g} N/m with {'forward ' if iso_pedestals else ''}critical {c['mode']}: "
              f"{c['speed_rad_s'] * RPM:.2f} rev/min ({c['speed_rad_s']:.4f} rad/s)")
    for w in cmap.warnings:
        print(f"warning: {w}", file=sys.stderr)
    if args.csv:
        write_csv(args.csv, ["stiffness_n_per_m"] + [f"forward_critical_{j + 1}_rad_s" for j in range(n)],
                  [[k] + [v if np.isfinite(v) else "" for v in row] for k, row in zip(ks, fwd)])
        print(f"wrote {args.csv}")
    if args.plot:
        from ..rotor.plots import plot_critical_speed_map

        drawn = plot_critical_speed_map(cmap, args.plot, title=study.title, forward=fwd, overlay=overlay,
                                        intersections=points, operating_range=op,
                                        label="forward critical" if iso_pedestals else "critical")
        print(f"wrote {drawn}")
    return 0


# ------------------------------------------------------------ stability
def stability(args) -> int:
    from ..modelfile.build.rotor import level1_spec, modes_count, operating_range, stability_speeds
    from ..rotor import stability_threshold
    from .progress import count_bar

    _check_outputs(args, json=False, csv=False, plot=False)
    study = _rotor_study(args)
    doc = study.doc
    s = stability_speeds(doc)
    n = modes_count(doc, doc.stability if doc.stability is not None and doc.stability.modes is not None
                    else doc.campbell, None)
    op = operating_range(doc)
    spec = level1_spec(doc, op)
    with count_bar("stability", "speeds", quiet=getattr(args, "quiet", False)) as update:
        update(0, 2 if spec else 1)
        thr = stability_threshold(study.rotor, float(s[-1]), n, speed_min=float(s[0]), n_grid=int(s.size))
        update(1, 2 if spec else 1)
        level1 = None
        if spec is not None:
            from ..rotor.api_level1 import api_level1

            level1 = api_level1(study.rotor.rotor, n_modes=n, **spec)
            update(2, 2)
    data = {"threshold": thr.to_dict(), "api_level1": None if level1 is None else level1.to_dict(),
            "operating_range_rad_s": None if op is None else list(op)}
    _emit(args, "stability", study, data)
    print(f"{study.title}\nstability: {n} tracked modes over {s.size} speeds [{s[0] * RPM:.6g}, {s[-1] * RPM:.6g}] rev/min")
    if thr.threshold_rad_s is None:
        print(f"stable up to {s[-1] * RPM:.6g} rev/min: no tracked mode's log decrement crosses zero "
              f"(smallest {np.nanmin(np.where(np.isfinite(thr.scan.log_decrement), thr.scan.log_decrement, np.nan)):.4g})")
    else:
        first = "already unstable at the lowest speed " if thr.unstable_from_start else ""
        print(f"stability threshold: {first}{thr.threshold_rad_s * RPM:.3f} rev/min = {thr.threshold_rad_s:.5f} rad/s, "
              f"mode {thr.mode + 1} ({thr.whirl} whirl) at {thr.frequency_rad_s:.5f} rad/s "
              f"({thr.frequency_rad_s / (2 * np.pi):.4f} Hz)")
        if op is not None and thr.threshold_rad_s <= op[1]:
            print(f"warning: the threshold lies below the top of the operating range ({op[1] * RPM:.6g} rev/min)")
    if level1 is not None:
        from ..rotor.api_level1 import EDITION

        print(f"API Level I screening ({EDITION}) at {level1.speed_rad_s * RPM:.6g} rev/min, {level1.machine}, Q at "
              f"{level1.placement}: " + ", ".join(f"x = {x:g} m" for x, _ in level1.stations)
              + (f"; without {', '.join(level1.excluded)}" if level1.excluded else ""))
        for st, q in zip(spec["stages"], level1.stage_q):
            print(f"  stage {st.name or 'at x = ' + format(st.x, 'g') + ' m'}: q = {q:.6g} N/m (P {st.power:g} W, "
                  f"D {st.diameter:g} m, H {st.width:g} m, rho_d/rho_s {st.density_ratio:g})")
        q0 = "> 1000 QA" if level1.q0 is None else f"{level1.q0:.6g} N/m"
        print(f"  QA = {level1.q_a:.6g} N/m; log decrement at QA {level1.log_decrement_a:.4f}; Q0 = {q0}"
              + ("" if level1.ratio is None else f"; Q0/QA = {level1.ratio:.4g}"))
        for c in level1.criteria:
            v = "n/a" if c["value"] is None else f"{c['value']:.4g}"
            print(f"  criterion {c['name']}: {v}: {'ok' if c['passed'] else 'FAILS'}")
        print("  " + ("passes Level I" if level1.passed else "Level II analysis required")
              + " (the CSR-density screen of SP6.8.5.10 is not implemented)")
        for w in level1.warnings:
            print(f"  warning: {w}")
    for w in thr.warnings + thr.scan.warnings:
        print(f"warning: {w}", file=sys.stderr)
    if args.csv:
        scan = thr.scan
        head = ["speed_rpm", "speed_rad_s"] + [f"mode{j + 1} log_decrement" for j in range(scan.n_modes)]
        rows = [[v * RPM, v] + [x if np.isfinite(x) else "" for x in scan.log_decrement[i]]
                for i, v in enumerate(scan.speeds_rad_s)]
        write_csv(args.csv, head, rows)
        print(f"wrote {args.csv}")
    if args.plot:
        from ..rotor.plots_stability import plot_stability

        print(f"wrote {plot_stability(thr, args.plot, level1=level1, title=study.title, operating_range=op)}")
    return 0
