"""Dynamic unloading: a spring between the working member and the frame (textbook §6.6).

Harmonic motion y = y_0 cos(omega t) of a member of mass m:
    (6.31)  R_max = m y_0 omega^2                        (mechanism reaction without unloader)
    (6.32)  R0_max = |c_0 - m omega^2| y_0               (with an unloading spring c_0)
R0_max = 0 at omega* = sqrt(c_0/m); the unloader helps (R0_max < R_max) for omega > omega*/sqrt 2.

Arbitrary loads (6.33)-(6.38): with the reaction R*(phi) of the mechanism without unloader and the
spring force U = u_0 + c_0 y (u_0: preload force; the book calls it a pre-deformation), the least-squares
condition  Phi = closed integral (R* + U)^2 |dy| -> min  (6.35) gives the normal equations

    u_0 I_0 + c_0 I_1 = S_1,   u_0 I_1 + c_0 I_2 = S_2,
    I_m = integral_0^{2 pi} Pi^m |Pi'| dphi,  S_1 = -integral R* |Pi'| dphi,  S_2 = -integral R* Pi |Pi'| dphi.

For a law rising from 0 to Pi_max and back, I_0 = 2 Pi_max, I_1 = Pi_max^2, I_2 = 2 Pi_max^3/3, i.e. (6.37)
as it must read -- the book prints the first line as "2 Pi_max u_0 + Pi_max c_0 = S_1"; the second term
is Pi_max^2 c_0 (dimensions, and (6.38) follows only from that form) -- with the solution (6.38)
u_0 = (2 S_1 Pi_max - 3 S_2)/Pi_max^2,  c_0 = 3 (2 S_2 - Pi_max S_1)/Pi_max^3.
The general moments are used here (valid for laws that do not start at 0); both forms are reported.
Note: (6.35) weights the reaction by |dy|, so dwells (dy = 0) do not count, although the spring force acts
there; the least-squares spring always lowers Phi but may raise the peak reaction (e.g. the cycloidal law).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..errors import ModelError
from ..motion.piecewise import PiecewiseLaw

WHERE = "unloading"


def harmonic_unloading(m: float, omega, y0: float, c0: float) -> dict:
    """(6.31), (6.32), omega* and the break-even frequency omega*/sqrt 2."""
    for key, v in (("m", m), ("y0", y0)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v > 0):
            raise ModelError(WHERE, key, v, "a finite number > 0")
    if isinstance(c0, bool) or not isinstance(c0, (int, float)) or not (math.isfinite(c0) and c0 >= 0):
        raise ModelError(WHERE, "c0", c0, "a finite stiffness >= 0")
    w = np.asarray(omega, dtype=float)
    ws = math.sqrt(c0 / m)
    return {"R_max": m * y0 * w**2, "R0_max": np.abs(c0 - m * w**2) * y0, "omega_star": ws,
            "break_even": ws / math.sqrt(2)}


@dataclass
class UnloadingSpring:
    u0: float                # preload force
    c0: float                # spring stiffness
    S1: float
    S2: float
    moments: tuple           # (I_0, I_1, I_2)
    pi_max: float
    book_u0: float           # (6.38) with the corrected (6.37) (assumes Pi from 0 to Pi_max)
    book_c0: float
    peak_before: float       # max |R*| over the cycle
    peak_after: float        # max |R* + U|
    functional_before: float  # Phi of (6.35) without the spring, closed integral R*^2 |dy|
    functional_after: float   # Phi with the spring (the minimum)

    @property
    def peak_ratio(self) -> float:
        return self.peak_before / self.peak_after if self.peak_after > 0 else math.inf

    def to_dict(self) -> dict:
        return {"u0": self.u0, "c0": self.c0, "S1": self.S1, "S2": self.S2, "moments": list(self.moments),
                "pi_max": self.pi_max, "book_u0": self.book_u0, "book_c0": self.book_c0,
                "peak_before": self.peak_before, "peak_after": self.peak_after,
                "functional_before": self.functional_before, "functional_after": self.functional_after}


def _integral(func, law: PiecewiseLaw, nodes: int = 64) -> float:
    """Integral over one cycle: Gauss-Legendre (``nodes`` points) on every smooth sub-interval, split at
    the knots and at the sign changes of Pi' (kinks of |Pi'|, located by brentq)."""
    x, wts = np.polynomial.legendre.leggauss(nodes)
    total = 0.0
    for i in range(law.n_pieces):
        a, b = law.knots[i], law.knots[i + 1]
        s = np.linspace(a, b, 257)
        d = law.piece_value(i, s - a, 1)
        cuts = [a]
        for j in range(1, s.size):
            if d[j - 1] * d[j] < 0:
                cuts.append(brentq(lambda p: float(law.piece_value(i, p - a, 1)), s[j - 1], s[j], xtol=1e-15))
        cuts.append(b)
        for lo, hi in zip(cuts, cuts[1:]):
            p = 0.5 * (hi - lo) * x + 0.5 * (hi + lo)
            total += 0.5 * (hi - lo) * float(np.dot(wts, func(p)))
    return total


def unloading_spring(law: PiecewiseLaw, reaction) -> UnloadingSpring:
    """Least-squares spring (6.35)-(6.38) for the periodic law y = Pi(phi) (one cycle) and the
    reaction R*(phi) (vectorised callable) of the member without the unloader."""
    if not isinstance(law, PiecewiseLaw) or not law.periodic:
        raise ModelError(WHERE, "law", getattr(law, "name", type(law).__name__), "a periodic PiecewiseLaw Pi(phi)")
    if not callable(reaction):
        raise ModelError(WHERE, "reaction", type(reaction).__name__, "a callable R*(phi)")
    absd = lambda p: np.abs(law(p, 1))
    R = lambda p: np.asarray(reaction(p), dtype=float)
    I = tuple(_integral(lambda p, m=m: law(p) ** m * absd(p), law) for m in range(3))
    S1 = -_integral(lambda p: R(p) * absd(p), law)
    S2 = -_integral(lambda p: R(p) * law(p) * absd(p), law)
    A = np.array([[I[0], I[1]], [I[1], I[2]]])
    if np.linalg.cond(A) > 1e12:
        raise ModelError(WHERE, "law", law.name or "law", "a law that moves (the moments of |dy| are degenerate)")
    u0, c0 = np.linalg.solve(A, [S1, S2])
    pmax = law.peak(0)[1]
    book_u0 = (2 * S1 * pmax - 3 * S2) / pmax**2
    book_c0 = 3 * (2 * S2 - pmax * S1) / pmax**3
    phi = np.linspace(law.knots[0], law.knots[-1], 4001)
    Rs = np.asarray(reaction(phi), dtype=float)
    U = u0 + c0 * law(phi)
    phi_before = _integral(lambda p: R(p) ** 2 * absd(p), law)
    phi_after = _integral(lambda p: (R(p) + u0 + c0 * law(p)) ** 2 * absd(p), law)
    return UnloadingSpring(u0=float(u0), c0=float(c0), S1=float(S1), S2=float(S2), moments=tuple(float(v) for v in I), pi_max=float(pmax),
                           book_u0=float(book_u0), book_c0=float(book_c0), peak_before=float(np.max(np.abs(Rs))),
                           peak_after=float(np.max(np.abs(Rs + U))), functional_before=float(phi_before),
                           functional_after=float(max(phi_after, 0.0)))
