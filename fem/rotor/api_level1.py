"""API Level I stability screening: log decrement of the first forward mode against an applied
aerodynamic cross-coupling, scaled from the anticipated cross-coupling Q_A of Wachel's formula.

**Source and edition.**  API Standard 617, 7th edition (2002), §2.6.5, reproduced with commentary
in API RP 684, 2nd edition (2005), SP6.8.5 (the "Level I" stability analysis).

**Anticipated cross-coupling** (Wachel's formula, SP6.8.5.6).  Each stage i of rated power P_i
(W) at the maximum continuous speed Omega (rad/s) carries the torque T_i = P_i / Omega and

    centrifugal stage:  q_i = B_c T_i / (D_c H_c) (rho_d / rho_s)_i,   B_c = 3,
    axial-flow stage:   q_i = B_t T_i / (D_t H_t),                     B_t = 1.5,

in N/m with the impeller diameter D_c and the smaller of the impeller discharge and diffuser
widths H_c (axial: blade pitch diameter D_t and effective blade height H_t) in metres, and the
stage's discharge-to-suction gas density ratio.  API writes it with P in kW, N in rev/min, D and
H in mm and the constant C = 9.55 (US units: 63) -- 9.55 is 60 / (2 pi) rounded: T = 9.55 P / N.
Here T = P / Omega exactly (the rounding moves Q_A by 7e-5 relative).  Q_A = sum q_i.

**The analysis** (SP6.8.5.7-9).  A cross-coupled stiffness k_yz = +Q, k_zy = -Q (the force
Q (-w, v) pushes a forward orbit along its path: destabilising) is applied at the rotor's
mid-span for a between-bearing rotor (``placement = "mid-span"``: the shaft node nearest the
middle of the outermost bearings), or at the stages with their shares q_i / Q_A for an overhung
rotor (``"stages"``; ``"auto"``: mid-span when every stage lies between the outermost bearings).
Q runs from 0 to 10 Q_A (``points`` values); at each, the complex modes at the maximum continuous
speed give the log decrement of the first forward mode (the lowest-frequency lateral mode that
does not whirl backward).  Q_0, where that log decrement crosses zero, is found by Brent's method
(the grid brackets; beyond 10 Q_A the range is doubled until it crosses, up to 1000 Q_A).

**Criteria implemented** (SP6.8.5.10, Level I screening): a Level II analysis is required when
(a) Q_0 / Q_A < 2, or (b) the log decrement at Q_A, delta_A, is below 0.1.  The third screen
(2 <= Q_0 / Q_A < 10 with the critical speed ratio in region B of the CSR-density chart) is not
implemented: its chart is not reproduced here (the result states it).  The model is the file's
rotor with the bearings named in ``exclude`` removed (API's Level I excludes the seals, whose
destabilising effect Q_A stands for).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from discrete.errors import ModelError

from .assembly import assemble_rotor
from .model import Bearing, Rotor

MACHINES = {"centrifugal": 3.0, "axial": 1.5}          # B_c, B_t
PLACEMENTS = ("auto", "mid-span", "stages")
LOG_DEC_MIN = 0.1                                       # criterion (b)
RATIO_MIN = 2.0                                         # criterion (a)
SCALE = 10.0                                            # Q from 0 to SCALE * Q_A
EDITION = "API 617 7th ed. (2002) 2.6.5 / API RP 684 2nd ed. (2005) SP6.8.5"


@dataclass
class Stage:
    """An impeller (or axial stage) at ``x`` (m): rated ``power`` (W), ``diameter`` D (m), ``width`` H
    (m: the smaller of impeller discharge and diffuser width; axial: effective blade height),
    ``density_ratio`` rho_discharge / rho_suction (centrifugal only), ``name``."""

    x: float
    power: float
    diameter: float
    width: float
    density_ratio: float = 1.0
    name: str = ""

    def check(self, where: str) -> None:
        for key in ("power", "diameter", "width", "density_ratio"):
            v = getattr(self, key)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v) or v <= 0:
                raise ModelError(where, key, v, "a number > 0" + (" (W)" if key == "power" else
                                                                  " (m)" if key in ("diameter", "width") else ""))


def anticipated_cross_coupling(stages, speed: float, machine: str = "centrifugal") -> np.ndarray:
    """q_i (N/m) of each :class:`Stage` at ``speed`` (rad/s > 0) by Wachel's formula (module notes)."""
    if machine not in MACHINES:
        raise ModelError("[stability.api_level1]", "machine", machine, " | ".join(map(repr, MACHINES)))
    if not np.isfinite(speed) or speed <= 0:
        raise ModelError("[stability.api_level1]", "speed", speed, "the maximum continuous speed > 0")
    B = MACHINES[machine]
    q = []
    for i, st in enumerate(stages, 1):
        st.check(f"[[stability.api_level1.stage]] #{i}")
        torque = st.power / speed
        q.append(B * torque / (st.diameter * st.width) * (st.density_ratio if machine == "centrifugal" else 1.0))
    return np.asarray(q, dtype=float)


@dataclass
class LevelIResult:
    """The Level I screening (module notes): ``cross_coupling`` Q (N/m) with the first forward
    mode's ``log_decrement`` and ``frequency_rad_s`` at each; Q_A, delta_A, Q_0 (None: no zero
    crossing up to 1000 Q_A), the criteria and the verdict."""

    speed_rad_s: float
    machine: str
    placement: str
    stations: list                 # [(x, share of Q)]
    stage_q: np.ndarray            # q_i, N/m
    q_a: float
    cross_coupling: np.ndarray
    log_decrement: np.ndarray
    frequency_rad_s: np.ndarray
    log_decrement_a: float
    q0: float | None
    excluded: list = field(default_factory=list)
    warnings: list = field(default_factory=list)

    @property
    def ratio(self) -> float | None:
        return None if self.q0 is None else self.q0 / self.q_a

    @property
    def criteria(self) -> list[dict]:
        r = self.ratio
        return [{"name": "Q0/QA >= 2", "value": r, "limit": RATIO_MIN,
                 "passed": r is None or r >= RATIO_MIN},
                {"name": "log decrement at QA >= 0.1", "value": self.log_decrement_a, "limit": LOG_DEC_MIN,
                 "passed": bool(self.log_decrement_a >= LOG_DEC_MIN)}]

    @property
    def passed(self) -> bool:
        """True: the rotor passes Level I; False: a Level II analysis is required."""
        return all(c["passed"] for c in self.criteria)

    def to_dict(self) -> dict:
        return {"standard": EDITION, "speed_rad_s": self.speed_rad_s, "speed_rpm": self.speed_rad_s * 30 / np.pi,
                "machine": self.machine, "placement": self.placement,
                "stations": [{"x": x, "share": s} for x, s in self.stations],
                "stage_cross_coupling_n_per_m": self.stage_q.tolist(), "qa_n_per_m": self.q_a,
                "cross_coupling_n_per_m": self.cross_coupling.tolist(), "log_decrement": self.log_decrement.tolist(),
                "frequency_rad_s": self.frequency_rad_s.tolist(), "log_decrement_at_qa": self.log_decrement_a,
                "q0_n_per_m": self.q0, "q0_over_qa": self.ratio, "criteria": self.criteria,
                "level_ii_required": not self.passed, "excluded_bearings": list(self.excluded),
                "not_implemented": "the CSR-density screen (2 <= Q0/QA < 10, region B) of SP6.8.5.10",
                "warnings": list(self.warnings)}


def _stations(rotor: Rotor, stages, q, placement: str) -> tuple[str, list]:
    if not rotor.bearings:
        raise ModelError("[[rotor.bearing]]", "bearings", 0, "bearings (the Level I analysis places Q between them)")
    bx = sorted(b.x for b in rotor.bearings)
    lo, hi = bx[0], bx[-1]
    if placement not in PLACEMENTS:
        raise ModelError("[stability.api_level1]", "placement", placement, " | ".join(map(repr, PLACEMENTS)))
    if placement == "auto":
        placement = "mid-span" if all(lo <= s.x <= hi for s in stages) else "stages"
    if placement == "stages":
        total = float(q.sum())
        return placement, [(float(s.x), float(qi / total)) for s, qi in zip(stages, q)]
    return placement, [(0.5 * (lo + hi), 1.0)]


def _first_forward(modes):
    """(log decrement, frequency) of the lowest-frequency lateral mode not whirling backward."""
    cand = [r for r in range(modes.n_modes) if modes.kind[r] == "lateral" and not modes.rigid[r]
            and modes.omega_damped_rad_s[r] > 0 and modes.whirl[r] != "backward"]
    if not cand:
        return np.nan, np.nan
    r = min(cand, key=lambda i: modes.omega_damped_rad_s[i])
    return float(modes.log_decrement[r]), float(modes.omega_damped_rad_s[r])


def api_level1(rotor: Rotor, stages, speed: float, *, machine: str = "centrifugal", placement: str = "auto",
               exclude=(), points: int = 21, n_modes: int = 6, xtol: float = 1e-12) -> LevelIResult:
    """The Level I screening of ``rotor`` (a :class:`Rotor`) at the maximum continuous ``speed``
    (rad/s) with the :class:`Stage` list ``stages`` (module notes); ``exclude``: names of bearings
    (seals) left out of the model."""
    from .modal import rotor_modes

    if not isinstance(rotor, Rotor):
        rotor = rotor.rotor
    if not stages:
        raise ModelError("[stability.api_level1]", "stage", [], "at least one [[stability.api_level1.stage]]")
    names = {b.name for b in rotor.bearings}
    for n in exclude:
        if n not in names:
            raise ModelError("[stability.api_level1]", "exclude", n, "names of [[rotor.bearing]]s: "
                             + ", ".join(repr(x) for x in sorted(names) if x))
    base = [b for b in rotor.bearings if b.name not in set(exclude)]
    if not base:
        raise ModelError("[stability.api_level1]", "exclude", list(exclude), "some bearing left to hold the rotor")
    if isinstance(points, bool) or not isinstance(points, int) or points < 3:
        raise ModelError("[stability.api_level1]", "points", points, "an integer >= 3")
    q = anticipated_cross_coupling(stages, speed, machine)
    q_a = float(q.sum())
    placement, stations = _stations(rotor, stages, q, placement)
    node_x = assemble_rotor(rotor).node_x                  # mid-span: the nearest shaft node
    stations = [(float(node_x[np.argmin(np.abs(node_x - x))]), share) for x, share in stations]
    warnings = []

    def modes_at(Q):
        extra = [Bearing(x, kyz=Q * share, kzy=-Q * share, name=f"Level I cross-coupling at x = {x:g} m")
                 for x, share in stations] if Q != 0 else []
        rs = assemble_rotor(dataclasses.replace(rotor, bearings=base + extra))
        return rotor_modes(rs, speed, n_modes)

    def logdec(Q):
        return _first_forward(modes_at(Q))

    Qs = np.linspace(0.0, SCALE * q_a, points)
    vals = [logdec(Q) for Q in Qs]
    ld = np.array([v[0] for v in vals])
    wf = np.array([v[1] for v in vals])
    if not np.all(np.isfinite(ld)):
        raise ModelError("[stability]", "modes", n_modes, "more modes: no forward lateral mode among them at some Q")
    ld_a = logdec(q_a)[0]
    q0 = None
    sign = np.flatnonzero(np.diff(np.sign(ld)) != 0)
    if ld[0] <= 0:
        q0 = 0.0
        warnings.append("the first forward mode is not stable without cross-coupling (log decrement "
                        f"{ld[0]:.4g} at Q = 0)")
    elif sign.size:
        i = int(sign[0])
        q0 = float(brentq(lambda Q: logdec(Q)[0], Qs[i], Qs[i + 1], xtol=xtol * q_a))
    else:
        lo, hi = Qs[-1], 2 * Qs[-1]
        while hi <= 1000 * q_a:
            if logdec(hi)[0] <= 0:
                q0 = float(brentq(lambda Q: logdec(Q)[0], lo, hi, xtol=xtol * q_a))
                break
            lo, hi = hi, 2 * hi
        if q0 is None:
            warnings.append("the log decrement stays positive up to 1000 QA: Q0 > 1000 QA")
    return LevelIResult(speed_rad_s=float(speed), machine=machine, placement=placement, stations=stations, stage_q=q,
                        q_a=q_a, cross_coupling=Qs, log_decrement=ld, frequency_rad_s=wf, log_decrement_a=float(ld_a),
                        q0=q0, excluded=list(exclude), warnings=warnings)
