"""Rotor-stator rub and clearance against closed forms: the Jeffcott rotor (massless shaft, point-mass
disc at mid-span, damper at the disc) whirling in a ring of radial clearance.

By isotropy the synchronous circular whirl is an exact solution of the nonlinear equations, so the
run at a constant speed settles on a circle whose radius (compliant ring) or contact force (rigid
ring) is a root of an algebraic equation (:mod:`validation.analytic.rotor`).  The reduced rotor is
exact here (two modes span every finite motion: restitution 1 at the ring), so the tolerances are
those of the integrators:

* event-located compliant contact (DOP853, rtol 1e-10, 3 s and 1.5 s = 17 and 21 decay times of the
  start's deviation, which is ~10 %): the settled radius to 1e-6 (measured 1e-10 ... 3e-8);
* Moreau-Jean with a rigid ring is first order in the step: the contact force at h0/2 and h0/8
  (h0 = a 40th of the natural period), the observed order log4(e1/e2) within 0.8 ... 1.2, the
  finer error below 1 %, and the Richardson extrapolation 2-step to 1e-3.

The energy balance of both integrators closes: event-located to 1e-8 (the rtol), Moreau-Jean
(theta = 1/2, an identity) to 1e-10 (measured 1e-13)."""
from __future__ import annotations

import math

import numpy as np

from fem.rotor import Bearing, Disc, Rotor, Rub, RunUp, ShaftSegment, Support, Unbalance, run_up
from fem.sections import Material
from validation.analytic import rotor as ref
from validation.registry import case, check, claim

MASSLESS = Material(E=211e9, G=81.2e9, rho=0.0)
L, D, M, E = 0.8, 0.03, 10.0, 1e-4
DELTA = 2e-4
SRC = "Jeffcott rotor in a clearance ring: synchronous circular whirl (closed form, validation.analytic.rotor)"


def _jeffcott(zeta: float):
    """The Jeffcott rotor and its k, c, omega*: rigid supports, a damper c at the disc."""
    from fem.rotor import undamped_critical_speeds

    bare = Rotor([ShaftSegment(L, 4, D, MASSLESS)], discs=[Disc(L / 2, M)], supports=[Support(0.0), Support(L)])
    w = undamped_critical_speeds(bare, 1).speeds_rad_s[0]
    k = M * w * w
    c = 2 * zeta * math.sqrt(k * M)
    rotor = Rotor([ShaftSegment(L, 4, D, MASSLESS)], discs=[Disc(L / 2, M)], supports=[Support(0.0), Support(L)],
                  bearings=[Bearing(L / 2, cyy=c, czz=c)])
    return rotor, k, c, w


def _settled(res, n: int = 200):
    r = np.hypot(res.orbit_y[-n:, 0], res.orbit_z[-n:, 0])
    return float(r.mean()), float(r.max() - r.min()), float(res.rubs[0].normal_force[-n:].mean())


@case("rotor-rub-compliant-annular", group="rotor")
def compliant_annular():
    """Compliant ring (event-located contact changes): without friction (a bearing clearance: mu = 0,
    k_c = 2 k, zeta = 0.02) and with friction (mu = 0.1, k_c = k / 2, zeta = 0.05, where the forward
    annular rub is stable), both at Omega = 1.2 omega*: the settled radius against the root of
    |k - m W^2 + i c W + k_c (1 - delta/R)(1 + i mu)| R = m e W^2, the normal force k_c (R - delta),
    and the energy balance; a ring far outside the orbit gives the linear radius m e W^2 / |k - m W^2
    + i c W| (the unbalance load's convention, no contact event)."""
    name = "rotor-rub-compliant-annular"
    out = []
    for mu, zeta, kc_ratio, T in ((0.0, 0.02, 2.0, 3.0), (0.1, 0.05, 0.5, 1.5)):
        rotor, k, c, w = _jeffcott(zeta)
        W = 1.2 * w
        kc = kc_ratio * k
        rub = Rub(L / 2, DELTA, stiffness=kc, friction=mu, radius=D / 2)
        res = run_up(rotor, RunUp(W, W, T, method="event", modes=2, rtol=1e-10), [Unbalance(L / 2, M * E)], [rub],
                     probes=[L / 2])
        R, spread, N = _settled(res)
        roots = ref.annular_rub_radius(M, k, c, kc, DELTA, mu, E, W, 5e-3)
        tag = f"mu = {mu:g}, k_c/k = {kc_ratio:g}, zeta = {zeta:g}"
        out.append(claim(name, SRC, f"{tag}: one circular-whirl root, the run reaches the end", len(roots) == 1
                         and res.stopped is None, note=f"roots {roots}"))
        out.append(check(name, SRC, f"{tag}: settled orbit radius R [m]", roots[0], R, 1e-6,
                         note=f"spread over the last 200 samples {spread:.2e} m"))
        out.append(check(name, SRC, f"{tag}: normal force k_c (R - delta) [N]", kc * (roots[0] - DELTA), N, 1e-5))
        out.append(check(name, "energy balance (works of every force integrated with the state)",
                         f"{tag}: relative balance error", 0.0, res.energy_error, 1e-8, scale=1.0))
    rotor, k, c, w = _jeffcott(0.02)
    W = 1.2 * w
    res = run_up(rotor, RunUp(W, W, 0.5, method="event", modes=2, rtol=1e-10), [Unbalance(L / 2, M * E)],
                 [Rub(L / 2, 1e-2, stiffness=k)], probes=[L / 2])
    R, _, _ = _settled(res)
    out.append(check(name, "linear unbalance response of the Jeffcott rotor", "ring out of reach: radius m e W^2 / "
                     "|k - m W^2 + i c W| [m]", M * E * W ** 2 / abs(k - M * W ** 2 + 1j * c * W), R, 1e-7,
                     note="the exact periodic start drifts by DOP853's global error: rtol 1e-10 over ~27 periods"))
    out.append(claim(name, SRC, "ring out of reach: no contact event", not res.events))
    return out


@case("rotor-rub-rigid-annular", group="rotor")
def rigid_annular():
    """Rigid ring (Moreau-Jean, Newton restitution 0, Coulomb mu = 0.1; zeta = 0.05, Omega = 1.2
    omega*, from rest): the full annular rub's normal force against the root of (1 + mu^2) N^2 +
    2 (a + mu b) N + a^2 + b^2 - (m e W^2)^2 = 0, at two steps h0/2 and h0/8; first-order
    convergence (Moreau-Jean's order with impulses), the Richardson value, the orbit on the ring,
    the energy identity."""
    name = "rotor-rub-rigid-annular"
    rotor, k, c, w = _jeffcott(0.05)
    W = 1.2 * w
    mu = 0.1
    N_ref = ref.annular_rub_force_rigid(M, k, c, DELTA, mu, E, W)
    h0 = 2 * math.pi / w / 40
    out, Ns = [], []
    for div in (2, 8):
        res = run_up(rotor, RunUp(W, W, 1.0, method="moreau", modes=2, time_step=h0 / div, start="rest"),
                     [Unbalance(L / 2, M * E)], [Rub(L / 2, DELTA, friction=mu, radius=D / 2, restitution=0.0)],
                     probes=[L / 2])
        R, spread, N = _settled(res)
        Ns.append(N)
        out.append(check(name, "the ring (position projection)", f"h0/{div}: orbit radius = delta [m]", DELTA, R, 1e-9))
        out.append(check(name, "Moreau-Jean theta = 1/2: discrete energy identity", f"h0/{div}: relative balance "
                         "error", 0.0, res.energy_error, 1e-10, scale=1.0))
    e1, e2 = abs(Ns[0] - N_ref), abs(Ns[1] - N_ref)
    order = math.log(e1 / e2) / math.log(4.0)
    out.append(check(name, SRC, "normal force at h0/8 [N] (first order: within 1 %)", N_ref, Ns[1], 1e-2))
    out.append(claim(name, "Moreau-Jean with impulses is first order", f"observed order {order:.3f} in [0.8, 1.2]",
                     0.8 <= order <= 1.2))
    out.append(check(name, SRC, "Richardson value 2-step (h0/2, h0/8) [N]", N_ref, Ns[1] + (Ns[1] - Ns[0]) / 3, 1e-3))
    return out


@case("rotor-rub-runup-example", group="rotor", slow=True)
def runup_example():
    """examples/rotor_rub_runup.toml (the Friswell 5.9.5 rotor run up through its first critical with
    an offset seal rub) against a second integration of the same reduced model: DOP853 over the
    whole ramp with the contact law evaluated from the state at every call (clipped Kelvin-Voigt,
    slip direction from the slip velocity), no event location, rtol 1e-11: its error control resolves
    the kinks by step rejections.  Compared: the largest normal force, the orbit at the seal at
    the end, the speeds of the first contact and of the largest force (tolerance 1e-6 where both
    integrations are at rtol <= 1e-8, measured 1e-12 ... 4e-10; the first contact of the second one is
    known to one output step only: 2e-3).  Claims: the reduced basis restores the
    seal's static flexibility (1 to 1e-9), the energy balance closes (1e-8), the first contact comes
    before the linear critical speed, the rub is partial there and full annular above it."""
    from scipy.integrate import solve_ivp

    from fem.rotor.reduced import reduce_rotor
    from fem.rotor.runup import _laws
    from fem.rotor.transient import SpeedRamp, UnbalanceLoad
    from fem.study import Study
    from validation.examples import EXAMPLES

    name = "rotor-rub-runup-example"
    study = Study.load(EXAMPLES / "rotor_rub_runup.toml")
    res = study.run_up()
    out = [claim(name, "the run", "reaches the end of the ramp", res.stopped is None, note=str(res.stopped))]
    red_rep = res.reduction
    out += [check(name, "K^-1 of the full rotor at the seal", f"static restitution {d}", 1.0, r, 1e-9)
            for d, r in zip(red_rep["contact_dofs"], red_rep["restitution"])]
    out.append(check(name, "energy balance", "relative balance error", 0.0, res.energy_error, 1e-8, scale=1.0))
    # the second integration
    from fem.modelfile.build import rotor as build_rotor

    spec = build_rotor.run_up_spec(study.doc)
    rs = study.rotor
    ramp = SpeedRamp(spec.run.speed_start, spec.run.speed_end, spec.run.duration)
    dofs = [(rs.dof(r.x, "v"), rs.dof(r.x, "w")) for r in spec.rubs]
    red = reduce_rotor(rs, np.array(dofs), spec.run.modes, reference_speed=ramp.start)
    (c,) = _laws(rs, red, spec.rubs)
    A_y = sum(u.magnitude * np.exp(1j * u.phase) * red.T[rs.dof(u.x, "v")] for u in spec.unbalances)
    A_z = sum(u.magnitude * np.exp(1j * u.phase) * red.T[rs.dof(u.x, "w")] for u in spec.unbalances)
    load = UnbalanceLoad(A_y, A_z, ramp)
    n = red.n

    def contact(eta, v, t):
        y, z, yd, zd = c.g_y @ eta, c.g_z @ eta, c.g_y @ v, c.g_z @ v
        dy, dz, rho = c.relative(y, z)
        if rho <= c.clearance:
            return 0.0, 0.0, 0.0
        N = max(0.0, float(c.normal_force(y, z, yd, zd)))
        vs = float(c.slip_velocity(y, z, yd, zd, ramp.speed(t)))
        Fy, Fz, _, _ = c.force(y, z, yd, zd, ramp.speed(t), 1.0 if vs >= 0 else -1.0)
        scale = N / max(float(c.normal_force(y, z, yd, zd)), 1e-300)
        return Fy * scale, Fz * scale, N

    def rhs(t, Y):
        eta, v = Y[:n], Y[n:]
        K, C = red.matrices(ramp.speed(t))
        Fy, Fz, _ = contact(eta, v, t)
        return np.concatenate([v, load(t) + Fy * c.g_y + Fz * c.g_z - C @ v - K @ eta])

    eta0 = np.linalg.solve(red.matrices(ramp.start)[0] - ramp.start ** 2 * np.eye(n)
                           + 1j * ramp.start * red.matrices(ramp.start)[1], load.steady_amplitude(ramp.start))
    Y0 = np.concatenate([eta0.real, -ramp.start * eta0.imag])
    sol = solve_ivp(rhs, (0.0, ramp.duration), Y0, method="DOP853", t_eval=res.t, rtol=1e-11,
                    atol=1e-11 * np.abs(Y0).max())
    N2 = np.array([contact(sol.y[:n, k], sol.y[n:, k], sol.t[k])[2] for k in range(sol.t.size)])
    rub = res.rubs[0]
    out.append(check(name, "second integration (DOP853, no event location)", "largest normal force [N]",
                     N2.max(), rub.normal_force.max(), 1e-6))
    ks, k2 = int(np.argmax(rub.normal_force)), int(np.argmax(N2))
    out.append(check(name, "second integration (DOP853, no event location)", "speed of the largest force [rad/s]",
                     res.speed[k2], res.speed[ks], 1e-6))
    k_first = int(np.argmax(N2 > 0))
    out.append(check(name, "second integration (DOP853, no event location)", "speed of the first contact [rad/s]",
                     res.speed[k_first], rub.first_contact["speed_rad_s"], 2e-3,
                     note="sampled: the second method's first contact is known to one output step"))
    iy = int(np.argmin(np.abs(res.probe_x - rub.x)))
    end2 = np.hypot(c.g_y @ sol.y[:n, -1], c.g_z @ sol.y[:n, -1])
    out.append(check(name, "second integration (DOP853, no event location)", "orbit radius at the seal at the end [m]",
                     end2, float(np.hypot(res.orbit_y[-1, iy], res.orbit_z[-1, iy])), 1e-6))
    camp = study.campbell()
    w_crit = min(cs.speed_rad_s for cs in camp.crossings if cs.order == 1.0)
    out.append(claim(name, "linear critical speed ([campbell])", f"first contact ({rub.first_contact['speed_rad_s']:.4g}"
                     f" rad/s) below the first critical ({w_crit:.4g} rad/s)", rub.first_contact["speed_rad_s"] < w_crit))
    spans = [(float(np.interp(a, res.t, res.speed)), float(np.interp(b, res.t, res.speed))) for a, b in rub.full_annular]
    at_crit = rub.regime[int(np.argmin(np.abs(res.speed - w_crit)))]
    out.append(claim(name, "linear critical speed ([campbell])", "the offset seal rubs partially at the critical speed "
                     "and fully (annular rub) above it", at_crit == "partial" and any(a > w_crit for a, _ in spans),
                     note=f"regime at the critical: {at_crit}; full annular rub {spans} rad/s"))
    return out
