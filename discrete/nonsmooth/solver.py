"""Event-driven integration of a :class:`Problem` with exact mode switches (true stick, no regularisation).

Between events the mode (slip direction / stick of each friction, contact state of each
one-sided spring, gap and stop) is fixed.  A piece in an affine, time-invariant mode is
propagated exactly, ``z(t0 + tau) = expm(A tau) z(t0)``; otherwise (variable mass, quadratic
friction law, smooth gap law) it is integrated with DOP853 at ``rtol`` (default 1e-12).

Event location (exact pieces): the guards are linear functionals ``Cg z`` of the state.  The
piece is marched with a step ``h <= pi / (steps_per_period/2 * rho)`` (rho: spectral radius of A),
and on every step the guard values *and* their derivatives ``Cg A z`` at both ends build a cubic
Hermite model; a sign change, or a dip of the cubic below zero checked against the exact value
at the dip, brackets a root.  This is the guard against the classic failure where a step during
stick jumps over the breakaway instant (a guard that goes negative and comes back within one
step).  Roots are refined by safeguarded Newton on the exact expression to ~1e-15 relative.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from ..errors import SolverError
from ..linalg.expm import expm_small as _expm
from .periodic import detect_period, detect_period_smooth
from .problem import Problem
from .result import Event, SimulationResult



@dataclass
class Options:
    max_events: int = 200_000
    max_step: float | None = None
    steps_per_period: int = 12
    rtol: float = 1e-12            # numeric (non-affine) pieces
    rest_tol: float = 1e-9         # impact accumulation: rebound speed / largest impact speed
    energy: bool = True
    max_zero_length: int = 100     # consecutive events without time progress before giving up
    output_step: float | None = None   # extra output samples inside exact pieces (plots, CSV)
    contact_tol: float = 1e-9      # persistent-contact force counted as negative only below -contact_tol F_ref
    progress: object = None        # called with the time reached (a progress bar of the caller's)


class _Piece:
    """Linear maps and step propagators of one affine mode."""

    def __init__(self, prob: Problem, mode, opts: Options, t_end_span: float):
        self.A, self.Cg, self.tags, self.Fm, self.Sm, self.Sdm = prob.linear_maps(mode)
        self.CgA = self.Cg @ self.A
        self.CgAA = self.CgA @ self.A
        ev = np.linalg.eigvals(self.A)
        rho = float(np.max(np.abs(ev))) if ev.size else 0.0
        h = np.inf if rho == 0 else 2 * np.pi / (opts.steps_per_period * rho)
        if opts.max_step:
            h = min(h, opts.max_step)
        self.h = min(h, t_end_span)
        self._phi = {}
        self.Q = _power_form(prob, mode, self.Fm, self.Sdm)

    def phi(self, tau: float) -> np.ndarray:
        P = self._phi.get(tau)
        if P is None:
            P = _expm(self.A * tau)
            if len(self._phi) < 64:
                self._phi[tau] = P
        return P

    def work_matrix(self, hh):
        """{part: G(hh)} with G = int_0^hh Phi(s)^T Q Phi(s) ds (Van Loan 1978), so the work of each
        source of non-conservative forces over a step is z0^T G z0 exactly (power = z^T Q z)."""
        key = ("w", hh)
        G = self._phi.get(key)
        if G is None:
            n = self.A.shape[0]
            G = {}
            for part, Q in self.Q.items():
                Cm = np.zeros((2 * n, 2 * n))
                Cm[:n, :n] = -self.A.T
                Cm[:n, n:] = Q
                Cm[n:, n:] = self.A
                F = _expm(Cm * hh)
                G[part] = F[n:, n:].T @ F[:n, n:]
            if len(self._phi) < 64:
                self._phi[key] = G
        return G


class EventDrivenSolver:
    def __init__(self, problem: Problem, options: Options | None = None):
        self.p = problem
        self.o = options or Options()
        self._pieces: dict = {}
        self.warnings: list[str] = []
        self._contact_ftol = self._contact_force_tolerances()

    def _contact_force_tolerances(self) -> dict:
        """Round-off tolerance of each persistent contact's force.  When an elastic body lands
        on a stop with restitution 0 the required contact force is exactly zero and grows
        afterwards; its round-off value (-1e-20) must not release the contact, or the run stalls
        on zero-length events.  Scale: F_ref = m_eff omega_max v_ref (effective mass of the
        contact coordinate, highest frequency of the linear part, largest initial or driver
        velocity); the release guard of the next piece then decides from the force's trend."""
        p = self.p
        v0 = np.asarray(getattr(p, "v0", np.zeros(0)), dtype=float)
        vref = max(float(np.max(np.abs(v0))) if v0.size else 0.0,
                   max((abs(d.velocity) + abs(d.amplitude * d.omega) for d in p.drivers.values()), default=0.0),
                   1e-300)
        tol = {}
        for i, el in enumerate(p.elements):
            if el.unilateral:
                g = p.gf[i]
                meff = 1.0 / float(g @ np.linalg.solve(p.M0, g)) if np.any(g) else 0.0
                tol[i] = self.o.contact_tol * meff * max(getattr(p, "omega_max", 0.0), 1e-300) * vref
        return tol

    # ------------------------------------------------------------ helpers
    def _split(self, z):
        nf = self.p.nf
        return z[:nf], z[nf:2 * nf], z[2 * nf:]

    def _eval(self, t, z, mode):
        q, v, e = self._split(z)
        return self.p.evaluate(t, q[:, None], v[:, None], e[:, None], mode)

    def _state_dict(self, z):
        q, v, e = self._split(z)
        x, xd = self.p.full_state(q[:, None], v[:, None], e[:, None])
        return {n: {"x": float(x[i, 0]), "v": float(xd[i, 0])} for i, n in enumerate(self.p.names)}

    def _project(self, t, z, i, target, velocity: bool):
        """Set s'_i (``velocity``) or s_i to ``target`` with the smallest mass-weighted change of the
        velocities or positions (the kinetic-energy-minimal projection along M^-1 g_i)."""
        p = self.p
        q, v, e = self._split(z)
        g = p.gf[i]
        current = g @ v + p.gve[i] @ e if velocity else g @ q + p.ge[i] @ e
        Mig = np.linalg.solve(p.mass(t), g)
        z = z.copy()
        part = slice(p.nf, 2 * p.nf) if velocity else slice(0, p.nf)
        z[part] += Mig * (target - current) / (g @ Mig)
        return z

    def _project_velocity(self, t, z, i, target):
        return self._project(t, z, i, target, velocity=True)

    def _project_position(self, t, z, i, target):
        return self._project(t, z, i, target, velocity=False)

    def _consistent_mode(self, t, z, mode, limits=None):
        """Release sticking frictions (|lam| above their limit) and persistent contacts (lam < 0),
        the most violated first, until the constraint forces are admissible."""
        mode = list(mode)
        limits = dict(limits or {})
        for _ in range(4 * len(mode) + 4):
            out = self._eval(t, z, mode)
            worst, wi = 0.0, None
            for i in out["rows"]:
                lam = out["F"][i, 0]
                excess = self.p.elements[i].constraint_excess(lam, t, limits.get(i), self._contact_ftol.get(i, 0.0))
                if excess > 1e-12 and excess > worst:
                    worst, wi = excess, i
            if wi is None:
                return mode, out
            mode[wi] = self.p.elements[wi].released_mode(out["F"][wi, 0])
            limits.pop(wi, None)
        raise SolverError(f"could not find a consistent contact/stick mode at t = {t!r}")

    def initial_mode(self, t, z):
        p = self.p
        q, v, e = self._split(z)
        mode = []
        scale_v = max(1e-300, np.max(np.abs(v)) if v.size else 0.0, abs(e[1]) if e.size > 1 else 0.0)
        for i, el in enumerate(p.elements):
            s, sd = p.gf[i] @ q + p.ge[i] @ e, p.gf[i] @ v + p.gve[i] @ e
            mode.append(el.initial_mode(s, sd, scale_v))
        mode, _ = self._consistent_mode(t, z, mode)
        return tuple(mode)

    # --------------------------------------------------------- exact pieces
    def _piece(self, mode, span):
        key = mode
        pc = self._pieces.get(key)
        if pc is None:
            pc = _Piece(self.p, mode, self.o, span)
            self._pieces[key] = pc
        return pc

    def _root(self, pc: _Piece, j, z0, a, b, ga, gb, guess=None):
        """Safeguarded Newton for Cg[j] expm(A tau) z0 = 0 on [a, b] with g(a) > 0 >= g(b),
        started from the Hermite-cubic root ``guess`` (exact for polynomial motion)."""
        c, cA = pc.Cg[j], pc.CgA[j]
        if gb == 0.0:
            return b, _expm(pc.A * b) @ z0
        tau = guess if guess is not None and a < guess < b else a + (b - a) * ga / (ga - gb)
        zt = None
        span = b
        prev = np.inf
        for it in range(60):
            zt = _expm(pc.A * tau) @ z0
            g, d = c @ zt, cA @ zt
            if g == 0.0:
                break
            if g > 0:
                a = tau
            else:
                b = tau
            new = tau - g / d if d != 0 else 0.5 * (a + b)
            if not (a <= new <= b):
                new = 0.5 * (a + b)
            step = abs(new - tau)
            # converged: step at round-off level of the step length, or Newton stagnating on noise
            if step <= 4e-16 * span or b - a <= 4e-16 * span or (it >= 2 and step >= 0.5 * prev and step <= 1e-12 * span):
                tau = new
                zt = _expm(pc.A * tau) @ z0
                break
            prev = step
            tau = new
        return tau, zt

    def _refine_min(self, pc: _Piece, j, z0, tau, lo, hi):
        """Newton on the guard's derivative to the exact local minimum near ``tau`` in [lo, hi]
        (grazing detection: the cubic's minimum can miss a shallow dip)."""
        best = None
        for _ in range(8):
            zt = _expm(pc.A * tau) @ z0
            g, d, dd = pc.Cg[j] @ zt, pc.CgA[j] @ zt, pc.CgAA[j] @ zt
            if best is None or g < best[2]:
                best = (tau, zt, g)
            if g <= 0 or dd <= 0:
                break
            new = min(max(tau - d / dd, lo), hi)
            if abs(new - tau) <= 1e-15 * max(abs(tau), hi):
                break
            tau = new
        return best

    def _propagate_exact(self, t, z, mode, t_end, rec, acc):
        pc = self._piece(mode, t_end - t)
        h = pc.h
        Cg, CgA = pc.Cg, pc.CgA
        first = True
        while True:
            hh = min(h, t_end - t)
            if hh <= 0:
                return t, z, []
            P = pc.phi(hh)
            z1 = P @ z
            acc["steps"] += 1
            g0, g1 = Cg @ z, Cg @ z1
            d0, d1 = CgA @ z, CgA @ z1
            cands = []
            for j in range(g0.size):
                a0, ga = 0.0, g0[j]
                scale = abs(g0[j]) + abs(g1[j]) + hh * (abs(d0[j]) + abs(d1[j])) + 1e-300
                if ga <= 1e-12 * scale:
                    # starting on (or numerically just across) the boundary: admissible only if leaving it
                    if first and d0[j] >= -1e-12 * scale / hh:
                        tm = _hermite_argmax(g0[j], g1[j], d0[j], d1[j], hh)
                        if tm is None:
                            continue
                        zm = _expm(pc.A * tm) @ z
                        gm = Cg[j] @ zm
                        if gm <= 0:
                            cands.append((0.0, j, z))
                            continue
                        a0, ga = tm, gm
                        if g1[j] > 0:
                            # check for a return within the rest of the step
                            tmin = _hermite_min(g0[j], g1[j], d0[j], d1[j], hh, lo=tm)
                            if tmin is None:
                                continue
                            tmin, zmin, gmin = self._refine_min(pc, j, z, tmin, tm, hh)
                            if gmin > 0:
                                continue
                            tr, zr = self._root(pc, j, z, a0, tmin, ga, gmin)
                            cands.append((tr, j, zr))
                            continue
                    else:
                        cands.append((0.0, j, z))
                        continue
                # bracket the FIRST crossing: a dip of the Hermite cubic before the step end (refined to
                # the exact minimum) takes precedence over a sign change at the end of the step
                b_end, gb = (hh, g1[j]) if g1[j] <= 0 else (None, None)
                tmin = _hermite_min(g0[j], g1[j], d0[j], d1[j], hh, lo=a0)
                if tmin is not None and tmin < hh * (1 - 1e-9):
                    pmin = _hermite_eval(g0[j], g1[j], d0[j], d1[j], hh, tmin)
                    if pmin < 0.05 * scale:
                        tmin, zmin, gmin = self._refine_min(pc, j, z, tmin, a0, hh)
                        if gmin <= 0 and tmin < hh * (1 - 1e-9):
                            b_end, gb = tmin, gmin
                if b_end is not None:
                    guess = _hermite_first_root(g0[j], g1[j], d0[j], d1[j], hh, a0, b_end)
                    tr, zr = self._root(pc, j, z, a0, b_end, ga, gb, guess)
                    cands.append((tr, j, zr))
            tend_step = min([c[0] for c in cands]) if cands else hh
            if self.o.output_step:
                dt_out = self.o.output_step
                k0 = int(np.floor(t / dt_out)) + 1
                for k in range(k0, k0 + int(tend_step / dt_out) + 2):
                    tau = k * dt_out - t
                    if not 0 < tau < tend_step:
                        continue
                    W = acc["W"] + (sum(self._quad_exact(pc, t, z, tau, mode).values()) if self.o.energy else 0.0)
                    rec(t + tau, _expm(pc.A * tau) @ z, mode, W)
            if self.o.energy:
                if tend_step > 0:
                    parts = self._quad_exact(pc, t, z, tend_step, mode)
                    acc["W"] += sum(parts.values())
                    for k_, w_ in parts.items():
                        acc["Wp"][k_] = acc["Wp"].get(k_, 0.0) + w_
            if cands:
                tmin_ = min(c[0] for c in cands)
                tol = 1e-12 * max(abs(t), hh, 1e-300)
                hits = [(c[1], c[2]) for c in cands if c[0] <= tmin_ + tol]
                zt = [c[2] for c in cands if c[0] == tmin_][0]
                te = t + tmin_
                return te, zt, [pc.tags[j] for j, _ in hits]
            t, z = t + hh, z1
            rec(t, z, mode, acc["W"])
            first = False
            if t >= t_end:
                return t, z, []

    def _quad_exact(self, pc: _Piece, t, z, hh, mode) -> dict:
        return {k: float(z @ G @ z) for k, G in pc.work_matrix(hh).items()}

    # -------------------------------------------------------- numeric pieces
    def _propagate_numeric(self, t, z, mode, t_end, rec, acc):
        p = self.p
        nf = p.nf
        cache = {}

        def ev(tt, y):
            key = (tt, y.tobytes())
            out = cache.get("k") == key and cache.get("v")
            if not out:
                q, v = y[:nf, None], y[nf:2 * nf, None]
                e = p.basis(tt)[:, None]
                out = p.evaluate(tt, q, v, e, mode)
                cache["k"], cache["v"] = key, out
            return out

        def fun(tt, y):
            out = ev(tt, y)
            q, v = y[:nf, None], y[nf:2 * nf, None]
            e = p.basis(tt)[:, None]
            if self.o.energy:
                pp = p.power_parts(tt, q, v, e, mode, out["F"], out["sd"])
                P = [pp[k][0] for k in p.WORK_PARTS]
            else:
                P = [0.0] * len(p.WORK_PARTS)
            return np.concatenate([y[nf:2 * nf], out["a"][:, 0], P])

        npart = len(p.WORK_PARTS)
        start = ev(t, np.concatenate([z[:2 * nf], np.zeros(npart)]))
        tags = start["tags"]
        # A slip that starts from rest with the slip force just at the limit (static = kinetic)
        # leaves w = 0 tangentially: rounding can make w dip below zero in the first step and
        # fire the stop guard at once, and stick/slip then alternate at one instant (seen with
        # the quadratic losses of seed 002 started at rest).  As the exact pieces do (a guard
        # on its boundary is admissible only if leaving it), a stop guard starting at |w| <= tol
        # fires only once w has crossed -tol; the stop then restores w = 0 exactly.
        v_scale = max(float(np.max(np.abs(z[nf:2 * nf]))) if nf else 0.0,
                      max((el.velocity_scale() for el in p.elements), default=0.0), 1.0)
        offset = np.zeros(len(tags))
        for j, (i, tag) in enumerate(tags):
            if tag in p.elements[i].soft_start_tags and abs(start["guards"][j, 0]) <= 1e-12 * v_scale:
                offset[j] = 1e-12 * v_scale
        events = []
        for j in range(len(tags)):
            def g(tt, y, j=j):
                return ev(tt, y)["guards"][j, 0] + offset[j]
            g.terminal, g.direction = True, -1
            events.append(g)
        y0 = np.concatenate([z[:2 * nf], np.zeros(npart)])
        W0, Wp0 = acc["W"], dict(acc["Wp"])

        def settle(y):
            for k_, w_ in zip(p.WORK_PARTS, y[2 * nf:]):
                acc["Wp"][k_] = Wp0.get(k_, 0.0) + w_
            acc["W"] = W0 + float(np.sum(y[2 * nf:]))
        # absolute tolerances in the units of q and v: the state, or -- for a piece starting at
        # rest -- the drivers' displacement and velocity amplitudes and friction surface speeds
        # (a state at rest once gave atol ~ 1e-310, an overflowing error norm and a failed piece:
        # seed 002 from rest); with neither (force-driven from rest) 1 in the model's units, and
        # v_scale never below 1: atol >= rtol 1e-2 in SI units, loose only for responses < 1e-8
        drive_q = max((float(np.max(np.abs(ge[2:]))) for ge in p.ge if ge.size > 2), default=0.0)
        drive_v = max((float(np.max(np.abs(gv))) for gv in p.gve if gv.size), default=0.0)
        q_scale = max(float(np.max(np.abs(z[:nf]))) if nf else 0.0, drive_q) or 1.0
        v_scale = max(float(np.max(np.abs(z[nf:2 * nf]))) if nf else 0.0, drive_v, v_scale) or 1.0
        scale = max(q_scale, v_scale)
        e_scale = abs(float(p.energy(t, z[:nf, None], z[nf:2 * nf, None], z[2 * nf:, None], mode)[0])) \
            + scale ** 2 * (np.max(np.abs(p.K)) + np.max(np.abs(p.mass(t)))) + 1e-300
        atol = np.concatenate([np.full(nf, self.o.rtol * q_scale * 1e-2), np.full(nf, self.o.rtol * v_scale * 1e-2),
                               np.full(npart, self.o.rtol * 1e-2 * e_scale)])
        max_step = np.inf
        if p.omega_max > 0:
            max_step = 2 * np.pi / (self.o.steps_per_period * p.omega_max)
        if self.o.max_step:
            max_step = min(max_step, self.o.max_step)
        sol = solve_ivp(fun, (t, t_end), y0, method="DOP853", rtol=self.o.rtol, atol=atol,
                        events=events, dense_output=False, max_step=max_step)
        if sol.status == -1:
            raise SolverError(f"numeric piece failed at t = {sol.t[-1]!r}: {sol.message}")
        acc["steps"] += sol.t.size - 1
        acc["numeric"] = acc.get("numeric", 0) + 1
        acc["nfev"] = acc.get("nfev", 0) + sol.nfev
        for k in range(1, sol.t.size):
            yk = sol.y[:, k]
            settle(yk)
            zk = np.concatenate([yk[:2 * nf], p.basis(sol.t[k])])
            if sol.status == 1 and k == sol.t.size - 1:
                break
            rec(sol.t[k], zk, mode, acc["W"])
        if sol.status == 1:
            hits = [(j, sol.t_events[j][0], sol.y_events[j][0]) for j in range(len(events)) if sol.t_events[j].size]
            te = min(h[1] for h in hits)
            tol = 1e-12 * max(abs(te), 1e-300)
            trig = [tags[h[0]] for h in hits if h[1] <= te + tol]
            y = [h[2] for h in hits if h[1] == te][0]
            settle(y)
            return te, np.concatenate([y[:2 * nf], p.basis(te)]), trig
        yk = sol.y[:, -1]
        return sol.t[-1], np.concatenate([yk[:2 * nf], p.basis(sol.t[-1])]), []

    # ----------------------------------------------------------- events
    def _apply(self, t, z, mode, trig, impact_ref):
        """Apply the element rules to the triggered guards; returns new z, mode, events, jump work."""
        p = self.p
        ctx = EventContext(self, t, z, list(mode), impact_ref)
        for (i, tag) in sorted(set(trig)):
            ctx.i = i
            p.elements[i].on_event(tag, ctx)
        z, mode, records, limits = ctx.z, ctx.modes, ctx.records, ctx.limits
        before = list(mode)
        mode, out = self._consistent_mode(t, z, mode, limits)
        for i, el in enumerate(p.elements):
            if mode[i] != before[i] and i not in {r[0] for r in records}:
                records.append([i, el.release_event()])
        events = []
        for i, kind in records:
            if kind == "stop":
                kind = "stick" if mode[i] == 0 else "reversal"
            events.append(Event(t=t, kind=kind, element=p.elements[i].name, state=self._state_dict(z)))
        return z, tuple(mode), events, ctx.jump

    # ------------------------------------------------------------- driver
    def run(self, t_end: float, t0: float = 0.0) -> SimulationResult:
        p, o = self.p, self.o
        if not t_end > t0:
            raise SolverError(f"t_end = {t_end!r} must exceed the start time {t0!r}")
        z = np.concatenate([p.q0, p.v0, p.basis(t0)])
        mode = self.initial_mode(t0, z)
        ts, zs, ms, Ws = [t0], [z.copy()], [mode], [0.0]

        def rec(tt, zz, md, W):
            ts.append(tt)
            zs.append(zz.copy())
            ms.append(md)
            Ws.append(W)
            if o.progress is not None:
                o.progress(tt)

        acc = {"W": 0.0, "Wp": {}, "steps": 0, "rejections": 0}
        events: list[Event] = []
        t = t0
        impact_ref: dict = {}
        zero_len = 0
        n_pieces = 0
        stopped, reason = False, ""
        try:
            while t < t_end:
                n_pieces += 1
                if p.mode_affine(mode):
                    te, ze, trig = self._propagate_exact(t, z, mode, t_end, rec, acc)
                else:
                    te, ze, trig = self._propagate_numeric(t, z, mode, t_end, rec, acc)
                if not trig:
                    t, z = te, ze
                    if ts[-1] != t:
                        rec(t, z, mode, acc["W"])
                    break
                zero_len = zero_len + 1 if te == t else 0
                if zero_len > o.max_zero_length:
                    stopped, reason = True, (f"no progress at t = {te!r}: {zero_len} consecutive events "
                                             f"({', '.join(f'{p.elements[i].name}:{g}' for i, g in trig)}) "
                                             "without time advancing (chattering or accumulation)")
                    t, z = te, ze
                    break
                rec(te, ze, mode, acc["W"])
                z, mode, evs, jump = self._apply(te, ze, mode, trig, impact_ref)
                acc["W"] += jump
                if jump:
                    acc["Wp"]["impacts"] = acc["Wp"].get("impacts", 0.0) + jump
                t = te
                rec(t, z, mode, acc["W"])
                events.extend(evs)
                if len(events) >= o.max_events:
                    stopped, reason = True, (f"event limit max_events = {o.max_events} reached at t = {t!r} "
                                             f"(last event: {evs[-1].kind if evs else '-'} of "
                                             f"{evs[-1].element if evs else '-'}); results up to there are kept")
                    break
        except SolverError as exc:
            stopped, reason = True, f"solver stopped at t = {t!r}: {exc}"
        except KeyboardInterrupt:
            n = min(len(ts), len(zs), len(ms), len(Ws))
            del ts[n:], zs[n:], ms[n:], Ws[n:]
            stopped, reason = True, f"interrupted (Ctrl-C) at t = {ts[-1]!r}: the results up to there are kept"
        return self._result(ts, zs, ms, Ws, events, t_end, n_pieces, acc, stopped, reason)

    def _result(self, ts, zs, ms, Ws, events, t_end, n_pieces, acc, stopped, reason):
        p = self.p
        T = np.array(ts)
        Z = np.array(zs).T
        q, v, e = Z[:p.nf], Z[p.nf:2 * p.nf], Z[2 * p.nf:]
        x, xd = p.full_state(q, v, e)
        E = np.zeros(T.size)
        Fel = np.zeros((len(p.elements), T.size))
        groups: dict = {}
        for k, md in enumerate(ms):
            groups.setdefault(md, []).append(k)
        for md, ks in groups.items():          # vectorised per mode (time enters only through M(t))
            ks = np.array(ks)
            if p.time_invariant:
                E[ks] = p.energy(0.0, q[:, ks], v[:, ks], e[:, ks], md)
                Fel[:, ks] = p.evaluate(0.0, q[:, ks], v[:, ks], e[:, ks], md)["F"]
            else:
                for k in ks:
                    E[k] = p.energy(T[k], q[:, k:k + 1], v[:, k:k + 1], e[:, k:k + 1], md)[0]
                    Fel[:, k] = p.evaluate(T[k], q[:, k:k + 1], v[:, k:k + 1], e[:, k:k + 1], md)["F"][:, 0]
        W = np.array(Ws)
        if self.o.energy:
            resid = (E - E[0]) - W
            scale = max(np.max(np.abs(E)), np.max(np.abs(W)), 1e-300)
            err = float(np.max(np.abs(resid)) / scale)
        else:
            err = float("nan")
        if acc.get("numeric"):
            self.warnings.append(f"{acc['numeric']} piece(s) integrated numerically (DOP853, rtol {self.o.rtol:g}, "
                                 f"{acc['nfev']} right-hand-side evaluations); scipy does not report their step "
                                 "rejections, so step_rejections counts the exact pieces only (always 0)")
        res = SimulationResult(t=T, x=x, v=xd, names=list(p.names), events=events, t_end=float(t_end),
                               energy=E, work=W, energy_error=err, n_pieces=n_pieces, n_steps=acc["steps"],
                               step_rejections=acc["rejections"], warnings=list(self.warnings),
                               stopped_early=stopped, reason=reason,
                               elements=[f"{el.kind}:{el.name}" for el in p.elements],
                               driven=[p.names[j] for j in p.c], element_forces=Fel,
                               work_parts={k: float(w) for k, w in acc["Wp"].items()})
        per = detect_period(res) if events else detect_period_smooth(res)
        if per is not None:
            res.period, res.period_info = per["period"], per
        return res


def _power_form(prob: Problem, mode, Fm, Sdm) -> dict:
    """{part: symmetric Q} with power_part(z) = z^T Q z in an affine, time-invariant mode (by
    polarization); parts that vanish identically are left out."""
    nz = Fm.shape[1]
    nf = prob.nf
    iu = np.triu_indices(nz)
    Z = np.zeros((nz, iu[0].size))
    cols = np.arange(iu[0].size)
    Z[iu[0], cols] += 1.0
    Z[iu[1], cols] += 1.0 * (iu[0] != iu[1])
    D = np.eye(nz)

    def P(Zc):
        return prob.power_parts(0.0, Zc[:nf], Zc[nf:2 * nf], Zc[2 * nf:], mode, Fm @ Zc, Sdm @ Zc)

    pd, pz = P(D), P(Z)
    out = {}
    for part in prob.WORK_PARTS:
        Q = np.zeros((nz, nz))
        for k, (i, j) in enumerate(zip(*iu)):
            if i == j:
                Q[i, i] = pd[part][i]
            else:
                Q[i, j] = Q[j, i] = 0.5 * (pz[part][k] - pd[part][i] - pd[part][j])
        if np.any(Q):
            out[part] = Q
    return out


# -------------------------------------------------------------- Hermite helpers
def _hermite_coeffs(g0, g1, d0, d1, h):
    """Cubic p(s) = c0 + c1 s + c2 s^2 + c3 s^3 on [0, h] matching values and slopes."""
    c0, c1 = g0, d0
    c2 = (3 * (g1 - g0) / h - 2 * d0 - d1) / h
    c3 = (d0 + d1 - 2 * (g1 - g0) / h) / h ** 2
    return c0, c1, c2, c3


def _hermite_eval(g0, g1, d0, d1, h, s):
    c0, c1, c2, c3 = _hermite_coeffs(g0, g1, d0, d1, h)
    return c0 + s * (c1 + s * (c2 + s * c3))


def _crit(g0, g1, d0, d1, h, lo):
    """Critical points of the Hermite cubic in (lo, h): roots of 3 c3 s^2 + 2 c2 s + c1."""
    c0, c1, c2, c3 = _hermite_coeffs(g0, g1, d0, d1, h)
    a, b, c = 3 * c3, 2 * c2, c1
    if a == 0 or abs(a) * h <= 1e-14 * (abs(b) + abs(c) / h):
        rs = [-c / b] if b != 0 else []
    else:
        disc = b * b - 4 * a * c
        if disc < 0:
            return []
        sq = np.sqrt(disc)
        qq = -0.5 * (b + np.copysign(sq, b))
        rs = [qq / a] + ([c / qq] if qq != 0 else [])
    return [float(r) for r in rs if lo < r < h]


def _hermite_first_root(g0, g1, d0, d1, h, lo, hi):
    c0, c1, c2, c3 = _hermite_coeffs(g0, g1, d0, d1, h)
    r = np.roots([c3, c2, c1, c0]) if (c3 or c2 or c1) else np.array([])
    rs = sorted(float(x.real) for x in np.atleast_1d(r) if abs(x.imag) <= 1e-9 * h and lo < x.real <= hi)
    return rs[0] if rs else None


def _hermite_min(g0, g1, d0, d1, h, lo=0.0):
    cs = _crit(g0, g1, d0, d1, h, lo)
    if not cs:
        return None
    vals = [_hermite_eval(g0, g1, d0, d1, h, s) for s in cs]
    return cs[int(np.argmin(vals))]


def _hermite_argmax(g0, g1, d0, d1, h):
    cs = _crit(g0, g1, d0, d1, h, 0.0) + [h]
    vals = [_hermite_eval(g0, g1, d0, d1, h, s) for s in cs]
    k = int(np.argmax(vals))
    return cs[k] if vals[k] > 0 else None


def simulate(problem: Problem, t_end: float, options: Options | None = None, t0: float = 0.0) -> SimulationResult:
    """Event-driven simulation of ``problem`` on [t0, t_end] (see module docstring)."""
    return EventDrivenSolver(problem, options).run(t_end, t0)


class EventContext:
    """What an element's event rule (``Element.on_event``) may read and change at an event: the
    state, its own mode, the stick limit of the restick rule, the event records, the energy jump."""

    def __init__(self, solver: EventDrivenSolver, t: float, z: np.ndarray, modes: list, impact_ref: dict):
        self.solver, self.t, self.z, self.modes, self.impact_ref = solver, t, z, modes, impact_ref
        self.i = 0
        self.records: list = []
        self.limits: dict = {}
        self.jump = 0.0
        self.rest_tol = solver.o.rest_tol

    @property
    def mode(self) -> int:
        return self.modes[self.i]

    @mode.setter
    def mode(self, value: int) -> None:
        self.modes[self.i] = value

    @property
    def limit(self):
        return self.limits.get(self.i)

    @limit.setter
    def limit(self, value: float) -> None:
        self.limits[self.i] = value

    def record(self, kind: str) -> None:
        self.records.append([self.i, kind])

    def velocity(self) -> float:
        """s' of the element."""
        p = self.solver.p
        q, v, e = self.solver._split(self.z)
        return p.gf[self.i] @ v + p.gve[self.i] @ e

    def energy(self) -> float:
        q, v, e = self.solver._split(self.z)
        return self.solver.p.energy(self.t, q[:, None], v[:, None], e[:, None], tuple(self.modes))[0]

    def constraint_force(self) -> float:
        """The constraint force of the element in the current modes."""
        return self.solver._eval(self.t, self.z, self.modes)["F"][self.i, 0]

    def impact_speed(self, speed: float) -> float:
        """The largest impact speed of the element so far (``speed`` included)."""
        self.impact_ref[self.i] = max(self.impact_ref.get(self.i, 0.0), speed)
        return self.impact_ref[self.i]

    def project_velocity(self, target: float) -> None:
        self.z = self.solver._project_velocity(self.t, self.z, self.i, target)

    def project_position(self, target: float) -> None:
        self.z = self.solver._project_position(self.t, self.z, self.i, target)
