"""Undamped critical speeds directly from a linear eigenproblem, and the critical speed map.

Without damping, a mode of frequency omega = k Omega at the speed Omega makes

    (K - (k Omega)^2 M + i k Omega Omega G) phi = 0   <=>   K phi = Omega^2 (k^2 M - i k G) phi,

a *linear* eigenproblem in mu = Omega^2 (G is skew, so k^2 M - i k G is Hermitian; with a
symmetric positive definite K every 1/mu is real).  Its positive eigenvalues are exactly the
undamped critical speeds of order k, forward and backward, with no tracking and no root
finding.  It is solved for the largest nu = 1/mu of (k^2 M - i k G) phi = nu K phi by
Arnoldi with one factorisation of K (lateral DOFs only: axial and torsional motion has no
gyroscopic term and decouples).  Used for the undamped critical speed map against bearing
stiffness, and as an independent check of the root finding of :mod:`fem.rotor.campbell`.
"""
from __future__ import annotations

import dataclasses
import warnings as _warnings
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from discrete.errors import ModelError, SolverError
from discrete.linalg.blas import single_threaded_blas

from .assembly import RotorSystem, assemble_rotor
from .model import Bearing, Rotor
from .modal import as_system, check_speed
from .whirl import classify

LATERAL_FIELDS = ("v", "w", "theta_y", "theta_z", "pedestal_v", "pedestal_w")


@dataclass
class UndampedCriticalSpeeds:
    """Critical speeds of one order from the linear eigenproblem (ascending)."""

    order: float
    speeds_rad_s: np.ndarray
    whirl: list
    shapes: np.ndarray                  # (n_dofs, n) complex
    residuals: np.ndarray

    def to_dict(self) -> dict:
        return {"order": self.order, "speeds_rad_s": self.speeds_rad_s.tolist(),
                "speeds_rpm": (self.speeds_rad_s * 30 / np.pi).tolist(), "whirl": list(self.whirl),
                "residuals": self.residuals.tolist()}


def undamped_critical_speeds(rotor, n: int = 4, *, order: float = 1.0, speed: float | None = None) -> UndampedCriticalSpeeds:
    """The lowest ``n`` undamped critical speeds of ``order`` (bearing damping ignored; tabulated
    bearings taken at ``speed``, required for them)."""
    rs = as_system(rotor)
    order = float(order)
    if not np.isfinite(order) or order <= 0:
        raise ModelError("[analysis]", "order", order, "an excitation order > 0 (1 = synchronous)")
    if rs.speed_dependent and speed is None:
        raise ModelError("[analysis]", "speed", None, "the speed (rad/s) at which to take the tabulated bearings")
    K = rs.stiffness(check_speed(speed) if speed is not None else 0.0)
    lat = np.isin(rs.dof_field, LATERAL_FIELDS)
    lat[rs.constrained] = False
    idx = np.flatnonzero(lat)
    Kl = sp.csc_matrix(K[idx][:, idx])
    B = sp.csr_matrix(order**2 * rs.M[idx][:, idx] - 1j * order * rs.G[idx][:, idx])
    m = idx.size
    try:
        lu = spla.splu(Kl)
    except RuntimeError:
        raise ModelError("[[rotor.bearing]]", "bearings", len(rs.rotor.bearings),
                         "supports that hold the rotor laterally: K is singular (a free rotor has no critical speeds "
                         "in this sense)") from None
    piv = np.abs(lu.U.diagonal())
    if piv.min() <= 1e3 * np.finfo(float).eps * piv.max():
        raise ModelError("[[rotor.bearing]]", "bearings", len(rs.rotor.bearings),
                         "supports that hold the rotor laterally (K is singular to working precision)")
    k = min(n + 2, m - 2)
    if m <= 40 or k < 1:
        nu, Phi = sla.eig(B.toarray(), Kl.toarray())
    else:
        def apply(x):
            y = B @ x
            return lu.solve(np.ascontiguousarray(y.real)) + 1j * lu.solve(np.ascontiguousarray(y.imag))

        op = spla.LinearOperator((m, m), matvec=apply, dtype=complex)
        with _warnings.catch_warnings(), single_threaded_blas():
            _warnings.simplefilter("ignore", sp.SparseEfficiencyWarning)
            v0 = np.random.default_rng(12345).uniform(0.5, 1.5, m).astype(complex)
            nu, Phi = spla.eigs(op, k=k, which="LR", v0=v0, ncv=min(m, max(2 * k + 1, 24)), tol=1e-13)
    real = np.isfinite(nu) & (nu.real > 0) & (np.abs(nu.imag) <= 1e-8 * np.abs(nu))
    nu, Phi = nu[real].real, Phi[:, real]
    order_idx = np.argsort(-nu)[:n]
    nu, Phi = nu[order_idx], Phi[:, order_idx]
    speeds = 1.0 / np.sqrt(nu)
    full = np.zeros((rs.n_dofs, nu.size), dtype=complex)
    full[idx] = Phi
    whirl = [classify(full[rs.node_dofs["v"], j], full[rs.node_dofs["w"], j])[0] for j in range(nu.size)]
    # residual of the quadratic problem at lam = i k Omega (no damping)
    res = []
    Kf, Mf, Gf = K[idx][:, idx], rs.M[idx][:, idx], rs.G[idx][:, idx]
    nK = abs(Kf).sum(axis=0).max()
    nM = abs(Mf).sum(axis=0).max()
    nG = abs(Gf).sum(axis=0).max() if Gf.nnz else 0.0
    for j, W in enumerate(speeds):
        lam = 1j * order * W
        r = Kf @ Phi[:, j] + lam * W * (Gf @ Phi[:, j]) + lam**2 * (Mf @ Phi[:, j])
        res.append(float(np.linalg.norm(r) / ((abs(lam) ** 2 * nM + abs(lam) * W * nG + nK) * np.linalg.norm(Phi[:, j]))))
    return UndampedCriticalSpeeds(order=order, speeds_rad_s=speeds, whirl=whirl, shapes=full,
                                  residuals=np.asarray(res))


@dataclass
class CriticalSpeedMap:
    """Undamped critical speeds (synchronous, order 1) against a common bearing stiffness.

    ``speeds_rad_s`` (n_stiffness, n): ascending per row, NaN where fewer were found;
    ``whirl`` likewise; ``bearing_curves``: per tabulated bearing (speeds, kyy, kzz) for the
    classical overlay of the bearings' own stiffness against speed."""

    stiffness: np.ndarray
    speeds_rad_s: np.ndarray
    whirl: list
    bearing_curves: list = field(default_factory=list)
    warnings: list = field(default_factory=list)

    def to_dict(self) -> dict:
        sp_ = np.where(np.isfinite(self.speeds_rad_s), self.speeds_rad_s, np.nan)
        return {"stiffness_n_per_m": self.stiffness.tolist(),
                "speeds_rad_s": [[None if np.isnan(v) else float(v) for v in row] for row in sp_],
                "whirl": [list(r) for r in self.whirl],
                "bearing_curves": [{k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in c.items()}
                                   for c in self.bearing_curves],
                "warnings": list(self.warnings)}


def critical_speed_map(rotor: Rotor, stiffness, n: int = 4) -> CriticalSpeedMap:
    """Undamped synchronous critical speeds of ``rotor`` with every bearing replaced by an
    isotropic, undamped bearing of each ``stiffness`` (N/m, > 0) in turn (pedestals kept)."""
    if isinstance(rotor, RotorSystem):
        rotor = rotor.rotor
    if not isinstance(rotor, Rotor):
        raise ModelError("rotor", "rotor", type(rotor).__name__, "a fem.rotor.Rotor")
    if not rotor.bearings:
        raise ModelError("[[rotor.bearing]]", "bearings", 0, "at least one bearing (the map varies their stiffness)")
    ks = np.atleast_1d(np.asarray(stiffness, dtype=float))
    if ks.size == 0 or not np.all(np.isfinite(ks)) or np.any(ks <= 0):
        raise ModelError("[analysis]", "stiffness", ks.tolist(), "bearing stiffness values > 0 (N/m)")
    out = np.full((ks.size, n), np.nan)
    whirl = [[""] * n for _ in ks]
    notes = []
    for i, kb in enumerate(ks):
        bearings = [Bearing(x=b.x, kyy=kb, kzz=kb, pedestal=b.pedestal, name=b.name,
                            k_axial=b.k_axial, c_axial=b.c_axial) for b in rotor.bearings]
        r = dataclasses.replace(rotor, bearings=bearings)
        try:
            cs = undamped_critical_speeds(assemble_rotor(r), n)
        except SolverError as exc:
            notes.append(f"k = {kb:g} N/m: {exc}")
            continue
        out[i, :cs.speeds_rad_s.size] = cs.speeds_rad_s
        for j, w in enumerate(cs.whirl):
            whirl[i][j] = w
    curves = []
    for b_no, b in enumerate(rotor.bearings, 1):
        if b.speed_dependent:
            t = b.table()
            curves.append({"bearing": b_no, "x": b.x, "speeds_rad_s": b.speed_grid, "kyy": t["kyy"], "kzz": t["kzz"]})
    return CriticalSpeedMap(stiffness=ks, speeds_rad_s=out, whirl=whirl, bearing_curves=curves, warnings=notes)


def forward_columns(cmap: CriticalSpeedMap, n: int, backward: bool = False) -> np.ndarray:
    """(n_stiffness, n): the lowest ``n`` forward (not backward) critical speeds of each row of the
    map, rad/s, NaN where fewer; a repeated pair (no gyroscopic split) counts once.  ``backward``:
    keep the backward ones too (anisotropic pedestals: forward and backward whirl couple, the
    classification of elliptic orbits changes along the map and the unbalance excites both)."""
    out = np.full((cmap.stiffness.size, n), np.nan)
    for i in range(cmap.stiffness.size):
        row = [w for w, h in zip(cmap.speeds_rad_s[i], cmap.whirl[i])
               if np.isfinite(w) and (backward or h != "backward")]
        keep = []
        for w in sorted(row):
            if not keep or abs(w - keep[-1]) > 1e-7 * w:
                keep.append(w)
        out[i, :min(n, len(keep))] = keep[:n]
    return out


def _log_interp(k, ks, S):
    """S(k) of a map column, interpolated linearly in log k and log S (NaN outside)."""
    ok = np.isfinite(S)
    if ok.sum() < 2 or not ks[ok][0] <= k <= ks[ok][-1]:
        return np.nan
    return float(np.exp(np.interp(np.log(k), np.log(ks[ok]), np.log(S[ok]))))


def bearing_overlay(rotor, cmap: CriticalSpeedMap, forward: np.ndarray, speeds=None) -> tuple[list, list]:
    """The model's own bearings on the map: per bearing and direct coefficient (kyy, kzz) a constant
    stiffness or its curve k(speed) over ``speeds`` (rad/s; tabulated bearings, interpolated as the
    model does), and the intersections with the forward critical-speed curves: speeds where
    Omega = S_j(k_b(Omega)), the classical reading of the map (exact for identical isotropic
    bearings; an estimate when the bearings differ, since the map varies all of them together)."""
    if isinstance(rotor, RotorSystem):
        rotor = rotor.rotor
    rs = assemble_rotor(rotor)
    ks = cmap.stiffness
    overlay, points = [], []
    for b_no, b in enumerate(rotor.bearings, 1):
        name = b.name or f"bearing {b_no}"
        if b.speed_dependent:
            t = rs.tables[[tb.index for tb in rs.tables].index(b_no)]
            s = np.linspace(t.grid[0], t.grid[-1], 200) if speeds is None else np.asarray(speeds, float)
            coeff = t.at(s)
            curves = {"kyy": coeff[:, 0], "kzz": coeff[:, 3]}
        else:
            tab = b.table()
            s, curves = None, {"kyy": float(tab["kyy"][0]), "kzz": float(tab["kzz"][0])}
        iso = np.array_equal(np.asarray(curves["kyy"]), np.asarray(curves["kzz"]))
        for kind, kb in curves.items():
            if kind == "kzz" and iso:
                continue                                      # isotropic: one line
            if np.all(np.asarray(kb) <= 0):
                continue
            kind = "k" if iso else kind
            overlay.append({"name": name, "kind": kind, "stiffness": kb if s is None else np.asarray(kb),
                            "speeds_rad_s": s})
            for j in range(forward.shape[1]):
                if s is None:
                    w = _log_interp(kb, ks, forward[:, j])
                    if np.isfinite(w):
                        points.append({"name": name, "kind": kind, "mode": j + 1, "stiffness": kb, "speed_rad_s": w})
                    continue
                g = np.array([_log_interp(k_, ks, forward[:, j]) - w_ if k_ > 0 else np.nan for k_, w_ in zip(kb, s)])
                for i in np.flatnonzero(np.isfinite(g[:-1]) & np.isfinite(g[1:]) & (g[:-1] * g[1:] <= 0)):
                    a = g[i] / (g[i] - g[i + 1]) if g[i] != g[i + 1] else 0.0
                    w = float(s[i] + a * (s[i + 1] - s[i]))
                    points.append({"name": name, "kind": kind, "mode": j + 1,
                                   "stiffness": float(kb[i] + a * (kb[i + 1] - kb[i])), "speed_rad_s": w})
    return overlay, points


def merge_identical(overlay: list, points: list) -> tuple[list, list]:
    """Bearings with the same stiffness (constant or curve) drawn and listed once, their names joined."""
    def key(c):
        k = c["stiffness"]
        return (c["kind"], tuple(np.round(np.atleast_1d(k), 9)), None if c["speeds_rad_s"] is None
                else tuple(np.round(np.asarray(c["speeds_rad_s"]), 9)))

    groups: dict = {}
    for c in overlay:
        groups.setdefault(key(c), []).append(c)
    merged = [dict(g[0], name=", ".join(c["name"] for c in g)) for g in groups.values()]
    names = {c["name"]: m["name"] for m in merged for c in groups[key(m)]}
    seen, pts = set(), []
    for p in points:
        q = dict(p, name=names.get(p["name"], p["name"]))
        k = (q["name"], q["kind"], q["mode"], round(q["speed_rad_s"], 6))
        if k not in seen:
            seen.add(k)
            pts.append(q)
    return merged, pts
