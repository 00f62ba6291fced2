"""Programme motion and cam laws (textbook §5.8-5.9, §6.2; digests textbook_ch2-5.md V5.9, textbook_ch6-9.md V6.2).

Every case compares the package (discrete.motion, discrete.linear.periodic_forced) with the book's printed
numbers and with an independent second method (adaptive Runge-Kutta integration, expm monodromy, closed
forms written out in validation/analytic/cam_refs.py).  Misprints followed in their corrected form:
Table 6.1 header |Delta q'|max -> |Delta q''|max; zeros of ae0 at nu = j (book: "nu = j pi");
(6.12)-(6.13) inequality reversed in print.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from discrete.linear.periodic_forced import PeriodicLoad, periodic_response
from discrete.lumped import Body, Driver, Link, LumpedModel
from discrete.motion import (PiecewiseLaw, PiecewiseOscillator, accumulation_factor, admissible_frequency_ratio,
                             band_threshold, discontinuity_table, dwell_rise_dwell_return, fourier_series,
                             min_frequency_ratio, mu_minus, mu_plus, residual_factor)
from discrete.motion.cam_report import TABLE_6_1_PHASES
from validation.analytic import cam_refs as ref
from validation.registry import case, check, claim, printed

SRC = "seed 001 §6.2 (digest textbook_ch6-9.md V6.2)"


def _single_jump_law(order: int, a: float, phi1: float) -> PiecewiseLaw:
    """Pi = 0 for phi < phi1, a (phi - phi1)^m/m! after: one jump of Pi^(m) of size a at phi1."""
    tail = np.zeros(order + 1)
    tail[order] = a / math.factorial(order)
    return PiecewiseLaw([0.0, phi1, phi1 + 2.0], [np.zeros(order + 1), tail])


@case("cam-table-6-1", group="cam")
def cam_table_6_1():
    """Table 6.1, one discontinuity at a time (Pi, Pi', Pi'', Pi''' jumping by +a and -a at phi_1 = 1 rad),
    omega0 = 20 rad/s, k = 170 rad/s, undamped.  The table's D, |Delta q''|max = k^2 D and alpha
    (alpha_1 for a positive jump, alpha_2 otherwise) against (i) the exact (6.4) with the particular
    solution's jumps (PiecewiseOscillator.knot_excitation) and (ii) a DOP853 integration (rtol 1e-12) of
    (6.1) restarted at phi_1 with the book's continuity conditions (6.3), the free part measured a third
    of a period later.  Both references are exact for this undamped model: tolerance 1e-8 (integration)."""
    out = []
    w0, k, phi1 = 20.0, 170.0, 1.0
    t1 = phi1 / w0
    for m in range(4):
        for a in (1e-3, -1e-3):
            law = _single_jump_law(m, a, phi1)
            rows = discontinuity_table(law, w0, k)
            tag = f"Delta Pi^({m}) = {a:+g}"
            out.append(claim("cam-table-6-1", SRC, f"{tag}: one row of order {m}", len(rows) == 1 and rows[0].order == m))
            row = rows[0]
            D_tab = w0**m * abs(a) / k**m
            out.append(check("cam-table-6-1", "Table 6.1 formula", f"{tag}: D", D_tab, row.D, 1e-14))
            out.append(check("cam-table-6-1", "(6.6)", f"{tag}: |Delta q''|max = k^2 D", k * k * D_tab,
                             row.extra_acceleration, 1e-14))
            alpha_exp = TABLE_6_1_PHASES[m][0 if a > 0 else 1]
            osc = PiecewiseOscillator.follower(law.in_time(w0), k, 0.0)
            kx = osc.knot_excitation()
            out.append(check("cam-table-6-1", "exact (6.4) with particular-solution jumps", f"{tag}: D", row.D,
                             kx.D[0], 1e-12))
            dal = (kx.alpha[0] - row.alpha + math.pi) % (2 * math.pi) - math.pi
            out.append(check("cam-table-6-1", "exact (6.4)", f"{tag}: alpha - alpha_table [rad]", 0.0, dal, 1e-12,
                             scale=1.0))
            # DOP853: programme acceleration after t1 is a w0^m (t - t1)^(m - 2)/(m - 2)! for m >= 2
            xdd = (lambda t: 0.0) if m < 2 else ((lambda t: a * w0**2) if m == 2 else (lambda t: a * w0**3 * (t - t1)))
            kick = [(0, 0), (-a if m == 0 else 0.0, -a * w0 if m == 1 else 0.0)]
            T = 2 * math.pi / k
            ts = np.array([t1 + T / 3])
            qv = ref.integrate_piecewise([lambda t, y: [y[1], -k * k * y[0]],
                                          lambda t, y: [y[1], -xdd(t) - k * k * y[0]]],
                                         [0.0, t1, t1 + T], kick, [0.0, 0.0], ts)[0]
            Y = -xdd(ts[0]) / k**2
            Yd = 0.0 if m < 3 else -a * w0**3 / k**2
            u, ud = qv[0] - Y, qv[1] - Yd
            D_num = math.hypot(u, ud / k)
            al_num = (math.atan2(u, ud / k) - k * (ts[0] - t1)) % (2 * math.pi)
            out.append(check("cam-table-6-1", "DOP853 integration of (6.1)", f"{tag}: D", row.D, D_num, 1e-8))
            dal = (al_num - row.alpha + math.pi) % (2 * math.pi) - math.pi
            out.append(check("cam-table-6-1", "DOP853 integration of (6.1)", f"{tag}: alpha - alpha_table [rad]", 0.0,
                             dal, 1e-7, scale=1.0))
    return out


@case("cam-standard-laws", group="cam")
def cam_standard_laws():
    """Dwell-rise-dwell-return cycles with the standard laws (h = 0.02 m, rise and return over 100 deg,
    top dwell 60 deg): the discontinuity table finds exactly the closed-form jumps of the law (cycloidal
    and 3-4-5: jerk 4 pi^2 h/beta^3 and 60 h/beta^3 at the ends; harmonic: soft impacts
    pi^2 h/(2 beta^2); constant acceleration: 4 h/beta^2 at the ends and -8 h/beta^2 mid-stroke) and the
    law's position, velocity and acceleration agree with the closed forms written out independently
    (cam_refs.rise_derivatives) to 1e-12 relative (round-off only)."""
    out = []
    h, beta, top = 0.02, math.radians(100), math.radians(60)
    for name in ("cycloidal", "harmonic", "polynomial345", "constant_acceleration"):
        law = dwell_rise_dwell_return(h, beta, top, beta, law=name)
        rows = discontinuity_table(law, 1.0, 1.0)
        ref_j = ref.end_jumps(name, h, beta)
        expected = []
        for m, (j0, j1) in ref_j.items():
            expected += [(0.0, m, j0), (beta, m, j1), (beta + top, m, -j0), (2 * beta + top, m, -j1)]
        if name == "constant_acceleration":
            expected += [(beta / 2, 2, -8 * h / beta**2), (beta + top + beta / 2, 2, 8 * h / beta**2)]
        expected = [e for e in expected if e[2] != 0]
        expected.sort()
        got = sorted((r.phase, r.order, r.jump) for r in rows)
        out.append(claim("cam-standard-laws", SRC, f"{name}: jump set (phases, orders)",
                         len(got) == len(expected) and all(abs(g[0] - e[0]) < 1e-12 and g[1] == e[1]
                                                           for g, e in zip(got, expected)),
                         note=f"{len(got)} jumps found, {len(expected)} expected"))
        if len(got) == len(expected):
            err = max(abs(g[2] - e[2]) / abs(e[2]) for g, e in zip(got, expected))
            out.append(check("cam-standard-laws", "closed-form jumps", f"{name}: max rel. error of the jumps", 0.0, err,
                             1e-12, scale=1.0))
        u = np.linspace(0, 1, 201)[:-1]          # [0, 1): at u = 1 the dwell's right limit takes over
        phi = u * beta
        s = ref.rise_derivatives(name, u)
        err = max(np.max(np.abs(law(phi, m) - h * s[m] / beta**m)) / np.max(np.abs(h * s[m] / beta**m))
                  for m in range(3))
        out.append(check("cam-standard-laws", "closed-form law", f"{name}: Pi, Pi', Pi'' on the rise", 0.0, err, 1e-12,
                         scale=1.0))
    return out


@case("cam-residual-factor", group="cam")
def cam_residual_factor():
    """(6.8) ae0(nu) = |sin pi nu|/(pi nu): the digest's values 0.98363, 0.90032, 0.63662, 0.21221 (nu = 0.1,
    0.25, 0.5, 1.5; half a printed digit), zeros at integer nu (the book's "nu = j pi" is a misprint:
    ae0(pi) = 0.0437), the bound ae0 <= 1/(pi nu).  Independent: DOP853 integration of the follower under an
    acceleration ramp of duration nu T (rtol 1e-12; residual amplitude after the ramp over x''_*/k^2,
    absolute tolerance 1e-8), and the package's exact piecewise follower on the same ramp law.
    Damped curves of Fig. 6.4 (book's expression, delta = 0.05): below the undamped curve except near
    integer nu, where they do not vanish."""
    out = []
    for nu, txt in ((0.1, "0.98363"), (0.25, "0.90032"), (0.5, "0.63662"), (1.5, "0.21221")):
        v, tol = printed(txt)
        out.append(check("cam-residual-factor", "digest V6.2-b (from (6.8))", f"ae0({nu:g})", v,
                         float(residual_factor(nu)), tol))
    out.append(check("cam-residual-factor", "(6.8), corrected: zeros at nu = j", "max ae0 at nu = 1, 2, 3", 0.0,
                     float(np.max(residual_factor([1.0, 2.0, 3.0]))), 1e-15, scale=1.0))
    out.append(claim("cam-residual-factor", "(6.8) misprint 'nu = j pi'", "ae0(pi) is not a zero (0.0437)",
                     float(residual_factor(math.pi)) > 0.04))
    grid = np.linspace(0.05, 5, 400)
    out.append(claim("cam-residual-factor", "seed 001 §6.2", "ae0 <= 1/(pi nu) for nu > 0",
                     bool(np.all(residual_factor(grid) <= 1 / (math.pi * grid) + 1e-15))))
    out.append(claim("cam-residual-factor", "seed 001 §6.2", "nu <= 0.25: ae0 >= 0.9 (practically a jump)",
                     bool(np.all(residual_factor(np.linspace(0, 0.25, 50)) >= 0.9))))
    k, acc = 3.0, 1.0
    for nu in (0.1, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 2.5):
        num = ref.ramp_residual(nu, k, acc)
        out.append(check("cam-residual-factor", "DOP853 ramp response", f"residual/(x''*/k^2) at nu = {nu:g}",
                         float(residual_factor(nu)), num, 1e-8, scale=1.0))
        dt = nu * 2 * math.pi / k
        t1 = 0.3
        law = PiecewiseLaw([0.0, t1, t1 + dt, t1 + dt + 10.0],
                           [[0, 0, 0, 0], [0, 0, 0, acc / (6 * dt)], [acc * dt**2 / 6, acc * dt / 2, acc / 2, 0]])
        osc = PiecewiseOscillator.follower(law, k, 0.0)
        tt = t1 + dt + 1.234
        q, v, _ = osc.response([tt], [0.0, 0.0])[0]
        u = q + acc / k**2
        out.append(check("cam-residual-factor", "exact piecewise follower", f"residual at nu = {nu:g}",
                         float(residual_factor(nu)), math.hypot(u, v / k) / (acc / k**2), 1e-11, scale=1.0))
    nu = np.linspace(0.05, 3, 600)
    damped, undamped = residual_factor(nu, 0.05), residual_factor(nu)
    far = np.abs(nu - np.round(nu)) > 0.15      # the zones widen with nu: +-0.12 around nu = 3 at delta = 0.05
    out.append(claim("cam-residual-factor", "Fig. 6.4", "damped curve below undamped (|nu - j| > 0.15, nu <= 3)",
                     bool(np.all(damped[far] < undamped[far]))))
    out.append(claim("cam-residual-factor", "Fig. 6.4", "damped curve > 0 at integer nu (partial compensation)",
                     bool(np.all(residual_factor([1.0, 2.0], 0.05) > 1e-3))))
    return out


@case("cam-accumulation", group="cam")
def cam_accumulation():
    """Accumulation factor (5.53) and (6.10)-(6.14).  Printed: mu(0.2, 8.5) = 0.84553 and mu(0.2, 9) = 1.19803
    (digest, lambda = 0.2 for the book's k = 170, omega0 = 20 example); mu at lambda N = 3: 0.9526 / 1.0524 and
    at 3.2: 0.9608 / 1.0425 -- the book's "lambda N > 3 gives 0.96 < mu < 1.04" holds only from lambda N = ln 26
    = 3.258 (mu+ binding; mu- > 0.96 from ln 24 = 3.178), found here also by root finding.  (6.13) as it must
    read (cos 2 pi N < 0.5 e^{-lambda N}) gives the book's limits N = E +- 1/6 (lambda N -> 0) and E +- 1/4
    (lambda -> infinity); the printed direction selects mu > 1.  (6.14): N > ln 11/lambda = 2.4/lambda, k >= 12 omega0.
    Independent: the exact map of a velocity kick repeated every tau (expm, 4000 cycles) equals (5.53) with
    N = k1/omega0, lambda = 2 pi n/k1 (the book's k-based values differ by O(delta^2)) to 1e-10, and so does
    the package's exact periodic follower with the same kick."""
    out = []
    for N, txt in ((8.5, "0.84553"), (9.0, "1.19803")):
        v, tol = printed(txt)
        out.append(check("cam-accumulation", "digest V6.2-c (5.53)", f"mu(0.2, {N:g})", v, float(accumulation_factor(0.2, N)), tol))
    out.append(check("cam-accumulation", "(6.11)", "mu(0.2, 9) = mu+", float(mu_plus(0.2, 9.0)),
                     float(accumulation_factor(0.2, 9.0)), 1e-14))
    out.append(check("cam-accumulation", "(6.11)", "mu(0.2, 8.5) = mu-", float(mu_minus(0.2, 8.5)),
                     float(accumulation_factor(0.2, 8.5)), 1e-14))
    for x, lo, hi in ((3.0, "0.9526", "1.0524"), (3.2, "0.9608", "1.0425")):
        for f, txt, nm in ((mu_minus, lo, "mu-"), (mu_plus, hi, "mu+")):
            v, tol = printed(txt)
            out.append(check("cam-accumulation", "digest (6.11)", f"{nm} at lambda N = {x:g}", v, float(f(1.0, x)), tol))
    band = band_threshold(0.96, 1.04)
    root_lo = brentq(lambda x: float(mu_minus(1.0, x)) - 0.96, 1.0, 10.0, xtol=1e-14)
    root_hi = brentq(lambda x: float(mu_plus(1.0, x)) - 1.04, 1.0, 10.0, xtol=1e-14)
    out.append(check("cam-accumulation", "root of mu- = 0.96", "lambda N threshold (lower)", root_lo, band["lower"], 1e-12))
    out.append(check("cam-accumulation", "root of mu+ = 1.04", "lambda N threshold (upper)", root_hi, band["upper"], 1e-12))
    out.append(claim("cam-accumulation", "seed 001 §6.2 'lambda N > 3'", "the printed band fails at lambda N = 3 "
                     "(mu+ = 1.0524 > 1.04) and holds from 3.258", float(mu_plus(1.0, 3.0)) > 1.04 and band["both"] > 3.2,
                     note=f"strict threshold {band['both']:.4f}"))
    # (6.13) corrected: admissible N with [mu] = 1
    for lam, d in ((1e-9, 1 / 6), (2.0, 1 / 4)):      # lambda N ~ 17: e^{-lambda N} ~ 4e-8
        f = lambda N: 1.0 if admissible_frequency_ratio(lam, N) else -1.0
        left = brentq(lambda N: f(N), 8.0 + 1e-6, 8.5, xtol=1e-12)
        right = brentq(lambda N: f(N), 8.5, 9.0 - 1e-6, xtol=1e-12)
        out.append(check("cam-accumulation", "(6.13) corrected", f"lambda = {lam:g}: lower edge - 8", d, left - 8.0, 1e-6))
        out.append(check("cam-accumulation", "(6.13) corrected", f"lambda = {lam:g}: 9 - upper edge", d, 9.0 - right, 1e-6))
    Ns = np.linspace(0.3, 12, 3001)
    for lam in (0.05, 0.2, 1.0):
        adm = admissible_frequency_ratio(lam, Ns)
        mu = accumulation_factor(lam, Ns)
        e = np.exp(-lam * Ns)
        printed_form = 0.5 * e < np.cos(2 * math.pi * Ns)
        out.append(claim("cam-accumulation", "(6.12)-(6.13) corrected", f"lambda = {lam:g}: admissible <=> mu < 1",
                         bool(np.all(adm == (mu < 1)))))
        out.append(claim("cam-accumulation", "(6.13) as printed", f"lambda = {lam:g}: printed inequality <=> mu > 1",
                         bool(np.all(printed_form == (mu > 1)))))
    v, tol = printed("2.4")
    out.append(check("cam-accumulation", "seed 001 §6.2 rec. 3", "lambda N_min for [mu] = 1.1 (ln 11)", v,
                     0.2 * min_frequency_ratio(0.2, 0.1), tol))
    v, tol = printed("12")
    out.append(check("cam-accumulation", "seed 001 §6.2 rec. 3", "k/omega0 for lambda = 0.2", v,
                     min_frequency_ratio(0.2, 0.1), tol))
    v, tol = printed("1.1")
    out.append(check("cam-accumulation", "seed 001 §6.2 example", "omega0 drop 20 -> 170/9 [1/s]", v, 20 - 170 / 9, tol))
    # independent: exact kick map
    w0 = 1.0
    for lam, N in ((0.2, 8.5), (0.2, 9.0), (0.05, 3.0), (0.5, 2.2)):
        k1 = N * w0
        n = lam * k1 / (2 * math.pi)
        k = math.hypot(k1, n)
        tau = 2 * math.pi / w0
        mp = ref.kick_map_amplitude(k, n, tau)
        out.append(check("cam-accumulation", "kick map (expm) with N = k1/omega0, lambda = 2 pi n/k1",
                         f"mu({lam:g}, {N:g})", float(accumulation_factor(lam, N)), mp, 1e-10))
        zero = PiecewiseLaw([0.0, tau], [[0.0]], periodic=True)
        osc = PiecewiseOscillator(zero, k, n, kicks=np.array([[0.0, 1.0], [0.0, 0.0]]))
        z = osc.periodic_state()
        amp = math.hypot(z[0], (z[1] + n * z[0]) / k1) * k1
        out.append(check("cam-accumulation", "package exact periodic follower with a kick", f"mu({lam:g}, {N:g})",
                         float(accumulation_factor(lam, N)), amp, 1e-10))
    return out


def _sawtooth_system(k: float, n: float):
    m = LumpedModel(bodies=[Body("mass", 1.0)], springs=[Link(("ground", "mass"), k * k)],
                    dampers=[Link(("ground", "mass"), 2 * n)] if n > 0 else [])
    return m.linear_system()


@case("cam-sawtooth-5-9", group="cam")
def cam_sawtooth():
    """V5.9: sawtooth force rising 0 -> k^2 over each period tau = 2 pi/1.3, a = 1, k = 10.
    Damped (delta = 0.05, lambda = 0.31416): mu = 0.966177 (5.53), exact periodic state q0 = 0.952930,
    q0' = 0.960353 (digest; half a printed digit) from (a) the package's exact piecewise solution
    (particular solution + transition matrix, periodicity (5.46) solved exactly), (b) expm monodromy, (c)
    DOP853 from rest over 12 periods (transient e^{-n t} < 1e-11), (d) Fourier superposition of harmonic
    responses (periodic_response, 4000 harmonics, modal method = exact for 1 DOF): q converges like 1/H^2 (tail bound
    2 k^2/(pi omega^2 H^2) = 2.4e-6 for the unit static amplitude), q' like 1/H at the jump (k^2/(pi omega H) =
    6e-3: the book's caveat that harmonic analysis suits smooth loads) but with an alternating tail inside the
    period (checked at tau/2 against twice the first omitted term, 3e-6).  Undamped (V5.9a): q = 0.5, 0.404804, -0.261934, 0.5,
    1.261934, 0.595196 at t = j tau/6 (printed 6 decimals) from the exact solution and from the closed form."""
    out = []
    k, tau = 10.0, 2 * math.pi / 1.3
    delta = 0.05
    n = delta * k
    lam = 2 * math.pi * delta
    v, tol = printed("0.966177")
    out.append(check("cam-sawtooth-5-9", "digest V5.9b (5.53)", "mu", v, float(accumulation_factor(lam, k / 1.3)), tol))
    F = PiecewiseLaw([0.0, tau], [[0.0, k * k / tau]], periodic=True, name="sawtooth")
    osc = PiecewiseOscillator.forced(F, k, n)
    z = osc.periodic_state()
    zr = ref.sawtooth_periodic_state(k, n, tau, k * k)
    for i, (txt, nm) in enumerate((("0.952930", "q0"), ("0.960353", "q0'"))):
        v, tol = printed(txt)
        out.append(check("cam-sawtooth-5-9", "digest V5.9b", f"{nm} (package exact)", v, z[i], tol))
        out.append(check("cam-sawtooth-5-9", "expm monodromy", f"{nm}: package - expm", zr[i], z[i], 1e-12))
    ss = osc.steady_state()
    out.append(check("cam-sawtooth-5-9", "periodicity (5.46)", "relative residual of the periodic state", 0.0,
                     ss.residual, 1e-12, scale=1.0))
    ts = np.linspace(11 * tau, 12 * tau, 7)[:-1]
    num = ref.integrate_piecewise([lambda t, y, c=c: [y[1], k * k * (t - c * tau) / tau - 2 * n * y[1] - k * k * y[0]]
                                   for c in range(12)], [c * tau for c in range(13)], [(0, 0)] * 13, [0.0, 0.0], ts)
    per = osc.response(ts - 11 * tau)
    out.append(check("cam-sawtooth-5-9", "DOP853 from rest, 12th period", "max |q_DOP853 - q_periodic|", 0.0,
                     float(np.max(np.abs(num[:, 0] - per[:, 0]))), 1e-9, scale=1.0))
    out.append(check("cam-sawtooth-5-9", "package transient vs periodic", "max |q(12th period) - q_periodic|", 0.0,
                     float(np.max(np.abs(osc.response(ts, [0, 0])[:, 0] - per[:, 0]))), 1e-9, scale=1.0))
    H = 4000
    fs = fourier_series(F, tau, H)
    pr = periodic_response(_sawtooth_system(k, n), loads=[PeriodicLoad(np.array([1.0]), fs)], method="modal",
                           n_modes=1)   # the single mode: modal superposition is exact here
    tail_q = k**2 / (math.pi * 1.3**2 * H**2) * 2
    tail_v = 2 * k**2 / (math.pi * 1.3 * H**2)    # at tau/2 the velocity tail alternates: first omitted term
    out.append(check("cam-sawtooth-5-9", "Fourier superposition (5.44)-(5.45)", "q(0)", z[0], float(pr([0.0])[0, 0]),
                     tail_q, scale=1.0, note=f"tail bound {tail_q:.1e}"))
    qq = pr(np.linspace(0, tau, 13)[1:-1])[:, 0]
    out.append(check("cam-sawtooth-5-9", "Fourier superposition", "max |q - exact| inside the period", 0.0,
                     float(np.max(np.abs(qq - osc.response(np.linspace(0, tau, 13)[1:-1])[:, 0]))), tail_q, scale=1.0))
    out.append(check("cam-sawtooth-5-9", "Fourier superposition", "q'(tau/2) (alternating tail)",
                     float(osc.response([tau / 2])[0, 1]), float(pr([tau / 2], 1)[0, 0]), tail_v, scale=1.0))
    # undamped V5.9a (W = t/tau, i.e. a = 1/k^2, c = 1)
    osc0 = PiecewiseOscillator.forced(PiecewiseLaw([0.0, tau], [[0.0, 1.0 / tau]], periodic=True), k, 0.0, inertia=1.0)
    t6 = np.arange(6) * tau / 6
    q0 = osc0.response(t6)[:, 0] * k * k
    for t, qq_, txt in zip(t6, q0, ("0.500000", "0.404804", "-0.261934", "0.500000", "1.261934", "0.595196")):
        v, tol = printed(txt)
        out.append(check("cam-sawtooth-5-9", "digest V5.9a", f"undamped q(t = {t / tau * 6:.0f} tau/6)", v, qq_, tol))
    out.append(check("cam-sawtooth-5-9", "closed form (5.50)", "undamped: max |exact - closed form|", 0.0,
                     float(np.max(np.abs(q0 - ref.sawtooth_undamped(t6, k, tau)))), 1e-12, scale=1.0))
    return out


@case("cam-follower-methods", group="cam")
def cam_follower_methods():
    """A cam-driven elastic follower (6.1): dwell-rise-dwell-return, cycloidal rise / harmonic return
    (h = 0.02 m, 100 deg / 60 deg / 100 deg), omega0 = 20 rad/s, k = 170 rad/s, lambda = 0.2 (the book's
    numbers of §6.2).  The package's exact periodic solution against (a) DOP853 over one cycle from the
    periodic state restarted at every knot (rtol 1e-12; max error relative to max|q| < 1e-8), (b) Fourier
    superposition of harmonic responses of a lumped follower driven by the cam (periodic_response with the
    law as base motion, 400 harmonics; the law is C1 with acceleration jumps (coefficients ~ 1/j^3), so the
    error in q decays like 1/H^2: observed 2.7e-8 at H = 400, asserted 1e-7), (c) the accompanying amplitude
    at the return's soft impacts: Table 6.1's D = omega0^2 |Delta Pi''|/k^2 against the exact (6.4) jump, which
    divides by 1 - (w/k)^2 for the harmonic return's own frequency w = pi omega0/beta (exact 1e-12 when
    undamped) and changes by O(2 delta) with damping (bound (w/k)^2/(1 - (w/k)^2) + 2 delta)."""
    out = []
    h, w0, k, lam = 0.02, 20.0, 170.0, 0.2
    law = dwell_rise_dwell_return(h, math.radians(100), math.radians(60), math.radians(100),
                                  law="cycloidal", return_law="harmonic")
    n = lam * k / (2 * math.pi)
    lt = law.in_time(w0)
    osc = PiecewiseOscillator.follower(lt, k, n)
    ss = osc.steady_state(100)
    qmax = float(np.max(np.abs(ss.q)))
    z0 = np.array([ss.q0, ss.dq0])
    knots = list(lt.knots)
    W = lt.derivative(2)

    def rhs(i):
        return lambda t, y: [y[1], -float(W.piece_value(i, t - knots[i], 0)) - 2 * n * y[1] - k * k * y[0]]

    kicks = [(0.0, 0.0)] * len(knots)
    ts = ss.t[:-1]
    num = ref.integrate_piecewise([rhs(i) for i in range(lt.n_pieces)], knots, kicks, z0, ts)
    out.append(check("cam-follower-methods", "DOP853 over one cycle", "max |q_exact - q_DOP853| / max|q|", 0.0,
                     float(np.max(np.abs(num[:, 0] - ss.q[:-1]))) / qmax, 1e-8, scale=1.0))
    out.append(check("cam-follower-methods", "periodicity (5.46)", "relative residual", 0.0, ss.residual, 1e-12, scale=1.0))
    mdl = LumpedModel(bodies=[Body("follower", 1.0)], drivers=[Driver("cam", velocity=0.0)],
                      springs=[Link(("cam", "follower"), k * k)], dampers=[Link(("cam", "follower"), 2 * n)])
    ls = mdl.linear_system()
    cam = ls.dof_index(name="cam")
    fol = ls.dof_index(name="follower")
    fs = fourier_series(lt, lt.span, 400)
    pr = periodic_response(ls, base_motion={cam: fs}, outputs=[fol])
    qF = pr(ts)[:, 0] - lt(ts)
    out.append(check("cam-follower-methods", "Fourier superposition (periodic_response)", "max |q_exact - q_Fourier| / max|q|",
                     0.0, float(np.max(np.abs(qF - ss.q[:-1]))) / qmax, 1e-7, scale=1.0))
    rows = [r for r in discontinuity_table(law, w0, k) if r.order == 2 and r.phase > math.radians(150)]
    wr = math.pi * w0 / math.radians(100)
    ratio = 1 / (1 - (wr / k) ** 2)
    kx = osc.knot_excitation()
    kx0 = PiecewiseOscillator.follower(lt, k, 0.0).knot_excitation()
    for r in rows:
        j = int(np.argmin(np.abs(kx.t * w0 - r.phase)))
        tag = f"soft impact at phi = {math.degrees(r.phase):.0f} deg"
        out.append(check("cam-follower-methods", "exact (6.4), undamped", f"{tag}: D_exact/D_table = 1/(1 - (w/k)^2)",
                         ratio, float(kx0.D[j]) / r.D, 1e-12))
        out.append(check("cam-follower-methods", "exact (6.4), damped", f"{tag}: D_exact vs Table 6.1 D", r.D,
                         float(kx.D[j]), ratio - 1 + 2 * lam / (2 * math.pi)))
    return out
