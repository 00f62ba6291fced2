"""Gap / backlash (textbook §11.1): exact law (11.1) and the smooth arctan law (11.2)."""
from __future__ import annotations


import numpy as np

from fem.modelfile.source import read_toml
from fem.study import simulate
from validation.analytic import gap as ref
from validation.registry import case, check, claim
from validation.examples import EXAMPLES

SRC = "textbook §11.1 (digest textbook_ch10-11.md (11.1), (11.2))"
EXAMPLE = EXAMPLES / "discrete_gap_backlash.toml"


def model(lower, upper, A, law="exact", L=1e3, periods=3.0, max_step=None):
    """examples/discrete_gap_backlash.toml (m = k0 = 1, clearance +-0.1, law (11.1), started at q = 1 at
    rest) with the clearance, start amplitude, law and run length a case varies."""
    doc = read_toml(EXAMPLE)
    sim = {"t_end": periods * ref.period(1.0, A, lower, upper)}
    if max_step:
        sim["max_step"] = max_step
    doc["simulation"] = sim
    doc["body"][0]["x0"] = A
    g = doc["gap"][0]
    g.update(law=law, L=L)
    if lower == -upper:
        g["delta"] = upper
    else:
        del g["delta"]
        g["lower"], g["upper"] = lower, upper
    return doc


def up_crossings(t, q, qd):
    """Times where q crosses 0 upwards, by cubic Hermite interpolation of (q, q') samples."""
    out = []
    for k in range(t.size - 1):
        h = t[k + 1] - t[k]
        if h <= 0 or not (q[k] < 0 <= q[k + 1]):
            continue
        g0, g1, d0, d1 = q[k], q[k + 1], qd[k] * h, qd[k + 1] * h
        c2 = 3 * (g1 - g0) - 2 * d0 - d1
        c3 = d0 + d1 - 2 * (g1 - g0)
        r = [x.real for x in np.roots([c3, c2, d0, g0]) if abs(x.imag) < 1e-9 and 0 <= x.real <= 1]
        out.append(t[k] + h * min(r))
    return np.array(out)


@case("discrete_gap_exact", group="discrete")
def gap_exact():
    """Free vibration with clearance, law (11.1), m = k0 = 1, started at q = A at rest: period
    2 pi/k0 + 2 (upper - lower)/(k0 (A - upper)) (symmetric: k/k0 = 1/(1 + 2 Delta/(pi (A - Delta)))).

    Exact piecewise-linear reference; tolerance 1e-10 (exact propagation, events to ~1e-15).
    The digest's table (Delta/A = 0.1: k/k0 = 0.933937) is checked against the closed form to its
    6 printed digits.  The first clearance is examples/discrete_gap_backlash.toml.
    """
    out = [check("gap closed form vs digest table", SRC + " [C] table", "k/k0 at Delta/A = 0.1", 0.933937,
                 ref.frequency_ratio(0.1), 1e-6)]
    for lower, upper, A in ((-0.1, 0.1, 1.0), (-0.3, 0.3, 1.0), (-0.05, 0.15, 1.0)):
        T = ref.period(1.0, A, lower, upper)
        res = simulate(model(lower, upper, A, periods=4.2))
        tag = f"[{lower}, {upper}], A={A}"
        closes = res.event_times("contact_close")
        out.append(check(f"gap period ({tag})", SRC + " (11.1)", "period (s)", T, closes[-1] - closes[-3], 1e-10))
        out.append(check(f"gap detected period ({tag})", SRC + " (11.1)", "period from the detector (s)", T,
                         res.period or np.nan, 1e-10))
        out.append(claim(f"gap energy conserved ({tag})", SRC, "energy_error <= 1e-10", res.energy_error <= 1e-10,
                         note=f"{res.energy_error:.2e}"))
    return out


@case("discrete_gap_arctan", group="discrete")
def gap_arctan():
    """Smooth law (11.2) converges to (11.1) as L grows: Delta/A = 0.1, L = 10, 100, 1000.

    The period of the smooth model (upward zero crossings of q, Hermite-interpolated on DOP853 steps
    at rtol 1e-12) is compared with the exact (11.1) period; the relative error must fall like 1/L:
    measured log-log slope -1 +- 0.1 (the digest reports error = -0.0235/L), and the L = 1000 error
    must be below 1e-4, and err * L must match the digest's 0.0235 to 5 %
    (its value is quoted to 3 digits).  No switching events occur in the smooth model.
    """
    A, d = 1.0, 0.1
    T = ref.period(1.0, A, -d, d)
    errs, Ls = [], (10.0, 100.0, 1000.0)
    n_events = 0
    for L in Ls:
        res = simulate(model(-d, d, A, law="arctan", L=L, periods=2.3, max_step=0.05))
        tc = up_crossings(res.t, res.x[0], res.v[0])
        errs.append((tc[-1] - tc[-2]) / T - 1.0)
        n_events += len(res.events)
    slope = np.polyfit(np.log(Ls), np.log(np.abs(errs)), 1)[0]
    return [
        check("gap arctan convergence rate", SRC + " (11.2)", "d log|err| / d log L", -1.0, slope, 0.1, scale=1.0),
        check("gap arctan error at L=1000", SRC + " (11.2)", "period error", 0.0, abs(errs[-1]), 1e-4, scale=1.0),
        check("gap arctan error coefficient", SRC + " [C] frequency error -0.0235/L",
              "period error * L at L = 1000 (= -frequency error * L)", 0.0235, errs[-1] * Ls[-1], 0.05),
        claim("gap arctan needs no events", SRC + " (11.2)", "no switching events", n_events == 0),
    ]
