"""Moreau-Jean time stepping for many friction and impact elements on any :class:`LinearSystem`.

Scheme (theta-method on velocities, impulses instead of forces; Jean 1999, Acary & Brogliato 2008):

    M (v1 - v0) = h (f_theta - C v_theta - K q_theta) + sum_i g_i p_i
    q1 = q0 + h v_theta,  v_theta = (1 - theta) v0 + theta v1,  q_theta = q0 + h theta v_theta

so that ``Mh (v1 - v0) = h (f_theta - C v0 - K (q0 + h theta v0)) + G p`` with the iteration
matrix ``Mh = M + h theta C + h^2 theta^2 K`` (sparse, factorised once).  The element impulses
``p_i`` over the step solve the one-step contact problem on the local velocities
``u = G^T v1 = u_free + D p`` (``D = G^T Mh^-1 G``, the Delassus matrix):

* friction (Coulomb, kinetic level F_k, static F_s, moving counter-surface): ``-p_i in h F Sign(u_i - w_i)``
  with ``F = F_s`` for an element at rest at the start of the step, else ``F_k``; the velocity-
  dependent part of the slip law (viscous, quadratic, cubic terms) is explicit;
* impact (unilateral stop s >= s_min, Newton restitution e): for an element whose predicted
  position ``s0 + h/2 s0'`` is at or beyond the stop, ``p_i >= 0`` complementary to
  ``u_i + e u_i(t0) >= 0``.

* one-sided springs and gaps (exact law): the impulse ``h F(s_theta)`` of the piecewise-linear
  force at the theta-point position ``s_theta = s0 + h theta ((1 - theta) u0 + theta u1)``, solved
  exactly on its branch (implicit, so stiff stops do not limit the step); their potential energy
  is part of E.

The local problem is solved by projected Gauss-Seidel (block-free, exact for one element),
iterated to ``tol`` relative to the largest impulse bound.

With ``theta = 1/2`` the linear part is energy-conserving (midpoint rule), so the balance
``E1 - E0 = h v_mid . (f - C v_mid) + p . u_mid + driver work`` closes to round-off in the
absence of impacts; impacts with e < 1 dissipate, which the balance counts in the contact work.
``theta > 1/2`` adds numerical damping of the high frequencies (reported in the energy error).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .. import checks
from ..errors import ModelError, SolverError
from ..linear_system import LinearSystem
from ..nonsmooth.problem import ExternalForce, MotionLaw
from ..nonsmooth.result import Event, TimeHistory


@dataclass
class StepOptions:
    dt: float
    theta: float = 0.5
    tol: float = 1e-10          # PGS convergence, relative to the largest impulse bound
    max_iter: int = 2000
    sample_every: int = 1       # store every n-th step
    events: bool = True         # record stick/slip/impact events
    max_events: int = 100_000
    progress: object = None     # called with the time reached every 1000 steps (a progress bar of the caller's)

    def __post_init__(self):
        """The [simulation] keys' rules of the model file (method = "moreau")."""
        w = "[simulation]"
        self.dt = checks.positive(w, "dt", self.dt, "time step, s")
        self.theta = checks.bounded(w, "theta", self.theta, (">=", 0.5), ("<=", 1.0),
                                    "theta of the theta-method, 0.5: energy-conserving midpoint")
        self.tol = checks.positive(w, "tol", self.tol, "tolerance of the contact/friction projections")
        self.max_iter = checks.integer(w, "max_iter", self.max_iter, 1, "iteration limit of the projections")
        self.sample_every = checks.integer(w, "sample_every", self.sample_every, 1, "store every n-th step")
        if not isinstance(self.events, (bool, np.bool_)):
            raise ModelError(w, "events", self.events, "true | false")
        self.max_events = checks.integer(w, "max_events", self.max_events, 1, "event limit")
        if self.progress is not None and not callable(self.progress):
            raise ModelError(w, "progress", self.progress, "None or a callable taking the time reached")


@dataclass
class SteppingResult(TimeHistory):
    """Result of the Moreau-Jean scheme: :class:`~discrete.nonsmooth.result.TimeHistory` plus the
    projected Gauss-Seidel statistics (``element_forces``: the mean force impulse / dt of each step)."""

    n_steps: int
    pgs_iterations_max: int
    pgs_unconverged: int
    method: str = field(default="moreau-jean", kw_only=True)

    def _solver_dict(self) -> dict:
        return {"n_steps": self.n_steps, "pgs_iterations_max": self.pgs_iterations_max,
                "pgs_unconverged": self.pgs_unconverged}


def _motion(law: MotionLaw, t: float):
    """Position, velocity, acceleration of a prescribed motion."""
    w = law.omega
    x = law.offset + law.velocity * t + law.amplitude * np.sin(w * t + law.phase)
    v = law.velocity + law.amplitude * w * np.cos(w * t + law.phase)
    a = -law.amplitude * w * w * np.sin(w * t + law.phase)
    return x, v, a


def _force_value(F: ExternalForce, t: float) -> float:
    return F.value + F.amplitude * np.sin(F.omega * t + F.phase)


def simulate_timestepping(system: LinearSystem, elements=(), drivers: dict | None = None, forces=(),
                          x0=None, v0=None, t_end: float = 1.0, options: StepOptions | None = None,
                          t0: float = 0.0) -> SteppingResult:
    """Integrate ``system`` with friction/impact ``elements`` by the Moreau-Jean scheme."""
    if not isinstance(options, StepOptions):
        raise ModelError("simulate_timestepping", "options", options, "StepOptions(dt=...) with a time step > 0")
    if not isinstance(system, LinearSystem):
        raise ModelError("simulate_timestepping", "system", type(system).__name__,
                         "a discrete.linear_system.LinearSystem")
    o = options
    if not (o.dt > 0 and np.isfinite(o.dt)):
        raise ModelError("[simulation]", "dt", o.dt, "a time step > 0")
    if not 0.5 <= o.theta <= 1.0:
        raise ModelError("[simulation]", "theta", o.theta, "a number in [0.5, 1] (0.5: energy-conserving midpoint)")
    t0 = checks.finite("simulate_timestepping", "t0", t0, "start time, s")
    t_end = checks.bounded("[simulation]", "t_end", t_end, (">", t0), note="end time, s")
    n = system.n_dofs
    f, c = system.free, system.constrained
    if drivers is not None and not isinstance(drivers, dict):
        raise ModelError("simulate_timestepping", "drivers", type(drivers).__name__,
                         "a dict {constrained DOF index: MotionLaw}")
    for j, law in (drivers or {}).items():
        checks.index("simulate_timestepping", "drivers", j, n)
        if j not in set(c.tolist()):
            raise ModelError("simulate_timestepping", "drivers", j, "the index of a constrained DOF (drivers move "
                             f"the constrained DOFs of the system: {c.tolist()})")
        if not isinstance(law, MotionLaw):
            raise ModelError("simulate_timestepping", "drivers", type(law).__name__, "a MotionLaw per driven DOF")
    for i, F in enumerate(forces):
        if not isinstance(F, ExternalForce) or F.g.shape != (n,):
            raise ModelError(f"force #{i + 1}", "g", getattr(getattr(F, "g", None), "shape", F),
                             f"an ExternalForce with a vector of {n} DOF coefficients")
    elements = list(elements)
    for el in elements:
        el.g = checks.vector(f"element {getattr(el, 'name', '?')!r}", "g", el.g, n,
                             "the element's coordinate s = g . x")
    x0 = None if x0 is None else checks.vector("simulate_timestepping", "x0", x0, n, "initial positions of all DOFs")
    v0 = None if v0 is None else checks.vector("simulate_timestepping", "v0", v0, n, "initial velocities of all DOFs")
    drivers = dict(drivers or {})
    for j in c:
        drivers.setdefault(int(j), MotionLaw())
    elements = list(elements)
    M = system.M.tocsr()
    K = system.K.tocsr()
    C = system.C.tocsr()
    Mff, Kff, Cff = M[f][:, f], K[f][:, f], C[f][:, f]
    Kfc, Cfc, Mfc = K[f][:, c], C[f][:, c], M[f][:, c]
    # the step is shortened slightly so that an integer number of steps ends exactly at t_end
    n_steps = int(np.ceil((t_end - t0) / float(o.dt) - 1e-9))
    h, th = (t_end - t0) / n_steps, float(o.theta)
    laws = [el.moreau(h, th) for el in elements]      # each element's law of one step
    Mh = sp.csc_matrix(Mff + h * th * Cff + (h * th) ** 2 * Kff)
    lu = spla.splu(Mh)
    nel = len(elements)
    G = np.array([np.asarray(el.g, float) for el in elements]).reshape(nel, n)
    Gf, Gc = G[:, f], G[:, c]
    W = lu.solve(np.ascontiguousarray(Gf.T)) if nel else np.zeros((f.size, 0))   # Mh^-1 G
    D = Gf @ W if nel else np.zeros((0, 0))
    Dd = np.diag(D).copy() if nel else np.zeros(0)
    if nel and np.any(Dd <= 0):
        bad = int(np.flatnonzero(Dd <= 0)[0])
        raise ModelError(f"element {elements[bad].name!r}", "g", "acts on constrained DOFs only",
                         "an element acting on at least one free DOF")
    motions = [drivers[int(j)] for j in c]

    def drv(t):
        if c.size == 0:
            return np.zeros(0), np.zeros(0), np.zeros(0)
        a = np.array([_motion(l, t) for l in motions])
        return a[:, 0], a[:, 1], a[:, 2]

    Fg = [np.asarray(F.g, float)[f] for F in forces]

    def fext(t):
        out = np.zeros(f.size)
        for F, gf in zip(forces, Fg):
            out += gf * _force_value(F, t)
        return out

    x0 = np.zeros(n) if x0 is None else np.asarray(x0, float)
    v0 = np.zeros(n) if v0 is None else np.asarray(v0, float)
    q, v = x0[f].copy(), v0[f].copy()
    conservative = np.array([law.conservative for law in laws], dtype=bool)
    explicit = [i for i, law in enumerate(laws) if law.has_explicit]
    names = [str(system.dof_name[i]) if system.dof_name[i] else system.label(i) for i in range(n)]

    def full(qq, vv, t):
        xc, vc, _ = drv(t)
        X = np.zeros(n)
        V = np.zeros(n)
        X[f], V[f] = qq, vv
        X[c], V[c] = xc, vc
        return X, V

    def energy(X, V):
        E = 0.5 * V[f] @ (Mff @ V[f]) + 0.5 * X @ (K @ X)
        if conservative.any():
            s_ = G[conservative] @ X
            E += 0.5 * np.sum([laws[i].energy_term(si) for i, si in zip(np.flatnonzero(conservative), s_)])
        return E

    ts, xs, vs, Es, Ws, Ps = [], [], [], [], [], []
    t = t0
    X, V = full(q, v, t)
    E0 = energy(X, V)
    Wacc = 0.0
    ts.append(t); xs.append(X); vs.append(V); Es.append(E0); Ws.append(0.0); Ps.append(np.zeros(nel))
    if nel:
        u0 = G @ V
        for law, ui in zip(laws, u0):
            law.start(ui, max(1.0, np.max(np.abs(V))))
    events: list[Event] = []
    it_max, unconv = 0, 0
    p = np.zeros(nel)
    warn: list[str] = []
    interrupted = None
    try:
        for k in range(1, n_steps + 1):
            t1 = t0 + k * h
            tth = t + th * h
            xc0, vc0, ac0 = drv(t)
            xc1, vc1, ac1 = drv(t1)
            xcth, vcth, acth = drv(tth)
            rhs = fext(tth) - Kfc @ xcth - Cfc @ vcth - Mfc @ acth if c.size else fext(tth)
            rhs = rhs - Cff @ v - Kff @ (q + h * th * v)
            if explicit:
                Vc = np.zeros(n); Vc[f] = v; Vc[c] = vc0
                for i in explicit:
                    g = elements[i].g
                    rhs += g[f] * laws[i].explicit_force(g @ Vc)
            vfree = v + lu.solve(h * rhs)
            if nel:
                ufree = Gf @ vfree + Gc @ vc1
                X0 = np.zeros(n); X0[f] = q; X0[c] = xc0
                V0 = np.zeros(n); V0[f] = v; V0[c] = vc0
                s0, u_prev = G @ X0, G @ V0
                for law, si, ui in zip(laws, s0, u_prev):
                    law.begin(si, ui)
                active = np.array([law.active for law in laws], dtype=bool)
                bound = np.array([law.bound for law in laws])
                p = np.where(active, p, 0.0)
                scale = max(float(np.max(bound)) if bound.size else 0.0,
                            float(np.max(np.abs(D @ np.ones(nel)))) * 1e-300, 1e-300)
                u = ufree + D @ p
                converged = False
                it = 0
                for _pass in range(2):
                  for it in range(it + 1, o.max_iter + 1):
                      dmax = 0.0
                      for i in range(nel):
                          if not active[i]:
                              continue
                          new = laws[i].project(u[i], Dd[i], p[i])
                          dp = new - p[i]
                          if dp != 0.0:
                              u += D[:, i] * dp
                              p[i] = new
                              dmax = max(dmax, abs(dp))
                      ref = max(scale, float(np.max(np.abs(p))) if p.size else 0.0)
                      if dmax <= o.tol * ref:
                          converged = True
                          break
                  # a law may need the step again (friction breaking away within it: the kinetic level)
                  if not any([law.retry(pi) for law, pi in zip(laws, p)]):
                      break
                  p = np.array([law.retry_clip(pi) for law, pi in zip(laws, p)])
                  u = ufree + D @ p
                  converged = False
                it_max = max(it_max, it)
                if not converged:
                    unconv += 1
                v1 = vfree + W @ p
            else:
                v1 = vfree
            vth = (1 - th) * v + th * v1
            q1 = q + h * vth
            # work of the non-conservative forces over the step (midpoint velocities)
            vm = 0.5 * (v + v1)
            dW = h * vm @ (fext(tth) - Cff @ vm)
            if c.size:
                Xm = np.zeros(n); Xm[f] = 0.5 * (q + q1); Xm[c] = xcth
                dW += h * (vcth @ (K[c] @ Xm) - vm @ (Cfc @ vcth + Mfc @ acth))
            if nel:
                um = 0.5 * (G[:, f] @ (v + v1)) + Gc @ vcth
                dW += p[~conservative] @ um[~conservative]      # conservative laws: their energy is in E
                for i in explicit:
                    g = elements[i].g
                    dW += h * laws[i].explicit_force(0.5 * (g[f] @ (v + v1)) + g[c] @ vcth) * (0.5 * (g[f] @ (v + v1)))
            Wacc += dW
            q, v, t = q1, v1, t1
            if nel:
                happened = sorted((rank, i, kind) for i, (law, pi) in enumerate(zip(laws, p)) for rank, kind in law.finish(pi))
                if o.events and len(events) < o.max_events:
                    events += [Event(t=t, kind=kind, element=elements[i].name, state={}) for _, i, kind in happened]
            if k % o.sample_every == 0 or k == n_steps:
                X, V = full(q, v, t)
                ts.append(t); xs.append(X); vs.append(V); Es.append(energy(X, V)); Ws.append(Wacc)
                Ps.append(p / h if nel else np.zeros(0))
            if not np.all(np.isfinite(v)):
                raise SolverError(f"Moreau-Jean: non-finite velocities at t = {t!r} (dt = {h!r})")
            if o.progress is not None and k % 1000 == 0:
                o.progress(t)
    except KeyboardInterrupt:
        n = min(len(ts), len(xs), len(vs), len(Es), len(Ws), len(Ps))
        del ts[n:], xs[n:], vs[n:], Es[n:], Ws[n:], Ps[n:]
        interrupted = f"interrupted (Ctrl-C) at t = {ts[-1]!r}: the results up to there are kept"
    if unconv:
        warn.append(f"projected Gauss-Seidel did not reach tol = {o.tol:g} in {unconv} step(s) "
                    f"(max_iter = {o.max_iter})")
    if len(events) >= o.max_events:
        warn.append(f"event recording stopped at max_events = {o.max_events}")
    E = np.array(Es)
    Wt = np.array(Ws)
    scale = max(np.max(np.abs(E)), np.max(np.abs(Wt)), 1e-300)
    err = float(np.max(np.abs(E - E[0] - Wt)) / scale)
    res = SteppingResult(t=np.array(ts), x=np.array(xs).T, v=np.array(vs).T, names=names, events=events,
                         t_end=float(t_end), energy=E, work=Wt, energy_error=err, n_steps=n_steps,
                         pgs_iterations_max=it_max, pgs_unconverged=unconv, warnings=warn,
                         element_forces=np.array(Ps).T if nel else None,    # impulse / dt of each step
                         elements=[f"{el.kind}:{el.name}" for el in elements], driven=[names[j] for j in c],
                         stopped_early=interrupted is not None, reason=interrupted or "")
    # periodic regime: upward velocity crossings of every moving DOF agree over the last 3 cycles
    from ..nonsmooth.periodic import detect_period_smooth

    per = detect_period_smooth(res)
    if per is not None:
        res.period = per["period"]
    return res
