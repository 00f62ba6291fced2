"""Plain journal bearings computed from their geometry (:mod:`fem.rotor.bearings`) against closed forms,
a published finite-bearing table, and the stability threshold of a Jeffcott rotor; the oil-whip
run-up against the linear threshold."""
from __future__ import annotations

import math

import numpy as np

from fem.rotor import Disc, Rotor, RunUp, ShaftSegment, Unbalance, assemble_rotor, run_up, stability_threshold
from fem.rotor.bearings.journal import JournalBearing
from fem.rotor.bearings.reynolds import ReynoldsFilm
from fem.rotor.whirl_spectrum import whirl_onset
from fem.sections import Material
from validation.analytic import bearings as ref
from validation.registry import case, check, claim

EPS = 0.5


def _load_and_attitude(f) -> tuple[float, float]:
    """|f| and the attitude angle (deg) of a film force f on a journal displaced along +y."""
    return float(np.hypot(*f)), math.degrees(math.atan2(f[1], -f[0]))


def _extrapolated(length_ratio: float, n_theta: int, n_axial: int, cavitation: str = "gumbel") -> np.ndarray:
    """The film force at EPS on two meshes (h, h/2) and its Richardson extrapolation (order 2)."""
    f1 = ReynoldsFilm(length_ratio, n_theta, n_axial, cavitation).force(EPS, 0.0, -6 * EPS, 0.0)
    f2 = ReynoldsFilm(length_ratio, 2 * n_theta, 2 * n_axial, cavitation).force(EPS, 0.0, -6 * EPS, 0.0)
    return (4 * f2 - f1) / 3


@case("bearing-reynolds-short-limit", group="bearings")
def short_limit():
    """The finite film (Guembel's condition, eccentricity ratio 0.5) tends to Ocvirk's short-bearing
    closed form as L/D -> 0.  The finite solution is Richardson-extrapolated from two meshes (72 x 8
    and 144 x 16 elements on the half bearing; the P1 discretisation is second order, its remaining
    error ~1e-5 of the load), so what is compared is the L/D effect itself: the short bearing neglects
    the circumferential pressure flow, whose relative size is (L/D)^2, so the relative load error
    falls by 4 per halving of L/D (observed order within [1.8, 2.2]) and is below 1 % at L/D = 1/16."""
    name = "bearing-reynolds-short-limit"
    src = "Ocvirk short bearing (Dubois & Ocvirk, NACA Rep. 1157, 1953), validation.analytic.bearings"
    out, errs = [], []
    for ld in (1 / 4, 1 / 8, 1 / 16):
        f = _extrapolated(ld, 72, 8)
        W, att = _load_and_attitude(f)
        Fr, Ft = ref.ocvirk_forces(EPS, ld)
        W0, att0 = math.hypot(Fr, Ft), math.degrees(math.atan2(Ft, Fr))
        errs.append(abs(W / W0 - 1))
        if ld == 1 / 16:
            out.append(check(name, src, "L/D = 1/16: load W c^2 / (mu omega R^4)", W0, W, 1e-2,
                             note=f"L/D = 1/4, 1/8, 1/16 errors {[f'{e:.2e}' for e in errs]}"))
            out.append(check(name, src, "L/D = 1/16: attitude angle [deg]", att0, att, 1e-2))
    for k in range(2):
        order = math.log2(errs[k] / errs[k + 1])
        out.append(check(name, "the short-bearing approximation's error is O((L/D)^2)",
                         f"observed order in L/D from L/D = {['1/4', '1/8'][k]} to half of it", 2.0, order, 0.1))
    return out


@case("bearing-reynolds-long-limit", group="bearings")
def long_limit():
    """The finite film (Guembel, eccentricity ratio 0.5) tends to Sommerfeld's long bearing as
    L/D -> oo.  Two measures: (1) the load per unit length at the mid-plane (from the nodal
    pressure at zeta = 0) converges exponentially: the end's disturbance of the first circumferential
    harmonic decays like exp(-z/R), so at the half length L/2 = (L/D) R its relative size is
    ~exp(-L/D): observed decay rate ln(e_4 / e_8) / 4 within 20 % of 1, and at L/D = 8 within 1e-3 of
    the closed form (exp(-8) = 3e-4 plus the mesh's ~1e-4); (2) the total load per unit length
    carries the O(D/L) end deficit: observed order in D/L of its error within [0.9, 1.1], and the
    Richardson extrapolation in D/L from L/D = 4 and 8 within 2e-3 (next term O((D/L)^2))."""
    name = "bearing-reynolds-long-limit"
    src = "Sommerfeld long bearing, half-Sommerfeld film (validation.analytic.bearings; checked by quadrature)"
    Fr, Ft = ref.sommerfeld_forces(EPS, 0.5)                   # per unit of L/R
    Fq = ref.sommerfeld_forces_by_quadrature(EPS)
    out = [check(name, "quadrature of Sommerfeld's pressure", "closed-form radial force per unit length", Fq[0], Fr,
                 1e-12),
           check(name, "quadrature of Sommerfeld's pressure", "closed-form tangential force per unit length", Fq[1], Ft,
                 1e-12)]
    W0 = math.hypot(Fr, Ft)
    ratios, mids = {}, {}
    for ld in (2.0, 4.0, 8.0):
        film = ReynoldsFilm(ld, 144, int(16 * ld), "gumbel")
        sol = film.solve(EPS, 0.0, -6 * EPS, 0.0)
        ratios[ld] = float(np.hypot(*sol.force)) / (2 * ld) / W0
        mid = film.zeta == 0.0                       # the mid-plane's nodal pressure, trapezoidal around
        order = np.argsort(film.theta[mid])
        th, P = film.theta[mid][order], np.maximum(sol.P[mid][order], 0.0)
        th, P = np.r_[th, th[0] + 2 * math.pi], np.r_[P, P[0]]
        fm = np.array([-np.trapezoid(P * np.cos(th), th), -np.trapezoid(P * np.sin(th), th)])
        mids[ld] = float(np.hypot(*fm)) / W0
    out.append(check(name, src, "L/D = 8: mid-plane load per unit length / Sommerfeld's", 1.0, mids[8.0], 1e-3,
                     note=f"L/D = 2, 4, 8: {mids}"))
    rate = math.log(abs(1 - mids[4.0]) / abs(1 - mids[8.0])) / 4.0
    out.append(check(name, "the end's disturbance decays like exp(-z/R)", "mid-plane: decay rate per radius "
                     "(L/D 4 -> 8)", 1.0, rate, 0.2))
    e = {ld: 1 - r for ld, r in ratios.items()}
    out.append(check(name, "the end effect of a long bearing is O(D/L)", "observed order in D/L (L/D 4 -> 8)", 1.0,
                     math.log2(e[4.0] / e[8.0]), 0.1, note=f"load / Sommerfeld's: {ratios}"))
    out.append(check(name, src, "Richardson (in D/L) of the total load per length, L/D = 4 and 8", 1.0,
                     2 * ratios[8.0] - ratios[4.0], 2e-3))
    return out


@case("bearing-reynolds-mesh-convergence", group="bearings")
def mesh_convergence():
    """The finite film with Reynolds' cavitation (L/D = 1, eccentricity ratio 0.6) on meshes of 36 x 4,
    72 x 8 and 144 x 16 elements (half bearing): the load converges with an observed order near 2 (P1
    elements; the free boundary of the Swift-Stieber condition has zero pressure gradient, so the
    solution stays smooth enough; orders within [1.6, 2.4] accepted), and the finest mesh (the
    default 144 x 16) lies within 5e-3 of the Richardson extrapolation: its discretisation error at
    L/D = 1, measured 2.5e-3 (L/D = 0.5 with the same mesh: ~6e-4).  A fourth
    mesh (288 x 32, 4 s) gave the same order (1.950 against 1.950) when the case was written."""
    name = "bearing-reynolds-mesh-convergence"
    W = []
    for n in (36, 72, 144):
        f = ReynoldsFilm(1.0, n, n // 9).force(0.6, 0.0, -3.6, 0.0)
        W.append(float(np.hypot(*f)))
    order = math.log2(abs(W[0] - W[1]) / abs(W[1] - W[2]))
    rich = W[2] + (W[2] - W[1]) / (2 ** order - 1)
    src = "successive mesh refinement (h, h/2, h/4)"
    return [check(name, src, "observed order of the load", 2.0, order, 0.2, note=f"loads {W}"),
            check(name, src, "finest load against its Richardson extrapolation", rich, W[2], 5e-3)]


# Lund & Thomsen (1978), two-axial-groove bearing (two 20-degree grooves at the horizontal split,
# 160-degree pads, Swift-Stieber cavitation): rows (S, eps, phi, Kxx, Kxy, Kyx, Kyy, Bxx, Bxy, Byy)
# with x along the (downward) load, y horizontal, the shaft turning from x to y.  L/D = 0.5: all the
# table's rows from S = 6.43 to 0.042 at eps 0.07-0.88 (every other row); L/D = 1: five rows (the
# S = 0.358 row is left out: its Kyy 1.48 breaks its neighbours' trend 1.56/1.52/1.55).  Transcribed
# in the DTU course notes 41524 (I. F. Santos) and in ROSS's tests (test_fluid_film_literature.py);
# the two transcriptions agree on every common row.
LUND_THOMSEN = {
    0.5: [(6.430, 0.071, 81.89, 1.55, 14.41, -6.60, 1.88, 28.75, 1.89, 13.31),
          (2.634, 0.165, 72.36, 1.61, 6.74, -3.01, 1.91, 13.36, 2.00, 6.28),
          (1.656, 0.244, 65.85, 1.69, 5.06, -2.20, 1.95, 9.93, 2.15, 4.80),
          (0.580, 0.477, 51.01, 2.67, 3.70, -0.78, 1.75, 6.96, 1.94, 2.40),
          (0.244, 0.655, 40.25, 4.21, 3.74, -0.13, 1.64, 6.87, 1.82, 1.54),
          (0.151, 0.734, 35.20, 5.48, 3.98, 0.15, 1.61, 7.26, 1.79, 1.27),
          (0.086, 0.809, 30.04, 7.51, 4.42, 0.47, 1.59, 8.03, 1.79, 1.03),
          (0.042, 0.879, 24.41, 11.45, 5.23, 0.92, 1.60, 9.48, 1.80, 0.82)],
    1.0: [(0.991, 0.150, 70.58, 1.56, 7.29, -2.16, 1.52, 14.66, 1.58, 4.49),
          (0.635, 0.224, 63.54, 1.62, 5.33, -1.57, 1.56, 10.80, 1.70, 3.41),
          (0.235, 0.460, 49.27, 2.19, 3.57, -0.80, 1.55, 7.36, 1.89, 2.19),
          (0.159, 0.559, 44.33, 2.73, 3.36, -0.48, 1.48, 6.94, 1.78, 1.74),
          (0.108, 0.650, 39.72, 3.45, 3.34, -0.23, 1.44, 6.89, 1.72, 1.43)],
}


def lund_thomsen_frame(st, W: float, c: float, omega: float) -> dict:
    """An operating point (drivefem's y across, z up, load along -z) in Lund & Thomsen's frame."""
    K, C = st.K * c / W, st.C * c * omega / W
    return {"eps": st.eccentricity, "phi": st.attitude_deg, "Kxx": K[1, 1], "Kxy": -K[1, 0], "Kyx": -K[0, 1],
            "Kyy": K[0, 0], "Bxx": C[1, 1], "Bxy": -C[1, 0], "Byy": C[0, 0]}


@case("bearing-journal-lund-thomsen", group="bearings", slow=True)
def lund_thomsen():
    """Sommerfeld number -> eccentricity, attitude angle and the 8 dynamic coefficients of the
    two-axial-groove bearing (L/D = 0.5 and 1) against Lund & Thomsen's published finite-bearing table
    (Lund, J. W. & Thomsen, K. K. (1978), 'A calculation method and data for the dynamic
    coefficients of oil-lubricated journal bearings', ASME, Topics in Fluid Film Bearing and Rotor
    Bearing System Design and Optimization, pp. 1-28; two-axial-groove bearing tables for L/D = 0.5
    and 1.0).  drivefem solves the same film (isoviscous, Swift-Stieber, 20-degree grooves at
    ambient pressure) at the table's Sommerfeld number: mesh 144 x 16 (L/D = 0.5) and 144 x 32
    (L/D = 1), converged to ~0.2 % in the coefficients against twice as fine (measured).

    Tolerances: the table prints 3-4 digits, but it is itself a finite-difference solution of 1978
    whose discretisation error is larger than its last digit (the differences to the converged film
    are systematic, measured up to 1.3 % of a row's largest coefficient, 0.1 deg and 0.0011 in eps,
    and the L/D = 1 table has an outlier row); the checks are therefore eps within 0.002, the
    attitude angle within 0.15 deg, and each coefficient within 2 % of the largest coefficient of its
    matrix (K or B) in the row.  How many
    entries also agree within half a printed digit is reported in the note of each L/D's last check."""
    name = "bearing-journal-lund-thomsen"
    src = "Lund & Thomsen (1978), two-axial-groove bearing table"
    D, c, mu, rpm = 0.1, 1e-4, 0.02, 3000.0
    w = rpm * math.pi / 30
    out = []
    for ld, rows in LUND_THOMSEN.items():
        L = ld * D
        within, total = 0, 0
        for row in rows:
            S = row[0]
            W = mu * rpm / 60 * L * D * (D / 2 / c) ** 2 / S
            b = JournalBearing(0.0, diameter=D, length=L, clearance=c, viscosity=mu, load=W, speeds=[w, 2 * w],
                               mesh=(144, 16 if ld == 0.5 else 32),
                               grooves=((0.0, math.radians(20.0)), (math.pi, math.radians(20.0))))
            got = lund_thomsen_frame(b.operating_point(w), W, c, w)
            table = dict(zip(("eps", "phi", "Kxx", "Kxy", "Kyx", "Kyy", "Bxx", "Bxy", "Byy"), row[1:]))
            for key, value in table.items():
                total += 1
                within += abs(got[key] - value) <= 0.5 * 10 ** (-len(f"{value}".split(".")[1])) * 1.0000001
            tag = f"L/D = {ld:g}, S = {S:g}"
            out.append(check(name, src, f"{tag}: eccentricity ratio", table["eps"], got["eps"], 0.002, scale=1.0))
            out.append(check(name, src, f"{tag}: attitude angle [deg]", table["phi"], got["phi"], 0.15, scale=1.0))
            kmax = max(abs(table[k]) for k in ("Kxx", "Kxy", "Kyx", "Kyy"))
            bmax = max(abs(table[k]) for k in ("Bxx", "Bxy", "Byy"))
            for key in ("Kxx", "Kxy", "Kyx", "Kyy", "Bxx", "Bxy", "Byy"):
                out.append(check(name, src, f"{tag}: {key} (relative to the row's largest)", table[key], got[key],
                                 0.02, scale=kmax if key[0] == "K" else bmax))
        out[-1].note = f"L/D = {ld:g}: {within} of {total} entries also within half a printed digit"
    return out


def _jeffcott(journal_mass: float = 4.0, speeds=None):
    """The Jeffcott rotor of the threshold and whip cases: a 20 kg disc at mid-span of a massless
    steel shaft (0.5 m x 50 mm), journals of ``journal_mass`` on two short journal bearings
    (D = 50 mm, L = 12.5 mm, c = 50 um, mu = 0.01 Pa s) carrying the weight."""
    mat = Material(E=211e9, G=81.2e9, rho=0.0)
    grid = list(np.linspace(600.0, 1500.0, 181)) if speeds is None else list(speeds)

    def jb(x):
        return JournalBearing(x, diameter=0.05, length=0.0125, clearance=50e-6, viscosity=0.01, film="short",
                              speeds=grid)

    return Rotor([ShaftSegment(0.5, 2, 0.05, mat)], discs=[Disc(0.0, journal_mass), Disc(0.25, 20.0),
                                                            Disc(0.5, journal_mass)], bearings=[jb(0.0), jb(0.5)])


def _jeffcott_reference(rotor) -> tuple[float, float]:
    """The closed-form threshold of :func:`_jeffcott` (see validation.analytic.bearings)."""
    d, Ls, E, G = 0.05, 0.5, 211e9, 81.2e9
    nu = E / (2 * G) - 1
    kap = 6 * (1 + nu) / (7 + 6 * nu)            # Cowper, solid circle (the element's default)
    I, A = math.pi * d ** 4 / 64, math.pi * d ** 2 / 4
    k_s = 1.0 / (Ls ** 3 / (48 * E * I) + Ls / (4 * kap * G * A))     # Timoshenko mid-span stiffness
    m_j = rotor.discs[0].mass
    W = (20.0 / 2 + m_j) * 9.81
    return ref.jeffcott_short_threshold(20.0, m_j, k_s, W, 0.01, 0.025, 0.0125, 50e-6, 600.0, 1500.0)


@case("bearing-jeffcott-threshold", group="bearings")
def jeffcott_threshold():
    """Stability threshold of a Jeffcott rotor (20 kg disc, massless 0.5 m x 50 mm shaft, 4 kg journals)
    on two short journal bearings computed from their geometry, against the closed-form threshold:
    Lund's equivalent stiffness and whirl ratio at neutral stability (Lund 1965) with the short
    bearing's closed-form coefficients (Friswell et al. 2010 §5.5.2) and the shaft's Timoshenko
    mid-span stiffness (derivation: validation.analytic.bearings).  drivefem's path is independent:
    the equilibrium by Newton on the closed-form film force, the coefficients by differentiating it,
    the pchip table over 181 speeds, and the complex modes of the finite-element rotor (the massless
    shaft condensed).  Tolerance 1e-5: the table's interpolation (pchip, h = 5 rad/s) and Brent's
    tolerance; the operating points themselves agree to ~1e-9."""
    name = "bearing-jeffcott-threshold"
    rotor = _jeffcott()
    rs = assemble_rotor(rotor)
    res = stability_threshold(rs, 1500.0, 4, speed_min=600.0, n_grid=30)
    w_ref, nu_ref = _jeffcott_reference(rotor)
    b = rotor.bearings[0]
    st = b.operating_point(w_ref)
    W = float(np.hypot(*b.static_load()))
    eps_ref = ref.short_eccentricity(W, 0.01, w_ref, 0.025, 0.0125, 50e-6)
    a, bb = ref.short_coefficients(eps_ref)
    src = "closed-form threshold (Lund 1965; short-bearing coefficients of Friswell et al. 2010)"
    return [check(name, src, "threshold speed [rad/s]", w_ref, res.threshold_rad_s, 1e-5),
            check(name, src, "whirl frequency at the threshold [rad/s]", nu_ref, res.frequency_rad_s, 1e-5),
            claim(name, src, "the unstable mode whirls forward", res.whirl == "forward"),
            check(name, "Ocvirk's load capacity", "eccentricity ratio at the threshold", eps_ref, st.eccentricity,
                  1e-9),
            check(name, "Friswell et al. (2010) short-bearing stiffness", "K_zy c / W (largest cross term)",
                  a[1, 0], st.K[1, 0] * 50e-6 / W, 1e-7),
            check(name, "Friswell et al. (2010) short-bearing damping", "C_zz c omega / W",
                  bb[1, 1], st.C[1, 1] * 50e-6 * w_ref / W, 1e-7)]


def _whip_checks(name: str, unb: float) -> list:
    rotor = _jeffcott()
    rs = assemble_rotor(rotor)
    w_ref, nu_ref = _jeffcott_reference(rotor)
    res = run_up(rs, RunUp(0.85 * w_ref, 1.15 * w_ref, 1.0, modes=6, start="rest", integrator="DOP853"),
                 [Unbalance(0.25, unb)] if unb else [], probes=[0.25])
    on = whirl_onset(res, 0.25)
    tag = f"unbalance {unb:g} kg m"
    src = "closed-form linear threshold (bearing-jeffcott-threshold)"
    out = [claim(name, src, f"{tag}: the run ends and shows an onset", res.stopped is None
                 and on.onset_speed is not None, note=str(res.stopped))]
    if on.onset_speed is None:
        return out
    return out + [check(name, src, f"{tag}: whirl onset speed [rad/s]", w_ref, on.onset_speed, 0.02),
                  check(name, src, f"{tag}: whirl frequency at the onset [rad/s]", nu_ref, on.whirl_frequency, 0.02),
                  claim(name, "oil whip: subsynchronous whirl near the natural frequency",
                        f"{tag}: whirl / speed at the end below 0.55", on.final_frequency / on.final_speed < 0.55,
                        note=f"{on.final_frequency / on.final_speed:.4f}; growth {on.growth:.3g}"),
                  check(name, "energy balance (works of every force integrated with the state)",
                        f"{tag}: relative balance error", 0.0, res.energy_error, 5e-8, scale=1.0)]


@case("bearing-whip-runup", group="bearings")
def whip_runup():
    """A run-up of the Jeffcott rotor of bearing-jeffcott-threshold through its stability threshold
    (0.85 -> 1.15 of the closed-form threshold in 1 s, starting from rest in the bearings: the
    journals lift off, which seeds the free whirl), with the nonlinear short-bearing film force in
    time and no unbalance.  The subsynchronous whirl decays below the threshold and grows above it;
    the minimum of its band-passed envelope is the onset (fem.rotor.whirl_spectrum).  Checks: onset
    speed within 2 % of the closed-form linear threshold (the issue's requirement; measured ~2e-4:
    the ramp is slow against the growth rate, ~15 /s at +-10 %), the whirl frequency at the onset
    within 2 % of the linear whirl frequency there, and the whirl locking near the rotor's natural
    frequency (ratio to the speed below 0.55 at the end: subsynchronous whip); the energy balance to
    5e-8 (DOP853 at rtol 1e-8: measured ~5e-9).  LSODA (the default with such bearings) gives the same
    onset to ~1e-6 with a balance of ~1e-6."""
    return _whip_checks("bearing-whip-runup", 0.0)


@case("bearing-whip-runup-unbalance", group="bearings", slow=True)
def whip_runup_unbalance():
    """bearing-whip-runup with an unbalance of 2e-5 kg m on the disc: the synchronous response is band-
    passed out of the whirl envelope; the same checks and tolerances (measured: onset 3.3e-3 early; a
    ten times larger unbalance moves the onset itself, by -7 %, and is not a test of the method)."""
    return _whip_checks("bearing-whip-runup-unbalance", 2e-5)
