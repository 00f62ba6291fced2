"""The motor as a model element in the time domain (textbook §5.10, (5.54)-(5.58); issue 14 item 4):
``[[motor]]`` with T_d M' + M = (1 - omega/omega_d0)/nu_d, the torque one more state of the event
solver's exact pieces, driving a rigid rotor J against a constant load torque M_L.

Reference: the closed-form response of the linear pair J omega' = M - M_L, T M' + M = (1 - omega/omega0)/nu
from rest with M(0) = 0 -- omega = omega_inf + e^(-n t) (A cos k1 t + B sin k1 t), n = 1/(2T),
k^2 = 1/(nu omega0 J T), k1 = sqrt(k^2 - n^2) (aperiodic: two real roots), omega_inf =
omega0 (1 - nu M_L) -- and the angle, its integral; printed k1 = 129.455 rad/s (J = 0.05) of the
catalogue example measured from the run's zero crossings of omega - omega_inf.
"""
from __future__ import annotations

import math

import numpy as np

from fem.study import Study
from validation.examples import example_doc
from validation.registry import case, check, claim, printed

SRC = "textbook §5.10 (5.54)-(5.58) (digest textbook_ch2-5.md §5.10)"
EXAMPLE = "motor_runup.toml"


def runup_closed_form(t, *, J, omega0, nu, T, load):
    """(angle, speed, torque) at t from rest, M(0) = 0 (T > 0; under- or over-damped roots)."""
    t = np.asarray(t, dtype=float)
    w_inf = omega0 * (1.0 - nu * load)
    # deviation x = omega - w_inf: x'' + x'/T + k^2 x = 0, x(0) = -w_inf, x'(0) = (M(0) - load)/J
    k2 = 1.0 / (nu * omega0 * J * T)
    x0, xd0 = -w_inf, -load / J
    roots = np.roots([1.0, 1.0 / T, k2])
    # x = a1 e^(r1 t) + a2 e^(r2 t) (complex for an oscillatory run-up), and its integral
    r1, r2 = roots.astype(complex)
    a2 = (xd0 - r1 * x0) / (r2 - r1)
    a1 = x0 - a2
    x = (a1 * np.exp(r1 * t) + a2 * np.exp(r2 * t)).real
    ix = (a1 * (np.exp(r1 * t) - 1) / r1 + a2 * (np.exp(r2 * t) - 1) / r2).real
    xd = (a1 * r1 * np.exp(r1 * t) + a2 * r2 * np.exp(r2 * t)).real
    return w_inf * t + ix, w_inf + x, load + J * xd


def _run(doc):
    r = Study.parse(doc).simulate()
    phi, w = r.series("rotor")
    return r, r.t, phi, w


@case("timedomain_motor_runup", group="motor")
def motor_runup():
    """examples/motor_runup.toml: the §5.10 catalogue motor (omega0 = 157.0796 rad/s, nu = 4.19692e-4,
    T = 0.0172372 s) on J = 0.05 kg m^2 against M_L = 50 N m.  Speed and angle of the event run against
    the closed form: 1e-10 relative to omega_inf (resp. omega_inf t_end) -- the motor is affine, its pieces
    are exact matrix exponentials, so only round-off remains.  The motor torque (recorded element force)
    against the closed form J omega' + M_L, 1e-9 relative to M_max.  The oscillation k1 of the run-up,
    pi over the mean spacing of the zero crossings of omega - omega_inf (linear interpolation on a 1e-5 s
    grid: error ~ n dt^2/4 relative ~1e-8), against the printed 129.455 (half a digit).  J = 2.0: the
    printed aperiodic case -- without load omega rises monotonically to omega0 (no overshoot), 1e-10 to the
    closed form with two real roots.  T = 0 (static
    characteristic): omega = omega_inf (1 - e^(-t/(nu omega0 J))), 1e-10.  Energy balance of the runs: the
    motor's work (category "motor") equals the kinetic energy gained plus the load's work, 1e-10."""
    out = []
    doc = example_doc(EXAMPLE)
    mot = doc["motor"][0]
    J, om0, nu, T = doc["body"][0]["inertia"], mot["omega0"], mot["nu"], mot["T"]
    load = -doc["force"][0]["value"]
    r, t, phi, w = _run(doc)
    ref_phi, ref_w, ref_M = runup_closed_form(t, J=J, omega0=om0, nu=nu, T=T, load=load)
    w_inf = om0 * (1 - nu * load)
    out.append(check("motor run-up", "closed form, linear motor + rigid rotor", "max |omega - omega_ref| / omega_inf",
                     0.0, float(np.max(np.abs(w - ref_w))) / w_inf, 1e-10, scale=1.0))
    out.append(check("motor run-up", "closed form, linear motor + rigid rotor", "max |phi - phi_ref| / (omega_inf t_end)",
                     0.0, float(np.max(np.abs(phi - ref_phi))) / (w_inf * t[-1]), 1e-10, scale=1.0))
    M = r.element_forces[r.elements.index("motor:motor")]
    out.append(check("motor run-up", "closed form, linear motor + rigid rotor", "max |M - M_ref| / max|M_ref|",
                         0.0, float(np.max(np.abs(M - ref_M)) / np.max(np.abs(ref_M))), 1e-9, scale=1.0))
    out.append(check("motor run-up", "steady speed omega0 (1 - nu M_L)", "omega(t_end)", w_inf, w[-1], 1e-6,
                     note="e^(-n t_end) = %.1e of the initial deviation remains" % math.exp(-t[-1] / (2 * T))))
    out.append(check("motor run-up", "energy balance", "|energy error|", 0.0, abs(r.energy_error), 1e-10, scale=1.0))
    out.append(check("motor run-up", "energy balance: motor work = J omega^2/2 + M_L phi", "motor work [J]",
                     0.5 * J * w[-1] ** 2 + load * phi[-1], r.work_parts["motor"], 1e-10))
    # k1 from the zero crossings, a fine output grid
    fine = dict(doc, simulation=dict(doc["simulation"], t_end=0.1, output_step=1e-5))
    _, tf, _, wf = _run(fine)
    d = wf - w_inf
    i = np.flatnonzero(np.sign(d[1:]) != np.sign(d[:-1]))
    i = i[d[i] != 0]
    tz = tf[i] - d[i] * (tf[i + 1] - tf[i]) / (d[i + 1] - d[i])
    k1 = math.pi / float(np.mean(np.diff(tz)))
    v, tol = printed("129.455")
    out.append(check("motor run-up", "digest §5.10 table (J = 0.05)", "k1 from the run's zero crossings [rad/s]", v, k1,
                     tol, note=f"{tz.size} zero crossings in 0.1 s"))
    # J = 2.0: aperiodic
    heavy = {k: v for k, v in doc.items() if k != "force"}
    heavy = dict(heavy, body=[dict(doc["body"][0], inertia=2.0)], simulation=dict(doc["simulation"], t_end=2.0))
    _, th, _, wh = _run(heavy)
    ref_h = runup_closed_form(th, J=2.0, omega0=om0, nu=nu, T=T, load=0.0)[1]
    out.append(claim("motor run-up", "digest §5.10 table: J = 2.0 aperiodic", "J = 2.0, no load: omega rises "
                     "monotonically, no overshoot of omega0", bool(np.all(np.diff(wh) >= -1e-12 * om0)
                                                                  and np.max(wh) <= om0 * (1 + 1e-12))))
    out.append(check("motor run-up", "closed form (two real roots)", "J = 2.0, no load: max |omega - omega_ref| / omega0",
                     0.0, float(np.max(np.abs(wh - ref_h))) / om0, 1e-10, scale=1.0))
    # static characteristic
    static = dict(doc, motor=[dict(mot, T=0.0)])
    _, ts, _, ws = _run(static)
    tau = nu * om0 * J
    out.append(check("motor run-up", "closed form, static characteristic (first order)",
                     "T = 0: max |omega - omega_inf (1 - e^(-t/(nu omega0 J)))| / omega_inf", 0.0,
                     float(np.max(np.abs(ws - w_inf * (1 - np.exp(-ts / tau))))) / w_inf, 1e-10, scale=1.0))
    return out
