"""Programme (cam) motion in the event solver (textbook §2.5, §6.1-6.2; issue 14 item 2): a
``[[driver]] programme = {..}`` integrated exactly -- each piece of the cam law is a sub-state of the
exogenous vector, its knots are time events -- against

* the exact elastic follower of discrete.motion.follower (closed-form particular solutions on every
  piece, 2x2 transition matrices; the book's (6.1)-(6.5)) started from rest, with no clearance;
* with a backlash between follower and output link (examples/cam_clearance.toml): an independent
  DOP853 integration of the 2-DOF piecewise-linear system, restarted at the cam's knots and at the
  located contact events.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from discrete.motion.cam_laws import dwell_rise_dwell_return
from discrete.motion.follower import PiecewiseOscillator
from fem.study import Study
from validation.examples import example_doc
from validation.registry import case, check, claim

SRC = "textbook §6.1-6.2 (digest textbook_ch6-9.md §6.2)"
EXAMPLE = "cam_clearance.toml"


def _follower_doc(doc: dict, t_end: float) -> dict:
    """The example without its output link and backlash: the cam, the elastic transmission, the follower."""
    return {"title": "cam follower", "body": [doc["body"][0]], "driver": doc["driver"], "spring": [doc["spring"][0]],
            "simulation": {"t_end": t_end, "output_step": 2.5e-4}}


def _law(doc: dict):
    p = doc["driver"][0]["programme"]
    return dwell_rise_dwell_return(p["stroke"], p["rise"], p["top_dwell"], p["return"], law=p["law"],
                                   return_law=p.get("return_law")).in_time(p["cam_speed"])


@case("timedomain_cam_follower", group="cam")
def cam_follower():
    """examples/cam_clearance.toml without the backlash: cycloidal rise / harmonic return (h = 20 mm,
    100/60/100 deg, cam speed 20 rad/s), k0 = 170 rad/s, lambda = 0.2, from rest, three cam cycles.
    The deformation q = y - x of the event run against the exact follower response (closed form): 1e-9
    relative to max|q| (exact pieces: round-off only; the knots are time events located to round-off).
    The driver's recorded position against the cam law itself (1e-12 of the stroke).  One knot event per
    piece of the cycle; the energy balance (driver work = energy change + damper loss) to 1e-10."""
    out = []
    doc = example_doc(EXAMPLE)
    lt = _law(doc)
    cycle = lt.span
    r = Study.parse(_follower_doc(doc, 3 * cycle)).simulate()
    y = r.series("follower")[0]
    x = r.series("cam")[0]
    t = r.t
    m = doc["body"][0]["inertia"]
    k = math.sqrt(doc["spring"][0]["k"] / m)
    n = doc["spring"][0]["c"] / (2 * m)
    exact = PiecewiseOscillator.follower(lt, k, n).response(t, z0=np.zeros(2))[:, 0]
    q = y - x
    out.append(check("cam follower", "exact follower (discrete.motion.follower, (6.1)-(6.5))",
                     "max |q - q_exact| / max|q_exact|", 0.0, float(np.max(np.abs(q - exact)) / np.max(np.abs(exact))),
                     1e-9, scale=1.0, note=f"max|q| = {np.max(np.abs(exact)):.4e} m"))
    stroke = doc["driver"][0]["programme"]["stroke"]
    out.append(check("cam follower", "the cam law (PiecewiseLaw)", "max |x - law(t)| / stroke", 0.0,
                     float(np.max(np.abs(x - lt(t)))) / stroke, 1e-12, scale=1.0))
    knots = r.event_times("knot")
    expected = lt.knots[1:][None, :] + cycle * np.arange(3)[:, None]
    expected = expected.ravel()[expected.ravel() <= 3 * cycle * (1 + 1e-12)]
    out.append(claim("cam follower", "one time event per knot", "knot events at the law's knots",
                     knots.size == expected.size and bool(np.allclose(knots, expected, rtol=0, atol=1e-12 * cycle)),
                     note=f"{knots.size} knot events"))
    out.append(check("cam follower", "energy balance", "|energy error|", 0.0, abs(r.energy_error), 1e-10, scale=1.0))
    return out


def clearance_reference(doc: dict, t_out: np.ndarray):
    """(y_follower, y_output, contact-change times) of the cam_clearance example by DOP853 (rtol 1e-12),
    piece by piece between the cam's knots, with the gap's boundary crossings as terminal events."""
    lt = _law(doc)
    v_law = lt.derivative(1)
    m1, m2 = doc["body"][0]["inertia"], doc["body"][1]["inertia"]
    k1, c1 = doc["spring"][0]["k"], doc["spring"][0]["c"]
    k2 = doc["spring"][1]["k"]
    gap = doc["gap"][0]
    kc, dl = gap["k"], gap["delta"]
    t_end = doc["simulation"]["t_end"]

    def rhs(mode):
        def f(t, z):
            y1, v1, y2, v2 = z
            s = y2 - y1
            F = -kc * (s - dl) if mode == 1 else (-kc * (s + dl) if mode == -1 else 0.0)
            x, xd = float(lt(t)), float(v_law(t))
            return [v1, (-k1 * (y1 - x) - c1 * (v1 - xd) - F) / m1, v2, (-k2 * y2 + F) / m2]
        return f

    breaks = [b for c in range(int(t_end / lt.span) + 2) for b in lt.knots[:-1] + c * lt.span if 0 < b < t_end]
    breaks = [0.0] + sorted(breaks) + [t_end]
    z = np.zeros(4)
    mode = 0
    segments, changes = [], []
    for a, b in zip(breaks, breaks[1:]):
        t = a
        while t < b:
            def open_hi(tt, zz):
                return zz[2] - zz[0] - dl
            def open_lo(tt, zz):
                return zz[2] - zz[0] + dl
            if mode == 0:
                evs = [open_hi, open_lo]
                open_hi.direction, open_lo.direction = 1, -1
            elif mode == 1:
                evs = [open_hi]
                open_hi.direction = -1
            else:
                evs = [open_lo]
                open_lo.direction = 1
            for e in evs:
                e.terminal = True
            sol = solve_ivp(rhs(mode), (t, b), z, method="DOP853", rtol=1e-12, atol=1e-15, events=evs, dense_output=True)
            seg_end = sol.t[-1]
            segments.append((t, seg_end, sol.sol))
            z = sol.y[:, -1]
            t = seg_end
            if sol.status == 1:
                hit = [i for i, te in enumerate(sol.t_events) if te.size]
                changes.append(t)
                if mode == 0:
                    mode = 1 if evs[hit[0]] is open_hi else -1
                else:
                    mode = 0
    starts = np.array([a for a, _, _ in segments])
    which = np.clip(np.searchsorted(starts, t_out, side="right") - 1, 0, len(segments) - 1)
    Z = np.zeros((t_out.size, 4))
    for j in np.unique(which):
        sel = which == j
        Z[sel] = segments[j][2](t_out[sel]).T
    return Z[:, 0], Z[:, 2], np.array(changes)


@case("timedomain_cam_clearance", group="cam")
def cam_clearance():
    """examples/cam_clearance.toml: the follower drives an output link (0.5 kg, return spring 500 N/m)
    through a backlash of +-0.5 mm with contact stiffness 2e5 N/m.  Against an independent DOP853
    integration (rtol 1e-12; restarts at the knots, contact changes located as events) over the first
    cam cycle: follower and output positions 1e-7 relative to the stroke, the contact-change times 1e-7
    of the cycle, the same contact changes (observed: 4e-13 after 0.05 s, 5e-9 at the cycle's end).  The
    motion with the backlash is sensitive to its initial state: any difference grows ~10x per 0.05 s (a
    finite-time Lyapunov exponent ~ 40/s), so the two methods part after the first cycle; the case
    shows this is the dynamics, not an error, by perturbing the event run's initial output position by
    1e-14 m (5e-13 of the stroke): the perturbed event run parts from the unperturbed one by the end of
    the run (t = 1 s) as much as from the reference (> 1e-4 of the stroke).  Energy balance of the event
    run (driver work = energy change + damper loss) to 1e-10."""
    out = []
    doc = example_doc(EXAMPLE)
    r = Study.parse(doc).simulate()
    lt = _law(doc)
    first = r.t <= lt.span
    y1, y2 = r.series("follower")[0], r.series("output")[0]
    r1, r2, changes = clearance_reference(doc, r.t)
    stroke = doc["driver"][0]["programme"]["stroke"]
    src = "DOP853 with located contact events (second method)"
    for nm, a, b in (("follower", y1, r1), ("output", y2, r2)):
        out.append(check("cam with clearance", src, f"first cycle: max |y_{nm} - y_ref| / stroke", 0.0,
                         float(np.max(np.abs(a[first] - b[first]))) / stroke, 1e-7, scale=1.0))
    ev = np.sort(np.concatenate([r.event_times("contact_close"), r.event_times("contact_open")]))
    ev, ref_ev = ev[ev <= lt.span], changes[changes <= lt.span]
    out.append(check("cam with clearance", src, "first cycle: number of contact changes", ref_ev.size, ev.size, 0.0))
    if ev.size == ref_ev.size and ev.size:
        out.append(check("cam with clearance", src, "first cycle: max |t_contact - t_ref| / cycle", 0.0,
                         float(np.max(np.abs(ev - ref_ev))) / lt.span, 1e-7, scale=1.0))
    pert = dict(doc, body=[doc["body"][0], dict(doc["body"][1], x0=1e-14)])
    rp = Study.parse(pert).simulate()
    yp = rp.series("output")[0]
    d_pert = abs(float(yp[-1] - y2[-1])) / stroke
    d_ref = abs(float(r2[-1] - y2[-1])) / stroke
    out.append(claim("cam with clearance", "sensitivity to the initial state", "a 5e-13 perturbation parts the run "
                     "from itself by t = 1 s as much as from the reference (> 1e-4 stroke)",
                     d_pert > 1e-4 and d_ref > 1e-4, note=f"|y(1 s) - y_perturbed| = {d_pert:.2e}, "
                     f"|y(1 s) - y_ref| = {d_ref:.2e} (stroke units)"))
    out.append(check("cam with clearance", "energy balance", "|energy error|", 0.0, abs(r.energy_error), 1e-10,
                     scale=1.0))
    return out
