"""Text tables printed by the command line (they take results, never recompute them)."""
from __future__ import annotations

import sys

import numpy as np


def modal_table(study, res, out=None) -> None:
    out = sys.stdout if out is None else out      # bound at call time (a captured stream may close)
    if study.kind == "drive":
        print((study.title + "\n" if study.title else "") + res.table(), file=out)
        return
    if study.kind == "fe":
        m = study.shaft
        head = (f"{m.physics}" + (f" ({m.theory})" if m.physics == "bending" else "")
                + f", {m.element_name}, {m.mass} mass, {study.fe_model.mesh.n_elements} elements")
    elif study.kind == "hybrid":
        head = f"hybrid model, {study.compiled.system.n_dofs} DOFs (FE part {'reduced' if study.compiled.reduced else 'full'})"
    else:
        head = f"lumped drive, {len(study.lumped.bodies)} bodies"
    print(f"{study.title}\n{head}; {res.n_dofs} free DOFs; solver: {res.method}", file=out)
    print(f"{'mode':>4} {'f [Hz]':>14} {'omega [rad/s]':>14} {'residual':>9} {'RQ mism.':>9}  note", file=out)
    for r in range(res.omega_rad_s.size):
        note = "rigid-body" if res.rigid[r] else ("" if res.reliable[r] else "NOT RELIABLE (see warnings)")
        if res.reliable[r] or res.rigid[r]:
            f, w = f"{res.frequencies_hz[r]:14.6f}", f"{res.omega_rad_s[r]:14.6f}"
        else:
            f = w = f"{'--':>14}"
        print(f"{r + 1:4d} {f} {w} {res.residuals[r]:9.1e} {res.rayleigh_rel_diff[r]:9.1e}  {note}".rstrip(), file=out)
    for wmsg in res.warnings:
        print(f"warning: {wmsg}", file=out)


def dunkerley_line(bound: float, omega1: float) -> str:
    return (f"Dunkerley's lower bound (4.40) of the first frequency: {bound:.6f} rad/s "
            f"({100 * (bound / omega1 - 1):+.2f} %)")


def forced_table(study, res, all_rows: bool = False, out=None) -> None:
    out = sys.stdout if out is None else out      # bound at call time (a captured stream may close)
    from discrete.steady import AFCResult

    if isinstance(res, AFCResult) or study.kind == "drive":
        print((study.title + "\n" if study.title else "") + res.table(), file=out)
        return
    print(f"{study.title}\nharmonic response: {res.method}; damping: {res.damping}", file=out)
    hdr = "".join(f" | {o:>24}" for o in res.outputs)
    print(f"{'f [Hz]':>12}{hdr}\n{'':>12}" + "".join(f" | {'amplitude':>12}{'lag [deg]':>12}" for _ in res.outputs),
          file=out)
    idx = np.arange(res.omega_rad_s.size)
    if idx.size > 40 and not all_rows:
        idx = np.unique(np.linspace(0, idx.size - 1, 40).astype(int))
    ok = res.reliable
    for j in idx:
        row = "".join(f" | {res.amplitude[j, k]:12.5e}{res.phase_lag_deg[j, k]:12.3f}" for k in range(len(res.outputs)))
        print(f"{res.frequencies_hz[j]:12.5f}{row}" + ("" if ok[j] else "  NOT RELIABLE (see warnings)"), file=out)
    if idx.size < res.omega_rad_s.size:
        print(f"({res.omega_rad_s.size} frequencies; every {res.omega_rad_s.size // idx.size}th shown, --all for all)",
              file=out)
    for wmsg in res.warnings:
        print(f"warning: {wmsg}", file=out)


def outputs_lines(d: dict, out=None, limit: int = 12) -> None:
    """The named outputs of a command's JSON ``d`` (``named_outputs``), one line each up to ``limit``:
    time histories -- peak, mean, rms, peak-to-peak, dynamic load factor, and per element its impacts and
    friction work; frequency responses and [steady] curves -- the largest amplitude and where; modes --
    how many load shapes were written."""
    out = sys.stdout if out is None else out
    outs = d.get("named_outputs") or {}
    for note in d.get("named_outputs_notes") or ():
        print(f"note: {note}", file=out)
    if not outs:
        return
    first = next(iter(outs.values()))
    if "modes" in first:
        print(f"load shapes of {len(outs)} named outputs per mode in the JSON (named_outputs) and the CSV", file=out)
        return
    if "rms" in first:
        print(f"{'output':<34} {'unit':>15} {'peak':>12} {'mean':>12} {'rms':>12} {'peak-peak':>12} {'DLF':>8}",
              file=out)
    else:
        print(f"{'output':<40} {'unit':>15} {'max amplitude':>14} {'at omega [rad/s]':>17}", file=out)
    for k, (name, o) in enumerate(outs.items()):
        if k == limit:
            print(f"... {len(outs) - limit} more outputs in the JSON/CSV", file=out)
            break
        if "rms" in o:
            dlf = o.get("dynamic_load_factor")
            print(f"{name[:34]:<34} {o['unit'][:15]:>15} {o['peak']:12.5g} {o['mean']:12.5g} {o['rms']:12.5g} "
                  f"{o['peak_to_peak']:12.5g} {'' if dlf is None else format(dlf, '8.4g'):>8}", file=out)
            continue
        peak = o.get("max_amplitude", o.get("peak"))
        w = o.get("at_omega_rad_s", o.get("peak_omega_rad_s", o.get("peak_speed_rad_s")))
        print(f"{name[:40]:<40} {o['unit'][:15]:>15} {'' if peak is None else format(peak, '14.6g'):>14} "
              f"{'' if w is None else format(w, '17.6g'):>17}", file=out)
    for name, e in (d.get("element_summary") or {}).items():
        parts = []
        if "impacts" in e:
            parts.append(f"{e['impacts']} impacts, impulse sum {e['impulse_sum']:.6g}")
        if "friction_work" in e:
            parts.append(f"friction work {e['friction_work']:.6g} (dissipated {e['friction_dissipated']:.6g})")
        if parts:
            print(f"{name}: " + "; ".join(parts), file=out)


def linearisation_lines(records, out=None) -> None:
    """What the linear analysis did with each nonsmooth element (never silently)."""
    out = sys.stdout if out is None else out
    for r in records or ():
        how = "declared" if r["declared"] else "default"
        print(f"linearised: {r['kind']} {r['element']!r} {r['state']} ({how}): {r['note']}", file=out)


def simulation_summary(title: str, d: dict, out=None) -> None:
    out = sys.stdout if out is None else out      # bound at call time (a captured stream may close)
    counts = ", ".join(f"{n} {k}" for k, n in sorted(d.get("event_counts", {}).items()))
    print(f"{title}\nsimulated to t = {d.get('t_end')} ({d.get('method', '')}); {len(d.get('events', []))} events"
          + (f" ({counts})" if counts else "") + f"; period = {d.get('period')}; energy error = {d.get('energy_error')}",
          file=out)
    red = d.get("reduction")
    if red:
        print(f"reduction: {red.get('method')}, {red.get('retained_modes')} modes, highest retained frequency "
              f"{red.get('highest_frequency_hz', float('nan')):.6g} Hz, suggested time step "
              f"{red.get('suggested_time_step_s', float('nan')):.3g} s; restitution at coupling DOFs: "
              + ", ".join(f"{c} {100 * r:.1f} %" for c, r in zip(red.get("coupling_dofs", []), red.get("restitution", []))),
              file=out)
    for wmsg in d.get("warnings", []):
        print(f"warning: {wmsg}", file=out)
    if d.get("stopped_early"):
        print(f"stopped early: {d.get('reason')}", file=out)
