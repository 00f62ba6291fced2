"""Shooting on periodic orbits with the exact event-driven integrator, and Floquet multipliers.

The period map ``P(y; w)`` (y = [q, v] of the free DOFs at t = 0, period ``T = nu 2 pi / w``) is one
call of :func:`discrete.nonsmooth.simulate` started from y (the Problem's public initial state
``q0, v0``; the initial mode is chosen by the solver from the state, as in any simulation).  A
periodic orbit solves ``P(y) - y = 0`` (Newton / arc-length continuation).

Monodromy: the Jacobian ``dP/dy`` by central finite differences of the exact period map.  The
map is piecewise smooth; away from grazing it is differentiable and the difference quotient equals
the monodromy matrix *with* the saltation matrices of the events (they are part of the flow map's
derivative).  Verified in ``tests/test_steady_shooting.py`` against expm(A T) for a linear system,
and against the closed-form saltation product of a one-sided (bilinear) oscillator.  The step is
``h = 1e-6`` of the state's scale (truncation ~h^2, round-off ~1e-16/h: ~1e-10 relative).
Floquet multipliers are its eigenvalues; stable if all |mu| < 1 + 1e-6.

Section: the map starts at the forcing phase ``phase`` (t0 = phase / w, default 0) and runs one period,
y = [q, v](t0).  An event of the orbit exactly at the section (e.g. a slip reversal at t0) makes the map's
Jacobian jump there (the saltation matrix moves from the end of the period to its start), so the fixed
point's branch y(w) has a kink and the continuation cannot pass it; the same orbit on a section between
its events is smooth there (:func:`section_phase`, :meth:`ShootingModel.transfer`).

Cost: every map at one frequency reuses one solver and so its exact pieces (built once per mode),
and the Problems of the few most recent frequencies are kept; a period map then costs its events.
"""
from __future__ import annotations

import numpy as np

from ..errors import SolverError
from ..nonsmooth import Options, simulate
from ..nonsmooth.solver import EventDrivenSolver

# the solver's per-run reset used by ShootingModel._solver (private API of discrete.nonsmooth.solver);
# without it every period map builds a fresh solver (same results, slower)
_REUSABLE = hasattr(EventDrivenSolver, "_contact_force_tolerances")


class ShootingModel:
    """Period map of ``factory(omega) -> Problem`` (the Problem built with forcing frequency omega)."""

    def __init__(self, factory, nu: int = 1, steps_per_period: int = 48, output_points: int = 2000,
                 options: dict | None = None, keep: int = 4, reuse: bool = True):
        self.factory = factory
        self.nu = int(nu)
        self.steps = int(steps_per_period)
        self.output_points = int(output_points)
        self._problems: dict = {}           # omega -> Problem (the ``keep`` most recent)
        self._solvers: dict = {}            # (omega, dense) -> solver: its cache of exact pieces is reused
        self.keep = max(1, int(keep))
        self.reuse = bool(reuse) and _REUSABLE     # False: a fresh solver per period map (the old cost)
        self.n_sims = 0
        self.options = dict(options or {})
        p = self.problem(1.0)
        self.n = 2 * p.nf

    def problem(self, omega):
        p = self._problems.pop(omega, None)
        if p is None:
            p = self.factory(omega)
            if len(self._problems) >= self.keep:
                old = next(iter(self._problems))
                del self._problems[old]
                for key in [k for k in self._solvers if k[0] == old]:
                    del self._solvers[key]
        self._problems[omega] = p            # most recent last
        return p

    def _solver(self, p, omega, dense, options):
        """The event-driven solver of the Problem at ``omega``, kept between period maps: every map at
        this frequency reuses its exact pieces (matrix exponentials, guard rows, work matrices --
        functions of the mode only), which is most of the cost of a one-period run.  What depends on
        the initial state is reset per run (the persistent-contact force tolerances scale with v0)."""
        key = (omega, dense)
        sol = self._solvers.get(key)
        if sol is None or sol.p is not p:
            sol = self._solvers[key] = EventDrivenSolver(p, Options(**options))
        else:
            sol.warnings = []
            sol._contact_ftol = sol._contact_force_tolerances()
        return sol

    def period(self, omega):
        return self.nu * 2 * np.pi / omega

    def run(self, y, omega, dense=False, periods=1, phase=0.0):
        p = self.problem(omega)
        T = self.period(omega)
        t0 = phase / omega
        nf = p.nf
        p.q0, p.v0 = np.array(y[:nf], float), np.array(y[nf:], float)
        kw = dict(energy=False, max_step=T / self.steps)
        kw.update(self.options)
        if dense:      # output inside exact pieces, and a step limit for numerically integrated pieces
            kw["output_step"] = T / self.output_points
            kw["max_step"] = min(kw["max_step"], T / self.output_points)
        if self.reuse:
            res = self._solver(p, omega, dense, kw).run(t0 + periods * T, t0)
        else:
            res = simulate(p, t0 + periods * T, Options(**kw), t0=t0)
        self.n_sims += 1
        if res.stopped_early:
            raise SolverError(f"period map at omega = {omega!r}: {res.reason}")
        yend = np.concatenate([res.x[p.f, -1], res.v[p.f, -1]])
        return yend, res

    def map(self, y, omega, phase=0.0):
        return self.run(y, omega, phase=phase)[0]

    def transfer(self, y, omega, phase_from, phase_to):
        """The state at the section ``phase_to`` of the orbit through y at the section ``phase_from``
        (integrated forward by less than one period)."""
        p = self.problem(omega)
        full = self.nu * 2 * np.pi
        dphi = (phase_to - phase_from) % full
        if dphi == 0.0:
            return np.array(y, float)
        t0 = phase_from / omega
        p.q0, p.v0 = np.array(y[:p.nf], float), np.array(y[p.nf:], float)
        kw = dict(energy=False, max_step=self.period(omega) / self.steps)
        kw.update(self.options)
        res = simulate(p, t0 + dphi / omega, Options(**kw), t0=t0)
        self.n_sims += 1
        if res.stopped_early:
            raise SolverError(f"section transfer at omega = {omega!r}: {res.reason}")
        return np.concatenate([res.x[p.f, -1], res.v[p.f, -1]])

    def jacobian(self, y, omega, scale, central=False, phase=0.0):
        n = y.size
        J = np.zeros((n, n))
        P0 = None if central else self.map(y, omega, phase)
        for j in range(n):
            h = 1e-6 * scale[j]
            e = np.zeros(n)
            e[j] = h
            if central:
                J[:, j] = (self.map(y + e, omega, phase) - self.map(y - e, omega, phase)) / (2 * h)
            else:
                J[:, j] = (self.map(y + e, omega, phase) - P0) / h
        return J, P0

    def fun(self, scale, phase=0.0):
        """Residual for :func:`~discrete.steady.continuation.arclength` (section at ``phase``)."""

        def f(y, w, need_w=True):
            J, P0 = self.jacobian(y, w, scale, phase=phase)
            R = P0 - y
            Jx = J - np.eye(y.size)
            Jw = None
            if need_w:
                hw = 1e-7 * w
                Jw = (self.map(y, w + hw, phase) - P0) / hw
            return R, Jx, Jw

        return f

    def floquet(self, y, omega, scale, phase=0.0):
        J, _ = self.jacobian(y, omega, scale, central=True, phase=phase)
        return np.linalg.eigvals(J)

    def solve(self, y0, omega, scale, tol=1e-10, maxit=30):
        y = np.array(y0, float)
        for it in range(1, maxit + 1):
            J, P0 = self.jacobian(y, omega, scale)
            R = P0 - y
            dy = np.linalg.solve(J - np.eye(y.size), -R)
            y = y + dy
            if np.max(np.abs(dy / scale)) <= tol:
                return y, it
        raise SolverError(f"shooting did not converge at omega = {omega!r} in {maxit} iterations")

    def settle(self, y0, omega, periods=200, tol=1e-9, scale=None):
        """Time integration to the steady state (the brute-force method): whole periods until the
        change over one period is below ``tol`` (relative to ``scale``) or ``periods`` are spent."""
        y = np.array(y0, float)
        sc = np.ones_like(y) if scale is None else scale
        for k in range(1, periods + 1):
            yn = self.map(y, omega)
            d = np.max(np.abs(yn - y) / sc)
            y = yn
            if d <= tol:
                return y, k, True
        return y, periods, False


def section_phase(res, omega, nu: int = 1) -> tuple[float, float]:
    """(phase, clearance): the forcing phase in [0, nu 2 pi) farthest from every event of the simulated
    orbit ``res`` (the middle of the largest gap between the events' phases), and its distance (rad) to
    the nearest event; (0, inf) for an orbit without events."""
    full = nu * 2 * np.pi
    ph = np.sort(np.mod(omega * np.array([e.t for e in res.events], float), full))
    if ph.size == 0:
        return 0.0, float("inf")
    gaps = np.diff(np.concatenate([ph, [ph[0] + full]]))
    k = int(np.argmax(gaps))
    return float(np.mod(ph[k] + 0.5 * gaps[k], full)), float(0.5 * gaps[k])
