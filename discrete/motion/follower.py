"""Exact response of a linear 1-DOF oscillator to a piecewise excitation: the elastic cam follower.

    q'' + 2 n q' + k^2 q = W(t)                                            (5.2), (6.1)

* cam follower (kinematic excitation, (6.1)): q is the follower's elastic deformation, y = x + q its
  absolute motion, W = -x''(t) for the programme motion x(t); where x or x' jumps, y and y' stay
  continuous (6.3), so q jumps by -Delta x and q' by -Delta x' (the book's conditions; with damping a
  position step would also make y' jump by 2 n Delta x, which the book, and this module, neglect:
  a step of the profile is not a realisable law anyway).
* periodic force (5.40): W = F(t)/a, no jumps of q, q'.

On each piece of the excitation (a :class:`~discrete.motion.piecewise.PiecewiseLaw`: polynomial +
sinusoidal terms) the particular solution Y_i is found in closed form (undetermined coefficients),
and the free part e^{-n s}(C_1 cos k_1 s + C_2 sin k_1 s), k_1 = sqrt(k^2 - n^2), is propagated
exactly by its 2x2 transition matrix.  The periodic steady state solves the periodicity conditions
(5.46) exactly -- the book's closed-form method of §5.9 without its simplifications (5.51).

Nothing is integrated numerically: the only errors are round-off (the validation cases compare with
an adaptive Runge-Kutta integration as the independent second method).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import ModelError, SolverError
from .piecewise import PiecewiseLaw

WHERE = "follower"


def _check_kn(k: float, n: float) -> tuple[float, float]:
    if isinstance(k, bool) or not isinstance(k, (int, float)) or not (math.isfinite(k) and k > 0):
        raise ModelError(WHERE, "k", k, "a natural frequency > 0 (rad/s)")
    if isinstance(n, bool) or not isinstance(n, (int, float)) or not (math.isfinite(n) and 0 <= n < k):
        raise ModelError(WHERE, "n", n, f"a damping exponent in [0, k) = [0, {k:g}) (under-damped oscillator)")
    return float(k), float(n)


def particular_solution(W: PiecewiseLaw, k: float, n: float = 0.0) -> PiecewiseLaw:
    """Y_i with Y'' + 2 n Y' + k^2 Y = W on every piece (polynomial part by back-substitution,
    sinusoidal part by the complex receptance 1/(k^2 - w^2 + 2 i n w))."""
    k, n = _check_kn(k, n)
    D = W.degree
    b = np.zeros_like(W.poly)
    for j in range(D, -1, -1):
        acc = W.poly[:, j].copy()
        if j + 1 <= D:
            acc -= 2 * n * (j + 1) * b[:, j + 1]
        if j + 2 <= D:
            acc -= (j + 2) * (j + 1) * b[:, j + 2]
        b[:, j] = acc / k**2
    den = k**2 - W.freq**2 + 2j * n * W.freq
    active = (W.cos != 0) | (W.sin != 0)
    if np.any(active & (np.abs(den) <= 1e-14 * k**2)):
        raise ModelError(WHERE, "k", k, "a frequency different from the excitation's sinusoidal terms "
                         "(undamped resonance: no bounded particular solution)")
    G = np.where(active, (W.cos - 1j * W.sin) / np.where(active, den, 1.0), 0.0)
    return PiecewiseLaw(W.knots.copy(), b, W.freq.copy(), G.real, -G.imag, W.periodic, "particular solution")


def transition(k: float, n: float, h):
    """Phi(h): [u, u'](h) = Phi(h) [u, u'](0) for u'' + 2 n u' + k^2 u = 0 (under-damped)."""
    k1 = math.sqrt(k * k - n * n)
    h = np.asarray(h, dtype=float)
    e, c, s = np.exp(-n * h), np.cos(k1 * h), np.sin(k1 * h)
    return np.moveaxis(np.array([[e * (c + n / k1 * s), e * s / k1], [-e * k * k / k1 * s, e * (c - n / k1 * s)]]),
                       [0, 1], [-2, -1])


@dataclass
class KnotExcitation:
    """Free vibration started at each knot, (6.4)-(6.5): A_1 = -(Delta x + Delta Y), B_1 = -(Delta x' +
    Delta Y')/k, D = sqrt(A_1^2 + B_1^2) (the "jump"), sin alpha = A_1/D, cos alpha = B_1/D,
    |Delta q''|max = k^2 D (6.6).  For a force excitation Delta x = Delta x' = 0."""

    t: np.ndarray
    A1: np.ndarray
    B1: np.ndarray

    @property
    def D(self) -> np.ndarray:
        return np.hypot(self.A1, self.B1)

    @property
    def alpha(self) -> np.ndarray:
        return np.mod(np.arctan2(self.A1, self.B1), 2 * math.pi)

    def to_dict(self) -> dict:
        return {"t": self.t.tolist(), "A1": self.A1.tolist(), "B1": self.B1.tolist(), "D": self.D.tolist(),
                "alpha": self.alpha.tolist()}


@dataclass
class SteadyState:
    """Periodic steady state over one cycle [t0, t0 + tau)."""

    t: np.ndarray
    q: np.ndarray
    dq: np.ndarray
    ddq: np.ndarray
    q0: float
    dq0: float
    period: float
    residual: float                  # |z(tau) - z(0)| after one more exact cycle, relative
    accompanying_amplitude: float    # amplitude of the free part at t0+ (D of (5.52))
    x: np.ndarray | None = None      # programme motion and its acceleration (kinematic excitation)
    ddx: np.ndarray | None = None

    @property
    def ddy(self) -> np.ndarray | None:
        """Absolute acceleration y'' = x'' + q'' of the follower (kinematic excitation)."""
        return None if self.ddx is None else self.ddx + self.ddq

    def to_dict(self) -> dict:
        d = {"t": self.t.tolist(), "q": self.q.tolist(), "dq": self.dq.tolist(), "ddq": self.ddq.tolist(),
             "q0": self.q0, "dq0": self.dq0, "period": self.period, "residual": self.residual,
             "accompanying_amplitude": self.accompanying_amplitude,
             "max_abs_q": float(np.max(np.abs(self.q))), "max_abs_ddq": float(np.max(np.abs(self.ddq)))}
        if self.ddx is not None:
            d.update(x=self.x.tolist(), ddx=self.ddx.tolist(), ddy=self.ddy.tolist())
        return d


@dataclass
class PiecewiseOscillator:
    """q'' + 2 n q' + k^2 q = W(t) with W a :class:`PiecewiseLaw` and state kicks at its knots."""

    W: PiecewiseLaw
    k: float
    n: float = 0.0
    kicks: np.ndarray | None = None        # (n_knots, 2): jumps of (q, q') at each knot
    law: PiecewiseLaw | None = None        # programme motion x(t) for a follower
    Y: PiecewiseLaw = field(init=False)

    def __post_init__(self):
        self.k, self.n = _check_kn(self.k, self.n)
        nk = self.W.knots.size
        self.kicks = np.zeros((nk, 2)) if self.kicks is None else np.asarray(self.kicks, dtype=float)
        if self.kicks.shape != (nk, 2):
            raise ModelError(WHERE, "kicks", list(self.kicks.shape), f"an array of shape ({nk}, 2)")
        self.Y = particular_solution(self.W, self.k, self.n)

    # ------------------------------------------------------------ builders
    @classmethod
    def follower(cls, law: PiecewiseLaw, k: float, n: float = 0.0) -> "PiecewiseOscillator":
        """Elastic follower (6.1) under the programme motion ``law`` x(t) (a time law)."""
        W = law.derivative(2)
        W = PiecewiseLaw(W.knots, -W.poly, W.freq, -W.cos, -W.sin, W.periodic, "-x''")
        kicks = np.zeros((law.knots.size, 2))
        for m in (0, 1):
            t, d = law.jumps(m)
            idx = np.searchsorted(law.knots, t)
            kicks[idx, m] = -d
        return cls(W=W, k=k, n=n, kicks=kicks, law=law)

    @classmethod
    def forced(cls, force: PiecewiseLaw, k: float, n: float = 0.0, inertia: float = 1.0) -> "PiecewiseOscillator":
        """a q'' + b q' + c q = F(t) (5.40) written as (5.2): W = F/a."""
        if not (isinstance(inertia, (int, float)) and math.isfinite(inertia) and inertia > 0):
            raise ModelError(WHERE, "inertia", inertia, "a number > 0")
        F = force
        return cls(W=PiecewiseLaw(F.knots, F.poly / inertia, F.freq, F.cos / inertia, F.sin / inertia, F.periodic,
                                  "F/a"), k=k, n=n)

    @property
    def k1(self) -> float:
        return math.sqrt(self.k**2 - self.n**2)

    @property
    def period(self) -> float:
        return self.W.span

    # ------------------------------------------------------ propagation
    def _piece(self, i: int, z: np.ndarray, h):
        """State at local time(s) h of piece i from the state z at its start (after the kick)."""
        Y0 = np.array([self.Y.piece_value(i, 0.0, 0), self.Y.piece_value(i, 0.0, 1)])
        u = transition(self.k, self.n, h) @ (z - Y0)
        return np.stack([self.Y.piece_value(i, h, 0), self.Y.piece_value(i, h, 1)], axis=-1) + u

    def cycle_map(self) -> tuple[np.ndarray, np.ndarray]:
        """(P, g): state at t0+ of the next cycle = P z + g for z at t0+ (periodic excitation)."""
        P, g = np.eye(2), np.zeros(2)
        for i in range(self.W.n_pieces):
            h = self.W.knots[i + 1] - self.W.knots[i]
            Phi = transition(self.k, self.n, h)
            Y0 = np.array([self.Y.piece_value(i, 0.0, 0), self.Y.piece_value(i, 0.0, 1)])
            Y1 = np.array([self.Y.piece_value(i, h, 0), self.Y.piece_value(i, h, 1)])
            P, g = Phi @ P, Phi @ (g - Y0) + Y1
            kick = self.kicks[0] if i == self.W.n_pieces - 1 else self.kicks[i + 1]
            g = g + kick
        return P, g

    def periodic_state(self) -> np.ndarray:
        """(q, q') at t0+ on the periodic orbit: (I - P) z = g (5.46)."""
        if not self.W.periodic:
            raise ModelError(WHERE, "law", self.W.name or "excitation", "a periodic excitation (periodic = True)")
        P, g = self.cycle_map()
        A = np.eye(2) - P
        S = np.diag([1.0, 1.0 / self.k])          # states (q, q'/k): the transition is a scaled rotation
        if np.linalg.svd(S @ A @ np.linalg.inv(S), compute_uv=False).min() < 1e-9:
            raise SolverError(f"no periodic state: k tau = {self.k * self.period:.6g} is a multiple of 2 pi with n = "
                              f"{self.n:g} (undamped resonance of a harmonic of the excitation)")
        return np.linalg.solve(A, g)

    def response(self, t, z0=None, derivative_max: int = 2) -> np.ndarray:
        """(q, q', q'') at the times ``t`` (>= knots[0]) from the state z0 = (q, q') at knots[0]+
        (default: the periodic state).  Periodic excitations repeat; others end at the last knot."""
        t = np.asarray(t, dtype=float)
        if z0 is None:
            z0 = self.periodic_state()
        z = np.asarray(z0, dtype=float).copy()
        t0, tau = self.W.knots[0], self.period
        if np.any(t < t0 - 1e-12 * max(1.0, abs(t0))):
            raise ModelError(WHERE, "t", float(t.min()), f"times >= {t0:g} (the start of the excitation)")
        if not self.W.periodic and np.any(t > self.W.knots[-1] * (1 + 1e-12) + 1e-300):
            raise ModelError(WHERE, "t", float(t.max()), f"times <= {self.W.knots[-1]:g} (non-periodic excitation)")
        out = np.zeros((t.size, 3))
        cyc = np.floor((t - t0) / tau).astype(int) if self.W.periodic else np.zeros(t.size, dtype=int)
        cyc = np.maximum(cyc, 0)
        if not self.W.periodic:
            cyc[:] = 0
        local = t - t0 - cyc * tau
        for c in range(int(cyc.max(initial=0)) + 1):
            for i in range(self.W.n_pieces):
                a, b = self.W.knots[i] - t0, self.W.knots[i + 1] - t0
                last = i == self.W.n_pieces - 1
                sel = (cyc == c) & (local >= a) & ((local < b) | (last & (local <= b + 1e-12 * tau)))
                if np.any(sel):
                    h = local[sel] - a
                    zz = self._piece(i, z, h)
                    W = self.W.piece_value(i, h, 0)
                    out[sel, 0], out[sel, 1] = zz[..., 0], zz[..., 1]
                    out[sel, 2] = W - 2 * self.n * zz[..., 1] - self.k**2 * zz[..., 0]
                z = self._piece(i, z, b - a)
                z = z + (self.kicks[0] if last else self.kicks[i + 1])
        return out

    def steady_state(self, samples_per_piece: int = 200) -> SteadyState:
        """The periodic orbit sampled over one cycle, its quality figure and accompanying amplitude."""
        z0 = self.periodic_state()
        t = np.concatenate([np.linspace(self.W.knots[i], self.W.knots[i + 1], samples_per_piece, endpoint=False)
                            for i in range(self.W.n_pieces)] + [self.W.knots[-1:]])
        r = self.response(t[:-1], z0)
        P, g = self.cycle_map()
        z1 = P @ z0 + g
        res = float(np.linalg.norm(z1 - z0) / max(np.linalg.norm(z0), 1e-300))
        last = self._piece(self.W.n_pieces - 1, self._state_at_piece(z0, self.W.n_pieces - 1),
                           self.W.knots[-1] - self.W.knots[-2])
        q = np.append(r[:, 0], last[0])
        dq = np.append(r[:, 1], last[1])
        Wend = self.W.piece_value(self.W.n_pieces - 1, self.W.knots[-1] - self.W.knots[-2], 0)
        ddq = np.append(r[:, 2], Wend - 2 * self.n * last[1] - self.k**2 * last[0])
        Y0 = np.array([self.Y.piece_value(0, 0.0, 0), self.Y.piece_value(0, 0.0, 1)])
        u = z0 - Y0
        amp = float(math.hypot(u[0], (u[1] + self.n * u[0]) / self.k1))
        ss = SteadyState(t=t, q=q, dq=dq, ddq=ddq, q0=float(z0[0]), dq0=float(z0[1]), period=self.period,
                         residual=res, accompanying_amplitude=amp)
        if self.law is not None:
            ss.x = np.append(self.law(t[:-1]), self.law(t[-1:], side="left"))
            ss.ddx = np.append(self.law(t[:-1], 2), self.law(t[-1:], 2, side="left"))
        return ss

    def _state_at_piece(self, z0: np.ndarray, i: int) -> np.ndarray:
        z = np.asarray(z0, dtype=float).copy()
        for j in range(i):
            z = self._piece(j, z, self.W.knots[j + 1] - self.W.knots[j]) + self.kicks[j + 1]
        return z

    # ----------------------------------------------------- (6.4) at knots
    def knot_excitation(self) -> KnotExcitation:
        """(6.4) at every knot with a jump, evaluated with the exact particular solutions."""
        t, dY = self.Y.jumps(0)
        _, dY1 = self.Y.jumps(1)
        idx = np.searchsorted(self.W.knots, t)
        kick = self.kicks[idx]
        # kicks are -(Delta x, Delta x'): A_1 = -(Delta x + Delta Y) = kick_q - Delta Y
        A1 = kick[:, 0] - dY
        B1 = (kick[:, 1] - dY1) / self.k
        return KnotExcitation(t=t, A1=A1, B1=B1)
