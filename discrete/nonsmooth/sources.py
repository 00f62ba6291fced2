"""Exogenous sources with modes: programme motions of drivers (textbook §2.5, §5.8-5.9, §6.1-6.2).

A programme driver moves as ``x(t) = offset + velocity t + amplitude sin(omega t + phase) + law(t)``
(:class:`~discrete.nonsmooth.problem.ProgrammeMotion`): the first terms are today's :class:`~discrete.nonsmooth.problem.MotionLaw`,
``law`` a :class:`~discrete.motion.piecewise.PiecewiseLaw` in time (polynomial + sinusoidal pieces
between knots: the standard cam laws, piecewise polynomials, cubic-spline tables).  On piece i the
law is exact in the sub-state of the exogenous vector

    u = [sigma, y_0, ..., y_D, c_1, s_1, ..., c_H, s_H]

* ``sigma``: time since the start of the piece, ``sigma' = e_0`` (the constant of the base basis);
* ``y_j``: the j-th time derivative of the polynomial part, ``y_j' = y_(j+1)``, ``y_D' = 0``;
* ``(c_h, s_h) = (C cos w_h s + S sin w_h s, -C sin w_h s + S cos w_h s)`` for every distinct
  frequency w_h of the law: ``c_h' = w_h s_h``, ``s_h' = -w_h c_h``;

so that ``u' = A u`` with ONE matrix for all pieces and ``law = y_0 + sum_h c_h`` with ONE output
row.  A piece only decides the guard of its end (``sigma = h_i``: the knot, a time event) and the
reset at that knot (``u := `` the initial values of the next piece).  Position and velocity are
continuous for a C1 law (to the round-off of the law's coefficients); the jump of the
acceleration at a knot is the cam's soft impact (Table 6.1), a jump of the velocity a hard one.
The mode of a source is its piece index; a periodic law wraps from its last piece to its first,
the last piece of a non-periodic law continues beyond its knot (its polynomial extended).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import ModelError
from ..motion.piecewise import PiecewiseLaw


class LawSource:
    """The exogenous sub-state, matrices, guards and resets of the law of one programme motion
    (:class:`~discrete.nonsmooth.problem.ProgrammeMotion`)."""

    def __init__(self, law: PiecewiseLaw, name: str):
        self.name = name
        self.law = law
        self.periodic = law.periodic
        self.knots = law.knots.copy()
        self.lengths = np.diff(self.knots)
        self.n_pieces = law.n_pieces
        self.D = law.degree
        active = (law.cos != 0) | (law.sin != 0)
        self.freqs = sorted({float(w) for w in law.freq[active]})
        self.H = len(self.freqs)
        self.size = 1 + (self.D + 1) + 2 * self.H
        n = self.size
        A = np.zeros((n, n))
        for j in range(self.D):
            A[1 + j, 2 + j] = 1.0
        o = 2 + self.D
        for h, w in enumerate(self.freqs):
            A[o + 2 * h, o + 2 * h + 1] = w
            A[o + 2 * h + 1, o + 2 * h] = -w
        self.A = A
        self.clock = np.zeros(n)          # sigma' = e_0: the column of e_0
        self.clock[0] = 1.0
        r = np.zeros(n)
        r[1] = 1.0
        r[o:o + 2 * self.H:2] = 1.0
        self.r = r
        self._fact = np.array([math.factorial(j) for j in range(self.D + 1)], dtype=float)
        self.resets = np.array([self.state(i, 0.0) for i in range(self.n_pieces)])
        # jumps of the position and velocity at each piece's start (the knot it begins at)
        self.jump_x = np.zeros(self.n_pieces)
        self.jump_v = np.zeros(self.n_pieces)
        for m, out in ((0, self.jump_x), (1, self.jump_v)):
            t, d = law.jumps(m)
            for tk, dk in zip(t, d):
                i = int(np.searchsorted(self.knots, tk))
                out[i % self.n_pieces] = dk
        self.scale_x = max(law.scale_of(0), 1e-300)
        self.scale_v = law.scale_of(1)

    # ------------------------------------------------------------ states
    def state(self, i: int, s: float) -> np.ndarray:
        """u at local time ``s`` of piece ``i`` (closed form)."""
        u = np.zeros(self.size)
        u[0] = s
        c = self.law.poly[i] * self._fact                   # derivatives at s = 0
        for j in range(self.D + 1):
            k = np.arange(j, self.D + 1)
            u[1 + j] = float(np.sum(c[k] * s ** (k - j) / self._fact[k - j]))
        o = 2 + self.D
        for h, w in enumerate(self.freqs):
            C = float(np.sum(self.law.cos[i][self.law.freq[i] == w]))
            S = float(np.sum(self.law.sin[i][self.law.freq[i] == w]))
            cw, sw = math.cos(w * s), math.sin(w * s)
            u[o + 2 * h] = C * cw + S * sw
            u[o + 2 * h + 1] = -C * sw + S * cw
        return u

    def advance(self, u: np.ndarray, dt: float) -> np.ndarray:
        """u after ``dt`` within the same piece (closed form of expm(A dt) u)."""
        out = np.empty_like(u)
        out[0] = u[0] + dt
        y = u[1:2 + self.D]
        for j in range(self.D + 1):
            k = np.arange(j, self.D + 1)
            out[1 + j] = float(np.sum(y[k] * dt ** (k - j) / self._fact[k - j]))
        o = 2 + self.D
        for h, w in enumerate(self.freqs):
            c, s = u[o + 2 * h], u[o + 2 * h + 1]
            cw, sw = math.cos(w * dt), math.sin(w * dt)
            out[o + 2 * h] = c * cw + s * sw
            out[o + 2 * h + 1] = -c * sw + s * cw
        return out

    def locate(self, t: float) -> tuple[int, float]:
        """(piece, local time) of the absolute time t (right-continuous at knots)."""
        k0, k1 = self.knots[0], self.knots[-1]
        if self.periodic:
            tt = k0 + (t - k0) % (k1 - k0)
        else:
            if t < k0 - 1e-12 * max(1.0, abs(k0)):
                raise ModelError(f"driver {self.name!r}", "t", t,
                                 f"a time >= {k0:g} s (the start of the non-periodic law)")
            tt = max(t, k0)
        i = int(np.clip(np.searchsorted(self.knots, tt, side="right") - 1, 0, self.n_pieces - 1))
        return i, float(tt - self.knots[i])

    def at_time(self, t: float) -> tuple[int, np.ndarray]:
        """(piece, u) at the absolute time t."""
        i, s = self.locate(t)
        return i, self.state(i, s)

    # ------------------------------------------------------------ modes
    def has_end(self, i: int) -> bool:
        """Whether piece i ends at a knot (the last piece of a non-periodic law does not)."""
        return self.periodic or i < self.n_pieces - 1

    def next_piece(self, i: int) -> int:
        return (i + 1) % self.n_pieces

    def speed_scale(self) -> float:
        return self.scale_v

    def max_frequency(self) -> float:
        return max(self.freqs, default=0.0)
