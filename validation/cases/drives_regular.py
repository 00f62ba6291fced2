"""Drives of regular structure (seed 001 §10.4): FE/lumped models against the closed-form
spectra.  References from validation.analytic.drives (brentq on (10.36), formulas (10.37),
(10.39)), independent of the package's closed forms and solvers."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from fem.drives import DistributedShaft, DriveModel, LumpedShaft, Mechanism, modal
from fem.study import Study
from validation.analytic import drives as ref
from validation.registry import case, check, claim, printed
from validation.examples import EXAMPLES

SRC = "seed 001 §10.4 (10.34)-(10.39), (10.16)"


def _massless_fe(n, boundary, R=ref.SET_R):
    """Massless P1 shaft (one element per segment, rho = 0) with point discs J0 at the stations:
    exactly the regular chain (segment stiffness GI/h = c0)."""
    h = 1.0
    shaft = DistributedShaft(length=h * (n if boundary == "clamped-free" else n + 1), GI=R["c0"] * h, rho=0.0,
                             J0=R["J0"], elements=1, order=1)
    mech = Mechanism(m=R["m"], c=R["c"], ratio=R["ratio"])
    return DriveModel(n=n, shaft=shaft, mechanism=mech, boundary=boundary, representation="discrete")


@case("drives-regular-fe", group="drives")
def drives_regular_fe():
    """Validation case 1.  Massless shaft + point discs + 1-DOF mechanisms (Set R, n = 6 and 48)
    in scikit-fem: all 2n FE eigenvalues equal the two roots per gamma_r of (10.36) with
    (10.16), case 2 (10.38) and case 1 (10.34; n discs, n+1 segments).  The FE model is then
    exactly the lumped chain, so only rounding remains: the digest measured <= 9e-13 for
    n = 48; tolerance 1e-9.  Also the digest's printed Set R roots (n = 6, 4 decimals)."""
    out = []
    for n in (6, 48):
        for boundary, bcase in (("clamped-free", 2), ("clamped-clamped", 1)):
            R = dict(ref.SET_R, n=n)
            expected = ref.regular_roots(n, R["c0"], R["J0"], R["m"], R["c"], R["ratio"], bcase)
            res = modal(_massless_fe(n, boundary), 2 * n, "discrete")
            err = np.max(np.abs(res.omega_rad_s / expected - 1))
            out.append(check("drives-regular-fe", SRC, f"max rel. diff of all {2 * n} roots, n = {n}, case {bcase}",
                             0.0, err, 1e-9, scale=1.0))
            if n == 6:
                table = ref.SET_R_CASE2 if bcase == 2 else ref.SET_R_CASE1
                for i in (0, 5, 6, 11):
                    v, tol = printed(ref.nums(table)[i])
                    out.append(check("drives-regular-fe", "digest Set R table", f"p_{i + 1}, case {bcase} [rad/s]",
                                     v, res.omega_rad_s[i], tol))
    # the stop band (k, p_*) holds no FE eigenvalue
    res = modal(_massless_fe(48, "clamped-free"), 96, "discrete")
    k, p_star = 300.0, 300.0 * np.sqrt(1 + ref.SET_R["m"] * 0.05**2 / ref.SET_R["J0"])
    inside = np.count_nonzero((res.omega_rad_s > k) & (res.omega_rad_s < p_star))
    out.append(claim("drives-regular-fe", SRC, "no eigenvalue in the stop band (k, p_*) = (300, 450), n = 48",
                     inside == 0, note=f"{inside} found"))
    below = np.count_nonzero(res.omega_rad_s < k)
    out.append(claim("drives-regular-fe", SRC, "exactly n roots below k (lower branch condenses at k)", below == 48,
                     note=f"{below} below k"))
    return out


@case("drives-rigid-mechanisms", group="drives")
def drives_rigid_mechanisms():
    """Validation case 2.  Rigid mechanisms (c = inf, disc J0 + m Pi'^2): p_r/p0 of the lumped FE
    model against (10.39) (case 2) and (10.37) (case 1) for n = 6, 9, 12 (exact relation: rtol
    1e-12; the FE model is the exact chain); the digest's 5-digit tables (half a unit of the
    last digit); pass band: p_1 = 2 p0 sin(pi/(2(2n+1))) (case 2) / 2 p0 sin(pi/(2(n+1)))
    (case 1) and p_max < 2 p0."""
    out = []
    J0, m, P, c0 = 0.01, 2.0, 0.05, 1.0e4
    p0 = np.sqrt(c0 / (J0 + m * P**2))
    for n in (6, 9, 12):
        for boundary, bcase in (("clamped-free", 2), ("clamped-clamped", 1)):
            model = DriveModel(n=n, shaft=LumpedShaft(c0=c0, J0=J0), mechanism=Mechanism(m=m, c=float("inf"), ratio=P),
                               boundary=boundary)
            w = modal(model, n, "discrete").omega_rad_s / p0
            formula = ref.rigid_ratio_formula(n, bcase)
            out.append(check("drives-rigid-mechanisms", SRC, f"max rel. diff p_r/p0 vs formula, n = {n}, case {bcase}",
                             0.0, np.max(np.abs(w / formula - 1)), 1e-12, scale=1.0))
            table = (ref.RIGID_CASE2 if bcase == 2 else ref.RIGID_CASE1)[n]
            errs = [abs(w[i] - printed(s)[0]) / (printed(s)[0] * printed(s)[1]) for i, s in enumerate(ref.nums(table))]
            out.append(check("drives-rigid-mechanisms", "digest tables (10.37)/(10.39)",
                             f"worst |p_r/p0 - table| in half-units of the last digit, n = {n}, case {bcase}",
                             0.0, max(errs), 1.0, scale=1.0))
            lo = 2 * np.sin(np.pi / (2 * (2 * n + 1))) if bcase == 2 else 2 * np.sin(np.pi / (2 * (n + 1)))
            out.append(check("drives-rigid-mechanisms", SRC, f"pass-band lower edge p_1/p0, n = {n}, case {bcase}",
                             lo, w[0], 1e-12))
            out.append(claim("drives-rigid-mechanisms", SRC, f"p_max < 2 p0, n = {n}, case {bcase}", w[-1] < 2.0))
    return out


LARGE_N = EXAMPLES / "drive_large_n.toml"


def _set_c_lumped(n: int, boundary: str) -> DriveModel:
    """Set C with n = 1000 mechanisms on a lumped shaft (segment c0 = GI n/L, discs J0 = rho0 L/n,
    m = 10/n) as examples/drive_large_n.toml holds it (clamped-free), with the boundary a check varies."""
    model = Study.load(LARGE_N).drive
    if model.n != n:
        raise ValueError(f"{LARGE_N.name} has n = {model.n}, not {n}")
    # the file's [drive.continuum] length = 2.0 m is the continuum's total length L; the model keeps the
    # per-segment length L/n (it only places the pseudo-medium estimates that seed the solver)
    return replace(model, boundary=boundary, continuum_length=ref.SET_C["L"] / n)


@case("drives-seeded-large-n", group="drives")
def drives_seeded_large_n():
    """Issue 5 performance path.  Set C with n = 1000 mechanisms: 19 of the lowest 20 roots
    crowd within 0.6 % below k = 300 (consecutive ones 1e-5 apart), where the package solves
    the FE model with the certified seeded solver (pseudo-medium estimates, multi-shift
    inverse iteration, Sylvester count).  Reference: brentq on (10.36) with (10.16), both
    boundary cases.  Tolerance 1e-12: the eigenvalues come from cancellation-free spring
    energies (measured 4e-16), the reference is brentq to 1e-15.  Also: the Sylvester count
    certifies 20 modes, and estimates that skip the lowest mode never give a wrong answer
    (the solver refuses; the Lanczos fallback returns the reference roots).  The drive is
    examples/drive_large_n.toml."""
    from discrete.errors import SolverError
    from fem.drives.discrete import build_discrete
    from fem.drives.seeding import continuum_estimates
    from discrete.linalg.seeded import seeded_eigenpairs

    out, n, k = [], 1000, 20
    for boundary, bcase in (("clamped-free", 2), ("clamped-clamped", 1)):
        model = _set_c_lumped(n, boundary)
        R = model.shaft, model.mechanism
        expected = ref.regular_roots(n, R[0].c0, R[0].J0, R[1].m, R[1].c, R[1].ratio, bcase)[:k]
        res = modal(model, k, "discrete")
        out.append(check("drives-seeded-large-n", SRC, f"max rel. diff of the lowest {k} roots, n = {n}, case {bcase}",
                         0.0, np.max(np.abs(res.omega_rad_s / expected - 1)), 1e-12, scale=1.0))
        out.append(claim("drives-seeded-large-n", "discrete.linalg.seeded", f"seeded solver used and certified, case {bcase}",
                         res.method.startswith("seeded") and f"Sylvester count {k} below" in res.method,
                         note=res.method))
        crowd = expected[1:] / 300.0
        out.append(claim("drives-seeded-large-n", SRC, f"roots 2..{k} crowd within 0.6 % below k, case {bcase}",
                         bool(np.all((crowd > 0.994) & (crowd < 1.0))), note=f"{crowd.min():.5f} .. {crowd.max():.7f}"))
    model = _set_c_lumped(n, "clamped-free")
    system = build_discrete(model).system
    lam, rows = continuum_estimates(model, system, k + 2)
    K, M = system.free_block(system.K), system.free_block(system.M)
    try:
        seeded_eigenpairs(K, M, lam[1:], k, start=rows[1:])       # estimates of modes 2..22: mode 1 missing
        refused = False
    except SolverError:
        refused = True
    out.append(claim("drives-seeded-large-n", "discrete.linalg.seeded", "estimates skipping mode 1: the solver refuses", refused))
    return out
