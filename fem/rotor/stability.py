"""Stability threshold speed: the lowest speed at which a mode's damping becomes negative.

Cross-coupled bearing or seal stiffness (k_yz = -k_zy > 0 growing with speed, as fluid films
and labyrinth seals do) feeds energy into forward whirl; the threshold is the lowest speed
where Re lam = 0 for some mode.  The speed range is scanned with the tracked modes of a
Campbell diagram; each sign change of a tracked mode's damping ratio zeta_j(Omega) is then
converged by Brent's method (each evaluation a modal solve with the mode picked by MAC), so
the grid only brackets the root.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from discrete.errors import ModelError

from .campbell import CampbellResult, campbell
from .modal import as_system, check_speed, eigen_workspace
from .whirl import mac


@dataclass
class StabilityResult:
    """``threshold_rad_s``: None if every mode stays stable up to ``speed_max``; ``unstable_from_start``:
    already unstable at the lowest scanned speed (then the threshold is at most that speed)."""

    threshold_rad_s: float | None
    frequency_rad_s: float | None
    whirl: str | None
    mode: int | None
    unstable_from_start: bool
    scan: CampbellResult
    evaluations: int = 0
    warnings: list = field(default_factory=list)

    def to_dict(self) -> dict:
        return {"threshold_rad_s": self.threshold_rad_s,
                "threshold_rpm": None if self.threshold_rad_s is None else self.threshold_rad_s * 30 / np.pi,
                "frequency_rad_s": self.frequency_rad_s, "whirl": self.whirl, "mode": self.mode,
                "unstable_from_start": self.unstable_from_start, "evaluations": self.evaluations,
                "scan": self.scan.to_dict(), "warnings": list(self.warnings)}


def stability_threshold(rotor, speed_max: float, n_modes: int = 6, *, speed_min: float | None = None,
                        n_grid: int = 41, xtol: float = 1e-10) -> StabilityResult:
    """Lowest speed in [speed_min, speed_max] (rad/s, > 0; ``speed_min`` default speed_max / n_grid)
    at which one of the ``n_modes`` lowest tracked modes loses stability."""
    rs = as_system(rotor)
    speed_max = check_speed(speed_max, key="speed_max", positive=True)
    lo = speed_max / n_grid if speed_min is None else check_speed(speed_min, key="speed_min", positive=True)
    if not lo < speed_max:
        raise ModelError("[analysis]", "speed_min", lo, f"a speed below speed_max = {speed_max:g} rad/s")
    s = np.linspace(lo, speed_max, int(n_grid))
    scan = campbell(rs, s, n_modes, critical=False)
    z = scan.damping_ratio
    stable = np.ones(z.shape[1], dtype=bool)
    for j, k in enumerate(scan.kind):
        if k == "rigid":
            stable[j] = False
    cols = np.flatnonzero(stable)
    if not cols.size:
        raise ModelError("[analysis]", "modes", n_modes, "more modes (all tracked modes are rigid-body modes)")
    if np.any(z[0, cols] < 0):
        j = cols[int(np.argmin(z[0, cols]))]
        return StabilityResult(threshold_rad_s=float(s[0]), frequency_rad_s=float(scan.omega_damped_rad_s[0, j]),
                               whirl=scan.whirl[0][j], mode=int(j), unstable_from_start=True, scan=scan,
                               warnings=[f"mode {j + 1} is already unstable at the lowest speed {s[0]:.6g} rad/s"])
    first = None
    for j in cols:
        neg = np.flatnonzero(z[:, j] < 0)
        if neg.size and (first is None or neg[0] < first[0]):
            first = (int(neg[0]), int(j))
    if first is None:
        return StabilityResult(threshold_rad_s=None, frequency_rad_s=None, whirl=None, mode=None,
                               unstable_from_start=False, scan=scan)
    # the earliest bracket of every column crossing in the same interval: take the lowest root
    i = first[0]
    eig = eigen_workspace(rs)
    n_cand = scan.n_modes + max(2, scan.n_modes // 2)
    shapes_prev = eig.modes(s[i - 1], n_cand)
    best = None
    count = 0
    for j in cols:
        if not z[i, j] < 0:
            continue
        # reference shape: the candidate at s[i-1] with the tracked frequency of column j
        ref_col = int(np.argmin(np.abs(shapes_prev.natural_frequency_rad_s - scan.natural_frequency_rad_s[i - 1, j])))
        ref = shapes_prev.shapes[:, ref_col]
        picked = {}

        def f(speed):
            m = eig.modes(speed, n_cand)
            M = mac(ref[:, None], m.shapes)[0]
            c = int(np.argmax(M))
            picked[speed] = (m, c)
            return m.damping_ratio[c]

        root = brentq(f, s[i - 1], s[i], xtol=xtol * s[i], rtol=4 * np.finfo(float).eps)
        if root not in picked:
            f(root)
        count += len(picked)
        m, c = picked[root]
        if best is None or root < best[0]:
            best = (root, float(m.omega_damped_rad_s[c]), m.whirl[c], int(j))
    return StabilityResult(threshold_rad_s=float(best[0]), frequency_rad_s=best[1], whirl=best[2], mode=best[3],
                           unstable_from_start=False, scan=scan, evaluations=count)
