"""The inner loop of the event-driven solver: march one exact piece to its first event.

Compiled by numba when it is installed (``DRIVEFEM_JIT=0`` runs the same source as plain Python,
for comparison and debugging); every function here works on float arrays and scalars only.

A piece is the affine, time-invariant mode ``z' = A z`` of :mod:`discrete.nonsmooth.piece`, given
by its step propagator ``P = expm(A h)``, the guard rows and slopes ``R = [Cg; Cg A]``, the local
expansion ``T_j = (h A)^j / j!`` and the work matrices of its power categories (``G_p(h)`` for a
full step, ``Q_p`` the power forms).  Event location per step (the scheme of the solver's
docstring): the guard values and slopes at both step ends give a cubic Hermite model; a sign
change, or a dip of the model confirmed by Newton at the exact local minimum, brackets the first
crossing, refined by safeguarded Newton on the guard along the exact local expansion
``z(t_k + s h) = sum_j s^j T_j z_k`` (a polynomial in s).
"""
from __future__ import annotations

import math

import numpy as np

from ..jit import JIT, njit  # noqa: F401  (JIT: whether numba compiles this module)


END, EVENT, FULL = 0, 1, 2       # why advance() returned: t_end reached, an event, output buffer full


# ------------------------------------------------------------ the cubic Hermite model of a guard
@njit(cache=True)
def _hermite(g0, g1, d0, d1, h):
    """Coefficients of p(s) = c0 + c1 s + c2 s^2 + c3 s^3 on [0, h] matching values and slopes."""
    c2 = (3.0 * (g1 - g0) / h - 2.0 * d0 - d1) / h
    c3 = (d0 + d1 - 2.0 * (g1 - g0) / h) / (h * h)
    return g0, d0, c2, c3


@njit(cache=True)
def _hermite_value(g0, g1, d0, d1, h, s):
    c0, c1, c2, c3 = _hermite(g0, g1, d0, d1, h)
    return c0 + s * (c1 + s * (c2 + s * c3))


@njit(cache=True)
def _critical(g0, g1, d0, d1, h, lo):
    """Critical points of the Hermite cubic in (lo, h): (count, first, second)."""
    c0, c1, c2, c3 = _hermite(g0, g1, d0, d1, h)
    a, b, c = 3.0 * c3, 2.0 * c2, c1
    r1, r2, n = 0.0, 0.0, 0
    if a == 0.0 or abs(a) * h <= 1e-14 * (abs(b) + abs(c) / h):
        if b != 0.0:
            r1, n = -c / b, 1
    else:
        disc = b * b - 4.0 * a * c
        if disc < 0.0:
            return 0, 0.0, 0.0
        qq = -0.5 * (b + math.copysign(math.sqrt(disc), b))
        r1, n = qq / a, 1
        if qq != 0.0:
            r2, n = c / qq, 2
    k, x1, x2 = 0, 0.0, 0.0
    if n >= 1 and lo < r1 < h:
        k, x1 = 1, r1
    if n == 2 and lo < r2 < h:
        if k == 0:
            k, x1 = 1, r2
        else:
            k, x2 = 2, r2
    return k, x1, x2


@njit(cache=True)
def _hermite_min(g0, g1, d0, d1, h, lo):
    """(found, s) of the lowest critical point of the cubic in (lo, h)."""
    k, x1, x2 = _critical(g0, g1, d0, d1, h, lo)
    if k == 0:
        return False, 0.0
    if k == 2 and _hermite_value(g0, g1, d0, d1, h, x2) < _hermite_value(g0, g1, d0, d1, h, x1):
        return True, x2
    return True, x1


@njit(cache=True)
def _hermite_argmax(g0, g1, d0, d1, h):
    """(found, s) of the cubic's largest value among its critical points in (0, h) and h, if > 0."""
    k, x1, x2 = _critical(g0, g1, d0, d1, h, 0.0)
    best, arg = -np.inf, h
    if k >= 1:
        best, arg = _hermite_value(g0, g1, d0, d1, h, x1), x1
    if k == 2:
        v = _hermite_value(g0, g1, d0, d1, h, x2)
        if v > best:
            best, arg = v, x2
    v = _hermite_value(g0, g1, d0, d1, h, h)
    if v > best:
        best, arg = v, h
    return best > 0.0, arg


# ------------------------------------------------------------ the exact local expansion
@njit(cache=True)
def _expand(T, z, W):
    """W_j = T_j z: the coefficients of z(t_k + s h) = sum_j s^j W_j."""
    J, n = T.shape[0], z.size
    for j in range(J):
        for i in range(n):
            acc = 0.0
            for k in range(n):
                acc += T[j, i, k] * z[k]
            W[j, i] = acc


@njit(cache=True)
def _guard_poly(W, R, j, c):
    """Ascending coefficients of guard j along the expansion."""
    for m in range(W.shape[0]):
        acc = 0.0
        for i in range(W.shape[1]):
            acc += R[j, i] * W[m, i]
        c[m] = acc


@njit(cache=True)
def _poly(c, h, tau):
    """Guard value and its first two time derivatives at tau (Horner in s = tau / h)."""
    x = tau / h
    p, dp, ddp = 0.0, 0.0, 0.0
    for m in range(c.size - 1, -1, -1):
        ddp = ddp * x + dp
        dp = dp * x + p
        p = p * x + c[m]
    return p, dp / h, 2.0 * ddp / (h * h)


@njit(cache=True)
def _state(W, h, tau, out):
    x = tau / h
    J, n = W.shape
    for i in range(n):
        acc = 0.0
        for m in range(J - 1, -1, -1):
            acc = acc * x + W[m, i]
        out[i] = acc


@njit(cache=True)
def _work_along(W, Q, h, tau, out):
    """out[p] = int_0^tau z^T Q_p z ds along the expansion: h sum_ij W_i.Q_p W_j x^(i+j+1)/(i+j+1)."""
    J, n = W.shape
    x = tau / h
    u = np.empty(2 * J - 1)
    xp = x
    for k in range(2 * J - 1):
        u[k] = xp / (k + 1)
        xp *= x
    QW = np.empty(n)
    for p in range(Q.shape[0]):
        total = 0.0
        for j in range(J):
            for i in range(n):
                acc = 0.0
                for k in range(n):
                    acc += Q[p, i, k] * W[j, k]
                QW[i] = acc
            for i in range(J):
                acc = 0.0
                for k in range(n):
                    acc += W[i, k] * QW[k]
                total += acc * u[i + j]
        out[p] = h * total


@njit(cache=True)
def _refine_min(c, h, tau, lo, hi):
    """Newton on the guard's derivative to the exact local minimum near tau in [lo, hi] (a shallow
    dip can hide from the cubic model); (tau, g) of the lowest value seen."""
    best_t, best_g = tau, np.inf
    for _ in range(8):
        g, d, dd = _poly(c, h, tau)
        if g < best_g:
            best_t, best_g = tau, g
        if g <= 0.0 or dd <= 0.0:
            break
        new = min(max(tau - d / dd, lo), hi)
        if abs(new - tau) <= 1e-15 * max(abs(tau), hi):
            break
        tau = new
    return best_t, best_g


@njit(cache=True)
def _first_root(c, h, a, b, ga, gb, span):
    """The first zero of the guard in (a, b] with g(a) > 0 >= g(b): the first sign change on eight
    sub-intervals brackets it, then safeguarded Newton to round-off of the step."""
    if gb == 0.0:
        return b
    lo, glo = a, ga
    for k in range(1, 8):
        s = a + (b - a) * k / 8.0
        v = _poly(c, h, s)[0]
        if v <= 0.0:
            b, gb = s, v
            break
        lo, glo = s, v
    a, ga = lo, glo
    if gb == 0.0:
        return b
    tau = a + (b - a) * ga / (ga - gb)
    prev = np.inf
    for it in range(60):
        g, d, _ = _poly(c, h, tau)
        if g == 0.0:
            break
        if g > 0.0:
            a = tau
        else:
            b = tau
        new = tau - g / d if d != 0.0 else 0.5 * (a + b)
        if not (a <= new <= b):
            new = 0.5 * (a + b)
        step = abs(new - tau)
        if step <= 4e-16 * span or b - a <= 4e-16 * span or (it >= 2 and step >= 0.5 * prev and step <= 1e-12 * span):
            tau = new
            break
        prev = step
        tau = new
    return tau


# ------------------------------------------------------------ one step, one piece
@njit(cache=True)
def _matvec(A, x, out):
    for i in range(A.shape[0]):
        acc = 0.0
        for k in range(x.size):
            acc += A[i, k] * x[k]
        out[i] = acc


@njit(cache=True)
def _quad(G, z):
    acc = 0.0
    for i in range(z.size):
        row = 0.0
        for k in range(z.size):
            row += G[i, k] * z[k]
        acc += z[i] * row
    return acc


@njit(cache=True)
def _step_events(R, T, ng, h, hh, z, gd0, gd1, first, W, have_W, c, cand_tau, cand_z):
    """Candidate events of one step of length hh from z: cand_tau[j] (inf: none) and the state
    cand_z[j] of every guard j.  Returns whether W holds the expansion about z."""
    for j in range(ng):
        cand_tau[j] = np.inf
        g0, g1, d0, d1 = gd0[j], gd1[j], gd0[ng + j], gd1[ng + j]
        a0, ga = 0.0, g0
        scale = abs(g0) + abs(g1) + hh * (abs(d0) + abs(d1)) + 1e-300
        b_end, gb, have_b = hh, g1, g1 <= 0.0
        if ga <= 1e-12 * scale:
            # starting on (or numerically just across) the boundary: admissible only if leaving it
            if not (first and d0 >= -1e-12 * scale / hh):
                cand_tau[j] = 0.0
                cand_z[j, :] = z
                continue
            found, tm = _hermite_argmax(g0, g1, d0, d1, hh)
            if not found:
                continue
            if not have_W:
                _expand(T, z, W)
                have_W = True
            _guard_poly(W, R, j, c)
            gm = _poly(c, h, tm)[0]
            if gm <= 0.0:
                cand_tau[j] = 0.0
                cand_z[j, :] = z
                continue
            a0, ga = tm, gm
            if g1 > 0.0:
                # a return within the rest of the step
                found, tmin = _hermite_min(g0, g1, d0, d1, hh, tm)
                if not found:
                    continue
                tmin, gmin = _refine_min(c, h, tmin, tm, hh)
                if gmin > 0.0:
                    continue
                tr = _first_root(c, h, a0, tmin, ga, gmin, tmin)
                cand_tau[j] = tr
                _state(W, h, tr, cand_z[j])
                continue
        # the FIRST crossing: a dip of the cubic before the step end (refined to the exact minimum)
        # takes precedence over a sign change at the end of the step
        found, tmin = _hermite_min(g0, g1, d0, d1, hh, a0)
        if found and tmin < hh * (1.0 - 1e-9):
            if _hermite_value(g0, g1, d0, d1, hh, tmin) < 0.05 * scale:
                if not have_W:
                    _expand(T, z, W)
                    have_W = True
                _guard_poly(W, R, j, c)
                tmin, gmin = _refine_min(c, h, tmin, a0, hh)
                if gmin <= 0.0 and tmin < hh * (1.0 - 1e-9):
                    b_end, gb, have_b = tmin, gmin, True
        if have_b:
            if not have_W:
                _expand(T, z, W)
                have_W = True
            _guard_poly(W, R, j, c)
            tr = _first_root(c, h, a0, b_end, ga, gb, b_end)
            cand_tau[j] = tr
            _state(W, h, tr, cand_z[j])
    return have_W


@njit(cache=True)
def advance(P, R, T, G, Q, ng, h, z0, t, t_end, first, dt_out, W_total, work, out_t, out_z, out_W, n0, z, hits,
            start):
    """March the piece from (t, z0) step by step, recording the step ends (and the output
    instants k dt_out inside the steps when dt_out > 0) in out_* from row ``n0`` on, until the first
    event (recorded too: the state reaching it), t_end or a full buffer; with ``start``, the state
    (t, z0) is recorded first (the state leaving the event before the piece).  ``work`` accumulates
    the work of each power category.  On return ``z`` holds the event's state (or the last step end)
    and ``hits`` which guards fire within round-off of the event instant.

    Returns (why, n, steps, t, W_total): the samples are rows n0 .. n - 1; t the event's instant (or
    the last step end)."""
    nz = z0.size
    nparts = Q.shape[0]
    z[:] = z0
    z1 = np.empty(nz)
    gd0 = np.empty(R.shape[0])
    gd1 = np.empty(R.shape[0])
    W = np.empty((T.shape[0], nz))
    c = np.empty(T.shape[0])
    cand_tau = np.empty(ng)
    cand_z = np.empty((ng, nz))
    w = np.empty(nparts)
    n, steps = n0, 0
    cap = out_t.size
    if start:
        out_t[n] = t
        out_z[n, :] = z0
        out_W[n] = W_total
        n += 1
    while True:
        hh = min(h, t_end - t)
        if hh <= 0.0:
            return END, n, steps, t, W_total
        if n >= cap - 1 or (dt_out > 0.0 and n + hh / dt_out + 3.0 >= cap):
            return FULL, n, steps, t, W_total
        have_W = False
        if hh == h:
            _matvec(P, z, z1)
        else:                      # the last, shorter step: along the expansion
            _expand(T, z, W)
            have_W = True
            _state(W, h, hh, z1)
        _matvec(R, z, gd0)
        _matvec(R, z1, gd1)
        steps += 1
        have_W = _step_events(R, T, ng, h, hh, z, gd0, gd1, first, W, have_W, c, cand_tau, cand_z)
        tev, jev = np.inf, -1
        for j in range(ng):
            if cand_tau[j] < tev:
                tev, jev = cand_tau[j], j
        tend = tev if jev >= 0 else hh
        if dt_out > 0.0:
            k = math.floor(t / dt_out) + 1
            while k * dt_out - t < tend:
                tau = k * dt_out - t
                k += 1
                if tau <= 0.0:
                    continue
                if not have_W:
                    _expand(T, z, W)
                    have_W = True
                _state(W, h, tau, out_z[n])
                _work_along(W, Q, h, tau, w)
                s = 0.0
                for p in range(nparts):
                    s += w[p]
                out_t[n] = t + tau
                out_W[n] = W_total + s
                n += 1
        if jev >= 0:
            if tev > 0.0:
                if not have_W:
                    _expand(T, z, W)
                _work_along(W, Q, h, tev, w)
                s = 0.0
                for p in range(nparts):
                    work[p] += w[p]
                    s += w[p]
                W_total += s
            tol = 1e-12 * max(abs(t), hh, 1e-300)
            for j in range(ng):
                hits[j] = cand_tau[j] <= tev + tol
            z[:] = cand_z[jev]
            out_t[n] = t + tev            # the state reaching the event, recorded too
            out_z[n, :] = z
            out_W[n] = W_total
            n += 1
            return EVENT, n, steps, t + tev, W_total
        s = 0.0
        if hh == h:
            for p in range(nparts):
                w[p] = _quad(G[p], z)
        else:
            _work_along(W, Q, h, hh, w)
        for p in range(nparts):
            work[p] += w[p]
            s += w[p]
        W_total += s
        t = t + hh
        z[:] = z1
        out_t[n] = t
        out_z[n, :] = z
        out_W[n] = W_total
        n += 1
        first = False
        if t >= t_end:
            return END, n, steps, t, W_total
