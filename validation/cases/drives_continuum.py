"""The continuum pseudo-medium (seed 001 §10.5): discrete drives converge to it, and its
two-field scikit-fem discretisation converges to the frequency equation (10.50).
References: validation.analytic.drives.pseudo_medium_roots (brentq on (10.50) with J0 = rho L,
the digest's correction) and the digest's printed Set C numbers."""
from __future__ import annotations

import numpy as np

from fem.drives import DistributedShaft, DriveModel, Mechanism
from fem.drives.continuum import build_continuum
from fem.drives.discrete import build_discrete
from discrete.linear.modal import modal_analysis
from validation.analytic import drives as ref
from validation.registry import case, check, claim, printed

SRC = "seed 001 §10.5 (10.48)-(10.54)"
C = ref.SET_C


def set_c(n: int, elements: int = 8, order: int = 2) -> DriveModel:
    m = C["M_total"] / n
    return DriveModel(n=n, shaft=DistributedShaft(length=C["L"], GI=C["GI"], rho=C["rho"], elements=elements, order=order),
                      mechanism=Mechanism(m=m, c=m * C["k"] ** 2, ratio=C["ratio"]), boundary="clamped-free",
                      continuum_elements=elements, continuum_order=order)


def _exact(r):
    return ref.pseudo_medium_roots(C["L"], C["GI"], C["rho"], C["M_total"], C["ratio"], C["k"], r)


@case("drives-discrete-to-continuum", group="drives")
def drives_discrete_to_continuum():
    """Validation case 3.  Distributed shaft (Set C, P2, 8 elements per segment) with n discrete
    mechanisms at x_j = jL/n, n = 6 ... 96, totals n m, k, Pi', rho0, GI0, L fixed: the roots
    p_11, p_21 (lowest two) and p_12, p_22 (upper branch, shift-invert near them) converge to
    (10.50) as O(1/n).  Asserted: |rel. dev.| <= 0.05/n (digest: the deviation is ~0.045/n for
    p_11, p_12), monotone decrease, observed order of p_11 and p_12 in [0.85, 1.15] between
    successive n; the digest's printed FE values for n = 6 and 96 to half a unit of the 3rd decimal
    (same discretisation); the lumped-disc variant (J0 = rho0 L/n, massless shaft) p_11, p_12 for
    n = 6 .. 48 against the digest's printed values."""
    ns = (6, 12, 24, 48, 96)
    exact = np.array([_exact(1)[0], _exact(2)[0], _exact(1)[1], _exact(2)[1]])
    printed_fe = {6: ("284.110", "298.139", "1172.169", "3351.944"), 96: ("286.208", "298.463", "1164.241", "3349.313")}
    devs, out = [], []
    for n in ns:
        sys_ = build_discrete(set_c(n)).system
        low = modal_analysis(sys_, 2).omega_rad_s
        up1 = modal_analysis(sys_, 1, shift=(0.97 * exact[2]) ** 2).omega_rad_s[0]
        up2 = modal_analysis(sys_, 1, shift=(0.99 * exact[3]) ** 2).omega_rad_s[0]
        got = np.array([low[0], low[1], up1, up2])
        dev = got / exact - 1
        devs.append(dev)
        for q, name in ((0, "p_11"), (2, "p_12")):
            out.append(check("drives-discrete-to-continuum", SRC, f"{name} rel. deviation from (10.50), n = {n} (bound 0.05/n)",
                             0.0, abs(dev[q]), 0.05 / n, scale=1.0))
        if n in printed_fe:
            for q, s in enumerate(printed_fe[n]):
                v, tol = printed(s)
                out.append(check("drives-discrete-to-continuum", "digest (a)3 FE table", f"root {q + 1} of 4, n = {n} [rad/s]",
                                 v, got[q], tol))
    # lumped-disc variant (discs J0 = rho0 L/n on a massless shaft): the digest's p_11, p_12
    from fem.drives import LumpedShaft, modal
    lumped = DriveModel(n=6, shaft=LumpedShaft(c0=6.0e4, J0=0.02 / 6), mechanism=Mechanism(m=10 / 6, c=10 / 6 * 9e4,
                        ratio=0.05), continuum_length=2.0 / 6)
    for n, p11, p12 in ((6, "283.9146", "1080.73"), (12, "285.1691", "1121.01"), (24, "285.7653", "1142.06"),
                        (48, "286.0556", "1152.81")):
        w = modal(lumped.with_n(n), n + 1, "discrete").omega_rad_s
        for s, got, name in ((p11, w[0], "p_11"), (p12, w[n], "p_12")):
            v, tol = printed(s)
            out.append(check("drives-discrete-to-continuum", "digest (a)3 lumped-disc variant",
                             f"{name}, lumped discs, n = {n} [rad/s]", v, got, tol))
    devs = np.abs(np.array(devs))
    out.append(claim("drives-discrete-to-continuum", SRC, "monotone convergence of all four roots as n doubles",
                     bool(np.all(np.diff(devs, axis=0) < 0))))
    order = np.log(devs[:-1] / devs[1:]) / np.log(2)
    for q, name in ((0, "p_11"), (2, "p_12")):
        out.append(claim("drives-discrete-to-continuum", SRC, f"observed order of {name} in [0.85, 1.15] (O(1/n))",
                         bool(np.all((order[:, q] > 0.85) & (order[:, q] < 1.15))),
                         note="orders " + ", ".join(f"{v:.3f}" for v in order[:, q])))
    return out


@case("drives-pseudo-medium-fe", group="drives")
def drives_pseudo_medium_fe():
    """Validation case 4.  The two-field FE (theta, y) of the pseudo-medium (Set C) against
    (10.50): upper-branch errors of r = 1..3 shrink as O(h^2) with P1 and O(h^4) with P2
    (observed orders in [1.8, 2.2] and [3.6, 4.4] where the error is above 1e-11); tolerances
    from the leading consistent-mass error (sigma h)^2/24 (P1) and (sigma h)^4/1440 (P2) with
    sigma the wavenumber of the root, times 3; lower roots within 2e-4 with 8 P1 elements (digest);
    NO eigenvalue in the stop band (k, p_*) = (300, 450) for any mesh (all eigenvalues counted;
    the clamped mesh has one extra y-only mode at exactly p = k -- theta = 0, y in the kernel of
    the coupling, since y has one DOF more than the clamped theta -- which lies on the band edge,
    not inside: |p/k - 1| < 1e-9 is counted as "at k");
    rigid mechanisms (c = inf) give (10.51) = 740.4805 (printed)."""
    out = []
    k, p_star = C["k"], C["k"] * np.sqrt(1 + C["M_total"] * C["ratio"] ** 2 / (C["rho"] * C["L"]))
    exact_hi = np.array([_exact(r)[1] for r in (1, 2, 3)])
    exact_lo = np.array([_exact(r)[0] for r in (1, 2, 3)])
    for order, meshes in ((1, (8, 16, 32, 64)), (2, (8, 16, 32))):
        errs = []
        for ne in meshes:
            cd = build_continuum(set_c(12, ne, order))
            res = modal_analysis(cd.system, cd.system.n_free)
            w = res.omega_rad_s
            at_k = np.abs(w / k - 1) < 1e-9
            inside = np.count_nonzero((w > k) & (w < p_star) & ~at_k)
            out.append(claim("drives-pseudo-medium-fe", SRC, f"no eigenvalue in (k, p_*), P{order} x {ne}", inside == 0,
                             note=f"{inside} inside; {np.count_nonzero(w < k)} below k; {np.count_nonzero(at_k)} at k"))
            up = np.sort(w[w > p_star])[:3]
            e = np.abs(up / exact_hi - 1)
            errs.append(e)
            h = C["L"] / ne
            sigma = exact_hi * np.sqrt((C["rho"] + (C["M_total"] / C["L"]) * C["ratio"] ** 2 / (1 - exact_hi**2 / k**2)) / C["GI"])
            lead = (sigma * h) ** 2 / 24 if order == 1 else (sigma * h) ** 4 / 1440
            for r in range(3):
                out.append(check("drives-pseudo-medium-fe", SRC, f"p_{r + 1}2, P{order} x {ne} el.", exact_hi[r], up[r],
                                 3 * lead[r] + 1e-11))
            if order == 1 and ne == 8:
                lo = np.sort(w)[:3]
                out.append(check("drives-pseudo-medium-fe", SRC, "max rel. error of p_11..p_31, P1 x 8", 0.0,
                                 np.max(np.abs(lo / exact_lo - 1)), 2e-4, scale=1.0))
        errs = np.array(errs)
        ok = errs[:-1] > 1e-11
        rates = np.log(errs[:-1] / errs[1:]) / np.log(2)
        lo_b, hi_b = (1.8, 2.2) if order == 1 else (3.6, 4.4)
        good = np.all((rates[ok] > lo_b) & (rates[ok] < hi_b))
        out.append(claim("drives-pseudo-medium-fe", SRC, f"observed order P{order} in [{lo_b}, {hi_b}]", bool(good),
                         note="rates " + np.array2string(rates, precision=2)))
    v, tol = printed(ref.SET_C_ROOTS["rigid"])
    rig = set_c(12, 32, 2)
    rig = DriveModel(n=12, shaft=rig.shaft, mechanism=Mechanism(m=rig.mechanism.m, c=float("inf"), ratio=C["ratio"]),
                     continuum_elements=32)
    w = modal_analysis(build_continuum(rig).system, 1).omega_rad_s[0]
    out.append(check("drives-pseudo-medium-fe", "seed 001 (10.51), digest Set C", "rigid mechanisms p_1 [rad/s]", v, w, tol))
    lead = (np.pi / 2 / C["L"] * C["L"] / 32) ** 4 / 1440      # (sigma h)^4/1440, P2 x 32
    out.append(check("drives-pseudo-medium-fe", "seed 001 (10.51)", "rigid mechanisms p_1 vs formula, P2 x 32",
                     ref.pseudo_medium_rigid(C["L"], C["GI"], C["rho"], C["M_total"], C["ratio"], 1), w, 3 * lead + 1e-11))
    for key, r, b in (("p11", 1, 0), ("p12", 1, 1), ("p21", 2, 0), ("p22", 2, 1), ("p31", 3, 0), ("p32", 3, 1)):
        v, tol = printed(ref.SET_C_ROOTS[key])
        out.append(check("drives-pseudo-medium-fe", "digest Set C (10.50) roots", f"reference {key} (brentq) vs printed",
                         v, _exact(r)[b], tol))
    return out
