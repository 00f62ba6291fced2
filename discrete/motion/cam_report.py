"""Cam report: how a programme-motion law excites an elastic follower (textbook §6.2, §5.9).

* :func:`discontinuity_table` -- Table 6.1: for every jump of Pi, Pi', Pi'' or Pi''' of a cam law, the
  "jump" D of the accompanying vibration, the extra acceleration |Delta q''|max = k^2 D and the phase
  alpha (alpha_1 for a positive jump, alpha_2 otherwise).  (The book's column header prints |Delta q'|max;
  it means |Delta q''|max.)
* :func:`residual_factor` -- (6.8): the equivalent jump of an acceleration ramp of duration Delta t = nu T,
  ae0(nu) = |sin pi nu|/(pi nu), T = 2 pi/k.  Zeros at integer nu = j (the book prints "nu = j pi": a
  misprint).  With damping the book's unsimplified expression (before exp(-n Delta t) ~ 1) is returned:
  sqrt(1 - 2 e^{-2 pi delta nu} cos 2 pi nu + e^{-4 pi delta nu})/(2 pi nu).
* :func:`accumulation_factor` (5.53), :func:`mu_plus`, :func:`mu_minus` (6.11), :func:`accumulated_acceleration`
  (6.10), :func:`admissible_frequency_ratio` (6.12)-(6.13) with the inequality as it must read
  (mu < [mu]  <=>  1 - 2 e^{-lambda N} cos 2 pi N + e^{-2 lambda N} > [mu]^-2; for [mu] = 1:
  cos 2 pi N < 0.5 e^{-lambda N}; the book prints both with the inequality reversed), and
  :func:`min_frequency_ratio` (6.14).
* :func:`cam_report` -- all of it for one law, speed and follower, plus the exact periodic response.

Conventions: lambda is the logarithmic decrement (lambda = 2 pi n / k, (4.15)), N = k/omega0 the
number of free periods per cam revolution.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import ModelError
from .follower import PiecewiseOscillator, SteadyState
from .piecewise import PiecewiseLaw

# Table 6.1: derivative order m -> (alpha_1, alpha_2); D = omega0^m |Delta Pi^(m)| / k^m, |Delta q''| = k^2 D
TABLE_6_1_PHASES = {0: (1.5 * math.pi, 0.5 * math.pi), 1: (math.pi, 0.0), 2: (0.5 * math.pi, 1.5 * math.pi),
                    3: (0.0, math.pi)}
KINDS = {0: "position (Delta Pi)", 1: "hard impact (Delta Pi')", 2: "soft impact (Delta Pi'')", 3: "jerk (Delta Pi''')"}


def _positive(value, key: str, where: str = "cam report") -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)) or not (math.isfinite(value) and value > 0):
        raise ModelError(where, key, value, "a finite number > 0")
    return float(value)


def _nonneg(value, key: str, where: str = "cam report") -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)) or not (math.isfinite(value) and value >= 0):
        raise ModelError(where, key, value, "a finite number >= 0")
    return float(value)


# ------------------------------------------------------------------ Table 6.1
@dataclass
class DiscontinuityRow:
    phase: float          # cam angle of the knot [rad]
    order: int            # 0: Pi, 1: Pi', 2: Pi'', 3: Pi'''
    jump: float           # Delta Pi^(m)
    D: float              # amplitude of the excited vibration (Table 6.1)
    extra_acceleration: float   # |Delta q''|max = k^2 D (6.6)
    alpha: float          # alpha_1 if jump > 0 else alpha_2
    alpha1: float
    alpha2: float

    @property
    def kind(self) -> str:
        return KINDS[self.order]

    def to_dict(self) -> dict:
        return {"phase": self.phase, "order": self.order, "kind": self.kind, "jump": self.jump, "D": self.D,
                "extra_acceleration": self.extra_acceleration, "alpha": self.alpha, "alpha1": self.alpha1,
                "alpha2": self.alpha2}


def discontinuity_table(law: PiecewiseLaw, omega0: float, k: float, rtol: float = 1e-9) -> list[DiscontinuityRow]:
    """Table 6.1 for every jump of Pi^(m), m = 0..3, of the cam law Pi(phi) (phase law) at cam speed
    omega0 [rad/s] and follower frequency k [rad/s].  A jump counts if it exceeds rtol max|Pi^(m)|."""
    omega0, k = _positive(omega0, "omega0"), _positive(k, "k")
    rows = []
    for m in range(4):
        t, d = law.jumps(m)
        tol = rtol * max(law.scale_of(m), 1e-300)
        for phi, dj in zip(t, d):
            if abs(dj) <= tol:
                continue
            D = float(omega0**m * abs(dj) / k**m)
            a1, a2 = TABLE_6_1_PHASES[m]
            rows.append(DiscontinuityRow(phase=float(phi), order=m, jump=float(dj), D=D, extra_acceleration=float(k**2 * D),
                                         alpha=a1 if dj > 0 else a2, alpha1=a1, alpha2=a2))
    rows.sort(key=lambda r: (r.phase, r.order))
    return rows


# ------------------------------------------------------- (6.8) ramp factor
def residual_factor(nu, delta: float = 0.0):
    """Equivalent jump of an acceleration ramp over Delta t = nu T relative to a step (6.8):
    |sin pi nu|/(pi nu) for delta = 0 (1 at nu = 0); with damping the book's expression before its
    simplification exp(-n Delta t) ~ 1."""
    delta = _nonneg(delta, "delta")
    nu = np.asarray(nu, dtype=float)
    if np.any(nu < 0) or not np.all(np.isfinite(nu)):
        raise ModelError("cam report", "nu", nu.tolist(), "ratios Delta t / T >= 0")
    x = 2 * math.pi * np.where(nu == 0, 1.0, nu)
    if delta == 0:
        val = np.abs(np.sin(0.5 * x)) / (0.5 * x)
    else:
        e = np.exp(-delta * x)
        val = np.sqrt(np.maximum(1 - 2 * e * np.cos(x) + e * e, 0.0)) / x
    return np.where(nu == 0, 1.0, val)


# ---------------------------------------------- accumulation (5.53), (6.10)-(6.14)
def _lam_N(lam, N):
    lam = np.asarray(lam, dtype=float)
    N = np.asarray(N, dtype=float)
    if np.any(lam < 0) or not np.all(np.isfinite(lam)):
        raise ModelError("cam report", "lambda", lam.tolist(), "a logarithmic decrement >= 0")
    if np.any(N <= 0) or not np.all(np.isfinite(N)):
        raise ModelError("cam report", "N", N.tolist(), "a frequency ratio k/omega0 > 0")
    return lam, N


def accumulation_factor(lam, N):
    """mu = 1/sqrt(1 - 2 e^{-lambda N} cos 2 pi N + e^{-2 lambda N}) (5.53)."""
    lam, N = _lam_N(lam, N)
    e = np.exp(-lam * N)
    den = 1 - 2 * e * np.cos(2 * math.pi * N) + e * e
    with np.errstate(divide="ignore"):
        return 1.0 / np.sqrt(np.maximum(den, 0.0))


def mu_plus(lam, N):
    """mu+ = 1/(1 - e^{-lambda N}) (6.11): in phase, near integer N."""
    lam, N = _lam_N(lam, N)
    with np.errstate(divide="ignore"):
        return 1.0 / (1.0 - np.exp(-lam * N))


def mu_minus(lam, N):
    """mu- = 1/(1 + e^{-lambda N}) (6.11): anti-phase, 2N odd."""
    lam, N = _lam_N(lam, N)
    return 1.0 / (1.0 + np.exp(-lam * N))


def accumulated_acceleration(D: float, k: float, lam: float, N: float) -> float:
    """Sum over cycles of the extra accelerations of one repeated jump, k^2 mu D (6.10)."""
    return float(_positive(k, "k") ** 2 * accumulation_factor(lam, N) * _nonneg(D, "D"))


def admissible_frequency_ratio(lam, N, mu_allowed: float = 1.0):
    """True where mu(lambda, N) < [mu]: (6.12) as it must read,
    1 - 2 e^{-lambda N} cos 2 pi N + e^{-2 lambda N} > [mu]^-2 ((6.13) for [mu] = 1)."""
    lam, N = _lam_N(lam, N)
    mu_allowed = _positive(mu_allowed, "mu_allowed")
    e = np.exp(-lam * N)
    return 1 - 2 * e * np.cos(2 * math.pi * N) + e * e > mu_allowed**-2


def min_frequency_ratio(lam: float, dmu: float) -> float:
    """(6.14): mu+ < 1 + [Delta mu]  <=>  N > ln((1 + [Delta mu])/[Delta mu]) / lambda."""
    return math.log((1 + _positive(dmu, "dmu")) / dmu) / _positive(lam, "lambda")


def band_threshold(lower: float = 0.96, upper: float = 1.04) -> dict:
    """lambda N above which mu- > lower and mu+ < upper (the book's "lambda N > 3 gives 0.96 < mu < 1.04"):
    mu- > lower  <=>  lambda N > ln(lower/(1 - lower));  mu+ < upper  <=>  lambda N > ln(upper/(upper - 1))."""
    if not 0.5 < lower < 1 < upper:
        raise ModelError("cam report", "band", [lower, upper], "0.5 < lower < 1 < upper")
    lo = math.log(lower / (1 - lower))
    hi = math.log(upper / (upper - 1))
    return {"lower": lo, "upper": hi, "both": max(lo, hi)}


# ------------------------------------------------------------------ report
@dataclass
class CamReport:
    law_name: str
    omega0: float
    k: float
    lam: float
    N: float
    mu: float
    mu_plus: float
    mu_minus: float
    continuity: int                       # highest continuous derivative of Pi
    peaks: dict                           # max |Pi'|, |Pi''|, |Pi'''|, |Pi' Pi''|
    table: list[DiscontinuityRow]
    knots_D: np.ndarray                   # exact (6.4) jump per knot with the particular solution
    knots_phase: np.ndarray
    steady: SteadyState | None = None
    warnings: list[str] = field(default_factory=list)

    def to_dict(self) -> dict:
        return {"law": self.law_name, "omega0_rad_s": self.omega0, "k_rad_s": self.k, "lambda": self.lam, "N": self.N,
                "mu": self.mu, "mu_plus": self.mu_plus, "mu_minus": self.mu_minus, "continuity": self.continuity,
                "peaks": self.peaks, "table": [r.to_dict() for r in self.table],
                "knots": {"phase": self.knots_phase.tolist(), "D": self.knots_D.tolist()},
                "steady_state": None if self.steady is None else {
                    k: v for k, v in self.steady.to_dict().items() if not isinstance(v, list)},
                "warnings": list(self.warnings)}


def cam_report(law: PiecewiseLaw, omega0: float, k: float, lam: float = 0.0, *, steady: bool = True) -> CamReport:
    """Table 6.1, the accumulation factors and the exact periodic follower response for the cam law
    Pi(phi) (a periodic phase law, cycle 2 pi) turning at omega0, follower frequency k, log decrement lam."""
    omega0, k, lam = _positive(omega0, "omega0"), _positive(k, "k"), _nonneg(lam, "lambda")
    if not law.periodic:
        raise ModelError("cam report", "law", law.name or "law", "a periodic cam law (one revolution)")
    if abs(law.span - 2 * math.pi) > 1e-9:
        raise ModelError("cam report", "law", f"cycle {law.span:.9g}", "a cam law over one revolution (2 pi)")
    N = k / omega0
    peaks = {"Pi'": abs(law.peak(1)[1]), "Pi''": abs(law.peak(2)[1]), "Pi'''": abs(law.peak(3)[1])}
    phi = np.linspace(0, 2 * math.pi, 20001)      # |Pi' Pi''|max (2.16) by dense sampling
    peaks["Pi' Pi''"] = float(np.max(np.abs(law(phi, 1) * law(phi, 2))))
    n = lam * k / (2 * math.pi)
    warn = []
    if n >= k:
        raise ModelError("cam report", "lambda", lam, "an under-damped follower: lambda < 2 pi")
    osc = PiecewiseOscillator.follower(law.in_time(omega0), k, n)
    kx = osc.knot_excitation()
    rep = CamReport(law_name=law.name, omega0=omega0, k=k, lam=lam, N=N, mu=float(accumulation_factor(lam, N)),
                    mu_plus=float(mu_plus(lam, N)) if lam > 0 else math.inf, mu_minus=float(mu_minus(lam, N)),
                    continuity=law.continuity(3), peaks=peaks, table=discontinuity_table(law, omega0, k),
                    knots_D=kx.D, knots_phase=kx.t * omega0, warnings=warn)
    if lam == 0:
        warn.append("lambda = 0: no damping, accumulation of excited vibration is unbounded near integer N")
    if steady:
        rep.steady = osc.steady_state()
    return rep
