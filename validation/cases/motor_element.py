"""The motor as a model element (textbook §5.10, (3.15), §10.6; digests textbook_ch2-5.md §5.10,
textbook_ch10-11.md §10.6).

The dynamic characteristic T M' + M = (1 - omega/omega0)/nu (discrete.motion.motor.DynamicMotor) against the
printed numbers and independent methods: catalogue formulas written out, roots of the characteristic
polynomials (numpy.roots) against the generalised eigenproblem of the first-order system with the torque as
a state, and the forced drive by a dense complex solve with the motor's dynamic stiffness, by the Maxwell
node added to the LinearSystem (harmonic_response) and by the transfer-matrix chain.  Misprints: (5.58)
prints "k^2 omega_d" for k^2 Delta omega_d; chi = nu M (1 + i T) in §10.6 must read (1 + i omega T).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import minimize_scalar

from discrete.linear.harmonic import Damping, harmonic_response
from discrete.lumped import Body, Link, LumpedModel
from discrete.motion.motor import DynamicMotor, motor_modes, with_motor
from discrete.transfer import Chain, Inertia, Load, Spring, forced_response
from discrete.transfer.motor import MotorCharacteristic
from validation.analytic import motor_refs as ref
from validation.registry import case, check, claim, printed

SRC = "seed 001 §5.10 (digest textbook_ch2-5.md §5.10)"
CAT = dict(f_mains=50.0, pole_pairs=2, torque_nominal=100.0, torque_ratio=2.2)
TABLE = {0.05: ("132.665", "0.2186", "129.455", "0.000824", "0.001648"),
         0.2: ("66.332", "0.4373", "59.654", "0.003296", "0.006593"),
         0.5: ("41.952", "0.6914", "30.308", "0.008241", "0.016481"),
         2.0: ("20.976", "1.3829", None, "0.03296", "0.06593")}


def roundoff_tolerance(conditions) -> float:
    """Tolerance of a comparison of two solves of the same linear system: 1e-12, or 2 cond eps where the
    system is worse conditioned (each backward-stable solve is within ~cond eps of the exact solution;
    near the rigid rotation at omega = 1 rad/s cond reaches 2.7e4, so the floor of 1e-12 alone depends on
    the CPU's BLAS kernels: 1.07e-12 measured on an AMD EPYC for h = 3)."""
    return max(1e-12, 2 * float(np.max(conditions)) * np.finfo(float).eps)


def _rotor(J):
    return LumpedModel(bodies=[Body("rotor", J)]).linear_system()


@case("motor-catalogue", group="motor")
def motor_catalogue():
    """Catalogue example (digest §5.10, [C] numbers): f_c = 50 Hz, 2 pole pairs, nominal slip 0.04, xi = 2.2,
    M_n = 100 N m -> s_k = 0.184664, T_d = 0.0172372 s, nu_d = 4.19692e-4, c_d = 880.0, b_d = 15.1687,
    n = 29.0070 (half a printed digit; also against the formulas written out independently, 1e-14).  Rotor
    alone, J = 0.05 / 0.2 / 0.5 / 2.0: k, delta = n/k, k_1, T*, T** of the table; J = 2.0 aperiodic.
    Independent: the eigenvalues of the 3-state system (angle, speed, torque; generalised eigenproblem,
    residual < 1e-12) equal the roots of s^2 + s/T + k^2 (numpy.roots) to 1e-10 -- which also confirms that
    the (5.58) term is k^2 Delta omega (product of the roots = k^2), not the printed k^2 omega_d.  T* and T**
    recovered from the eigenproblem alone (bisection on the loss of oscillatory roots; bounded maximisation of
    Im s over T) to 1e-8; k_1max = 1/(nu omega0 J).  The "equivalent deformation" under the nominal torque,
    M_n/c_d = 1/(2 xi p) = 0.114 rad, supports reading the printed "(0.05-1.4) rad" as 0.05-0.14 rad."""
    out = []
    mot = DynamicMotor.from_catalogue(speed_nominal=0.96 * 2 * math.pi * 50 / 2, **CAT)
    r = ref.catalogue(50.0, 2, 0.04, 100.0, 2.2)
    sk = (1 - 0.96) * (2.2 + math.sqrt(2.2**2 + 1))
    for nm, val, txt, rv in (("s_k", sk, "0.184664", r["s_k"]), ("T_d [s]", mot.T, "0.0172372", r["T"]),
                             ("nu_d [1/(N m)]", mot.nu, "4.19692e-4", r["nu"]), ("c_d [N m/rad]", mot.c, "880.0", r["c_d"]),
                             ("b_d [N m s/rad]", mot.b, "15.1687", r["b_d"]),
                             ("n [1/s]", mot.rotor_constants(1.0)["n"], "29.0070", r["n"])):
        v, tol = printed(txt)
        out.append(check("motor-catalogue", "digest §5.10 catalogue example", nm, v, val, tol))
        out.append(check("motor-catalogue", "§5.10 formulas written out", nm + " (formula)", rv, val, 1e-14))
    for J, (k_t, d_t, k1_t, ts_t, tss_t) in TABLE.items():
        rc = mot.rotor_constants(J)
        for nm, key, txt in (("k [rad/s]", "k", k_t), ("delta = n/k", "delta", d_t), ("T* [s]", "T_star", ts_t),
                             ("T** [s]", "T_star2", tss_t)):
            v, tol = printed(txt)
            out.append(check("motor-catalogue", "digest §5.10 table", f"J = {J:g}: {nm}", v, rc[key], tol))
        mm = motor_modes(_rotor(J), 0, mot)
        roots = ref.rotor_roots(mot.omega0, mot.nu, mot.T, J)
        nz = mm.eigenvalues[np.abs(mm.eigenvalues) > 1e-6 * np.max(np.abs(mm.eigenvalues))]
        err = max(min(abs(s - q) for s in nz) for q in roots) / np.max(np.abs(roots)) if nz.size == 2 else 1.0
        out.append(check("motor-catalogue", "numpy.roots of s^2 + s/T + k^2", f"J = {J:g}: eigenvalues vs roots", 0.0, err,
                         1e-10, scale=1.0))
        out.append(check("motor-catalogue", "(5.58) corrected: the term is k^2 Delta omega", f"J = {J:g}: s1 s2 = k^2",
                         rc["k"] ** 2, float(abs(np.prod(nz))), 1e-10))
        out.append(check("motor-catalogue", "generalised eigenproblem", f"J = {J:g}: max residual", 0.0,
                         float(mm.residuals.max()), 1e-12, scale=1.0))
        if k1_t is None:
            out.append(claim("motor-catalogue", "digest §5.10 table", f"J = {J:g}: aperiodic (k_1 = 0)",
                             rc["aperiodic"] and mm.oscillatory().size == 0))
        else:
            v, tol = printed(k1_t)
            out.append(check("motor-catalogue", "digest §5.10 table", f"J = {J:g}: k_1 [rad/s]", v, rc["k1"], tol))
            out.append(check("motor-catalogue", "generalised eigenproblem", f"J = {J:g}: Im s [rad/s]", v,
                             float(mm.oscillatory()[0].imag), tol))
    J = 0.05
    rc = mot.rotor_constants(J)
    osc = lambda T: motor_modes(_rotor(J), 0, DynamicMotor(mot.omega0, mot.nu, T)).oscillatory().size > 0
    lo, hi = 0.1 * rc["T_star"], 10 * rc["T_star"]
    for _ in range(60):
        mid = math.sqrt(lo * hi)
        lo, hi = (lo, mid) if osc(mid) else (mid, hi)
    out.append(check("motor-catalogue", "bisection on the eigenproblem", "T* (loss of oscillation) [s]", rc["T_star"], hi, 1e-8))
    res = minimize_scalar(lambda T: -float(np.max(np.abs(motor_modes(_rotor(J), 0, DynamicMotor(mot.omega0, mot.nu, T))
                                                         .eigenvalues.imag))),
                          bounds=(1.01 * rc["T_star"], 20 * rc["T_star"]), method="bounded", options={"xatol": 1e-14})
    out.append(check("motor-catalogue", "maximisation over T of Im s", "T** [s]", rc["T_star2"], res.x, 1e-6,
                     note="flat maximum: T to ~sqrt(eps)"))
    out.append(check("motor-catalogue", "maximisation over T of Im s", "k_1max = 1/(nu omega0 J)", rc["k1_max"], -res.fun, 1e-12))
    eq = CAT["torque_nominal"] / mot.c
    out.append(check("motor-catalogue", "c_d = 2 p xi M_n (derivation)", "M_n/c_d = 1/(2 xi p) [rad]", 1 / (2 * 2.2 * 2), eq, 1e-14))
    out.append(claim("motor-catalogue", "seed 001 §5.10 '(0.05-1.4) rad'", "M_n/c_d lies in 0.05-0.14 rad (1.4: misprint)",
                     0.05 <= eq <= 0.14, note=f"{eq:.4f} rad"))
    Jmin = mot.flywheel_min_inertia(200.0)
    k_at = mot.rotor_constants(Jmin)["k"]
    out.append(check("motor-catalogue", "§5.10 flywheel condition", "omega/k at J = J_min", math.sqrt(2), 200.0 / k_at, 1e-14))
    return out


@case("motor-drive-10-6", group="motor")
def motor_drive():
    """§10.6 example: omega0 = 157, nu = 3e-3, T = 0.043, J0 = 0.224: p0 = 9.2 (book, half of its last digit) and
    9.2313 (digest) from the rotor constants and from the eigenproblem.  The two-inertia drive (J1 = h J0,
    c1 = p1^2 J1, p1 = 150): eigenvalues of the drive with the motor torque as a state equal the roots of
    the characteristic polynomial (numpy.roots, 1e-9 relative); the motor mode is oscillatory near the rigid-
    drive estimate sqrt(k^2 - n^2) with J0 (1 + h) (6.41 and 3.43 rad/s for h = 0.25, 0.5; tolerance 2%: the
    motor mode is close to critical damping, so an O(1e-3) elastic correction of k^2 moves k_1 by ~6x that)
    and aperiodic for h = 1, 3 (digest).  Forced (M1 = 1 N m on the load, delta1 = 0.02): the Maxwell node
    added to the LinearSystem (with_motor + harmonic_response) against the dense solve with the motor's
    dynamic stiffness and against the transfer-matrix chain (1e-12), and the digest's spot values for h = 1:
    |a1| = 8.77999e-4 and |M_D| = 4.38071e-2 at omega = 50, |a1| = 1.22174e-3 and |M_D| = 6.05471e-2 at
    212.132, |a1| = 0.465335 at omega = 1 (half a printed digit)."""
    out = []
    prm = dict(omega0=157.0, nu=3e-3, T=0.043)
    mot = DynamicMotor(**prm)
    J0, p1, d1 = 0.224, 150.0, 0.02
    v, tol = printed("9.2")
    out.append(check("motor-drive-10-6", "seed 001 §10.6 (printed)", "p0 [1/s]", v, mot.partial_frequency(J0), tol))
    v, tol = printed("9.2313")
    out.append(check("motor-drive-10-6", "digest §10.6", "p0 from the eigenproblem [1/s]", v,
                     float(motor_modes(_rotor(J0), 0, mot).oscillatory()[0].imag), tol))
    for h, est in ((0.25, "6.41"), (0.5, "3.43"), (1.0, None), (3.0, None)):
        J1, c1 = h * J0, p1**2 * h * J0
        mdl = LumpedModel(bodies=[Body("rotor", J0), Body("load", J1)], springs=[Link(("rotor", "load"), c1)])
        ls = mdl.linear_system()
        mm = motor_modes(ls, 0, mot)
        roots = ref.drive_roots(prm["omega0"], prm["nu"], prm["T"], J0, J1, c1)
        roots = roots[np.abs(roots) > 1e-6]                      # the rigid rotation s = 0 of both
        nz = mm.eigenvalues[np.abs(mm.eigenvalues) > 1e-6]
        err = max(min(abs(s - q) for s in nz) for q in roots) / np.max(np.abs(roots)) if nz.size == roots.size else 1.0
        out.append(check("motor-drive-10-6", "roots of the characteristic polynomial", f"h = {h:g}: eigenvalues", 0.0,
                         err, 1e-9, scale=1.0))
        slow = [s for s in mm.oscillatory() if abs(s.imag) < 50]
        if est is None:
            out.append(claim("motor-drive-10-6", "digest §10.6", f"h = {h:g}: motor mode aperiodic", not slow))
        else:
            v, _ = printed(est)
            out.append(check("motor-drive-10-6", "digest §10.6 rigid-drive estimate", f"h = {h:g}: motor mode Im s",
                             v, float(slow[0].imag) if slow else math.nan, 0.02))
            out.append(check("motor-drive-10-6", "rigid drive J0 (1 + h)", f"h = {h:g}: k_1 (helper)", v,
                             mot.rotor_constants(J0 * (1 + h))["k1"], printed(est)[1]))
        ws = np.array([1.0, 50.0, 150.0, 212.132, 400.0])
        sys_m = with_motor(LumpedModel(bodies=[Body("rotor", J0), Body("load", J1)],
                                       springs=[Link(("rotor", "load"), c1, psi=4 * math.pi * d1)]).linear_system(), 0, mot)
        Fv = np.zeros(sys_m.n_dofs, dtype=complex)
        Fv[1] = 1.0
        hr = harmonic_response(sys_m, ws, force=Fv, damping=Damping("viscous"))
        dense = np.array([ref.drive_forced(w, prm["omega0"], prm["nu"], prm["T"], J0, J1, c1, d1) for w in ws])
        tol = roundoff_tolerance([ref.drive_forced_condition(w, prm["omega0"], prm["nu"], prm["T"], J0, J1, c1, d1)
                                  for w in ws])
        out.append(check("motor-drive-10-6", "dense solve with Z(omega)", f"h = {h:g}: max |a - a_dense|/|a_dense|", 0.0,
                         float(np.max(np.abs(hr.response[:, :2] - dense[:, :2]) / np.abs(dense[:, :2]))), tol, scale=1.0))
        MD = -mot.complex_stiffness(ws) * hr.response[:, 0]
        out.append(check("motor-drive-10-6", "dense solve with Z(omega)", f"h = {h:g}: max |M_D - M_D,dense|/|M_D,dense|",
                         0.0, float(np.max(np.abs(MD - dense[:, 2]) / np.abs(dense[:, 2]))), tol, scale=1.0))
        mc = MotorCharacteristic(**prm)
        ch = Chain([*mc.elements(), Inertia(J0), Spring(c1, d1), Inertia(J1), Load(1.0)], start="clamped", end="free")
        a_tm = forced_response(ch, ws).a[:, -1]
        out.append(check("motor-drive-10-6", "transfer-matrix chain (10.65)-(10.69)", f"h = {h:g}: max ||a1| - |a1_TM||/|a1_TM|",
                         0.0, float(np.max(np.abs(np.abs(hr.response[:, 1]) - np.abs(a_tm)) / np.abs(a_tm))), 1e-12, scale=1.0))
        if h == 1.0:
            for w, a_txt, m_txt in ((50.0, "8.77999e-4", "4.38071e-2"), (212.132, "1.22174e-3", "6.05471e-2"),
                                    (1.0, "0.465335", None)):
                j = int(np.flatnonzero(ws == w)[0])
                v, tol = printed(a_txt)
                out.append(check("motor-drive-10-6", "digest §10.6 spot values", f"|a1| at omega = {w:g}", v,
                                 abs(hr.response[j, 1]), tol))
                if m_txt:
                    v, tol = printed(m_txt)
                    out.append(check("motor-drive-10-6", "digest §10.6 spot values", f"|M_D| at omega = {w:g}", v,
                                     abs(MD[j]), tol))
    return out


@case("motor-drive-forced-file", group="motor")
def motor_drive_forced_file():
    """The §10.6 drive (h = 1) as a model file, examples/motor_drive_forced.toml: ``drivefem forced`` adds the
    [[motor]]'s complex stiffness Z = i omega b/(1 + i omega T) along its coordinate (discrete.motion.motor.
    with_motor_along).  The load's response against the dense 2x2 solve with Z (1e-12: the same linear
    system, round-off), the digest's spot values (half a printed digit), and with T = 0 (the static
    characteristic: Z = i omega b, a damper to ground) against the same dense solve with T = 0."""
    from fem.modelfile.source import read_toml
    from fem.study import Study
    from validation.examples import EXAMPLES

    out = []
    doc = read_toml(EXAMPLES / "motor_drive_forced.toml")
    J0, J1, c1, d1 = 0.224, 0.224, 5040.0, 0.02
    for T in (0.043, 0.0):
        d = dict(doc)
        d["motor"] = [dict(doc["motor"][0], T=T)]
        r = Study.parse(d).forced()
        ws = np.asarray(r.omega_rad_s, float)
        a = r.response[:, 0]
        dense = np.array([ref.drive_forced(w, 157.0, 3e-3, T, J0, J1, c1, d1)[1] for w in ws])
        tol = roundoff_tolerance([ref.drive_forced_condition(w, 157.0, 3e-3, T, J0, J1, c1, d1) for w in ws])
        out.append(check("motor-drive-forced-file", "dense solve with Z(omega)", f"T = {T:g}: max |a1 - a1_dense|/|a1_dense|",
                         0.0, float(np.max(np.abs(a - dense) / np.abs(dense))), tol, scale=1.0))
        if T > 0:
            for w, txt in ((50.0, "8.77999e-4"), (212.132, "1.22174e-3"), (1.0, "0.465335")):
                v, tol = printed(txt)
                j = int(np.argmin(np.abs(ws - w)))
                out.append(check("motor-drive-forced-file", "digest §10.6 spot values", f"|a1| at omega = {w:g}", v,
                                 abs(a[j]), tol))
    return out
