"""Time integration of a reduced rotor with radial clearances (rub, bearing clearance) during a run-up.

Both integrators solve  eta'' + (C(Omega) + Omega G) eta' + K(Omega) eta = f_u(t) + sum b F_contact
(:mod:`fem.rotor.reduced`) along the speed ramp Omega(t) = Omega_0 + alpha t, with the unbalance
forces of a mass m e at the angle phi(t) + beta:  F_y + i F_z = m e (Omega^2 - i alpha) e^{i(phi + beta)}.

* :func:`integrate_compliant` (``method = "event"``): compliant contacts
  (:class:`~discrete.nonsmooth.elements.radial.RadialClearance` with a stiffness) as piecewise
  smooth modes, open / in contact with the slip direction held; DOP853 inside a mode, the mode
  changes located as roots of the guards on the dense output (contact at k (rho - delta) + c rho'
  H(rho - delta) = 0 rising, separation at N = 0 falling, slip reversal at v_s = 0) and the
  integration restarted there.  The energy balance integrates the power of every force with the
  state, so its residual measures the integration error.  A slip reversal (sticking contact,
  dry whip) is outside the compliant law: the run stops there and says so.
* :func:`integrate_moreau` (``method = "moreau"``): rigid contacts with Newton's restitution and
  Coulomb friction (stick included), Moreau-Jean with theta = 1/2 and the contacts' index set
  from the position predicted half a step ahead; the 2 x 2 local problem of each contact is solved
  exactly (:meth:`RadialClearance.impulse`), several contacts by block Gauss-Seidel.  With theta
  = 1/2 the discrete energy balance is an identity (kinetic + potential change = works of the
  step), so its residual is round-off.

Work categories: ``unbalance`` (the forcing), ``damping`` (-eta'.C_sym eta': bearings, shaft),
``circulatory`` (-eta'.K_skew eta: cross-coupled stiffness), ``parametric`` (speed-dependent
bearing stiffness changing along the ramp), ``contact_loss`` (contact damping; impact losses),
``friction`` (friction on the lateral motion); ``spin_friction`` is the friction's work on the spin
(the braking torque mu N R times Omega: the drive makes it up; not part of the lateral balance);
``projection`` the strain-energy change of Moreau-Jean's position projection onto the clearance
circles (a numerical term: it shrinks with the step); ``bearings`` the work of the smooth planar
elements (fluid films, rolling-element clearance laws: :class:`SmoothPlanarElement`, evaluated at
every state; Moreau-Jean takes their force at the step's predicted midpoint, explicitly);
``static_load`` the work of the constant load (the weight the bearings carry).  The last two are
reported only when the run has such elements or loads.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
from scipy.integrate import solve_ivp

from discrete.errors import SolverError

WORKS = ("unbalance", "damping", "circulatory", "parametric", "contact_loss", "friction", "spin_friction", "projection",
         "bearings", "static_load")
_OPTIONAL_WORKS = ("bearings", "static_load")


@dataclass
class SpeedRamp:
    """Omega(t) = start + (end - start) t / duration (rad/s); the shaft's angle phi = int Omega dt."""

    start: float
    end: float
    duration: float

    @property
    def acceleration(self) -> float:
        return (self.end - self.start) / self.duration

    def speed(self, t):
        return self.start + self.acceleration * t

    def angle(self, t):
        return self.start * t + 0.5 * self.acceleration * t * t


class UnbalanceLoad:
    """Reduced unbalance forces f(t) = Re(z A_y) + Im(z A_z), z = (Omega^2 - i alpha) e^{i phi}:
    A_y = sum m e e^{i beta} b_v, A_z likewise with b_w (b: rows of the basis at the node)."""

    def __init__(self, A_y: np.ndarray, A_z: np.ndarray, ramp: SpeedRamp):
        self.A_y, self.A_z, self.ramp = A_y, A_z, ramp

    def __call__(self, t: float) -> np.ndarray:
        r = self.ramp
        z = (r.speed(t) ** 2 - 1j * r.acceleration) * np.exp(1j * r.angle(t))
        return (z * self.A_y).real + (z * self.A_z).imag

    def steady_amplitude(self, speed: float) -> np.ndarray:
        """Complex amplitude F of f = Re(F e^{i Omega t}) at a constant speed."""
        return speed ** 2 * (self.A_y - 1j * self.A_z)


@dataclass
class Trajectory:
    """What an integrator returns: samples (t, eta, eta'), per-contact contact flags and normal
    forces at the samples, the events, the works, the stop reason (None: reached the end)."""

    t: np.ndarray
    eta: np.ndarray
    eta_dot: np.ndarray
    normal_force: np.ndarray          # (n_t, n_contacts)
    slip: np.ndarray                  # (n_t, n_contacts) slip velocity
    in_contact: np.ndarray            # (n_t, n_contacts) bool
    events: list
    works: dict
    energy_start: float
    energy_end: float
    stopped: str | None
    steps: int
    max_penetration: np.ndarray       # (n_contacts,) rigid contacts: largest rho - delta (m)
    warnings: list = field(default_factory=list)


def _mechanical(eta, v, Ks) -> float:
    """Kinetic + strain energy of the reduced rotor (M = I) with the symmetric stiffness Ks."""
    return float(0.5 * v @ v + 0.5 * eta @ Ks @ eta)


class _Model:
    """The reduced rotor's forces at (t, eta, eta') with the contacts' kinematics."""

    def __init__(self, red, ramp: SpeedRamp, load: UnbalanceLoad, contacts, smooth=(), static=None):
        self.red, self.ramp, self.load, self.contacts = red, ramp, load, list(contacts)
        self.n = red.n
        self.by = np.array([c.g_y for c in self.contacts]).reshape(-1, self.n)
        self.bz = np.array([c.g_z for c in self.contacts]).reshape(-1, self.n)
        self.smooth = list(smooth)
        self.sy = np.array([e.g_y for e in self.smooth]).reshape(-1, self.n)
        self.sz = np.array([e.g_z for e in self.smooth]).reshape(-1, self.n)
        self.static = None if static is None else np.asarray(static, dtype=float)
        # the work categories of this run (an optional one only when present: the state vector, hence the
        # integrator's error norm and steps, of a run without them is as before they existed)
        self.work_keys = [k for k in WORKS if k not in _OPTIONAL_WORKS or (k == "bearings" and self.smooth)
                          or (k == "static_load" and self.static is not None)]
        self.windex = {k: i for i, k in enumerate(self.work_keys)}
        self.const = not red.Kc.shape[0]
        if self.const:
            self.K, self.C = red.K0, red.C0
            self.Ks, self.Kskew, self.Cs = self._parts(self.K, self.C)

    def smooth_forces(self, t: float, eta, v):
        """(reduced force of the smooth planar elements, their power) at (t, eta, eta')."""
        f = np.zeros(self.n)
        power = 0.0
        if not self.smooth:
            return f, power
        Om, phi = self.ramp.speed(t), self.ramp.angle(t)
        y, z, yd, zd = self.sy @ eta, self.sz @ eta, self.sy @ v, self.sz @ v
        for j, e in enumerate(self.smooth):
            Fy, Fz = e.force(y[j], z[j], yd[j], zd[j], Om, phi)
            f += Fy * self.sy[j] + Fz * self.sz[j]
            power += Fy * yd[j] + Fz * zd[j]
        return f, power

    def works(self, values) -> dict:
        """The work dictionary, without the optional categories this run does not have."""
        return dict(zip(self.work_keys, (float(w) for w in values)))

    @staticmethod
    def _parts(K, C):
        return 0.5 * (K + K.T), 0.5 * (K - K.T), 0.5 * (C + C.T)

    def matrices(self, t: float):
        """(K, C + Omega G, K_sym, K_skew, C_sym) at time t."""
        Om = self.ramp.speed(t)
        if self.const:
            return self.K, self.C + Om * self.red.G, self.Ks, self.Kskew, self.Cs
        K, C = self.red.matrices(Om)
        Ks, Kskew, _ = self._parts(K, C)
        C0 = C - Om * self.red.G
        return K, C, Ks, Kskew, 0.5 * (C0 + C0.T)

    def energy(self, t, eta, v, engaged) -> float:
        """Kinetic + strain energy, with the energy of the engaged contacts."""
        E = _mechanical(eta, v, self.matrices(t)[2])
        for j, c in enumerate(self.contacts):
            if engaged[j]:
                E += float(c.potential(self.by[j] @ eta, self.bz[j] @ eta))
        return float(E)


# ------------------------------------------------------------------ compliant contacts: located modes
def _guard_open(c, y, z, yd, zd):
    dy, dz, rho = c.relative(y, z)
    rd = (dy * yd + dz * zd) / max(rho, 1e-300)
    return c.stiffness * (rho - c.clearance) + (c.damping * rd if rho > c.clearance else 0.0)


def _started(fns, t0, Y0):
    """Guards restarted on their boundary: a guard that starts at zero or a round-off on the wrong side
    (the state of a located event) is shifted by twice its start value, so it starts strictly on its
    admissible side and a crossing within the first step is not lost."""
    out = []
    for g in fns:
        v0 = g(t0, Y0)
        off = 0.0
        if g.direction * v0 >= 0:
            off = 2.0 * v0 if v0 != 0 else g.direction * 1e-300
        if off:
            def shifted(t, Y, g=g, off=off):
                return g(t, Y) - off
            shifted.direction, shifted.terminal, shifted.tag = g.direction, g.terminal, g.tag
            out.append(shifted)
        else:
            out.append(g)
    return out


def integrate_compliant(red, ramp: SpeedRamp, load: UnbalanceLoad, contacts, eta0, v0, t_out: np.ndarray, *,
                        rtol: float = 1e-8, max_events: int = 100_000, progress=None, smooth=(),
                        static=None, integrator: str = "DOP853") -> Trajectory:
    """Event-located integration of compliant contacts (see the module docstring); ``smooth``:
    smooth planar elements, ``static``: a constant reduced load; ``integrator`` "DOP853" (explicit,
    order 8) or "LSODA" (switches to BDF where the problem is stiff: fluid films on light journals,
    whose damping over the journal's mass sets the explicit step)."""
    mdl = _Model(red, ramp, load, contacts, smooth, static)
    n, nc = mdl.n, len(mdl.contacts)
    by, bz, cs = mdl.by, mdl.bz, mdl.contacts
    t_end = ramp.duration
    nw = len(mdl.work_keys)

    def local(j, eta, v):
        return by[j] @ eta, bz[j] @ eta, by[j] @ v, bz[j] @ v

    def rhs(t, Y, modes):
        eta, v = Y[:n], Y[n:2 * n]
        K, C, Ks, Kskew, Cs = mdl.matrices(t)
        fu = load(t)
        f = fu.copy()
        dW = np.zeros(nw)
        Om = ramp.speed(t)
        for j in range(nc):
            c = cs[j]
            y, z, yd, zd = local(j, eta, v)
            dy, dz, rho = c.relative(y, z)
            rd = (dy * yd + dz * zd) / max(rho, 1e-300)
            if modes[j]:
                Fy, Fz, N, vs = c.force(y, z, yd, zd, Om, modes[j])
                f += Fy * by[j] + Fz * bz[j]
                dW[4] -= c.damping * rd * rd
                Ft = -c.friction * N * modes[j]
                dW[5] += Ft * (vs - Om * c.radius)
                dW[6] += Ft * Om * c.radius
        if mdl.smooth:
            fb, dW[mdl.windex["bearings"]] = mdl.smooth_forces(t, eta, v)
            f += fb
        if mdl.static is not None:
            f += mdl.static
            dW[mdl.windex["static_load"]] = v @ mdl.static
        dW[0] = v @ fu
        dW[1] = -v @ Cs @ v
        dW[2] = -v @ Kskew @ eta
        if not mdl.const:
            dW[3] = 0.5 * eta @ red.stiffness_rate(Om, ramp.acceleration) @ eta
        a = f - C @ v - K @ eta
        return np.concatenate([v, a, dW])

    def guards(modes):
        fns = []
        for j in range(nc):
            c = cs[j]
            if modes[j] == 0:
                def g(t, Y, j=j, c=c):
                    return _guard_open(c, *local(j, Y[:n], Y[n:2 * n]))
                g.direction, g.tag = 1.0, ("contact", j)
            else:
                def g(t, Y, j=j, c=c):
                    return float(c.normal_force(*local(j, Y[:n], Y[n:2 * n])))
                g.direction, g.tag = -1.0, ("separation", j)
            g.terminal = True
            fns.append(g)
            if modes[j] and c.friction > 0:
                def s(t, Y, j=j, c=c, m=modes[j]):
                    return m * float(c.slip_velocity(*local(j, Y[:n], Y[n:2 * n]), ramp.speed(t)))
                s.direction, s.terminal, s.tag = -1.0, True, ("slip_reversal", j)
                fns.append(s)
        return fns

    def slip_sign(j, eta, v, t):
        vs = float(cs[j].slip_velocity(*local(j, eta, v), ramp.speed(t)))
        return 1 if vs >= 0 else -1

    modes = [slip_sign(j, eta0, v0, 0.0) if _guard_open(cs[j], *local(j, eta0, v0)) > 0 else 0 for j in range(nc)]
    Y = np.concatenate([eta0, v0, np.zeros(nw)])
    E0 = mdl.energy(0.0, eta0, v0, modes)
    # absolute tolerances: positions on the scale of the clearances (or of the start), velocities at the
    # top speed; the work integrals are not error-controlled (their error is what the balance shows)
    s_eta = max([float(np.abs(eta0).max(initial=0.0))] + [c.clearance / max(np.abs(by[j]).max(), np.abs(bz[j]).max(), 1e-300)
                                                           for j, c in enumerate(cs)]
                + [e.scale / max(np.abs(mdl.sy[j]).max(), np.abs(mdl.sz[j]).max(), 1e-300)
                   for j, e in enumerate(mdl.smooth)] + [1e-12])
    s_v = max(float(np.abs(v0).max(initial=0.0)), s_eta * max(ramp.start, ramp.end, red.omega.min(initial=1.0)))
    atol = np.concatenate([np.full(n, rtol * s_eta), np.full(n, rtol * s_v), np.full(nw, 1e30)])
    ts, Ys, modes_at, events, steps, t, stopped = [], [], [], [], 0, 0.0, None
    max_step = 2 * math.pi / max(red.omega.max() if integrator == "DOP853" else 8 * max(ramp.start, ramp.end),
                                 ramp.end, 1e-12)
    chunk = t_end / 50                  # the integration restarts at least every 2 % (progress, bounded memory)
    while t < t_end:
        t_stop = t_end if t_end - t <= 1.5 * chunk else t + chunk
        te = t_out[(t_out > t) & (t_out < t_stop)]
        te = np.concatenate([[t] if not ts else [], te, [t_stop]])
        extra = not np.any(t_out == t_stop)          # t_stop is sampled to carry the state on, not an output
        fns = _started(guards(modes), t, Y)
        held = list(modes)
        sol = solve_ivp(lambda tt, YY: rhs(tt, YY, held), (t, t_stop), Y, method=integrator, t_eval=te,
                        events=fns or None, rtol=rtol, atol=atol, max_step=max_step)
        steps += int(sol.nfev)
        if sol.status == -1:
            stopped = f"the integrator failed at t = {t:.6g} s: {sol.message}"
            break
        keep = np.size(sol.t) - (1 if sol.status == 0 and extra else 0)
        if keep > 0:
            ts.append(np.asarray(sol.t)[:keep])
            Ys.append(sol.y[:, :keep])
            modes_at.append(np.repeat(np.array(modes, dtype=int)[None, :], keep, 0))
        if sol.status == 0:
            Y, t = sol.y[:, -1].copy(), t_stop
            if progress is not None:
                progress(t / t_end)
            continue
        hit = [k for k, tev in enumerate(sol.t_events) if tev.size]
        k = hit[0]
        t, Y = float(sol.t_events[k][0]), sol.y_events[k][0].copy()
        kind, j = fns[k].tag
        eta, v = Y[:n], Y[n:2 * n]
        y, z, yd, zd = local(j, eta, v)
        rec = {"t": t, "kind": kind, "rub": cs[j].name, "speed_rad_s": float(ramp.speed(t)),
               "radius": float(cs[j].relative(y, z)[2])}
        # the contact's energy k (rho - delta)^2 / 2 counts in contact only: a damped contact that releases
        # (N = 0) or engages while rho > delta leaves or takes it at once (a loss, or a gain, of the clipped law)
        pen = max(float(cs[j].relative(y, z)[2]) - cs[j].clearance, 0.0)
        jump = 0.5 * cs[j].stiffness * pen * pen
        if kind == "contact":
            modes[j] = slip_sign(j, eta, v, t)
            Y[2 * n + 4] += jump
        elif kind == "separation":
            modes[j] = 0
            Y[2 * n + 4] -= jump
        else:
            events.append(rec)
            stopped = (f"the slip velocity at rub {cs[j].name!r} reached zero at t = {t:.6g} s (speed "
                       f"{rec['speed_rad_s']:.6g} rad/s): the contact would stick (dry whip), which the compliant "
                       "law does not model; use method = 'moreau' (rigid contact with Coulomb stick)")
            break
        events.append(rec)
        if len(events) > max_events:
            stopped = (f"more than {max_events} contact events by t = {t:.6g} s (chattering contact): raise "
                       "[run_up] max_events or add contact damping")
            break
        if progress is not None:
            progress(t / t_end)
    T = np.concatenate(ts) if ts else np.zeros(0)
    Yh = np.hstack(Ys) if Ys else np.zeros((2 * n + nw, 0))
    modes_h = np.vstack(modes_at) if modes_at else np.zeros((0, nc), dtype=int)
    keep = np.concatenate([[True], np.diff(T) > 0]) if T.size else np.zeros(0, bool)
    T, Yh, modes_h = T[keep], Yh[:, keep], modes_h[keep]
    eta_h, v_h = Yh[:n].T, Yh[n:2 * n].T
    N = np.zeros((T.size, nc))
    slip = np.zeros((T.size, nc))
    for j, c in enumerate(cs):
        y, z, yd, zd = eta_h @ by[j], eta_h @ bz[j], v_h @ by[j], v_h @ bz[j]
        N[:, j] = np.where(modes_h[:, j] != 0, c.normal_force(y, z, yd, zd), 0.0)
        slip[:, j] = c.slip_velocity(y, z, yd, zd, ramp.speed(T))
    works = mdl.works(Y[2 * n:])
    E1 = mdl.energy(t, Y[:n], Y[n:2 * n], modes)
    return Trajectory(t=T, eta=eta_h, eta_dot=v_h, normal_force=N, slip=slip, in_contact=modes_h != 0, events=events,
                      works=works, energy_start=E0, energy_end=E1, stopped=stopped, steps=steps,
                      max_penetration=np.zeros(nc))


# ------------------------------------------------------------------ rigid contacts: Moreau-Jean
def integrate_moreau(red, ramp: SpeedRamp, load: UnbalanceLoad, contacts, eta0, v0, t_out: np.ndarray, h: float, *,
                     progress=None, smooth=(), static=None) -> Trajectory:
    """Moreau-Jean (theta = 1/2) with rigid radial contacts (see the module docstring); ``smooth``
    planar elements explicitly at the predicted midpoint, ``static`` a constant reduced load."""
    mdl = _Model(red, ramp, load, contacts, smooth, static)
    n, nc = mdl.n, len(mdl.contacts)
    by, bz, cs = mdl.by, mdl.bz, mdl.contacts
    t_end = ramp.duration
    steps = int(math.ceil(t_end / h - 1e-9))
    h = t_end / steps
    out_idx = np.unique(np.clip(np.rint(t_out / h).astype(int), 0, steps))
    q, v = np.array(eta0, float), np.array(v0, float)
    works = mdl.works(np.zeros(len(mdl.work_keys)))
    rec_t, rec_q, rec_v, rec_N, rec_s, rec_c = [], [], [], [], [], []
    state = ["free"] * nc
    events = []
    pen = np.zeros(nc)
    Ks_prev = None
    last_P = np.zeros((nc, 2))
    last_slip = np.zeros(nc)
    next_out = 0
    unconverged = 0

    def record(k, t):
        nonlocal next_out
        while next_out < out_idx.size and out_idx[next_out] == k:
            rec_t.append(t)
            rec_q.append(q.copy())
            rec_v.append(v.copy())
            rec_N.append(last_P[:, 0] / h)
            rec_s.append(last_slip.copy())
            rec_c.append([s != "free" for s in state])
            next_out += 1

    record(0, 0.0)
    for k in range(steps):
        t0 = k * h
        tm = t0 + 0.5 * h
        Om = float(ramp.speed(tm))
        K, C, Ks, Kskew, Cs = mdl.matrices(tm)
        if Ks_prev is None:
            E0 = _mechanical(q, v, Ks)      # the balance's reference: the first step's stiffness
        else:
            works["parametric"] += 0.5 * q @ (Ks - Ks_prev) @ q
        Ks_prev = Ks
        A = np.eye(n) + 0.5 * h * C + 0.25 * h * h * K
        lu = sla.lu_factor(A)
        f = load(tm)
        fx = None
        if mdl.smooth or mdl.static is not None:
            fb, _ = mdl.smooth_forces(tm, q + 0.5 * h * v, v)
            fx = fb + (mdl.static if mdl.static is not None else 0.0)
        v_free = sla.lu_solve(lu, v - 0.5 * h * (C @ v) - h * (K @ q) - 0.25 * h * h * (K @ v) + h * (f if fx is None
                                                                                                      else f + fx))
        # index set: contacts whose position predicted half a step ahead is at or beyond the clearance
        qp = q + 0.5 * h * v
        Hs, Ws, Ufree, un0, active = [], [], [], [], []
        for j, c in enumerate(cs):
            y, z = by[j] @ qp, bz[j] @ qp
            if c.relative(y, z)[2] < c.clearance:
                continue
            ny, nz, ty, tz = c.frame(y, z)
            hn, ht = ny * by[j] + nz * bz[j], ty * by[j] + tz * bz[j]
            H = np.column_stack([-hn, ht])
            AH = sla.lu_solve(lu, H)
            active.append(j)
            Hs.append((H, AH))
            Ws.append(H.T @ AH)
            Ufree.append(H.T @ v_free + np.array([0.0, Om * c.radius]))
            un0.append(-hn @ v)
        P = np.zeros((len(active), 2))
        cases = ["free"] * len(active)
        for _sweep in range(1 if len(active) <= 1 else 100):
            change = 0.0
            for a, j in enumerate(active):
                U = Ufree[a] + sum(Hs[a][0].T @ (Hs[b][1] @ P[b]) for b in range(len(active)) if b != a)
                Pa, cases[a] = cs[j].impulse(Ws[a], U, un0[a])
                change = max(change, float(np.abs(Pa - P[a]).max()))
                P[a] = Pa
            if change <= 1e-12 * (np.abs(P).max(initial=0.0) + 1e-300):
                break
        else:
            if len(active) > 1:
                unconverged += 1
        v_new = v_free.copy()
        for a in range(len(active)):
            v_new += Hs[a][1] @ P[a]
        vm = 0.5 * (v + v_new)
        q_new = q + h * vm
        qm = 0.5 * (q + q_new)
        works["unbalance"] += h * vm @ f
        if fx is not None:
            if mdl.smooth:
                works["bearings"] += h * vm @ fb
            if mdl.static is not None:
                works["static_load"] += h * vm @ mdl.static
        works["damping"] -= h * vm @ Cs @ vm
        works["circulatory"] -= h * vm @ Kskew @ qm
        last_P[:] = 0.0
        for a, j in enumerate(active):
            H = Hs[a][0]
            works["contact_loss"] += P[a, 0] * (H[:, 0] @ vm)
            works["friction"] += P[a, 1] * (H[:, 1] @ vm)
            works["spin_friction"] += P[a, 1] * Om * cs[j].radius
            last_P[j] = P[a]
        new_state = ["free"] * nc
        for a, j in enumerate(active):
            new_state[j] = cases[a] if P[a, 0] > 0 else "free"
        t1 = t0 + h
        # position projection of the engaged contacts back onto their clearance circles (the velocity-level
        # law alone lets a persistent contact on a curved boundary drift outwards by ~ delta (Omega h)^2 / 2
        # per step): the shortest correction in the mass metric, its strain-energy change reported as the
        # work "projection"
        for a, j in enumerate(active):
            if P[a, 0] <= 0:
                continue
            c = cs[j]
            pen[j] = max(pen[j], float(c.relative(by[j] @ q_new, bz[j] @ q_new)[2] - c.clearance))
            for _it in range(3):
                y, z = by[j] @ q_new, bz[j] @ q_new
                over = float(c.relative(y, z)[2] - c.clearance)
                if over <= 1e-14 * c.clearance:
                    break
                ny, nz, _, _ = c.frame(y, z)
                hn = ny * by[j] + nz * bz[j]
                dq = -over * hn / (hn @ hn)
                works["projection"] += 0.5 * (q_new + dq) @ Ks @ (q_new + dq) - 0.5 * q_new @ Ks @ q_new
                q_new = q_new + dq
        for j, c in enumerate(cs):
            y, z, yd, zd = by[j] @ q_new, bz[j] @ q_new, by[j] @ v_new, bz[j] @ v_new
            pen[j] = max(pen[j], float(c.relative(y, z)[2] - c.clearance))
            last_slip[j] = float(c.slip_velocity(y, z, yd, zd, ramp.speed(t1)))
            old, new = state[j], new_state[j]
            if old != new:
                kind = new if new == "paradox" else "contact" if old == "free" else "separation" if new == "free" else new
                events.append({"t": t1, "kind": kind, "rub": c.name, "speed_rad_s": float(ramp.speed(t1)),
                               "radius": float(c.relative(y, z)[2])})
        state = new_state
        q, v = q_new, v_new
        record(k + 1, t1)
        if progress is not None and k % 1000 == 0:
            progress(t1 / t_end)
    E_now = _mechanical(q, v, Ks_prev)         # steps >= 1: Ks_prev is the last step's stiffness
    return Trajectory(t=np.array(rec_t), eta=np.array(rec_q).reshape(-1, n), eta_dot=np.array(rec_v).reshape(-1, n),
                      normal_force=np.array(rec_N).reshape(len(rec_t), nc), slip=np.array(rec_s).reshape(len(rec_t), nc),
                      in_contact=np.array(rec_c, dtype=bool).reshape(len(rec_t), nc), events=events, works=works,
                      energy_start=E0, energy_end=E_now, stopped=None, steps=steps,
                      max_penetration=np.maximum(pen, 0.0),
                      warnings=[f"{unconverged} steps where the block Gauss-Seidel over simultaneous contacts did not "
                                "converge in 100 sweeps (their impulses are the last sweep's)"] if unconverged else [])


def check_rigid(contacts, method: str) -> None:
    """The compliant integrator needs a stiffness on every contact, Moreau-Jean rigid contacts."""
    for c in contacts:
        if method == "event" and c.rigid:
            raise SolverError(f"rub {c.name!r} is a rigid contact: method = 'event' needs a contact stiffness "
                              "(or use method = 'moreau')")
        if method == "moreau" and not c.rigid:
            raise SolverError(f"rub {c.name!r} has a contact stiffness: method = 'moreau' treats rigid contacts "
                              "with restitution (leave out the stiffness, or use method = 'event')")
