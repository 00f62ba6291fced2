"""Exact periodic orbits of a one-DOF oscillator with a piecewise-linear continuous restoring force, by
piecewise-analytic shooting -- an independent reference for harmonic balance on gaps, stops and bilinear
springs (folds, period doubling, symmetry-breaking branch points).

    m x'' + c x' + r(x) = F sin(w t + phi),   r(x) = k_i x - f_i  on region i = (b_{i-1}, b_i)

(``r`` continuous at the breakpoints b_i).  In a region the motion is the closed-form solution of a
linear oscillator: the periodic particular solution ``x_p = f_i / k_i + Im(F e^{i(w t + phi)} / Z_i)``,
``Z_i = k_i - m w^2 + i c w``, plus the free motion ``e^{A_i (t - t0)} (y0 - y_p(t0))`` (A_i by its
eigen-decomposition).  A crossing of a breakpoint is the root of the closed-form ``x(t) - b``, bracketed on
a grid of 1/200 of the shortest period involved and polished by Brent's method to 1e-15 relative.  The
vector field is continuous across a breakpoint (r continuous, c the same everywhere), so the saltation
matrices are the identity and the monodromy matrix is the ordered product of the regions' exponentials
``e^{A_i dt_i}`` -- exact, no finite differences.

Nothing here uses drivefem's solvers (no HB, no event-driven integrator, no continuation).

Branches are followed in the *phase parametrisation* (used by :func:`fold`, :func:`branch`): the time
origin is put at a turning point of the orbit (x(0) = A, x'(0) = 0) and the forcing phase ``phi`` is the
parameter; for each phi the unknowns (A, w) solve the two periodicity conditions.  Along a resonance curve
the phase increases monotonically, so w(phi) is single valued and a fold of the amplitude-frequency curve
is an extremum of w(phi) -- located as the root of det(Phi - I) (Phi the monodromy).  For a symmetric law
(r(-x) = -r(x)) a symmetric orbit (x(t + T/2) = -x(t)) is a fixed point of the half-period map
``G(y) = -P_{T/2}(y)``; its symmetry-breaking (pitchfork) branch point is where DG has the eigenvalue -1,
i.e. the half-period transition matrix Phi_h has the eigenvalue +1 (the full monodromy Phi = (-Phi_h)^2
has mu = +1 there without a fold: det(Phi_h - I) = 0 while det(Phi_h + I) != 0).
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import brentq


class PiecewiseLinearOscillator:
    """``m x'' + c x' + r(x) = F sin(w t + phi) + f0``; ``regions`` [(k_i, f_i)] from -inf upwards,
    separated by the increasing ``breaks`` (len(regions) - 1), r(x) = k_i x - f_i continuous."""

    def __init__(self, m, c, F, regions, breaks, f0=0.0):
        self.m, self.c, self.F, self.f0 = float(m), float(c), float(F), float(f0)
        self.k = np.array([r[0] for r in regions], float)
        self.f = np.array([r[1] for r in regions], float) + self.f0
        self.b = np.array(breaks, float)
        if len(self.b) != len(self.k) - 1:
            raise ValueError("one breakpoint between consecutive regions")
        for i, b in enumerate(self.b):
            left, right = self.k[i] * b - self.f[i], self.k[i + 1] * b - self.f[i + 1]
            if abs(left - right) > 1e-12 * max(abs(left), abs(right), 1.0):
                raise ValueError(f"r(x) is not continuous at x = {b}")
        self._eig = []
        for k in self.k:
            A = np.array([[0.0, 1.0], [-k / self.m, -self.c / self.m]])
            lam, V = np.linalg.eig(A.astype(complex))
            self._eig.append((lam, V, np.linalg.inv(V)))

    @classmethod
    def gap(cls, m, c, k, kc, delta, F):
        """Linear spring k plus a symmetric clearance +-delta with contact stiffness kc (two-sided stop)."""
        return cls(m, c, F, [(k + kc, -kc * delta), (k, 0.0), (k + kc, kc * delta)], [-delta, delta])

    @classmethod
    def one_sided(cls, m, c, k, kc, gap, F, f0=0.0):
        """Linear spring k plus a one-sided stop at x = gap of stiffness kc (bilinear oscillator)."""
        return cls(m, c, F, [(k, 0.0), (k + kc, kc * gap)], [gap], f0=f0)

    def region(self, x, v):
        """The region of a state (on a breakpoint: the side the velocity points to)."""
        i = int(np.searchsorted(self.b, x, side="right"))
        if i > 0 and x == self.b[i - 1] and v < 0:
            i -= 1
        return i

    def expA(self, i, tau):
        lam, V, Vi = self._eig[i]
        return (V @ np.diag(np.exp(lam * tau)) @ Vi).real

    def _particular(self, i, w, phi, t):
        """(x_p, v_p) of region i at times t."""
        Z = self.k[i] - self.m * w * w + 1j * self.c * w
        e = np.exp(1j * (w * np.asarray(t, float) + phi)) * self.F / Z
        return self.f[i] / self.k[i] + e.imag, (1j * w * e).imag

    def _x(self, i, w, phi, t0, d, t):
        """x(t) in region i after (t0, y(t0)) with d = y(t0) - y_p(t0)."""
        lam, V, Vi = self._eig[i]
        c = Vi @ d
        tau = np.asarray(t, float) - t0
        free = (V[0, 0] * c[0] * np.exp(lam[0] * tau) + V[0, 1] * c[1] * np.exp(lam[1] * tau)).real
        return self._particular(i, w, phi, t)[0] + free

    def flow(self, y0, w, phi, t_end, t0=0.0, record=False):
        """The state at ``t_end`` from y0 at t0, its transition matrix (product of exponentials), and with
        ``record`` the list of (t_start, t_stop, region) pieces."""
        y = np.array(y0, float)
        i = self.region(y[0], y[1])
        t = float(t0)
        Phi = np.eye(2)
        pieces = []
        shortest = min([2 * np.pi / w] + [2 * np.pi / abs(l.imag) for lam, _, _ in self._eig for l in lam if l.imag])
        h = shortest / 200
        while t < t_end:
            d = y - np.array(self._particular(i, w, phi, t))
            lo = self.b[i - 1] if i > 0 else -np.inf
            hi = self.b[i] if i < self.b.size else np.inf

            def g(s):           # >= 0 inside region i
                x = self._x(i, w, phi, t, d, s)
                return np.minimum(x - lo, hi - x)

            grid = np.append(np.arange(t, t_end, h), t_end)
            grid[0] = t + min(1e-9 * h, 0.5 * (t_end - t))
            vals = g(grid)
            out = np.flatnonzero(vals < 0)
            if out.size == 0:
                t_next, new = t_end, None
            else:
                j = out[0]
                a = grid[j - 1] if j > 0 else t
                t_next = brentq(g, a, grid[j], xtol=1e-300, rtol=1e-15, maxiter=200)
                new = True
            tau = t_next - t
            E = self.expA(i, tau)
            yp = np.array(self._particular(i, w, phi, t_next))
            y = yp + E @ d
            Phi = E @ Phi
            if record:
                pieces.append((t, t_next, i))
            if new:
                x_b = lo if abs(y[0] - lo) < abs(y[0] - hi) else hi
                y[0] = x_b
                i = i + 1 if x_b == hi else i - 1
            t = t_next
        return y, Phi, pieces

    # ------------------------------------------------------------ periodic orbits
    def period_map(self, y0, w, phi=0.0, nu=1):
        return self.flow(y0, w, phi, nu * 2 * np.pi / w)

    def periodic(self, y0, w, phi=0.0, nu=1, tol=1e-13, maxit=50):
        """Fixed point of the period map (Newton with the exact monodromy) and its multipliers.

        Converged when the step is below ``tol`` (relative), or when it has reached the round-off floor
        of the map: a step no smaller than the one before, below 1e-11 relative in each component
        (position and velocity scaled apart), and the closing error |P(y) - y| as small (near a fold
        Phi - I is ill-conditioned and the step alternates at ~cond * eps instead of falling below tol)."""
        y = np.array(y0, float)
        last = np.inf
        for _ in range(maxit):
            P, Phi, _ = self.period_map(y, w, phi, nu)
            dy = np.linalg.solve(Phi - np.eye(2), -(P - y))
            y = y + dy
            step = np.max(np.abs(dy)) / max(np.max(np.abs(y)), 1e-300)
            if step <= tol:
                P, Phi, _ = self.period_map(y, w, phi, nu)
                return y, np.linalg.eigvals(Phi)
            scale = np.maximum(np.abs(y), 1e-300)
            floor = np.max(np.abs(dy) / scale)
            if step >= last and floor <= 1e-11:
                P, Phi, _ = self.period_map(y, w, phi, nu)
                if np.max(np.abs(P - y) / scale) <= 1e-11:
                    return y, np.linalg.eigvals(Phi)
            last = step
        raise RuntimeError(f"no periodic orbit found at w = {w}")

    def phase_solution(self, phi, A0, w0, nu=1, symmetric=False, tol=1e-13, maxit=60):
        """(A, w) of the orbit through the turning point (A, 0) at t = 0 with forcing phase phi: Newton on
        the periodicity conditions (``symmetric``: the half-period map ``-P_{T/2}``)."""
        z = np.array([A0, w0], float)

        def res(z):
            A, w = z
            T = nu * 2 * np.pi / w
            if symmetric:
                y, Phi, _ = self.flow([A, 0.0], w, phi, 0.5 * T)
                return -y - np.array([A, 0.0]), -Phi
            y, Phi, _ = self.flow([A, 0.0], w, phi, T)
            return y - np.array([A, 0.0]), Phi

        for _ in range(maxit):
            r, Phi = res(z)
            hw = 1e-7 * z[1]
            rw = (res(z + [0, hw])[0] - res(z - [0, hw])[0]) / (2 * hw)
            J = np.column_stack([(Phi - np.eye(2))[:, 0], rw])
            dz = np.linalg.solve(J, -r)
            lam = min(1.0, 0.05 * z[1] / max(abs(dz[1]), 1e-300), 0.2 * abs(z[0]) / max(abs(dz[0]), 1e-300))
            z = z + lam * dz          # damped: the law's kinks make large steps unsafe
            if lam == 1.0 and abs(dz[0]) <= tol * abs(z[0]) and abs(dz[1]) <= tol * z[1]:
                return z
        raise RuntimeError(f"no orbit at phase {phi}")

    def monodromy(self, A, w, phi, nu=1, half=False):
        T = nu * 2 * np.pi / w
        return self.flow([A, 0.0], w, phi, 0.5 * T if half else T)[1]

    def branch(self, phis, A0, w0, nu=1, symmetric=False):
        """[(phi, A, w, multipliers)] along the phase parametrisation (continuation in phi)."""
        out, A, w = [], A0, w0
        for phi in phis:
            A, w = self.phase_solution(phi, A, w, nu, symmetric)
            mu = np.linalg.eigvals(self.monodromy(A, w, phi, nu))
            out.append((phi, A, w, mu))
        return out

    def locate(self, test, phi_a, phi_b, A0, w0, nu=1, symmetric=False):
        """The phase in [phi_a, phi_b] where ``test(Phi, Phi_half)`` changes sign on the branch, and (A, w)
        there: Brent's method on the phase, each value solved from the nearest solution."""
        state = {"z": (A0, w0)}

        def f(phi):
            A, w = self.phase_solution(phi, *state["z"], nu=nu, symmetric=symmetric)
            state["z"] = (A, w)
            return test(self.monodromy(A, w, phi, nu), self.monodromy(A, w, phi, nu, half=True) if symmetric else None)

        phi = brentq(f, phi_a, phi_b, xtol=1e-14, rtol=1e-15)
        A, w = self.phase_solution(phi, *state["z"], nu=nu, symmetric=symmetric)
        return phi, A, w


def det_minus_identity(Phi, _half=None):
    """Fold test: det(Phi - I) (a multiplier +1)."""
    return float(np.linalg.det(Phi - np.eye(2)))


def det_plus_identity(Phi, _half=None):
    """Period-doubling test: det(Phi + I) (a multiplier -1)."""
    return float(np.linalg.det(Phi + np.eye(2)))


def symmetry_breaking(_Phi, Phi_half):
    """Symmetry-breaking test of a symmetric orbit: det(Phi_h - I) (DG = -Phi_h has the eigenvalue -1)."""
    return float(np.linalg.det(Phi_half - np.eye(2)))


def continue_branch(osc, A0, phi0, w0, w_stop, nu=1, ds=0.01, ds_max=0.05, ds_min=1e-9, max_steps=20000,
                    symmetric=False, tol=1e-12):
    """Pseudo-arc-length continuation of the orbits through a turning point (A, 0), unknowns (A, phi, w)
    scaled by (A0, 1, w0), secant predictor, Newton corrector (Jacobian: the exact monodromy column and
    central differences in phi and w), step halved on failure; from (A0, phi0, w0) (a converged orbit)
    until w leaves [min(w0, w_stop), max(w0, w_stop)].  Returns arrays (A, phi, w, multipliers)."""
    sc = np.array([abs(A0), 1.0, abs(w0)])
    lo, hi = min(w0, w_stop), max(w0, w_stop)

    def res(u):
        A, phi, w = u * sc
        T = nu * 2 * np.pi / w
        if symmetric:
            y, Phi, _ = osc.flow([A, 0.0], w, phi, 0.5 * T)
            return (-y - [A, 0.0]) / [sc[0], sc[0] * w], -Phi
        y, Phi, _ = osc.flow([A, 0.0], w, phi, T)
        return (y - [A, 0.0]) / [sc[0], sc[0] * w], Phi

    def jac(u, Phi):
        w = u[2] * sc[2]
        J = np.empty((2, 3))
        J[:, 0] = (Phi - np.eye(2))[:, 0] * sc[0] / [sc[0], sc[0] * w]
        for j, h in ((1, 1e-7), (2, 1e-7)):
            e = np.zeros(3)
            e[j] = h
            J[:, j] = (res(u + e)[0] - res(u - e)[0]) / (2 * h)
        return J

    u = np.array([A0, phi0, w0]) / sc
    r, Phi = res(u)
    J = jac(u, Phi)
    t = np.linalg.svd(J)[2][-1]
    if t[2] * (w_stop - w0) < 0:
        t = -t
    pts = [(u * sc, np.linalg.eigvals(osc.monodromy(A0, w0, phi0, nu)))]
    h = ds
    for _ in range(max_steps):
        ok = False
        while h >= ds_min:
            up = u + h * t
            v = up.copy()
            try:
                for it in range(25):
                    r, Phi = res(v)
                    J = jac(v, Phi)
                    Jb = np.vstack([J, t])
                    dv = np.linalg.solve(Jb, -np.concatenate([r, [t @ (v - up)]]))
                    v = v + dv
                    if np.max(np.abs(dv)) < tol:
                        break
                else:
                    raise RuntimeError("no convergence")
                tn = np.linalg.svd(J)[2][-1]
                if tn @ t < 0:
                    tn = -tn
                if tn @ t < 0.95:
                    raise RuntimeError("turn")
                ok = True
                break
            except (RuntimeError, np.linalg.LinAlgError, ValueError):
                h *= 0.5
        if not ok:
            raise RuntimeError(f"continuation stalled at w = {u[2] * sc[2]}")
        u, t = v, tn
        A, phi, w = u * sc
        pts.append((u * sc, np.linalg.eigvals(osc.monodromy(A, w, phi, nu, half=False))))
        if not lo <= w <= hi:
            break
        if it <= 4:
            h = min(1.5 * h, ds_max)
    U = np.array([p[0] for p in pts])
    return U[:, 0], U[:, 1], U[:, 2], np.array([p[1] for p in pts])


def fixed_point(osc, y0, w, nu=1, symmetric=False, tol=1e-13, maxit=60):
    """The orbit at the fixed frequency w through y0's neighbourhood: Newton on P(y) = y (``symmetric``:
    on the half-period map -P_{T/2}(y) = y) with the exact transition matrix.  Returns (y, Phi, Phi_half):
    Phi the full-period monodromy, Phi_half the half-period one (None unless symmetric)."""
    y = np.array(y0, float)
    T = nu * 2 * np.pi / w
    for _ in range(maxit):
        if symmetric:
            P, Ph, _ = osc.flow(y, w, 0.0, 0.5 * T)
            r, J = -P - y, -Ph - np.eye(2)
        else:
            P, Phi, _ = osc.flow(y, w, 0.0, T)
            r, J = P - y, Phi - np.eye(2)
        dy = np.linalg.solve(J, -r)
        y = y + dy
        if np.max(np.abs(dy)) <= tol * max(np.max(np.abs(y)), 1e-300):
            break
    else:
        raise RuntimeError(f"no periodic orbit at w = {w}")
    if symmetric:
        _, Ph, _ = osc.flow(y, w, 0.0, 0.5 * T)
        return y, Ph @ Ph, Ph          # (-Ph)^2 = Ph^2 for the full period
    _, Phi, _ = osc.flow(y, w, 0.0, T)
    return y, Phi, None


def locate_in_omega(osc, test, wa, wb, y0, nu=1, symmetric=False):
    """The frequency in [wa, wb] where ``test(Phi, Phi_half)`` changes sign along orbits solved at fixed
    frequency (a branch without a fold in between), by Brent's method; returns (w, y, multipliers)."""
    state = {"y": np.array(y0, float)}

    def f(w):
        y, Phi, Ph = fixed_point(osc, state["y"], w, nu, symmetric)
        state["y"] = y
        return test(Phi, Ph)

    w = brentq(f, wa, wb, xtol=1e-13 * wb, rtol=1e-15)
    y, Phi, _ = fixed_point(osc, state["y"], w, nu, symmetric)
    return w, y, np.linalg.eigvals(Phi)


def fold_newton(osc, y0, w0, nu=1, tol=1e-12, maxit=30):
    """A fold of the periodic orbits: Newton on P(y; w) - y = 0, det(Phi(y; w) - I) = 0 in (y, w)
    (Jacobian by central differences; started from an approximation, e.g. an HB fold's state at t = 0).
    Returns (w, y)."""
    z = np.concatenate([np.asarray(y0, float), [float(w0)]])

    def G(z):
        y, w = z[:2], z[2]
        P, Phi, _ = osc.period_map(y, w, 0.0, nu)
        return np.concatenate([P - y, [np.linalg.det(Phi - np.eye(2))]])

    for _ in range(maxit):
        g = G(z)
        J = np.empty((3, 3))
        for j in range(3):
            h = 1e-7 * max(abs(z[j]), 1e-6 if j < 2 else 1.0)
            e = np.zeros(3)
            e[j] = h
            J[:, j] = (G(z + e) - G(z - e)) / (2 * h)
        dz = np.linalg.solve(J, -g)
        z = z + dz
        if abs(dz[2]) <= tol * abs(z[2]) and np.max(np.abs(dz[:2])) <= tol * max(np.max(np.abs(z[:2])), 1e-300):
            return float(z[2]), z[:2]
    raise RuntimeError(f"no fold near w = {w0}")


def dense(osc, y0, w, ts, phi=0.0):
    """x at the sorted instants ts (from 0) of the motion from y0 at t = 0: the pieces of one flow, each
    evaluated in closed form at the instants inside it."""
    ts = np.asarray(ts, float)
    _, _, pieces = osc.flow(y0, w, phi, float(ts[-1]), record=True)
    out = np.empty(ts.size)
    y = np.array(y0, float)
    for t0, t1, i in pieces:
        sel = (ts >= t0) & (ts <= t1)
        d = y - np.array(osc._particular(i, w, phi, t0))
        if np.any(sel):
            out[sel] = osc._x(i, w, phi, t0, d, ts[sel])
        E = osc.expA(i, t1 - t0)
        y = np.array(osc._particular(i, w, phi, t1)) + E @ d
    return out
