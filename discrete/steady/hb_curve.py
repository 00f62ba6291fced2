"""The harmonic-balance amplitude-frequency curve, with its error estimate and its bifurcations.

Steps (docs/steady.md, "Truncation control" and "Bifurcations"):

1. pseudo-arc-length continuation of the HB equations (:func:`~.continuation.arclength`, the tangent from
   the corrector's last Jacobian); with ``adaptive`` the truncation estimate (:mod:`.truncation`) is
   evaluated at every accepted point and, where it exceeds ``truncation_tol``, the harmonics are raised
   (H -> max(H + 2, H (e / tol)^(1/3)), at most ``max_harmonics``: the estimate of a kinked law decays
   about like H^-3), the point is carried over (zero new harmonics, corrected on the plane orthogonal to
   the tangent, regular at folds) and the branch goes on with the new model (one *segment* per H);
2. per point: Floquet multipliers (batched), the response measure (exact, :mod:`.measures`), the
   truncation estimate;
3. folds located by Newton on the minimally extended system, then checked at H' = H + max(2, H/3): the
   fold re-located with H' harmonics gives its frequency change (the fold's estimate); a fold that does
   not persist is dropped, and a jump interval narrower than its folds' estimates is not reported;
4. bifurcations classified from the test functions (:mod:`.bifurcation`) and located on the branch;
5. with ``switch_branches``: the period-doubled branch from each period doubling (the orbit written with
   period 2T, H -> 2H) and the other branch at each branch point are continued over the range.

Condensation (``[steady] condense``, :mod:`.condense`): the Newton work on the branch -- continuation,
fold location and check, the peak's corrections -- runs on the *solver* of each model
(:meth:`Models.solver`: the model itself, or its exact condensation onto the nonlinear DOFs, decided
once per curve), whose unknowns are the coupling DOFs' coefficients; a segment's branch is in those
coordinates, and everything that needs the whole orbit (Floquet multipliers, measures, truncation
estimates, the bifurcations' test functions and branch switching) gets the full coefficients
(:func:`to_full`, exact: the condensed states solve the full equations).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import SolverError
from . import bifurcation as bif
from . import measures
from .condense import CondensedHB, arclength_scale, condensation_rule
from .continuation import arclength, correct_on_plane, locate_fold, refine_fold, refine_fold_bounded
from .hb import HBModel, floquet_hb, floquet_hb_batch
from .truncation import estimates as truncation_estimates
from .truncation import response_direction


class Models:
    """HB models of one steady model by (harmonics, subharmonic order), built once, and the solvers of
    their equations (module docstring): with ``[steady] condense`` (:func:`.condense.condensation_rule`,
    decided for the curve's harmonics and kept for every H, so that all segments share their unknowns)
    the exact condensations onto the nonlinear DOFs, else the models themselves."""

    def __init__(self, sm):
        self.sm = sm
        self._m = {}
        self._solvers = {}
        self._scales = {}
        cfg = sm.cfg
        self.condensed, why = condensation_rule(sm.system, cfg.harmonics, getattr(cfg, "condense", "no"))
        self.condensation = why if self.condensed else None      # the rule's sentence (JSON), or None

    def get(self, H: int, nu: int | None = None) -> HBModel:
        cfg = self.sm.cfg
        nu = cfg.subharmonic if nu is None else int(nu)
        key = (int(H), nu)
        hb = self._m.get(key)
        if hb is None:
            N = cfg.samples if cfg.samples and cfg.samples >= 4 * H + 2 else None
            if N is not None and H != cfg.harmonics:
                N = max(N, int(math.ceil(N * H / cfg.harmonics)))     # same sample density per harmonic
            hb = self._m[key] = HBModel(self.sm.system, harmonics=H, nu=nu, samples=N, kinks=cfg.kinks)
        return hb

    def solver(self, hb: HBModel):
        """The equations the Newton work on hb's branch solves: hb itself, or its condensation."""
        if not self.condensed:
            return hb
        key = (hb.H, hb.nu)
        sv = self._solvers.get(key)
        if sv is None:
            sv = self._solvers[key] = CondensedHB(hb)
        return sv

    def xscale(self, solver, scale: float) -> np.ndarray:
        """Per-unknown scales of the solver's arc length: every full coefficient by ``scale``; a condensed
        coefficient so that, at the start frequency, a step has the length it has in the full coefficients
        (:func:`.condense.arclength_scale`)."""
        if not isinstance(solver, CondensedHB):
            return np.full(solver.nq, scale)
        key = (solver.H, solver.nu, float(scale))
        xs = self._scales.get(key)
        if xs is None:
            xs = self._scales[key] = arclength_scale(solver, None, self.sm.cfg.range[0], xs=scale)
        return xs

    def start(self, w0: float, fallback):
        """The converged full HB state at w0 of the curve's model: condensed, Newton on the condensed
        equations from the restricted linear guess (``fallback()``, the full start, if that fails, and always
        for ``start = "time"``, whose integrated state chooses the branch)."""
        cfg = self.sm.cfg
        hb = self.get(cfg.harmonics)
        if not self.condensed or cfg.start == "time":
            return fallback()
        cond = self.solver(hb)
        return cond.expand(cond.start(w0, fallback), w0)


def to_full(solver, x, w):
    """Full HB coefficients of a solver's unknowns (the identity unless condensed)."""
    return solver.expand(x, w) if isinstance(solver, CondensedHB) else x


def restrict(solver, X):
    """A solver's unknowns of full HB coefficients (the identity unless condensed)."""
    return solver.restrict(X) if isinstance(solver, CondensedHB) else X


def carry(models, solver, xs, x, t, hbn, scale):
    """The solver state x and its scaled tangent t (scales xs) carried to the model hbn (more or fewer
    harmonics, zero new ones): (solver of hbn, state, tangent, its scales).  The full tangent keeps its
    norm (padding), a condensed one is rescaled to the new scales and normalised."""
    sn = models.solver(hbn)
    xsn = models.xscale(sn, scale)
    nd = solver.c.size if isinstance(solver, CondensedHB) else solver.s.n
    xp = bif.pad_harmonics(x, nd, solver.H, hbn.H)
    t = np.asarray(t, float)
    if isinstance(solver, CondensedHB):
        tp = np.concatenate([bif.pad_harmonics(t[:-1] * xs, nd, solver.H, hbn.H) / xsn, t[-1:]])
        tp /= np.linalg.norm(tp)
    else:
        tp = np.concatenate([bif.pad_harmonics(t[:-1], nd, solver.H, hbn.H), t[-1:]])
    return sn, xp, tp, xsn


def full_tangent(solver, x, w, t, xs, scale, wscale):
    """The unit tangent in the full scaled variables [X / scale, w / wscale] of a condensed branch point x
    with scaled tangent t (scales xs): expand is affine in x at fixed w, its omega-derivative is taken by
    central differences."""
    if not isinstance(solver, CondensedHB):
        return t
    t = np.asarray(t, float)
    base = solver.expand(x, w)
    d = solver.expand(x + t[:-1] * xs, w) - base
    h = 1e-6 * abs(w)
    d += (t[-1] * wscale) * (solver.expand(x, w + h) - solver.expand(x, w - h)) / (2 * h)
    u = np.concatenate([d / scale, t[-1:]])
    return u / np.linalg.norm(u)


def residual_function(hb: HBModel):
    """``fun(x, w, need_w=True) -> (R, J, dR/dw)`` of the continuation (the compiled evaluation called
    directly when the model has one: two Python frames less per evaluation)."""
    ck = hb._kernel() if isinstance(hb, HBModel) else False
    if ck:
        def fun(x, w, need_w=True):
            return ck(x, w, True, need_w)
    else:
        def fun(x, w, need_w=True):
            return hb.evaluate_residual(x, w, jac=True, dw=need_w)
    return fun


def max_harmonics(cfg) -> int:
    return int(cfg.max_harmonics or 4 * cfg.harmonics)


# ------------------------------------------------------------------ continuation in segments
class Segment:
    """A part of the branch computed with one HB model: its branch in the coordinates of the model's
    solver (scales xs)."""

    def __init__(self, hb, branch, xs, solver=None):
        self.hb, self.br, self.xs = hb, branch, xs
        self.solver = hb if solver is None else solver


def continue_branch(sm, models, hb, X0, w0, w_stop, scale, progress=None, orientation=None,
                    max_steps=None, stop_if=None, adaptive=None, bounds=None) -> list:
    """Segments of the branch from the converged (X0, w0) towards w_stop (module docstring, step 1).  X0,
    ``orientation`` (scaled by ``scale``) and the states ``stop_if`` sees are full coefficients; each
    segment's branch is in its solver's unknowns (:meth:`Models.solver`)."""
    cfg = sm.cfg
    lo, hi = bounds or (min(cfg.range), max(cfg.range))
    wscale = abs(cfg.range[1] - cfg.range[0])
    g = response_direction(sm)
    adaptive = cfg.adaptive if adaptive is None else adaptive
    Hmax = max_harmonics(cfg)
    segs = []
    solver = models.solver(hb)
    xs = models.xscale(solver, scale)
    x0, wa, orient = restrict(solver, X0), w0, orientation
    if orientation is not None and solver is not hb:
        o = np.asarray(orientation, float)
        orient = np.concatenate([restrict(solver, o[:-1] * scale) / xs, o[-1:]])
    steps_left = cfg.max_steps if max_steps is None else max_steps
    ds = cfg.ds
    while True:
        model = hb

        why = []

        def stop(x, w, model=model, solver=solver, why=why):
            if stop_if is None and not adaptive:
                return False
            xf = to_full(solver, x, w)
            if stop_if is not None and stop_if(xf, w):
                why.append("caller")
                return True
            if adaptive and model.H < Hmax and truncation_estimates(model, [xf], [w], g)[0] > cfg.truncation_tol:
                why.append("truncation")
                return True
            return False

        br = arclength(residual_function(solver), x0, wa, w_stop, xscale=xs, wscale=wscale, ds=ds, ds_max=cfg.ds_max,
                       ds_min=cfg.ds_min, max_steps=steps_left, start_converged=True, w_bounds=(lo, hi),
                       orientation=orient, reuse_jacobian=True, early_stop=True,
                       callback=_report(progress, skip_first=bool(segs)),
                       stop_if=stop if (adaptive or stop_if is not None) else None)
        segs.append(Segment(hb, br, xs, solver))
        steps_left -= max(len(br.w) - 1, 0)
        if br.stop != "stop_if" or steps_left <= 0 or why[-1:] != ["truncation"]:
            return segs
        # raise the harmonics at the last point and go on
        e = truncation_estimates(hb, [to_full(solver, br.x[-1], br.w[-1])], [br.w[-1]], g)[0]
        Hn = min(Hmax, max(hb.H + 2, int(math.ceil(hb.H * (e / cfg.truncation_tol) ** (1 / 3)))))
        hbn = models.get(Hn, hb.nu)
        sn, xp, tp, xsn = carry(models, solver, xs, br.x[-1], br.tangents[-1], hbn, scale)
        tp /= np.linalg.norm(tp)
        try:
            xc, wc, _ = correct_on_plane(residual_function(sn), xp, br.w[-1], tp, xsn, wscale)
        except (SolverError, np.linalg.LinAlgError) as exc:
            br.reason += f"; raising the harmonics to {Hn} at omega = {br.w[-1]:.10g} failed: {exc}"
            br.stop = "ds_min"
            return segs
        x0, wa, orient, hb, solver, xs = xc, wc, tp, hbn, sn, xsn
        ds = br.last_step if np.isfinite(br.last_step) else cfg.ds


def _report(progress, skip_first=False):
    if progress is None:
        return None
    seen = []

    def cb(x, w):
        if seen or not skip_first:
            progress(w)
        seen.append(w)

    return cb


# ------------------------------------------------------------------ response measures of HB orbits
def measure_orbits(sm, hb: HBModel, Xs, omegas) -> np.ndarray:
    """The [steady] response measure of HB orbits, exactly (:mod:`.measures`), divided by the scale."""
    cfg = sm.cfg
    s = sm.system
    if not len(Xs):
        return np.zeros(0)
    Q = np.asarray(Xs, float).reshape(-1, s.n, hb.m)
    w = np.asarray(omegas, float)
    meas = cfg.measure
    if sm.resp_el is None:
        C = Q[:, sm.resp_dof]
        if meas == "h1":
            val = measures.series_h1(C, hb.nu)
        else:
            val = measures.from_extremes(meas, *measures.series_extremes(C, compiled=bool(hb._kernel())))
        return val / cfg.scale
    e = sm.resp_el
    el = s.elements[e]
    A = s.Gf[e] @ Q                                               # (k, 2H+1)
    k = A.shape[0]
    Om = w / hb.nu
    sa, sb, sda, sdb = hb.exogenous_series(e)                     # trigonometric series of the exogenous parts
    Cs = A + sa + np.multiply.outer(1.0 / w, sb)
    ADs = A @ hb.D
    Cv = Om[:, None] * ADs + sda + np.multiply.outer(w, sdb)

    def force(theta):                                             # |F| of the element at phases (k, p)
        th = np.asarray(theta, float)
        S = measures.series_values(Cs, th)
        Sd = measures.series_values(Cv, th)
        return np.abs(el.smooth_force(S, Sd, s.eps)[0])

    law = el.piecewise_law()
    if meas != "h1" and law is not None and not np.any(np.asarray(law.c)) and not np.any(sb):
        # a law of s alone, affine between its breaks: the extremes of |F| over the orbit are among
        # |F| at the extremes of s and at the breaks (and zeros of F) inside that range
        smax, smin = measures.series_extremes(Cs, compiled=bool(hb._kernel()))
        return measures.from_extremes(meas, *_piecewise_abs_extremes(law, smin, smax)) / cfg.scale
    P = max(512, hb.N)
    if meas == "h1":
        P = max(4096, hb.N)
        th = np.broadcast_to(2 * np.pi * np.arange(P) / P, (k, P))
        val = measures.periodic_h1(force(th), w, hb.nu)
    else:
        val = measures.from_extremes(meas, *measures.golden_extremes(force, k, P, iterations=30))
    return val / cfg.scale


def _piecewise_abs_extremes(law, smin, smax):
    """(max, min) of |F(s)| over s in [smin, smax] (per orbit) for a piecewise-affine law of s alone:
    the candidates are the interval's ends, the breaks inside it and the zeros of each piece."""
    a, b = np.asarray(law.a, float), np.asarray(law.b, float)
    br = np.asarray(law.breaks, float)
    cand = [smin, smax] + [np.clip(np.full_like(smin, x), smin, smax) for x in br]
    for p in range(a.size):
        if b[p] != 0:
            z = -a[p] / b[p]
            lo = br[p - 1] if p > 0 else -np.inf
            hi = br[p] if p < br.size else np.inf
            if lo <= z <= hi:
                cand.append(np.clip(np.full_like(smin, z), smin, smax))
    V = np.abs(np.array([law.force(c, 0.0 * c) for c in cand]))
    return V.max(axis=0), V.min(axis=0)


# ------------------------------------------------------------------ folds
def hermite_fold(xa, wa, ta, xb, wb, tb, xs, wscale):
    """The fold between two branch points a, b with unit scaled tangents ta, tb (whose omega components
    differ in sign) on the cubic Hermite curve through them (:func:`.bifurcation.hermite_point`; L the
    scaled chord): its omega component is a cubic in r in [0, 1] whose extremum there is the
    fold, accurate to O(L^4) against the O(L^2) of interpolating linearly in the tangent.  Returns (x, w,
    the curve's unit tangent there) or None (no extremum inside)."""
    ua = np.concatenate([np.asarray(xa, float) / xs, [wa / wscale]])
    ub = np.concatenate([np.asarray(xb, float) / xs, [wb / wscale]])
    L = float(np.linalg.norm(ub - ua))
    if not L > 0:
        return None
    ma, mb = L * np.asarray(ta, float), L * np.asarray(tb, float)
    # d/dr of the cubic: (6r^2 - 6r)(ua - ub) + (3r^2 - 4r + 1) ma + (3r^2 - 2r) mb, omega component
    d = ua[-1] - ub[-1]
    roots = np.roots([6 * d + 3 * ma[-1] + 3 * mb[-1], -6 * d - 4 * ma[-1] - 2 * mb[-1], ma[-1]])
    inside = [r.real for r in roots if abs(r.imag) < 1e-12 and 0.0 <= r.real <= 1.0]
    if len(inside) != 1:
        return None
    r = inside[0]
    u = bif.hermite_point(ua, ub, ta, tb, L, r)
    t = (6 * r ** 2 - 6 * r) * (ua - ub) + (3 * r ** 2 - 4 * r + 1) * ma + (3 * r ** 2 - 2 * r) * mb
    nt = np.linalg.norm(t)
    if not nt > 0:
        return None
    return u[:-1] * xs, u[-1] * wscale, t / nt


def fold_point(hb, br, i, xs, wscale):
    """The fold between branch points i, i+1: Newton on the extended system from the point interpolated
    on the cubic Hermite curve of the two points (:func:`hermite_fold`); :func:`_refine` if that fails."""
    fun = residual_function(hb)
    ta, tb = br.tangents[i], br.tangents[i + 1]
    fr = ta[-1] / (ta[-1] - tb[-1]) if ta[-1] != tb[-1] else 0.5
    x0 = br.x[i] + fr * (br.x[i + 1] - br.x[i])
    w0 = br.w[i] + fr * (br.w[i + 1] - br.w[i])
    t0 = ta + fr * (tb - ta)
    start = hermite_fold(br.x[i], br.w[i], ta, br.x[i + 1], br.w[i + 1], tb, xs, wscale)
    if start is not None:           # the Newton system's basin is small on large steps: start on the cubic
        x0, w0, t0 = start
    try:
        x, w, _ = locate_fold(fun, x0, w0, t0, xs, wscale)
        # on this stretch of the branch: within the two points' segment, in the scaled variables
        ua = np.concatenate([br.x[i] / xs, [br.w[i] / wscale]])
        ub = np.concatenate([br.x[i + 1] / xs, [br.w[i + 1] / wscale]])
        uf = np.concatenate([x / xs, [w / wscale]])
        d = ub - ua
        L2 = float(d @ d)
        f = float((uf - ua) @ d) / max(L2, 1e-300)
        if -0.5 <= f <= 1.5 and np.linalg.norm(uf - ua - f * d) <= np.sqrt(L2):
            return x, w, t0, True
    except (SolverError, np.linalg.LinAlgError):
        pass
    try:
        x, w = _refine(hb, fun, br.x[i], br.w[i], br.x[i + 1], br.w[i + 1], xs, ta[-1] > 0)
        return x, w, t0, True
    except (SolverError, np.linalg.LinAlgError):
        return x0, w0, t0, False


def _refine(hb, fun, xa, wa, xb, wb, xs, is_max):
    """The fold between two branch points where the extended Newton system failed: the zero of the slope
    dw/ds (:func:`.continuation.refine_fold`: the Jacobian is exact), or where the model samples a kink
    (its branch zig-zags, w(s) has kinks and its slope jumps) the extremum of the values w(s) (bounded
    search, :func:`.continuation.refine_fold_bounded`; ``is_max``: w has a maximum there)."""
    model = hb.inner if isinstance(hb, CondensedHB) else hb
    if model.samples_kinks:
        return refine_fold_bounded(fun, xa, wa, xb, wb, xs, is_max)
    return refine_fold(fun, xa, wa, xb, wb, xs)


def check_fold(sm, models, hb, x, w, t, scale, wscale):
    """The fold re-located with H' = H + max(2, H/3) harmonics from the padded fold (Newton on the
    extended system): (omega', H', x') or (None, H', None) if it does not converge there.  x, t and x' are
    in the unknowns of the models' solvers (:meth:`Models.solver`)."""
    Hc = hb.H + max(2, hb.H // 3)
    hc = models.get(Hc, hb.nu)
    sv = models.solver(hb)
    sc, xp, tp, xs = carry(models, sv, models.xscale(sv, scale), x, t, hc, scale)
    fun = residual_function(sc)
    try:
        xc, wc, _ = locate_fold(fun, xp, w, tp, xs, wscale)
        if abs(wc - w) <= 0.05 * wscale:
            return wc, Hc, xc
    except (SolverError, np.linalg.LinAlgError):
        pass
    # the Newton system needs a differentiable Jacobian (sampled kinks are not) and a basin (not next to a
    # grazing): two points on either side of the fold with H' harmonics, on planes across the tangent, and
    # the refinement between them (_refine)
    try:
        d = max(1e-3, 1e-4 * wscale / max(abs(w), 1e-300))
        pts = []
        for sgn in (-1.0, 1.0):
            u = np.concatenate([xp / xs, [w / wscale]]) + sgn * d * tp
            pts.append(correct_on_plane(fun, u[:-1] * xs, u[-1] * wscale, tp, xs, wscale)[:2])
        (xa, wa), (xb, wb) = pts
        xc, wc = _refine(hc, fun, xa, wa, xb, wb, xs, 0.5 * (wa + wb) < w)     # a maximum of omega?
        if abs(wc - w) <= 0.05 * wscale:
            return wc, Hc, xc
    except (SolverError, np.linalg.LinAlgError, ValueError):
        pass
    return None, Hc, None


# ------------------------------------------------------------------ the whole curve
class CurveData:
    """Everything the HB curve computes, point by point (concatenated over segments) and per event."""

    def __init__(self):
        self.omega, self.states, self.models, self.response = [], [], [], []
        self.mus, self.estimate, self.tangents, self.bp_sign = [], [], [], []
        self.folds, self.bifurcations, self.warnings, self.dropped = [], [], [], []
        self.index = []            # (segment, local index) per point
        self.peak = None           # (omega, response) of the maximum located along the branch
        self.segs, self.wscale = [], 1.0

    def tangent(self, p: int):
        """The unit tangent of point p in the full scaled variables [X / scale, w / wscale]."""
        t = self.tangents[p]
        if t is None:
            k, j = self.index[p]
            seg = self.segs[k]
            t = self.tangents[p] = full_tangent(seg.solver, seg.br.x[j], seg.br.w[j], seg.br.tangents[j], seg.xs,
                                                self.scale, self.wscale)
        return t


def analyse(sm, models, segs, scale, stability=True, locate=True) -> CurveData:
    """Steps 2-4 of the module docstring over the segments of one branch."""
    cfg = sm.cfg
    wscale = abs(cfg.range[1] - cfg.range[0])
    g = response_direction(sm)
    cd = CurveData()
    cd.segs, cd.scale, cd.wscale = segs, scale, wscale
    for k, seg in enumerate(segs):
        br, hb, sv = seg.br, seg.hb, seg.solver
        last = len(br.x) - (1 if k < len(segs) - 1 else 0)     # a raised segment's last point is redone
        ws_ = br.w[:last]
        xs_ = [to_full(sv, x, w) for x, w in zip(br.x[:last], ws_)]
        mus = floquet_hb_batch(hb, xs_, ws_) if stability and xs_ else [None] * len(xs_)
        resp = measure_orbits(sm, hb, xs_, ws_)
        est = truncation_estimates(hb, xs_, ws_, g) if len(xs_) else np.zeros(0)
        for j in range(len(xs_)):
            cd.omega.append(float(ws_[j]))
            cd.states.append(xs_[j])
            cd.models.append(hb)
            cd.response.append(float(resp[j]))
            cd.mus.append(None if mus[j] is None else np.asarray(mus[j]))
            cd.estimate.append(float(est[j]))
            cd.tangents.append(br.tangents[j] if sv is hb else None)       # condensed: full on demand
            cd.bp_sign.append(br.bp_sign[j] if br.bp_sign[j] != 0 else None)
            cd.index.append((k, j))
        # folds of this segment, with the index of their interval on the whole branch
        offset = len(cd.omega) - len(xs_)
        for i, _, _ in br.folds:
            _add_fold(sm, models, cd, seg, i, scale, wscale, stability, offset + i)
    _fold_jumps(cd, cfg)
    cd.peak = locate_peak(sm, cd, scale, wscale)
    if locate:
        _locate_bifurcations(sm, models, cd, segs, scale, wscale, stability)
    if stability:
        _critical_multipliers(cd)
    return cd


def _critical_multipliers(cd):
    """The critical multiplier of every located bifurcation: the Floquet multipliers of their orbits, one
    batch per HB model."""
    groups = {}
    for b in cd.bifurcations:
        if b.x is not None and getattr(b, "model", None) is not None:
            groups.setdefault(id(b.model), (b.model, []))[1].append(b)
    for hb, bs in groups.values():
        try:
            mus = floquet_hb_batch(hb, [b.x for b in bs], [b.omega for b in bs])
        except (SolverError, np.linalg.LinAlgError, ValueError):
            continue
        for b, mu in zip(bs, mus):
            b.multiplier = bif.critical(mu, b.kind)


def _add_fold(sm, models, cd, seg, i, scale, wscale, stability, index=-1):
    cfg = sm.cfg
    hb, br = seg.hb, seg.br
    x, w, t, ok = fold_point(seg.solver, br, i, seg.xs, wscale)
    H = hb.H
    wc, Hc, xc = check_fold(sm, models, hb, x, w, t, scale, wscale) if ok else (None, None, None)
    # adaptive: raise the fold's harmonics until its change is within the tolerance
    Hmax = max_harmonics(cfg)
    while cfg.adaptive and wc is not None and abs(wc - w) > cfg.truncation_tol * abs(w) and Hc <= Hmax:
        sv = models.solver(hb)
        hb = models.get(Hc, hb.nu)
        t = carry(models, sv, models.xscale(sv, scale), x, t, hb, scale)[2]
        x, w, H = xc, wc, Hc
        wc, Hc, xc = check_fold(sm, models, hb, x, w, t, scale, wscale)
    x = to_full(models.solver(hb), x, w)
    resp = float(measure_orbits(sm, hb, [x], [w])[0])
    est = abs(wc - w) / abs(w) if wc is not None else float("nan")
    fold = {"omega": float(w), "response": resp, "harmonics": int(H), "located": bool(ok)}
    if wc is not None:
        fold.update({"omega_check": float(wc), "check_harmonics": int(Hc), "estimate": float(est)})
    else:
        fold.update({"omega_check": None, "check_harmonics": int(Hc) if Hc else None, "estimate": None})
    if ok and wc is None:
        cd.dropped.append(fold)
        cd.warnings.append(f"the fold near omega = {w:.8g} rad/s found with H = {H} did not persist with "
                           f"H = {Hc} harmonics: not reported (a truncation artefact)")
        return
    if wc is not None and est > cfg.truncation_tol:
        cd.warnings.append(f"the fold at omega = {w:.8g} rad/s moves by {abs(wc - w):.3g} rad/s ({est:.2g} relative) "
                           f"from H = {H} to {Hc} harmonics: above truncation_tol = {cfg.truncation_tol:g}"
                           + ("" if cfg.adaptive else " (set adaptive = true or raise harmonics)"))
    cd.folds.append(fold)
    b = bif.Bifurcation("fold", float(w), resp, None, "tangent d omega / ds (extended Newton)", bool(ok), index, x)
    b.model = hb
    b.harmonics, b.check = int(H), (wc, Hc)
    if wc is not None:
        b.note = f"{wc:.8g} rad/s with {Hc} harmonics (change {est:.2g} relative)"
    cd.bifurcations.append(b)


def locate_peak(sm, cd, scale, wscale, iterations: int = 3):
    """The maximum of the response along the branch: successive parabolic interpolation in the scaled arc
    length through the largest point and its neighbours, each trial point corrected on the plane across
    the branch (regular at a fold next to the peak) and measured exactly.  None if the largest point is
    an end of the branch or next to a change of harmonics."""
    r = np.asarray(cd.response, float)
    if r.size < 3:
        return None
    i = int(np.nanargmax(r))
    if i == 0 or i == r.size - 1 or not (cd.models[i - 1] is cd.models[i] is cd.models[i + 1]):
        return None
    hb = cd.models[i]
    seg = cd.segs[cd.index[i][0]]
    solver = seg.solver
    fun = residual_function(solver)
    xs = seg.xs
    U = [np.concatenate([restrict(solver, cd.states[j]) / xs, [cd.omega[j] / wscale]]) for j in (i - 1, i, i + 1)]
    pts = [(-np.linalg.norm(U[1] - U[0]), U[0], r[i - 1]), (0.0, U[1], r[i]), (np.linalg.norm(U[2] - U[1]), U[2], r[i + 1])]
    best = pts[1]
    for _ in range(iterations):
        (s0, u0, f0), (s1, u1, f1), (s2, u2, f2) = sorted(pts, key=lambda p: p[0])
        den = (s1 - s0) * (f1 - f2) - (s1 - s2) * (f1 - f0)
        if den == 0:
            break
        sv = s1 - 0.5 * ((s1 - s0) ** 2 * (f1 - f2) - (s1 - s2) ** 2 * (f1 - f0)) / den
        if not s0 < sv < s2 or abs(sv - s1) < 1e-6 * (s2 - s0):      # (the value's error ~ its square)
            break
        # the quadratic (Lagrange) curve through the three points at sv, corrected across the branch
        L0 = (sv - s1) * (sv - s2) / ((s0 - s1) * (s0 - s2))
        L1 = (sv - s0) * (sv - s2) / ((s1 - s0) * (s1 - s2))
        L2 = (sv - s0) * (sv - s1) / ((s2 - s0) * (s2 - s1))
        up = L0 * u0 + L1 * u1 + L2 * u2
        d = u2 - u0
        d /= np.linalg.norm(d)
        try:
            x, w, _ = correct_on_plane(fun, up[:-1] * xs, up[-1] * wscale, d, xs, wscale)
        except (SolverError, np.linalg.LinAlgError):
            break
        f = float(measure_orbits(sm, hb, [to_full(solver, x, w)], [w])[0])
        new = (sv, np.concatenate([x / xs, [w / wscale]]), f)
        pts = sorted([(s0, u0, f0), (s1, u1, f1), (s2, u2, f2), new], key=lambda p: p[2])[1:]
        if f > best[2]:
            best = new
    if best is pts[1] and best[0] == 0.0:
        return None
    return float(best[1][-1] * wscale), float(best[2])


def _fold_jumps(cd, cfg):
    """Drop pairs of consecutive folds (in frequency) closer than their estimates (not resolved)."""
    fs = sorted(cd.folds, key=lambda f: f["omega"])
    keep = list(fs)
    for a, b in zip(fs, fs[1:]):
        ea = (a.get("estimate") or 0.0) * abs(a["omega"])
        eb = (b.get("estimate") or 0.0) * abs(b["omega"])
        if abs(b["omega"] - a["omega"]) < ea + eb and a in keep and b in keep:
            keep.remove(a)
            keep.remove(b)
            cd.dropped += [a, b]
            cd.warnings.append(f"folds at omega = {a['omega']:.8g} and {b['omega']:.8g} rad/s are closer than their "
                               "truncation estimates: the jump between them is not resolved and not reported")
    if len(keep) != len(cd.folds):
        gone = [f["omega"] for f in cd.folds if f not in keep]
        cd.folds = [f for f in cd.folds if f in keep]
        cd.bifurcations = [b for b in cd.bifurcations if not (b.kind == "fold" and b.omega in gone)]


def _psi(hb, kind, test, fun, xa, wa, d, xs, wscale):
    """The test function of a bifurcation kind on the segment direction d (bifurcation.py)."""
    if kind == "branch_point" and test.startswith("psi_BP"):
        ref = bif.log_abs_det(fun, xa, wa, d, xs, wscale)
        return lambda x, w: bif.bordered_det(fun, x, w, d, xs, wscale, ref)
    f = {"branch_point": bif.psi_plus, "period_doubling": bif.psi_pd, "neimark_sacker": bif.psi_ns}[kind]
    return lambda x, w: f(floquet_hb(hb, x, w))


def locate_between(hb, kind, test, xa, wa, xb, wb, scale, wscale, ta=None, tb=None):
    """(x, w, located) of the bifurcation ``kind`` between the branch points a and b of the model hb
    (ta, tb: their scaled tangents, for the predictor)."""
    fun = residual_function(hb)
    xs = np.full(np.size(xa), scale)
    ua = np.concatenate([xa / xs, [wa / wscale]])
    ub = np.concatenate([xb / xs, [wb / wscale]])
    d = (ub - ua) / max(np.linalg.norm(ub - ua), 1e-300)
    psi = _psi(hb, kind, test, fun, xa, wa, d, xs, wscale)
    try:
        x, w, sig, ok = bif.locate_on_segment(psi, fun, xa, wa, xb, wb, xs, wscale, ta=ta, tb=tb)
    except (SolverError, np.linalg.LinAlgError):
        ok = False
    if not ok:
        fa, fb = psi(xa, wa), psi(xb, wb)
        sig = fa / (fa - fb) if fa != fb and fa * fb < 0 else 0.5
        x, w = xa + sig * (xb - xa), wa + sig * (wb - wa)
    return x, w, ok


def _bracket(hb, kind, test, cd, i, scale, wscale):
    """Branch points (a, b) around interval i between which the test function, evaluated at the points
    themselves, changes sign (the continuation's determinant sign comes from the corrector's last
    Jacobian, one iterate before its point: next to a branch point it may flip one interval early)."""
    n = len(cd.omega)
    fun = residual_function(hb)
    for a, b in ((i, i + 1), (i - 1, i + 1), (i, i + 2), (i - 1, i + 2)):
        if a < 0 or b >= n or not all(cd.models[j] is hb for j in range(a, b + 1)):
            continue
        xs = np.full(cd.states[a].size, scale)
        ua = np.concatenate([cd.states[a] / xs, [cd.omega[a] / wscale]])
        ub = np.concatenate([cd.states[b] / xs, [cd.omega[b] / wscale]])
        d = (ub - ua) / max(np.linalg.norm(ub - ua), 1e-300)
        psi = _psi(hb, kind, test, fun, cd.states[a], cd.omega[a], d, xs, wscale)
        if psi(cd.states[a], cd.omega[a]) * psi(cd.states[b], cd.omega[b]) < 0:
            return a, b
    return i, i + 1


def check_between(sm, models, hb, kind, test, states, omegas, i, scale, wscale):
    """The bifurcation re-located with H' = H + max(2, H/3) harmonics: the bracketing points i, i + 1 (or
    the next ones out, if the bifurcation moved) padded and corrected with H' harmonics.  (w', H') or
    (None, H')."""
    n = sm.system.n
    Hc = hb.H + max(2, hb.H // 3)
    hc = models.get(Hc, hb.nu)
    fun = residual_function(hc)
    pts = {}

    def point(j):
        if j not in pts:
            xp = bif.pad_harmonics(states[j], n, hb.H, Hc)
            xs = np.full(xp.size, scale)
            k = j + 1 if j + 1 < len(states) else j - 1
            d = np.concatenate([(bif.pad_harmonics(states[k], n, hb.H, Hc) - xp) / xs, [(omegas[k] - omegas[j]) / wscale]])
            d /= max(np.linalg.norm(d), 1e-300)
            pts[j] = correct_on_plane(fun, xp, omegas[j], d, xs, wscale)[:2]
        return pts[j]

    for lo, hi in ((i, i + 1), (i - 1, i + 2), (i - 2, i + 3)):
        if lo < 0 or hi >= len(states):
            continue
        try:
            (xa, wa), (xb, wb) = point(lo), point(hi)
            xs = np.full(xa.size, scale)
            ua = np.concatenate([xa / xs, [wa / wscale]])
            ub = np.concatenate([xb / xs, [wb / wscale]])
            d = (ub - ua) / max(np.linalg.norm(ub - ua), 1e-300)
            psi = _psi(hc, kind, test, fun, xa, wa, d, xs, wscale)
            if psi(xa, wa) * psi(xb, wb) < 0:
                x, w, ok = locate_between(hc, kind, test, xa, wa, xb, wb, scale, wscale)
                return (w if ok else None), Hc, x
        except (SolverError, np.linalg.LinAlgError):
            continue
    return None, Hc, None


def _locate_bifurcations(sm, models, cd, segs, scale, wscale, stability):
    """Classify (bifurcation.detect), locate the non-fold bifurcations between consecutive points, and
    check each with more harmonics (its estimate: the frequency change)."""
    cfg = sm.cfg
    fold_int = {b.index for b in cd.bifurcations if b.kind == "fold"} | {
        p for k, seg in enumerate(segs) for i, _, _ in seg.br.folds
        for p, (kk, j) in enumerate(cd.index) if kk == k and j == i}
    mus = cd.mus if stability else [None] * len(cd.mus)
    Hmax = max_harmonics(cfg)
    n = sm.system.n
    for i, kind, test in bif.detect(mus, cd.bp_sign, fold_int):
        if cd.models[i] is not cd.models[i + 1]:
            continue                      # across a change of harmonics: the test values are not comparable
        hb = cd.models[i]
        a, b_ = _bracket(hb, kind, test, cd, i, scale, wscale)
        x, w, ok = locate_between(hb, kind, test, cd.states[a], cd.omega[a], cd.states[b_], cd.omega[b_],
                                  scale, wscale, cd.tangent(a) if b_ == a + 1 else None,
                                  cd.tangent(b_) if b_ == a + 1 else None)
        wc, Hc, xc = check_between(sm, models, hb, kind, test, cd.states, cd.omega, i, scale, wscale) if ok \
            else (None, None, None)
        states = cd.states
        while cfg.adaptive and wc is not None and abs(wc - w) > cfg.truncation_tol * abs(w) and Hc <= Hmax:
            # the branch near it with Hc harmonics: carry the neighbouring points over and check again
            H0 = hb.H
            hb = models.get(Hc, hb.nu)
            states = [bif.pad_harmonics(s_, n, H0, Hc) for s_ in states]
            x, w = xc, wc
            wc, Hc, xc = check_between(sm, models, hb, kind, test, states, cd.omega, i, scale, wscale)
        resp = float(measure_orbits(sm, hb, [x], [w])[0])
        b = bif.Bifurcation(kind, float(w), resp, None, test, bool(ok), i, x)
        b.model = hb
        b.harmonics = hb.H
        b.check = (wc, Hc)
        if wc is not None:
            est = abs(wc - w) / abs(w)
            b.note = f"{wc:.8g} rad/s with {Hc} harmonics (change {est:.2g} relative)"
            if est > cfg.truncation_tol:
                cd.warnings.append(f"the {bif.LABELS[kind]} at omega = {w:.8g} rad/s moves by {abs(wc - w):.3g} rad/s "
                                   f"({est:.2g} relative) from H = {hb.H} to {Hc} harmonics: above truncation_tol = "
                                   f"{cfg.truncation_tol:g}" + ("" if cfg.adaptive else " (set adaptive = true or raise "
                                                                                          "harmonics)"))
        elif ok:
            cd.warnings.append(f"the {bif.LABELS[kind]} near omega = {w:.8g} rad/s found with H = {hb.H} was not "
                               f"re-located with {Hc} harmonics: not reported (a truncation artefact)")
            continue
        cd.bifurcations.append(b)
    cd.bifurcations.sort(key=lambda b: (b.index, b.omega))


# ------------------------------------------------------------------ branch switching
def switch(sm, models, cd, b: "bif.Bifurcation", scale, progress=None):
    """The branch born at the bifurcation b (a branch point or a period doubling), continued over the
    range: (segments, the model, a description) or None with a reason."""
    cfg = sm.cfg
    wscale = abs(cfg.range[1] - cfg.range[0])
    i = b.index
    n = sm.system.n
    hb0 = cd.models[i]
    hb = models.get(b.harmonics or hb0.H, hb0.nu)      # adaptive: the harmonics it was located with
    sa_, sb_ = (bif.pad_harmonics(cd.states[j], n, hb0.H, hb.H) for j in (i, i + 1))
    lo, hi = min(cfg.range), max(cfg.range)
    if b.kind == "branch_point":
        hs = hb
        xa, xb, x0 = sa_, sb_, b.x
        what = f"branch from the branch point at omega = {b.omega:.8g} rad/s"
    else:
        hs = models.get(2 * hb.H, 2 * hb.nu)
        xa, xb = bif.embed_doubled(sa_, n, hb.H), bif.embed_doubled(sb_, n, hb.H)
        x0 = bif.embed_doubled(b.x, n, hb.H)
        what = f"period-doubled branch from omega = {b.omega:.8g} rad/s (subharmonic {hs.nu})"
    fun = residual_function(hs)
    xs = np.full(np.size(x0), scale)
    ua = np.concatenate([xa / xs, [cd.omega[i] / wscale]])
    ub = np.concatenate([xb / xs, [cd.omega[i + 1] / wscale]])
    t = (ub - ua) / max(np.linalg.norm(ub - ua), 1e-300)
    w0 = b.omega
    if b.kind == "period_doubling":        # the branch point of the doubled system (an algebraic test)
        ref = bif.log_abs_det(fun, xa, cd.omega[i], t, xs, wscale)
        psi = lambda x, w: bif.bordered_det(fun, x, w, t, xs, wscale, ref)        # noqa: E731
        try:
            x1, w1, _, ok = bif.locate_on_segment(psi, fun, xa, cd.omega[i], xb, cd.omega[i + 1], xs, wscale)
            if ok:
                x0, w0 = x1, w1
        except (SolverError, np.linalg.LinAlgError):
            pass
    try:
        t2, ratio = bif.switch_direction(fun, x0, w0, t, xs, wscale)
    except np.linalg.LinAlgError as exc:
        return None, f"{what}: no switching direction ({exc})", None
    u0 = np.concatenate([x0 / xs, [w0 / wscale]])
    found = False
    for h in (max(cfg.ds, 0.05 * cfg.ds_max), 0.004, 0.001):        # a curved branch: smaller steps
        for sgn in (1.0, -1.0):
            up = u0 + sgn * h * t2
            try:
                xn, wn, _ = correct_on_plane(fun, up[:-1] * xs, up[-1] * wscale, sgn * t2, xs, wscale)
            except (SolverError, np.linalg.LinAlgError):
                continue
            un = np.concatenate([xn / xs, [wn / wscale]])
            if lo <= wn <= hi and np.linalg.norm(un - u0) < 4 * h:
                found = True
                break
        if found:
            break
    else:
        return None, f"{what}: the corrector did not leave the known branch (singular-value ratio {ratio:.2g})", None
    others = [c for c in cd.bifurcations if c.kind == b.kind and c is not b and c.x is not None]

    def ref_state(c):          # another bifurcation's orbit in the switched branch's representation
        x = bif.pad_harmonics(c.x, n, (c.x.size // n - 1) // 2, hb.H)
        return bif.embed_doubled(x, n, hb.H) if b.kind == "period_doubling" else x

    ref_pts = [(ref_state(c), c.omega, c) for c in others]
    travelled = [0.0]
    prev = [un]
    arrived = []

    def stop_if(x, w):             # back at another bifurcation of the same kind (or the origin) of the primary
        u = np.concatenate([x / xs, [w / wscale]])
        step = u - prev[0]
        L = float(np.linalg.norm(step))
        travelled[0] += L
        a = prev[0]
        prev[0] = u
        for xr, wr, c in ref_pts + ([(x0, w0, None)] if travelled[0] > 4 * cfg.ds_max else []):
            if xr.size != x.size:
                continue
            # the last step passed the bifurcation: its distance to the step's segment is a fraction of the step
            ur = np.concatenate([xr / xs, [wr / wscale]])
            f = np.clip(float((ur - a) @ step) / max(L * L, 1e-300), 0.0, 1.0)
            if np.linalg.norm(ur - a - f * step) <= 0.25 * L:
                arrived.append(c)
                return True
        return False

    w_stop = hi if t2[-1] * sgn >= 0 else lo
    segs = continue_branch(sm, models, hs, xn, wn, w_stop, scale, progress=None, orientation=sgn * t2,
                           max_steps=min(cfg.max_steps, 1000), stop_if=stop_if, adaptive=False, bounds=(lo, hi))
    if arrived:
        segs[-1].br.reason = (f"reached the primary branch again at omega = {segs[-1].br.w[-1]:.10g}"
                              + (f" (the {bif.LABELS[arrived[-1].kind]} at {arrived[-1].omega:.8g} rad/s)"
                                 if arrived[-1] is not None else " (where it was born)"))
    return segs, what, (arrived[-1] if arrived else None)
