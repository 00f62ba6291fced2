"""Pseudo-arc-length continuation of a periodic solution in the forcing frequency.

``fun(x, w) -> (R, Jx, Jw)`` is any steady-state residual (harmonic balance, shooting).  Variables are
scaled (``x / xscale``, ``w / wscale``) so that the arc length weighs amplitude and frequency alike.
Predictor: the tangent (null vector of ``[Jx Jw]``, oriented along the previous tangent); corrector:
Newton on ``R = 0`` plus the arc-length condition ``tau . (u - u_pred) = 0``.  Step control: the step
grows by 1.5 after a corrector of <= 3 iterations and is halved after a failure (no convergence in
``maxit``, a residual that cannot be evaluated, or a tangent that turns by more than ~37 degrees).
Folds (turning points) are the sign changes of the frequency component of the tangent; their frequency
and amplitude are interpolated linearly in the tangent component.

How a branch ends (``Branch.stop``, ``Branch.completed``, ``Branch.reason``):

* ``"end"`` -- a corrected point lies at or beyond the end ``w_stop`` of the range.  The branch is
  *landed* there: Newton on ``R(x, w_stop) = 0`` at the fixed frequency ``w_stop``, started from the
  secant between the last point inside and the point beyond (so the last point is a solution at
  exactly ``w_stop``, not an interpolation).  ``completed = True``.
* ``"left_range"`` -- the branch turned back (a fold) and crossed the other end of the range (its
  start); it is landed there the same way and stops, ``completed = False``.
* ``"ds_min"`` -- the step fell below ``ds_min``; the reason names the last frequency reached and the
  last failure (corrector divergence, residual error, tangent turn, landing failure).
* ``"max_steps"`` -- ``max_steps`` points were added before the end was reached.

Discontinuity-induced transitions (``transition`` hook, e.g. shooting on nonsmooth models): where an
orbit grazes a switching surface (a contact that starts with zero depth) the branch is only C^1 -- the
map has a term ~ depth^(3/2) whose coefficient grows with the contact stiffness -- so its tangent turns
by O(1) within an arc length far below ``ds_min`` and the tangent-turn test stalls the branch.  As a
last resort, when the step has fallen below ``ds_min``, the largest rejected step whose corrector
converged (a solution of ``R = 0`` on the arc-length plane) and was rejected only for its tangent turn
is accepted if ``transition(x, w, xn, wn)`` names a change between the two orbits (e.g. contact events
that appear); it is recorded in ``Branch.transitions`` (w before, w after, description) and the branch
goes on.  Without the hook, or if it names no change, the branch stalls as before.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import lapack, lu_factor

from ..errors import SolverError


@dataclass
class Branch:
    x: list = field(default_factory=list)
    w: list = field(default_factory=list)
    tangent_w: list = field(default_factory=list)
    iterations: list = field(default_factory=list)
    folds: list = field(default_factory=list)          # (index before fold, w_fold, fraction)
    reason: str = ""                                   # one sentence: where and why the branch ended
    steps_rejected: int = 0
    completed: bool = False                            # True iff the last point is solved at w_end
    stop: str = ""                                     # "end" | "left_range" | "ds_min" | "max_steps" | "interrupted"
    #                                                    | "transition" | "stop_if" (only with those options)
    w_end: float = float("nan")                        # the end of the range that was asked for
    transitions: list = field(default_factory=list)    # (w before, w after, description): stepped-over grazings
    tangents: list = field(default_factory=list)       # the oriented scaled tangent [x / xscale, w / wscale] per point
    bp_sign: list = field(default_factory=list)        # sign of det [Jx Jw; t] per point (branch-point test)
    last_step: float = float("nan")                    # the arc-length step after the last point

    @property
    def stopped_at(self) -> float:
        """The last frequency reached (``w_end`` exactly when completed)."""
        return float(self.w[-1]) if self.w else float("nan")


class _StepFailure(Exception):
    """A rejected continuation step (the message says why)."""


_gesv, _getrs = lapack.get_lapack_funcs(("gesv", "getrs"), (np.zeros(1),))


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


def _land(fun, xa, wa, xb, wb, wt, xs, tol, maxit, h):
    """The branch point at the fixed frequency ``wt`` between the solved points a (inside) and b (at or
    beyond ``wt``): Newton on ``R(x, wt) = 0`` from the secant a-b at ``wt``.  The result must stay
    within one arc-length step ``h`` (scaled) of the secant, else it is another branch."""
    f = (wt - wa) / (wb - wa) if wb != wa else 1.0
    xp = xa + f * (xb - xa)
    x = xp.copy()
    for it in range(1, maxit + 1):
        R, Jx, _ = fun(x, wt, need_w=False)
        dx = np.linalg.solve(Jx, -R)
        x = x + dx
        if not np.all(np.isfinite(x)):
            raise _StepFailure(f"the landing corrector at omega = {wt:.10g} diverged")
        if np.max(np.abs(dx / xs)) <= tol * max(1.0, np.max(np.abs(x / xs))):
            if np.linalg.norm((x - xp) / xs) > max(h, 1e-300):
                raise _StepFailure(f"the landing corrector at omega = {wt:.10g} converged to a point off the "
                                   f"branch (scaled distance {np.linalg.norm((x - xp) / xs):.3g} > step {h:.3g})")
            return x, it
    raise _StepFailure(f"the landing corrector at omega = {wt:.10g} did not converge in {maxit} iterations")


def arclength(fun, x0, w0, w_stop, *, xscale, wscale, ds=0.02, ds_min=1e-5, ds_max=0.1, max_steps=2000,
              tol=1e-9, maxit=12, w_bounds=None, start_converged=False, callback=None, orientation=None,
              transition=None, stop_at_transition=False, stop_if=None, reuse_jacobian=False,
              early_stop=False) -> Branch:
    """Follow the branch from (x0, w0) (corrected at fixed w0 first) towards ``w_stop``; it ends exactly
    at ``w_stop`` (landed, ``completed``) or says where and why it stopped (module docstring).
    ``orientation``: a direction in the scaled variables ``[x / xscale, w / wscale]`` that the first
    tangent must follow (default: increasing w towards ``w_stop``), e.g. to resume a branch.
    ``transition``: the hook of the module docstring (or None).  ``stop_at_transition``: end the branch
    (``stop = "transition"``) at the point after a stepped-over transition, and ``stop_if(x, w) -> bool``:
    end it (``stop = "stop_if"``) after an accepted point for which it holds -- the caller resumes the
    branch, e.g. with the variables rescaled to the new orbit.  ``reuse_jacobian``: the tangent at a new
    point from the corrector's last bordered matrix (one evaluation less per point; the Jacobian is
    taken one Newton step before convergence, i.e. within the tolerance of the point).  ``early_stop``:
    the corrector stops when quadratic convergence predicts its next step far below the tolerance (one
    evaluation less per point; the point is then accurate to ~tol^2/|step| instead of to rounding)."""
    xs = np.asarray(xscale, float)
    direction = 1.0 if w_stop >= w0 else -1.0
    lo, hi = w_bounds if w_bounds is not None else (min(w0, w_stop), max(w0, w_stop))
    w_end = hi if direction > 0 else lo
    w_start = lo if direction > 0 else hi
    near = 1e-10 * abs(wscale)         # a corrected point this close to a bound is landed on it
    if start_converged:
        x, its = np.array(x0, float), 0
    else:
        x, its = newton_fixed(fun, x0, w0, tol=tol, xscale=xs)
    w = float(w0)
    br = Branch(w_end=float(w_end))
    n = x.size

    def tangent(x, w, prev):
        R, Jx, Jw = fun(x, w)
        A = np.zeros((n + 1, n + 1))
        A[:n, :n] = Jx * xs[None, :]
        A[:n, n] = Jw * wscale
        A[n] = prev
        return tangent_from(A, prev)

    ar = np.arange(n + 1)
    e_last = np.zeros(n + 1)               # the right-hand side of the tangent's bordered system
    e_last[n] = 1.0
    Ab = np.empty((n + 1, n + 1))          # the corrector's bordered matrix and right-hand side (reused)
    rb = np.empty(n + 1)
    Abx, Abw, rbx = Ab[:n, :n], Ab[:n, n], rb[:n]

    def corrector(up, tau):
        """Newton on R = 0 and tau . (u - up) = 0, one LAPACK call (gesv) per step; returns (u, iterations,
        the LU, (0-based) pivots and the last bordered matrix): its last row is tau, so the tangent at the new point is its
        solution for e_n (the Jacobian one iteration before convergence, where the step was already below
        the tolerance)."""
        uu = up.copy()
        ww = uu[n] * wscale
        last = np.inf
        for it in range(1, maxit + 1):
            xx, ww = uu[:n] * xs, uu[n] * wscale
            R, Jx, Jw = fun(xx, ww)
            np.multiply(Jx, xs, out=Abx)
            np.multiply(Jw, wscale, out=Abw)
            Ab[n] = tau
            np.negative(R, out=rbx)
            rb[n] = -(tau @ (uu - up))
            lu, piv, du, info = _gesv(Ab, rb)
            if info != 0:
                raise np.linalg.LinAlgError("singular bordered Jacobian")
            uu = uu + du
            big = np.abs(du).max()
            top = np.abs(uu).max()
            if not (big <= 1e300 and top <= 1e300):         # also NaN
                raise _StepFailure(f"the corrector diverged near omega = {ww:.6g}")
            lim = tol * max(1.0, top)
            # converged: this step below the tolerance, or (early_stop) quadratic convergence predicting the
            # next one far below it (|du_k| <= 0.1 |du_k-1| and |du_k|^2 / |du_k-1| <= tol / 10)
            if big <= lim or (early_stop and it > 1 and big <= 0.1 * last and big * big <= 0.1 * lim * last):
                return uu, it, (lu, piv, Ab)
            last = big
        raise _StepFailure(f"the corrector did not converge in {maxit} iterations near omega = {ww:.6g}")

    def tangent_from(A, prev):
        """The tangent from a bordered matrix [Jx Jw; prev] (the corrector's or a fresh one; or its LU and
        0-based pivots), oriented along prev; the sign of det A (= sign det [Jx Jw; t], t . prev > 0) is
        kept in ``sign[0]``: it changes at a branch point, not at a fold."""
        if isinstance(A, tuple):
            lu, piv, A = A
        else:
            lu, piv = lu_factor(A, check_finite=False)
        try:
            t, info = _getrs(lu, piv, e_last)
            d = lu.diagonal()
            tt = t @ t
            if info != 0 or not 0 < tt < np.inf or not d.all():
                raise np.linalg.LinAlgError("singular")
            # sign of det A: the signs of U's diagonal and the parity of the row interchanges
            sign[0] = -1.0 if ((d < 0).sum() + (piv != ar).sum()) % 2 else 1.0
            t /= np.sqrt(tt)
        except (np.linalg.LinAlgError, ValueError):
            t = np.linalg.lstsq(A, e_last, rcond=None)[0]
            sign[0] = 0.0
            t /= np.linalg.norm(t)
        return -t if t @ prev < 0 else t

    def crossed(wn):
        """The range bound at or beyond which ``wn`` lies (None inside)."""
        if wn >= hi - near and (direction > 0 or w < hi - near):
            return hi
        if wn <= lo + near and (direction < 0 or w > lo + near):
            return lo
        return None

    prev = np.zeros(n + 1)
    prev[n] = direction
    if orientation is not None:
        prev = np.asarray(orientation, float) / np.linalg.norm(orientation)
    sign = [0.0]
    tau = tangent(x, w, prev)
    br.x.append(x.copy())
    br.w.append(w)
    br.tangent_w.append(tau[n])
    br.tangents.append(tau.copy())
    br.bp_sign.append(sign[0])
    br.iterations.append(its)
    if callback:
        callback(x, w)
    h = ds
    try:
        for step in range(max_steps):
            u = np.concatenate([x / xs, [w / wscale]])
            ok = False
            failure = f"the step ds = {h:g} is below ds_min before any try"
            landed = None
            turned = None          # the largest step rejected only for its tangent turn: (xn, wn, tn, it, landed, h)
            while h >= ds_min:
                try:
                    uu, it, fac = corrector(u + h * tau, tau)
                    xn, wn = uu[:n] * xs, uu[n] * wscale
                    landed = crossed(wn)
                    if landed is not None:     # at or beyond a bound: land on it at the fixed frequency
                        xn, it_land = _land(fun, x, w, xn, wn, landed, xs, tol, maxit, h)
                        wn = float(landed)
                        it = max(it, it_land)
                        tn = tangent(xn, wn, tau)
                    elif reuse_jacobian:
                        tn = tangent_from(fac, tau)
                    else:
                        tn = tangent(xn, wn, tau)
                    if tn @ tau <= 0.8:
                        if turned is None and transition is not None:
                            turned = (xn, wn, tn, it, landed, h)
                        raise _StepFailure(f"the tangent turned by {np.degrees(np.arccos(np.clip(tn @ tau, -1, 1))):.1f}"
                                           f" deg (limit 36.9 deg) between omega = {w:.6g} and {wn:.6g}")
                    ok = True
                    break
                except (SolverError, np.linalg.LinAlgError, _StepFailure) as exc:
                    failure = str(exc) or type(exc).__name__
                    landed = None
                br.steps_rejected += 1
                h *= 0.5
            if not ok and turned is not None:
                what = transition(x, w, turned[0], turned[1])
                if what:
                    xn, wn, tn, it, landed, h = turned
                    br.transitions.append((float(w), float(wn), str(what)))
                    ok = True
            if not ok:
                br.stop = "ds_min"
                br.reason = (f"stalled at omega = {w:.10g} (range end {w_end:.10g} not reached): the step fell below "
                             f"ds_min = {ds_min:g}; last failure: {failure}")
                break
            if np.sign(tn[n]) != np.sign(tau[n]) and tau[n] != 0:
                fr = tau[n] / (tau[n] - tn[n])
                br.folds.append((len(br.w) - 1, w + fr * (wn - w), fr))
            x, w, tau = xn, wn, tn
            br.x.append(x.copy())
            br.w.append(w)
            br.tangent_w.append(tau[n])
            br.tangents.append(tau.copy())
            br.bp_sign.append(sign[0])
            br.iterations.append(it)
            if callback:
                callback(x, w)
            if it <= 3:
                h = min(1.5 * h, ds_max)
            elif it >= 7:
                h = max(0.6 * h, ds_min)
            br.last_step = h
            if stop_if is not None and landed is None and stop_if(x, w):
                br.stop = "stop_if"
                br.reason = f"stopped at omega = {w:.10g} on request (stop_if)"
                break
            if stop_at_transition and br.transitions and br.transitions[-1][1] == w and landed is None:
                br.stop = "transition"
                br.reason = f"stopped at omega = {w:.10g} after a transition: {br.transitions[-1][2]}"
                break
            if landed == w_end:
                br.stop, br.completed = "end", True
                br.reason = f"reached the end of the frequency range: omega = {w_end:.10g} (solved there)"
                break
            if landed is not None:
                fold = f" at the fold near omega = {br.folds[-1][1]:.6g}" if br.folds else ""
                br.stop = "left_range"
                br.reason = (f"stopped at omega = {w:.10g} (range end {w_end:.10g} not reached): the branch turned "
                             f"back{fold} and left the range through its start omega = {w_start:.10g}")
                break
        else:
            br.stop = "max_steps"
            br.reason = (f"stopped at omega = {w:.10g} (range end {w_end:.10g} not reached): max_steps = {max_steps} "
                         f"reached")
    except KeyboardInterrupt:
        m = min(len(br.x), len(br.w), len(br.tangent_w), len(br.iterations), len(br.tangents), len(br.bp_sign))
        del br.x[m:], br.w[m:], br.tangent_w[m:], br.iterations[m:], br.tangents[m:], br.bp_sign[m:]
        br.stop = "interrupted"
        br.reason = (f"interrupted (Ctrl-C) at omega = {br.w[-1]:.10g} (range end {w_end:.10g} not reached): the "
                     "points computed are kept")
    return br


def locate_fold(fun, x0, w0, t0, xscale, wscale, tol=1e-12, maxit=12):
    """A fold (limit point in omega) by Newton on the minimally extended system (Govaerts, *Numerical
    methods for bifurcations of dynamical equilibria*, SIAM 2000, §3.2): R(x, w) = 0 and g(x, w) = 0,
    where g solves the bordered system ``[Jx b; c^T 0] [v; g] = [0; 1]`` (b, c: the left and right null
    vectors of the last iterate; g = 0 iff Jx is singular).  Its gradient ``-w^T (d Jx) v`` needs second
    derivatives; by the symmetry of R_xx it is the directional difference of one more evaluation,
    ``g_x = -(w^T Jx(x + e v) - w^T Jx(x)) / e`` and ``g_w = -(w^T Jw(x + e v) - w^T Jw(x)) / e``, so
    an iteration costs two evaluations and converges quadratically from the branch points next to the
    fold.  Variables scaled by (xscale, wscale); ``t0``: the scaled tangent near the fold (x part: the
    first right null vector).  Returns (x, w, iterations); SolverError if it does not converge."""
    xs = np.asarray(xscale, float)
    n = xs.size
    x, w = np.array(x0, float), float(w0)
    c = np.asarray(t0, float)[:n].copy()
    c /= max(np.linalg.norm(c), 1e-300)
    b = c.copy()
    last = before = np.inf
    for it in range(1, maxit + 1):
        R, Jx, Jw = fun(x, w)
        Js = Jx * xs[None, :]
        Jws = Jw * wscale
        Bd = np.zeros((n + 1, n + 1))
        Bd[:n, :n] = Js
        Bd[:n, n] = b
        Bd[n, :n] = c
        e = np.zeros(n + 1)
        e[n] = 1.0
        vg = np.linalg.solve(Bd, e)
        wg = np.linalg.solve(Bd.T, e)
        v, g = vg[:n], vg[n]
        wl = wg[:n]
        eps = 1e-7 * max(1.0, np.linalg.norm(x / xs)) / max(np.linalg.norm(v), 1e-300)
        _, Jx2, Jw2 = fun(x + eps * v * xs, w)
        gx = -(wl @ (Jx2 * xs[None, :]) - wl @ Js) / eps
        gw = -(wl @ (Jw2 * wscale) - wl @ Jws) / eps
        A = np.zeros((n + 1, n + 1))
        A[:n, :n] = Js
        A[:n, n] = Jws
        A[n, :n] = gx
        A[n, n] = gw
        du = np.linalg.solve(A, -np.concatenate([R, [g]]))
        if not np.all(np.isfinite(du)):
            break
        x = x + du[:n] * xs
        w = w + du[n] * wscale
        nv, nw = np.linalg.norm(v), np.linalg.norm(wl)
        c, b = v / max(nv, 1e-300), wl / max(nw, 1e-300)
        big = np.max(np.abs(du))
        lim = tol * max(1.0, np.max(np.abs(x / xs)))
        # converged, or quadratic convergence predicting the next step far below the tolerance
        if big <= lim or (it > 1 and big <= 0.1 * last and big * big <= 0.1 * lim * last):
            return x, w, it
        if big > last > before:            # two growing steps in a row: outside the basin (a fold next to a
            break                          # grazing), where the caller's bounded search takes over
        before, last = last, big
    raise SolverError(f"the fold near omega = {w0:.6g} was not located by the extended Newton system")


def correct_on_plane(fun, xp, wp, normal, xscale, wscale, tol=1e-10, maxit=40):
    """The branch point on the hyperplane through (xp, wp) orthogonal to the scaled direction ``normal``
    (Newton on R = 0 and normal . (u - u_p) = 0: regular at folds; at a branch point the system is
    singular and Newton converges linearly, hence the iteration limit).  Returns (x, w, iterations)."""
    xs = np.asarray(xscale, float)
    n = xs.size
    up = np.concatenate([np.asarray(xp, float) / xs, [wp / wscale]])
    u = up.copy()
    for it in range(1, maxit + 1):
        x, w = u[:n] * xs, u[n] * wscale
        R, Jx, Jw = fun(x, w)
        A = np.zeros((n + 1, n + 1))
        A[:n, :n] = Jx * xs[None, :]
        A[:n, n] = Jw * wscale
        A[n] = normal
        du = np.linalg.solve(A, -np.concatenate([R, [normal @ (u - up)]]))
        u = u + du
        if not np.all(np.isfinite(u)):
            break
        if np.max(np.abs(du)) <= tol * max(1.0, np.max(np.abs(u))):
            return u[:n] * xs, u[n] * wscale, it
    raise SolverError(f"no branch point on the plane near omega = {wp:.6g}")


def _fold_chart(fun, xa, wa, xb, wb, xs, tol, slope: bool, strict: bool):
    """The local parametrisation of a branch across a fold between its points a and b: the component k of
    x that changes most is fixed to a value s, the rest of x and w solve R = 0 (well posed at a fold), each
    solve warm-started from the nearest parameter solved before: ``solve(s)``
    gives (x, w, dw/ds) -- the slope (``slope``) from the same bordered matrix, ``[Jx_keep Jw] [dx; dw] =
    -Jx[:, k]``, else None; ``strict``: a solve that does not converge raises SolverError (else its last
    iterate is taken).  Returns (solve, s_a, s_b, k)."""
    xa, xb = np.asarray(xa, float), np.asarray(xb, float)
    k = int(np.argmax(np.abs(xb - xa) / xs))
    keep = [j for j in range(xa.size) if j != k]
    sa, sb = xa[k], xb[k]
    span = sb - sa
    cache = {}

    def solve(s):
        if s in cache:
            return cache[s]
        if cache:
            near = min(cache, key=lambda r: abs(r - s))
            x, w = cache[near][0].copy(), cache[near][1]
        else:
            f = (s - sa) / span if span != 0 else 0.0
            x = xa + f * (xb - xa)
            w = wa + f * (wb - wa)
        x[k] = s
        g = None
        for _ in range(30):
            R, Jx, Jw = fun(x, w)
            A = np.hstack([Jx[:, keep], Jw[:, None]])
            if slope:
                d2 = np.linalg.solve(A, np.stack([-R, -Jx[:, k]], axis=1))
                d, g = d2[:, 0], d2[-1, 1]
            else:
                d = np.linalg.solve(A, -R)
            x[keep] += d[:-1]
            w += d[-1]
            if strict and not (np.all(np.isfinite(d)) and abs(w) < 1e300 and (g is None or np.isfinite(g))):
                raise SolverError(f"the fold near omega = {wa:.6g} was not refined: a solve diverged")
            if np.max(np.abs(d[:-1] / xs[keep])) <= tol and abs(d[-1]) <= tol * abs(w):
                break
        else:
            if strict:
                raise SolverError(f"the fold near omega = {wa:.6g} was not refined: a solve did not converge")
        cache[s] = (x.copy(), w, g)
        return cache[s]

    return solve, sa, sb, k


def refine_fold(fun, xa, wa, xb, wb, xscale, tol=1e-11):
    """Locate a fold between two branch points a, b precisely, where the extended Newton system of
    :func:`locate_fold` has no basin (a fold next to a grazing, where the branch is only C^1), for a
    residual with an exact Jacobian (harmonic balance).  On the local parametrisation of
    :func:`_fold_chart` the fold is the extremum of w(s), i.e. the zero of its slope dw/ds, which comes
    with each solve.  The zero is bracketed by the two points (their slopes differ in sign; else the
    bracket is widened by half its width on either side) and found by regula falsi with the Illinois
    modification to 1e-10 of the parameter's scale (w is stationary there).  A maximum and a minimum of w
    are found alike.  No scipy.optimize (its import is ~0.07 s of a ``drivefem forced`` run).  Returns
    (x, w); SolverError if no fold is bracketed or a solve fails."""
    xs = np.asarray(xscale, float)
    solve, sa, sb, k = _fold_chart(fun, xa, wa, xb, wb, xs, tol, slope=True, strict=True)
    lo, hi = (sa, sb) if sa < sb else (sb, sa)
    xtol = 1e-10 * max(abs(lo), abs(hi), xs[k])
    ga, gb = solve(lo)[2], solve(hi)[2]
    if ga * gb > 0:                      # the fold a little outside the two points
        pad = 0.5 * (hi - lo)
        lo, hi = lo - pad, hi + pad
        ga, gb = solve(lo)[2], solve(hi)[2]
        if ga * gb > 0:
            raise SolverError(f"no fold between omega = {wa:.6g} and {wb:.6g} (the slope dw/ds keeps its sign)")
    side = 0
    for _ in range(200):
        if hi - lo <= xtol or ga == 0 or gb == 0:
            break
        s = (lo * gb - hi * ga) / (gb - ga)
        if not lo < s < hi:
            s = 0.5 * (lo + hi)
        g = solve(s)[2]
        if g * gb > 0:
            hi, gb = s, g
            if side == 1:
                ga *= 0.5                # Illinois: the retained end's value halved
            side = 1
        else:
            lo, ga = s, g
            if side == -1:
                gb *= 0.5
            side = -1
        if g == 0:
            break
    x, w, _ = solve(lo if abs(ga) <= abs(gb) else hi)
    return x.copy(), w


def refine_fold_bounded(fun, xa, wa, xb, wb, xscale, is_max: bool, tol=1e-11):
    """:func:`refine_fold` for a residual whose Jacobian is a finite difference (shooting: the period map
    differentiated numerically), where the slope dw/ds is only as accurate as that difference: the
    extremum of the values w(s) themselves by a bounded scalar search (Brent), over the two points'
    parameters widened by half their width on either side.  ``is_max``: w has a maximum there.  Returns
    (x, w)."""
    from scipy.optimize import minimize_scalar

    xs = np.asarray(xscale, float)
    solve, sa, sb, k = _fold_chart(fun, xa, wa, xb, wb, xs, tol, slope=False, strict=False)
    lo, hi = (sa, sb) if sa < sb else (sb, sa)
    pad = 0.5 * (hi - lo)
    sgn = -1.0 if is_max else 1.0
    r = minimize_scalar(lambda s: sgn * solve(s)[1], bounds=(lo - pad, hi + pad), method="bounded",
                        options={"xatol": 1e-10 * max(abs(lo), abs(hi), xs[k])})
    x, w, _ = solve(r.x)
    return x, w
