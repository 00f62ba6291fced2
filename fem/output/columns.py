"""The CSV tables of the commands, as (header, rows) for the one CSV writer (:func:`write_csv`)."""
from __future__ import annotations

import numpy as np

from .tablefile import write_csv


def harmonic(res, loads=None):
    """Linear forced response: f, omega, then amplitude, lag, Re, Im of every output, then of every named
    output (element loads, reactions: ``loads``, :class:`fem.loads.analyses.NamedOutputs`)."""
    head = ["f_hz", "omega_rad_s"] + [f"{o} {q}" for o in res.outputs for q in ("amplitude", "lag_deg", "re", "im")]
    names = loads.names if loads is not None else []
    head += [f"{o} {q}" for o in names for q in ("amplitude", "lag_deg", "re", "im")]
    rows = []
    for j in range(res.omega_rad_s.size):
        row = [res.frequencies_hz[j], res.omega_rad_s[j]]
        for k in range(len(res.outputs)):
            z = res.response[j, k]
            row += [abs(z), res.phase_lag_deg[j, k], z.real, z.imag]
        for k in range(len(names)):
            z = complex(loads.values[k, j])
            row += [abs(z), float(np.mod(-np.degrees(np.angle(z)), 360.0)), z.real, z.imag]
        rows.append(row)
    return head, rows


def modal(res, shapes=None):
    """Modes: number, f [Hz], omega [rad/s] (the damped frequency of a rotor's complex mode; empty where not
    reliable), then the load shape of every named output (its value for the mode shape as written in the
    JSON: real, or ``<name> re`` and ``<name> im`` for complex modes)."""
    ok = np.asarray(res.reliable) | np.asarray(res.rigid)
    omega = getattr(res, "omega_damped_rad_s", None)
    omega = res.omega_rad_s if omega is None else omega
    names = shapes.names if shapes is not None else []
    values = shapes.values if shapes is not None else np.zeros((0, omega.size))
    complex_ = np.iscomplexobj(values) and bool(np.any(np.imag(values)))
    head = ["mode", "f_hz", "omega_rad_s"] + ([f"{n} {p}" for n in names for p in ("re", "im")] if complex_ else names)
    rows = []
    for r in range(omega.size):
        row = [r + 1, res.frequencies_hz[r] if ok[r] else "", omega[r] if ok[r] else ""]
        if complex_:
            row += [v for k in range(len(names)) for v in (float(values[k, r].real), float(values[k, r].imag))]
        else:
            row += [float(np.real(values[k, r])) for k in range(len(names))]
        rows.append(row)
    return head, rows


def drive_forced(res):
    """Drive forced response: omega, f, then Re/Im of theta at every station and of y at every output."""
    n = res.theta.shape[1]
    head = ["omega_rad_s", "f_hz"]
    cols = [res.omega_rad_s, res.frequencies_hz]
    for name, arr in (("theta", res.theta), ("y", res.y)):
        for j in range(n):
            cols += [arr[:, j].real, arr[:, j].imag]
            head += [f"{name}{j + 1}_re", f"{name}{j + 1}_im"]
    return head, zip(*cols)


def afc(res, loads=None):
    """Nonlinear amplitude-frequency curve in continuation order, then the amplitude (half the
    peak-to-peak over the period) of every named output at each point."""
    z = res.z
    names = list(loads) if loads else []
    rows = [[res.omega[i], "" if z is None else z[i], res.response[i], int(bool(res.stable[i])),
             "" if not np.isfinite(res.max_multiplier[i]) else res.max_multiplier[i]]
            + [loads[n]["amplitude"][i] for n in names] for i in range(res.omega.size)]
    return ["omega_rad_s", "z", res.response_label, "stable", "max_multiplier"] + [f"{n} amplitude" for n in names], rows


def _output_columns(outputs, idx):
    """(names, columns) of named outputs (:class:`fem.loads.analyses.NamedOutputs`) at the samples idx."""
    if outputs is None:
        return [], []
    return list(outputs.names), [outputs.values[k, idx] for k in range(len(outputs.channels))]


def time_history(res, outputs=None, idx=None):
    """Lumped simulation: t, <dof>.x, <dof>.v for every DOF (drivers included), energy, work, then the
    named outputs (element loads, reactions: docs/outputs.md); ``idx``: the samples written (decimation)."""
    idx = np.arange(res.t.size) if idx is None else idx
    has_e = res.energy.size == res.t.size
    head = ["t"] + [f"{n}.{c}" for n in res.names for c in ("x", "v")] + (["energy", "work"] if has_e else [])
    cols = [res.t[idx]]
    for i in range(len(res.names)):
        cols += [res.x[i, idx], res.v[i, idx]]
    if has_e:
        cols += [res.energy[idx], res.work[idx]]
    names, extra = _output_columns(outputs, idx)
    return head + names, zip(*(c.tolist() for c in cols + extra))


def selected_outputs(t, outputs, idx=None):
    """The [[output]] selection: t and the named outputs only."""
    idx = np.arange(np.size(t)) if idx is None else idx
    names, extra = _output_columns(outputs, idx)
    return ["t"] + names, zip(*(c.tolist() for c in [np.asarray(t)[idx]] + extra))


def hybrid(res, outputs=None):
    """Hybrid simulation: t, every FE DOF of the sampled field, then the lumped bodies' x and v, then the
    named outputs at the same instants."""
    sys_ = res.fe.system
    comp = res.compiled
    bodies = list(range(comp.n_fe, comp.system.n_dofs))
    solver = res.solver
    idx = res.sample_index if res.sample_index is not None else \
        np.searchsorted(solver.t, res.t).clip(0, solver.t.size - 1)
    head = ["t"] + sys_.labels() + [f"{comp.system.dof_name[i]}.{c}" for i in bodies for c in ("x", "v")]
    names, extra = _output_columns(outputs, idx)
    rows = []
    for k in range(res.t.size):
        row = [res.t[k]] + list(res.field_history[k])
        for i in bodies:
            row += [solver.x[i, idx[k]], solver.v[i, idx[k]]]
        row += [c[k] for c in extra]
        rows.append(row)
    return head + names, rows


def write(path, table) -> None:
    head, rows = table
    write_csv(path, head, rows)
