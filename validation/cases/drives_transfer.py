"""Transfer matrices (seed 001 §10.1-10.3, 10.6) and slowly varying parameters (10.20).
References: validation.analytic.drives (Table 10.1 as printed, hand-built lumped chains,
the motor example's direct complex solve, a DOP853 integration) and the FE eigen-solver."""
from __future__ import annotations

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from discrete.transfer import (Chain, Inertia, Load, RegularDrive, Spring, chain_product, connection, count_below,
                               damper_matrix, element_matrix, forced_response, inertia_matrix, mechanism_branch,
                               mechanism_matrix, naive_product, natural_frequencies, parallel, propagate, spring_matrix)
from discrete.transfer.motor import MotorCharacteristic
from discrete.transfer.slow import adiabatic_response
from fem.drives import DriveModel, LumpedShaft, Mechanism, modal
from validation.analytic import drives as ref
from validation.registry import case, check, claim, printed

SRC = "seed 001 §10.1-10.3 (10.1)-(10.19), Table 10.1"
R = ref.SET_R


def _set_r(n=6, boundary="clamped-free", output="free"):
    return DriveModel(n=n, shaft=LumpedShaft(c0=R["c0"], J0=R["J0"]),
                      mechanism=Mechanism(m=R["m"], c=R["c"], ratio=R["ratio"], output=output), boundary=boundary)


@case("drives-transfer-matrices", group="drives")
def drives_transfer_matrices():
    """Validation case 6.
    det Gamma = 1 (10.4) for every element and product (rtol 1e-12); Table 10.1 rows = products
    of the primitives in reverse order (10.6) (rtol 1e-12; row c-Pi-J with C = -J p^2 Pi', the
    printed -J p^2/Pi' gives det != 1); transfer-matrix roots (count bisection) = FE eigenvalues
    of the same drive, Set R cases 1 and 2, and the grounded-output branch (10.13) against FE and
    the closed form (rtol 1e-10: both exact, rounding only); a 200-block chain at |xi| = 15:
    the literal product overflows (entries > 1e250 or inf) while the normalised propagation stays
    finite and the first 10 roots and the 10 above k equal the closed form (rtol 1e-10);
    parallel connection (10.9) of c_a with [c_b - J - c_c] ending in a free disc against the
    eigenvalues of the hand-built 2-DOF chain (rtol 1e-10), the same block as a Parallel member
    inside chains (count-bisection roots, forced response vs a direct solve), and parallel
    springs add."""
    out = []
    p, c, J, P = 137.0, 2.5e4, 0.3, 0.07
    mats = {"spring": spring_matrix(c), "inertia": inertia_matrix(J, p), "mechanism": mechanism_matrix(P),
            "damper": damper_matrix(3.0, p), "branch J*(p)": element_matrix(mechanism_branch(2.0, 5e4, P), p)}
    from discrete.transfer import Shaft
    mats["shaft segment"] = element_matrix(Shaft(0.7, 2e4, 0.01), 2000.0)
    for name, G in mats.items():
        out.append(check("drives-transfer-matrices", "seed 001 (10.4)", f"det Gamma, {name}", 1.0,
                         abs(np.linalg.det(G)), 1e-12))
    Gp = chain_product(list(mats.values()))
    out.append(check("drives-transfer-matrices", "seed 001 (10.4)-(10.6)",
                     "det of the product of all six (error relative to ||G||^2, the rounding scale of a 2x2 det)", 1.0,
                     abs(np.linalg.det(Gp)), 1e-12, scale=np.linalg.norm(Gp) ** 2))
    for name in ("c-J-Pi", "c-Pi-J", "J-c-Pi", "J-Pi-c", "Pi-J-c", "Pi-c-J"):
        G, T = connection(name, p, c, J, P), ref.table_10_1(name, p, c, J, P)
        out.append(check("drives-transfer-matrices", SRC, f"Table 10.1 row {name}: max|product - row|/max|row|", 0.0,
                         np.max(np.abs(G - T)) / np.max(np.abs(T)), 1e-12, scale=1.0))
    Tp = ref.table_10_1("c-Pi-J", p, c, J, P, printed=True)
    out.append(claim("drives-transfer-matrices", "Table 10.1 as printed", "printed row c-Pi-J (C = -J p^2/Pi') has det != 1",
                     abs(np.linalg.det(Tp) - 1) > 1e-3, note=f"det = {np.linalg.det(Tp):.6f}"))
    # roots = FE eigenvalues
    for boundary, output in (("clamped-free", "free"), ("clamped-clamped", "free"), ("clamped-free", "grounded"),
                             ("free-free", "free")):
        m = _set_r(boundary=boundary, output=output)
        nm = 12 if output == "free" else 6
        tm = modal(m, nm, "transfer-matrix").omega_rad_s
        fe = modal(m, nm, "discrete").omega_rad_s
        sel = fe > 0
        out.append(check("drives-transfer-matrices", SRC, f"TM roots vs FE eigenvalues, {boundary}, output {output}",
                         0.0, np.max(np.abs(tm[sel] / fe[sel] - 1)), 1e-10, scale=1.0))
        reg = RegularDrive(n=6, c0=R["c0"], J0=R["J0"], m=R["m"], c=R["c"], ratio=R["ratio"], boundary=boundary,
                           output=output).natural_frequencies()[:nm]
        out.append(check("drives-transfer-matrices", "regular closed form", f"TM roots vs closed form, {boundary}, {output}",
                         0.0, np.max(np.abs(tm[sel] / reg[sel] - 1)), 1e-10, scale=1.0))
    # rigid limit of the branch: J*(p -> 0) = J0 + m Pi'^2 (sign of (10.16), digest flag 1)
    br = mechanism_branch(R["m"], R["c"], R["ratio"])
    Jstar = -element_matrix(br, 1e-3)[1, 0] / 1e-6
    out.append(check("drives-transfer-matrices", "seed 001 (10.16)", "branch: J*(p -> 0) - J0 = m Pi'^2 (positive)",
                     R["m"] * R["ratio"] ** 2, Jstar, 1e-9))
    # long chain
    n = 200
    long = _set_r(n=n)
    reg = RegularDrive(n=n, c0=R["c0"], J0=R["J0"], m=R["m"], c=R["c"], ratio=R["ratio"])
    chain = reg.chain()
    p15 = brentq(lambda q: reg.xi(q) - 15.0, 300.0 * (1 + 1e-9), 449.0)
    G = naive_product(chain, p15)
    v, log10 = propagate(chain, p15, (0.0, 1.0))
    out.append(claim("drives-transfer-matrices", "seed 001 §10.2 (long chains)",
                     f"literal product of {n} blocks at xi = 15 overflows (max entry > 1e250 or inf)",
                     (not np.all(np.isfinite(G))) or np.nanmax(np.abs(G)) > 1e250,
                     note=f"max |entry| = {np.nanmax(np.abs(G)):.3e}"))
    out.append(claim("drives-transfer-matrices", "normalised propagation", "normalised propagation finite, scale "
                     "log10 ~ n log10|eta|", bool(np.all(np.isfinite(v))) and abs(log10 / (n * np.log10(15 + np.sqrt(224))) - 1) < 0.05,
                     note=f"log10 scale {log10:.1f}"))
    exact = reg.natural_frequencies()
    low = natural_frequencies(chain, 10, p_guess=150.0).omega_rad_s
    out.append(check("drives-transfer-matrices", SRC, f"n = {n}: first 10 TM roots vs closed form", 0.0,
                     np.max(np.abs(low / exact[:10] - 1)), 1e-10, scale=1.0))
    hi = natural_frequencies(chain, p_range=(450.0, exact[n + 9] * (1 + 1e-7))).omega_rad_s
    out.append(check("drives-transfer-matrices", SRC, f"n = {n}: 10 TM roots above p_* vs closed form", 0.0,
                     np.max(np.abs(hi / exact[n:n + 10] - 1)), 1e-10, scale=1.0))
    out.append(claim("drives-transfer-matrices", "Wittrick-Williams count", f"n = {n}: exactly n roots below k, none in (k, p_*)",
                     list(count_below(chain, [300.0 * (1 - 1e-12), 300.0 * (1 + 1e-9), 449.99])) == [n, n, n]))
    fe = modal(long, 3, "discrete").omega_rad_s
    out.append(check("drives-transfer-matrices", SRC, f"n = {n}: TM vs sparse FE, first 3", 0.0,
                     np.max(np.abs(low[:3] / fe - 1)), 1e-10, scale=1.0))
    # parallel connection (10.9)
    ca, cb, cc, Jm, Je = 1.0e4, 2.0e4, 3.0e4, 0.2, 0.5
    fe = ref.chain_eigen([Jm, Je], [(-1, 1, ca), (-1, 0, cb), (0, 1, cc)])

    def D_of(q):
        sub = chain_product([spring_matrix(cb), inertia_matrix(Jm, q), spring_matrix(cc)])
        G = inertia_matrix(Je, q) @ parallel([spring_matrix(ca), sub])
        return G[1, 1] * (ca * sub[0, 1] + 1.0)   # D(p) gamma_2 B_sub (gamma_2 = c_a + 1/B_sub): pole-free

    grid = np.linspace(1.0, 2 * fe[-1], 4000)
    vals = np.array([D_of(q) for q in grid])
    roots = [brentq(D_of, grid[i], grid[i + 1], xtol=1e-13) for i in np.flatnonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))]
    out.append(check("drives-transfer-matrices", "seed 001 (10.9)", "parallel block: roots of D(p) vs FE (2 roots)", 0.0,
                     np.max(np.abs(np.array(roots) / fe - 1)) if len(roots) == 2 else 1.0, 1e-10, scale=1.0))
    from discrete.transfer import Parallel
    P = Parallel(((Spring(ca),), (Spring(cb), Inertia(Jm), Spring(cc))))
    ch = Chain([P, Inertia(Je), Spring(5e3), Inertia(0.1), Spring(5e3)], "clamped", "clamped")
    fe3 = ref.chain_eigen([Jm, Je, 0.1], [(-1, 1, ca), (-1, 0, cb), (0, 1, cc), (1, 2, 5e3), (2, -1, 5e3)])
    out.append(check("drives-transfer-matrices", "seed 001 (10.7)-(10.9)",
                     "Parallel member inside a clamped-clamped chain: count-bisection roots vs FE (3 roots)", 0.0,
                     np.max(np.abs(natural_frequencies(ch, 3).omega_rad_s / fe3 - 1)), 1e-10, scale=1.0))
    ch = Chain([Spring(1e4), Inertia(1.0), Load(1.0), P, Inertia(Je), Load(2.0)], "clamped", "free")
    K = np.array([[1e4 + ca + cb, -cb, -ca], [-cb, cb + cc, -cc], [-ca, -cc, ca + cc]])
    for w in (50.0, 400.0):
        x = np.linalg.solve(K - w**2 * np.diag([1.0, Jm, Je]), [1.0, 0.0, 2.0])
        a = forced_response(ch, [w]).a[0]
        out.append(check("drives-transfer-matrices", "seed 001 (10.9), (10.26)",
                         f"Parallel member, forced at w = {w:g}: max|a - direct|/max|a|", 0.0,
                         max(abs(a[1] - x[0]), abs(a[-1] - x[2])) / np.max(np.abs(x)), 1e-12, scale=1.0))
    par = parallel([spring_matrix(ca), spring_matrix(cb)])
    out.append(check("drives-transfer-matrices", "seed 001 (10.9)", "parallel springs: B = 1/(c_a + c_b)", 1 / (ca + cb),
                     par[0, 1], 1e-14))
    return out


@case("drives-motor", group="drives")
def drives_motor():
    """Validation case 7.  Motor dynamic characteristic §10.6 with the book's parameters
    (omega_D0 = 157, nu = 3e-3, T = 0.043, J0 = 0.224, p1 = 150, delta1 = 0.02, M1 = 1):
    p0 = 9.2313 (digest; book 9.2), Gamma_c Gamma_b = Gamma_b Gamma_c (10.66); the complex
    transfer-matrix response |a1|, arg a1 against a direct 3-DOF complex solve (rel. 1e-12,
    both exact); resonance peaks for h = 0.25, 0.5, 1, 3 located by a bounded scalar
    maximisation of |a1| from the TM: omega_peak to half a unit of the printed 0.01 and
    |a1|_peak to half a unit of its 5 printed digits."""
    prm = ref.MOTOR
    mot = MotorCharacteristic(prm["omega0"], prm["nu"], prm["T"])
    v, tol = printed("9.2313")
    out = [check("drives-motor", "digest §10.6", "motor partial frequency p0 [1/s]", v, mot.partial_frequency(prm["J0"]), tol),
           check("drives-motor", "seed 001 §10.6 (book: 9.2)", "p0 to the book's 2 digits", 9.2,
                 mot.partial_frequency(prm["J0"]), 0.05 / 9.2)]
    w = 37.0
    Gc, Gb = spring_matrix(mot.c), damper_matrix(mot.b, w)
    out.append(check("drives-motor", "seed 001 (10.66)", "Gamma_c Gamma_b - Gamma_b Gamma_c", 0.0,
                     np.max(np.abs(Gc @ Gb - Gb @ Gc)), 1e-15, scale=1.0))
    out.append(check("drives-motor", "seed 001 (10.66)", "B of Gamma_cb = 1/c_D - i/(b_D w)", 0.0,
                     abs((Gc @ Gb)[0, 1] - (1 / mot.c - 1j / (mot.b * w))), 1e-15, scale=1 / mot.c))

    def chain(h):
        J1 = h * prm["J0"]
        return Chain([*mot.elements(), Inertia(prm["J0"]), Spring(prm["p1"] ** 2 * J1, prm["delta1"]), Inertia(J1),
                      Load(prm["M1"])], start="clamped", end="free")

    for h in (0.25, 0.5, 1.0, 3.0):
        ch = chain(h)
        ws = np.array([1.0, 50.0, 150.0, 212.132, 400.0])
        a1 = forced_response(ch, ws).a[:, -1]
        direct = np.array([ref.motor_direct(wi, h, **prm)[2] for wi in ws])
        out.append(check("drives-motor", "direct complex solve", f"h = {h:g}: max|a1_TM - a1_direct|/|a1_direct|", 0.0,
                         np.max(np.abs(a1 - direct) / np.abs(direct)), 1e-12, scale=1.0))
        amp = lambda q: -abs(forced_response(ch, [q]).a[0, -1])
        w_exp, a_exp = ref.MOTOR_PEAKS[h]
        wv, wt = printed(w_exp)
        res = minimize_scalar(amp, bounds=(wv - 3, wv + 3), method="bounded", options={"xatol": 1e-6})
        out.append(check("drives-motor", "digest §10.6 peak table", f"h = {h:g}: omega_peak [1/s]", wv, res.x, wt))
        av, at = printed(a_exp)
        out.append(check("drives-motor", "digest §10.6 peak table", f"h = {h:g}: |a1|_peak [rad]", av, -res.fun, at))
    return out


@case("drives-slow-variation", group="drives")
def drives_slow_variation():
    """Validation case 8.  Slowly varying frequency (10.20): q'' + p(t)^2 q = 0 with
    p = p0 (1 + 0.5 sin eps t), p0 = 100, q(0) = 1, q'(0) = 0, over one modulation period,
    eps/p0 = 0.005, 0.01, 0.05; DOP853 (rtol 1e-11) as the reference.
    (a) At the turning points (q' = 0, located as events) |q| must equal the package's
    adiabatic amplitude a0 sqrt(p(0)/p(t)) to second order in the slowness: measured
    0.58 (eps/p0)^2; asserted <= (eps/p0)^2 and an observed order in [1.8, 2.2].
    (b) The continuous envelope sqrt(q^2 + (q'/p)^2) ripples at first order (about p'/(2p^2),
    measured 0.21 eps/p0): asserted <= 0.25 eps/p0 (the digest quotes 0.13 eps/p0 for its own
    envelope measure).  (c) The adiabatic phase (integral of p) predicts the number of turning
    points within +-1."""
    out, errs = [], []
    p0 = 100.0
    ratios = (0.005, 0.01, 0.05)
    for ratio in ratios:
        eps = ratio * p0
        t_end = 2 * np.pi / eps
        pf = lambda s, eps=eps: p0 * (1 + 0.5 * np.sin(eps * s))
        tt, qq = ref.slow_oscillator_turning_points(p0, eps, t_end)
        ad_t = adiabatic_response(pf, np.r_[0.0, tt], refine=64)
        err2 = np.max(np.abs(qq / ad_t.amplitude[1:] - 1))
        errs.append(err2)
        out.append(check("drives-slow-variation", "seed 001 (10.20)",
                         f"turning points: max rel. |q| vs adiabatic amplitude, eps/p0 = {ratio:g}", 0.0, err2,
                         ratio**2, scale=1.0))
        t, env = ref.slow_oscillator_envelope(p0, eps, t_end)
        ad = adiabatic_response(pf, t)
        out.append(check("drives-slow-variation", "seed 001 (10.20)", f"envelope ripple, eps/p0 = {ratio:g}",
                         0.0, np.max(np.abs(ad.amplitude / env - 1)), 0.25 * ratio, scale=1.0))
        n_turn = int(np.floor(ad.phase[-1] / np.pi))
        out.append(check("drives-slow-variation", "seed 001 (10.20) phase", f"turning points predicted by the phase, "
                         f"eps/p0 = {ratio:g} (within +-1)", tt.size, n_turn, 1.5 / tt.size))
    order = np.log(errs[-1] / errs[0]) / np.log(ratios[-1] / ratios[0])
    out.append(claim("drives-slow-variation", "seed 001 (10.20)", "turning-point error is second order (order in [1.8, 2.2])",
                     1.8 < order < 2.2, note=f"observed order {order:.3f}"))
    return out
