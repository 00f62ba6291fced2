"""Oscillating systems with a quasi-constant amplitude-frequency characteristic (textbook §6.7).

A platform (total mass M = m_0 + m_1 + m_2, spring c_0 to the housing) carries a linkage whose input
link has the unbalance m_1 R and drives m_2 through the crank r and a spring c_1; with y_3 = 0 (6.40)

    M q'' + b q' + (c_0 + c_1) q = -[c_1 r - omega^2 (m_1 R + m_2 r)] sin(omega t).

(6.41)  A = |c_1 r - omega^2 (m_1 R + m_2 r)| / ((c_0 + c_1) sqrt((1 - z^2)^2 + 4 delta^2 z^4)),
        z = omega/p, p^2 = (c_0 + c_1)/M, delta = psi/(4 pi)  (the book's damping term: a resistance
        growing with omega, b = 2 delta M omega; :func:`kappa` also offers viscous and hysteretic forms)
(6.42)  synthesis c_1 r/(m_1 R + m_2 r) = p^2   =>   (6.43) A = A* = c_1 r/(c_0 + c_1) for every omega (delta = 0)
(6.44)  kappa(z) = A/A* = 1/sqrt(1 + 4 delta^2 z^4/(1 - z^2)^2): kappa(1) = 0 (antiresonance wins).

Detuning theta^2 = p^2 (m_1 R + m_2 r)/(c_1 r):  kappa = |1 - theta^2 z^2| / sqrt((1 - z^2)^2 + 4 delta^2 z^4);
zero (antiresonance) at z_1 = 1/theta; maximum at z_2^2 = (1 - theta^2)/(1 - theta^2 + 4 delta^2) -- the book
prints z_2 = sqrt((1 - theta^2)(1 - theta^2 - 4 delta^2)), which contradicts its own derivative
d(kappa^2)/d(z^2) (also printed as d kappa/d(z^2)); near z = 1, kappa ~ 0.5 |Delta theta^2|/delta.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ModelError

WHERE = "quasi-constant platform"
DAMPING_FORMS = ("book", "viscous", "hysteretic")


def _num(v, key, positive=False):
    ok = isinstance(v, (int, float, np.floating)) and not isinstance(v, bool) and math.isfinite(v) and (v > 0 if positive else v >= 0)
    if not ok:
        raise ModelError(WHERE, key, v, "a finite number > 0" if positive else "a finite number >= 0")
    return float(v)


def kappa(z, delta: float, theta2: float = 1.0, damping: str = "book"):
    """A/A* (6.44) with detuning theta^2; damping term 4 delta^2 z^4 ('book'), z^2 ('viscous'), 1 ('hysteretic')."""
    z = np.asarray(z, dtype=float)
    if np.any(z < 0) or not np.all(np.isfinite(z)):
        raise ModelError(WHERE, "z", z.tolist(), "frequency ratios >= 0")
    delta, theta2 = _num(delta, "delta"), _num(theta2, "theta2", positive=True)
    if damping not in DAMPING_FORMS:
        raise ModelError(WHERE, "damping", damping, " | ".join(map(repr, DAMPING_FORMS)))
    p = {"book": 4, "viscous": 2, "hysteretic": 0}[damping]
    den = np.sqrt((1 - z**2) ** 2 + 4 * delta**2 * z**p)
    num = np.abs(1 - theta2 * z**2)
    # den = 0 only at z = 1 without damping: a resonance, unless theta = 1 cancels it (limit kappa = 1)
    singular = np.where(num <= 1e-9, 1.0, np.inf)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den > 0, num / np.where(den > 0, den, 1.0), singular)


def kappa_extrema(delta: float, theta2: float) -> dict:
    """Zero z_1 = 1/theta, maximum z_2 = sqrt((1 - theta^2)/(1 - theta^2 + 4 delta^2)) (book damping form,
    theta^2 < 1) and kappa there; the near-resonance estimate 0.5 |1 - theta^2|/delta."""
    delta, theta2 = _num(delta, "delta", positive=True), _num(theta2, "theta2", positive=True)
    out = {"z_zero": 1 / math.sqrt(theta2), "kappa_at_1_estimate": 0.5 * abs(1 - theta2) / delta,
           "kappa_at_1": float(kappa(1.0, delta, theta2))}
    if theta2 < 1:
        z2 = math.sqrt((1 - theta2) / (1 - theta2 + 4 * delta**2))
        out.update(z_peak=z2, kappa_peak=float(kappa(z2, delta, theta2)))
    return out


@dataclass
class QuasiConstantPlatform:
    """Parameters of (6.40): M, c_0, c_1, r, the unbalance moment u = m_1 R + m_2 r, damping delta."""

    M: float
    c0: float
    c1: float
    r: float
    unbalance: float
    delta: float = 0.0

    def __post_init__(self):
        for k in ("M", "c1", "r", "unbalance"):
            setattr(self, k, _num(getattr(self, k), k, positive=True))
        self.c0 = _num(self.c0, "c0")
        self.delta = _num(self.delta, "delta")

    @classmethod
    def synthesised(cls, M: float, c0: float, c1: float, r: float, delta: float = 0.0) -> "QuasiConstantPlatform":
        """Choose m_1 R + m_2 r by (6.42): c_1 r/(m_1 R + m_2 r) = p^2 = (c_0 + c_1)/M."""
        M, c1, r = _num(M, "M", True), _num(c1, "c1", True), _num(r, "r", True)
        c0 = _num(c0, "c0")
        return cls(M=M, c0=c0, c1=c1, r=r, unbalance=c1 * r * M / (c0 + c1), delta=delta)

    @property
    def p(self) -> float:
        return math.sqrt((self.c0 + self.c1) / self.M)

    @property
    def theta2(self) -> float:
        return self.p**2 * self.unbalance / (self.c1 * self.r)

    @property
    def A_star(self) -> float:
        """(6.43) A* = c_1 r/(c_0 + c_1)."""
        return self.c1 * self.r / (self.c0 + self.c1)

    def force_amplitude(self, omega):
        """Right-hand side amplitude of (6.40): c_1 r - omega^2 (m_1 R + m_2 r) (signed)."""
        w = np.asarray(omega, dtype=float)
        return self.c1 * self.r - w**2 * self.unbalance

    def amplitude(self, omega, damping: str = "book"):
        """(6.41) with the chosen damping form."""
        z = np.asarray(omega, dtype=float) / self.p
        return self.A_star * kappa(z, self.delta, self.theta2, damping)

    def to_dict(self) -> dict:
        return {"M": self.M, "c0": self.c0, "c1": self.c1, "r": self.r, "unbalance": self.unbalance,
                "delta": self.delta, "p": self.p, "theta2": self.theta2, "A_star": self.A_star}
