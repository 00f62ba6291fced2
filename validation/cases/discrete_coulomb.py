"""Free Coulomb decay (textbook §4.3, V4.3a; §8.2 V8.2-a)."""
from __future__ import annotations

import math

import numpy as np

from fem.modelfile.source import read_toml
from fem.study import simulate
from validation.analytic import friction_ch8 as ref
from validation.registry import case, check, claim
from validation.examples import EXAMPLES

SRC = "textbook §4.3 (digest textbook_ch2-5.md V4.3a)"
EXAMPLE = EXAMPLES / "discrete_coulomb_decay.toml"


@case("discrete_coulomb_decay", group="discrete")
def coulomb_decay():
    """m = 1, c = 100, P = 1, q0 = 1.005 at rest: extrema drop by 2P/c per half-cycle (4P/c per
    period), each half-cycle lasts pi/k (period unchanged, 2 pi/k), the motion stops at the first
    extremum inside the dead band |q| <= F_s/c.  Run with F_s = P and with F_s = 1.5 P (earlier stop).
    The model is examples/discrete_coulomb_decay.toml (the F_s = P run; the case sets F_s and t_end).

    The reference is exact for this piecewise-linear system; tolerance 1e-10 (relative to q0 for
    positions, to pi/k for times) leaves room for round-off over ~50 events (observed ~1e-14).
    """
    out = []
    m, c, P, q0 = 1.0, 100.0, 1.0, 1.005
    k = math.sqrt(c / m)
    for Fs in (P, 1.5 * P):
        ext = ref.coulomb_extrema(q0, P, c, static=Fs)
        doc = read_toml(EXAMPLE)
        if Fs != P:
            doc["friction"][0]["static"] = Fs
        doc["simulation"]["t_end"] = (len(ext) + 2) * math.pi / k
        res = simulate(doc)
        turns = [e for e in res.events if e.kind in ("reversal", "stick")]
        xs = np.array([e.state["mass"]["x"] for e in turns])
        ts = np.array([e.t for e in turns])
        tag = f"F_s/P={Fs / P:g}"
        out.append(check(f"coulomb number of half-cycles ({tag})", SRC, "half-cycles until stop", len(ext) - 1,
                         len(turns), 0.0, scale=1.0))
        n = min(len(ext) - 1, xs.size)
        err = np.max(np.abs(xs[:n] - np.array(ext[1:n + 1]))) if n else np.inf
        out.append(check(f"coulomb extrema ({tag})", SRC + ": |q| drops by 2P/c per half-cycle", "max |extremum error| / q0",
                         0.0, err, 1e-10, scale=q0))
        d4 = (abs(ext[0]) - abs(ext[2])) if len(ext) > 2 else np.nan
        out.append(check(f"coulomb drop per period ({tag})", SRC, "amplitude drop per period", 4 * P / c,
                         abs(xs[1]) - abs(xs[3]) if xs.size > 3 else np.nan, 1e-10))
        out.append(check(f"coulomb reference drop ({tag})", SRC, "4P/c from the reference sequence", 4 * P / c, d4, 1e-12))
        halves = np.diff(np.concatenate([[0.0], ts]))
        out.append(check(f"coulomb half-period ({tag})", SRC + ": period unchanged 2 pi/k", "max |half-cycle - pi/k|",
                         0.0, np.max(np.abs(halves - math.pi / k)), 1e-10, scale=math.pi / k))
        stop = res.x[0, -1]
        out.append(check(f"coulomb stop position ({tag})", SRC, "final position", ext[-1], stop, 1e-10, scale=q0))
        out.append(claim(f"coulomb stop inside the dead band ({tag})", SRC, "|q_stop| <= F_s/c and at rest",
                         abs(stop) <= Fs / c and abs(res.v[0, -1]) == 0.0 and turns[-1].kind == "stick"))
        out.append(claim(f"coulomb energy balance ({tag})", "friction work = loss of energy", "energy_error <= 1e-9",
                         res.energy_error <= 1e-9, note=f"{res.energy_error:.2e}"))
    return out
