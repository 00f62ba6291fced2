"""Parametric vibrations of mechanisms (textbook §7.1, §7.3): variable reduced inertia (7.3)-(7.7),
the pendulum-rod of Fig. 7.5 (7.31), and a two-DOF drive (combination resonance, cross-check with
an independent integrator)."""
from __future__ import annotations

import math

import numpy as np
import scipy.integrate as si
import scipy.sparse as sp

from discrete.linear import parametric as par
from discrete.linear.harmonic import Damping
from discrete.linear_system import LinearSystem
from discrete.lumped import Body, Driver, Link, LumpedModel
from validation.analytic import parametric as ref
from validation.registry import case, check, claim

SRC_INERTIA = "textbook §7.1-7.2 (7.3)-(7.12), corrected (7.9), (7.11)"
SRC_ROD = "textbook §7.3 (7.31), Fig. 7.5 (digest V7.3-c)"


def sdof(m=1.0, c0=1.0) -> LinearSystem:
    return LinearSystem(M=sp.csr_matrix([[m]]), K=sp.csr_matrix([[c0]]), dof_field=["x"], dof_name=["shaft"])


@case("parametric_variable_inertia", group="parametric")
def variable_inertia():
    """Variable reduced inertia J(t) = J0 (1 - eps sin Omega t) on a shaft c0 (J0 = c0 = 1, eps = 0.1),
    in the three forms: "programme" (7.7) J q'' + J' q' + (c0 + J''/2) q = 0, "momentum"
    (J q')' + c0 q = 0 and "newton" J q'' + c0 q = 0.

    Reference: the conditional-oscillator substitution (7.10)-(7.12), q = q1 exp(-int n dt) with
    2 n = J'/J (the corrected (7.11) has n q1), turns each form into a Hill equation
    q1'' + k1^2(t) q1 = 0 with k1^2 = k^2 - n^2 - n' (programme: c0/J + J'^2/(4 J^2)); since
    exp(-int n dt) = sqrt(J(0)/J(t)) is periodic, the multipliers agree.  Its tongue edges come from
    Hill's determinant with FFT Fourier coefficients (20 pairs, converged).  Tolerance 1e-8 as for
    the Mathieu edges (monodromy error / slope of det(Phi +- I)).  The newton and momentum forms
    share their multipliers (p = J q' of the momentum form obeys the newton form), and their
    second tongue has zero width (coexistence: Hill's +1 eigenvalues coincide); the programme form
    has a +1 tongue there.
    The Liouville reference int tr A dt = -2 zeta T / sqrt(1 - eps^2) (modal damping zeta = 0.02,
    closed form of int dt / J) is checked to 1e-12, and det Phi against it to 1e-12.
    """
    out = []
    eps = 0.1
    mod = par.Modulation(target="inertia", label="mechanism")
    edges = {}
    for form in ("programme", "momentum", "newton"):
        b = par.tongue_boundaries(sdof(), mod, depth=eps, omega_min=0.6, omega_max=2.2, n_omega=161,
                                  damping=Damping("none"), inertia_form=form)
        edges[form] = b
        h, r = ref.inertia_hill_terms(eps, form)
        odd = ref.hill_edges(h, r, parity=1)
        even = ref.hill_edges(h, r, parity=0)
        expected = [(odd[-4], odd[-3]), (odd[-2], odd[-1])]           # s = 3, s = 1
        if form == "programme":
            expected.insert(1, (even[-2], even[-1]))                  # s = 2
        out.append(check(f"number of tongues ({form})", SRC_INERTIA, "instability intervals in [0.6, 2.2]",
                         len(expected), len(b.omega_low_rad_s), 0.0, scale=1.0))
        if len(expected) != len(b.omega_low_rad_s):
            continue
        for (lo, hi), mlo, mhi, lab in zip(expected, b.omega_low_rad_s, b.omega_high_rad_s, b.centre):
            out.append(check(f"{lab} lower edge vs conditional oscillator ({form})",
                             SRC_INERTIA + "; Hill's determinant",
                             "Omega / k0", lo, mlo, 1e-8))
            out.append(check(f"{lab} upper edge vs conditional oscillator ({form})",
                             SRC_INERTIA + "; Hill's determinant",
                             "Omega / k0", hi, mhi, 1e-8))
        if form == "newton":
            out.append(check("coexistence: zero-width s = 2 tongue (newton)", "Hill's +1 eigenvalues coincide",
                             "|Omega_b - Omega_a| / k0", 0.0, abs(even[-1] - even[-2]), 1e-9, scale=1.0))
    same = (edges["newton"].omega_low_rad_s.size == edges["momentum"].omega_low_rad_s.size and
            np.allclose(edges["newton"].omega_low_rad_s, edges["momentum"].omega_low_rad_s, rtol=1e-9) and
            np.allclose(edges["newton"].omega_high_rad_s, edges["momentum"].omega_high_rad_s, rtol=1e-9))
    out.append(claim("momentum and newton forms share their tongues", "p = J q' maps one onto the other",
                     "edges equal to 1e-9", same))
    zeta, Om = 0.02, 2.0
    f = par.floquet(sdof(), mod, omega=Om, depth=eps, damping=Damping("modal", zeta=zeta))
    T = 2 * math.pi / Om
    out.append(check("Liouville reference with variable inertia",
                     "int_0^T dt / (1 - eps sin Omega t) = T / sqrt(1 - eps^2)",
                     "int tr A dt", -2 * zeta * T / math.sqrt(1 - eps**2), f.liouville_reference, 1e-12))
    out.append(check("Liouville residual with variable inertia", "det Phi = exp(int tr A dt)",
                     "|ln|det Phi| - int tr A|", 0.0, f.liouville_residual, 1e-12, scale=1.0))
    return out


@case("parametric_pendulum_rod", group="parametric")
def pendulum_rod():
    """Pendulum-rod of Fig. 7.5: massless rod l with end mass m on a spring c0 with dissipation psi,
    hinge moving along the rod, x = x0 sin Omega t.  (7.31): y'' + 2 n0 y' + k0^2 (1 - eps sin Omega t) y = 0,
    2 n0 = 0.5 psi k0 / pi, eps = m x0 Omega^2 / (l c0) = 4 x0 / l at Omega = 2 k0, stable if 4 x0/l < psi/pi.

    The book gives only the formula; the numbers are the digest's V7.3-c: psi = 0.4, x0/l = 0.02
    (eps = 0.08 < 0.127: stable) and 0.04 (eps = 0.16: growth), with m = 1 kg, c0 = 100 N/m
    (k0 = 10 rad/s), l = 0.5 m.  Checks:
    * eps(2 k0) = 4 x0 / l (identity, 1e-14);
    * the critical x0/l at Omega = 2 k0 from the Floquet threshold against the book's psi/(4 pi),
      tolerance twice the second-order correction of the energy method (Hill, two pairs);
    * the linearisation itself: the rigid rod with exact kinematics (moments about the hinge,
      transport inertia force -m x'' at height l sin alpha; validation.analytic) integrated by DOP853
      (rtol 1e-12) from alpha = 1e-5 along the dominant Floquet eigenvector: after 10 periods the
      state is rho^10 times the initial one; rho from the simulation matches the Floquet
      multiplier to 1e-6 (geometric nonlinearity O(alpha^2) ~ 1e-8, integration ~1e-10); the
      stable case decays over 20 periods.  The rigid body gives c0 (1 + eps sin Omega t), the book's
      sign with the hinge on the other side (phase pi in the Modulation; multipliers do not
      depend on the phase).
    """
    out = []
    m, c0, l, psi = 1.0, 100.0, 0.5, 0.4
    k0 = math.sqrt(c0 / m)
    Om = 2 * k0
    b = psi * m * k0 / (2 * math.pi)                 # 2 n0 = b / m = 0.5 psi k0 / pi
    damp = Damping("hysteretic", psi=psi)
    system = sdof(m, c0)
    mod = par.Modulation(phase=math.pi, label="rod")
    for ratio in (0.02, 0.04):
        eps = ref.pendulum_rod_depth(m=m, x0=ratio * l, l=l, c0=c0, omega=Om)
        out.append(check(f"eps = 4 x0/l at Omega = 2 k0 (x0/l={ratio:g})", SRC_ROD, "eps", 4 * ratio, eps, 1e-14))
    th = par.damping_threshold(system, mod, damping=damp, search_minimum=False)
    crit = th.depth_at_centre / 4
    book = ref.pendulum_rod_critical_ratio(psi)
    second = abs(ref.hill_damped_threshold(2.0, zeta=ref.zeta_from_psi(psi), n_terms=2) / 4 - book) / book
    out.append(check("critical x0/l vs the book's psi/(4 pi)", SRC_ROD + ": 4 x0/l < psi/pi", "x0/l at Omega = 2 k0",
                     book, crit, 2 * second + 1e-9, note=f"second-order correction {second:.2e}"))
    for ratio, grows in ((0.02, False), (0.04, True)):
        eps = ref.pendulum_rod_depth(m=m, x0=ratio * l, l=l, c0=c0, omega=Om)
        prob = par.ParametricProblem.build(system, [mod], damping=damp)
        f = prob.floquet(Om, eps)
        out.append(claim(f"Floquet: {'growth' if grows else 'stable'} at x0/l = {ratio:g}", SRC_ROD,
                         "rho_max > 1" if grows else "rho_max < 1", (f.rho_max > 1) == grows,
                         note=f"rho_max = {f.rho_max:.6f}"))
        Phi = prob.physical_monodromy(f.monodromy)
        vals, vecs = np.linalg.eig(Phi)
        k = int(np.argmax(np.abs(vals)))
        v = np.real(vecs[:, k] if abs(vals[k].imag) < 1e-12 else vecs[:, k] + vecs[:, k].conj())
        v = v / np.max(np.abs(v)) * 1e-5 * l                      # (y, y'), alpha ~ 1e-5 rad
        rhs = ref.pendulum_rod_rhs(m=m, l=l, c0=c0, b=b, x0=ratio * l, omega=Om)
        n_per = 10 if grows else 20
        T = 2 * math.pi / Om
        s0 = [math.asin(v[0] / l), v[1] / (l * math.cos(math.asin(v[0] / l)))]
        sol = si.solve_ivp(rhs, (0.0, n_per * T), s0, method="DOP853", rtol=1e-12, atol=1e-20)
        al, om = sol.y[0, -1], sol.y[1, -1]
        state = np.array([l * math.sin(al), l * math.cos(al) * om])
        if grows:
            proj = state @ v / (v @ v)                               # = rho^10 along the eigenvector
            out.append(check("rigid-body growth per period = |Floquet multiplier| (x0/l = 0.04)",
                             SRC_ROD + "; rigid rod with exact kinematics (DOP853)", "|multiplier|", abs(vals[k]),
                             abs(proj) ** (1.0 / n_per), 1e-6))
            out.append(claim("rigid-body state stays on the Floquet eigenvector (x0/l = 0.04)", SRC_ROD,
                             "sign of rho^10 and |state - proj v| < 1e-6 |state|",
                             np.sign(proj) == np.sign(vals[k].real) ** n_per
                             and np.linalg.norm(state - proj * v) < 1e-6 * np.linalg.norm(state)))
        else:
            decay = np.linalg.norm(state) / np.linalg.norm(v)
            out.append(claim("rigid-body motion decays (x0/l = 0.02)", SRC_ROD + "; rigid rod (DOP853)",
                             "|state(20 T)| < |state(0)|", decay < 1.0, note=f"ratio {decay:.4f}, rho^20 = "
                             f"{f.rho_max ** 20:.4f}"))
    return out


def two_mass_drive(c_ab: float = 0.8, dampers: bool = False):
    """motor (held) -- spring 1.0 -- body a (1 kg) -- spring c_ab -- body b (0.5 kg); optional dampers."""
    damp = [Link(("motor", "a"), 0.01), Link(("a", "b"), 0.02)] if dampers else []
    lm = LumpedModel(bodies=[Body("a", 1.0), Body("b", 0.5)], drivers=[Driver("motor", velocity=0.0)],
                     springs=[Link(("motor", "a"), 1.0), Link(("a", "b"), c_ab)], dampers=damp)
    system = lm.linear_system()
    names = lm.transformation()[0]
    g = np.zeros(len(names))
    g[names.index("a")], g[names.index("b")] = -1.0, 1.0
    Pk = c_ab * np.outer(g, g)
    Qm = np.diag([1.0 if n == "a" else 0.0 for n in names])
    return system, Pk, Qm


@case("parametric_two_mass_drive", group="parametric")
def two_mass_drive_case():
    """Two-mass drive with a pulsating coupling spring (and a pulsating inertia of body a).

    1. Independent integrator: the monodromy on [q, q'] from DOP853 (rtol 1e-13) of the physical
       equations written here directly, M(t) q'' + (C + M') q' + (K(t) + M''/2) q = 0, against the
       Magnus result mapped back from modal coordinates; tolerance 1e-9 relative to ||Phi||
       (both ~1e-11).
    2. Combination resonance (undamped, coupling spring only): the sum-type tongue at
       Omega = w1 + w2 leaves through a complex pair; its width against the first-order averaging
       result (Hsu): Omega = w1 + w2 +- eps |p12| / (2 sqrt(w1 w2)), p = Phi^T P Phi (mass-normalised
       modes).  The neglected term is O(eps^2) relative: tolerance 1e-3 at eps = 0.02 (measured
       5.5e-5), and the discrepancy must fall by 4 +- 1 when eps is halved (second order).
    3. The principal tongues Omega = 2 w_r +- eps p_rr / (2 w_r) (first order) likewise.
    """
    out = []
    system, Pk, Qm = two_mass_drive(dampers=True)
    mods = [par.Modulation(part=Pk, label="coupling spring"),
            par.Modulation(target="inertia", part=Qm, depth=0.3, harmonic=2, phase=0.4, label="body a")]
    prob = par.ParametricProblem.build(system, mods, damping=Damping("viscous"))
    eps, Om = 0.35, 1.7
    f = prob.floquet(Om, eps)
    f_ = system.free
    M0, K0, C0 = (system.free_block(A).toarray() for A in (system.M, system.K, system.C))
    P, Q = Pk[np.ix_(f_, f_)], Qm[np.ix_(f_, f_)]
    d, h, ph = 0.3, 2, 0.4
    n = M0.shape[0]

    def rhs(t, x):
        X = x.reshape(2 * n, 2 * n)
        arg = h * Om * t + ph
        M = M0 - eps * d * Q * math.sin(arg)
        Md = -eps * d * Q * h * Om * math.cos(arg)
        Mdd = eps * d * Q * (h * Om) ** 2 * math.sin(arg)
        K = K0 - eps * P * math.sin(Om * t) + 0.5 * Mdd
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C0 + Md)]])
        return (A @ X).ravel()

    sol = si.solve_ivp(rhs, (0.0, 2 * math.pi / Om), np.eye(2 * n).ravel(), method="DOP853", rtol=1e-13, atol=1e-15)
    ref_phi = sol.y[:, -1].reshape(2 * n, 2 * n)
    mine = prob.physical_monodromy(f.monodromy)
    out.append(check("monodromy vs DOP853 (stiffness + inertia pulsation, damped)",
                     "independent integration of the physical equations", "max |Phi - Phi_ref| / max |Phi_ref|",
                     0.0, np.abs(mine - ref_phi).max() / np.abs(ref_phi).max(), 1e-9, scale=1.0))
    system, Pk, _ = two_mass_drive()
    prob = par.ParametricProblem.build(system, [par.Modulation(part=Pk)], damping=Damping("none"))
    w = prob.omega_modes
    p = prob.parts_K[0][0]
    errs = {}
    for eps in (0.02, 0.01):
        centre, half = w[0] + w[1], eps * abs(p[0, 1]) / (2 * math.sqrt(w[0] * w[1]))
        b = par.tongue_boundaries(prob, depth=eps, omega_min=centre - 3 * half, omega_max=centre + 3 * half, n_omega=41)
        ok = len(b.crossing) == 1 and b.crossing[0] == "complex" and b.centre[0] == "(w1+w2)/1"
        out.append(claim(f"combination tongue (w1+w2) through a complex pair (eps={eps:g})",
                         "sum-type combination resonance", "one 'complex' interval at (w1+w2)/1", ok))
        if not ok:
            continue
        width = b.omega_high_rad_s[0] - b.omega_low_rad_s[0]
        errs[eps] = width / (2 * half) - 1
        if eps == 0.02:
            out.append(check("combination tongue width vs first order (eps=0.02)",
                             "averaging (Hsu): 2 eps |p12| / (2 sqrt(w1 w2))",
                             "width", 2 * half, width, 1e-3))
            for r in (0, 1):
                c2, h2 = 2 * w[r], eps * p[r, r] / (2 * w[r])
                b2 = par.tongue_boundaries(prob, depth=eps, omega_min=c2 - 3 * h2, omega_max=c2 + 3 * h2, n_omega=41)
                if len(b2.crossing) == 1:
                    out.append(check(f"principal tongue width, mode {r + 1} (eps=0.02)", "first order: eps p_rr / w_r",
                                     "width", 2 * h2, b2.omega_high_rad_s[0] - b2.omega_low_rad_s[0], 1e-3))
                else:
                    out.append(claim(f"principal tongue of mode {r + 1} found", "(7.26)", "one interval", False))
    if len(errs) == 2:
        out.append(check("second-order discrepancy of the first-order width", "O(eps^2) error of averaging",
                         "discrepancy(0.02) / discrepancy(0.01)", 4.0, errs[0.02] / errs[0.01], 0.25))
    return out
