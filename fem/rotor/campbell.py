"""Campbell diagram with mode tracking, and critical speeds as roots of omega_j(Omega) = k Omega.

Tracking: at each speed the solver returns a few more modes than tracked; they are matched to
the previous speed's tracked modes by the modal assurance criterion of their complex shapes
(an optimal assignment, :func:`scipy.optimize.linear_sum_assignment`, on 1 - MAC plus a small
frequency-distance term that only breaks ties between equal-MAC candidates, e.g. the planar
pairs of a repeated frequency at zero speed).  So a column of the result follows one mode
through crossings and veerings instead of sorting frequencies.

Crossings of order k (k = 1: synchronous, 2: twice per revolution, 0.5 ...): for each
tracked mode the sign changes of g(Omega) = omega_j(Omega) - k Omega on the grid bracket the
roots, which are then found by Brent's method, each evaluation a modal solve at that speed
with the mode picked by MAC against the bracket's shape.  The grid only brackets; the root is
converged to ``xtol`` (relative 1e-10 by default).  Modes that do not oscillate have no critical
speed: rigid-body modes, and at rest the modes with a real eigenvalue (omega_d = 0: bearing modes
that are overdamped at low speed), whose omega_d = 0 = k Omega there is the origin of the
diagram, not a resonance (orders are > 0).  Once such a mode oscillates, its crossings are roots
like any other (with their damping reported).

**Critical speeds are the forward crossings.**  Unbalance (and its harmonics) is a force that
turns with the shaft: forward.  On a rotor whose supports are rotationally symmetric (every
bearing and pedestal with K = [[a, b], [-b, a]], C alike: the isotropic rotor) forward and
backward whirl decouple exactly, so a backward-whirl mode crossing k Omega is not excited by
unbalance at all (Friswell et al. 2010, §6.3; Genta 2005, §4.7): ``critical_speeds`` are the
crossings of forward (and mixed) modes, ``backward_crossings`` the others, listed apart.  On
anisotropic supports a backward mode couples to the forward force and can respond (weakly):
``isotropic_supports`` says which case holds; the crossings stay listed apart either way.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq, linear_sum_assignment

from discrete.errors import ModelError
from discrete.linalg.blas import single_threaded_blas

from .modal import RotorEigen, RotorModes, as_system, check_speed, eigen_workspace
from .whirl import mac

#: weight of the relative frequency distance in the tracking cost (ties between equal-MAC candidates)
FREQ_WEIGHT = 0.05
#: below this MAC a tracking step is reported as uncertain
MAC_WARN = 0.8
#: relative frequency difference below which previous modes count as one repeated eigenvalue
REPEATED = 1e-7


@dataclass
class CriticalSpeed:
    """A root of omega_mode(Omega) = order * Omega."""

    speed_rad_s: float
    frequency_rad_s: float
    order: float
    mode: int                  # tracked column of the Campbell diagram (0-based)
    whirl: str
    kind: str
    damping_ratio: float
    log_decrement: float
    mac: float                 # MAC between the root's mode and the bracket's shape
    evaluations: int

    @property
    def speed_rpm(self) -> float:
        return self.speed_rad_s * 30.0 / np.pi

    def to_dict(self) -> dict:
        return {"speed_rad_s": self.speed_rad_s, "speed_rpm": self.speed_rpm,
                "frequency_rad_s": self.frequency_rad_s, "order": self.order, "mode": self.mode,
                "whirl": self.whirl, "kind": self.kind, "damping_ratio": self.damping_ratio,
                "log_decrement": None if not np.isfinite(self.log_decrement) else self.log_decrement,
                "mac": self.mac, "evaluations": self.evaluations}


@dataclass
class CampbellResult:
    """Tracked modes over ``speeds_rad_s``: arrays (n_speeds, n_modes), column j one mode."""

    speeds_rad_s: np.ndarray
    omega_damped_rad_s: np.ndarray
    natural_frequency_rad_s: np.ndarray
    log_decrement: np.ndarray
    damping_ratio: np.ndarray
    whirl: list                 # n_speeds lists of n_modes labels
    kind: list                  # per tracked mode
    mac_min: np.ndarray         # (n_speeds,) worst MAC of the tracking step into each speed
    residual_max: np.ndarray    # (n_speeds,)
    crossings: list = field(default_factory=list)     # every root of omega_j = k Omega, any whirl
    orders: tuple = (1.0,)
    warnings: list = field(default_factory=list)
    isotropic_supports: bool | None = None    # every support rotationally symmetric (None: not known)
    shapes: list = field(default_factory=list, repr=False)       # per speed: (n_dofs, n_modes) tracked complex
    #                                                              shapes (largest DOF 1), not in to_dict
    eigenvalues: np.ndarray | None = field(default=None, repr=False)   # (n_speeds, n_modes) their lambda

    @property
    def n_modes(self) -> int:
        return self.omega_damped_rad_s.shape[1]

    @property
    def critical_speeds(self) -> list:
        """The critical speeds: crossings of forward (or mixed) whirling modes (module notes)."""
        return [c for c in self.crossings if c.whirl != "backward"]

    @property
    def backward_crossings(self) -> list:
        """Crossings of backward-whirl modes: not excited by unbalance on isotropic supports."""
        return [c for c in self.crossings if c.whirl == "backward"]

    def to_dict(self) -> dict:
        ld = np.where(np.isfinite(self.log_decrement), self.log_decrement, np.nan)
        return {"speeds_rad_s": self.speeds_rad_s.tolist(), "speeds_rpm": (self.speeds_rad_s * 30 / np.pi).tolist(),
                "omega_rad_s": self.omega_damped_rad_s.T.tolist(),
                "natural_frequency_rad_s": self.natural_frequency_rad_s.T.tolist(),
                "log_decrement": [[None if np.isnan(v) else float(v) for v in col] for col in ld.T],
                "damping_ratio": self.damping_ratio.T.tolist(),
                "whirl": [list(col) for col in zip(*self.whirl)], "kind": list(self.kind),
                "mac_min": self.mac_min.tolist(), "residual_max": self.residual_max.tolist(),
                "orders": list(self.orders), "critical_speeds": [c.to_dict() for c in self.critical_speeds],
                "backward_crossings": [c.to_dict() for c in self.backward_crossings],
                "isotropic_supports": self.isotropic_supports, "warnings": list(self.warnings)}


def _speeds(speeds, where="[analysis]") -> np.ndarray:
    s = np.atleast_1d(np.asarray(speeds, dtype=float))
    if s.size < 2 or not np.all(np.isfinite(s)) or np.any(s < 0) or np.any(np.diff(s) <= 0):
        raise ModelError(where, "speeds", s.tolist(), "at least two increasing speeds >= 0 (rad/s)")
    return s


def _orders(orders) -> tuple:
    out = tuple(float(k) for k in np.atleast_1d(orders))
    for k in out:
        if not np.isfinite(k) or k <= 0:
            raise ModelError("[analysis]", "orders", list(out), "excitation orders > 0 (1 = synchronous)")
    return out


def _extra(n_modes: int) -> int:
    return max(2, n_modes // 2)


def _subspace_mac(prev_shapes, prev_freq, cand_shapes):
    """MAC of the candidates against each previous mode -- against the span of its group when
    several previous modes share one frequency (a repeated eigenvalue, e.g. an isotropic rotor at
    zero speed, whose vectors are any basis of the plane they span)."""
    M = mac(prev_shapes, cand_shapes)
    f = np.asarray(prev_freq)
    done = np.zeros(f.size, dtype=bool)
    for j in range(f.size):
        if done[j]:
            continue
        group = np.flatnonzero(np.abs(f - f[j]) <= REPEATED * max(abs(f[j]), 1e-300))
        done[group] = True
        if group.size > 1:
            Q, _ = np.linalg.qr(prev_shapes[:, group])
            proj = np.linalg.norm(Q.conj().T @ cand_shapes, axis=0) ** 2
            M[group] = proj / np.maximum(np.linalg.norm(cand_shapes, axis=0) ** 2, 1e-300)
    return M


def _assign(prev_shapes, prev_freq, cand: RotorModes, n_track):
    """Columns of ``cand`` matched to the previous tracked modes; returns (index, MAC) per tracked mode."""
    M = _subspace_mac(prev_shapes, prev_freq, cand.shapes)
    f = cand.natural_frequency_rad_s
    scale = np.maximum(np.abs(prev_freq)[:, None], 1e-12 * max(np.max(np.abs(f)), 1.0))
    cost = (1.0 - M) + FREQ_WEIGHT * np.minimum(np.abs(f[None, :] - prev_freq[:, None]) / scale, 1.0)
    rows, cols = linear_sum_assignment(cost)
    idx = np.empty(n_track, dtype=int)
    idx[rows] = cols
    return idx, M[np.arange(n_track), idx]


def isotropic_supports(rotor) -> bool:
    """Whether every bearing (at every table speed) and pedestal is rotationally symmetric:
    K = [[a, b], [-b, a]] and C alike, so forward and backward whirl decouple (module notes)."""
    from .model import Rotor

    r = rotor if isinstance(rotor, Rotor) else rotor.rotor
    for b in r.bearings:
        t = b.table()
        for a, d, o1, o2 in (("kyy", "kzz", "kyz", "kzy"), ("cyy", "czz", "cyz", "czy")):
            if not (np.array_equal(t[a], t[d]) and np.array_equal(t[o1], -t[o2])):
                return False
    return all(p.kyy == p.kzz and p.cyy == p.czz for p in r.pedestals)


def campbell(rotor, speeds, n_modes: int = 6, *, orders=(1.0,), critical: bool = True,
             tolerance: float = 1e-6, xtol: float = 1e-10, progress=None) -> CampbellResult:
    """Campbell diagram of ``rotor`` over ``speeds`` (rad/s, increasing, >= 0): ``n_modes``
    tracked modes, and (``critical``) the crossings omega_j = k Omega of the given ``orders``
    inside the range (``critical_speeds``: forward whirl; ``backward_crossings``).
    ``progress(done, total)`` is called after each speed's solve and each crossing refined."""
    rs = as_system(rotor)
    s = _speeds(speeds)
    orders = _orders(orders)
    eig = eigen_workspace(rs)
    n_cand = min(n_modes + _extra(n_modes), rs.n_dofs - rs.constrained.size)
    eig.solver.sweep(True)                  # warm starts from speed to speed (reproducible per diagram)
    try:
        # one BLAS thread: the tracking's products are tiny (n x 24); a second OpenBLAS thread only
        # adds its wake-up, which on a loaded 2-core machine cost 70-100 ms per MAC matrix (measured)
        with single_threaded_blas():
            result = _track(eig, s, n_modes, n_cand, tolerance, orders, critical, xtol, progress)
    finally:
        eig.solver.sweep(False)
    result.isotropic_supports = isotropic_supports(rs)
    return result


def _track(eig, s, n_modes, n_cand, tolerance, orders, critical, xtol, progress=None):
    ns = s.size
    wd = np.zeros((ns, n_modes))
    wn, ld, zeta = np.zeros_like(wd), np.zeros_like(wd), np.zeros_like(wd)
    whirl, mac_min, res_max = [], np.ones(ns), np.zeros(ns)
    shapes_track = []
    lam = np.zeros((ns, n_modes), dtype=complex)
    warnings = []
    prev = prev_f = None
    kinds = None
    for i, speed in enumerate(s):
        m = eig.modes(speed, n_cand, tolerance)
        if m.n_modes < n_modes:
            raise ModelError("[analysis]", "modes", n_modes, f"at most {m.n_modes} modes for this rotor")
        if prev is None:
            idx = np.arange(n_modes)
            kinds = [m.kind[j] for j in idx]
        else:
            idx, macs = _assign(prev, prev_f, m, n_modes)
            mac_min[i] = float(macs.min())
            if macs.min() < MAC_WARN:
                warnings.append(f"speed {speed:.6g} rad/s: tracking uncertain (MAC {macs.min():.2f} < {MAC_WARN}); "
                                "refine the speed grid")
        wd[i], wn[i] = m.omega_damped_rad_s[idx], m.natural_frequency_rad_s[idx]
        ld[i], zeta[i] = m.log_decrement[idx], m.damping_ratio[idx]
        whirl.append([m.whirl[j] for j in idx])
        res_max[i] = float(m.residuals.max())
        prev, prev_f = m.shapes[:, idx], m.natural_frequency_rad_s[idx]
        shapes_track.append(prev)
        if progress is not None:
            progress(i + 1, ns)
        lam[i] = m.eigenvalues[idx]
    result = CampbellResult(speeds_rad_s=s, omega_damped_rad_s=wd, natural_frequency_rad_s=wn, log_decrement=ld,
                            damping_ratio=zeta, whirl=whirl, kind=kinds, mac_min=mac_min, residual_max=res_max,
                            orders=orders, warnings=warnings, shapes=shapes_track, eigenvalues=lam)
    if critical:
        result.crossings = _critical_speeds(eig, result, shapes_track, n_cand, tolerance, xtol, progress)
    return result


def _critical_speeds(eig: RotorEigen, camp: CampbellResult, shapes, n_cand, tolerance, xtol, progress=None) -> list:
    s = camp.speeds_rad_s
    cache = {}

    def solve(speed):
        if speed not in cache:
            cache[speed] = eig.modes(speed, n_cand, tolerance)
        return cache[speed]

    out = []
    n_brackets, done = 0, 0
    for k in camp.orders:
        for j in range(camp.n_modes):
            if camp.kind[j] != "rigid":
                g = camp.omega_damped_rad_s[:, j] - k * s
                n_brackets += int(np.count_nonzero((g[:-1] == 0) | (g[:-1] * g[1:] < 0)))
    for k in camp.orders:
        for j in range(camp.n_modes):
            if camp.kind[j] == "rigid":
                continue
            g = camp.omega_damped_rad_s[:, j] - k * s
            for i in range(s.size - 1):
                if not (g[i] == 0 or g[i] * g[i + 1] < 0):
                    continue
                if g[i] == 0 and camp.omega_damped_rad_s[i, j] == 0.0:
                    # omega = k Omega = 0 at rest: a mode that does not oscillate there (a real
                    # eigenvalue: an overdamped bearing mode) meets the line at its origin, which is
                    # no resonance; a crossing after it, once the mode oscillates, is bracketed next
                    continue
                ref = shapes[i][:, j]
                picked = {}

                def f(speed):
                    m = solve(speed)
                    M = mac(ref[:, None], m.shapes)[0]
                    c = int(np.argmax(M))
                    picked[speed] = (m, c, float(M[c]))
                    return m.omega_damped_rad_s[c] - k * speed

                if g[i] == 0:
                    root = s[i]
                    f(root)
                else:
                    fa, fb = f(s[i]), f(s[i + 1])
                    if not fa * fb <= 0:        # the MAC pick at a bracket end is another mode than the tracked one
                        camp.warnings.append(
                            f"order {k:g}, mode {j + 1}: omega = k Omega between {s[i]:.6g} and {s[i + 1]:.6g} rad/s "
                            "on the tracked grid, but the shape-matched modes at the bracket ends do not change sign "
                            "(MAC {:.2f}, {:.2f}); root not refined: refine the speed grid".format(
                                picked[s[i]][2], picked[s[i + 1]][2]))
                        continue
                    root = brentq(f, s[i], s[i + 1], xtol=xtol * max(s[i + 1], 1e-300), rtol=4 * np.finfo(float).eps)
                    if root not in picked:
                        f(root)
                m, c, quality = picked[root]
                out.append(CriticalSpeed(speed_rad_s=float(root), frequency_rad_s=float(m.omega_damped_rad_s[c]),
                                         order=k, mode=j, whirl=m.whirl[c], kind=m.kind[c],
                                         damping_ratio=float(m.damping_ratio[c]),
                                         log_decrement=float(m.log_decrement[c]), mac=quality,
                                         evaluations=len(picked)))
                if quality < MAC_WARN:
                    camp.warnings.append(f"critical speed near {root:.6g} rad/s (mode {j + 1}, order {k:g}): the mode "
                                         f"at the root matches the tracked shape only with MAC {quality:.2f}")
                if progress is not None:
                    done += 1
                    progress(s.size + done, s.size + n_brackets)
    out.sort(key=lambda c: (c.order, c.speed_rad_s))
    return out


def critical_speeds(rotor, speed_max: float, n_modes: int = 6, *, orders=(1.0,), n_grid: int = 41,
                    tolerance: float = 1e-6, xtol: float = 1e-10) -> list:
    """Crossings of the given ``orders`` between 0 and ``speed_max`` (rad/s, > 0): every root of
    omega_j(Omega) = k Omega of the lowest ``n_modes`` tracked modes, bracketed on ``n_grid`` speeds,
    forward and backward whirl (:attr:`CriticalSpeed.whirl`; the critical speeds proper are the
    forward ones: :attr:`CampbellResult.critical_speeds`)."""
    speed_max = check_speed(speed_max, key="speed_max", positive=True)
    return campbell(rotor, np.linspace(0.0, speed_max, int(n_grid)), n_modes, orders=orders,
                    tolerance=tolerance, xtol=xtol).crossings
