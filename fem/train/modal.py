"""Complex modes of a train at a speed, Campbell diagram and critical speeds (each shaft at its own
speed Omega_i = ratio_i Omega).

The eigen-solution is the rotor's :class:`discrete.linear.complex_modal.QuadraticEigensolver` on the
train's :class:`LinearSystem` (shift-invert Arnoldi of the linearised quadratic problem on the train's
common sparsity pattern; undamped symmetric blocks by the symmetric solver).  This module adds what is
train-specific: the kind of each mode by where its kinetic energy lies (torsion: rotations about x of
shafts and bodies; lateral; axial; "coupled" when no class holds 90 %), and the whirl of every rotor
shaft relative to its own spin (a shaft turning backwards about +x whirls forward when its orbit turns
backwards about +x).  The Campbell diagram and the critical speeds use the rotor's tracking
(:func:`fem.rotor.campbell._track`): MAC assignment from speed to speed, roots of omega_j = k Omega by
Brent's method.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import scipy.sparse as sp

from discrete.errors import ModelError
from discrete.linear.complex_modal import ComplexModeFigures, QuadraticEigensolver

from ..rotor.campbell import CampbellResult, _extra, _orders, _speeds, _track, isotropic_supports
from ..rotor.modal import check_speed
from ..rotor.whirl import Orbits, classify_orbits
from .assembly import TrainSystem, assemble_train
from .model import Train

#: share of the kinetic energy above which a mode is named after one motion class
DOMINANT = 0.9


@dataclass
class TrainModes(ComplexModeFigures):
    """Modes of a train at one reference speed, lowest |lam| first (one of each conjugate pair).

    ``kind``: torsion / lateral / axial / coupled / rigid; ``energy_share`` (n_modes, 3): kinetic
    energy shares of torsion, lateral and axial motion; ``whirl``: the whirl of the rotor shaft with the
    most lateral energy (relative to its own spin), ``whirl_by_shaft``: per rotor shaft."""

    speed_rad_s: float
    eigenvalues: np.ndarray
    shapes: np.ndarray
    residuals: np.ndarray
    rigid: np.ndarray
    tolerance: float
    method: str
    n_dofs: int
    kind: list
    energy_share: np.ndarray
    whirl: list
    whirl_by_shaft: list
    labels: list
    speeds_by_member: dict
    warnings: list = field(default_factory=list)

    def to_dict(self) -> dict:
        return {"speed_rad_s": self.speed_rad_s, "speed_rpm": self.speed_rad_s * 30 / np.pi, "n_dofs": self.n_dofs,
                "n_modes": self.n_modes, **self.frequency_fields(),
                "kind_of_mode": list(self.kind), "energy_share": {"torsion": self.energy_share[:, 0].tolist(),
                                                                   "lateral": self.energy_share[:, 1].tolist(),
                                                                   "axial": self.energy_share[:, 2].tolist()},
                "whirl": list(self.whirl), "whirl_by_shaft": [dict(w) for w in self.whirl_by_shaft],
                "speeds_rad_s_by_member": dict(self.speeds_by_member), **self.reliability_fields()}


def motion_classes(ts: TrainSystem) -> np.ndarray:
    """Class of every DOF: 0 torsion (rotation about x), 1 lateral, 2 axial."""
    cls = np.ones(ts.n_dofs, dtype=int)
    cls[np.isin(ts.dof_field, ("theta_x", "theta"))] = 0
    cls[ts.dof_field == "u"] = 2
    return cls


def describe(ts: TrainSystem, res, speed: float) -> TrainModes:
    """The train view of a :class:`~discrete.linear.complex_modal.ComplexModalResult` of ``ts``."""
    phi = res.shapes
    Mphi = ts.M @ phi
    e = np.abs(np.conj(phi) * Mphi)                     # kinetic energy density per DOF
    cls = motion_classes(ts)
    share = np.stack([e[cls == k].sum(axis=0) for k in range(3)], axis=1)
    tot = share.sum(axis=1, keepdims=True)
    share = np.where(tot > 0, share / np.where(tot > 0, tot, 1.0), 0.0)
    kinds = []
    for r in range(phi.shape[1]):
        if res.rigid[r]:
            kinds.append("rigid")
        elif share[r].max() >= DOMINANT:
            kinds.append(("torsion", "lateral", "axial")[int(np.argmax(share[r]))])
        else:
            kinds.append("coupled")
    whirl, by_shaft = [], []
    rotors = ts.rotor_nodes
    for r in range(phi.shape[1]):
        per, best, best_e = {}, "none", 0.0
        for name, ratio, iv, iw in rotors:
            V, W = phi[iv, r], phi[iw, r]
            sgn = -1.0 if ratio < 0 else 1.0            # mirror w: the orbit's sense relative to the spin
            w_, _ = classify_orbits(Orbits.of(V[None, :], sgn * W[None, :]))
            energy = float(e[np.concatenate([iv, iw]), r].sum())
            per[name] = w_ if energy > 1e-12 * max(float(e[:, r].sum()), 1e-300) else "none"
            if kinds[r] in ("lateral", "coupled") and energy > best_e:
                best, best_e = per[name], energy
        whirl.append(best if kinds[r] in ("lateral", "coupled") else "none")
        by_shaft.append(per)
    speeds = {m: ratio * speed for m, ratio in ts.ratios.items()}
    return TrainModes(speed_rad_s=float(speed), eigenvalues=res.eigenvalues, shapes=phi, residuals=res.residuals,
                      rigid=res.rigid, tolerance=res.tolerance, method=res.method, n_dofs=res.n_dofs, kind=kinds,
                      energy_share=share, whirl=whirl, whirl_by_shaft=by_shaft,
                      labels=[ts.label(i) for i in range(ts.n_dofs)], speeds_by_member=speeds,
                      warnings=list(res.warnings) + list(ts.warnings))


def _rigid_once(res, n_modes: int):
    """Each rigid-body motion once.  A rigid-body eigenvalue lam = 0 of a damped or gyroscopic block is
    defective (q = a + b t): the Arnoldi solver may return it as two real eigenvalues +-eps, both kept.
    The rigid shapes are replaced by an orthonormal basis of their span (its rank: the number of rigid
    motions) and the surplus entries dropped; then the lowest ``n_modes`` are kept."""
    R = np.flatnonzero(res.rigid)
    keep = np.ones(res.eigenvalues.size, dtype=bool)
    shapes = res.shapes.copy()
    if R.size > 1:
        V = np.hstack([shapes[:, R].real, shapes[:, R].imag])
        U, sv, _ = np.linalg.svd(V, full_matrices=False)
        r = int(np.sum(sv > 1e-6 * sv[0])) if sv.size and sv[0] > 0 else 0
        r = max(r, 1)
        shapes[:, R[:r]] = U[:, :r] / np.abs(U[:, :r]).max(axis=0)
        keep[R[r:]] = False
    idx = np.flatnonzero(keep)[:n_modes]
    return replace(res, eigenvalues=res.eigenvalues[idx], shapes=shapes[:, idx], residuals=res.residuals[idx],
                   rigid=res.rigid[idx], block=res.block[idx]), int(keep.sum())


def _all_modes(ts: TrainSystem, speed: float, K, C, tolerance: float):
    """Every mode of a small train (all eigenpairs of the free DOFs' linearisation, dense shift-invert):
    for trains whose duplicate rigid-body entries the capped count of the sparse solver would cut."""
    from discrete.linear.complex_modal import (ComplexModalResult, _dense, _normalise, _one_of_each_pair,
                                               _residuals, _scale)

    sys_ = ts.system_at(speed)
    K = sys_.K if K is None else K
    C = sys_.C if C is None else C
    f = sys_.free
    Mf, Kf = sys_.free_block(sys_.M), sp.csr_matrix(K)[f][:, f]
    Df = sp.csr_matrix(C + speed * sys_.G)[f][:, f]
    lam, phi, sigma = _dense(Mf, Kf, Df)
    lam, phi = _one_of_each_pair(lam, phi)
    level = (1e-2 * abs(sigma)) if sigma else 1e-9 * max(_scale(Mf, Kf), 1e-300)
    rigid = np.abs(lam) <= level
    lam = np.where(rigid, 0.0, lam)
    order = np.lexsort((np.abs(lam.imag), np.abs(lam)))
    lam, phi, rigid = lam[order], _normalise(phi[:, order]), rigid[order]
    res = _residuals(Mf, Kf, Df, lam, phi)
    shapes = np.zeros((ts.n_dofs, lam.size), complex)
    shapes[f] = phi
    return ComplexModalResult(eigenvalues=lam, shapes=shapes, residuals=res, rigid=rigid,
                              block=np.zeros(lam.size, int), speed=speed, n_dofs=int(f.size),
                              method="dense shift-invert of the linearisation (all modes)", tolerance=tolerance)


class TrainEigen:
    """Repeated complex modal solves of one assembled train (the rotor's workspace on the train)."""

    def __init__(self, ts: TrainSystem):
        self.ts = ts
        self.solver = QuadraticEigensolver(ts.system_at(_any_speed(ts)), patterns=[ts.pattern])
        self.extra = 0                  # surplus rigid entries seen (asked for on top of n_modes)

    def modes(self, speed: float, n_modes: int, tolerance: float = 1e-6) -> TrainModes:
        ts = self.ts
        K = ts.stiffness(speed) if ts.speed_dependent else None
        C = ts.damping(speed) if ts.speed_dependent else None
        n_free = ts.n_dofs - ts.constrained.size
        while True:
            k = min(n_modes + self.extra, n_free)
            res = self.solver.solve(k, speed=speed, K=K, C=C, tolerance=tolerance)
            res, n_ok = _rigid_once(res, n_modes)
            if n_ok >= min(n_modes, n_free):
                break
            if k == n_free:             # the solver's count is capped at the free DOFs: all modes densely
                res, _ = _rigid_once(_all_modes(ts, speed, K, C, tolerance), n_modes)
                break
            self.extra += n_modes - n_ok
        return describe(ts, res, speed)


def _any_speed(ts: TrainSystem) -> float:
    """A reference speed at which every shaft's bearing tables are defined (the solver's template)."""
    if not ts.speed_dependent:
        return 0.0
    lo, hi = 0.0, np.inf
    for b in ts.blocks:
        if b.rs is not None and b.rs.tables:
            r = abs(b.ratio)
            for t in b.rs.tables:
                if t.extrapolate == "refuse":
                    lo, hi = max(lo, t.grid[0] / r), min(hi, t.grid[-1] / r)
    if lo > hi:
        raise ModelError("[[shaft]]", "bearing speeds", [lo, hi], "bearing tables whose speed ranges overlap at the "
                         "shafts' own speeds")
    return lo


def as_train_system(train) -> TrainSystem:
    if isinstance(train, TrainSystem):
        return train
    if isinstance(train, Train):
        return assemble_train(train)
    raise ModelError("train", "train", type(train).__name__, "a fem.train.Train or an assembled TrainSystem")


def workspace(ts: TrainSystem) -> TrainEigen:
    if ts._workspace is None:
        ts._workspace = TrainEigen(ts)
    return ts._workspace


def train_modes(train, speed: float = 0.0, n_modes: int = 6, *, tolerance: float = 1e-6) -> TrainModes:
    """Complex modes of ``train`` (a :class:`Train` or :class:`TrainSystem`) at the reference ``speed``
    (rad/s, >= 0): the lowest ``n_modes`` by |lam|."""
    ts = as_train_system(train)
    return workspace(ts).modes(check_speed(speed), n_modes, tolerance)


def train_campbell(train, speeds, n_modes: int = 6, *, orders=(1.0,), critical: bool = True,
                   tolerance: float = 1e-6, xtol: float = 1e-10, progress=None) -> CampbellResult:
    """Campbell diagram over reference ``speeds`` (rad/s): ``n_modes`` tracked modes and the critical
    speeds of ``orders`` (omega_j(Omega) = k Omega: k times the *reference* speed; an excitation of
    another shaft at its own speed is the order k |ratio_i|)."""
    ts = as_train_system(train)
    s = _speeds(speeds)
    orders = _orders(orders)
    eig = workspace(ts)
    n_cand = min(n_modes + _extra(n_modes), ts.n_dofs - ts.constrained.size)
    eig.solver.sweep(True)
    try:
        result = _track(eig, s, n_modes, n_cand, tolerance, orders, critical, xtol, progress)
    finally:
        eig.solver.sweep(False)
    result.isotropic_supports = train_isotropic(ts)
    return result


def train_isotropic(ts: TrainSystem) -> bool:
    """Every rotor shaft's supports and every connection rotationally symmetric (a gear mesh acting on
    lateral DOFs is not: its line of action is one direction)."""
    return (all(isotropic_supports(b.rs.rotor) for b in ts.blocks if b.rs is not None)
            and all(c.isotropic(ts) for c in ts.train.connections))
