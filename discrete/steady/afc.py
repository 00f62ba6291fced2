"""Amplitude-frequency curves of nonlinear lumped models from a model file (``drivefem forced``).

Model-file tables (besides those of the nonsmooth simulation, docs/discrete.md):

    [steady]
    method = "hb"            # "hb" (harmonic balance + AFT, default) | "shooting" (exact event-driven)
    omega = [20.0, 80.0]     # forcing frequency range in rad/s, continued from the first to the second
    # z = [0.3, 1.6]         # ... or a ratio range z = omega / omega_ref, with
    # omega_ref = 54.15      # the reference frequency in rad/s
    harmonics = 9            # HB: number of harmonics of omega/subharmonic
    subharmonic = 1          # orbits of period subharmonic * 2 pi / omega
    samples = 128            # HB: AFT time samples per period (default max(64, 8 H + 4))
    regularisation = 1e-3    # HB: friction sign(w) ~ tanh(w / regularisation)
    response = { element = "strand", measure = "max", scale = 30.0 }   # or { body = "disk" }
    #   measure: "amplitude" (half peak-to-peak, default), "max", "min", "peak" (max |.|),
    #   "h1" (amplitude of the component at the forcing frequency);
    #   for an element the force along its coordinate, as a magnitude (tension of a strand)
    stability = true         # Floquet multipliers (HB: variational equation; shooting: monodromy)
    ds = 0.02                # initial arc-length step (scaled), ds_max, ds_min, max_steps
    steps_per_period = 48    # shooting: step limit of the event-driven integrator

    [[cubic_spring]]         # cubic spring F = -k3 s^3 (textbook (8.20)); HB only
    between = ["ground", "disk"]
    k3 = 0.5

Every harmonic ``[[driver]]`` and ``[[force]]`` is set to the continued frequency; ``[simulation]`` is
optional here.
"""
from __future__ import annotations

import copy
import csv
from dataclasses import dataclass, field

import numpy as np

from ..errors import ModelError, SolverError
from ..schema import check_keys, choice, number
from ..nonsmooth import build_problem
from ..nonsmooth.elements import Friction
from .continuation import arclength, refine_fold
from .hb import HBModel, floquet_hb, time_guess
from .shooting import ShootingModel
from .system import Cubic, PeriodicSystem

TOP_LEVEL_KEYS = {"steady", "cubic_spring", "sweep"}   # "sweep": the [sweep] table of fem.sweep
STEADY_KEYS = {"method", "omega", "z", "omega_ref", "harmonics", "subharmonic", "samples", "regularisation",
               "response", "stability", "ds", "ds_max", "ds_min", "max_steps", "steps_per_period"}


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
                "n_points": int(self.omega.size), "reason": self.reason, **self.extra}

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


def write_csv(result: AFCResult, path) -> None:
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["omega_rad_s", "z", result.response_label, "stable", "max_multiplier"])
        z = result.z
        for i in range(result.omega.size):
            w.writerow([repr(float(result.omega[i])), "" if z is None else repr(float(z[i])),
                        repr(float(result.response[i])), int(bool(result.stable[i])),
                        repr(float(result.max_multiplier[i]))])


def plot_afc(result: AFCResult, path, ax=None, label=None) -> None:
    """PNG of the curve: stable parts solid, unstable parts dashed red, folds marked."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    own = ax is None
    if own:
        fig, ax = plt.subplots(figsize=(7, 4.5))
    x = result.z if result.omega_ref else result.omega
    y = result.response
    st = np.asarray(result.stable, bool)
    ys = np.where(st, y, np.nan)
    yu = np.where(~st, y, np.nan)
    # extend unstable segments by one point on each side so the curve is continuous
    for i in range(1, len(st)):
        if st[i] != st[i - 1]:
            yu[i - 1 if st[i - 1] else i] = y[i - 1 if st[i - 1] else i]
    line, = ax.plot(x, ys, "-", lw=1.6, label=label or f"{result.method} (stable)")
    ax.plot(x, yu, "--", color=line.get_color(), lw=1.2, alpha=0.9,
            label=None if label else "unstable")
    for f in result.folds:
        fx = f["omega"] / result.omega_ref if result.omega_ref else f["omega"]
        ax.plot([fx], [f["response"]], "o", ms=4, color=line.get_color(), mfc="none")
    if own:
        ax.set_xlabel("z = omega / omega_ref" if result.omega_ref else "omega, rad/s")
        ax.set_ylabel(result.response_label)
        ax.grid(alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(path, dpi=120)
        plt.close(fig)


# ------------------------------------------------------------------ model file
def is_nonlinear_forced(doc: dict) -> bool:
    """True if the model file asks for a nonlinear steady-state AFC (a ``[steady]`` table)."""
    return isinstance(doc, dict) and "steady" in doc


def _split(doc: dict):
    base = {k: v for k, v in doc.items() if k not in TOP_LEVEL_KEYS}
    base.setdefault("simulation", {"t_end": 1.0})
    return base


def _set_omega(doc: dict, omega: float) -> dict:
    d = copy.deepcopy(doc)
    for key in ("driver", "force"):
        for t in d.get(key, []) or []:
            if isinstance(t, dict) and t.get("amplitude", 0) != 0:
                t["omega"] = float(omega)
    return d


def _cubic_elements(doc: dict, base: dict):
    tabs = doc.get("cubic_spring", [])
    if not isinstance(tabs, list):
        raise ModelError("model file", "cubic_spring", tabs, "an array of tables [[cubic_spring]]")
    out = []
    for i, t in enumerate(tabs, 1):
        w = f"[[cubic_spring]] #{i}"
        check_keys(t, {"name", "body", "between", "ratios", "k3"}, w)
        if "k3" not in t:
            raise ModelError(w, "k3", None, "the cubic stiffness (force = -k3 s^3)")
        k3 = number(t["k3"], "k3", w)
        probe = copy.deepcopy(base)
        spec = {k: t[k] for k in ("body", "between", "ratios") if k in t}
        probe["one_sided"] = list(probe.get("one_sided", [])) + [dict(spec, name="__probe__", k=1.0)]
        p, _ = build_problem(probe)
        out.append(Cubic(name=str(t.get("name", f"cubic{i}")), g=p.elements[-1].g.copy(), k3=k3))
    return out


def parse_steady(doc: dict) -> dict:
    st = doc.get("steady")
    if not isinstance(st, dict):
        raise ModelError("model file", "steady", st, "a table [steady]")
    w = "[steady]"
    check_keys(st, STEADY_KEYS, w)
    out = {}
    if ("omega" in st) == ("z" in st):
        raise ModelError(w, "omega", st.get("omega"), "exactly one of omega = [start, stop] (rad/s) or z = [start, stop]")
    key = "omega" if "omega" in st else "z"
    rng = st[key]
    if not (isinstance(rng, list) and len(rng) == 2 and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in rng)):
        raise ModelError(w, key, rng, "[start, stop], two numbers")
    if not (rng[0] > 0 and rng[1] > 0):
        raise ModelError(w, key, rng, "a range of positive frequencies")
    if rng[0] == rng[1]:
        raise ModelError(w, key, rng, "a non-empty range (start != stop)")
    ref = None
    if key == "z":
        if "omega_ref" not in st:
            raise ModelError(w, "omega_ref", None, "the reference frequency (rad/s) of z = omega / omega_ref")
        ref = number(st["omega_ref"], "omega_ref", w, positive=True)
        out["range"] = (rng[0] * ref, rng[1] * ref)
    else:
        out["range"] = (float(rng[0]), float(rng[1]))
        if "omega_ref" in st:
            ref = number(st["omega_ref"], "omega_ref", w, positive=True)
    out["omega_ref"] = ref
    out["method"] = choice(st.get("method", "hb"), "method", w, ("hb", "shooting"))
    out["harmonics"] = int(number(st.get("harmonics", 7), "harmonics", w, positive=True, integer=True))
    out["subharmonic"] = int(number(st.get("subharmonic", 1), "subharmonic", w, positive=True, integer=True))
    out["samples"] = int(number(st["samples"], "samples", w, positive=True, integer=True)) if "samples" in st else None
    if out["samples"] is not None and out["samples"] < 4 * out["harmonics"] + 2:
        raise ModelError(w, "samples", out["samples"], f"at least 4 harmonics + 2 = {4 * out['harmonics'] + 2}")
    out["regularisation"] = number(st.get("regularisation", 1e-3), "regularisation", w, positive=True)
    out["ds"] = number(st.get("ds", 0.02), "ds", w, positive=True)
    out["ds_max"] = number(st.get("ds_max", 0.1), "ds_max", w, positive=True)
    out["ds_min"] = number(st.get("ds_min", 1e-5), "ds_min", w, positive=True)
    out["max_steps"] = int(number(st.get("max_steps", 2000), "max_steps", w, positive=True, integer=True))
    out["steps_per_period"] = int(number(st.get("steps_per_period", 48), "steps_per_period", w, positive=True, integer=True))
    stab = st.get("stability", True)
    if not isinstance(stab, bool):
        raise ModelError(w, "stability", stab, "true | false")
    out["stability"] = stab
    resp = st.get("response", None)
    if resp is None:
        resp = {}
    if not isinstance(resp, dict):
        raise ModelError(w, "response", resp, "a table { body = .. } or { element = .. }")
    check_keys(resp, {"body", "element", "measure", "scale"}, f"{w} response")
    if "body" in resp and "element" in resp:
        raise ModelError(f"{w} response", "element", resp["element"], "not together with body")
    out["response"] = {"body": resp.get("body"), "element": resp.get("element"),
                       "measure": choice(resp.get("measure", "amplitude"), "measure", f"{w} response",
                                         ("amplitude", "max", "min", "peak", "h1")),
                       "scale": number(resp.get("scale", 1.0), "scale", f"{w} response", positive=True)}
    return out


class SteadyModel:
    """A model file compiled for steady-state analysis at any forcing frequency."""

    def __init__(self, doc: dict, settings: dict | None = None):
        self.doc = doc
        self.cfg = settings or parse_steady(doc)
        self.base = _split(doc)
        p0, _ = build_problem(self.base)
        if not p0.omegas:
            raise ModelError("model file", "driver/force", None,
                             "a harmonic [[driver]] or [[force]] (amplitude and omega) for a forced steady state")
        self.cubics = _cubic_elements(doc, self.base)
        self.problem0 = p0
        self.system = PeriodicSystem(p0, extra=self.cubics, regularisation=self.cfg["regularisation"])
        names = p0.names
        r = self.cfg["response"]
        self.resp_label = "response"
        if r["element"] is not None:
            en = [el.name for el in self.system.elements]
            if r["element"] not in en:
                raise ModelError("[steady] response", "element", r["element"], f"one of {en}")
            self.resp_el = en.index(r["element"])
            el = self.system.elements[self.resp_el]
            if isinstance(el, Friction):
                raise ModelError("[steady] response", "element", r["element"], "a spring-like element (not friction)")
            self.resp_label = f"{r['measure']} |F| {r['element']}" + (f" / {r['scale']:g}" if r["scale"] != 1 else "")
            self.resp_dof = None
        else:
            body = r["body"]
            free = [names[j] for j in p0.f]
            if body is None:
                body = free[0]
            if body not in free:
                raise ModelError("[steady] response", "body", body, f"one of the free bodies {free}")
            self.resp_dof = free.index(body)
            self.resp_el = None
            self.resp_label = f"{r['measure']} {body}" + (f" / {r['scale']:g}" if r["scale"] != 1 else "")

    def factory(self, omega):
        p, _ = build_problem(_set_omega(self.base, omega))
        return p

    def measure(self, t, q, v, omega):
        """Response measure from a periodic time series of the free DOFs."""
        r = self.cfg["response"]
        if self.resp_el is not None:
            F, _ = self.system.element_series(t, q, v, omega)
            y = np.abs(F[self.resp_el])
        else:
            y = q[self.resp_dof]
        m = r["measure"]
        if m == "h1":
            T = 2 * np.pi / omega * self.cfg["subharmonic"]
            tt = np.asarray(t) - t[0]
            sel = tt <= T * (1 + 1e-12)
            tt, yy = tt[sel], y[sel]
            a = 2 / T * np.trapezoid(yy * np.cos(omega * tt), tt)
            b = 2 / T * np.trapezoid(yy * np.sin(omega * tt), tt)
            return float(np.hypot(a, b) / r["scale"])
        val = {"amplitude": 0.5 * (np.max(y) - np.min(y)), "max": np.max(y), "min": np.min(y),
               "peak": np.max(np.abs(y))}[m]
        return float(val / r["scale"])



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

def _hb_curve(sm: SteadyModel) -> AFCResult:
    cfg = sm.cfg
    hb = HBModel(sm.system, harmonics=cfg["harmonics"], nu=cfg["subharmonic"], samples=cfg["samples"])
    w0, w1 = cfg["range"]
    try:
        X0 = hb.solve(hb.linear_guess(w0), w0)[0]
    except (SolverError, np.linalg.LinAlgError):
        try:       # fall back on a time-integrated start (same model, 60 periods from rest)
            X0 = hb.solve(time_guess(hb, w0), w0)[0]
        except (SolverError, np.linalg.LinAlgError) as exc:
            raise SolverError(f"continuation cannot start at omega = {w0!r} (no HB convergence from the "
                              f"linear or the time-integrated guess): {exc}") from exc
    xs = np.full(X0.size, max(np.max(np.abs(X0)), 1e-12))

    def fun(x, w, need_w=True):
        R, J = hb.residual(x, w)
        return R, J, (hb.residual_omega(x, w) if need_w else None)

    br = arclength(fun, X0, w0, w1, xscale=xs, wscale=abs(w1 - w0), ds=cfg["ds"], ds_max=cfg["ds_max"],
                   ds_min=cfg["ds_min"], max_steps=cfg["max_steps"], start_converged=True)
    om, resp, stab, mm, states, crit = [], [], [], [], [], []
    lo, hi = min(w0, w1), max(w0, w1)
    pts = list(zip(br.x, br.w))
    if br.reason.startswith("reached") and len(pts) >= 2 and not lo <= pts[-1][1] <= hi:
        wend = hi if pts[-1][1] > hi else lo           # close the curve exactly at the range end
        try:
            pts[-1] = (hb.solve(pts[-2][0], wend)[0], wend)
        except SolverError:
            pass
    for x, w in pts:
        if not lo - 1e-12 <= w <= hi + 1e-12:
            continue
        t, q, v = hb.evaluate(x, w, points=max(512, hb.N))
        states.append(x)
        om.append(w)
        resp.append(sm.measure(t, q, v, w))
        _record_stability(floquet_hb(hb, x, w) if cfg["stability"] else None, mm, crit, stab)
    folds = []
    for i, wf, fr in br.folds:
        try:
            xf, wf = refine_fold(fun, br.x[i], br.w[i], br.x[i + 1], br.w[i + 1], xs, br.tangent_w[i] > 0)
        except (SolverError, np.linalg.LinAlgError):
            xf, wf = _refine_fold(br, i, wf, fr)
        t, q, v = hb.evaluate(xf, wf, points=max(512, hb.N))
        folds.append({"omega": wf, "response": sm.measure(t, q, v, wf)})
    return AFCResult(omega=np.array(om), response=np.array(resp), stable=np.array(stab, bool),
                     max_multiplier=np.array(mm), folds=folds, method=f"hb (H = {hb.H}, N = {hb.N}, AFT)",
                     response_label=sm.resp_label, omega_ref=cfg["omega_ref"], reason=br.reason,
                     stability_computed=cfg["stability"], extra={"steps_rejected": br.steps_rejected}, states=states,
                     critical=np.array(crit))


def _shooting_curve(sm: SteadyModel) -> AFCResult:
    cfg = sm.cfg
    if not sm.system.exact_ok:
        raise ModelError("[steady]", "method", "shooting", "'hb' for models with [[cubic_spring]] (no exact element)")
    sh = ShootingModel(sm.factory, nu=cfg["subharmonic"], steps_per_period=cfg["steps_per_period"])
    w0, w1 = cfg["range"]
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
    fun = sh.fun(sc)
    br = arclength(fun, y, w0, w1, xscale=sc, wscale=abs(w1 - w0), ds=cfg["ds"], ds_max=cfg["ds_max"],
                   ds_min=cfg["ds_min"], max_steps=cfg["max_steps"], start_converged=True, tol=1e-8)
    om, resp, stab, mm, states, crit = [], [], [], [], [], []
    lo, hi = min(w0, w1), max(w0, w1)
    for x, w in zip(br.x, br.w):
        if not lo - 1e-12 <= w <= hi + 1e-12:
            continue
        resp.append(_shoot_measure(sm, sh, x, w))
        states.append(x)
        om.append(w)
        _record_stability(sh.floquet(x, w, sc) if cfg["stability"] else None, mm, crit, stab)
    folds = []
    for i, wf, fr in br.folds:
        try:
            xf, wf = refine_fold(fun, br.x[i], br.w[i], br.x[i + 1], br.w[i + 1], sc, br.tangent_w[i] > 0)
        except (SolverError, np.linalg.LinAlgError):
            xf, wf = _refine_fold(br, i, wf, fr)
        folds.append({"omega": wf, "response": _shoot_measure(sm, sh, xf, wf)})
    return AFCResult(omega=np.array(om), response=np.array(resp), stable=np.array(stab, bool),
                     max_multiplier=np.array(mm), folds=folds, method="shooting (event-driven, FD monodromy)",
                     response_label=sm.resp_label, omega_ref=cfg["omega_ref"], reason=br.reason,
                     stability_computed=cfg["stability"],
                     extra={"steps_rejected": br.steps_rejected, "simulations": sh.n_sims}, states=states,
                     critical=np.array(crit))


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


def _shoot_measure(sm, sh, y, w):
    _, res = sh.run(y, w, dense=True)
    p = sh.problem(w)
    return sm.measure(res.t, res.x[p.f], res.v[p.f], w)


def run_forced(doc: dict) -> AFCResult:
    """AFC of a nonlinear model file with a ``[steady]`` table (see the module docstring)."""
    sm = SteadyModel(doc)
    if sm.cfg["method"] == "hb":
        if not sm.system.smooth_ok:
            raise ModelError("[steady]", "method", "hb", "'shooting' for models with [[impact]] elements")
        return _hb_curve(sm)
    return _shooting_curve(sm)
