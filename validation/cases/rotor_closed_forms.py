"""Rotordynamics against closed forms: textbook §5.12 self-centring, the gyroscopic disc on a
massless cantilever, the anisotropic Jeffcott rotor, the stability threshold with cross-coupled
stiffness, the spinning simply supported Timoshenko shaft.

The rotor finite element (Nelson-McVaugh Timoshenko element) solves the static beam exactly, so
models with a massless shaft (rho = 0: all inertia in the discs) reproduce the closed forms to
round-off whatever the mesh; tolerances there are 1e-9 (a few hundred eps of the conditioning of
these small, stiff problems; measured 1e-13 ... 1e-11)."""
from __future__ import annotations

import math

import numpy as np

from fem.rotor import (Bearing, Disc, Probe, Rotor, ShaftSegment, Support, Unbalance, campbell, rotor_modes,
                       stability_threshold, unbalance_response, undamped_critical_speeds)
from fem.sections import Material
from validation.analytic import rotor as ref
from validation.registry import case, check, claim, printed

STEEL = Material(E=211e9, G=81.2e9, rho=7810.0)
MASSLESS = Material(E=211e9, G=81.2e9, rho=0.0)
NU = STEEL.E / (2 * STEEL.G) - 1
KAPPA = ref.cowper_solid(NU)
SRC_512 = "seed 001 §5.12 (5.65)-(5.66); digest textbook_ch2-5.md"


def _jeffcott(L=0.8, d=0.03, m=10.0, n=4, **kw):
    """Massless shaft, point-mass disc at mid-span, rigid short supports at both ends."""
    return Rotor([ShaftSegment(L, n, d, MASSLESS)], discs=[Disc(L / 2, m)], supports=[Support(0.0), Support(L)], **kw)


@case("rotor-self-centring-5-12", group="rotor")
def self_centring():
    """§5.12: the centre of mass of an eccentric disc whirls at r = e / |1 - (w/w*)^2| (undamped).
    The unbalance response of the Jeffcott rotor (massless shaft, disc at mid-span) gives the
    shaft-centre amplitude U; the centre of mass is U + e (same rotating phase), so r/e = |U + e|/e.
    Tolerance: half a unit of the printed digit (the model itself is exact to ~1e-12).  The
    critical speed w* = sqrt(c/m) (c_eff = c - m w^2 = 0 there) is checked from the linear
    critical-speed eigenproblem to 1e-9, and the printed band 0.7 <= w/w* <= 1.4 must contain it."""
    name = "rotor-self-centring-5-12"
    L, d, m, e = 0.8, 0.03, 10.0, 1e-4
    A, I, _ = ref.circle(d)
    c = ref.simply_supported_midspan_stiffness(STEEL.E, STEEL.G, KAPPA, A, I, L)
    w_star = math.sqrt(c / m)
    rotor = _jeffcott(L, d, m)
    out = []
    crit = undamped_critical_speeds(rotor, 1).speeds_rad_s[0]
    out.append(check(name, SRC_512, "critical speed w* = sqrt(c/m) [rad/s] (c_eff = c - m w^2 = 0)", w_star, crit, 1e-9))
    ratios = [float(s) for s, _ in ref.TEXTBOOK_5_12]
    res = unbalance_response(rotor, [Unbalance(L / 2, m * e)], np.array(ratios) * w_star,
                             probes=[Probe(L / 2, "major")], find_peaks=False)
    F = res.probes[0].value                       # forward circle of the shaft centre (phase of the unbalance)
    r_over_e = np.abs(F + e) / e
    for (s_txt, r_txt), got in zip(ref.TEXTBOOK_5_12, r_over_e):
        val, tol = printed(r_txt)
        out.append(check(name, SRC_512, f"r/e at w/w* = {s_txt}", val, got, tol))
        out.append(check(name, "(5.66) closed form", f"r/e at w/w* = {s_txt} (exact)", ref.self_centring_ratio(float(s_txt)),
                         got, 1e-9))
    lo, hi = (float(v) for v in ref.TEXTBOOK_5_12_BAND)
    out.append(claim(name, SRC_512, "the band to avoid 0.7 <= w/w* <= 1.4 contains the critical speed",
                     lo * w_star < crit < hi * w_star))
    return out


@case("rotor-gyroscopic-cantilever-disc", group="rotor")
def gyroscopic_cantilever():
    """Rigid disc (m, Id, Ip) at the tip of a massless Timoshenko cantilever: forward and backward
    whirl frequencies against the quartic (k11 - m w^2)(k22 - Id w^2 + Ip Omega w) = k12^2 of the
    module :mod:`validation.analytic.rotor`, at 0, 500, 1500 and 4000 rad/s (Ip/Id = 1.9: the
    forward tilting mode stiffens strongly).  One element suffices (exact tip stiffness); 3 are
    used.  Tolerance 1e-9 (measured ~1e-12).  Claims: the forward frequencies rise and the
    backward ones fall with speed, as gyroscopic stiffening/softening requires."""
    name = "rotor-gyroscopic-cantilever-disc"
    L, d = 0.4, 0.04
    disc = Disc.from_geometry(L, 0.03, 0.3, 0.0, 7810.0)
    rotor = Rotor([ShaftSegment(L, 3, d, MASSLESS)], discs=[disc], supports=[Support(0.0, ("v", "w", "theta_y", "theta_z"))])
    A, I, _ = ref.circle(d)
    k11, k12, k22 = ref.cantilever_tip_stiffness(STEEL.E, STEEL.G, KAPPA, A, I, L)
    out, fw_prev, bw_prev, mono = [], None, None, True
    for speed in (0.0, 500.0, 1500.0, 4000.0):
        fw, bw = ref.disc_whirl_frequencies(disc.mass, disc.Id, disc.Ip, k11, k12, k22, speed)
        m = rotor_modes(rotor, speed, 4)
        got_f, got_b = _split(m, speed)
        for j in range(2):
            out.append(check(name, "closed form (disc on massless cantilever)",
                             f"forward whirl w_{j + 1} at {speed:g} rad/s [rad/s]", fw[j], got_f[j], 1e-9))
            out.append(check(name, "closed form (disc on massless cantilever)",
                             f"backward whirl w_{j + 1} at {speed:g} rad/s [rad/s]", bw[j], got_b[j], 1e-9))
        if speed > 0 and fw_prev is not None:
            mono &= bool(np.all(fw > fw_prev - 1e-9) and np.all(bw < bw_prev + 1e-9))
        fw_prev, bw_prev = fw, bw
    out.append(claim(name, "gyroscopic effect", "forward whirl frequencies rise, backward fall with speed", mono))
    return out


@case("rotor-jeffcott-anisotropic", group="rotor")
def jeffcott_anisotropic():
    """Jeffcott rotor on anisotropic bearings (k_y = 2 MN/m, k_z = 0.5 MN/m at both ends, in
    series with the shaft's mid-span stiffness), point-mass disc, damper c at the disc: two
    critical speeds sqrt(k_y/m), sqrt(k_z/m) (no gyroscopic coupling for a point mass), found as
    roots of omega(Omega) = Omega by Brent's method on the Campbell diagram (tolerance 1e-8:
    the root is converged to 1e-10 relative).  Unbalance response: each direction is an SDOF
    driven by m e Omega^2, so the v- and w-probe peaks lie at w_n / sqrt(1 - 2 zeta^2) and the
    amplification factors Nc/(N2 - N1) follow from the exact half-power speeds (module notes);
    the peak is refined by bounded maximisation (1e-9) and the half-power speeds by root finding,
    tolerance 1e-6 on the speeds and the AF."""
    name = "rotor-jeffcott-anisotropic"
    L, d, m, c = 0.8, 0.03, 10.0, 150.0
    ky, kz = 2e6, 0.5e6
    A, I, _ = ref.circle(d)
    ks = ref.simply_supported_midspan_stiffness(STEEL.E, STEEL.G, KAPPA, A, I, L)
    k_eff = {"v": ref.series(ks, 2 * ky), "w": ref.series(ks, 2 * kz)}
    rotor = Rotor([ShaftSegment(L, 4, d, MASSLESS)], discs=[Disc(L / 2, m)],
                  bearings=[Bearing(0.0, kyy=ky, kzz=kz), Bearing(L, kyy=ky, kzz=kz), Bearing(L / 2, cyy=c, czz=c)])
    wn = {k: math.sqrt(v / m) for k, v in k_eff.items()}
    camp = campbell(rotor, np.linspace(0.0, 1.6 * max(wn.values()), 17), 2)
    crit = sorted(cs.speed_rad_s for cs in camp.crossings)
    src = "closed form (Jeffcott rotor, series springs)"
    out = [check(name, src, "critical speed 1 (soft direction z) [rad/s]", wn["w"] * _damped(c, m, wn["w"]), crit[0], 1e-8),
           check(name, src, "critical speed 2 (stiff direction y) [rad/s]", wn["v"] * _damped(c, m, wn["v"]), crit[1], 1e-8),
           claim(name, src, "two critical speeds below 1.6 w_y", len(crit) == 2, note=f"found {len(crit)}")]
    speeds = np.linspace(0.3 * wn["w"], 1.8 * wn["v"], 300)
    res = unbalance_response(rotor, [Unbalance(L / 2, 1e-3)], speeds, probes=[Probe(L / 2, "v"), Probe(L / 2, "w")])
    for j, f in enumerate(("v", "w")):
        zeta = c / (2 * math.sqrt(k_eff[f] * m))
        s_pk, _, (s1, s2) = ref.sdof_unbalance_peak(zeta)
        pk = [p for p in res.peaks if p.probe == j]
        pk = min(pk, key=lambda p: abs(p.speed_rad_s - s_pk * wn[f])) if pk else None
        out.append(claim(name, src, f"{f}-probe peak found", pk is not None))
        if pk is None:
            continue
        out.append(check(name, src, f"{f}-probe peak speed w_n/sqrt(1 - 2 zeta^2) [rad/s]", s_pk * wn[f], pk.speed_rad_s, 1e-6))
        out.append(check(name, src, f"{f}-probe amplification factor (exact half-power)", s_pk / (s2 - s1),
                         pk.amplification_factor if pk.amplification_factor else np.nan, 1e-6))
    return out


def _split(m, speed):
    """(forward, backward) frequencies, ascending; at zero speed the repeated pairs, whose whirl
    is undefined (any orbit), count as both."""
    w = m.omega_damped_rad_s
    if speed == 0:
        pairs = np.sort(w)[0::2]
        return pairs, pairs
    return (np.sort(w[[x == "forward" for x in m.whirl]]), np.sort(w[[x == "backward" for x in m.whirl]]))


def _damped(c, m, wn):
    """Crossing of the damped frequency w_d = w_n sqrt(1 - zeta^2) with the 1x line: w_d / w_n."""
    zeta = c / (2 * m * wn)
    return math.sqrt(1 - zeta * zeta)


@case("rotor-stability-threshold", group="rotor")
def stability():
    """Jeffcott rotor with a seal at the disc: damping c and cross-coupled stiffness
    k_yz = -k_zy = beta Omega (a speed table, linear, so its interpolation is exact): the forward
    mode loses stability at Omega_th = c w_n / beta (module notes).  The scan brackets, Brent's
    method converges the damping ratio's root to 1e-10; tolerance 1e-8.  Claims: the unstable mode
    whirls forward at w_n."""
    name = "rotor-stability-threshold"
    L, d, m, c, beta = 0.8, 0.03, 10.0, 200.0, 30.0
    A, I, _ = ref.circle(d)
    k = ref.simply_supported_midspan_stiffness(STEEL.E, STEEL.G, KAPPA, A, I, L)
    th = ref.jeffcott_threshold(m, k, c, beta)
    top = 3 * th
    rotor = _jeffcott(L, d, m, bearings=[Bearing(L / 2, cyy=c, czz=c, kyz=[0.0, beta * top], kzy=[0.0, -beta * top],
                                                 speeds=[0.0, top])])
    res = stability_threshold(rotor, 2 * th, 2, n_grid=11)
    src = "closed form (Jeffcott rotor with cross-coupled stiffness)"
    return [check(name, src, "threshold speed c sqrt(k/m)/beta [rad/s]", th,
                  res.threshold_rad_s if res.threshold_rad_s else np.nan, 1e-8),
            check(name, src, "whirl frequency at the threshold sqrt(k/m) [rad/s]", math.sqrt(k / m),
                  res.frequency_rad_s if res.frequency_rad_s else np.nan, 1e-8),
            claim(name, src, "the destabilised mode whirls forward", res.whirl == "forward", note=str(res.whirl))]


@case("rotor-spinning-timoshenko-shaft", group="rotor")
def spinning_shaft():
    """Simply supported uniform spinning Timoshenko shafts against the exact quartic (module
    notes), forward and backward whirl of modes 1-3 at 0 and 3000 rad/s.

    Convergence of the Nelson-McVaugh element measured here: its interpolation solves the static
    beam exactly and reduces to the Hermite cubic for Phi = 12 EI/(kappa G A h^2) << 1, where the
    frequencies converge at O(h^4) (slender shaft L/d = 60, 4 -> 8 elements: observed order 3.6-3.8);
    once the elements are shorter than about the diameter (Phi >> 1) it tends to linear
    interpolation of deflection and rotation, and the consistent mass converges at O(h^2) (stubby
    shaft L/d = 6, 48 -> 96 elements: order 2.00).  Checks: the order claims; the Richardson
    extrapolation of order 2 from 48 and 96 elements of the stubby shaft against the exact roots,
    tolerance 3e-7 (measured 1.1e-7: the remainder is the next order), which shows that the
    limit is the Timoshenko theory with gyroscopics and nothing else; the 32-element slender shaft's
    mode 1 to 5e-7 (measured 2.8e-7)."""
    name = "rotor-spinning-timoshenko-shaft"
    src = "spinning SS Timoshenko shaft (exact quartic)"
    out = []
    for L, d, meshes in ((0.6, 0.1, (48, 96)), (1.5, 0.025, (4, 8, 32))):
        A, I, Ip = ref.circle(d)
        for speed in (0.0, 3000.0):
            exact = np.array([ref.spinning_timoshenko_ss(STEEL.E, STEEL.G, KAPPA, STEEL.rho, A, I, Ip, L, n, speed)
                              for n in (1, 2, 3)])
            got = {}
            for ne in meshes:
                m = rotor_modes(Rotor([ShaftSegment(L, ne, d, STEEL)], supports=[Support(0.0), Support(L)]), speed, 8)
                fw, bw = _split(m, speed)
                got[ne] = np.column_stack([fw[:3], bw[:3]])
            tag = f"L/d = {L / d:.0f}, {speed:g} rad/s"
            if L / d < 10:
                e48, e96 = np.abs(got[48] / exact - 1), np.abs(got[96] / exact - 1)
                order = np.log2(e48 / e96)
                out.append(claim(name, "discretisation order", f"O(h^2) for Phi >> 1 ({tag})",
                                 bool(np.all((order > 1.9) & (order < 2.1))),
                                 note=f"orders {order.min():.2f}-{order.max():.2f}, Phi = "
                                      f"{12 * STEEL.E * I / (KAPPA * STEEL.G * A * (L / 96) ** 2):.0f} at 96 el."))
                rich = got[96] + (got[96] - got[48]) / 3.0
                for n in range(3):
                    for k, w in enumerate(("forward", "backward")):
                        out.append(check(name, src, f"{w} w_{n + 1}, {tag}, Richardson 48/96 el. [rad/s]",
                                         exact[n, k], rich[n, k], 3e-7))
            else:
                e4, e8 = np.abs(got[4] / exact - 1), np.abs(got[8] / exact - 1)
                order = np.log2(e4 / e8)
                out.append(claim(name, "discretisation order", f"O(h^4) for Phi << 1 ({tag})", bool(np.all(order > 3.5)),
                                 note=f"orders {order.min():.2f}-{order.max():.2f}"))
                for k, w in enumerate(("forward", "backward")):
                    out.append(check(name, src, f"{w} w_1, {tag}, 32 el. [rad/s]", exact[0, k], got[32][0, k], 5e-7))
    return out
