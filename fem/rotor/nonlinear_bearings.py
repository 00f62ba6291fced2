"""Bearings computed from their geometry in a run-up: their nonlinear laws instead of their tables.

A bearing with ``nonlinear`` True (:mod:`fem.rotor.bearings`: journal bearing, squeeze-film
damper, rolling-element bearing) enters the linear analyses with its linearised coefficient table
and a run-up with its law F(y, z, y', z', Omega, phi) as a smooth planar element
(:class:`discrete.nonsmooth.elements.planar.SmoothPlanarElement`).  This module does what that
takes, for every such bearing alike:

* the *dynamic* rotor: the assembly without these bearings (their forces are the laws), and the
  reduced basis built on the *linearised* rotor (:func:`fem.rotor.reduced.reduce_rotor` with a
  ``basis_system``) with attachment shapes at the bearings, so the basis spans their static
  deflections;
* the static load the bearings carry (the rotor's weight, or the loads given per bearing), applied
  in the run as a constant force;
* the start: the static equilibrium of the nonlinear reduced rotor (Newton with the laws'
  Jacobians by central differences) and the laws linearised there (for the steady start's
  synchronous orbit).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from discrete.errors import ModelError, SolverError
from discrete.nonsmooth.elements.planar import SmoothPlanarElement

from .assembly import RotorSystem, assemble_rotor
from .bearings.static_load import GRAVITY


@dataclass
class BearingHistory:
    """One nonlinear bearing over a run: the journal's ``y``, ``z`` relative to the bearing (m),
    its ``eccentricity`` ratio |r| / clearance, the force magnitude ``force`` on the shaft (N) and its
    components ``force_y``, ``force_z`` (N; evaluated at most at 2000 samples, interpolated between)."""

    name: str
    kind: str
    x: float
    clearance: float
    y: np.ndarray
    z: np.ndarray
    eccentricity: np.ndarray
    force: np.ndarray
    force_y: np.ndarray | None = None
    force_z: np.ndarray | None = None

    def to_dict(self) -> dict:
        return {"name": self.name, "kind": self.kind, "x": self.x, "clearance": self.clearance,
                "max_eccentricity": float(self.eccentricity.max(initial=0.0)),
                "final_eccentricity": float(self.eccentricity[-1]) if self.eccentricity.size else 0.0,
                "max_force": float(self.force.max(initial=0.0))}


def nonlinear_bearings(rs: RotorSystem) -> list:
    """The rotor's bearings that run with their own laws in time runs."""
    return [b for b in rs.rotor.bearings if getattr(b, "nonlinear", False)]


def dynamic_system(rs: RotorSystem) -> RotorSystem:
    """The rotor without its nonlinear bearings (same DOFs: pedestals stay)."""
    return assemble_rotor(rs.rotor, nonlinear_bearings="omitted")


def bearing_dofs(rs: RotorSystem, bearings) -> list[tuple[int, int]]:
    """(v, w) DOF pairs of each bearing's shaft node and, on a pedestal, of the pedestal."""
    out = []
    for b in bearings:
        node = rs.node(b.x, f"[[rotor.{b.kind}]]")
        out.append((int(rs.node_dofs["v"][node]), int(rs.node_dofs["w"][node])))
        if b.pedestal is not None:
            out.append(_pedestal_dofs(rs, b.pedestal))
    return out


def _pedestal_dofs(rs: RotorSystem, name: str) -> tuple[int, int]:
    idx = np.flatnonzero((rs.dof_name == name) & (rs.dof_field == "pedestal_v"))
    jdx = np.flatnonzero((rs.dof_name == name) & (rs.dof_field == "pedestal_w"))
    return int(idx[0]), int(jdx[0])


def elements(rs: RotorSystem, T: np.ndarray, bearings) -> list[SmoothPlanarElement]:
    """One smooth planar element per bearing on the reduced coordinates (rows of the basis T)."""
    out = []
    for i, b in enumerate(bearings, 1):
        node = rs.node(b.x)
        gy, gz = T[rs.node_dofs["v"][node]].copy(), T[rs.node_dofs["w"][node]].copy()
        if b.pedestal is not None:
            pv, pw = _pedestal_dofs(rs, b.pedestal)
            gy, gz = gy - T[pv], gz - T[pw]
        out.append(SmoothPlanarElement(name=b.name or f"{b.kind.replace('_', ' ')} at x = {b.x:g} m", g_y=gy, g_z=gz,
                                       law=b.planar_law(), scale=b.length_scale))
    return out


def static_load(rs: RotorSystem, bearings) -> np.ndarray | None:
    """The full load vector of the run's static state: the rotor's weight when the bearings' loads
    come from it, else the loads given per bearing at their nodes (None: no static load)."""
    weight = [b for b in bearings if b.needs_weight_load]
    given = [b for b in bearings if not b.needs_weight_load and np.any(b.static_load() != 0)]
    if weight and given:
        raise ModelError(f"[[rotor.{given[0].kind}]]", "load", given[0].load,
                         "the same static state for every bearing computed from its geometry: either all take their "
                         "load from the rotor's weight (leave `load` out) or all are given a load")
    if weight:
        return rs.gravity_load(GRAVITY)
    if not given:
        return None
    f = np.zeros(rs.n_dofs)
    for b in given:
        node = rs.node(b.x)
        W = b.static_load()                 # the shaft presses the bearing with W: the load on the shaft is W
        f[rs.node_dofs["v"][node]] += W[0]
        f[rs.node_dofs["w"][node]] += W[1]
    return f


def law_jacobian(e: SmoothPlanarElement, y, z, yd, zd, speed, angle=0.0) -> tuple[np.ndarray, np.ndarray]:
    """(dF/d(y, z), dF/d(y', z')), 2 x 2 each, by central differences (steps 1e-6 of the law's
    length scale and of that scale times max(speed, 1 rad/s))."""
    hp = 1e-6 * e.scale
    hv = hp * max(abs(speed), 1.0)
    base = np.array([y, z, yd, zd], dtype=float)
    J = np.zeros((2, 4))
    for j, h in enumerate((hp, hp, hv, hv)):
        up, dn = base.copy(), base.copy()
        up[j] += h
        dn[j] -= h
        J[:, j] = (np.array(e.force(*up, speed, angle)) - np.array(e.force(*dn, speed, angle))) / (2 * h)
    return J[:, :2], J[:, 2:]


def linearised(els, eta, v, speed, angle=0.0) -> tuple[np.ndarray, np.ndarray]:
    """The laws' stiffness and damping in reduced coordinates at (eta, eta'): K_b = -G^T dF/dr G."""
    n = eta.size
    Kb, Cb = np.zeros((n, n)), np.zeros((n, n))
    for e in els:
        G = np.vstack([e.g_y, e.g_z])
        Jp, Jv = law_jacobian(e, e.g_y @ eta, e.g_z @ eta, e.g_y @ v, e.g_z @ v, speed, angle)
        Kb -= G.T @ Jp @ G
        Cb -= G.T @ Jv @ G
    return Kb, Cb


def equilibrium(K: np.ndarray, els, static: np.ndarray, speed: float, eta0: np.ndarray) -> np.ndarray:
    """The static state K eta = static + sum G^T F(G eta, 0) of the reduced rotor at ``speed`` (Newton
    from ``eta0`` with the laws' Jacobians; steps halved while a law refuses the state)."""
    eta = np.array(eta0, dtype=float)
    zero = np.zeros_like(eta)

    def residual(x):
        r = K @ x - static
        for e in els:
            Fy, Fz = e.force(e.g_y @ x, e.g_z @ x, 0.0, 0.0, speed, 0.0)
            r -= Fy * e.g_y + Fz * e.g_z
        return r

    r = residual(eta)
    scale = max(np.linalg.norm(static), np.linalg.norm(K @ eta), 1e-300)
    for _ in range(100):
        if np.linalg.norm(r) <= 1e-10 * scale:
            return eta
        Kb, _ = linearised(els, eta, zero, speed)
        step = -np.linalg.solve(K + Kb, r)
        lam = 1.0
        while lam > 1e-6:
            try:
                trial = eta + lam * step
                rt = residual(trial)
                if np.linalg.norm(rt) < np.linalg.norm(r) or lam < 1e-3:
                    break
            except SolverError:
                pass
            lam *= 0.5
        else:
            break
        eta, r = trial, rt
    raise SolverError(f"no static equilibrium of the rotor on its nonlinear bearings at {speed:.6g} rad/s (residual "
                      f"{np.linalg.norm(r) / scale:.2e}): the bearings cannot carry the static load there")


def histories(rs: RotorSystem, bearings, els, eta_h: np.ndarray, v_h: np.ndarray, speed: np.ndarray,
              angle: np.ndarray) -> list[BearingHistory]:
    """Each bearing's journal motion and force over the samples."""
    out = []
    n = eta_h.shape[0]
    pick = np.unique(np.r_[np.arange(0, n, max(1, -(-n // 2000))), n - 1]) if n else np.zeros(0, dtype=int)
    for b, e in zip(bearings, els):
        y, z = eta_h @ e.g_y, eta_h @ e.g_z
        yd, zd = v_h @ e.g_y, v_h @ e.g_z
        # the force at (at most) 2000 samples, interpolated between (a finite film solves per evaluation)
        Fc = np.array([e.force(y[k], z[k], yd[k], zd[k], speed[k], angle[k]) for k in pick]).reshape(-1, 2)
        Fp = np.hypot(Fc[:, 0], Fc[:, 1])
        F = np.interp(np.arange(n), pick, Fp) if n else np.zeros(0)
        Fy, Fz = ((np.interp(np.arange(n), pick, Fc[:, j]) for j in (0, 1)) if n else (np.zeros(0), np.zeros(0)))
        out.append(BearingHistory(name=e.name, kind=b.kind, x=float(b.x), clearance=float(b.clearance), y=y, z=z,
                                  force_y=Fy, force_z=Fz,
                                  eccentricity=np.hypot(y, z) / b.clearance, force=F))
    return out
