"""The pulsating spring in the time domain (textbook §7.3, (7.1), (7.30); issue 14 item 1): a
``[[spring]] modulation = {depth, omega, phase}`` integrated by the event solver (numeric pieces of
the time-dependent law, DOP853 at rtol 1e-12, with the exact friction events) against

* the Floquet analysis of the same linear system (discrete.linear.parametric: Magnus/expm monodromy,
  an independent method) -- monodromy matrices over one pulsation period, inside and outside the
  principal tongue and across the viscous threshold eps* = psi/pi;
* the friction-limited threshold A* = 8|P|/(pi c0 eps) of (7.30) (printed 0.12732 for P = 0.01,
  c0 = 1, eps = 0.2) and the independent event-driven reference integrator of
  validation.analytic.parametric (turning points, stick).
"""
from __future__ import annotations

import math

import numpy as np

from discrete.linear.harmonic import Damping
from discrete.linear.parametric import Modulation, ParametricProblem
from discrete.lumped import Body, Link, LumpedModel
from fem.study import Study
from validation.analytic import parametric as ref
from validation.registry import case, check, claim, printed

SRC = "textbook §7.3 (7.30) (digest textbook_ch6-9.md V7.3-d)"
SRC_F = "Floquet monodromy (discrete.linear.parametric, Magnus/expm)"


def _doc(depth, omega, phase=0.0, *, c=0.0, x0=0.0, v0=0.0, t_end=1.0, friction=None):
    doc = {"body": [{"name": "m", "inertia": 1.0, "x0": x0, "v0": v0}],
           "spring": [{"between": ["ground", "m"], "k": 1.0, **({"c": c} if c else {}),
                       "modulation": {"depth": depth, "omega": omega, "phase": phase}}],
           "simulation": {"t_end": t_end}}
    if friction is not None:
        doc["friction"] = [{"name": "dry", "body": "m", "kinetic": friction}]
    else:
        doc["force"] = [{"body": "m", "value": 0.0}]          # a simulation needs an element or a force
    return doc


def time_domain_monodromy(depth: float, omega: float, c: float = 0.0) -> np.ndarray:
    """[q, q'](T) from the unit initial states over one period T = 2 pi/omega (event solver)."""
    T = 2 * math.pi / omega
    cols = []
    for x0, v0 in ((1.0, 0.0), (0.0, 1.0)):
        r = Study.parse(_doc(depth, omega, c=c, x0=x0, v0=v0, t_end=T)).simulate()
        x, v = r.series("m")
        cols.append([x[-1], v[-1]])
    return np.array(cols).T


def floquet_monodromy(depth: float, omega: float, c: float = 0.0) -> np.ndarray:
    ls = LumpedModel(bodies=[Body("m", 1.0)], springs=[Link(("ground", "m"), 1.0)],
                     dampers=[Link(("ground", "m"), c)] if c else []).linear_system()
    pp = ParametricProblem.build(ls, [Modulation(target="stiffness", depth=1.0)], damping=Damping("viscous"))
    fl = pp.floquet(omega, depth, tolerance=1e-12)
    return pp.physical_monodromy(fl.monodromy)


@case("timedomain_parametric_floquet", group="parametric")
def parametric_floquet():
    """m = 1, c0 = 1 (k0 = 1), c(t) = c0 (1 - eps sin Omega t).  Monodromy of the time run against the
    Floquet monodromy: eps = 0.1 at Omega = 2 (inside the first tongue (1.94970, 2.04968): rho > 1) and
    at Omega = 2.1 (outside: |rho| = 1); viscous damping psi = 0.2 (c = 2 zeta k0, zeta = psi/(4 pi)) at
    eps = 0.9 and 1.1 eps*, eps* = 0.063666 (the Floquet threshold at Omega = 2 k0): rho_max < 1 below,
    > 1 above, in both methods.  Tolerance 1e-8 on the entries (relative to the largest): both monodromies
    are accurate to ~1e-10 (DOP853 at rtol 1e-12 over one period; the Floquet tolerance 1e-12 on the step-
    halving estimate)."""
    out = []
    zeta = 0.2 / (4 * math.pi)
    eps_star = 0.063666
    points = [(0.1, 2.0, 0.0, "eps = 0.1, Omega = 2 (in the tongue)", True),
              (0.1, 2.1, 0.0, "eps = 0.1, Omega = 2.1 (outside)", None),
              (0.9 * eps_star, 2.0, 2 * zeta, "psi = 0.2, eps = 0.9 eps*", False),
              (1.1 * eps_star, 2.0, 2 * zeta, "psi = 0.2, eps = 1.1 eps*", True)]
    for eps, om, c, label, grows in points:
        Pt = time_domain_monodromy(eps, om, c)
        Pf = floquet_monodromy(eps, om, c)
        err = float(np.max(np.abs(Pt - Pf)) / np.max(np.abs(Pf)))
        out.append(check("time-domain monodromy", SRC_F, f"{label}: max |Phi_time - Phi_Floquet| / max|Phi|",
                         0.0, err, 1e-8, scale=1.0))
        rt, rf = (float(np.max(np.abs(np.linalg.eigvals(P)))) for P in (Pt, Pf))
        out.append(check("time-domain monodromy", SRC_F, f"{label}: rho_max", rf, rt, 1e-8))
        if grows is not None:
            out.append(claim("time-domain monodromy", "(7.26) corrected: instability above the threshold",
                             f"{label}: {'growth' if grows else 'decay'} (rho_max {'>' if grows else '<'} 1)",
                             (rt > 1) == grows, note=f"rho_max = {rt:.9f}"))
        else:
            out.append(check("time-domain monodromy", "undamped, outside the tongue: |rho| = 1",
                             f"{label}: rho_max", 1.0, rt, 1e-8))
    return out


def turning_points(result) -> tuple[np.ndarray, np.ndarray, str]:
    """(t, y) of the stops of the friction element (reversals and sticks) from the event list, the
    start included, and the final mode."""
    ev = [e for e in result.events if e.element == "dry" and e.kind in ("reversal", "stick")]
    t = np.array([0.0] + [e.t for e in ev])
    y = np.array([result.series("m")[0][0]] + [e.state["m"]["x"] for e in ev])
    final = "stick" if ev and ev[-1].kind == "stick" else "slip"
    return t, y, final


@case("timedomain_parametric_friction", group="parametric")
def parametric_friction():
    """(7.30) in the package's time domain: m = 1, c0 = 1, eps = 0.2, Omega = 2 = 2 k0, P = 0.01
    (true stick, static = kinetic), from rest at y = A0 with the pulsation phase pi (the favourable
    phase of this start).  A0 = 0.99 A*: the turning-point amplitudes decrease and the body sticks for
    good (reference: stick at t = 90.877 s after 29 turning points); 1.01 A*: they grow beyond 2 A0 by
    t = 200 s.  Every turning point (time and position) against the independent reference integrator:
    1e-7 relative to the largest turning point and to the pulsation period (both integrate the slip pieces by DOP853, rtol
    1e-12 / 1e-11, over up to 60 turning points; the errors add from piece to piece).  The time-domain
    threshold lies within 1.00037 A* +- 0.1 % (the reference's bisection): 0.999 A* decays, 1.001 A*
    grows (first 40 s)."""
    out = []
    P, c0, eps, om = 0.01, 1.0, 0.2, 2.0
    A_star = ref.friction_critical_amplitude(P, c0, eps)
    v, tol = printed("0.12732")
    out.append(check("A* = 8|P|/(pi c0 eps)", SRC, "critical amplitude A*", v, A_star, tol))
    for factor, t_end in ((0.99, 200.0), (1.01, 200.0)):
        r = Study.parse(_doc(eps, om, math.pi, x0=factor * A_star, t_end=t_end, friction=P)).simulate()
        t, y, final = turning_points(r)
        rf = ref.coulomb_parametric_turning_points(factor * A_star, phase=math.pi, P=P, c0=c0, m=1.0, eps=eps,
                                                   omega=om, t_end=t_end)
        amp = np.abs(y)
        tag = f"A0 = {factor:g} A*"
        if factor < 1:
            out.append(claim("friction-limited threshold", SRC, f"{tag}: amplitudes decrease, final stick",
                             bool(np.all(np.diff(amp) < 0)) and final == "stick",
                             note=f"{amp.size - 1} turning points, stick at t = {t[-1]:.6f} s"))
        else:
            out.append(claim("friction-limited threshold", SRC, f"{tag}: amplitudes grow beyond 2 A0",
                             bool(np.all(np.diff(amp) > 0)) and amp[-1] > 2 * amp[0] and final == "slip",
                             note=f"last turning point {amp[-1] / A_star:.1f} A*"))
        n = min(t.size, rf["t"].size)
        out.append(check("friction-limited threshold", "reference integrator (validation.analytic.parametric)",
                         f"{tag}: number of turning points", rf["t"].size, t.size, 0.0))
        out.append(check("friction-limited threshold", "reference integrator (validation.analytic.parametric)",
                         f"{tag}: max |t - t_ref| / (2 pi/Omega)", 0.0,
                         float(np.max(np.abs(t[:n] - rf["t"][:n]))) / (2 * math.pi / om), 1e-7, scale=1.0))
        out.append(check("friction-limited threshold", "reference integrator (validation.analytic.parametric)",
                         f"{tag}: max |y - y_ref| / max|y_ref|", 0.0,
                         float(np.max(np.abs(y[:n] - rf["y"][:n])) / np.max(np.abs(rf["y"][:n]))),
                         1e-7, scale=1.0))
    for factor, grows in ((0.999, False), (1.001, True)):
        r = Study.parse(_doc(eps, om, math.pi, x0=factor * A_star, t_end=40.0, friction=P)).simulate()
        amp = np.abs(turning_points(r)[1])
        d = np.diff(amp)
        out.append(claim("friction-limited threshold", "reference bisection: threshold 1.00037 A*",
                         f"A0 = {factor:g} A*: amplitudes {'grow' if grows else 'decrease'}",
                         bool(np.all(d > 0) if grows else np.all(d < 0)), note=f"{amp.size - 1} turning points, "
                         f"last/first = {amp[-1] / amp[0]:.6f}"))
    return out
