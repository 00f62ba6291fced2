"""Textbook §8.6: relaxation and quasi-harmonic friction self-oscillations."""
from __future__ import annotations

import math

import numpy as np

from fem.modelfile.source import read_toml
from fem.study import simulate
from validation.analytic import friction_ch8 as ref
from validation.registry import case, check, claim
from validation.examples import EXAMPLES

SRC = "textbook §8.6 (digest textbook_ch6-9.md)"
RELAXATION = EXAMPLES / "discrete_ch8_relaxation.toml"
QUASI_HARMONIC = EXAMPLES / "discrete_ch8_quasi_harmonic.toml"
QUASI_HARMONIC_SET = (0.02, -0.07, 0.05, 2.0)
"""(b, h1, h3, v0) of examples/discrete_ch8_quasi_harmonic.toml."""


def drive(v0, b=0.0, t_end=1.0, static=None, **extra) -> dict:
    """Fig. 8.10 as examples/discrete_ch8_relaxation.toml holds it (link -- spring c -- body m with
    friction F0 static / F1 kinetic, m = 1, c = 1e4, F1 = 2, F0 = 2.4905), the link driven at v0, with a
    dashpot b in parallel with the spring where a case adds one; ``static`` replaces F0."""
    doc = read_toml(RELAXATION)
    doc["driver"][0]["velocity"] = v0
    if static is not None:
        doc["friction"][0]["static"] = static
    if b:
        doc["damper"] = [{"between": ["link", "body"], "c": b}]
    doc["simulation"] = {"t_end": t_end, **extra}
    return doc


def extrema(t, q, qd):
    """Extrema of q from samples (t, q, q') by cubic Hermite interpolation where q' changes sign."""
    out = []
    for k in range(t.size - 1):
        h = t[k + 1] - t[k]
        if h <= 0 or qd[k] == 0 or qd[k] * qd[k + 1] > 0:
            continue
        g0, g1, d0, d1 = q[k], q[k + 1], qd[k] * h, qd[k + 1] * h
        c2 = 3 * (g1 - g0) - 2 * d0 - d1
        c3 = d0 + d1 - 2 * (g1 - g0)
        roots = np.roots([3 * c3, 2 * c2, d0]) if c3 or c2 else []
        for r in np.atleast_1d(roots):
            if abs(r.imag) < 1e-12 and 0 <= r.real <= 1:
                s = r.real
                out.append(g0 + s * (d0 + s * (c2 + s * c3)))
                break
    return np.array(out)


@case("discrete_ch8_relaxation", group="discrete")
def relaxation_undamped():
    """§8.6 V8.6-a: undamped stick-slip period (8.38)-(8.39), slip time 2(pi - phi0)/k, stick time
    2 dF/(c v0), for m = 1, c = 1e4 (k = 100), F1 = 2, dF = 0.4905, v0 = 0.001 .. 0.05.

    (8.38) is exact for this piecewise-linear model (restick rule "static"), so the tolerance is
    1e-9 relative: exact propagation and event location give ~1e-14.  The model is
    examples/discrete_ch8_relaxation.toml (v0 = 0.01 there; the case sweeps v0).
    """
    out = []
    m, c, F1, dF = 1.0, 1e4, 2.0, 0.4905
    k = math.sqrt(c / m)
    for v0 in (0.001, 0.005, 0.01, 0.05):
        r = ref.stick_slip_period(k, c, dF, v0)
        res = simulate(drive(v0, t_end=(F1 + dF) / (c * v0) + 4.5 * r["period"]))
        slips, sticks = res.event_times("slip"), res.event_times("stick")
        T = slips[-1] - slips[-2]
        st = sticks[(sticks > slips[-2])][0]
        tag = f"v0={v0:g}"
        out.append(check(f"ch8 period ({tag})", SRC + " (8.38)", "period (s)", r["period"], T, 1e-9))
        out.append(check(f"ch8 slip time ({tag})", SRC + " (8.37)-(8.38)", "slip time (s)", r["slip_time"],
                         st - slips[-2], 1e-9))
        out.append(check(f"ch8 stick time ({tag})", SRC + " (8.38)", "stick time (s)", r["stick_time"],
                         slips[-1] - st, 1e-9))
        out.append(check(f"ch8 detected period ({tag})", SRC + " (8.38)", "period from the detector (s)",
                         r["period"], res.period or np.nan, 1e-9))
    out.append(check("ch8 worked number tau (v0=0.01)", SRC + " V8.6-a", "tau (s), digest value 0.0635215",
                     0.0635215, ref.stick_slip_period(k, c, dF, 0.01)["period"], 1e-6))
    return out


def _sticks_again(v0, m, c, b, F0):
    """Whether the body sticks again after its first slip (m, c, F0 set the run length only)."""
    tb = max(F0 - b * v0, 0.0) / (c * v0)
    res = simulate(drive(v0, b=b, t_end=tb + 3 * 2 * math.pi / math.sqrt(c / m), static=F0))
    slips = res.event_times("slip")
    return res.event_times("stick")[res.event_times("stick") > slips[0]].size > 0 if slips.size else True


@case("discrete_ch8_critical_speed", group="discrete")
def critical_speed():
    """§8.6 V8.6-b: critical drive speed with viscous damping (book example k = 100 s^-1,
    df = 0.05, lambda = 0.2, so dF = m g df, b = lambda k m / pi).

    * Simulator vs the exact tangency computed independently from the closed-form damped slip
      motion (dashpot loading the body during stick, as the model Fig. 8.10 implies): 1e-6
      relative (bisection on the drive speed to 1e-9; grazing detection resolves dips of ~1e-12).
    * Simulator vs the book's approximate (8.43)-(8.44): within 6 % -- the book's lambda* and the
      breakaway point neglect the dashpot load in stick; the digest shows the two modelling
      variants at +5.3 % / -4.4 % of (8.44).  Book's printed 7.42 mm/s vs (8.44) evaluated: 1e-3.
    * Below v0* stick-slip persists (0.8 v0*), above it the motion decays to steady sliding (1.2 v0*).
    * The stick-slip period just below v0* against (8.46) tau* = ds*/v0*: 2e-3 (the book's ds*
      neglects the damping of the slip arc; the simulated value differs by 4e-4), and against the
      printed 6.36e-2 s: 1e-3 (half a unit of the printed digit is 8e-4).
    * The book's printed numbers (8.44)-(8.46): v0* = 0.741e-2 m/s and ds* = 0.471 mm, with g = 9.8 as
      the book computes (with g = 9.81 they would be 0.7417e-2 and 0.4717: an earlier version of this
      case quoted 7.42e-3, which is not what the book prints), at half a unit of the printed digit.
    The model is examples/discrete_ch8_relaxation.toml with the dashpot b added and F0 = F1 + m g df
    for g = 9.8 (the file holds V8.6-a's F0 with g = 9.81, which the digest's 0.0635215 s uses).
    """
    m, k, g, df, lam = 1.0, 100.0, 9.8, 0.05, 0.2     # g = 9.8: the book's printed v0*, ds* follow from it exactly
    c = k * k * m
    dF = m * g * df
    F1 = 2.0
    F0 = F1 + dF
    b = lam * k * m / math.pi
    book = ref.critical_speed_book(k, c, dF, lam)
    exact = ref.critical_speed_exact(m, c, b, F0, F1)
    lo, hi = 0.8 * exact, 1.2 * exact
    stick_lo, stick_hi = _sticks_again(lo, m, c, b, F0), _sticks_again(hi, m, c, b, F0)
    a, z = lo, hi
    while z - a > 1e-9 * exact:
        mid = 0.5 * (a + z)
        if _sticks_again(mid, m, c, b, F0):
            a = mid
        else:
            z = mid
    vsim = 0.5 * (a + z)
    near = simulate(drive(vsim * (1 - 1e-6), b=b, t_end=1.0, static=F0))
    return [
        check("ch8 period at the critical speed vs (8.46)", SRC + " (8.46)", "tau* (s)", book["tau"],
              near.period or float("nan"), 2e-3),
        check("ch8 period at the critical speed vs printed", SRC + " example", "tau* (s), printed 6.36e-2", 6.36e-2,
              near.period or float("nan"), 1e-3),
        claim("ch8 stick-slip persists at 0.8 v0*", SRC + " (8.44)", "stick after the first slip", stick_lo),
        claim("ch8 steady sliding at 1.2 v0*", SRC + " (8.44)", "no stick after the first slip", not stick_hi),
        check("ch8 critical speed vs exact tangency", SRC + " (8.41)-(8.42) exact", "v0* (m/s)", exact, vsim, 1e-6),
        check("ch8 critical speed vs book (8.44)", SRC + " (8.43)-(8.44)", "v0* (m/s)", book["v0"], vsim, 0.06),
        check("ch8 book example number", SRC + " example", "v0* (m/s), printed 0.741e-2", 0.741e-2, book["v0"],
              0.0005 / 0.741),
        check("ch8 book example jump", SRC + " (8.46) example", "ds* (mm), printed 0.471", 0.471, 1e3 * book["ds"],
              0.0005 / 0.471),
        check("ch8 phi0* of the example", SRC + " (8.43)", "phi0* (rad), printed 0.584", 0.584, book["phi0"], 1e-3),
    ]


@case("discrete_ch8_quasi_harmonic", group="discrete", slow=True)
def quasi_harmonic():
    """§8.6 V8.6-c: quasi-harmonic self-oscillation on a falling friction characteristic,
    F(v) = 1 + h1 (v - v0) + h3 (v - v0)^3 (as the law a0 + a1 v + a2 v^2 + a3 v^3 in the body
    velocity v > 0), m = c = 1, viscous b in parallel with the spring.  Amplitude vs (8.55).

    Tolerance 2e-3 relative: (8.55) is first-order harmonic balance; its error is O(h3 A^2 k^2 / |b + h1|)
    higher harmonics (the digest's independent simulations differ from (8.55) by 2e-4 .. 9e-4).
    The mean deformation is -h0/c = -1 (exact, 1e-6 of the amplitude).
    The model is examples/discrete_ch8_quasi_harmonic.toml (the first parameter set, run to t = 160);
    the damper, the drive speed, the start on the cycle and the friction polynomial are set from each
    (b, h1, h3, v0) as computed here (the file's printed a0 = 0.74, a2 = -0.3 and x0 differ from them in
    the last bit, which moves the measured amplitude by 3e-8 -- far inside the tolerance, but the
    catalogue's numbers are kept to 1e-12).
    """
    out = []
    for (b, h1, h3, v0) in (QUASI_HARMONIC_SET, (0.05, -0.06, 0.2, 1.5)):
        A = ref.quasi_harmonic_amplitude(b, h1, h3, 1.0)
        a0 = 1 - h1 * v0 - h3 * v0 ** 3
        a1, a2, a3 = h1 + 3 * h3 * v0 ** 2, -3 * h3 * v0, h3
        doc = read_toml(QUASI_HARMONIC)
        doc["body"][0].update(x0=-1.0 + A, v0=v0)
        doc["driver"][0]["velocity"] = v0
        doc["damper"][0]["c"] = b
        doc["friction"][0].update(kinetic=a0, viscous=a1, quadratic=a2, cubic=a3)
        doc["simulation"]["t_end"] = 160.0
        res = simulate(doc)
        q, qd = res.x[0] - res.x[1], res.v[0] - res.v[1]
        sel = res.t > res.t[-1] - 30.0
        ext = extrema(res.t[sel], q[sel], qd[sel])
        amp = 0.5 * (ext.max() - ext.min())
        mean = 0.5 * (ext.max() + ext.min())
        tag = f"b={b}, h1={h1}, h3={h3}"
        out.append(check(f"ch8 quasi-harmonic amplitude ({tag})", SRC + " (8.55)", "A", A, amp, 2e-3))
        out.append(check(f"ch8 quasi-harmonic mean ({tag})", SRC + " (8.49)", "mean deformation", -1.0, mean, 1e-3,
                         scale=A))
        out.append(claim(f"ch8 quasi-harmonic: no stick ({tag})", SRC + " (8.55) validity q'max < v0",
                         "no friction events", len(res.events) == 0))
    return out
