"""The piecewise-linear SDOF gear-pair oscillator with backlash (Kahraman & Singh, J. Sound Vib. 142 (1990)
49-75): exact periodic solutions, their Floquet multipliers and the jump frequencies.

Dimensionless dynamic transmission error x (time in 1/omega_n, x in units of the characteristic length):

    x'' + 2 zeta x' + f(x) = F_m + F_a cos(Omega t),
    f(x) = x - b (x > b),  0 (|x| <= b),  x + b (x < -b)        (2b: the total backlash)

In each region the equation is linear with constant coefficients, x'' + 2 zeta x' + a x = p + F_a cos(Omega t)
with (a, p) = (1, F_m + b) in drive-flank contact, (0, F_m) in the backlash, (1, F_m - b) in coast-flank
contact, and its solution from any state is closed form (homogeneous exponentials plus the particular
solution).  A periodic orbit that crosses the boundaries x = +-b at t_1 < ... < t_m < t_1 + T in a
known sequence of regions is found by matching the closed forms at the boundaries: unknowns the
crossing times and the velocity at t_1; equations x(t_{i+1}) = boundary for every segment and the
velocity after one period equal to v_1 -- m + 1 equations, solved by Newton (scipy.optimize.fsolve)
from a guess that an independent event-located integration (scipy solve_ivp, not the package) provides.
The force is continuous across the boundaries, so the monodromy matrix is the product of the segments'
exact state-transition matrices (no saltation): the exact Floquet multipliers.  A fold of the branch of
such orbits (a jump frequency) is where the Jacobian of the matching equations is singular: solved for
together with Omega.  A period doubling of the branch is where its smallest real multiplier passes
through -1: Brent's method on mu_min + 1 along the branch, each trial orbit continued from the last.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, fsolve


@dataclass(frozen=True)
class Oscillator:
    zeta: float = 0.05
    b: float = 1.0
    Fm: float = 0.1
    Fa: float = 0.1

    def region(self, x: float) -> int:
        return 1 if x > self.b else (-1 if x < -self.b else 0)

    def coefficients(self, r: int) -> tuple[float, float]:
        return {1: (1.0, self.Fm + self.b), 0: (0.0, self.Fm), -1: (1.0, self.Fm - self.b)}[r]

    def force(self, x):
        x = np.asarray(x, float)
        return np.where(x > self.b, x - self.b, np.where(x < -self.b, x + self.b, 0.0))

    # ------------------------------------------------------------------ closed form per region
    def particular(self, r: int, Om: float):
        """(c0, c1, X, Y): x_p(t) = c0 + c1 t + X cos(Om t) + Y sin(Om t) of region r."""
        a, p = self.coefficients(r)
        z = self.zeta
        A = np.array([[a - Om * Om, 2 * z * Om], [-2 * z * Om, a - Om * Om]])
        X, Y = np.linalg.solve(A, [self.Fa, 0.0])
        if a == 0:
            return 0.0, p / (2 * z), X, Y
        return p / a, 0.0, X, Y

    def homogeneous(self, r: int):
        """The two roots of s^2 + 2 zeta s + a (complex pair or real)."""
        a, _ = self.coefficients(r)
        return np.roots([1.0, 2 * self.zeta, a]).astype(complex)

    def propagate(self, r: int, Om: float, t0: float, x0: float, v0: float, t):
        """x(t), x'(t) in region r from (x0, v0) at t0 (closed form)."""
        c0, c1, X, Y = self.particular(r, Om)

        def xp(s):
            return c0 + c1 * s + X * np.cos(Om * s) + Y * np.sin(Om * s)

        def vp(s):
            return c1 - X * Om * np.sin(Om * s) + Y * Om * np.cos(Om * s)

        s1, s2 = self.homogeneous(r)
        dx, dv = x0 - xp(t0), v0 - vp(t0)
        # h(tau) = A e^{s1 tau} + B e^{s2 tau}, h(0) = dx, h'(0) = dv
        A_, B_ = np.linalg.solve(np.array([[1, 1], [s1, s2]]), np.array([dx, dv], complex))
        tau = np.asarray(t, float) - t0
        h = (A_ * np.exp(s1 * tau) + B_ * np.exp(s2 * tau)).real
        hd = (A_ * s1 * np.exp(s1 * tau) + B_ * s2 * np.exp(s2 * tau)).real
        return xp(t) + h, vp(t) + hd

    def transition(self, r: int, tau: float) -> np.ndarray:
        """State-transition matrix of the homogeneous part of region r over tau (for the multipliers)."""
        a, _ = self.coefficients(r)
        return sla.expm(np.array([[0.0, 1.0], [-a, -2 * self.zeta]]) * tau)

    # ------------------------------------------------------------------ reference integration (guess)
    def integrate(self, Om: float, x0: float, v0: float, periods: int, t0: float = 0.0, rtol: float = 1e-12,
                  steps: int = 50):
        """Event-located solve_ivp (DOP853, rtol 1e-12, at most T/steps per step) over ``periods`` forcing
        periods: (t, x, v) and the boundary crossings [(t, x, v)] (an independent route to a starting guess)."""
        b = self.b

        def rhs(t, y):
            return [y[1], -2 * self.zeta * y[1] - float(self.force(y[0])) + self.Fm + self.Fa * math.cos(Om * t)]

        def up(t, y):
            return y[0] - b

        def lo(t, y):
            return y[0] + b

        T = 2 * math.pi / Om
        sol = solve_ivp(rhs, (t0, t0 + periods * T), [x0, v0], method="DOP853", rtol=rtol, atol=1e-2 * rtol,
                        events=(up, lo), dense_output=True, max_step=T / steps)
        cross = sorted([(t, y[0], y[1]) for ev, ys in zip(sol.t_events, sol.y_events) for t, y in zip(ev, ys)])
        return sol, cross

    # ------------------------------------------------------------------ exact periodic orbit
    def linear_orbit(self, Om: float):
        """The orbit that stays in drive-flank contact (valid when its minimum exceeds b)."""
        c0, _, X, Y = self.particular(1, Om)
        return c0, math.hypot(X, Y)

    def residual(self, u, Om: float, pattern: list) -> np.ndarray:
        """Matching equations for crossings u = [t_1..t_m, v_1] with ``pattern`` [(boundary x_i, region after
        the crossing r_i)]."""
        m = len(pattern)
        ts, v1 = list(u[:m]), u[m]
        T = 2 * math.pi / Om
        ts.append(ts[0] + T)
        out = []
        v = v1
        for i in range(m):
            xb, r = pattern[i]
            xn, vn = self.propagate(r, Om, ts[i], xb, v, ts[i + 1])
            nxt = pattern[(i + 1) % m][0]
            out.append(float(xn) - nxt)
            v = float(vn)
        out.append(v - v1)
        return np.array(out)

    def solve_orbit(self, Om: float, guess: np.ndarray, pattern: list) -> np.ndarray:
        sol, info, ier, msg = fsolve(self.residual, guess, args=(Om, pattern), xtol=1e-14, full_output=True)
        if np.max(np.abs(self.residual(sol, Om, pattern))) > 1e-10:
            raise RuntimeError(f"exact orbit not converged at Omega = {Om}: {msg}")
        return sol

    def orbit_from_integration(self, Om: float, x0: float = None, v0: float = 0.0, periods: int = 400):
        """(pattern, u): the crossing pattern of the settled response and the exact orbit refined from it;
        (None, None) when the settled response never leaves contact."""
        x0 = self.b + self.Fm if x0 is None else x0
        sol, cross = self.integrate(Om, x0, v0, periods)
        T = 2 * math.pi / Om
        last = [c for c in cross if c[0] > sol.t[-1] - T]
        if not last:
            return None, None
        pattern = [(self.b if abs(x - self.b) < abs(x + self.b) else -self.b,
                    self.region_after(x, v)) for t, x, v in last]
        shift = math.floor(last[0][0] / T) * T            # times in [0, T) (forcing phase unchanged)
        u0 = np.array([c[0] - shift for c in last] + [last[0][2]])
        return pattern, self.solve_orbit(Om, u0, pattern)

    def continue_to(self, Om_from: float, u, pattern, Om_to: float, step: float = 0.005):
        """The orbit of the branch through (Om_from, u) at Om_to (natural continuation in small steps)."""
        n = max(1, int(math.ceil(abs(Om_to - Om_from) / step)))
        for Om in np.linspace(Om_from, Om_to, n + 1)[1:]:
            u = self.solve_orbit(Om, u, pattern)
        return u

    def region_after(self, xb: float, v: float) -> int:
        if xb > 0:
            return 1 if v > 0 else 0
        return -1 if v < 0 else 0

    def samples(self, Om: float, u, pattern, n: int = 4000):
        """(t, x, v) of the exact orbit on n points of one period from t_1."""
        m = len(pattern)
        T = 2 * math.pi / Om
        ts = list(u[:m]) + [u[0] + T]
        t = np.linspace(ts[0], ts[0] + T, n, endpoint=False)
        x, v = np.empty(n), np.empty(n)
        vi = u[m]
        for i in range(m):
            xb, r = pattern[i]
            sel = (t >= ts[i]) & (t < ts[i + 1])
            xs, vs = self.propagate(r, Om, ts[i], xb, vi, t[sel])
            x[sel], v[sel] = xs, vs
            vi = float(self.propagate(r, Om, ts[i], xb, vi, ts[i + 1])[1])
        return t, x, v

    def multipliers(self, Om: float, u, pattern) -> np.ndarray:
        """Exact Floquet multipliers: product of the segments' transition matrices (continuous force: no
        saltation)."""
        m = len(pattern)
        T = 2 * math.pi / Om
        ts = list(u[:m]) + [u[0] + T]
        P = np.eye(2)
        for i in range(m):
            P = self.transition(pattern[i][1], ts[i + 1] - ts[i]) @ P
        return np.linalg.eigvals(P)

    # ------------------------------------------------------------------ folds (jump frequencies)
    def at_duration(self, delta: float, guess, pattern) -> tuple[float, np.ndarray]:
        """The orbit of the branch whose first segment lasts ``delta`` (t_2 - t_1 = delta), with Omega as
        an unknown: (Omega, u).  Along the branch Omega(delta) is smooth through a fold, where it is extreme."""
        m = len(pattern)

        def eqs(z):
            t1, rest, v1, Om = z[0], z[1:m - 1], z[m - 1], z[m]
            u = np.concatenate([[t1, t1 + delta], rest, [v1]])
            return self.residual(u, Om, pattern)

        u, Om = guess
        z0 = np.concatenate([[u[0]], u[2:m], [u[m], Om]])
        z, info, ier, msg = fsolve(eqs, z0, xtol=1e-14, full_output=True)
        if np.max(np.abs(eqs(z))) > 1e-10:
            raise RuntimeError(f"orbit with first segment {delta} not converged: {msg}")
        u = np.concatenate([[z[0], z[0] + delta], z[1:m - 1], [z[m - 1]]])
        return float(z[m]), u

    def fold(self, Om0: float, u0, pattern, kind: str = "min", step: float = 2e-3) -> tuple[float, np.ndarray]:
        """The fold of the branch near (Om0, u0) where Omega is extreme (``kind`` "min" or "max") over the
        first segment's duration delta: delta is marched from u0's in relative steps ``step`` in the
        direction in which Omega decreases ("min") or increases ("max"), each orbit solved from the last,
        until Omega turns back; then bounded Brent minimisation on the last two steps (xatol 1e-13 delta)."""
        from scipy.optimize import minimize_scalar

        sgn = 1.0 if kind == "min" else -1.0
        d0 = u0[1] - u0[0]
        guess = (np.array(u0, float), Om0)
        Om_p, up = self.at_duration(d0 * (1 + step), guess, pattern)
        Om_m, um = self.at_duration(d0 * (1 - step), guess, pattern)
        direction = 1.0 if sgn * Om_p < sgn * Om_m else -1.0
        d, val, guess = d0, sgn * Om0, guess
        hist = [(d0, sgn * Om0, guess)]
        for _ in range(2000):
            d_new = d * (1 + direction * step)
            Om, u = self.at_duration(d_new, guess, pattern)
            guess = (u, Om)
            hist.append((d_new, sgn * Om, guess))
            if sgn * Om > val:
                break
            d, val = d_new, sgn * Om
        else:
            raise RuntimeError("no fold found along the branch")
        (da, _, ga), (db, _, _), (dc, _, _) = hist[-3], hist[-2], hist[-1]
        lo, hi = min(da, dc), max(da, dc)
        state = {"guess": hist[-2][2]}

        def f(delta):
            Om, u = self.at_duration(delta, state["guess"], pattern)
            state["guess"] = (u, Om)
            return sgn * Om

        res = minimize_scalar(f, bounds=(lo, hi), method="bounded", options={"xatol": 1e-13 * abs(db)})
        Om, u = self.at_duration(res.x, state["guess"], pattern)
        return Om, u

    def grazing_frequencies(self, lo: float, hi: float, n: int = 400) -> list[float]:
        """Frequencies where the contact orbit touches x = b (its minimum c0 - amplitude = b), in (lo, hi)."""
        def g(Om):
            c0, amp = self.linear_orbit(Om)
            return c0 - amp - self.b
        w = np.linspace(lo, hi, n)
        vals = [g(x) for x in w]
        out = []
        for i in range(n - 1):
            if vals[i] * vals[i + 1] < 0:
                out.append(brentq(g, w[i], w[i + 1], xtol=1e-15, rtol=1e-15))
        return out

    # ------------------------------------------------------------------ period doubling (flip)
    def impact_orbit_near_grazing(self, Om: float):
        """(pattern, u): the single-sided impact orbit just below a grazing frequency of the contact orbit,
        from the contact orbit's own crossings of x = b as the guess (drive flank -> backlash -> drive flank)."""
        c0, _, X, Y = self.particular(1, Om)
        R, ph = math.hypot(X, Y), math.atan2(Y, X)
        if R <= self.Fm:
            raise ValueError(f"the contact orbit at Omega = {Om} does not reach x = b")
        a = math.acos(-self.Fm / R)
        pattern = [(self.b, 0), (self.b, 1)]
        guess = np.array([(ph + a) / Om, (ph + 2 * math.pi - a) / Om, -R * Om * math.sin(a)])
        return pattern, self.solve_orbit(Om, guess, pattern)

    def consistent(self, Om: float, u, pattern, n: int = 4000) -> bool:
        """Whether the orbit stays in the regions its pattern assumes (no unaccounted crossing)."""
        m = len(pattern)
        T = 2 * math.pi / Om
        t, x, _ = self.samples(Om, u, pattern, n)
        ts = list(u[:m]) + [u[0] + T]
        tol = 1e-9 * self.b
        for i in range(m):
            sel = (t > ts[i]) & (t < ts[i + 1])
            r = pattern[i][1]
            xs = x[sel]
            if r == 1 and np.any(xs < self.b - tol) or r == -1 and np.any(xs > -self.b + tol) or \
                    r == 0 and np.any(np.abs(xs) > self.b + tol):
                return False
        return True

    def flip(self, Om_a: float, u_a, pattern, Om_b: float) -> tuple[float, np.ndarray, np.ndarray]:
        """(Omega, u, multipliers) of the period doubling between Om_a and Om_b on the branch through
        (Om_a, u_a): Brent's method (xtol 1e-14) on the smallest real multiplier + 1, each trial orbit
        continued from the last in steps of at most 1e-3; the multipliers must be real in the bracket."""
        state = {"Om": Om_a, "u": np.array(u_a, float)}

        def g(Om):
            u = self.continue_to(state["Om"], state["u"], pattern, Om, step=1e-3)
            state.update(Om=Om, u=u)
            mu = self.multipliers(Om, u, pattern)
            if np.max(np.abs(mu.imag)) > 0:
                raise RuntimeError(f"complex multipliers at Omega = {Om}: no flip bracket")
            return float(np.min(mu.real)) + 1.0

        Om = brentq(g, Om_a, Om_b, xtol=1e-14, rtol=1e-15)
        u = self.continue_to(state["Om"], state["u"], pattern, Om, step=1e-3)
        if not self.consistent(Om, u, pattern):
            raise RuntimeError(f"the orbit at the flip Omega = {Om} leaves its crossing pattern")
        return Om, u, self.multipliers(Om, u, pattern)
