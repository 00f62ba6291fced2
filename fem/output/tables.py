"""Text tables printed by the command line (they take results, never recompute them).  ``out``: a text
stream, default the ``sys.stdout`` of the moment of the call (not of the import: a test harness or a
caller may replace and close streams in between)."""
from __future__ import annotations

import sys

import numpy as np


def modal_table(study, res, out=None) -> None:
    out = sys.stdout if out is None else out
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
    out = sys.stdout if out is None else out
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
    for j in idx:
        row = "".join(f" | {res.amplitude[j, k]:12.5e}{res.phase_lag_deg[j, k]:12.3f}" for k in range(len(res.outputs)))
        print(f"{res.frequencies_hz[j]:12.5f}{row}", file=out)
    if idx.size < res.omega_rad_s.size:
        print(f"({res.omega_rad_s.size} frequencies; every {res.omega_rad_s.size // idx.size}th shown, --all for all)",
              file=out)


def simulation_summary(title: str, d: dict, out=None) -> None:
    out = sys.stdout if out is None else out
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
