"""The CSV tables of the commands, as (header, rows) for the one CSV writer (:func:`write_csv`)."""
from __future__ import annotations

import numpy as np

from .tablefile import write_csv


def harmonic(res):
    """Linear forced response: f, omega, then amplitude, lag, Re, Im of every output."""
    head = ["f_hz", "omega_rad_s"] + [f"{o} {q}" for o in res.outputs for q in ("amplitude", "lag_deg", "re", "im")]
    rows = []
    for j in range(res.omega_rad_s.size):
        row = [res.frequencies_hz[j], res.omega_rad_s[j]]
        for k in range(len(res.outputs)):
            z = res.response[j, k]
            row += [abs(z), res.phase_lag_deg[j, k], z.real, z.imag]
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


def afc(res):
    """Nonlinear amplitude-frequency curve in continuation order."""
    z = res.z
    rows = [[res.omega[i], "" if z is None else z[i], res.response[i], int(bool(res.stable[i])),
             "" if not np.isfinite(res.max_multiplier[i]) else res.max_multiplier[i]] for i in range(res.omega.size)]
    return ["omega_rad_s", "z", res.response_label, "stable", "max_multiplier"], rows


def time_history(res):
    """Lumped simulation: t, <dof>.x, <dof>.v for every DOF (drivers included), energy, work."""
    has_e = res.energy.size == res.t.size
    head = ["t"] + [f"{n}.{c}" for n in res.names for c in ("x", "v")] + (["energy", "work"] if has_e else [])
    rows = []
    for k in range(res.t.size):
        row = [res.t[k]]
        for i in range(len(res.names)):
            row += [res.x[i, k], res.v[i, k]]
        if has_e:
            row += [res.energy[k], res.work[k]]
        rows.append(row)
    return head, rows


def hybrid(res):
    """Hybrid simulation: t, every FE DOF of the sampled field, then the lumped bodies' x and v."""
    sys_ = res.fe.system
    comp = res.compiled
    bodies = list(range(comp.n_fe, comp.system.n_dofs))
    solver = res.solver
    idx = np.searchsorted(solver.t, res.t).clip(0, solver.t.size - 1)
    head = ["t"] + sys_.labels() + [f"{comp.system.dof_name[i]}.{c}" for i in bodies for c in ("x", "v")]
    rows = []
    for k in range(res.t.size):
        row = [res.t[k]] + list(res.field_history[k])
        for i in bodies:
            row += [solver.x[i, idx[k]], solver.v[i, idx[k]]]
        rows.append(row)
    return head, rows


def write(path, table) -> None:
    head, rows = table
    write_csv(path, head, rows)
