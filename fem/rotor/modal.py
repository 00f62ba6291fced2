"""Complex modes of a rotor at a speed: damped natural frequencies, damping, whirl, orbit shapes.

The eigen-solution is :class:`discrete.linear.complex_modal.QuadraticEigensolver` on the
rotor's :class:`LinearSystem` at the speed (shift-invert Arnoldi of the linearised quadratic
problem, residuals per mode); this module adds what is rotor-specific: which motion a mode is
(lateral, axial, torsional, rigid), its whirl direction and the orbit of every shaft node.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from discrete.errors import ModelError
from discrete.linear.complex_modal import ComplexModalResult, ComplexModeFigures, QuadraticEigensolver

from .assembly import RotorSystem, assemble_rotor
from .model import Rotor
from .whirl import Orbits, classify_many


@dataclass
class RotorModes(ComplexModeFigures):
    """Modes at one speed, lowest |lam| first (one of each conjugate pair).

    Frequencies in rad/s: ``omega_damped_rad_s`` = Im lam, ``natural_frequency_rad_s`` = |lam|;
    ``damping_ratio`` = -Re lam / |lam|; ``log_decrement`` = -2 pi Re lam / Im lam (negative:
    unstable); ``whirl``: forward / backward / mixed / planar for lateral modes, none for axial
    and torsional ones; ``kind``: lateral / axial / torsion / rigid.  ``orbit_*`` arrays are
    (n_modes, n_nodes) over the shaft nodes ``node_x`` for the shape scaled to a largest entry 1."""

    speed_rad_s: float
    eigenvalues: np.ndarray
    shapes: np.ndarray
    node_x: np.ndarray
    whirl: list
    whirl_ratio: np.ndarray
    kind: list
    orbit_major: np.ndarray
    orbit_minor: np.ndarray
    orbit_angle: np.ndarray
    orbit_forward: np.ndarray          # bool: node whirls forward
    residuals: np.ndarray
    rigid: np.ndarray
    tolerance: float
    method: str
    n_dofs: int
    warnings: list = field(default_factory=list)

    def to_dict(self) -> dict:
        return {"speed_rad_s": self.speed_rad_s, "n_dofs": self.n_dofs, "n_modes": self.n_modes,
                **self.frequency_fields(),
                "whirl": list(self.whirl), "whirl_ratio": self.whirl_ratio.tolist(), "kind": list(self.kind),
                "node_x": self.node_x.tolist(), "orbit_major": self.orbit_major.tolist(),
                "orbit_minor": self.orbit_minor.tolist(), "orbit_angle": self.orbit_angle.tolist(),
                **self.reliability_fields()}


def _kinds(rs: RotorSystem, shapes: np.ndarray, rigid: np.ndarray) -> list:
    """lateral / axial / torsion by where each shape is largest (the motions decouple), rigid first."""
    a = np.abs(shapes)
    none = np.zeros(0, dtype=int)
    iu, it = rs.node_dofs.get("u", none), rs.node_dofs.get("theta_x", none)
    lat = np.ones(a.shape[0], dtype=bool)          # every other DOF (shaft and pedestals) is lateral
    lat[iu] = lat[it] = False
    amp_lat = a[lat].max(axis=0, initial=0.0)
    amp_u = a[iu].max(axis=0, initial=0.0)
    amp_t = a[it].max(axis=0, initial=0.0)
    out = []
    for r in range(shapes.shape[1]):
        if rigid[r]:
            out.append("rigid")
        elif amp_lat[r] >= max(amp_u[r], amp_t[r]):
            out.append("lateral")
        else:
            out.append("axial" if amp_u[r] >= amp_t[r] else "torsion")
    return out


def describe_modes(rs: RotorSystem, res: ComplexModalResult) -> RotorModes:
    """Rotor view of a :class:`ComplexModalResult` of ``rs``'s system."""
    iv, iw = rs.node_dofs["v"], rs.node_dofs["w"]
    V, W = res.shapes[iv].T, res.shapes[iw].T                  # (n_modes, n_nodes)
    orb = Orbits.of(V, W)
    kind = _kinds(rs, res.shapes, res.rigid)
    lateral = [r for r, k in enumerate(kind) if k == "lateral"]
    whirl, ratio = ["none"] * len(kind), np.zeros(len(kind))
    if lateral:
        labels, overall = classify_many(Orbits(orb.forward[lateral], orb.backward[lateral], orb.angle[lateral]))
        for r, w, q in zip(lateral, labels, overall):
            whirl[r], ratio[r] = w, q
    return RotorModes(speed_rad_s=res.speed, eigenvalues=res.eigenvalues, shapes=res.shapes, node_x=rs.node_x,
                      whirl=whirl, whirl_ratio=ratio, kind=kind, orbit_major=orb.major,
                      orbit_minor=orb.minor, orbit_angle=orb.angle, orbit_forward=orb.forward > orb.backward,
                      residuals=res.residuals, rigid=res.rigid, tolerance=res.tolerance, method=res.method,
                      n_dofs=res.n_dofs, warnings=list(res.warnings))


class RotorEigen:
    """Repeated complex modal solves of one assembled rotor (orderings, band maps and, on
    constant bearings, the factorisation of K are reused from speed to speed)."""

    def __init__(self, rs: RotorSystem):
        self.rs = rs
        self.solver = QuadraticEigensolver(rs.system_at(_any_speed(rs)), patterns=[rs.pattern])

    def modes(self, speed: float, n_modes: int, tolerance: float = 1e-6) -> RotorModes:
        rs = self.rs
        K, C = rs.stiffness_and_damping(speed) if rs.speed_dependent else (None, None)
        res = self.solver.solve(n_modes, speed=speed, K=K, C=C, tolerance=tolerance)
        return describe_modes(rs, res)


def _any_speed(rs: RotorSystem) -> float:
    """A speed at which every bearing table is defined (for building the solver's template)."""
    if not rs.tables:
        return 0.0
    strict = [t for t in rs.tables if t.extrapolate == "refuse"] or rs.tables
    lo = max(t.grid[0] for t in strict)
    hi = min(t.grid[-1] for t in strict)
    if lo > hi:
        raise ModelError("[[rotor.bearing]]", "speeds", [(t.grid[0], t.grid[-1]) for t in rs.tables],
                         "bearing tables whose speed ranges overlap")
    return lo


def as_system(rotor) -> RotorSystem:
    if isinstance(rotor, RotorSystem):
        return rotor
    if isinstance(rotor, Rotor):
        return assemble_rotor(rotor)
    raise ModelError("rotor", "rotor", type(rotor).__name__, "a fem.rotor.Rotor or an assembled RotorSystem")


def check_speed(speed, where: str = "[analysis]", key: str = "speed", positive: bool = False) -> float:
    try:
        s = float(speed)
    except (TypeError, ValueError):
        raise ModelError(where, key, speed, "a speed in rad/s") from None
    if not np.isfinite(s) or s < 0 or (positive and s == 0):
        raise ModelError(where, key, speed, "a speed > 0 (rad/s)" if positive else "a speed >= 0 (rad/s)")
    return s


def eigen_workspace(rs: RotorSystem) -> RotorEigen:
    """The assembled rotor's reusable modal solver (block split, orderings, band maps, the
    factorisation of K on constant bearings, the modes of blocks that do not change with speed)."""
    if rs._workspace is None:
        rs._workspace = RotorEigen(rs)
    return rs._workspace


def rotor_modes(rotor, speed: float = 0.0, n_modes: int = 6, *, tolerance: float = 1e-6) -> RotorModes:
    """Complex modes of ``rotor`` (a :class:`Rotor` or an assembled :class:`RotorSystem`) at
    ``speed`` (rad/s, >= 0): the lowest ``n_modes`` by |lam| with whirl and orbits.  Repeated
    calls on one :class:`RotorSystem` reuse its solver workspace (:func:`eigen_workspace`)."""
    rs = as_system(rotor)
    speed = check_speed(speed)
    return eigen_workspace(rs).modes(speed, n_modes, tolerance)
