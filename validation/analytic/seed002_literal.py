"""Seed 002 (1)-(2) read literally, for Figs. 2-3 (phase portraits): the strand force is zero while the spool
angle phi < 0 and c (r phi + a sin w1 t) otherwise, with phi counted from the untensioned position (so the
clutch torque M0 = F0 r holds the static state at phi_s = F0/(c r)), the losses of (1) acting on phi'.

This differs from the package's reading (validation.analytic.steady_seed002: slack iff the strand's
elongation r phi - x_cam falls below -F0/c) in that the switch looks at the spool angle alone, not at the
strand; under it the strand can even push (c (r phi + a sin) < 0 with phi >= 0).  Integrated here with scipy
(DOP853), the sign changes of phi and phi' located as events and the right-hand side fixed between them
(no smoothing of sign): an independent code, not the package's solvers."""
from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from .steady_seed002 import C_STRAND, COMBINED, F0, J, K_NAT, M0, R, SIMPLE


def literal_orbit(friction: str, a: float, z: float, periods: int = 80, keep: int = 2, samples: int = 400,
                  switch: str = "angle") -> dict:
    """The state after ``periods`` forcing periods from the static state (phi_s, 0), sampled over the last
    ``keep`` periods: t, phi (from the untensioned position), phi', the strand force c (r phi + a sin w1 t)
    (zero while phi < 0), and phi_s.  ``switch = "tension"``: the force is zero while c (r phi + a sin w1 t)
    itself would be negative -- the physical slack condition of the package's reading, integrated by the
    same independent code (with phi from the untensioned position, F0 is the static value of that force)."""
    w = z * K_NAT
    kin = COMBINED["kinetic"] if friction == "combined" else 0.0
    vis = COMBINED["viscous"] if friction == "combined" else SIMPLE["viscous"]
    quad = COMBINED["quadratic"] if friction == "combined" else 0.0
    T = 2 * np.pi / w

    def gate(t, y):
        """The switching quantity: the angle (literal reading) or the strand force itself."""
        return y[0] if switch == "angle" else R * y[0] + a * np.sin(w * t)

    def rhs(t, y, taut, sv):
        p, v = y
        F = C_STRAND * (R * p + a * np.sin(w * t)) if taut else 0.0
        return [v, (M0 - R * F - kin * sv - vis * v - quad * sv * v * v) / J]

    phi_s = F0 / (C_STRAND * R)
    y = np.array([phi_s, 0.0])
    t0, t_end = 0.0, periods * T
    t_keep = np.linspace(t_end - keep * T, t_end, keep * samples + 1)
    taut = True
    ts, ys = [], []

    def drive(t, p, taut):
        """Torque on the spool at rest (clutch minus strand)."""
        return M0 - (R * C_STRAND * (R * p + a * np.sin(w * t)) if taut else 0.0)

    def leave_stick(t0, y):
        """From rest at t0: the time the torque exceeds the kinetic level, and the direction."""
        if abs(drive(t0, y[0], taut)) > kin:
            return t0, np.sign(drive(t0, y[0], taut))
        grid = t0 + np.linspace(0, T, 2001)[1:]
        g = np.abs([drive(t, y[0], taut) for t in grid]) - kin
        j = int(np.argmax(g > 0))
        if g[j] <= 0:
            raise RuntimeError(f"literal_orbit: the spool stays stuck from t = {t0:.6g}")
        lo = grid[j - 1] if j else t0
        t1 = brentq(lambda t: abs(drive(t, y[0], taut)) - kin, lo, grid[j], xtol=1e-15, rtol=1e-15)
        t1 = min(t1 * (1 + 1e-14) + 1e-15, grid[j])
        return t1, np.sign(drive(t1, y[0], taut))

    t0, sv = leave_stick(t0, y)
    def on_vel(t, yy):
        return yy[1]

    gate.terminal = on_vel.terminal = True
    for _ in range(200 * periods):
        gate.direction = -1.0 if taut else 1.0         # the next crossing leaves the current side
        on_vel.direction = -sv
        sel = t_keep[t_keep > t0]
        s = solve_ivp(lambda t, yy: rhs(t, yy, taut, sv), (t0, t_end), y, method="DOP853", rtol=1e-10, atol=1e-13,
                      events=(gate, on_vel), t_eval=sel if sel.size else None, max_step=T / 50, first_step=min(T / 1e4, t_end - t0))
        if sel.size and len(s.t):
            ts.append(np.asarray(s.t))
            ys.append(s.y.reshape(2, -1))
        if s.status != 1:
            break
        hit_phi = s.t_events[0].size > 0
        t0 = float(s.t_events[0][0] if hit_phi else s.t_events[1][0])
        y = np.array(s.y_events[0][0] if hit_phi else s.y_events[1][0], float)
        if hit_phi:
            taut = not taut
            if switch == "angle":
                y[0] = 0.0
        else:
            y[1] = 0.0
            sv = -sv
            if rhs(t0, y, taut, sv)[1] * sv < 0:       # neither direction is consistent: it sticks
                t0, sv = leave_stick(t0, y)
    else:
        raise RuntimeError("literal_orbit: too many switches")
    t = np.concatenate(ts)
    q = np.concatenate(ys, axis=1)
    order = np.argsort(t)
    t, p, v = t[order], q[0, order], q[1, order]
    F = C_STRAND * (R * p + a * np.sin(w * t))
    F = np.where((p < 0) if switch == "angle" else (F < 0), 0.0, F)
    return {"t": t, "phi": p, "phidot": v, "force": F, "phi_s": phi_s}
