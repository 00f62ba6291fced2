"""Amplitude-frequency curves of nonlinear models: harmonic balance (AFT) or shooting with the exact
event-driven integrator, continued in the forcing frequency by pseudo-arc-length continuation, with
folds and Floquet stability.

A :class:`SteadyModel` takes a *problem factory* -- any object whose ``problem(omega)`` returns the
:class:`~discrete.nonsmooth.Problem` with every harmonic driver and force at ``omega`` (e.g. a
:class:`~discrete.nonsmooth.ProblemSpec`) -- and the :class:`SteadySettings`.  The model-file layer
(``[steady]`` table) builds both for lumped and hybrid models.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import ModelError, SolverError
from .condense import arclength_scale, condensed_model
from .continuation import arclength, refine_fold
from .hb import HBModel, floquet_hb_batch, time_guess
from .shooting import ShootingModel, section_phase
from .system import PeriodicSystem



@dataclass(frozen=True)
class SteadySettings:
    """Settings of an amplitude-frequency curve (the ``[steady]`` table, docs/steady.md)."""

    range: tuple[float, float]               # forcing frequencies (rad/s), continued from the first
    method: str = "hb"                       # "hb" | "shooting"
    omega_ref: float | None = None           # reference of z = omega / omega_ref
    harmonics: int = 7
    subharmonic: int = 1
    samples: int | None = None
    regularisation: float = 1e-3
    stability: bool = True
    ds: float = 0.02
    ds_max: float = 0.1
    ds_min: float = 1e-5
    max_steps: int = 2000
    steps_per_period: int = 48
    response_body: str | None = None         # a free body (default: the first free DOF) ...
    response_element: str | None = None      # ... or an element's force magnitude
    measure: str = "amplitude"               # "amplitude" | "max" | "min" | "peak" | "h1"
    scale: float = 1.0
    start: str = "linear"                    # HB start: "linear" guess, or "time": integrated from x0/v0
    start_periods: int = 100                 # "time": forcing periods (x subharmonic) integrated first
    condense: str = "auto"                   # HB on the nonlinear DOFs by exact condensation: auto|yes|no (condense.py)


@dataclass
class AFCResult:
    """An amplitude-frequency curve: points in continuation order (one branch, folds included)."""

    omega: np.ndarray
    response: np.ndarray
    stable: np.ndarray                     # bool per point (True if no stability computed)
    max_multiplier: np.ndarray             # max |Floquet multiplier| (nan if not computed)
    folds: list = field(default_factory=list)  # [{"omega":, "response":}]
    method: str = "hb"
    response_label: str = "response"
    omega_ref: float | None = None
    reason: str = ""
    n_points: int = 0
    stability_computed: bool = True
    extra: dict = field(default_factory=dict)
    critical: np.ndarray | None = None    # real part of the largest-modulus multiplier (< 0: flip/period doubling)
    completed: bool = False               # the last point is solved exactly at the end of the asked range
    stopped_at: float = float("nan")      # the last frequency reached, rad/s (the range end when completed)
    stop_cause: str = ""                  # "end" | "left_range" | "ds_min" | "max_steps" (continuation.Branch.stop)
    states: list = field(default_factory=list, repr=False)   # solver unknowns per point (HB coefficients
    #                                                          or shooting initial state), not in to_dict

    @property
    def z(self):
        return None if self.omega_ref is None else self.omega / self.omega_ref

    def jump_intervals(self):
        """Frequency intervals between consecutive folds (hysteresis: several coexisting states)."""
        w = sorted(f["omega"] for f in self.folds)
        return [(w[i], w[i + 1]) for i in range(0, len(w) - 1, 2)]

    def unstable_intervals(self, kind: str = "any"):
        """Frequency intervals of consecutive unstable points: kind "flip" (dominant multiplier < -1:
        period doubling), "fold" (> +1), or "any"."""
        st = np.asarray(self.stable, bool)
        crit = self.critical if self.critical is not None else np.full(st.size, np.nan)
        sel = ~st
        if kind == "flip":
            sel = sel & (crit < 0)
        elif kind == "fold":
            sel = sel & ~(crit < 0)
        out, i = [], 0
        while i < sel.size:
            if sel[i]:
                j = i
                while j + 1 < sel.size and sel[j + 1]:
                    j += 1
                out.append((float(min(self.omega[i:j + 1])), float(max(self.omega[i:j + 1]))))
                i = j + 1
            else:
                i += 1
        return out

    def peak(self):
        i = int(np.nanargmax(self.response))
        return float(self.omega[i]), float(self.response[i])

    def to_dict(self) -> dict:
        return {"method": self.method, "response_label": self.response_label,
                "omega_rad_s": [float(x) for x in self.omega],
                "z": None if self.omega_ref is None else [float(x) for x in self.z],
                "omega_ref_rad_s": self.omega_ref,
                "response": [float(x) for x in self.response], "stable": [bool(s) for s in self.stable],
                "max_multiplier": [None if not np.isfinite(x) else float(x) for x in self.max_multiplier],
                "stability_computed": self.stability_computed,
                "folds": [{k: float(v) for k, v in f.items()} for f in self.folds],
                "jump_intervals_rad_s": [list(map(float, j)) for j in self.jump_intervals()],
                "period_doubling_intervals_rad_s": [list(j) for j in self.unstable_intervals("flip")],
                "critical_multiplier_re": None if self.critical is None else
                [None if not np.isfinite(x) else float(x) for x in self.critical],
                "peak": dict(zip(("omega_rad_s", "response"), self.peak())) if self.omega.size else None,
                "n_points": int(self.omega.size), "reason": self.reason, "completed": bool(self.completed),
                "stopped_at_rad_s": None if not np.isfinite(self.stopped_at) else float(self.stopped_at),
                "stop_cause": self.stop_cause, **self.extra}

    def table(self) -> str:
        head = f"{'omega rad/s':>12} " + (f"{'z':>8} " if self.omega_ref else "") + f"{self.response_label:>14} {'stable':>6} {'max|mu|':>9}"
        rows = [head]
        for i in range(self.omega.size):
            r = f"{self.omega[i]:12.6g} " + (f"{self.z[i]:8.4f} " if self.omega_ref else "")
            mm = self.max_multiplier[i]
            r += f"{self.response[i]:14.6g} {('yes' if self.stable[i] else 'NO'):>6} {mm if np.isfinite(mm) else float('nan'):9.4f}"
            rows.append(r)
        for f in self.folds:
            rows.append(f"fold at omega = {f['omega']:.6g} rad/s, response = {f['response']:.6g}")
        if self.reason:
            rows.append(f"branch end: {self.reason}")
        return "\n".join(rows)


class SteadyModel:
    """A nonlinear model compiled for steady-state analysis at any forcing frequency."""

    def __init__(self, spec, settings: SteadySettings):
        self.spec = spec
        self.cfg = settings
        p0 = spec.problem()
        if not p0.omegas:
            raise ModelError("model file", "driver/force", None,
                             "a harmonic [[driver]] or [[force]] (amplitude and omega) for a forced steady state")
        self.problem0 = p0
        self.system = PeriodicSystem(p0, regularisation=settings.regularisation)
        names = p0.names
        self.resp_label = "response"
        scale = f" / {settings.scale:g}" if settings.scale != 1 else ""
        if settings.response_element is not None:
            en = [el.name for el in self.system.elements]
            if settings.response_element not in en:
                raise ModelError("[steady.response]", "element", settings.response_element, f"one of {en}")
            self.resp_el = en.index(settings.response_element)
            el = self.system.elements[self.resp_el]
            if el.work == "friction":
                raise ModelError("[steady.response]", "element", settings.response_element,
                                 "a spring-like element (not friction)")
            self.resp_label = f"{settings.measure} |F| {settings.response_element}{scale}"
            self.resp_dof = None
        else:
            body = settings.response_body
            free = [names[j] for j in p0.f]
            if body is None:
                body = free[0]
            if body not in free:
                raise ModelError("[steady.response]", "body", body, f"one of the free bodies {free}")
            self.resp_dof = free.index(body)
            self.resp_el = None
            self.resp_label = f"{settings.measure} {body}{scale}"

    def factory(self, omega):
        return self.spec.problem(omega)

    def measure(self, t, q, v, omega):
        """Response measure from a periodic time series of the free DOFs."""
        if self.resp_el is not None:
            F, _ = self.system.element_series(t, q, v, omega)
            y = np.abs(F[self.resp_el])
        else:
            y = q[self.resp_dof]
        m = self.cfg.measure
        if m == "h1":
            T = 2 * np.pi / omega * self.cfg.subharmonic
            tt = np.asarray(t) - t[0]
            sel = tt <= T * (1 + 1e-12)
            tt, yy = tt[sel], y[sel]
            a = 2 / T * np.trapezoid(yy * np.cos(omega * tt), tt)
            b = 2 / T * np.trapezoid(yy * np.sin(omega * tt), tt)
            return float(np.hypot(a, b) / self.cfg.scale)
        val = {"amplitude": 0.5 * (np.max(y) - np.min(y)), "max": np.max(y), "min": np.min(y),
               "peak": np.max(np.abs(y))}[m]
        return float(val / self.cfg.scale)

    def measure_hb(self, hb, states, omegas, points: int | None = None) -> list:
        """:meth:`measure` of HB orbits (coefficients ``states``) sampled at ``points`` (default
        max(512, N)) instants -- all orbits at once (the ``h1`` measure one by one)."""
        P = points or max(512, hb.N)
        if not len(states):
            return []
        if self.cfg.measure == "h1":
            return [self.measure(*hb.evaluate(x, w, points=P), w) for x, w in zip(states, omegas)]
        s = self.system
        Q = np.asarray(states, float).reshape(-1, s.n, hb.m)
        w = np.asarray(omegas, float)[:, None]
        G, DG = hb.basis(P)
        if self.resp_el is not None:
            e = self.resp_el
            g = hb.grid(P)
            A = s.Gf[e] @ Q                                   # (orbits, 2H+1)
            S = A @ G + g.sa[e] + g.sb[e] / w
            Sd = (w / hb.nu) * (A @ DG) + g.sda[e] + w * g.sdb[e]
            y = np.abs(s.elements[e].smooth_force(S, Sd, s.eps)[0])
        else:
            y = Q[:, self.resp_dof] @ G
        val = {"amplitude": lambda: 0.5 * (np.max(y, axis=1) - np.min(y, axis=1)), "max": lambda: np.max(y, axis=1),
               "min": lambda: np.min(y, axis=1), "peak": lambda: np.max(np.abs(y), axis=1)}[self.cfg.measure]()
        return [float(x) for x in val / self.cfg.scale]



def _record_stability(mu, max_multiplier: list, critical: list, stable: list) -> None:
    """Append the largest Floquet multiplier modulus, the real part of the critical multiplier
    (sign: fold +1 / period doubling -1) and stability (|mu| < 1 + 1e-6); NaN / True when the
    stability was not computed (``mu`` is None)."""
    if mu is None:
        max_multiplier.append(np.nan)
        critical.append(np.nan)
        stable.append(True)
        return
    max_multiplier.append(float(np.max(np.abs(mu))))
    critical.append(float(mu[np.argmax(np.abs(mu))].real))
    stable.append(max_multiplier[-1] < 1 + 1e-6)

def _hb_curve(sm: SteadyModel, progress=None) -> AFCResult:
    cfg = sm.cfg
    hb = HBModel(sm.system, harmonics=cfg.harmonics, nu=cfg.subharmonic, samples=cfg.samples)
    w0, w1 = cfg.range
    # hook (condense.py): the continuation runs on the exactly condensed HB equations of the nonlinear DOFs
    # when [steady] condense says so; its states are expanded to the full coefficients (to_full)
    cond, cond_why = condensed_model(sm.system, hb, cfg.condense)
    solver = hb if cond is None else cond
    to_full = (lambda x, w: x) if cond is None else cond.expand
    X0 = _hb_start(sm, hb, w0) if cond is None else cond.start(w0, lambda: _hb_start(sm, hb, w0))
    xs = np.full(X0.size, max(np.max(np.abs(X0)), 1e-12)) if cond is None else arclength_scale(cond, X0, w0)

    def fun(x, w, need_w=True):
        return solver.evaluate_residual(x, w, jac=True, dw=need_w)

    br = arclength(fun, X0, w0, w1, xscale=xs, wscale=abs(w1 - w0), ds=cfg.ds, ds_max=cfg.ds_max,
                   ds_min=cfg.ds_min, max_steps=cfg.max_steps, start_converged=True, callback=_report(progress))
    om, stab, mm, states, crit = [], [], [], [], []
    xfull = [to_full(x, w) for x, w in zip(br.x, br.w)]
    mus = floquet_hb_batch(hb, xfull, br.w) if cfg.stability and br.x else [None] * len(br.x)
    resp = sm.measure_hb(hb, xfull, br.w)
    for x, w, mu in zip(xfull, br.w, mus):           # all inside the range: a crossing is landed on the bound
        states.append(x)
        om.append(w)
        _record_stability(mu, mm, crit, stab)
    folds = []
    for i, wf, fr in br.folds:
        try:
            xf, wf = refine_fold(fun, br.x[i], br.w[i], br.x[i + 1], br.w[i + 1], xs, br.tangent_w[i] > 0)
        except (SolverError, np.linalg.LinAlgError):
            xf, wf = _refine_fold(br, i, wf, fr)
        t, q, v = hb.evaluate(to_full(xf, wf), wf, points=max(512, hb.N))
        folds.append({"omega": wf, "response": sm.measure(t, q, v, wf)})
    return AFCResult(omega=np.array(om), response=np.array(resp), stable=np.array(stab, bool),
                     max_multiplier=np.array(mm), folds=folds, method=f"hb (H = {hb.H}, N = {hb.N}, AFT)",
                     response_label=sm.resp_label, omega_ref=cfg.omega_ref, reason=br.reason,
                     completed=br.completed, stopped_at=br.stopped_at, stop_cause=br.stop,
                     stability_computed=cfg.stability, extra={"steps_rejected": br.steps_rejected,
                                                              "condensation": cond_why if cond else None},
                     states=states,
                     critical=np.array(crit))


def _hb_start(sm: SteadyModel, hb: HBModel, w0: float):
    """The converged HB state at the first frequency.  start = "linear": from the linear guess, falling back
    on 60 periods integrated from rest; start = "time": from ``start_periods`` periods (of the
    subharmonic response) integrated from the model's initial state x0/v0 -- the way onto a branch that
    the linear guess does not lead to (a 1/nu subharmonic, textbook §8.4, or the upper branch of a fold)."""
    cfg = sm.cfg
    p0 = sm.problem0
    if cfg.start == "time":
        y0 = np.concatenate([p0.q0, p0.v0])
        try:
            return hb.solve(time_guess(hb, w0, periods=cfg.start_periods, y0=y0), w0)[0]
        except (SolverError, np.linalg.LinAlgError) as exc:
            raise SolverError(f"continuation cannot start at omega = {w0!r}: no HB convergence from the state "
                              f"integrated over {cfg.start_periods} periods from x0/v0 ({exc}); integrate longer "
                              "(start_periods) or start nearer the branch") from exc
    try:
        return hb.solve(hb.linear_guess(w0), w0)[0]
    except (SolverError, np.linalg.LinAlgError):
        try:       # fall back on a time-integrated start (same model, 60 periods from rest)
            return hb.solve(time_guess(hb, w0), w0)[0]
        except (SolverError, np.linalg.LinAlgError) as exc:
            raise SolverError(f"continuation cannot start at omega = {w0!r} (no HB convergence from the "
                              f"linear or the time-integrated guess): {exc}") from exc


def _shooting_curve(sm: SteadyModel, progress=None) -> AFCResult:
    cfg = sm.cfg
    sh = ShootingModel(sm.factory, nu=cfg.subharmonic, steps_per_period=cfg.steps_per_period)
    w0, w1 = cfg.range
    n = sh.n
    try:
        y, _, _ = sh.settle(np.zeros(n), w0, periods=400, tol=1e-8, scale=np.ones(n))
        _, res = sh.run(y, w0, dense=True)
    except SolverError as exc:
        raise SolverError(f"continuation cannot start at omega = {w0!r}: time integration to the first "
                          f"steady state failed: {exc}") from exc
    p = sh.problem(w0)
    sc = np.concatenate([np.max(np.abs(res.x[p.f]), axis=1), np.max(np.abs(res.v[p.f]), axis=1)])
    sc = np.maximum(sc, 1e-9 * max(np.max(sc), 1e-300))
    try:
        y, _ = sh.solve(y, w0, sc)
    except (SolverError, np.linalg.LinAlgError) as exc:
        raise SolverError(f"continuation cannot start at omega = {w0!r}: {exc}") from exc
    wscale = abs(w1 - w0)
    segments = _shooting_segments(sh, y, cfg, sc, wscale, progress)
    om, resp, stab, mm, states, crit, phases, folds = [], [], [], [], [], [], [], []
    for k, (br, phase, fun, sc) in enumerate(segments):
        first = 0 if k == 0 else 1         # a resumed segment starts at the previous one's last orbit
        for x, w in zip(br.x[first:], br.w[first:]):   # all inside the range: a crossing is landed on the bound
            resp.append(_shoot_measure(sm, sh, x, w, phase))
            states.append(x)
            phases.append(phase)
            om.append(w)
            _record_stability(sh.floquet(x, w, sc, phase) if cfg.stability else None, mm, crit, stab)
        for i, wf, fr in br.folds:
            try:
                xf, wf = refine_fold(fun, br.x[i], br.w[i], br.x[i + 1], br.w[i + 1], sc, br.tangent_w[i] > 0)
            except (SolverError, np.linalg.LinAlgError):
                xf, wf = _refine_fold(br, i, wf, fr)
            folds.append({"omega": wf, "response": _shoot_measure(sm, sh, xf, wf, phase)})
    br = segments[-1][0]
    reason = br.reason
    moves = [s[0].w[0] for s0, s in zip(segments, segments[1:]) if s[1] != s0[1]]
    if moves:
        reason += (f" ({len(moves)} change(s) of the shooting section away from events, at omega = "
                   + ", ".join(f"{m:.8g}" for m in moves) + ")")
    transitions = [t for s in segments for t in s[0].transitions]
    if transitions:
        reason += "; stepped over: " + "; ".join(t[2] for t in transitions)
    return AFCResult(omega=np.array(om), response=np.array(resp), stable=np.array(stab, bool),
                     max_multiplier=np.array(mm), folds=folds, method="shooting (event-driven, FD monodromy)",
                     response_label=sm.resp_label, omega_ref=cfg.omega_ref, reason=reason,
                     completed=br.completed, stopped_at=br.stopped_at, stop_cause=br.stop,
                     stability_computed=cfg.stability,
                     extra={"steps_rejected": sum(s[0].steps_rejected for s in segments), "simulations": sh.n_sims,
                            "section_changes": len(moves),
                            "transitions": [{"omega_before": a, "omega_after": b, "what": d} for a, b, d in transitions],
                            "section_phase_rad": [float(p) for p in phases]}, states=states,
                     critical=np.array(crit))


def _shooting_segments(sh: ShootingModel, y, cfg: SteadySettings, sc, wscale, progress, max_changes: int = 200):
    """Shooting continuation from the converged start ``y`` (section phase 0) in segments: when a segment
    stalls (``ds_min``) and its last orbit has an event near the section (the map's Jacobian jumps when
    an event crosses the section: shooting.py), the section is moved to the middle of the largest gap
    between the orbit's events (:func:`section_phase`), the last point is carried there
    (:meth:`ShootingModel.transfer`) and the branch is resumed along its last secant.  After a stepped-
    over grazing (continuation.py) the branch is resumed with the variables' scales raised to the new
    orbit's amplitudes (a contact excites DOFs that were nearly at rest: with the old scales the arc
    length is all theirs and the steps stay tiny), and from then on again whenever a component of the
    state outgrows twice its scale.  Returns [(Branch, phase, residual function, scale)]."""
    w0, w1 = cfg.range
    lo, hi = min(w0, w1), max(w0, w1)
    segments, phase, x0, wa, orient, converged = [], 0.0, y, w0, None, True
    steps_left = cfg.max_steps
    rescaling = False                  # after a stepped-over grazing: scales follow the orbit
    while True:
        fun = sh.fun(sc, phase)
        sc_seg = sc
        try:
            br = arclength(fun, x0, wa, w1, xscale=sc, wscale=wscale, ds=cfg.ds, ds_max=cfg.ds_max,
                           ds_min=cfg.ds_min, max_steps=steps_left, start_converged=converged, tol=1e-8,
                           callback=_report(progress) if not segments else _report_after_first(progress),
                           w_bounds=(lo, hi), orientation=orient, transition=_event_change(sh, phase),
                           stop_at_transition=True,
                           stop_if=(lambda x, w, s=sc: bool(np.any(np.abs(x) > 2 * s))) if rescaling else None)
        except (SolverError, np.linalg.LinAlgError) as exc:     # the carried point did not re-converge
            last = segments[-1][0]
            last.reason += f"; resuming on the section at phase {phase:.4f} rad failed: {exc}"
            return segments
        segments.append((br, phase, fun, sc_seg))
        steps_left -= max(len(br.w) - 1, 0)
        if br.stop not in ("ds_min", "transition", "stop_if") or len(segments) > max_changes or steps_left <= 0:
            return segments
        if br.stop in ("transition", "stop_if"):
            rescaling = True
            xl, wl = br.x[-1], br.w[-1]
            try:
                _, res = sh.run(xl, wl, dense=True, phase=phase)
            except SolverError:
                return segments
            p = sh.problem(wl)
            new_sc = np.concatenate([np.max(np.abs(res.x[p.f]), axis=1), np.max(np.abs(res.v[p.f]), axis=1)])
            sc = np.maximum(sc, new_sc)
            orient = np.concatenate([(xl - br.x[-2]) / sc, [(wl - br.w[-2]) / wscale]])
            x0, wa, converged = xl, wl, True
            continue
        if len(segments) > 1 and len(br.w) < 2:          # no progress on the new section either
            return segments
        xl, wl = br.x[-1], br.w[-1]
        try:
            _, res = sh.run(xl, wl, phase=phase)
        except SolverError:
            return segments
        new, clear = section_phase(res, wl, sh.nu)
        full = sh.nu * 2 * np.pi
        ev = np.mod(wl * np.array([e.t for e in res.events], float), full)
        now = float(np.min(np.abs(np.mod(ev - phase + 0.5 * full, full) - 0.5 * full))) if ev.size else np.inf
        if not now < 0.5 * clear:            # the section is not near an event: not the cause of the stall
            return segments
        try:
            x0 = sh.transfer(xl, wl, phase, new)
            if len(br.w) >= 2:
                xp = sh.transfer(br.x[-2], br.w[-2], phase, new)
                orient = np.concatenate([(x0 - xp) / sc, [(wl - br.w[-2]) / wscale]])
            else:
                orient = None
        except SolverError:
            return segments
        phase, wa, converged = new, wl, False


def _event_change(sh: ShootingModel, phase: float, short: float = 0.01):
    """The continuation's ``transition`` hook: a description of the discontinuity-induced transition
    between the orbits (x, w) and (xn, wn), or None.  A transition is a change of the events of one
    period (e.g. ``contact_close`` and ``contact_open`` appear at a grazing), or a grazing contact (or
    stick) on either orbit: two consecutive events of one element less than ``short`` of the period
    apart (depth ~ duration^2: the map's term ~ depth^(3/2) makes the branch bend sharply there)."""
    full = sh.nu * 2 * np.pi

    def events(y, w):
        _, res = sh.run(y, w, phase=phase)
        kinds, closest = {}, np.inf
        by_el = {}
        for e in res.events:
            key = f"{e.kind} ({e.element})"
            kinds[key] = kinds.get(key, 0) + 1
            by_el.setdefault(e.element, []).append(w * e.t)
        for ph in by_el.values():
            if len(ph) > 1:
                ph = np.sort(np.mod(ph, full))
                closest = min(closest, float(np.min(np.diff(np.concatenate([ph, [ph[0] + full]])))))
        return kinds, closest / full

    def change(x, w, xn, wn):
        try:
            (a, ca), (b, cb) = events(x, w), events(xn, wn)
        except SolverError:
            return None
        where = f"between omega = {w:.10g} and {wn:.10g}"
        if a != b:
            diff = [f"{k}: {a.get(k, 0)} -> {b.get(k, 0)}" for k in sorted(set(a) | set(b)) if a.get(k, 0) != b.get(k, 0)]
            return f"grazing / sticking transition {where} (events per period " + "; ".join(diff) + ")"
        if min(ca, cb) < short:
            return (f"grazing {where} (shortest contact / stick interval {ca:.2g} -> {cb:.2g} of the period: "
                    f"the branch bends sharply there)")
        return None

    return change


def _report_after_first(progress):
    """The callback of a resumed segment: its first point repeats the previous segment's last one."""
    if progress is None:
        return None
    seen = []

    def cb(x, w):
        if seen:
            progress(w)
        seen.append(w)

    return cb


def _refine_fold(br, i, wf, fr):
    """Fold point from a quadratic fit of omega(sigma) through the 4 branch points around it
    (sigma: scaled arc length), its vertex; falls back to the tangent interpolation."""
    idx = [j for j in range(i - 1, i + 3) if 0 <= j < len(br.w)]
    if len(idx) >= 3:
        X = np.array([br.x[j] for j in idx])
        xs = np.maximum(np.max(np.abs(X), axis=0), 1e-300)
        sig = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(X / xs, axis=0), axis=1))])
        c = np.polyfit(sig, [br.w[j] for j in idx], 2)
        if c[0] != 0:
            sv = -c[1] / (2 * c[0])
            if sig[0] <= sv <= sig[-1]:
                k = int(np.clip(np.searchsorted(sig, sv) - 1, 0, len(idx) - 2))
                f = (sv - sig[k]) / max(sig[k + 1] - sig[k], 1e-300)
                return br.x[idx[k]] + f * (br.x[idx[k + 1]] - br.x[idx[k]]), float(np.polyval(c, sv))
    return br.x[i] + fr * (br.x[i + 1] - br.x[i]), float(wf)


def _shoot_measure(sm, sh, y, w, phase=0.0):
    _, res = sh.run(y, w, dense=True, phase=phase)
    p = sh.problem(w)
    return sm.measure(res.t, res.x[p.f], res.v[p.f], w)


def _report(progress):
    """The continuation's callback for a progress function of the frequency reached (or None)."""
    return None if progress is None else (lambda x, w: progress(w))


def afc(sm: SteadyModel, progress=None) -> AFCResult:
    """The amplitude-frequency curve of a steady-state model (HB or shooting by its settings);
    ``progress(omega)`` is called at every point of the continuation."""
    if sm.cfg.method == "hb":
        if not sm.system.smooth_ok:
            raise ModelError("[steady]", "method", "hb", "'shooting' for models with [[impact]] elements")
        return _hb_curve(sm, progress)
    return _shooting_curve(sm, progress)
