"""Impacts: a ball dropped on a rigid floor with restitution e (accumulation in finite time)."""
from __future__ import annotations

import math

import numpy as np

from fem.modelfile.source import read_toml
from fem.study import simulate
from validation.registry import case, check, claim
from validation.examples import EXAMPLES

SRC = "bouncing ball, Newton restitution (closed form)"
EXAMPLE = EXAMPLES / "discrete_bouncing_ball.toml"


@case("discrete_impact_ball", group="discrete")
def bouncing_ball():
    """Ball of mass m dropped from h on a rigid floor, restitution e = 0.5 and 0.8, g = 9.81.

    Impact times t_1 = sqrt(2h/g), t_{n+1} = t_n + 2 e^n v_1 / g; accumulation (Zeno) time
    t_inf = t_1 + 2 e v_1 / (g (1 - e)); afterwards the ball rests on the floor.
    Tolerances: impact times 1e-12 relative (exact propagation, Newton root).  The solver closes the
    sequence into persistent contact when the rebound speed drops below rest_tol v_1 (1e-9): the
    skipped flights add at most 2 rest_tol v_1/(g (1 - e)), so the accumulation time is checked to
    2 rest_tol v_1/(g (1-e)) / t_inf plus round-off (< 1e-8), and the number of impacts to be
    ceil(log(rest_tol)/log(e)).  The model is examples/discrete_bouncing_ball.toml (e = 0.5 there; the
    case sets e, the run length and rest_tol).
    """
    out = []
    h, g = 1.0, 9.81           # drop height and gravity of the example file (the mass drops out)
    for e in (0.5, 0.8):
        t_end = 1.5 * (math.sqrt(2 * h / g) * (1 + 2 * e / (1 - e)))
        doc = read_toml(EXAMPLE)
        doc["impact"][0]["restitution"] = e
        doc["simulation"] = {"t_end": t_end, "rest_tol": 1e-9}
        res = simulate(doc)
        t1 = math.sqrt(2 * h / g)
        v1 = g * t1
        ref_t = t1 + np.concatenate([[0.0], np.cumsum([2 * e ** n * v1 / g for n in range(1, 8)])])
        ti = res.event_times("impact")
        tinf = t1 + 2 * e * v1 / (g * (1 - e))
        tc = res.event_times("contact_close")
        tag = f"e={e}"
        out.append(check(f"impact times ({tag})", SRC, "max relative error of the first 8 impact times", 0.0,
                         np.max(np.abs(ti[:8] - ref_t) / ref_t), 1e-12, scale=1.0))
        tol = 2 * 1e-9 * v1 / (g * (1 - e)) / tinf + 1e-12
        out.append(check(f"impact accumulation time ({tag})", SRC, "t_inf (s)", tinf, tc[0] if tc.size else np.nan, tol))
        nexp = math.ceil(math.log(1e-9) / math.log(e))
        out.append(check(f"impact count to rest ({tag})", SRC, "number of impacts", nexp, ti.size, 0.0, scale=1.0))
        out.append(claim(f"impact: rests on the floor and the run completes ({tag})", SRC,
                         "x = 0, v = 0 at t_end, not stopped early",
                         (not res.stopped_early) and res.t[-1] == t_end and abs(res.x[0, -1]) <= 1e-12
                         and abs(res.v[0, -1]) <= 1e-12))
        out.append(check(f"impact energy loss per impact ({tag})", SRC, "KE after / KE before, 1st impact", e * e,
                         _ke_ratio(res), 1e-12))
    return out


def _ke_ratio(res):
    k = int(np.flatnonzero(np.isclose(res.t, res.event_times("impact")[0], rtol=0, atol=0))[0])
    return (res.v[0, k + 1] / res.v[0, k]) ** 2
