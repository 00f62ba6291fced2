"""The 1/3 subharmonic of the hardening cubic oscillator (textbook §8.4): examples/steady_subharmonic.toml
run in time by Moreau-Jean (150 subharmonic periods from the state x0 of the file) and the converged HB orbit
of the same file (subharmonic = 3, started from a time run), over the last two periods 2 pi/omega, with the
forcing F3 cos(3 omega t) scaled for comparison.

    python examples/subharmonic_third.py [OUT.png]      (default docs/img/subharmonic_third.png)

Returns the omega-components of the time run and of HB (the validation case steady_subharmonic_third
checks them against each other and against an independent integration).
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from discrete.steady import HBModel
from fem.modelfile.source import read_toml
from fem.output.figures.steady import plot_orbit_overlay
from fem.study import Study

MODEL = Path(__file__).resolve().parent / "steady_subharmonic.toml"
OMEGA = 1.2          # the subharmonic; the forcing is 3 omega = 3.6 rad/s


def main(out: str | Path = "docs/img/subharmonic_third.png") -> dict:
    doc = read_toml(MODEL)
    study = Study.parse(doc)
    run = study.simulate()
    T = 2 * np.pi / OMEGA
    sel = run.t >= run.t[-1] - 2 * T * (1 - 1e-9)
    t, q = run.t[sel], run.x[0, sel]
    last = t >= t[-1] - T * (1 - 1e-9)
    a_time = 2 / T * abs(np.trapezoid(q[last] * np.exp(-1j * OMEGA * t[last]), t[last]))
    afc = study.forced()
    X = afc.states[0]
    hb = HBModel(study.steady_model().system, harmonics=9, nu=3)
    th, qh, _ = hb.evaluate(X, 3 * OMEGA, points=400)
    Q = np.asarray(X).reshape(1, -1)
    a_hb = float(np.hypot(Q[0, 1], Q[0, 2]))
    # align the HB orbit with the run's time axis: both are periodic in 2 pi/omega and locked to the forcing
    # cos(3 omega t), so the HB time th (from t = 0 of a forcing cycle) is shifted by whole forcing periods
    Tf = 2 * np.pi / (3 * OMEGA)
    k = np.ceil((t[0]) / T) * T
    th2 = np.concatenate([th, th + T]) + k - T
    qh2 = np.concatenate([qh[0], qh[0]])
    keep = (th2 >= t[0]) & (th2 <= t[-1])
    F3 = doc["force"][0]["amplitude"]
    Path(out).parent.mkdir(parents=True, exist_ok=True)
    plot_orbit_overlay([(t, q, "Moreau-Jean time run (200 steps / period)", "-"),
                        (th2[keep], qh2[keep], "HB orbit (9 harmonics of omega = Omega/3)", "--"),
                        (t, 0.1 * np.cos(3 * OMEGA * t), f"forcing F3 cos(Omega t) / {F3 / 0.1:g}", ":")], out,
                       ylabel="displacement q of the mass [m]",
                       title=f"{doc['title']}\n1/3 subharmonic: omega-component {a_time:.5f} (time run), {a_hb:.5f} (HB); "
                             f"forcing period {Tf:.3f} s")
    print(f"omega-component: time run {a_time:.6f}, HB {a_hb:.6f}")
    return {"time_run": float(a_time), "hb": a_hb}


if __name__ == "__main__":
    main(*sys.argv[1:])
