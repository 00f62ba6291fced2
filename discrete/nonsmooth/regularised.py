"""Regularised / penalty alternative (for comparison and benchmarks; not exact).

Friction:  F = -(F_k + (F_s - F_k) zeta) tanh(w / eps) - viscous w - ...  with the slip velocity
w and a *rest memory* zeta in [0, 1]:
  - restick = "static": zeta = r (memoryless; the static peak is available at every stop, the
    classic rule);
  - restick = "kinetic" (seed 000): zeta' = r (1 - zeta)/tau - (1 - r) zeta/tau_f with
    r = 1/(1 + (w/eps_m)^8) (a sharp rest window, insensitive to the creep |w| <~ 4 eps of a
    regularised stick): the static peak builds up only after a rest longer than ``memory_time``
    tau and is lost within tau_f = tau/100 once slipping; a momentary stop (|w| < eps_m for much
    less than tau) sees F_k and the velocity reverses, as in the exact model.
  ``eps`` = ``regularisation`` (a velocity), eps_m = 20 eps, tau = ``memory_time``.
Impacts: penalty spring-dashpot of stiffness ``penalty`` with the damping ratio that gives the
restitution coefficient of a linear contact, e = exp(-pi z / sqrt(1 - z^2)).
One-sided springs and exact gaps keep their piecewise-linear (continuous) force laws.
Integrated by ``scipy.integrate.solve_ivp`` (LSODA by default) with no events.
"""
from __future__ import annotations

import math

import numpy as np

from .problem import Problem
from .result import SimulationResult


def regularised_rhs(prob: Problem, regularisation: float, penalty: float | None, memory_time: float):
    """Right-hand side f(t, y) of the regularised model, y = [q, v, memory states of the elements]
    (the elements with memory -- friction's rest memory -- come first, as their states)."""
    nf = prob.nf
    order = sorted(range(len(prob.elements)), key=lambda i: prob.elements[i].n_memory == 0)
    slots, k = {}, 0
    for i in order:
        slots[i] = slice(k, k + prob.elements[i].n_memory)
        k += prob.elements[i].n_memory
    settings = {"eps": regularisation, "eps_m": 20.0 * regularisation, "tau": memory_time,
                "tau_f": memory_time / 100.0, "penalty": penalty}

    def fun(t, y):
        q, v = y[:nf], y[nf:2 * nf]
        memory = y[2 * nf:]
        e = prob.basis(t)
        rhs = -prob.K @ q - (prob.C + prob.Cr) @ v - prob.B @ e + prob.Fx @ e
        dz = np.zeros(k)
        for i in order:
            el = prob.elements[i]
            settings["effective_mass"] = lambda i=i: 1.0 / (prob.gf[i] @ np.linalg.solve(prob.mass(t), prob.gf[i]))
            s_, sd = prob.gf[i] @ q + prob.ge[i] @ e, prob.gf[i] @ v + prob.gve[i] @ e
            F, d = el.regularised_force(s_, sd, t, memory[slots[i]], settings)
            dz[slots[i]] = d
            rhs = rhs + prob.gf[i] * F
        a = np.linalg.solve(prob.mass(t), rhs)
        return np.concatenate([v, a, dz])

    return fun, k


def simulate_regularised(prob: Problem, t_end: float, regularisation: float | None = None,
                         penalty: float | None = None, memory_time: float | None = None, rtol: float = 1e-8,
                         max_step: float | None = None, method: str = "LSODA", t_eval=None) -> SimulationResult:
    """Integrate the regularised model with ``solve_ivp`` (no events, no exact stick)."""
    if regularisation is None:
        regularisation = 1e-4 * max(1e-300, max([abs(d.velocity) for d in prob.drivers.values()] + [1.0]))
    if memory_time is None:
        memory_time = 1e-3 * (2 * math.pi / prob.omega_max if prob.omega_max > 0 else t_end)
    from scipy.integrate import solve_ivp       # here: importing scipy.integrate costs ~0.15 s of start-up

    fun, nz = regularised_rhs(prob, regularisation, penalty, memory_time)
    y0 = np.concatenate([prob.q0, prob.v0, np.ones(nz)])
    kw = {} if max_step is None else {"max_step": max_step}
    if prob.omega_max > 0:
        # a small first step: LSODA's own guess from a long span fails on the stiff tanh law
        kw["first_step"] = 1e-5 * 2 * math.pi / prob.omega_max
    sol = solve_ivp(fun, (0.0, t_end), y0, method=method, rtol=rtol, atol=rtol * 1e-3 * max(1e-300, np.max(np.abs(y0)) + 1e-3),
                    t_eval=t_eval, **kw)
    nf = prob.nf
    E = prob.basis_many(sol.t)
    x, xd = prob.full_state(sol.y[:nf], sol.y[nf:2 * nf], E)
    res = SimulationResult(t=sol.t, x=x, v=xd, names=list(prob.names), events=[], t_end=float(t_end),
                           energy=np.zeros(0), work=np.zeros(0), energy_error=float("nan"), n_steps=int(sol.nfev),
                           stopped_early=sol.status != 0, reason="" if sol.status == 0 else sol.message,
                           method=f"regularised ({method}, eps = {regularisation:g})",
                           elements=[f"{el.kind}:{el.name}" for el in prob.elements],
                           driven=[prob.names[j] for j in prob.c],
                           warnings=["regularised model: no exact stick, no events; energy balance not computed"])
    return res
