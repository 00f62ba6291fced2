"""Design inequalities of vibration isolation (textbook §6.4).

Model 1 (Fig. 6.7a): machine m on an isolator c, force F_0 cos(omega t).  Undamped, post-resonant
(z = omega/k > sqrt 2), amplitude (6.16) A = (F_0/c)/|1 - z^2|, isolation factor (6.17) xi = cA/F_0 = 1/|1 - z^2|:

    (6.18)  xi < xi*           <=>  c < m omega^2 / (1 + 1/xi*)          (line 1)
    (6.19)  A < A*             <=>  c < m omega^2 - F_0/A*               (line 2)
    (6.20)  settlement m g/c < Delta*  <=>  c > m g / Delta*              (line 3)
    m* < m < m**                                                          (lines 4, 4')

The lightest feasible machine is the optimum point N of Fig. 6.8a.  Lines 1 and 3 both pass through the
origin, so when line 3 lies above line 1 no mass is feasible (the book's incompatible case).

Model 2 (Fig. 6.7b): frame m_0 on c carrying links of total mass M whose centre of mass moves by
y_s = y* cos(omega t) relative to the frame; (6.22) (m_0 + M) y_0'' + c y_0 = -M y_s'':

    (6.24)  A = y* omega^2 M / |(m_0 + M) omega^2 - c|,   (6.23) xi_1 = cA/(y* omega^2 M)
    (6.25)  xi_1 < xi_1*  <=>  c < xi_1*/(1 + xi_1*) (m_0 + M) omega^2   (the book prints "xi_1 < xi_1")
    (6.27)  A/y* < xi_2*  <=>  c < omega^2 [m_0 - M (1/xi_2* - 1)]
    (6.28)  c > g (m_0 + M)/Delta*

:func:`damped_stiffness_limit` is the exact line 1 with viscous damping (the book neglects damping
post-resonance): T(z, delta) = xi* solved for z^2 (a quadratic).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..errors import ModelError

WHERE = "isolation"


def _pos(v, key):
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v > 0):
        raise ModelError(WHERE, key, v, "a finite number > 0")
    return float(v)


def _opt(v, key):
    return None if v is None else _pos(v, key)


@dataclass
class IsolationDesign:
    """Stiffness bounds of model 1 for the mass m (and the optimum mass over the allowed range)."""

    omega: float
    c_min: float                       # from (6.20) (0 if no settlement limit)
    c_max: float                       # min of (6.18), (6.19) (inf if neither given)
    lines: dict                        # slope/offset of each line: c = slope m + offset
    m_opt: float | None                # lightest feasible mass in the range (point N), None if infeasible
    feasible: bool                     # c_min < c_max at the given m
    reasons: list[str] = field(default_factory=list)

    def to_dict(self) -> dict:
        return {"omega": self.omega, "c_min": self.c_min, "c_max": self.c_max, "lines": self.lines,
                "m_opt": self.m_opt, "feasible": self.feasible, "reasons": list(self.reasons)}


def isolation_design(m: float, omega: float, *, xi_allowed: float | None = None, force_amplitude: float | None = None,
                     amplitude_allowed: float | None = None, settlement_allowed: float | None = None,
                     mass_range: tuple[float, float] | None = None, g: float = 9.81) -> IsolationDesign:
    """Bounds (6.18)-(6.20) on c for machine mass m at the forcing frequency omega [rad/s]."""
    m, omega, g = _pos(m, "m"), _pos(omega, "omega"), _pos(g, "g")
    xi = _opt(xi_allowed, "xi_allowed")
    if xi is not None and not xi < 1:
        raise ModelError(WHERE, "xi_allowed", xi, "an isolation factor < 1 (isolation means xi < 1)")
    A = _opt(amplitude_allowed, "amplitude_allowed")
    F0 = _opt(force_amplitude, "force_amplitude")
    if A is not None and F0 is None:
        raise ModelError(WHERE, "force_amplitude", None, "the force amplitude F_0 (needed with amplitude_allowed)")
    D = _opt(settlement_allowed, "settlement_allowed")
    lines = {}
    w2 = omega**2
    if xi is not None:
        lines["6.18"] = {"slope": w2 / (1 + 1 / xi), "offset": 0.0, "kind": "upper"}
    if A is not None:
        lines["6.19"] = {"slope": w2, "offset": -F0 / A, "kind": "upper"}
    if D is not None:
        lines["6.20"] = {"slope": g / D, "offset": 0.0, "kind": "lower"}
    upper = [l for l in lines.values() if l["kind"] == "upper"]
    lower = [l for l in lines.values() if l["kind"] == "lower"]
    cmax = min((l["slope"] * m + l["offset"] for l in upper), default=math.inf)
    cmin = max((l["slope"] * m + l["offset"] for l in lower), default=0.0)
    reasons = []
    if cmax <= 0:
        reasons.append("no positive stiffness satisfies the upper bounds at this mass")
    if not cmin < cmax:
        reasons.append(f"c > {cmin:.6g} (settlement) and c < {cmax:.6g} (isolation/amplitude) are incompatible")
    # lightest feasible mass: every upper line above every lower line
    lo, hi = (0.0, math.inf) if mass_range is None else (_pos(mass_range[0], "m_min"), _pos(mass_range[1], "m_max"))
    m_need = lo
    ok = True
    for u in upper:
        for l in lower + [{"slope": 0.0, "offset": 0.0}]:
            ds, do = u["slope"] - l["slope"], u["offset"] - l["offset"]
            # ds m + do > 0
            if ds > 0:
                m_need = max(m_need, -do / ds)
            elif do <= 0:
                ok = False
    m_opt = m_need if ok and m_need <= hi else None
    return IsolationDesign(omega=omega, c_min=cmin, c_max=cmax, lines=lines, m_opt=m_opt,
                           feasible=bool(cmin < cmax and cmax > 0), reasons=reasons)


def damped_stiffness_limit(m: float, omega: float, xi_allowed: float, delta: float) -> float:
    """Largest c with viscous force transmissibility T(z, delta) <= xi* at omega (z^2 = m omega^2/c).

    T^2 = xi^2 gives xi^2 u^2 - (2 xi^2 + 4 delta^2 (1 - xi^2)) u + xi^2 - 1 = 0 for u = z^2; the
    post-resonant root is taken.  delta = 0 reproduces (6.18)."""
    m, omega, xi = _pos(m, "m"), _pos(omega, "omega"), _pos(xi_allowed, "xi_allowed")
    if not xi < 1:
        raise ModelError(WHERE, "xi_allowed", xi, "an isolation factor < 1")
    if isinstance(delta, bool) or not isinstance(delta, (int, float)) or not (math.isfinite(delta) and delta >= 0):
        raise ModelError(WHERE, "delta", delta, "a damping ratio >= 0")
    b = 2 * xi**2 + 4 * delta**2 * (1 - xi**2)
    u = (b + math.sqrt(b * b - 4 * xi**2 * (xi**2 - 1))) / (2 * xi**2)
    return m * omega**2 / u


@dataclass
class MovingMassIsolation:
    """Model 2 of §6.4: response and isolation factors (6.23)-(6.24)."""

    m0: float
    M: float
    c: float
    omega: float

    def __post_init__(self):
        for k in ("m0", "M", "c", "omega"):
            setattr(self, k, _pos(getattr(self, k), k))

    @property
    def amplitude_ratio(self) -> float:
        """A/y* = omega^2 M/|(m_0 + M) omega^2 - c| (6.24)."""
        return self.omega**2 * self.M / abs((self.m0 + self.M) * self.omega**2 - self.c)

    @property
    def xi1(self) -> float:
        """xi_1 = R_max/R_0max = c A/(y* omega^2 M) (6.23)."""
        return self.c * self.amplitude_ratio / (self.omega**2 * self.M)

    @property
    def k(self) -> float:
        return math.sqrt(self.c / (self.m0 + self.M))

    def bounds(self, *, xi1_allowed: float | None = None, xi2_allowed: float | None = None,
               settlement_allowed: float | None = None, g: float = 9.81) -> dict:
        """Upper/lower stiffness bounds (6.25), (6.27), (6.28) for this m_0, M, omega."""
        w2, out = self.omega**2, {}
        if xi1_allowed is not None:
            x = _pos(xi1_allowed, "xi1_allowed")
            out["6.25"] = x / (1 + x) * (self.m0 + self.M) * w2
        if xi2_allowed is not None:
            x = _pos(xi2_allowed, "xi2_allowed")
            out["6.27"] = w2 * (self.m0 - self.M * (1 / x - 1))
        if settlement_allowed is not None:
            out["6.28"] = _pos(g, "g") * (self.m0 + self.M) / _pos(settlement_allowed, "settlement_allowed")
        return out

    def to_dict(self) -> dict:
        return {"m0": self.m0, "M": self.M, "c": self.c, "omega": self.omega, "A_over_y": self.amplitude_ratio,
                "xi1": self.xi1, "k": self.k}
