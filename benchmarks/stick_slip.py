"""Benchmark: exact event-driven stick-slip vs scipy solve_ivp with tanh-regularised friction.

Seed 000 case with k* = 2 velocity reversals per period (eps = M1/M0 = 6, Omega = 1; I = 2,
c = 50, M0 = 3), 1000 periods.  The baseline is the package's regularised model
(discrete.nonsmooth.regularised: F = -(F_k + (F_s - F_k) zeta) tanh(w/eps) with a rest memory
zeta so that momentary stops reverse as in seed 000), integrated by solve_ivp (LSODA, the fastest
scipy method for this stiff problem; rtol 1e-8).  Its velocity scale eps is tuned first: reduced
by factors of 3 until the period error over a short run is below 1e-3.

Both are timed in the same process on the same 1000 periods (wall and process-CPU time; BLAS
threads 1): the event-driven solver ``--runs`` times after one warm-up call (numba's compile/load),
median and spread; the baseline (about 75 s on the quiet machine: five whole runs would take most
of the 10-minute budget of ``make bench``) once, timed in ``--legs`` consecutive legs that continue
from each other's state (:class:`RegularisedLegs`), its time being the sum of the legs; the
package's runs interleave with the legs so that both see the same machine load.  Printed: the
speed-up (target >= 500x, issue 13) from the wall-time medians and from the CPU-time medians, and
the accuracy side by side: both period errors against the closed form (20) (the event-driven one
must stay <= 1e-11) and the accuracy ratio (target >= 1000x).

    python benchmarks/stick_slip.py [--periods 1000] [--runs 5] [--legs 5] [--quick]
"""
from __future__ import annotations

import argparse
import pathlib
import sys
import time

import common

common.limit_blas_threads(1)

import numpy as np  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))

from discrete.nonsmooth import Options, simulate, simulate_regularised  # noqa: E402
from fem.study import Study  # noqa: E402
from validation.analytic import seed000  # noqa: E402

EPS, OMEGA, I, C, M0 = 6.0, 1.0, 2.0, 50.0, 3.0
SPEED_TARGET, ACCURACY_TARGET, PERIOD_ERROR_MAX = 500.0, 1000.0, 1e-11


def model(periods: float) -> tuple[dict, dict]:
    """Seed 000 model dict (k* = 2) running ``periods`` periods after the first breakaway, and the
    closed-form data of validation.analytic.seed000.dimensional."""
    d = seed000.dimensional(EPS, OMEGA, I, C, M0)
    return {"body": [{"name": "disk", "inertia": I}],
            "driver": [{"name": "top", "velocity": d["omega"]}],
            "spring": [{"between": ["top", "disk"], "k": C}],
            "friction": [{"name": "bit", "body": "disk", "kinetic": M0, "static": d["M1"], "restick": "kinetic"}],
            "simulation": {"t_end": d["M1"] / (C * d["omega"]) + periods * d["period"]}}, d


def regularised_period(res, d) -> float:
    """Mean period from the slip onsets after long rests (velocity rising through 5 % of omega
    after at least 10 % of a period below it), linearly interpolated between samples."""
    v, t = res.v[res.names.index("disk")], res.t
    thr = 0.05 * d["omega"]
    idx = np.flatnonzero((v[:-1] < thr) & (v[1:] >= thr))
    above = np.abs(v) >= thr
    last_above = np.maximum.accumulate(np.where(above, np.arange(v.size), -1))
    onsets = []
    for i in idx:
        j = last_above[i]
        if t[i] - (t[j] if j >= 0 else 0.0) > 0.1 * d["period"]:
            onsets.append(t[i] + (thr - v[i]) * (t[i + 1] - t[i]) / (v[i + 1] - v[i]))
    onsets = np.array(onsets)
    if onsets.size < 3:
        return float("nan")
    return float((onsets[-1] - onsets[1]) / (onsets.size - 2))   # skip the first (start-up) cycle


def _problem(periods):
    doc, _ = model(periods)
    study = Study.parse(doc)
    return study.problem_spec().problem(), study.simulation_settings()["t_end"]


def regularised_runner(periods, d, eps_rel, tau_rel):
    """The baseline as a callable (the problem is built once, outside the timed call)."""
    prob, t_end = _problem(periods)
    return lambda: simulate_regularised(prob, t_end, regularisation=eps_rel * d["omega"],
                                        memory_time=tau_rel * d["period"], rtol=1e-8, method="LSODA")


class RegularisedLegs:
    """The baseline's run over ``periods`` split into ``legs`` consecutive legs of equal length,
    each a call: solve_ivp (LSODA, rtol 1e-8) on the package's regularised right-hand side
    (discrete.nonsmooth.regularised.regularised_rhs), continuing from the previous leg's final
    state (memory variables included), with the post-processing of simulate_regularised (full
    state at every output point).  The sum of the legs' times is the time of the whole run (one
    restart of LSODA per leg: a few hundred RHS calls of millions); the legs give the spread and
    let the package's runs interleave with the baseline's, so both see the same machine load.
    The settings are those of simulate_regularised (atol, first step)."""

    def __init__(self, periods, d, eps_rel, tau_rel, legs):
        from discrete.nonsmooth.regularised import regularised_rhs

        self.prob, t_end = _problem(periods)
        p = self.prob
        self.fun, nz = regularised_rhs(p, eps_rel * d["omega"], None, tau_rel * d["period"])
        self.y = np.concatenate([p.q0, p.v0, np.ones(nz)])
        self.atol = 1e-8 * 1e-3 * max(1e-300, np.max(np.abs(self.y)) + 1e-3)
        self.first_step = 1e-5 * 2 * np.pi / p.omega_max
        self.bounds = np.linspace(0.0, t_end, legs + 1)
        self.k, self.t, self.v, self.nfev, self.status = 0, [], [], 0, []
        self.disk = p.names.index("disk")

    def __call__(self):
        from scipy.integrate import solve_ivp

        if self.k >= self.bounds.size - 1:
            raise RuntimeError("all legs already run")
        p = self.prob
        sol = solve_ivp(self.fun, (self.bounds[self.k], self.bounds[self.k + 1]), self.y, method="LSODA", rtol=1e-8,
                        atol=self.atol, first_step=self.first_step)
        E = np.array([p.basis(t) for t in sol.t]).T
        x, xd = p.full_state(sol.y[:p.nf], sol.y[p.nf:2 * p.nf], E)
        self.y = sol.y[:, -1].copy()
        self.t.append(sol.t if self.k == 0 else sol.t[1:])
        self.v.append(xd[self.disk] if self.k == 0 else xd[self.disk, 1:])
        self.nfev += int(sol.nfev)
        self.status.append(sol.message if sol.status != 0 else "")
        self.k += 1
        return self

    @property
    def result(self):
        """The whole run as the attributes regularised_period reads (t, v, names)."""
        from types import SimpleNamespace

        v = np.zeros((len(self.prob.names), sum(a.size for a in self.t)))
        v[self.disk] = np.concatenate(self.v)
        return SimpleNamespace(t=np.concatenate(self.t), v=v, names=list(self.prob.names), n_steps=self.nfev,
                               stopped_early=any(self.status), reason="; ".join(s for s in self.status if s))


def exact_runner(periods):
    prob, t_end = _problem(periods)
    return lambda: simulate(prob, t_end, Options())


def exact_errors(res, T) -> tuple[float, float]:
    """Period error of the detector and of the mean slip-to-slip interval over all cycles."""
    slips = res.event_times("slip")
    mean_T = (slips[-1] - slips[0]) / (slips.size - 1)
    return abs(res.period / T - 1), abs(mean_T / T - 1)


def tune(d, memory, T) -> float:
    """The largest tanh velocity scale eps (factors of 3 from 1e-3 omega) whose period error over
    8 periods is below 1e-3."""
    eps_rel = 1e-3
    while eps_rel > 1e-8:
        w0, c0 = time.perf_counter(), time.process_time()
        res = regularised_runner(8, d, eps_rel, memory)()
        err = abs(regularised_period(res, d) / T - 1)
        print(f"tuning: eps = {eps_rel:.3g} omega -> period error {err:.2e} (8 periods; "
              f"{time.perf_counter() - w0:.2f} s wall, {time.process_time() - c0:.2f} s cpu)", flush=True)
        if err < 1e-3:
            return eps_rel
        eps_rel /= 3
    raise SystemExit("tuning failed: no eps down to 1e-8 omega reaches 1e-3")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--periods", type=int, default=1000)
    ap.add_argument("--runs", type=int, default=5, help="timed runs of the event-driven solver")
    ap.add_argument("--legs", type=int, default=5, help="the baseline's run is timed in this many consecutive legs")
    ap.add_argument("--memory", type=float, default=1e-2, help="rest-memory time of the baseline / period")
    ap.add_argument("--quick", action="store_true", help="200 periods (the target is stated at 1000)")
    a = ap.parse_args(argv)
    if a.quick:
        a.periods = 200
    common.header(__file__, f"event-driven vs solve_ivp (tanh friction), seed 000 k* = 2, {a.periods} periods")
    _, d = model(a.periods)
    T = d["period"]
    eps_rel = tune(d, a.memory, T)
    exact = exact_runner(a.periods)
    w0 = time.perf_counter()
    exact()                                          # warm-up: numba kernel load (or compile)
    print(f"warm-up call of the event-driven solver: {time.perf_counter() - w0:.3f} s (not timed)")
    legs = RegularisedLegs(a.periods, d, eps_rel, a.memory, a.legs)
    tm = common.interleaved({"event-driven": exact, "solve_ivp leg": legs}, runs=max(a.runs, a.legs),
                            runs_of={"event-driven": a.runs, "solve_ivp leg": a.legs}, verbose=True)
    ex, leg = tm["event-driven"], tm["solve_ivp leg"]
    # the baseline's whole run: the sum of its legs
    reg = common.Timing(wall=[sum(leg.wall)], cpu=[sum(leg.cpu)])
    res_ex, res_reg = ex.result, legs.result
    err_ex, err_ex_mean = exact_errors(res_ex, T)
    err_reg = abs(regularised_period(res_reg, d) / T - 1)
    if res_reg.stopped_early or not np.isfinite(err_reg):
        print(f"baseline failed: {res_reg.reason or 'no periods detected'}")
    ratio, ratio_cpu = common.speedup(reg, ex)
    acc = err_reg / max(err_ex, err_ex_mean, 1e-16)
    print(f"seed 000, eps = {EPS}, Omega = {OMEGA}: k* = {d['k_star']} reversals per period, "
          f"period (20) = {T:.12g} s, {a.periods} periods")
    print(f"event-driven : {ex.line()}; {len(res_ex.events)} events, period error {err_ex:.2e} (detector), "
          f"{err_ex_mean:.2e} (mean over all cycles), energy error {res_ex.energy_error:.1e}")
    print(f"solve_ivp    : {reg.wall[0]:.3f} s wall, {reg.cpu[0]:.3f} s cpu for the {a.periods} periods = the sum of "
          f"{a.legs} legs of {a.periods / a.legs:g} periods, each {leg.line()}; LSODA, tanh eps = {eps_rel:.3g} "
          f"omega, memory {a.memory:g} T, {res_reg.n_steps} RHS evaluations, period error {err_reg:.2e}")
    print(f"speed-up (solve_ivp / event-driven): {ratio:.1f}x from the wall-time medians, {ratio_cpu:.1f}x from the "
          f"CPU-time medians (target >= {SPEED_TARGET:g}x)")
    print(f"accuracy: period error {err_ex:.1e} (event-driven, must stay <= {PERIOD_ERROR_MAX:g}) vs {err_reg:.1e} "
          f"(solve_ivp): ratio >= {acc:.1e}x (target >= {ACCURACY_TARGET:g}x)")
    spread = {"package": ex.spread_dict(), "baseline": reg.spread_dict(), "baseline_legs": leg.spread_dict()}
    what = f"seed 000 k* = 2, {a.periods} periods"
    recs = [
        common.record(__file__, f"event-driven vs solve_ivp (LSODA, tanh tuned to 1e-3), {what}", "event-driven",
                      "solve_ivp", ratio, (">=", SPEED_TARGET), ratio_cpu=ratio_cpu, accuracy="period error",
                      accuracy_package=max(err_ex, err_ex_mean), accuracy_baseline=err_reg,
                      runs={"package": ex.runs, "baseline_legs": leg.runs}, spread=spread),
        common.record(__file__, f"period error of the event-driven solver against (20), {what}", "event-driven",
                      None, max(err_ex, err_ex_mean), ("<=", PERIOD_ERROR_MAX), metric="period error", unit="",
                      accuracy="energy error", accuracy_package=float(res_ex.energy_error), runs=ex.runs),
        common.record(__file__, f"accuracy ratio (period error solve_ivp / event-driven), {what}", "event-driven",
                      "solve_ivp", acc, (">=", ACCURACY_TARGET), metric="accuracy ratio",
                      accuracy="period error", accuracy_package=max(err_ex, err_ex_mean), accuracy_baseline=err_reg,
                      runs=1),
    ]
    print()
    return common.finish(recs)


if __name__ == "__main__":
    sys.exit(main())
