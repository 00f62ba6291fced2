"""Dynamic vibration absorber (textbook §6.5).

Main mass m_1 on c_1 to ground, absorber m_2 on c_2 attached to m_1 (Fig. 6.9a; torsional analogue:
disc J_2 on a shaft c_2, Fig. 6.9b), force F_1 cos(omega t) on m_1.  With a_11 = m_1, a_22 = m_2,
c_11 = c_1 + c_2, c_22 = c_2, c_12 = -c_2 (absolute coordinates):

    (6.29)  A_1 = F_1 (c_22 - a_22 omega^2)/Delta(omega^2),   Delta = frequency determinant (4.25)
    (6.30)  A_1 = 0 at omega* = sqrt(c_22/a_22) = p_2   =>   tuning c_2 = m_2 omega*^2,

and then A_2 = -F_1/c_2 (the absorber's spring force cancels the exciting force).  An optional damper
b between the masses (Fig. 6.10, curve 3) makes the numerators complex; it raises A_1 near omega*.
:meth:`Absorber.lumped_model` builds the same system as a :class:`discrete.lumped.LumpedModel`
for the package's harmonic and modal solvers.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ModelError

WHERE = "absorber"


def _pos(v, key, allow_zero=False):
    ok = isinstance(v, (int, float, np.floating)) and not isinstance(v, bool) and math.isfinite(v) and (v >= 0 if allow_zero else v > 0)
    if not ok:
        raise ModelError(WHERE, key, v, "a finite number >= 0" if allow_zero else "a finite number > 0")
    return float(v)


def tuned_stiffness(m2: float, omega_star: float) -> float:
    """c_2 = m_2 omega*^2 (6.30)."""
    return _pos(m2, "m2") * _pos(omega_star, "omega_star") ** 2


@dataclass
class Absorber:
    m1: float
    c1: float
    m2: float
    c2: float
    b: float = 0.0                 # optional damper between main mass and absorber

    def __post_init__(self):
        for k in ("m1", "c1", "m2", "c2"):
            setattr(self, k, _pos(getattr(self, k), k))
        self.b = _pos(self.b, "b", allow_zero=True)

    @classmethod
    def design(cls, m1: float, c1: float, omega_star: float, force_amplitude: float, stroke_allowed: float,
               b: float = 0.0) -> "Absorber":
        """Lightest absorber tuned to omega* whose stroke |A_2| = F_1/c_2 stays within ``stroke_allowed``:
        c_2 = F_1/stroke, m_2 = c_2/omega*^2."""
        c2 = _pos(force_amplitude, "force_amplitude") / _pos(stroke_allowed, "stroke_allowed")
        return cls(m1=m1, c1=c1, m2=c2 / _pos(omega_star, "omega_star") ** 2, c2=c2, b=b)

    @property
    def antiresonance(self) -> float:
        """omega* = p_2 = sqrt(c_22/a_22) (6.30)."""
        return math.sqrt(self.c2 / self.m2)

    def natural_frequencies(self) -> np.ndarray:
        """Roots of Delta(k^2) = m_1 m_2 k^4 - (m_1 c_2 + m_2 (c_1 + c_2)) k^2 + c_1 c_2 = 0 (4.26), undamped."""
        a = self.m1 * self.m2
        bq = self.m1 * self.c2 + self.m2 * (self.c1 + self.c2)
        cq = self.c1 * self.c2
        disc = math.sqrt(bq * bq - 4 * a * cq)
        # numerically stable pair of roots
        s_hi = (bq + disc) / (2 * a)
        s_lo = cq / (a * s_hi)
        return np.sqrt(np.array([s_lo, s_hi]))

    def amplitudes(self, omega, force_amplitude: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
        """Complex (A_1, A_2) by Cramer's rule (5.31)/(6.29), with the damper b if any."""
        w = np.asarray(omega, dtype=float)
        zb = 1j * w * self.b
        d11 = self.c1 + self.c2 + zb - self.m1 * w**2
        d22 = self.c2 + zb - self.m2 * w**2
        d12 = -(self.c2 + zb)
        det = d11 * d22 - d12 * d12
        F = force_amplitude
        return F * d22 / det, -F * d12 / det

    def lumped_model(self):
        """The same system as a LumpedModel: bodies 'main', 'absorber'."""
        from ..lumped import Body, Link, LumpedModel

        dampers = [Link(("main", "absorber"), self.b)] if self.b > 0 else []
        return LumpedModel(bodies=[Body("main", self.m1), Body("absorber", self.m2)],
                           springs=[Link(("ground", "main"), self.c1), Link(("main", "absorber"), self.c2)],
                           dampers=dampers, title="main mass with a dynamic absorber (§6.5)")

    def to_dict(self) -> dict:
        return {"m1": self.m1, "c1": self.c1, "m2": self.m2, "c2": self.c2, "b": self.b,
                "antiresonance": self.antiresonance, "natural_frequencies": self.natural_frequencies().tolist()}
