"""Steady case 4: the backlash (gap) oscillator under a harmonic force -- HB (penalty law) vs exact shooting."""
from __future__ import annotations


import numpy as np

from discrete.steady import ShootingModel
from fem.modelfile.source import read_toml
from fem.study import forced, steady_model
from validation.registry import case, check, claim
from validation.examples import EXAMPLES

SRC = "textbook §11.1 (11.1) gap oscillator (discrete issue), forced; HB vs event-driven shooting"


EXAMPLE = EXAMPLES / "steady_gap.toml"


def gap_doc(**steady):
    """examples/steady_gap.toml (HB, 15 harmonics) continued over w = 0.5 .. 1.4 with ds_max = 0.2."""
    d = read_toml(EXAMPLE)
    d["steady"].update({"omega": [0.5, 1.4], "ds_max": 0.2, **steady})
    return d


@case("steady_gap_hb_vs_shooting", group="steady")
def gap_case():
    """m q'' + 0.1 q' + F_gap(q) = 0.3 sin(w t), F_gap = k (q -+ Delta) outside the clearance +-0.1 (exact
    law (11.1), a penalty-type contact with k = 1).  HB (15 harmonics, 256 AFT samples, continuation over
    w = 0.5..1.4, Floquet stability) against shooting with the exact event-driven integrator (the orbit is
    found by Newton from time integration started at rest, independent of HB), at every 8th branch point.
    Tolerance 1e-3: the HB truncation error of a kinked (C0) force law decays like H^-2.5, measured 3.6e-4
    at H = 15.  Stability: each shooting orbit is reached from rest by time integration (so it is stable), and
    HB marks those points stable; the shooting Floquet multipliers are inside the unit circle.
    The oscillator is examples/steady_gap.toml (the case continues over 0.5 .. 1.4).
    """
    out = []
    r = forced(gap_doc())
    sm = steady_model(gap_doc())
    sh = ShootingModel(sm.factory)
    errs, agree = [], True
    for j in range(0, r.omega.size, max(1, r.omega.size // 8)):
        w = float(r.omega[j])
        y, n, ok = sh.settle(np.zeros(2), w, periods=400, tol=1e-10, scale=np.ones(2))
        y, _ = sh.solve(y, w, np.ones(2))
        _, res = sh.run(y, w, dense=True)
        A = 0.5 * (res.x[0].max() - res.x[0].min())
        errs.append(abs(r.response[j] - A) / A)
        mu = np.abs(sh.floquet(y, w, np.ones(2)))
        agree &= bool(r.stable[j] and mu.max() < 1 and ok)
    out.append(check("HB (penalty) vs shooting (exact), gap oscillator", SRC, "max rel. amplitude difference", 0.0,
                     max(errs), 1e-3, scale=1.0, note=f"{len(errs)} points, w = 0.5..1.4"))
    out.append(claim("stability: HB Floquet and shooting agree on the sampled stable branch", SRC,
                     "stable in both, reached from rest", agree))
    i = int(np.argmax(r.response))
    out.append(claim("softening peak below the contact frequency 1", SRC, "w_peak < 1",
                     bool(r.omega[i] < 1.0), note=f"peak amplitude {r.response[i]:.4f} at w = {r.omega[i]:.4f}"))
    return out
