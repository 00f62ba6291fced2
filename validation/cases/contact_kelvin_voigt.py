"""The contact with stiffness and damping switched on at closure (textbook §11.2-11.3): the element
added through the element protocol alone (discrete/nonsmooth/elements/contact.py)."""
from __future__ import annotations

import math

import numpy as np

from fem.study import simulate
from validation.analytic.contact_refs import SEC_11_2, kelvin_voigt_impact
from validation.registry import case, check, claim, printed

SRC = "textbook §11.2 (11.3)-(11.4), digest textbook_ch10-11.md"


@case("contact_kelvin_voigt_impact", group="discrete")
def impact_closed_form():
    """A unit mass at 1 m/s into a stop with k = 100 and c = 2 zeta sqrt(k m), zeta = 0.05 and 0.3: the
    contact lasts pi/omega_d and the mass leaves at e = exp(-pi zeta/sqrt(1 - zeta^2)) (the damped
    half-sine, :func:`kelvin_voigt_impact`).  The solver propagates the contact exactly (expm) and
    locates its closing and opening to round-off: tolerance 1e-10; the energy balance counts the
    dashpot's work (1e-10)."""
    out = []
    k, m, x0 = 100.0, 1.0, 0.01
    for zeta in (0.05, 0.3):
        c = 2 * zeta * math.sqrt(k * m)
        ref = kelvin_voigt_impact(k, c, m, 1.0)
        doc = {"body": [{"name": "m", "inertia": m, "x0": x0, "v0": -1.0}],
               "contact": [{"name": "stop", "body": "m", "k": k, "c": c, "lower": 0.0}],
               "simulation": {"t_end": x0 + ref["duration"] + 0.05, "output_step": ref["duration"] / 2000}}
        r = simulate(doc)
        t_close = r.event_times("contact_close")
        t_open = r.event_times("contact_open")
        tag = f"zeta = {zeta}"
        out.append(check(f"contact duration ({tag})", "damped half-sine pi/omega_d", "t_open - t_close",
                         ref["duration"], t_open[0] - t_close[0], 1e-10))
        v_out = r.v[0, -1]
        out.append(check(f"restitution ({tag})", "exp(-pi zeta/sqrt(1 - zeta^2))", "exit speed / impact speed",
                         ref["restitution"], v_out, 1e-10))
        out.append(check(f"largest penetration ({tag})", "damped half-sine", "-min x (samples of T/2000: "
                         "error <= (pi/2000)^2/8 of the peak)", ref["max_penetration"], -np.min(r.x[0]), 4e-7))
        out.append(claim(f"energy balance ({tag})", "dashpot work = energy lost", "energy_error <= 1e-10",
                         r.energy_error <= 1e-10, note=f"{r.energy_error:.2e}"))
    return out


@case("contact_11_2_impact_excitation", group="discrete")
def impact_excitation_11_2():
    """(11.4) in the digest's reading q'' + [2 delta N q' + N^2 (q - Delta sign q)] u(|q| - Delta) = cos phi
    with N = 30, delta = 0.03, s = 2 Delta = 1e-3 (Fig. 11.2-11.3): the steady state (39 periods to
    settle: the contact's decay e^(-delta N phi) is 1e-300 by then) has, per half-cycle, one long flight
    across the gap and a short second one, contact angles as printed by the digest (4 decimals: half a
    unit of the last digit, 5e-5 rad, as absolute tolerance relative to 2 pi), max |q| = 1.78e-3 and
    max |q''| = 0.46 (half a printed digit).  The estimate (11.7) of the first flight (0.18171 rad with the
    corrected third derivative) is the book's own approximation: it overestimates (claim)."""
    d = SEC_11_2
    N, delta, D = d["N"], d["delta"], d["gap"] / 2
    T = 2 * math.pi
    base = {"body": [{"name": "q", "inertia": 1.0}],
            "contact": [{"name": "gap", "body": "q", "k": N * N, "c": 2 * delta * N, "delta": D}],
            "force": [{"body": "q", "amplitude": 1.0, "omega": 1.0, "phase": math.pi / 2}]}
    r = simulate(dict(base, simulation={"t_end": 39 * T}))
    base["body"][0].update(x0=float(r.x[0, -1]), v0=float(r.v[0, -1]))
    r = simulate(dict(base, simulation={"t_end": T, "output_step": T / 4000}))
    out = []
    for kind, printed_angles in (("contact_open", d["opens"]), ("contact_close", d["closes"])):
        got = r.event_times(kind)
        for text, phi in zip(printed_angles, got):
            out.append(check(f"{kind} angle {text}", SRC + ": digest simulation", f"{kind} phi mod 2 pi",
                             float(text), phi, 0.5e-4 / T, scale=T))
        out.append(check(f"{kind} events per period", SRC, f"number of {kind} per period", len(printed_angles),
                         got.size, 0.0, scale=1.0))
    q, v, t = r.x[0], r.v[0], r.t
    a = np.cos(t) - (2 * delta * N * v + N * N * (q - D * np.sign(q))) * (np.abs(q) > D)
    for key, value in (("max_displacement", np.max(np.abs(q))), ("max_acceleration", np.max(np.abs(a)))):
        ref, tol = printed(d[key])
        out.append(check(key.replace("_", " "), SRC + ": digest simulation", key, ref, value, tol))
    flight = r.event_times("contact_close")[0] - r.event_times("contact_open")[0]
    out.append(claim("(11.7) overestimates the first flight", "textbook (11.7) with |Pi'''| (digest erratum)",
                     "0.18171 > simulated flight", float(d["flight_estimate"]) > flight, note=f"{flight:.5f} rad"))
    out.append(claim("energy balance", "contact work = energy lost", "energy_error <= 1e-9", r.energy_error <= 1e-9,
                     note=f"{r.energy_error:.2e}"))
    return out
