"""Steady truncation control and bifurcations: HB folds, branch points, period doublings and
Neimark-Sacker points against exact or independent references (issue 27).

References, all independent of drivefem's solvers:

* one-DOF piecewise-linear oscillators (two-sided stop, one-sided stop, bilinear impact oscillator):
  exact piecewise-analytic shooting (validation/analytic/piecewise_shooting.py: closed-form motion in
  each region, crossings by Brent's method, the monodromy as the product of the regions' exponentials);
* coupled Duffing oscillators: shooting with scipy's DOP853 (rtol 1e-12) and the variational equation
  (validation/analytic/ode_shooting.py);
* seed 002: the exact event-driven integrator's period map (shooting, finite-difference monodromy), a
  method with no harmonic truncation and no AFT.
"""
from __future__ import annotations

import numpy as np

from discrete.steady import HBModel, ShootingModel
from discrete.steady.piecewise import trig_eval
from fem.study import forced, steady_model
from validation.analytic import ode_shooting as ode
from validation.analytic import piecewise_shooting as pws
from validation.analytic.steady_seed002 import K_NAT, seed002_doc
from validation.registry import case, check, claim

SRC_STOP = "issue 27: two-sided stop (m 2 kg, k 8e4, c 20, [[gap]] k 8e5 delta 1e-3, 60 N); exact piecewise shooting"
SRC_ONE = "pyHarm comparison (../shared/reference/pyharm_comparison.md) stop problem; exact piecewise shooting"
SRC_PD = "bilinear impact oscillator (Shaw & Holmes, J. Sound Vib. 90 (1983) 129, type of model); exact shooting"
SRC_NS = "two coupled Duffing oscillators; independent shooting (DOP853 + variational equation)"
SRC_002 = "seed 002 (Khromov et al. 2012) a = 8.6e-4, simplified model; exact event-driven shooting"


def stop_doc(**steady) -> dict:
    """The two-sided stop of issue 27 (HB, 15 harmonics, omega 100..900 rad/s)."""
    d = {"title": "two-sided stop", "body": [{"name": "mass", "inertia": 2.0}],
         "spring": [{"between": ["ground", "mass"], "k": 8e4}], "damper": [{"between": ["ground", "mass"], "c": 20.0}],
         "gap": [{"name": "stop", "body": "mass", "k": 8e5, "delta": 1e-3}],
         "force": [{"body": "mass", "amplitude": 60.0, "omega": 200.0}],
         "steady": {"method": "hb", "omega": [100.0, 900.0], "harmonics": 15}}
    d["steady"].update(steady)
    return d


STOP = pws.PiecewiseLinearOscillator.gap(2.0, 20.0, 8e4, 8e5, 1e-3, 60.0)


def _state(hb, x, w, phase=0.0):
    """[q, q'] of the HB orbit x (one DOF) at the instant where the force F sin(w t + phase) has phase 0."""
    th = -(w / hb.nu) * phase / w
    return np.array([trig_eval(x, th), (w / hb.nu) * trig_eval(x, th, 1)])


@case("steady_stop_folds_exact", group="steady")
def stop_folds():
    """Issue 27's two-sided stop, HB with 15 harmonics and the kinks integrated exactly: exactly the two
    folds of the exact piecewise-analytic orbits (before: 6 folds and 3 jump intervals, from sampling the
    kink at 256 points).  Exact folds: Newton on P(y; w) = y, det(Phi - I) = 0 of the exact period map
    (584.404326840 and 264.326786256 rad/s; the same to 1e-15 from an independent pseudo-arc-length
    continuation of the exact orbits).  Tolerance 1e-5 in omega: the orbit is C^2 (continuous law), its
    Fourier coefficients decay like k^-4 and the HB-15 fold error measured is 1e-6; issue 27 asks for 1e-3.
    The truncation estimate of every point is within truncation_tol = 1e-3, the fold check with H = 20
    bounds each fold's actual error within a factor 5, and at points with contact the estimate bounds the
    amplitude's actual error against the exact orbit."""
    out = []
    r = forced(stop_doc())
    sm = steady_model(stop_doc())
    hb = HBModel(sm.system, harmonics=15)
    folds = [b for b in r.bifurcations if b.kind == "fold"]
    out.append(claim("exactly two folds (the exact curve's)", SRC_STOP, "number of folds == 2", len(folds) == 2,
                     note=f"HB folds at {[round(b.omega, 5) for b in folds]}"))
    out.append(claim("one jump interval", SRC_STOP, "jump intervals == 1", len(r.jump_intervals()) == 1,
                     note=f"{r.jump_intervals()}"))
    for b in folds:
        w_ex, _ = pws.fold_newton(STOP, _state(hb, b.x, b.omega), b.omega)
        out.append(check(f"fold near {w_ex:.2f} rad/s", SRC_STOP, "omega, rad/s", w_ex, b.omega, 1e-5,
                         note=f"H = 15; fold check with {b.check[1]} harmonics {b.check[0]:.10g}"))
        est = abs(b.check[0] - b.omega)
        out.append(claim(f"fold check bounds the error (fold near {w_ex:.2f})", SRC_STOP,
                         "|omega - exact| <= 5 |omega(H') - omega(H)| + 1e-9 omega",
                         abs(b.omega - w_ex) <= 5 * est + 1e-9 * w_ex,
                         note=f"error {abs(b.omega - w_ex):.3g} rad/s, change with H' {est:.3g} rad/s"))
    out.append(claim("truncation estimate within the tolerance at every point", SRC_STOP,
                     "max estimate <= truncation_tol", bool(r.truncation_ok()), note=r.truncation_line()))
    worst = 0.0
    for j in range(0, r.omega.size, 15):
        if r.truncation[j] == 0 or not r.stable[j]:
            continue                      # no contact (the linear orbit: HB exact), or unstable (not settled)
        w = float(r.omega[j])
        y, _ = STOP.periodic(_state(hb, r.states[j], w), w)
        xs = _exact_series(STOP, y, w, np.linspace(0, 2 * np.pi / w, 20001))
        a_ex = 0.5 * (xs.max() - xs.min())
        worst = max(worst, abs(r.response[j] - a_ex) / a_ex / r.truncation[j])
    out.append(claim("the point estimate bounds the amplitude error (contact points, stable)", SRC_STOP,
                     "|A_HB - A_exact| / A_exact <= estimate", worst <= 1.0,
                     note=f"largest ratio error / estimate {worst:.3g}"))
    rs = forced(stop_doc(kinks="sampled"))
    out.append(claim("with the kink sampled (kinks = 'sampled', 256 samples) HB reports spurious folds", SRC_STOP,
                     "number of folds > 2 (the artefact this case guards against)", len(rs.folds) > 2,
                     note=f"{len(rs.folds)} folds, {len(rs.jump_intervals())} jump intervals"))
    return out


def _exact_series(osc, y0, w, ts):
    """x(t) of the exact orbit from y0 at t = 0 (forcing phase 0) at the instants ts (sorted)."""
    return pws.dense(osc, y0, w, ts)


@case("steady_stop_branch_points", group="steady")
def stop_branch_points():
    """The two-sided stop is symmetric (F(-s) = -F(s), harmonic force): its primary orbits are symmetric,
    x(t + T/2) = -x(t), and they lose stability where the half-period map G(y) = -P_{T/2}(y) has the
    eigenvalue -1 -- a real Floquet multiplier through +1 *without a fold*: a symmetry-breaking
    (pitchfork) branch point, where the stability is lost with a real multiplier up to 2.6 (issue 27:
    "reported only as stable: NO").  Exact branch points: Brent's method on det(Phi_h - I) along the
    exact symmetric orbits (100.295634772, 101.210590576, 109.460787148, 153.182224442 rad/s).  HB with
    15 harmonics, adaptive (truncation_tol 1e-3): each branch point re-located with more harmonics until
    its change is below the tolerance.  Tolerance 1e-3 (= truncation_tol; the grazing orbits near 100 and
    110 rad/s have a contact a few hundredths of the period long: their Fourier series converge slowly).
    Branch switching: the asymmetric branch from the third branch point, one of its points re-solved by
    exact shooting (full period, no symmetry) to 1e-3."""
    out = []
    r = forced(stop_doc(adaptive=True, switch_branches=True))
    bps = [b for b in r.bifurcations if b.kind == "branch_point"]
    exact = _stop_branch_points()
    out.append(claim("four branch points, no fold among them (symmetry breaking)", SRC_STOP,
                     "branch points == 4, folds == 2 (the resonance's)",
                     len(bps) == 4 and len([b for b in r.bifurcations if b.kind == "fold"]) == 2,
                     note=f"branch points at {[round(b.omega, 4) for b in bps]}"))
    for w_ex in exact:
        b = min(bps, key=lambda b: abs(b.omega - w_ex)) if bps else None
        out.append(check(f"branch point near {w_ex:.2f} rad/s", SRC_STOP, "omega, rad/s", w_ex,
                         b.omega if b else np.nan, 1e-3, note=b.note if b else "missing"))
    mus = [m for m, w in zip(r.multipliers, r.omega) if m is not None and exact[2] < w < exact[3]]
    big = max((float(np.max(np.real(m))) for m in mus), default=0.0)
    out.append(claim("the unstable stretch between the third and fourth branch points: real multiplier > 2, "
                     "bracketed by branch points", SRC_STOP, "max real multiplier > 2 between them", big > 2.0,
                     note=f"largest real multiplier {big:.3f}"))
    sec = [s for s in r.secondary if "109.4" in s.origin or "109.5" in s.origin]
    ok, note = False, "no secondary branch from the third branch point"
    if sec:
        s = sec[0]
        j = s.omega.size // 2
        hb = HBModel(steady_model(stop_doc()).system, harmonics=int(len(s.states[j]) - 1) // 2)
        w = float(s.omega[j])
        y, _ = STOP.periodic(_state(hb, s.states[j], w), w)
        xs = _exact_series(STOP, y, w, np.linspace(0, 2 * np.pi / w, 20001))
        a_ex = 0.5 * (xs.max() - xs.min())
        mean = 0.5 * (xs.max() + xs.min())
        err = abs(s.response[j] - a_ex) / a_ex
        ok = err <= 1e-3 and abs(mean) > 1e-3 * a_ex
        note = (f"omega {w:.4f}: HB amplitude {s.response[j]:.8g}, exact {a_ex:.8g} (error {err:.2g}), "
                f"centre {mean:.3g} m (asymmetric)")
    out.append(claim("switched branch = exact asymmetric orbit", SRC_STOP, "amplitude error <= 1e-3, x_mid != 0",
                     ok, note=note))
    return out


def _stop_branch_points():
    """The exact symmetry-breaking branch points of the two-sided stop (100..160 rad/s)."""
    w = 100.0
    Z = 8e4 - 2 * w * w + 1j * 20 * w
    X = 60 / Z
    y = np.array([X.imag, (1j * w * X).imag])
    ws = np.concatenate([np.linspace(100.0, 102.0, 41), np.linspace(102.5, 160.0, 116)])
    vals, ys = [], []
    for w in ws:
        y, Phi, Ph = pws.fixed_point(STOP, y, w, symmetric=True)
        vals.append(pws.symmetry_breaking(Phi, Ph))
        ys.append(y)
    vals = np.array(vals)
    return [pws.locate_in_omega(STOP, pws.symmetry_breaking, ws[i], ws[i + 1], ys[i], symmetric=True)[0]
            for i in np.flatnonzero(np.sign(vals[1:]) != np.sign(vals[:-1]))]


@case("steady_one_sided_stop_folds", group="steady")
def one_sided_stop():
    """The penalty stop of the pyHarm comparison (m = k = 1, c = 0.05, 10 (x - 0.5)+, 0.05 cos w t, H = 15,
    1024 samples, w = 0.5..2): with the kink sampled, drivefem listed 8 folds and 4 jump intervals (3
    spurious); integrated exactly, the two folds of the exact orbits (1.228321557, 1.041803863: Newton on
    the exact fold equations).  Tolerance 1e-5 as for the two-sided stop (measured 1.1e-6 and 3e-8)."""
    d = {"title": "one-sided penalty stop", "body": [{"name": "mass", "inertia": 1.0}],
         "spring": [{"between": ["ground", "mass"], "k": 1.0}], "damper": [{"between": ["ground", "mass"], "c": 0.05}],
         "gap": [{"name": "stop", "body": "mass", "k": 10.0, "upper": 0.5}],
         "force": [{"body": "mass", "amplitude": 0.05, "omega": 1.0, "phase": np.pi / 2}],
         "steady": {"method": "hb", "omega": [0.5, 2.0], "harmonics": 15, "samples": 1024,
                    "response": {"body": "mass", "measure": "h1"}}}
    r = forced(d)
    hb = HBModel(steady_model(d).system, harmonics=15, samples=1024)
    osc = pws.PiecewiseLinearOscillator.one_sided(1.0, 0.05, 1.0, 10.0, 0.5, 0.05)
    folds = [b for b in r.bifurcations if b.kind == "fold"]
    out = [claim("exactly two folds, one jump interval", SRC_ONE, "folds == 2, jumps == 1",
                 len(folds) == 2 and len(r.jump_intervals()) == 1, note=f"{[round(b.omega, 6) for b in folds]}")]
    for b in folds:
        w_ex, _ = pws.fold_newton(osc, _state(hb, b.x, b.omega, np.pi / 2), b.omega)
        out.append(check(f"fold near {w_ex:.4f}", SRC_ONE, "omega", w_ex, b.omega, 1e-5, note=b.note))
    return out


@case("steady_impact_period_doubling", group="steady")
def impact_period_doubling():
    """A bilinear impact oscillator (m = k = 1, c = 0.05, stop at 0.2 of stiffness 20, 3 sin w t, w from 5
    down to 2): the period-1 orbit loses stability by period doubling twice (a multiplier through -1).
    Exact: Brent's method on det(Phi + I) of the exact piecewise-analytic orbits (3.936466863,
    2.329007677 rad/s).  HB with 25 harmonics; tolerance 1e-4 (the kinked law: HB-25 measured 1.8e-6 and
    1.8e-5; the check with 33 harmonics is printed).  Branch switching: the period-doubled branch from the
    first period doubling (the orbit written with period 2T, 50 harmonics of omega/2); one of its points
    re-solved by exact shooting over two periods, amplitude to 1e-4, and its period is 2T (its
    harmonics of odd order of omega/2 are not zero)."""
    d = {"title": "bilinear impact oscillator", "body": [{"name": "mass", "inertia": 1.0}],
         "spring": [{"between": ["ground", "mass"], "k": 1.0}], "damper": [{"between": ["ground", "mass"], "c": 0.05}],
         "gap": [{"name": "stop", "body": "mass", "k": 20.0, "upper": 0.2}],
         "force": [{"body": "mass", "amplitude": 3.0, "omega": 3.0}],
         "steady": {"method": "hb", "omega": [5.0, 2.0], "harmonics": 25, "switch_branches": True,
                    "response": {"body": "mass", "measure": "max"}}}
    r = forced(d)
    osc = pws.PiecewiseLinearOscillator.one_sided(1.0, 0.05, 1.0, 20.0, 0.2, 3.0)
    exact = []
    w = 5.0
    Z = 1 - w * w + 1j * 0.05 * w
    y = np.array([(3 / Z).imag, (1j * w * 3 / Z).imag])
    ws = np.linspace(5.0, 2.0, 121)
    vals, ys = [], []
    for w in ws:
        y, Phi, _ = pws.fixed_point(osc, y, w)
        vals.append(pws.det_plus_identity(Phi))
        ys.append(y)
    vals = np.array(vals)
    for i in np.flatnonzero(np.sign(vals[1:]) != np.sign(vals[:-1])):
        exact.append(pws.locate_in_omega(osc, pws.det_plus_identity, ws[i], ws[i + 1], ys[i])[0])
    pds = [b for b in r.bifurcations if b.kind == "period_doubling"]
    out = [claim("two period doublings (and no other bifurcation)", SRC_PD, "period doublings == 2, others == 0",
                 len(pds) == 2 and len(r.bifurcations) == 2, note=f"{[b.line() for b in r.bifurcations]}")]
    for w_ex in exact:
        b = min(pds, key=lambda b: abs(b.omega - w_ex)) if pds else None
        out.append(check(f"period doubling near {w_ex:.3f}", SRC_PD, "omega", w_ex, b.omega if b else np.nan, 1e-4,
                         note=b.note if b else "missing"))
        if b is not None:
            out.append(claim(f"critical multiplier -1 (near {w_ex:.3f})", SRC_PD, "|mu + 1| < 1e-3",
                             b.multiplier is not None and abs(b.multiplier + 1) < 1e-3, note=f"mu = {b.multiplier}"))
    ok, note = False, "no period-doubled branch"
    if r.secondary:
        s = r.secondary[0]
        j = s.omega.size // 3
        H2 = (len(s.states[j]) - 1) // 2
        x, w = s.states[j], float(s.omega[j])
        th = 0.0
        y0 = np.array([trig_eval(x, th), (w / 2) * trig_eval(x, th, 1)])
        y, mu = osc.periodic(y0, w, nu=2)
        xs = pws.dense(osc, y, w, np.linspace(0, 4 * np.pi / w, 20001))
        odd = float(np.max(np.hypot(x[1::4], x[2::4])))             # harmonics 1, 3, 5.. of omega / 2
        err = abs(s.response[j] - xs.max()) / xs.max()
        ok = err <= 1e-4 and odd > 1e-3 * np.max(np.abs(x))
        note = (f"{s.origin}: omega {w:.5f}, H = {H2}, max HB {s.response[j]:.8g}, exact {xs.max():.8g} "
                f"(error {err:.2g}); largest odd harmonic of omega/2 {odd:.3g}")
    out.append(claim("period-doubled branch = exact period-2 orbit", SRC_PD, "max error <= 1e-4, period 2T",
                     ok, note=note))
    return out


@case("steady_coupled_duffing_neimark_sacker", group="steady")
def coupled_duffing_ns():
    """Two coupled Duffing oscillators (m = k = 1 each, coupling 0.1, damping 0.01, k3 = 1, 0.02 sin w t on
    the first), HB with 7 harmonics over w = 0.8..1.25: on the stretch where the first oscillator is near
    anti-resonance a complex pair of Floquet multipliers leaves and re-enters the unit circle --
    two Neimark-Sacker points (a torus branch between them).  Reference: the periodic orbits re-solved by
    shooting with an independent integrator (DOP853, rtol 1e-12, variational equation for the monodromy),
    the NS points by Brent's method on |mu| - 1 of the complex pair (1.057135126, 1.067295686).
    Tolerance 1e-5: the HB orbit (smooth law, 7 harmonics) is accurate to ~1e-10, its multipliers from the
    exponential midpoint rule on 512 intervals to ~1e-6 (measured location errors 2e-7 and 3e-7)."""
    d = {"title": "two coupled Duffing oscillators",
         "body": [{"name": "m1", "inertia": 1.0}, {"name": "m2", "inertia": 1.0}],
         "spring": [{"between": ["ground", "m1"], "k": 1.0}, {"between": ["ground", "m2"], "k": 1.0},
                    {"between": ["m1", "m2"], "k": 0.1}],
         "damper": [{"between": ["ground", "m1"], "c": 0.01}, {"between": ["ground", "m2"], "c": 0.01}],
         "cubic_spring": [{"between": ["ground", "m1"], "k3": 1.0}, {"between": ["ground", "m2"], "k3": 1.0}],
         "force": [{"body": "m1", "amplitude": 0.02, "omega": 1.0}],
         "steady": {"method": "hb", "omega": [0.8, 1.25], "harmonics": 7,
                    "response": {"body": "m1", "measure": "amplitude"}}}
    r = forced(d)
    hb = HBModel(steady_model(d).system, harmonics=7)
    sys_ = ode.coupled_duffing(1.0, 1.0, 0.1, 0.01, 1.0, 0.02)
    ns = [b for b in r.bifurcations if b.kind == "neimark_sacker"]
    out = [claim("two Neimark-Sacker points", SRC_NS, "NS count == 2", len(ns) == 2,
                 note=f"{[round(b.omega, 7) for b in ns]}")]
    for b in ns:
        i = b.index
        t, q, v = hb.evaluate(r.states[i], r.omega[i])
        y0 = np.concatenate([q[:, 0], v[:, 0]])
        w_ex, _, mu = sys_.locate(ode.complex_pair_modulus, r.omega[i], r.omega[i + 1], y0)
        out.append(check(f"Neimark-Sacker near {w_ex:.5f}", SRC_NS, "omega", w_ex, b.omega, 1e-5,
                         note=f"critical multiplier HB {b.multiplier:.6f}, exact "
                              f"{mu[np.argmin(np.abs(np.abs(mu) - 1))]:.6f}"))
        out.append(claim(f"complex critical multiplier on the unit circle (near {w_ex:.5f})", SRC_NS,
                         "| |mu| - 1 | < 1e-4 and Im mu != 0", b.multiplier is not None
                         and abs(abs(b.multiplier) - 1) < 1e-4 and abs(b.multiplier.imag) > 1e-3))
    return out


@case("steady_seed002_period_doubling", group="steady")
def seed002_period_doubling():
    """Seed 002, a = 8.6e-4, simplified model: the period-1 branch loses stability by period doubling at
    z ~ 1.08 and regains it at z ~ 1.91 (docs/steady.md).  Reference: the exact event-driven period map
    (shooting, no truncation, true slack of the strand and the clutch's constant slip torque), its
    monodromy by central differences, Brent's method on det(Phi + I) in z.  HB (15 harmonics): the
    period doublings located on the branch; tolerance 1e-4 in z (the HB truncation estimate is 1e-4 at
    most along the branch; the finite-difference monodromy is accurate to ~1e-7).  Branch switching onto
    the period-doubled branch: its fold at z = 1.270 (docs: "turns at a fold near z = 1.27"), and at
    z = 1.183 it passes through the stable period-2 orbit that exact shooting over two periods finds from
    a state settled from rest (as steady_seed002_afc; mu = 3.02): the HB value (30 harmonics of omega/2)
    to 1e-4."""
    from scipy.optimize import brentq

    out = []
    doc = seed002_doc(8.6e-4, "simple", switch_branches=True)
    r = forced(doc)
    sm = steady_model(seed002_doc(8.6e-4, "simple"))
    sh = ShootingModel(sm.factory, steps_per_period=48)
    hb = HBModel(sm.system, harmonics=15)
    sc = np.array([0.02, 1.0])
    pds = [b for b in r.bifurcations if b.kind == "period_doubling"]
    out.append(claim("two period doublings on the period-1 branch", SRC_002, "count == 2", len(pds) == 2,
                     note=f"z = {[round(b.omega / K_NAT, 5) for b in pds]}"))
    for b in pds:
        state = {}

        def f(z):
            w = z * K_NAT
            if "y" not in state:
                t, q, v = hb.evaluate(b.x, b.omega)
                state["y"] = np.array([q[0, 0], v[0, 0]])
            y, _ = sh.solve(state["y"], w, sc)
            state["y"] = y
            mu = sh.floquet(y, w, sc)
            return float(np.real(np.prod(mu + 1)))

        z0 = b.omega / K_NAT
        z_ex = brentq(f, z0 - 0.004, z0 + 0.004, xtol=1e-9)
        out.append(check(f"period doubling near z = {z_ex:.4f}", SRC_002, "z", z_ex, z0, 1e-4, note=b.note))
    sec = r.secondary[0] if r.secondary else None
    folds = [c for c in sec.bifurcations if c.kind == "fold"] if sec else []
    out.append(claim("period-doubled branch turns at a fold near z = 1.27", SRC_002, "fold in 1.26 .. 1.28",
                     any(1.26 < c.omega / K_NAT < 1.28 for c in folds),
                     note=f"folds of the switched branch at z = {[round(c.omega / K_NAT, 5) for c in folds]}"))
    if sec is not None:
        # the exact stable period-2 orbit reached from rest (as steady_seed002_afc), and the switched branch
        # re-solved at that frequency from each of its stretches that cross it
        w = 1.183 * K_NAT
        sh1, sh2 = ShootingModel(sm.factory), ShootingModel(sm.factory, nu=2, steps_per_period=48)
        y, _, _ = sh1.settle(np.zeros(2), w, periods=300, tol=1e-12, scale=sc)
        y, _ = sh2.solve(y, w, sc)
        _, res = sh2.run(y, w, dense=True)
        p = sh2.problem(w)
        mu_sh = sm.measure(res.t, res.x[p.f], res.v[p.f], w, events=[e.t for e in res.events])
        hb2 = HBModel(sm.system, harmonics=(len(sec.states[0]) - 1) // 2, nu=2)
        cand = []
        for j in np.flatnonzero(np.diff(np.sign(sec.omega - w)) != 0):
            X, _ = hb2.solve(sec.states[j], w)
            cand.append(sm.measure_hb(hb2, [X], [w])[0])
        mu_hb = min(cand, key=lambda m: abs(m - mu_sh)) if cand else np.nan
        out.append(check("switched period-2 branch through the stable period-2 orbit at z = 1.183", SRC_002, "mu",
                         mu_sh, mu_hb, 1e-4, note=f"the branch crosses z = 1.183 {len(cand)} times: mu = "
                                                  f"{[round(m, 5) for m in cand]}"))
    return out


SRC_MEAS = "issue 27 item 6: response measures (exact Fourier coefficient; extremes by root-finding)"


@case("steady_measures_exact", group="steady")
def measures_exact():
    """The [steady] response measures computed exactly from the HB series.  (a) h1 of a linear oscillator
    (m = k = 1, c = 0.1, 0.25 at w = 0.5, H = 3): 0.25 / |1 - w^2 + 0.1 i w| = 0.332595 to 1e-10 (the
    trapezoid over the samples without the period's closing point gave 0.331303).  (b) h1 of the 1/3
    subharmonic of examples/steady_subharmonic.toml (Omega = 3.6): the amplitude at the forcing frequency
    is harmonic 3 of the series in Omega t / 3 -- against the Omega-component of an independent DOP853
    integration settled on the same orbit (300 forcing periods, rtol 1e-11, the DFT of 3 x 512 samples of
    its last subharmonic period), tolerance 1e-7 (HB-9 truncation ~1e-10; the old trapezoid let the
    Omega/3 component leak in, 2.4-2.9 %).  (c) The amplitude (half peak-to-peak) of the gap oscillator's
    HB orbit (examples/steady_gap.toml, H = 15, a kinked law) against the extremes of the same series on
    2^16 equidistant samples refined by golden-section search: 1e-12 (the extremes of 512 samples are
    low by up to (pi/512)^2/2 ~ 2e-5 relative)."""
    from scipy.integrate import solve_ivp

    from fem.modelfile.source import read_toml
    from validation.examples import EXAMPLES

    out = []
    doc = {"body": [{"name": "m", "inertia": 1.0}], "spring": [{"between": ["ground", "m"], "k": 1.0}],
           "damper": [{"between": ["ground", "m"], "c": 0.1}],
           "force": [{"body": "m", "amplitude": 0.25, "omega": 0.5}],
           "steady": {"omega": [0.5, 0.6], "harmonics": 3, "response": {"body": "m", "measure": "h1"}}}
    r = forced(doc)
    out.append(check("h1 of a linear oscillator (issue 27 repro)", SRC_MEAS, "h1 at w = 0.5",
                     0.25 / abs(1 - 0.25 + 0.1j * 0.5), r.response[0], 1e-10))
    d = read_toml(EXAMPLES / "steady_subharmonic.toml")
    d["steady"].update(response={"body": "mass", "measure": "h1"}, omega=[3.6, 3.7])
    r = forced(d)
    W = 3.6
    k0, c, k3, F = 1.0, 0.0477465, 0.5, 2.0

    def f(t, y):
        return [y[1], F * np.cos(W * t) - c * y[1] - k0 * y[0] - k3 * y[0] ** 3]

    sm = steady_model(d)
    hb = HBModel(sm.system, harmonics=9, nu=3)
    t, q, v = hb.evaluate(r.states[0], W)
    T3 = 3 * 2 * np.pi / W
    sol = solve_ivp(f, (0.0, 100 * T3), [q[0, 0], v[0, 0]], method="DOP853", rtol=1e-11, atol=1e-13,
                    dense_output=True)
    ts = 99 * T3 + T3 * np.arange(3 * 512) / (3 * 512)
    x = sol.sol(ts)[0]
    c3 = 2 * abs(np.sum(x * np.exp(-1j * W * ts))) / ts.size
    out.append(check("h1 of the 1/3 subharmonic = its Omega-component (DOP853)", SRC_MEAS, "h1 at Omega = 3.6",
                     c3, r.response[0], 1e-7,
                     note=f"the Omega/3 component is {2 * abs(np.sum(x * np.exp(-1j * W / 3 * ts))) / ts.size:.4f}"))
    g = read_toml(EXAMPLES / "steady_gap.toml")
    r = forced(g)
    i = int(np.argmax(r.response))
    x = r.states[i]
    P = 1 << 16
    th = 2 * np.pi * np.arange(P) / P
    y = trig_eval(x, th)
    from discrete.steady import measures as ms
    golden = ms.golden_extremes(lambda t: ms.series_values(x[None, :], t), 1, P, iterations=40)
    a_ref = 0.5 * (max(y.max(), float(golden[0][0])) - min(y.min(), float(golden[1][0])))
    y512 = trig_eval(x, 2 * np.pi * np.arange(512) / 512)
    out.append(check("amplitude of the gap oscillator's peak orbit (extremes by Newton)", SRC_MEAS,
                     "half peak-to-peak", a_ref, r.response[i], 1e-12,
                     note=f"512 samples: {0.5 * (y512.max() - y512.min()):.10g} "
                          f"({(0.5 * (y512.max() - y512.min()) - a_ref) / a_ref:.2g})"))
    return out
