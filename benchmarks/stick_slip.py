"""Benchmark: exact event-driven stick-slip vs scipy solve_ivp with tanh-regularised friction.

Seed 000 case with k* = 2 velocity reversals per period (eps = M1/M0 = 6, Omega = 1; I = 2,
c = 50, M0 = 3), 1000 periods.  The baseline is the package's regularised model
(discrete.nonsmooth.regularised: F = -(F_k + (F_s - F_k) zeta) tanh(w/eps) with a rest memory
zeta so that momentary stops reverse as in seed 000), integrated by solve_ivp (LSODA, the fastest
scipy method for this stiff problem; rtol 1e-8).  Its velocity scale eps is tuned first: reduced
by factors of 3 until the period error over a short run is below 1e-3.  Both are timed in the
same process, interleaved (median of --repeat runs, same 1000 periods; BLAS threads set to 1), and the
script prints the wall-time ratio and both period errors against the closed form (20).

    python benchmarks/stick_slip.py [--periods 1000] [--repeat 3]
"""
from __future__ import annotations

import argparse
import os
import pathlib
import statistics
import sys
import time

for _v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")   # small dense matrices: BLAS threads only add contention (both methods)

import numpy as np  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))

from discrete.nonsmooth import Options, simulate, simulate_regularised  # noqa: E402
from fem.study import Study  # noqa: E402
from validation.analytic import seed000  # noqa: E402

EPS, OMEGA, I, C, M0 = 6.0, 1.0, 2.0, 50.0, 3.0


def model(periods: float) -> tuple[dict, dict]:
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


def run_regularised(periods, d, eps_rel, tau_rel):
    doc, _ = model(periods)
    study = Study.parse(doc)
    prob, st = study.problem_spec().problem(), study.simulation_settings()
    t0 = time.perf_counter()
    res = simulate_regularised(prob, st["t_end"], regularisation=eps_rel * d["omega"],
                               memory_time=tau_rel * d["period"], rtol=1e-8, method="LSODA")
    return time.perf_counter() - t0, res


def run_exact(periods):
    doc, d = model(periods)
    study = Study.parse(doc)
    prob, st = study.problem_spec().problem(), study.simulation_settings()
    t0 = time.perf_counter()
    res = simulate(prob, st["t_end"], Options())
    dt = time.perf_counter() - t0
    slips = res.event_times("slip")
    mean_T = (slips[-1] - slips[0]) / (slips.size - 1)
    return dt, res, mean_T


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--periods", type=int, default=1000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--memory", type=float, default=1e-2, help="rest-memory time of the baseline / period")
    a = ap.parse_args(argv)
    _, d = model(a.periods)
    T = d["period"]
    # 1. tune the baseline's regularisation to 1e-3 period accuracy on a short run
    eps_rel, err_short = 1e-3, np.inf
    while eps_rel > 1e-8:
        _, res = run_regularised(8, d, eps_rel, a.memory)
        err_short = abs(regularised_period(res, d) / T - 1)
        print(f"tuning: eps = {eps_rel:.3g} omega -> period error {err_short:.2e} (8 periods)")
        if err_short < 1e-3:
            break
        eps_rel /= 3
    # 2. time both on the full run
    t_ex, t_reg = [], []
    for _ in range(a.repeat):          # interleaved, so both see the same machine load
        dt, res_ex, mean_T = run_exact(a.periods)
        t_ex.append(dt)
        dt, res_reg = run_regularised(a.periods, d, eps_rel, a.memory)
        t_reg.append(dt)
    err_ex = abs(res_ex.period / T - 1)
    err_ex_mean = abs(mean_T / T - 1)
    err_reg = abs(regularised_period(res_reg, d) / T - 1)
    if res_reg.stopped_early or not np.isfinite(err_reg):
        print(f"baseline failed: {res_reg.reason or 'no periods detected'}")
    m_ex, m_reg = statistics.median(t_ex), statistics.median(t_reg)
    print(f"seed 000, eps = {EPS}, Omega = {OMEGA}: k* = {d['k_star']} reversals per period, "
          f"period (20) = {T:.12g} s, {a.periods} periods")
    print(f"event-driven : median {m_ex:8.3f} s over {a.repeat} runs, {len(res_ex.events)} events, "
          f"period error {err_ex:.2e} (detector), {err_ex_mean:.2e} (mean over all cycles), "
          f"energy error {res_ex.energy_error:.1e}")
    print(f"regularised  : median {m_reg:8.3f} s over {a.repeat} runs (solve_ivp LSODA, tanh eps = {eps_rel:.3g} omega, "
          f"memory {a.memory:g} T), {res_reg.n_steps} RHS evaluations, period error {err_reg:.2e}")
    acc = err_reg / max(err_ex, err_ex_mean, 1e-16)
    print(f"RATIO wall time (regularised / event-driven) = {m_reg / m_ex:.1f}x   "
          f"accuracy ratio (period error regularised / event-driven) >= {acc:.1e}x")
    ok = m_reg / m_ex >= 10 and acc >= 1000
    print("target (>= 10x faster, >= 1000x more accurate):", "MET" if ok else "NOT MET")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
