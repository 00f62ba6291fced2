"""Pseudo-arc-length continuation of a periodic solution in the forcing frequency.

``fun(x, w) -> (R, Jx, Jw)`` is any steady-state residual (harmonic balance, shooting).  Variables are
scaled (``x / xscale``, ``w / wscale``) so that the arc length weighs amplitude and frequency alike.
Predictor: the tangent (null vector of ``[Jx Jw]``, oriented along the previous tangent); corrector:
Newton on ``R = 0`` plus the arc-length condition ``tau . (u - u_pred) = 0``.  Step control: the step
grows by 1.5 after a corrector of <= 3 iterations and is halved after a failure (no convergence in
``maxit``, or a tangent that turns by more than ~37 degrees); a step below ``ds_min`` stops the
branch with reason "stalled".  Folds (turning points) are the sign changes of the frequency component
of the tangent; their frequency and amplitude are interpolated linearly in the tangent component.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import SolverError


@dataclass
class Branch:
    x: list = field(default_factory=list)
    w: list = field(default_factory=list)
    tangent_w: list = field(default_factory=list)
    iterations: list = field(default_factory=list)
    folds: list = field(default_factory=list)          # (index before fold, w_fold)
    reason: str = ""
    steps_rejected: int = 0


def newton_fixed(fun, x0, w, tol=1e-9, maxit=30, xscale=None):
    x = np.array(x0, float)
    xs = np.ones_like(x) if xscale is None else xscale
    for it in range(1, maxit + 1):
        R, Jx, _ = fun(x, w, need_w=False)
        if not (np.all(np.isfinite(Jx)) and np.all(np.isfinite(R))):
            break
        try:
            dx = np.linalg.solve(Jx, -R)
        except np.linalg.LinAlgError:
            dx = np.linalg.lstsq(Jx, -R, rcond=None)[0]
        x = x + dx
        if np.max(np.abs(dx / xs)) <= tol:
            return x, it
    raise SolverError(f"Newton did not converge at omega = {w!r} in {maxit} iterations (no start of continuation)")


def arclength(fun, x0, w0, w_stop, *, xscale, wscale, ds=0.02, ds_min=1e-5, ds_max=0.1, max_steps=2000,
              tol=1e-9, maxit=12, w_bounds=None, start_converged=False, callback=None) -> Branch:
    """Follow the branch from (x0, w0) (corrected at fixed w0 first) towards ``w_stop``."""
    xs = np.asarray(xscale, float)
    direction = 1.0 if w_stop >= w0 else -1.0
    lo, hi = w_bounds if w_bounds is not None else (min(w0, w_stop), max(w0, w_stop))
    if start_converged:
        x, its = np.array(x0, float), 0
    else:
        x, its = newton_fixed(fun, x0, w0, tol=tol, xscale=xs)
    w = float(w0)
    br = Branch()
    n = x.size

    def tangent(x, w, prev):
        R, Jx, Jw = fun(x, w)
        A = np.zeros((n + 1, n + 1))
        A[:n, :n] = Jx * xs[None, :]
        A[:n, n] = Jw * wscale
        A[n] = prev
        rhs = np.zeros(n + 1)
        rhs[n] = 1.0
        try:
            t = np.linalg.solve(A, rhs)
        except np.linalg.LinAlgError:
            t = np.linalg.lstsq(A, rhs, rcond=None)[0]
        t /= np.linalg.norm(t)
        if t @ prev < 0:
            t = -t
        return t

    prev = np.zeros(n + 1)
    prev[n] = direction
    tau = tangent(x, w, prev)
    br.x.append(x.copy())
    br.w.append(w)
    br.tangent_w.append(tau[n])
    br.iterations.append(its)
    if callback:
        callback(x, w)
    h = ds
    for step in range(max_steps):
        u = np.concatenate([x / xs, [w / wscale]])
        ok = False
        while h >= ds_min:
            up = u + h * tau
            uu = up.copy()
            conv = False
            for it in range(1, maxit + 1):
                xx, ww = uu[:n] * xs, uu[n] * wscale
                try:
                    R, Jx, Jw = fun(xx, ww)
                except SolverError:
                    break
                A = np.zeros((n + 1, n + 1))
                A[:n, :n] = Jx * xs[None, :]
                A[:n, n] = Jw * wscale
                A[n] = tau
                rhs = -np.concatenate([R, [tau @ (uu - up)]])
                try:
                    du = np.linalg.solve(A, rhs)
                except np.linalg.LinAlgError:
                    break
                uu = uu + du
                if not np.all(np.isfinite(uu)):
                    break
                if np.max(np.abs(du)) <= tol * max(1.0, np.max(np.abs(uu))):
                    conv = True
                    break
            if conv:
                xn, wn = uu[:n] * xs, uu[n] * wscale
                try:
                    tn = tangent(xn, wn, tau)
                except (SolverError, np.linalg.LinAlgError):
                    tn = None
                if tn is not None and tn @ tau > 0.8:
                    ok = True
                    break
            br.steps_rejected += 1
            h *= 0.5
        if not ok:
            br.reason = f"stalled at omega = {w:.6g}: no corrector convergence down to ds = {ds_min:g}"
            break
        if np.sign(tn[n]) != np.sign(tau[n]) and tau[n] != 0:
            fr = tau[n] / (tau[n] - tn[n])
            br.folds.append((len(br.w) - 1, w + fr * (wn - w), fr))
        x, w, tau = xn, wn, tn
        br.x.append(x.copy())
        br.w.append(w)
        br.tangent_w.append(tau[n])
        br.iterations.append(it)
        if callback:
            callback(x, w)
        if it <= 3:
            h = min(1.5 * h, ds_max)
        elif it >= 7:
            h = max(0.6 * h, ds_min)
        if w > hi or w < lo:
            br.reason = "reached the end of the frequency range"
            break
    else:
        br.reason = f"max_steps = {max_steps} reached"
    return br


def refine_fold(fun, xa, wa, xb, wb, xscale, is_max: bool, tol=1e-11):
    """Locate a fold between two branch points a, b precisely.  Local parametrisation: the component
    k that changes most is fixed to a value s, the rest of x and w solve R = 0 (well posed at a fold);
    w(s) has an extremum at the fold, found by bounded scalar minimisation.  Returns (x, w)."""
    from scipy.optimize import minimize_scalar

    xs = np.asarray(xscale, float)
    xa, xb = np.asarray(xa, float), np.asarray(xb, float)
    k = int(np.argmax(np.abs(xb - xa) / xs))
    n = xa.size
    keep = [j for j in range(n) if j != k]
    sa, sb = xa[k], xb[k]
    span = sb - sa
    cache = {}

    def solve(s):
        f = (s - sa) / span if span != 0 else 0.0
        x = xa + f * (xb - xa)
        w = wa + f * (wb - wa)
        x[k] = s
        for _ in range(30):
            R, Jx, Jw = fun(x, w)
            A = np.hstack([Jx[:, keep], Jw[:, None]])
            d = np.linalg.solve(A, -R)
            x[keep] += d[:-1]
            w += d[-1]
            if np.max(np.abs(d[:-1] / xs[keep])) <= tol and abs(d[-1]) <= tol * abs(w):
                break
        cache[s] = (x.copy(), w)
        return w

    lo, hi = (sa, sb) if sa < sb else (sb, sa)
    pad = 0.5 * (hi - lo)
    sgn = -1.0 if is_max else 1.0
    r = minimize_scalar(lambda s: sgn * solve(s), bounds=(lo - pad, hi + pad), method="bounded",
                        options={"xatol": 1e-10 * max(abs(lo), abs(hi), xs[k])})
    x, w = cache.get(r.x) or (None, solve(r.x))
    if x is None:
        x, w = cache[r.x]
    return x, w
