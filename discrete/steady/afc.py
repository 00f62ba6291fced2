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
from . import bifurcation as bif
from . import measures
from .continuation import arclength, refine_fold_bounded
from .hb import HBModel, time_guess
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
    kinks: str = "exact"                     # HB: piecewise-affine laws integrated "exact"ly or "sampled" (AFT)
    truncation_tol: float = 1e-3             # HB: tolerance of the relative truncation estimate
    adaptive: bool = False                   # HB: raise the harmonics where the estimate exceeds the tolerance
    max_harmonics: int | None = None         # HB, adaptive: at most this many harmonics (default 4 harmonics)
    bifurcations: bool = True                # classify and locate folds, branch points, PD, NS
    switch_branches: bool = False            # HB: follow the period-doubled branches and those of branch points


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
    multipliers: list = field(default_factory=list, repr=False)   # all Floquet multipliers per point (or None)
    bifurcations: list = field(default_factory=list)      # bifurcation.Bifurcation, in branch order
    truncation: np.ndarray | None = None                  # HB: relative truncation estimate per point
    truncation_tol: float | None = None
    harmonics: np.ndarray | None = None                   # HB: harmonics per point (adaptive)
    secondary: list = field(default_factory=list)         # AFCResults of switched branches
    warnings: list = field(default_factory=list)
    origin: str = ""                                      # a secondary branch: where it was born
    peak_point: tuple | None = None                       # HB: the maximum located along the branch

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
        """(omega, response) of the largest response: the located maximum along the branch (HB) if there
        is one, else the largest point."""
        if self.peak_point is not None:
            return self.peak_point
        i = int(np.nanargmax(self.response))
        return float(self.omega[i]), float(self.response[i])

    def truncation_ok(self) -> bool | None:
        """Whether every point's truncation estimate is within the tolerance (None: not estimated)."""
        if self.truncation is None or self.truncation_tol is None or not self.truncation.size:
            return None
        return bool(np.all(self.truncation <= self.truncation_tol))

    def truncation_line(self) -> str:
        """One sentence on the truncation estimate (empty without one)."""
        ok = self.truncation_ok()
        if ok is None:
            return ""
        e = self.truncation
        i = int(np.argmax(e))
        Hs = "" if self.harmonics is None else (f", harmonics {int(self.harmonics.min())}..{int(self.harmonics.max())}"
                                                if self.harmonics.min() != self.harmonics.max() else "")
        if ok:
            return (f"truncation estimate: max {e[i]:.2g} at omega = {self.omega[i]:.6g} rad/s, within the tolerance "
                    f"{self.truncation_tol:g}{Hs}")
        above = int(np.sum(e > self.truncation_tol))
        return (f"truncation estimate ABOVE the tolerance {self.truncation_tol:g} at {above} of {e.size} points (max "
                f"{e[i]:.2g} at omega = {self.omega[i]:.6g} rad/s){Hs}: raise harmonics or set adaptive = true")

    def to_dict(self) -> dict:
        d = self._dict()
        if self.method.startswith("hb"):
            d["truncation_estimate"] = None if self.truncation is None else [float(x) for x in self.truncation]
            d["truncation_tolerance"] = self.truncation_tol
            d["truncation_ok"] = self.truncation_ok()
            if self.harmonics is not None:
                d["harmonics"] = [int(h) for h in self.harmonics]
        d["bifurcations"] = [b.to_dict() for b in self.bifurcations]
        if self.secondary or self.origin:
            d["secondary_branches"] = [b.to_dict() for b in self.secondary]
        if self.origin:
            d["origin"] = self.origin
        d["warnings"] = list(self.warnings) + list(d.get("warnings", []))
        return d

    def _dict(self) -> dict:
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
        if self.bifurcations:
            for b in self.bifurcations:
                rows.append(b.line(self.omega_ref))
        else:
            for f in self.folds:
                rows.append(f"fold at omega = {f['omega']:.6g} rad/s, response = {f['response']:.6g}")
        line = self.truncation_line()
        if line:
            rows.append(line)
        for w in self.warnings:
            rows.append(f"warning: {w}")
        if self.reason:
            rows.append(f"branch end: {self.reason}")
        for b in self.secondary:
            rows.append(f"secondary {b.origin}: {b.omega.size} points, omega {b.omega.min():.6g} .. "
                        f"{b.omega.max():.6g} rad/s, {b.reason}")
            for c in b.bifurcations:
                rows.append("  " + c.line(self.omega_ref))
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

    def measure(self, t, q, v, omega, events=None):
        """Response measure from a periodic time series of the free DOFs (:mod:`.measures`; ``events``:
        the instants where the law switches -- an extreme there is not refined by a parabola)."""
        if self.resp_el is not None:
            F, _ = self.system.element_series(t, q, v, omega)
            y = np.abs(F[self.resp_el])
        else:
            y = q[self.resp_dof]
        m = self.cfg.measure
        if m == "h1":
            T = 2 * np.pi / omega * self.cfg.subharmonic
            return measures.series_h1_time(t, y, omega, T) / self.cfg.scale
        ymax, ymin = measures.refined_sample_extremes(t, y, events)
        return float(measures.from_extremes(m, ymax, ymin) / self.cfg.scale)

    def measure_hb(self, hb, states, omegas) -> list:
        """The response measure of HB orbits (coefficients ``states``), exactly (:mod:`.measures`)."""
        from .hb_curve import measure_orbits

        return [float(x) for x in measure_orbits(self, hb, states, omegas)]



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
    """The HB curve (:mod:`.hb_curve`): segments of the continuation, per-point stability, measures and
    truncation estimates, folds checked at more harmonics, bifurcations, switched branches."""
    from . import hb_curve

    cfg = sm.cfg
    models = hb_curve.Models(sm)
    hb = models.get(cfg.harmonics)
    w0, w1 = cfg.range
    # hook (condense.py): with [steady] condense the Newton work of the curve (continuation, folds, peak) runs on
    # the exactly condensed HB equations of the nonlinear DOFs (hb_curve.Models.solver); states stay full
    X0 = models.start(w0, lambda: _hb_start(sm, hb, w0))
    scale = max(float(np.max(np.abs(X0))), 1e-12)
    segs = hb_curve.continue_branch(sm, models, hb, X0, w0, w1, scale, progress)
    res = _hb_result(sm, models, segs, scale, cfg.bifurcations)
    if cfg.switch_branches and cfg.stability:
        cd_primary = res.extra.pop("_data")
        reached = set()
        for b in list(res.bifurcations):
            if b.kind not in ("branch_point", "period_doubling") or not b.located or id(b) in reached:
                continue
            segs2, what, arrived = hb_curve.switch(sm, models, cd_primary, b, scale)
            if segs2 is None:
                res.warnings.append(f"branch switching: {what}")
                continue
            if arrived is not None:          # the branch came back to the primary at another bifurcation
                reached.add(id(arrived))
                what += f", back on the primary branch at omega = {arrived.omega:.8g} rad/s"
            sec = _hb_result(sm, models, segs2, scale, cfg.bifurcations)
            sec.extra.pop("_data", None)
            sec.origin = what
            res.secondary.append(sec)
    else:
        res.extra.pop("_data", None)
    return res


def _hb_result(sm: SteadyModel, models, segs, scale, locate: bool) -> AFCResult:
    from . import hb_curve

    cfg = sm.cfg
    cd = hb_curve.analyse(sm, models, segs, scale, stability=cfg.stability, locate=locate)
    om, stab, mm, crit = [], [], [], []
    for mu in cd.mus:
        _record_stability(mu, mm, crit, stab)
    br = segs[-1].br
    Hs = np.array([m.H for m in cd.models], int)
    Ns = sorted({m.N for m in cd.models})
    Hlabel = f"H = {Hs.min()}" if Hs.min() == Hs.max() else f"H = {Hs.min()}..{Hs.max()} (adaptive)"
    nu = segs[0].hb.nu
    method = (f"hb ({Hlabel}, N = {'/'.join(str(n) for n in Ns)}, "
              f"{'AFT, kinks integrated exactly' if segs[0].hb.exact_elements else 'AFT'}"
              f"{f', subharmonic {nu}' if nu != cfg.subharmonic else ''})")
    reason = br.reason
    bifs = [b for b in cd.bifurcations if locate or b.kind == "fold"]
    res = AFCResult(omega=np.array(cd.omega), response=np.array(cd.response), stable=np.array(stab, bool),
                    max_multiplier=np.array(mm), folds=cd.folds, method=method, response_label=sm.resp_label,
                    omega_ref=cfg.omega_ref, reason=reason, completed=br.completed, stopped_at=br.stopped_at,
                    stop_cause=br.stop, stability_computed=cfg.stability,
                    extra={"steps_rejected": sum(s.br.steps_rejected for s in segs), "_data": cd,
                           "condensation": models.condensation, "dropped_folds": list(cd.dropped)},
                    states=cd.states, critical=np.array(crit), multipliers=cd.mus, bifurcations=bifs,
                    truncation=np.array(cd.estimate), truncation_tol=cfg.truncation_tol,
                    harmonics=Hs if (cfg.adaptive or Hs.min() != Hs.max()) else None, warnings=list(cd.warnings),
                    peak_point=cd.peak)
    if res.truncation_ok() is False:
        res.warnings.append(res.truncation_line())
    return res


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
    mus, bifs = [], []
    for k, (br, phase, fun, sc) in enumerate(segments):
        first = 0 if k == 0 else 1         # a resumed segment starts at the previous one's last orbit
        for x, w in zip(br.x[first:], br.w[first:]):   # all inside the range: a crossing is landed on the bound
            resp.append(_shoot_measure(sm, sh, x, w, phase))
            states.append(x)
            phases.append(phase)
            om.append(w)
            mu = sh.floquet(x, w, sc, phase) if cfg.stability else None
            mus.append(mu)
            _record_stability(mu, mm, crit, stab)
        for i, wf, fr in br.folds:
            located = True
            try:
                xf, wf = refine_fold_bounded(fun, br.x[i], br.w[i], br.x[i + 1], br.w[i + 1], sc,
                                             br.tangent_w[i] > 0)
            except (SolverError, np.linalg.LinAlgError):
                xf, wf = _refine_fold(br, i, wf, fr)
                located = False
            folds.append({"omega": wf, "response": _shoot_measure(sm, sh, xf, wf, phase)})
            bifs.append(bif.Bifurcation("fold", float(wf), folds[-1]["response"], None,
                                        "tangent d omega / ds (bounded search)", located, -1))
    br = segments[-1][0]
    reason = br.reason
    moves = [s[0].w[0] for s0, s in zip(segments, segments[1:]) if s[1] != s0[1]]
    if moves:
        reason += (f" ({len(moves)} change(s) of the shooting section away from events, at omega = "
                   + ", ".join(f"{m:.8g}" for m in moves) + ")")
    transitions = [t for s in segments for t in s[0].transitions]
    if transitions:
        reason += "; stepped over: " + "; ".join(t[2] for t in transitions)
    if cfg.bifurcations and cfg.stability:
        bifs += _interpolated_bifurcations(sm, sh, om, states, mus, phases, [f["omega"] for f in folds])
    return AFCResult(omega=np.array(om), response=np.array(resp), stable=np.array(stab, bool),
                     max_multiplier=np.array(mm), folds=folds, method="shooting (event-driven, FD monodromy)",
                     response_label=sm.resp_label, omega_ref=cfg.omega_ref, reason=reason,
                     completed=br.completed, stopped_at=br.stopped_at, stop_cause=br.stop,
                     stability_computed=cfg.stability,
                     extra={"steps_rejected": sum(s[0].steps_rejected for s in segments), "simulations": sh.n_sims,
                            "section_changes": len(moves),
                            "transitions": [{"omega_before": a, "omega_after": b, "what": d} for a, b, d in transitions],
                            "section_phase_rad": [float(p) for p in phases]}, states=states,
                     critical=np.array(crit), multipliers=mus, bifurcations=sorted(bifs, key=lambda b: b.omega))


def _interpolated_bifurcations(sm, sh, om, states, mus, phases, fold_omegas):
    """Period doublings, Neimark-Sacker points and branch points of a shooting branch: the test functions
    of the multipliers (bifurcation.detect) interpolated linearly between the branch points (each orbit
    costs period maps; not located)."""
    out = []
    folds = {i for i in range(len(om) - 1) for wf in fold_omegas if min(om[i], om[i + 1]) <= wf <= max(om[i], om[i + 1])}
    f = {"branch_point": bif.psi_plus, "period_doubling": bif.psi_pd, "neimark_sacker": bif.psi_ns}
    for i, kind, test in bif.detect(mus, None, folds):
        if phases[i] != phases[i + 1]:
            continue
        fa, fb = f[kind](mus[i]), f[kind](mus[i + 1])
        sig = fa / (fa - fb) if fa != fb else 0.5
        w = om[i] + sig * (om[i + 1] - om[i])
        x = states[i] + sig * (states[i + 1] - states[i])
        mu = bif.critical(mus[i] + sig * (mus[i + 1] - mus[i]), kind) if mus[i].shape == mus[i + 1].shape else None
        try:
            r = _shoot_measure(sm, sh, x, w, phases[i])
        except SolverError:
            r = float("nan")
        out.append(bif.Bifurcation(kind, float(w), r, mu, test, False, i))
    return out


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
    return sm.measure(res.t, res.x[p.f], res.v[p.f], w, events=[e.t for e in res.events])


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
