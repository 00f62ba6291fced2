"""Rolling-element bearings computed from their geometry (:mod:`fem.rotor.bearings.rolling`): Hertzian
contact, the load zone's closed forms, the linearised stiffness, and the clearance-induced nonlinear
response of a rotor against an independent integration of the same equations."""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from fem.rotor import Disc, Rotor, RunUp, ShaftSegment, Unbalance, run_up
from fem.rotor.bearings.hertz import ball_contacts, effective_modulus
from fem.rotor.bearings.rolling import RollingBearing
from fem.sections import Material
from validation.analytic import bearings as ref
from validation.registry import case, check

# a 209-size deep-groove ball bearing (Harris's example geometry): D = 12.7 mm, d_m = 65 mm, f = 0.52
BALL_D, PITCH, CONFORMITY = 12.7e-3, 65e-3, 0.52
STEEL = (2.079e11, 0.3)


@case("bearing-hertz-point-contact", group="bearings")
def hertz_point_contact():
    """The ball's contacts with the inner and outer races of a 209-size bearing (D = 12.7 mm, d_m =
    65 mm, groove conformity 0.52, steel): the exact Hertz solution (ellipticity from the curvature
    difference with the complete elliptic integrals, Brent's method) against the closed-form
    approximations of Brewe & Hamrock (1977) quoted by Harris and by Hamrock & Dowson.  Tolerances
    are the approximations' own error: about 2 % on the ellipticity (3 % allowed), 0.1 % on the
    elliptic integrals (0.3 % allowed), and what these make of the load-deflection constant (3 %)."""
    name = "bearing-hertz-point-contact"
    src = "Brewe & Hamrock (1977) approximations of the point contact (validation.analytic.bearings)"
    E = effective_modulus(*STEEL, *STEEL)
    inner, outer = ball_contacts(BALL_D, PITCH, CONFORMITY, CONFORMITY, 0.0, E)
    g = BALL_D / PITCH
    out = []
    for tag, c, rx_inv in (("inner", inner, 2 / BALL_D + 2 / BALL_D * g / (1 - g)),
                           ("outer", outer, 2 / BALL_D - 2 / BALL_D * g / (1 + g))):
        ry_inv = 2 / BALL_D - 1 / (CONFORMITY * BALL_D)
        kappa, Em, Km = ref.brewe_hamrock(1 / rx_inv, 1 / ry_inv)
        R = 1 / (rx_inv + ry_inv)
        K_approx = math.pi * kappa * E * math.sqrt(2 * Em * R / 9) / Km ** 1.5
        out += [check(name, src, f"{tag} race: ellipticity a/b", kappa, c.kappa, 0.03),
                check(name, src, f"{tag} race: elliptic integral of the 2nd kind E", Em, c.E_m, 3e-3),
                check(name, src, f"{tag} race: elliptic integral of the 1st kind K", Km, c.K_m, 3e-3),
                check(name, src, f"{tag} race: Q = K delta^1.5, K [N/m^1.5]", K_approx, c.K, 0.03,
                      note=f"curvature difference F = {c.curvature_difference:.4f}")]
    return out


def _cage_average(b: RollingBearing, y: float, z: float, n: int = 4096) -> np.ndarray:
    """The elements' force averaged over the cage positions of one element pitch."""
    pitch = 2 * math.pi / b.elements
    return np.mean([b.elastic_force(y, z, c) for c in pitch * np.arange(n) / n], axis=0)


@case("bearing-rolling-load-zone", group="bearings")
def load_zone():
    """The bearing's law summed over its elements and averaged over the cage position equals
    Sjoevall's load-zone integral F_r = Z K_n delta^n J_r(eps) (Harris & Kotzalas 2007, ch. 7): for
    zero clearance 1/J_r(1/2) = 4.37 (balls) and 4.08 (rollers), Stribeck's constants as printed
    (NSK technical report E728g §5 Table 1; Harris) to half a unit of their last digit; with
    clearance (P_d / 2 = 0.3 delta_r: eps = 0.35) J_r by quadrature to 1e-6 (the cage average's
    trapezoidal error over 4096 positions, ~1e-8).  The linearised stiffness of a bearing with many
    elements (Z = 400, zero clearance) under the load W equals n W / delta_r (Euler's theorem for
    F_r ~ delta_r^n) to 1e-4 (the sum over 400 elements against the integral)."""
    name = "bearing-rolling-load-zone"
    out = []
    for element, printed in (("ball", 4.37), ("roller", 4.08)):
        b = RollingBearing(0.0, element=element, elements=9, contact_stiffness=1e10, clearance=0.0, load=1.0)
        n = b.exponent
        dr = 10e-6
        F = _cage_average(b, 0.0, -dr)
        stribeck = 9 * 1e10 * dr ** n / math.hypot(*F)
        out.append(check(name, "Stribeck's constant as printed (Harris ch. 7; NSK E728g Table 1)",
                         f"{element}s, zero clearance: Z K_n delta_r^n / F_r = 1 / J_r(0.5)", printed, stribeck,
                         0.005 / printed, note=f"1/J_r by quadrature {1 / ref.sjovall(0.5, n):.6f}"))
        cb = RollingBearing(0.0, element=element, elements=9, contact_stiffness=1e10, clearance=0.3 * dr, load=1.0)
        eps = 0.5 * (1 - 0.3)
        Fc = _cage_average(cb, 0.0, -dr)
        dmax = dr - 0.3 * dr
        out.append(check(name, "Sjoevall's integral J_r(eps) by quadrature", f"{element}s, clearance 0.3 delta_r: "
                         "F_r / (Z K_n delta_max^n)", ref.sjovall(eps, n),
                         math.hypot(*Fc) / (9 * 1e10 * dmax ** n), 1e-6))
        W = 2000.0
        many = RollingBearing(0.0, element=element, elements=400, contact_stiffness=1e10, clearance=0.0, load=W)
        delta = (W / (400 * 1e10 * ref.sjovall(0.5, n))) ** (1 / n)
        out.append(check(name, "Euler's theorem on F_r = Z K_n J_r(1/2) delta^n", f"{element}s, Z = 400: stiffness along "
                         "the load [N/m]", n * W / delta, many.linearised_stiffness()[1, 1], 1e-4))
    return out


def _shaft_stiffness(d: float, L: float, E: float, G: float) -> float:
    nu = E / (2 * G) - 1
    kap = 6 * (1 + nu) / (7 + 6 * nu)
    return 1.0 / (L ** 3 / (48 * E * math.pi * d ** 4 / 64) + L / (4 * kap * G * math.pi * d * d / 4))


@case("bearing-rolling-clearance-response", group="bearings", slow=True)
def clearance_response():
    """A rotor on two ball bearings with radial clearance (8 balls, K_n = 7e9 N/m^1.5, clearance
    10 um, damping 300 N s/m, the rotor's weight and an unbalance of 2e-4 kg m on a 10 kg disc at
    mid-span of a massless 0.4 m x 30 mm shaft, 1 kg journals) at 3000 rev/min for 0.1 s from rest:
    drivefem's run-up (reduced rotor, the bearing law as a smooth planar element, DOP853 at rtol
    1e-10) against an independent integration of the same equations written by hand here (three
    masses, the shaft's condensed stiffness k_s/4 [[1, -2, 1], [-2, 4, -2], [1, -2, 1]] with the
    Timoshenko mid-span stiffness k_s, the balls on the cage turning at (1 - D/d_m)/2 of the shaft,
    scipy's LSODA at rtol 1e-11).  The journals drop into the clearance and the balls engage and
    release as the orbit grows (the clearance law is the nonlinearity).  Tolerance 1e-6 of the largest
    disc orbit radius: both integrators' tolerances with margin (the reduced rotor spans the three
    masses exactly; measured 6e-8 ... 1.5e-7 against LSODA, 2e-8 against Radau at rtol 1e-11, which takes
    minutes)."""
    name = "bearing-rolling-clearance-response"
    d, Ls, E, G = 0.03, 0.4, 211e9, 81.2e9
    m, mj, Kn, cr, cb, Z = 10.0, 1.0, 7e9, 10e-6, 300.0, 8
    D_ball, dm = 12e-3, 60e-3
    me, rpm = 2e-4, 3000.0
    W = 2 * math.pi * rpm / 60
    T = 0.1
    mat = Material(E=E, G=G, rho=0.0)

    def brg(x):
        return RollingBearing(x, element="ball", elements=Z, contact_stiffness=Kn, element_diameter=D_ball,
                              pitch_diameter=dm, clearance=cr, damping=cb)

    rotor = Rotor([ShaftSegment(Ls, 2, d, mat)], discs=[Disc(0.0, mj), Disc(Ls / 2, m), Disc(Ls, mj)],
                  bearings=[brg(0.0), brg(Ls)])
    res = run_up(rotor, RunUp(W, W, T, modes=6, start="rest", rtol=1e-10, integrator="DOP853", output_step=T / 2000),
                 [Unbalance(Ls / 2, me)], probes=[0.0, Ls / 2])
    # the independent model
    ks = _shaft_stiffness(d, Ls, E, G)
    K3 = 0.25 * ks * np.array([[1, -2, 1], [-2, 4, -2], [1, -2, 1]])
    M = np.array([mj, m, mj])
    g = 9.81
    ratio = 0.5 * (1 - D_ball / dm)
    offsets = 2 * math.pi * np.arange(Z) / Z

    def bearing(y, z, yd, zd, t):
        psi = ratio * W * t + offsets
        c, s = np.cos(psi), np.sin(psi)
        q = Kn * np.maximum(y * c + z * s - cr, 0.0) ** 1.5
        return -q @ c - cb * yd, -q @ s - cb * zd

    def rhs(t, x):
        y, z, yd, zd = x[0:3], x[3:6], x[6:9], x[9:12]
        fy, fz = -K3 @ y, -K3 @ z - M * g
        fy[1] += me * W * W * math.cos(W * t)
        fz[1] += me * W * W * math.sin(W * t)
        for j in (0, 2):
            by, bz = bearing(y[j], z[j], yd[j], zd[j], t)
            fy[j] += by
            fz[j] += bz
        return np.concatenate([yd, zd, fy / M, fz / M])

    sol = solve_ivp(rhs, (0.0, T), np.zeros(12), method="LSODA", t_eval=res.t, rtol=1e-11, atol=1e-15)
    scale = float(np.hypot(sol.y[1], sol.y[4]).max())
    err_disc = float(np.hypot(res.orbit_y[:, 1] - sol.y[1], res.orbit_z[:, 1] - sol.y[4]).max())
    err_brg = float(np.hypot(res.orbit_y[:, 0] - sol.y[0], res.orbit_z[:, 0] - sol.y[3]).max())
    engaged = res.bearings[0].eccentricity
    src = "independent integration of the same equations (scipy LSODA, rtol 1e-11)"
    return [check(name, src, "disc orbit: largest difference / largest radius", 0.0, err_disc, 1e-6, scale=scale,
                  note=f"largest disc radius {scale:.4e} m"),
            check(name, src, "journal orbit: largest difference / largest disc radius", 0.0, err_brg, 1e-6, scale=scale,
                  note=f"journal radius / clearance: {engaged.min():.3f} ... {engaged.max():.3f}")]
