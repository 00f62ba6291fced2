"""Parametric resonance of one DOF (textbook §7.3, (7.25)-(7.28)): the Floquet analysis of
:mod:`discrete.linear.parametric` against Hill's infinite determinant, scipy's Mathieu
characteristic values and the book's energy estimate eps* = psi/pi.

Book misprints followed in corrected form: (7.26) calls the regions around Omega* = 2 k0/s
"areas of dynamic stability" -- they are the instability tongues (hatched in Fig. 7.4); (7.9)
lacks q in k^2(t) q; (7.11) prints n q for n q1.  The damping convention is the book's (7.31):
2 n0 = 0.5 psi k0 / pi, i.e. zeta = psi / (4 pi) (lambda = psi/2, not psi = 1 - exp(-2 lambda)).
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from discrete.linear import parametric as par
from discrete.linear.harmonic import Damping
from discrete.linear_system import LinearSystem
from discrete.lumped import Body, Driver, Link, LumpedModel
from validation.analytic import parametric as ref
from validation.registry import case, check, claim, printed

SRC = "textbook §7.3 (7.25)-(7.28) (digest textbook_ch6-9.md V7.3-a/b)"
TOL_FLOQUET = 1e-10          # relative monodromy error target of the Floquet runs below


def sdof(m: float = 1.0, c0: float = 1.0) -> LinearSystem:
    """m y'' + c0 (1 - eps sin Omega t) y = 0 on one DOF ((7.2) without the damper)."""
    return LinearSystem(M=sp.csr_matrix([[m]]), K=sp.csr_matrix([[c0]]), dof_field=["x"], dof_name=["mass"])


def spring_with_psi(psi: float) -> LinearSystem:
    """The same oscillator built as a lumped chain: motor (held) -- spring c0 = 1 with the book's
    dissipation coefficient psi -- body m = 1; the spring's psi enters as hysteretic H."""
    lm = LumpedModel(bodies=[Body("mass", 1.0)], drivers=[Driver("motor", velocity=0.0)],
                     springs=[Link(("motor", "mass"), 1.0, psi=psi)])
    return lm.linear_system()


@case("parametric_damped_threshold", group="parametric")
def damped_threshold():
    """Damping threshold of the principal tongue (7.28): eps* = psi/pi at Omega = 2 k0.

    For psi = 0.05, 0.2, 0.4, 0.6 (zeta = psi/(4 pi)) the depth at which max|rho| = 1 at
    Omega = 2 k0 is compared with
    * Hill's determinant (an independent method: the smallest real eigenvalue eps of the
      truncated infinite determinant for a 2T-periodic solution, 20 harmonic pairs; converged to
      round-off: 20 and 40 pairs agree to < 1e-11, checked here, also for the undamped edges at
      eps = 0.3): tolerance 1e-8, i.e. 100 x the effect of the 1e-10 monodromy tolerance;
    * the digest's Floquet values 0.063666 (psi = 0.2) and 0.127352 (0.4), half a unit of the last
      printed digit;
    * the book's energy estimate psi/pi, a first-order balance (it equals the one-harmonic-pair
      Hill truncation exactly): tolerance twice the second-order correction, estimated
      independently by the two-pair Hill truncation (~0.014 (psi/pi)^2, 5e-4 at psi = 0.6).
    The tongue tip (min over Omega, slightly below 2 k0) is compared with Hill's tip: depth 1e-8,
    Omega 1e-5 (the minimum is flat: its location is fixed only to ~sqrt of the depth accuracy).
    The same threshold is obtained with the lumped spring's psi (hysteretic H converted to modal
    viscous damping) and with a dimensional oscillator (m = 2 kg, c0 = 800 N/m, k0 = 20 rad/s):
    eps* is dimensionless (1e-9).
    """
    out = []
    for psi, printed_value in ((0.05, None), (0.2, "0.063666"), (0.4, "0.127352"), (0.6, None)):
        zeta = ref.zeta_from_psi(psi)
        damp = Damping("hysteretic", psi=psi)
        th = par.damping_threshold(sdof(), par.Modulation(), damping=damp, tolerance=TOL_FLOQUET)
        hill = ref.hill_damped_threshold(2.0, zeta=zeta)
        tag = f"psi={psi:g}"
        out.append(check(f"threshold vs Hill ({tag})", SRC + "; Hill's determinant", "eps* at Omega = 2 k0",
                         hill, th.depth_at_centre, 1e-8))
        if printed_value:
            v, tol = printed(printed_value)
            out.append(check(f"threshold vs digest ({tag})", "digest textbook_ch6-9.md §7.3 Floquet table",
                             "eps* at Omega = 2 k0", v, th.depth_at_centre, tol))
        book = ref.energy_threshold(psi)
        second = abs(ref.hill_damped_threshold(2.0, zeta=zeta, n_terms=2) - book) / book
        out.append(check(f"threshold vs (7.28) psi/pi ({tag})", "textbook (7.28) eps* = psi/pi (first order)",
                         "eps* at Omega = 2 k0", book, th.depth_at_centre, 2 * second + 1e-9,
                         note=f"second-order correction {second:.2e}"))
        out.append(check(f"energy estimate reported ({tag})", "4 zeta / kappa = psi/pi for one DOF",
                         "DampingThreshold.energy_estimate", book, th.energy_estimate, 1e-14))
        w_tip, e_tip = ref.hill_damped_tip(zeta=zeta)
        out.append(check(f"tongue tip depth vs Hill ({tag})", SRC + "; Hill's determinant", "min over Omega of eps*",
                         e_tip, th.depth_minimum, 1e-8))
        out.append(check(f"tongue tip Omega vs Hill ({tag})", SRC + "; Hill's determinant", "Omega of the tip / k0",
                         w_tip, th.omega_at_minimum_rad_s, 1e-5))
        below = par.floquet(sdof(), par.Modulation(), omega=2.0, depth=0.99 * th.depth_at_centre, damping=damp)
        above = par.floquet(sdof(), par.Modulation(), omega=2.0, depth=1.01 * th.depth_at_centre, damping=damp)
        out.append(claim(f"stable below, unstable above eps* ({tag})", "textbook (7.28): eps < eps* is stable",
                         "rho(0.99 eps*) < 1 < rho(1.01 eps*)", below.stable and not above.stable,
                         note=f"rho = {below.rho_max:.6f}, {above.rho_max:.6f}"))
        if psi == 0.6:
            out.append(check("Hill truncation converged (psi=0.6)", "Hill's determinant, 20 vs 40 harmonic pairs",
                             "eps* at Omega = 2 k0", ref.hill_damped_threshold(2.0, zeta=zeta, n_terms=40), hill,
                             1e-11))
            wide = ref.mathieu_hill_edges(0.3, parity=1, n_terms=40)[-4:]
            out.append(check("Hill truncation converged, undamped (eps=0.3)", "Hill's determinant, 20 vs 40 pairs",
                             "max edge difference / k0", 0.0,
                             float(np.max(np.abs(ref.mathieu_hill_edges(0.3, parity=1)[-4:] - wide))), 1e-11, scale=1.0,
                             note="eigensolver round-off grows with the matrix size"))
        if psi == 0.2:
            lumped = par.damping_threshold(spring_with_psi(psi), par.Modulation(), damping=Damping("viscous"),
                                           search_minimum=False)
            out.append(check("threshold from the spring's psi (H -> modal viscous)",
                             "(9.14)-(9.18) with zeta = psi/(4 pi)",
                             "eps* at Omega = 2 k0", th.depth_at_centre, lumped.depth_at_centre, 1e-9))
            dim = par.damping_threshold(sdof(m=2.0, c0=800.0), par.Modulation(), damping=damp, search_minimum=False)
            out.append(check("threshold is dimensionless (k0 = 20 rad/s)", "(7.28)", "eps* at Omega = 2 k0",
                             th.depth_at_centre, dim.depth_at_centre, 1e-9))
            out.append(check("Liouville residual at the threshold", "det Phi = exp(int tr A dt)",
                             "|ln|det Phi| - int tr A|", 0.0, above.liouville_residual, 1e-12, scale=1.0))
    return out


@case("parametric_undamped_tongues", group="parametric")
def undamped_tongues():
    """Tongue edges of q'' + k0^2 (1 - eps sin Omega t) q = 0 (Fig. 7.4, (7.26) Omega* = 2 k0/s).

    Edges located by root finding on det(Phi +- I) along Omega (k0 = 1, Omega in [0.5, 2.5],
    201 samples) for eps = 0.1 and 0.2, tongues s = 1, 2, 3, against
    * scipy.special.mathieu_a / mathieu_b (a = 4 k0^2/Omega^2, q = eps a / 2; root of
      a = a_s(q), b_s(q)), and
    * Hill's determinant (the symmetric-definite eigenproblem in k0^2/Omega^2, 20 pairs), a
      second independent reference (the two agree to ~1e-12).
    Tolerance 1e-8 relative: the edge error is the monodromy error (1e-10) over the slope of
    det(Phi +- I) in Omega; the s = 3 tongue (width 1e-4 at eps = 0.1) has the smallest slope.
    The digest's first tongue at eps = 0.1, (1.94970, 2.04968), is checked at half a unit of its
    last digit.  The digest's other rows are not used: its s = 3 edges (0.66617, 0.66622) and its
    s = 2 lower edge 0.9980 are wrong (Mathieu and Hill give 0.666143, 0.666249 and 0.997917).
    The damped edges at eps = 0.1, psi = 0.2 are compared with Hill (1e-8) and the digest
    (1.96088, 2.03799; half a digit).
    """
    out = []
    for eps in (0.1, 0.2):
        b = par.tongue_boundaries(sdof(), par.Modulation(), depth=eps, omega_min=0.5, omega_max=2.5, n_omega=201,
                                  damping=Damping("none"), tolerance=TOL_FLOQUET)
        out.append(check(f"number of tongues in [0.5, 2.5] (eps={eps:g})", "(7.26) Omega* = 2 k0/s, s = 1, 2, 3",
                         "instability intervals", 3, len(b.omega_low_rad_s), 0.0, scale=1.0))
        if len(b.omega_low_rad_s) != 3:
            continue
        for s, lo, hi, kind in zip((3, 2, 1), b.omega_low_rad_s, b.omega_high_rad_s, b.crossing):
            m_lo, m_hi = ref.mathieu_edges(eps, s)
            hill = ref.mathieu_hill_edges(eps, parity=s % 2)
            k = (s + 1) // 2                      # rank of the tongue among those of its parity
            h_lo, h_hi = hill[-2 * k], hill[-2 * k + 1]
            tag = f"s={s}, eps={eps:g}"
            for name, mine, mat, hl in (("lower", lo, m_lo, h_lo), ("upper", hi, m_hi, h_hi)):
                out.append(check(f"{name} edge vs Mathieu ({tag})", "scipy.special.mathieu_a/b", "Omega / k0",
                                 mat, mine, 1e-8))
                out.append(check(f"{name} edge vs Hill ({tag})", "Hill's determinant", "Omega / k0", hl, mine, 1e-8))
            out.append(claim(f"multiplier leaves through {'-1' if s % 2 else '+1'} ({tag})",
                             "odd s: period 2T at the edges, even s: period T", "crossing",
                             kind == ("-1" if s % 2 else "+1")))
            if eps == 0.1 and s == 1:
                for txt, mine in (("1.94970", lo), ("2.04968", hi)):
                    v, tol = printed(txt)
                    out.append(check(f"first tongue edge {txt} (digest)", "digest §7.3 tongue edges, eps = 0.1",
                                     "Omega / k0", v, mine, tol))
    psi, eps = 0.2, 0.1
    b = par.tongue_boundaries(sdof(), par.Modulation(), depth=eps, omega_min=1.5, omega_max=2.5, n_omega=101,
                              damping=Damping("hysteretic", psi=psi), tolerance=TOL_FLOQUET)
    h_lo, h_hi = ref.hill_damped_edges(eps, zeta=ref.zeta_from_psi(psi))
    out.append(check("damped tongue count (eps=0.1, psi=0.2)", SRC, "instability intervals in [1.5, 2.5]", 1,
                     len(b.omega_low_rad_s), 0.0, scale=1.0))
    if len(b.omega_low_rad_s) == 1:
        for name, mine, hl, txt in (("lower", b.omega_low_rad_s[0], h_lo, "1.96088"),
                                    ("upper", b.omega_high_rad_s[0], h_hi, "2.03799")):
            out.append(check(f"damped {name} edge vs Hill", "Hill's determinant with damping", "Omega / k0", hl, mine,
                             1e-8))
            v, tol = printed(txt)
            out.append(check(f"damped {name} edge {txt} (digest)", "digest §7.3 (eps = 0.1, psi = 0.2)", "Omega / k0",
                             v, mine, tol))
    return out


@case("parametric_chart_consistency", group="parametric")
def chart_consistency():
    """The stability chart (vectorised grid scan) agrees with the root-found edges and the
    threshold: at eps = 0.1 (a grid row) every grid point strictly inside a located tongue is
    unstable and every point outside all tongues stable, for psi = 0 and psi = 0.2; with
    psi = 0.2 no grid point below eps* (min over Omega) is unstable.  Quality figures: the
    largest step-halving error estimate stays below the tolerance and the Liouville residual
    below 1e-12 over the grid.  Grid points within 1e-9 of an edge are skipped (the grid and the
    root finder may disagree there by the monodromy error)."""
    out = []
    for psi in (0.0, 0.2):
        damp = Damping("hysteretic", psi=psi) if psi else Damping("none")
        ch = par.stability_chart(sdof(), par.Modulation(), omega_min=0.5, omega_max=2.5, n_omega=161, depth_max=0.3,
                                 n_depth=31, damping=damp, boundaries_at=[0.1], tolerance=TOL_FLOQUET)
        row = int(np.argmin(np.abs(ch.depth - 0.1)))
        b = ch.boundaries[0]
        inside = np.zeros(ch.omega_rad_s.size, dtype=bool)
        near = np.zeros_like(inside)
        for lo, hi in zip(b.omega_low_rad_s, b.omega_high_rad_s):
            inside |= (ch.omega_rad_s > lo) & (ch.omega_rad_s < hi)
            near |= (np.abs(ch.omega_rad_s - lo) < 1e-9) | (np.abs(ch.omega_rad_s - hi) < 1e-9)
        agree = (~ch.stable[row] == inside) | near
        tag = f"psi={psi:g}"
        out.append(claim(f"grid row eps = 0.1 agrees with the edges ({tag})", SRC, "unstable <=> inside a tongue",
                         bool(np.all(agree)), note=f"{int(np.sum(~agree))} disagreements"))
        out.append(check(f"max error estimate over the grid ({tag})", "step halving (Magnus order 6)",
                         "max error_estimate", 0.0, float(ch.error_estimate.max()), TOL_FLOQUET, scale=1.0))
        out.append(check(f"max Liouville residual over the grid ({tag})", "det Phi = exp(int tr A dt)",
                         "max |ln|det Phi| - int tr A|", 0.0, float(ch.liouville_residual.max()), 1e-12, scale=1.0))
        if psi:
            eps_star = ch.thresholds[0].depth_minimum
            out.append(claim("no instability below the threshold (psi=0.2)",
                             "textbook (7.28): eps < eps* stable at all Omega",
                             "all grid points with eps < eps* stable", bool(np.all(ch.stable[ch.depth < eps_star])),
                             note=f"eps* = {eps_star:.6f}"))
    return out
