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

import gc
import math

from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np

from .. import checks
from ..errors import ModelError, SolverError
from ..linalg.blas import single_threaded_blas
from .periodic import detect_period, detect_period_smooth
from .piece import AffinePiece
from .problem import Problem
from .result import Event, EventState, SimulationResult



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
    max_evaluations: int | None = None  # right-hand sides of the numeric pieces before the run stops (None: any)

    def __post_init__(self):
        """The [simulation] keys' rules of the model file (method = "event"), checked once here."""
        w = "[simulation]"
        self.max_events = checks.integer(w, "max_events", self.max_events, 1, "event limit")
        self.max_step = checks.optional(checks.positive, w, "max_step", self.max_step, "largest step, s")
        self.steps_per_period = checks.integer(w, "steps_per_period", self.steps_per_period, 1,
                                               "marching steps per period of the highest frequency")
        self.rtol = checks.positive(w, "rtol", self.rtol, "relative tolerance of numerically integrated pieces")
        self.rest_tol = checks.positive(w, "rest_tol", self.rest_tol, "impact accumulation threshold")
        if not isinstance(self.energy, (bool, np.bool_)):
            raise ModelError(w, "energy", self.energy, "true | false")
        self.max_zero_length = checks.integer(w, "max_zero_length", self.max_zero_length, 1,
                                              "consecutive events without time progress")
        self.output_step = checks.optional(checks.positive, w, "output_step", self.output_step, "s")
        self.contact_tol = checks.non_negative(w, "contact_tol", self.contact_tol,
                                               "relative tolerance of persistent-contact forces")
        if self.progress is not None and not callable(self.progress):
            raise ModelError(w, "progress", self.progress, "None or a callable taking the time reached")
        self.max_evaluations = checks.optional(checks.integer, w, "max_evaluations", self.max_evaluations, 1,
                                               "right-hand-side evaluations of the numeric pieces")


class EventDrivenSolver:
    def __init__(self, problem: Problem, options: Options | None = None):
        self.p = problem
        self.o = options or Options()
        self._pieces: dict = {}
        self.warnings: list[str] = []
        self._contact_ftol = self._contact_force_tolerances()
        self._projections: dict = {}        # (element, velocity?) -> (row, direction) of _project
        self._t_end = np.inf
        self._event_states: list = []       # (event, state vector): the events' DOF states, filled in at the end

    def _contact_force_tolerances(self) -> dict:
        """Round-off tolerance of each persistent contact's force.  When an elastic body lands
        on a stop with restitution 0 the required contact force is exactly zero and grows
        afterwards; its round-off value (-1e-20) must not release the contact, or the run stalls
        on zero-length events.  Scale: F_ref = m_eff omega_max v_ref (effective mass of the
        contact coordinate, highest frequency of the linear part, largest initial or driver
        velocity); the release guard of the next piece then decides from the force's trend."""
        p = self.p
        v0 = np.asarray(getattr(p, "v0", np.zeros(0)), dtype=float)
        vref = max(float(np.max(np.abs(v0))) if v0.size else 0.0, p.speed_scale(), 1e-300)
        tol = {}
        for i, el in enumerate(p.elements):
            if el.unilateral:
                g = p.gf[i]
                meff = 1.0 / float(g @ np.linalg.solve(p.M0, g)) if np.any(g) else 0.0
                tol[i] = self.o.contact_tol * meff * max(getattr(p, "omega_max", 0.0), 1e-300) * vref
        return tol

    # ------------------------------------------------------------ helpers
    def _split(self, z):
        """(q, v, e) of a state vector (the internal states w: :meth:`Problem.split`)."""
        q, v, _, e = self.p.split(z)
        return q, v, e

    def _eval(self, t, z, mode):
        q, v, w, e = self.p.split(z)
        return self.p.evaluate(t, q[:, None], v[:, None], e[:, None], mode, w[:, None])

    def _forces(self, t, z, mode):
        """(element forces along s, constraint rows) at one state: the cached linear map of an
        affine mode, the full evaluation otherwise."""
        if type(mode) is not tuple:
            mode = tuple(mode)
        pc = self._pieces.get(mode)
        if pc is None and self.p.mode_affine(mode) and np.isfinite(self._t_end):
            pc = self._piece(mode, self._t_end - t)
        if pc is not None:
            return pc.Fm.dot(z).tolist(), pc.rows          # (ndarray.dot: matmul's value at half its call cost)
        out = self._eval(t, z, mode)
        return out["F"][:, 0].tolist(), out["rows"]

    def _fill_event_states(self) -> None:
        """The DOF states of the events ({name: {x, v}}), from their state vectors in one pass."""
        if not self._event_states:
            return
        Z = np.array([z for _, z in self._event_states]).T
        x, xd = self.p.full_state(*self._split(Z))
        names = tuple(self.p.names)
        for k, (ev, _) in enumerate(self._event_states):
            ev.state = EventState(names, x, xd, k)
        self._event_states = []

    def _project(self, t, z, i, target, velocity: bool):
        """Set s'_i (``velocity``) or s_i to ``target`` with the smallest mass-weighted change of the
        velocities or positions (the kinetic-energy-minimal projection along M^-1 g_i):
        z + d (target - r . z) with r the row of s'_i (s_i) and d = M^-1 g_i / (g_i M^-1 g_i) in the
        velocity (position) part."""
        key = (i, velocity)
        rd = self._projections.get(key) if self.p.time_invariant else None
        if rd is None:
            p = self.p
            nf = p.nf
            Mig = np.linalg.solve(p.mass(t), p.gf[i])
            r = np.zeros(z.size)
            d = np.zeros(z.size)
            part = slice(nf, 2 * nf) if velocity else slice(0, nf)
            r[part] = p.gf[i]
            r[2 * nf + p.nw:] = p.gve[i] if velocity else p.ge[i]
            d[part] = Mig / float(p.gf[i] @ Mig)
            rd = (r, d)
            if p.time_invariant:
                self._projections[key] = rd
        r, d = rd
        out = d * (target - r.dot(z))
        out += z
        return out

    def _effective_mass(self, t, i) -> float:
        """1 / (g_f M(t)^-1 g_f): the mass of the coordinate s_i seen by an impulse along it."""
        key = ("meff", i)
        m = self._projections.get(key) if self.p.time_invariant else None
        if m is None:
            g = self.p.gf[i]
            m = 1.0 / float(g @ np.linalg.solve(self.p.mass(t), g)) if np.any(g) else 0.0
            if self.p.time_invariant:
                self._projections[key] = m
        return m

    def _project_velocity(self, t, z, i, target):
        return self._project(t, z, i, target, velocity=True)

    def _project_position(self, t, z, i, target):
        return self._project(t, z, i, target, velocity=False)

    def _consistent_mode(self, t, z, mode, limits=None):
        """Release sticking frictions (|lam| above their limit) and persistent contacts (lam < 0),
        the most violated first, until the constraint forces are admissible.  Returns a new list
        of the modes (``mode`` itself is left as it was)."""
        mode = list(mode)
        limits = limits or {}
        pieces, elements, ftol = self._pieces, self.p.elements, self._contact_ftol
        for _ in range(4 * len(mode) + 4):
            key = tuple(mode)
            pc = pieces.get(key)
            if pc is not None and not pc.rows:  # no constraint in this mode: nothing (more) to release
                return mode
            F, rows = self._forces(t, z, key)
            worst, wi = 0.0, None
            for i in rows:
                excess = elements[i].constraint_excess(F[i], t, limits.get(i), ftol.get(i, 0.0))
                if excess > 1e-12 and excess > worst:
                    worst, wi = excess, i
            if wi is None:
                return mode
            mode[wi] = elements[wi].released_mode(F[wi])
            if wi in limits:
                limits = {i: v for i, v in limits.items() if i != wi}     # (the caller's dict stays as it was)
        raise SolverError(f"could not find a consistent contact/stick mode at t = {t!r}")

    def initial_mode(self, t, z, pieces=()):
        """The element modes of the state z (then made consistent), followed by ``pieces``, the
        piece of every programme law."""
        p = self.p
        q, v, e = self._split(z)
        mode = []
        scale_v = max(1e-300, np.max(np.abs(v)) if v.size else 0.0, abs(e[1]) if e.size > 1 else 0.0)
        for i, el in enumerate(p.elements):
            s, sd = p.gf[i] @ q + p.ge[i] @ e, p.gf[i] @ v + p.gve[i] @ e
            mode.append(el.initial_mode(s, sd, scale_v))
        return tuple(self._consistent_mode(t, z, mode + list(pieces)))

    # --------------------------------------------------------- exact pieces
    def _piece(self, mode, span) -> AffinePiece:
        pc = self._pieces.get(mode)
        if pc is None:
            pc = AffinePiece(self.p, mode, self.o.steps_per_period, self.o.max_step, span)
            self._pieces[mode] = pc
        return pc

    def _propagate_exact(self, t, z, mode, t_end, rec, acc):
        """March the exact piece of ``mode`` from (t, z) to its first event or t_end; the kernel writes
        the step ends (and the output instants) straight into the recorder's arrays."""
        pc = self._pieces.get(mode)
        if pc is None:
            pc = self._piece(mode, t_end - t)
        dt_out = float(self.o.output_step or 0.0)
        room = 4096 if not dt_out else max(4096, int(2 * pc.h / dt_out) + 16)    # rows free before a call
        energy = self.o.energy
        hits = pc.hits
        kernel = _kernel()
        advance, EVENT, END = kernel.advance, kernel.EVENT, kernel.END
        P, R, T, G, Q, ng, h, nz, work = pc.P, pc.R, pc.T, pc.G, pc.Q, pc.ng, pc.h, pc.nz, pc.work_total
        first = True
        while True:
            n0 = rec.n
            if n0 + room > rec.t.size:
                rec.grow(room)
            z_out = np.empty(nz)
            start = rec.pending is not None        # the state leaving the last event: the kernel records it
            why, n, steps, t, W = advance(P, R, T, G, Q, ng, h, z, t, t_end, first, dt_out, acc["W"], work,
                                          rec.t, rec.Z, rec.W, n0, z_out, hits, start)
            if start:
                rec.pending = None
            z = z_out
            acc["steps"] += steps
            if n > n0:
                if not energy:
                    rec.W[n0:n] = acc["W"]
                rec.filled(n, mode)
            if energy:
                acc["W"] = W
            if why == EVENT:
                tags = pc.tags
                return t, z, [tags[j] for j, hit in enumerate(hits.tolist()) if hit]
            if why == END:
                return t, z, []
            first = False

    # -------------------------------------------------------- numeric pieces
    def _propagate_numeric(self, t, z, mode, t_end, rec, acc):
        p = self.p
        nf, nw = p.nf, p.nw
        nqv = 2 * nf + nw                 # integrated: q, v, w (then the work of each part)
        t_start, e_start = t, z[nqv:].copy()
        cache = {}

        def exo(tt):
            """The exogenous state at tt (closed forms from the piece's start: no knot inside)."""
            return p.exogenous_after(e_start, t_start, tt)

        def ev(tt, y):
            key = (tt, y.tobytes())
            out = cache.get("k") == key and cache.get("v")
            if not out:
                q, v, w = y[:nf, None], y[nf:2 * nf, None], y[2 * nf:nqv, None]
                e = exo(tt)[:, None]
                out = p.evaluate(tt, q, v, e, mode, w)
                cache["k"], cache["v"] = key, out
            return out

        budget = None if self.o.max_evaluations is None else self.o.max_evaluations - acc.get("nfev", 0)
        calls = [0]

        def fun(tt, y):
            calls[0] += 1
            if budget is not None and calls[0] > budget:     # a stiff law for the explicit integrator
                raise SolverError(f"the numerically integrated pieces used their {self.o.max_evaluations} "
                                  f"right-hand-side evaluations at t = {tt:.6g} (a law too stiff for the explicit "
                                  "DOP853 steps: a huge coefficient, or a tiny inertia); the results up to the start "
                                  "of this piece are kept; a deliberate longer run needs a larger DRIVEFEM_BUDGET")
            out = ev(tt, y)
            q, v = y[:nf, None], y[nf:2 * nf, None]
            e = exo(tt)[:, None]
            if self.o.energy:
                pp = p.power_parts(tt, q, v, e, mode, out["F"], out["sd"])
                P = [pp[k][0] for k in p.WORK_PARTS]
            else:
                P = [0.0] * len(p.WORK_PARTS)
            return np.concatenate([y[nf:2 * nf], out["a"][:, 0], out["wd"][:, 0], P])

        npart = len(p.WORK_PARTS)
        start = ev(t, np.concatenate([z[:nqv], np.zeros(npart)]))
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
        y0 = np.concatenate([z[:nqv], np.zeros(npart)])
        W0, Wp0 = acc["W"], dict(acc["Wp"])

        def settle(y):
            for k_, w_ in zip(p.WORK_PARTS, y[nqv:]):
                acc["Wp"][k_] = Wp0.get(k_, 0.0) + w_
            acc["W"] = W0 + float(np.sum(y[nqv:]))
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
        e_scale = abs(float(np.asarray(p.energy(t, z[:nf, None], z[nf:2 * nf, None], z[nqv:, None], mode))
                            .reshape(-1)[0])) + scale ** 2 * (np.max(np.abs(p.K)) + np.max(np.abs(p.mass(t)))) + 1e-300
        w_scale = np.ones(nw)
        for i in p.stateful:
            sl = p.state_slices[i]
            w_scale[sl] = max(p.elements[i].state_scale(), float(np.max(np.abs(z[2 * nf:nqv][sl]))))
        atol = np.concatenate([np.full(nf, self.o.rtol * q_scale * 1e-2), np.full(nf, self.o.rtol * v_scale * 1e-2),
                               self.o.rtol * 1e-2 * w_scale, np.full(npart, self.o.rtol * 1e-2 * e_scale)])
        max_step = np.inf
        if p.omega_max > 0:
            max_step = 2 * np.pi / (self.o.steps_per_period * p.omega_max)
        if self.o.max_step:
            max_step = min(max_step, self.o.max_step)
        dt_out = float(self.o.output_step or 0.0)
        from scipy.integrate import solve_ivp   # only numeric pieces need it (~0.15 s of start-up)

        sol = solve_ivp(fun, (t, t_end), y0, method="DOP853", rtol=self.o.rtol, atol=atol,
                        events=events, dense_output=bool(dt_out), max_step=max_step)
        if sol.status == -1:
            raise SolverError(f"numeric piece failed at t = {sol.t[-1]!r}: {sol.message}")
        acc["steps"] += sol.t.size - 1
        acc["numeric"] = acc.get("numeric", 0) + 1
        acc["nfev"] = acc.get("nfev", 0) + sol.nfev
        t_stop = sol.t[-1] if sol.status == 1 else None      # a terminal event ends the piece there
        for k in range(1, sol.t.size):
            if dt_out:        # the output instants k dt_out inside the step (as the exact pieces record them)
                b = sol.t[k] if t_stop is None else min(sol.t[k], t_stop)
                j = math.floor(sol.t[k - 1] / dt_out) + 1
                while j * dt_out < b:
                    tj = j * dt_out
                    yj = sol.sol(tj)
                    settle(yj)
                    rec(tj, np.concatenate([yj[:nqv], exo(tj)]), mode, acc["W"])
                    j += 1
            yk = sol.y[:, k]
            settle(yk)
            zk = np.concatenate([yk[:nqv], exo(sol.t[k])])
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
            ze = np.concatenate([y[:nqv], exo(te)])
            rec(te, ze, mode, acc["W"])            # the state reaching the event
            return te, ze, trig
        yk = sol.y[:, -1]
        return sol.t[-1], np.concatenate([yk[:nqv], exo(sol.t[-1])]), []

    # ----------------------------------------------------------- events
    def _apply(self, t, z, mode, trig, impact_ref):
        """Apply the knots of the programme laws, then the element rules, to the triggered guards;
        returns new z, mode, events, and the energy jumps {part: work}."""
        p = self.p
        elements = p.elements
        nel = p.n_el
        if len(trig) != 1:
            trig = sorted(set(trig))           # (the knots of programme laws, i >= nel, come last)
        modes = list(mode)
        jumps, knot_events = {}, []
        if trig[-1][0] >= nel:
            knots = [i - nel for i, _ in trig if i >= nel]
            E0 = self._energy(t, z, modes)
            moved = False
            for k in knots:
                z, modes[nel + k], dx, dv = p.knot(k, z, modes[nel + k])
                moved = moved or dx != 0.0 or dv != 0.0
                ev = Event(t, "knot", p.sources[k].name, {})
                knot_events.append(ev)
                self._event_states.append((ev, z))
            if moved:
                # a jump of a driver's position or velocity (a constant-velocity cam's hard impact):
                # the element modes follow the new state
                q, v, e = self._split(z)
                scale_v = max(1e-300, np.max(np.abs(v)) if v.size else 0.0)
                for i, el in enumerate(elements):
                    s_, sd_ = p.gf[i] @ q + p.ge[i] @ e, p.gf[i] @ v + p.gve[i] @ e
                    modes[i] = el.initial_mode(s_, sd_, scale_v)
            # the reset moves the drivers by round-off (or by a jump of the law): their work
            jumps["drivers"] = self._energy(t, z, modes) - E0
        ctx = EventContext(self, t, z, modes, impact_ref)
        for (i, tag) in trig:
            if i < nel:
                ctx.i = i
                elements[i].on_event(tag, ctx)
        z, records, before = ctx.z, ctx.records, ctx.modes
        mode = self._consistent_mode(t, z, before, ctx.limits)
        if mode != before:
            recorded = [r[0] for r in records]
            for i, el in enumerate(elements):
                if mode[i] != before[i] and i not in recorded:
                    records.append([i, el.release_event()])
        events = knot_events
        impulses = ctx.impulses
        event_states = self._event_states
        for i, kind in records:
            if kind == "stop":
                kind = "stick" if mode[i] == 0 else "reversal"
            ev = Event(t, kind, elements[i].name, {}, float(impulses.pop(i, 0.0)))
            events.append(ev)
            event_states.append((ev, z))
        if ctx.jump:
            jumps["impacts"] = ctx.jump
        return z, tuple(mode), events, jumps

    def _energy(self, t, z, modes) -> float:
        q, v, e = self._split(z)
        return float(np.asarray(self.p.energy(t, q[:, None], v[:, None], e[:, None], tuple(modes))).reshape(-1)[0])

    # ------------------------------------------------------------- driver
    def run(self, t_end: float, t0: float = 0.0) -> SimulationResult:
        """Simulate on [t0, t_end].  The linear algebra here is on tiny matrices (the pieces'
        expansions, projections, the energy): BLAS threads only add synchronisation, and their
        spinning costs several times the work on a busy machine (seed 000, 801 events: 21 ms of
        CPU single-threaded against 50-110 ms with two OpenBLAS threads).  Python's cyclic garbage
        collector is paused meanwhile (:func:`_collector_paused`)."""
        with single_threaded_blas(), _collector_paused():
            return self._run(t_end, t0)

    def _run(self, t_end: float, t0: float = 0.0) -> SimulationResult:
        p, o = self.p, self.o
        if not t_end > t0:
            raise SolverError(f"t_end = {t_end!r} must exceed the start time {t0!r}")
        self._t_end = t_end
        self._event_states = []
        for pc in self._pieces.values():
            pc.work_total[:] = 0.0
        z, pieces = p.initial_state(t0)
        mode = self.initial_mode(t0, z, pieces)
        rec = _Recorder(t0, z, mode, o.progress)

        acc = {"W": 0.0, "Wp": {}, "steps": 0, "rejections": 0}
        events: list[Event] = []
        t = t0
        impact_ref: dict = {}
        zero_len = 0
        n_pieces = 0
        stopped, reason = False, ""
        mode_affine, exact, numeric, apply = p.mode_affine, self._propagate_exact, self._propagate_numeric, self._apply
        max_zero_length, max_events = o.max_zero_length, o.max_events
        try:
            while t < t_end:
                n_pieces += 1
                if mode_affine(mode):
                    te, ze, trig = exact(t, z, mode, t_end, rec, acc)
                else:
                    rec.flush()
                    te, ze, trig = numeric(t, z, mode, t_end, rec, acc)
                if not trig:
                    t, z = te, ze
                    if rec.last_t != t:
                        rec(t, z, mode, acc["W"])
                    break
                zero_len = zero_len + 1 if te == t else 0
                if zero_len > max_zero_length:
                    rec.drop_last()            # the state reaching the event (the event is not applied)
                    stopped, reason = True, (f"no progress at t = {te!r}: {zero_len} consecutive events "
                                             f"({', '.join(f'{p.actor_name(i)}:{g}' for i, g in trig)}) "
                                             "without time advancing (chattering or accumulation)")
                    t, z = te, ze
                    break
                z, mode, evs, jumps = apply(te, ze, mode, trig, impact_ref)
                if jumps:
                    for part, jump in jumps.items():
                        acc["W"] += jump
                        acc["Wp"][part] = acc["Wp"].get(part, 0.0) + jump
                t = te
                rec.pending = (t, z, mode, acc["W"])     # recorded by the next piece's kernel (or flush)
                events += evs
                if len(events) >= max_events:
                    stopped, reason = True, (f"event limit max_events = {o.max_events} reached at t = {t!r} "
                                             f"(last event: {evs[-1].kind if evs else '-'} of "
                                             f"{evs[-1].element if evs else '-'}); results up to there are kept")
                    break
        except SolverError as exc:
            stopped, reason = True, f"solver stopped at t = {t!r}: {exc}"
        except KeyboardInterrupt:
            stopped, reason = True, "interrupted (Ctrl-C): the results up to there are kept"
        rec.flush()
        return self._result(rec, events, t_end, n_pieces, acc, stopped, reason)

    def _result(self, rec, events, t_end, n_pieces, acc, stopped, reason):
        p = self.p
        for pc in self._pieces.values():           # the work of the exact pieces, by category
            for k, part in enumerate(pc.parts):
                acc["Wp"][part] = acc["Wp"].get(part, 0.0) + float(pc.work_total[k])
        T, Z, modes, which, W = rec.arrays()
        if stopped and reason.startswith("interrupted"):
            reason = f"interrupted (Ctrl-C) at t = {T[-1]!r}: the results up to there are kept"
        self._fill_event_states()
        Z = np.ascontiguousarray(Z.T)
        q, v, w, e = p.split(Z)
        x, xd = p.full_state(q, v, e)
        E = p.linear_energy(0.0, x, v) if p.time_invariant else np.zeros(T.size)
        Fel = np.zeros((len(p.elements), T.size))
        qdd = np.zeros((p.nf, T.size))          # free accelerations (the equations of motion of each mode)
        nf = p.nf
        for m, md in enumerate(modes):         # vectorised per mode (time enters only through M(t))
            ks = np.flatnonzero(which == m) if len(modes) > 1 or not p.time_invariant else slice(None)
            if p.time_invariant:
                # time-dependent elements (a modulated spring) take the samples' times
                tk = T[ks] if p.time_dependent else 0.0
                E[ks] += p.potential_energy(q[:, ks], e[:, ks], md, tk)
                pc = self._pieces.get(md)
                if pc is not None:
                    Zk = Z[:, ks]
                    Fel[:, ks] = pc.Fm @ Zk
                    qdd[:, ks] = pc.A[nf:2 * nf] @ Zk
                else:
                    out = p.evaluate(tk, q[:, ks], v[:, ks], e[:, ks], md, w[:, ks])
                    Fel[:, ks], qdd[:, ks] = out["F"], out["a"]
            else:
                for k in ks:
                    E[k] = p.energy(T[k], q[:, k:k + 1], v[:, k:k + 1], e[:, k:k + 1], md)[0]
                    out = p.evaluate(T[k], q[:, k:k + 1], v[:, k:k + 1], e[:, k:k + 1], md, w[:, k:k + 1])
                    Fel[:, k], qdd[:, k] = out["F"][:, 0], out["a"][:, 0]
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
                               acceleration=p.full_acceleration(qdd, e), applied=p.force_rows @ e,
                               work_parts={k: float(w) for k, w in acc["Wp"].items()})
        per = detect_period(res) if events else detect_period_smooth(res)
        if per is not None:
            res.period, res.period_info = per["period"], per
        return res


@contextmanager
def _collector_paused():
    """Python's cyclic garbage collector paused (then restored as it was).  The event loop makes
    a few long-lived objects per event (the event, its record) and no reference cycles; every time
    such objects grow by a quarter, the collector walks every object of the process (the model, the
    loaded modules: ~150 000 objects behind a ``drivefem simulate``).  Seed 000, 16 000 events:
    those walks took 0.2-0.3 s, more than the events' own work (measured with ``gc.callbacks``)."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


_KERNEL = []


def _kernel():
    """The compiled piece kernel, imported on first use (numba's import and the cached compiled code
    cost ~0.5 s: commands that never integrate do not pay it)."""
    if not _KERNEL:
        from . import kernel
        _KERNEL.append(kernel)
    return _KERNEL[0]


class _Recorder:
    """The recorded instants, states and accumulated work, in growing arrays (doubled when full):
    single samples (an instant at an event) and blocks (written by the kernel straight into the
    arrays, then counted by :meth:`filled`); the mode of the samples as runs (the sample where each
    mode starts).  The sample count ``n`` is advanced last, so a Ctrl-C halfway through a record
    leaves the arrays consistent.  The progress callback is told the time reached every
    ``PROGRESS_SAMPLES`` samples (a bar needs no more: a call per event cost ~5% of a run of short
    pieces) and at the end (:meth:`arrays`)."""

    PROGRESS_SAMPLES = 256

    def __init__(self, t0, z0, mode, progress):
        cap = 1024
        self.t, self.W = np.empty(cap), np.empty(cap)
        self.Z = np.empty((cap, z0.size))
        self.ids: dict = {}
        self._mode, self._mode_id = None, -1          # the mode of the last sample and its id
        self._starts, self._run_ids = [], []          # the first sample of each run of one mode, its id
        self.n = 0
        self.progress = progress
        self._report_at = 0 if progress is not None else math.inf     # sample count of the next report
        self.pending = None        # (t, z, mode, W) of a sample to record before the next ones
        self(t0, z0, mode, 0.0)

    def grow(self, k: int) -> None:
        """Room for at least ``k`` more samples."""
        need = self.n + k
        if need > self.t.size:
            cap = max(2 * self.t.size, need)
            for name in ("t", "W", "Z"):
                old = getattr(self, name)
                new = np.empty((cap,) + old.shape[1:], dtype=old.dtype)
                new[:self.n] = old[:self.n]
                setattr(self, name, new)

    def _switch(self, mode) -> None:
        """The samples from ``n`` on are in ``mode``."""
        i = self.ids.get(mode)
        if i is None:
            i = self.ids[mode] = len(self.ids)
        if i != self._mode_id:
            self._starts.append(self.n)
            self._run_ids.append(i)
        self._mode, self._mode_id = mode, i

    @property
    def last_t(self) -> float:
        return float(self.t[self.n - 1])

    def _report(self, n: int, t) -> None:
        self._report_at = n + self.PROGRESS_SAMPLES
        self.progress(t)

    def __call__(self, t, z, mode, W) -> None:
        if mode is not self._mode:
            self._switch(mode)
        n = self.n
        if n == self.t.size:
            self.grow(1)
        self.t[n] = t
        self.W[n] = W
        self.Z[n] = z
        self.n = n + 1
        if n >= self._report_at:
            self._report(n, t)

    def filled(self, n: int, mode) -> None:
        """Count the samples self.n .. n - 1 the kernel wrote into the arrays (all in ``mode``)."""
        if mode is not self._mode:
            self._switch(mode)
        self.n = n
        if n >= self._report_at:
            self._report(n, float(self.t[n - 1]))

    def flush(self) -> None:
        """Record the pending sample (if any)."""
        if self.pending is not None:
            sample, self.pending = self.pending, None
            self(*sample)

    def drop_last(self) -> None:
        """Forget the last sample."""
        self.n -= 1

    def which(self) -> np.ndarray:
        """The mode id of every sample."""
        n = self.n
        starts = np.minimum(np.array(self._starts + [n], dtype=np.int64), n)
        return np.repeat(np.array(self._run_ids, dtype=np.int64), np.diff(starts))

    def arrays(self):
        """(t, Z with one row per sample, the distinct modes, the index of each sample's mode, W)."""
        n = self.n
        if self.progress is not None:
            self.progress(float(self.t[n - 1]))
        return self.t[:n].copy(), self.Z[:n], list(self.ids), self.which(), self.W[:n].copy()


def simulate(problem: Problem, t_end: float, options: Options | None = None, t0: float = 0.0) -> SimulationResult:
    """Event-driven simulation of ``problem`` on [t0, t_end] (see module docstring)."""
    if not isinstance(problem, Problem):
        raise ModelError("simulate", "problem", type(problem).__name__, "a discrete.nonsmooth.Problem")
    if options is not None and not isinstance(options, Options):
        raise ModelError("simulate", "options", options, "None or a discrete.nonsmooth.Options")
    t0 = checks.finite("simulate", "t0", t0, "start time, s")
    t_end = checks.bounded("simulate", "t_end", t_end, (">", t0), note="end time, s")
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
        self.impulses: dict = {}           # element index -> generalised impulse along its s applied here

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
        z, i, nf = self.z, self.i, p.nf
        return p.gf[i].dot(z[nf:2 * nf]) + p.gve[i].dot(z[2 * nf + p.nw:])

    def energy(self) -> float:
        q, v, e = self.solver._split(self.z)
        return self.solver.p.energy(self.t, q[:, None], v[:, None], e[:, None], tuple(self.modes))[0]

    def constraint_force(self) -> float:
        """The constraint force of the element in the current modes."""
        return float(self.solver._forces(self.t, self.z, self.modes)[0][self.i])

    def impact_speed(self, speed: float) -> float:
        """The largest impact speed of the element so far (``speed`` included)."""
        self.impact_ref[self.i] = max(self.impact_ref.get(self.i, 0.0), speed)
        return self.impact_ref[self.i]

    def project_velocity(self, target: float) -> None:
        """Set s' to ``target`` (the kinetic-energy-minimal velocity jump); the generalised impulse along
        s this takes, m_eff (target - s'), is recorded with the element's event (Event.impulse)."""
        solver, i, t = self.solver, self.i, self.t
        jump = (target - self.velocity()) * solver._effective_mass(t, i)
        impulses = self.impulses
        impulses[i] = impulses.get(i, 0.0) + jump
        self.z = solver._project(t, self.z, i, target, True)

    def project_position(self, target: float) -> None:
        self.z = self.solver._project_position(self.t, self.z, self.i, target)
