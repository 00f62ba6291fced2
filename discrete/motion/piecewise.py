"""Piecewise motion laws: per-piece polynomial (+ optional sinusoidal) terms between knots.

On piece i, with the local variable s = t - t_i (t_i <= t < t_{i+1}),

    x(t) = sum_j poly[i, j] s^j + sum_h ( cos[i, h] cos(freq[i, h] s) + sin[i, h] sin(freq[i, h] s) ).

``t`` is the phase phi of a cam (textbook §2.5: Pi(phi) and its transfer functions Pi', Pi'', Pi''')
or time (x(t), x', x'', x''' with x' = omega0 Pi' etc. for phi = omega0 t, (2.13)).  The polynomial
part alone is the usual piecewise polynomial (scipy ``PPoly`` converts both ways); the sinusoidal
terms keep the cycloidal and harmonic cam laws exact instead of approximated.

Every piece is the output of a small constant-coefficient linear system (:meth:`PiecewiseLaw.exogenous`):
e' = A e, x = r . e, with e = [1, s, s^2/2!, ..., s^D/D!, cos w s, sin w s, ...].  This is the form an
exact (matrix-exponential) integrator propagates without error, with events at the knots.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ModelError

WHERE = "motion law"


def _as2d(a, n_pieces: int, key: str) -> np.ndarray:
    a = np.asarray(a, dtype=float)
    if a.ndim == 1 and n_pieces == 1:
        a = a[None, :]
    if a.ndim != 2 or a.shape[0] != n_pieces:
        raise ModelError(WHERE, key, list(np.shape(a)), f"an array of shape ({n_pieces}, terms): one row per piece")
    if not np.all(np.isfinite(a)):
        raise ModelError(WHERE, key, "non-finite entries", "finite numbers")
    return a


@dataclass
class PiecewiseLaw:
    """x on pieces [knots[i], knots[i+1]) (see the module docstring).

    ``periodic``: the law repeats with period knots[-1] - knots[0] (a cam cycle); otherwise it is
    defined on [knots[0], knots[-1]] only.
    """

    knots: np.ndarray
    poly: np.ndarray
    freq: np.ndarray | None = None
    cos: np.ndarray | None = None
    sin: np.ndarray | None = None
    periodic: bool = False
    name: str = ""

    def __post_init__(self):
        k = np.asarray(self.knots, dtype=float)
        if k.ndim != 1 or k.size < 2 or not np.all(np.isfinite(k)) or not np.all(np.diff(k) > 0):
            raise ModelError(WHERE, "knots", np.asarray(self.knots).tolist(),
                             "at least two finite, strictly increasing numbers")
        self.knots = k
        n = k.size - 1
        self.poly = _as2d(self.poly, n, "poly")
        if self.freq is None:
            self.freq = np.zeros((n, 0))
        self.freq = _as2d(self.freq, n, "freq")
        h = self.freq.shape[1]
        self.cos = np.zeros((n, h)) if self.cos is None else _as2d(self.cos, n, "cos")
        self.sin = np.zeros((n, h)) if self.sin is None else _as2d(self.sin, n, "sin")
        if self.cos.shape != self.freq.shape or self.sin.shape != self.freq.shape:
            raise ModelError(WHERE, "cos/sin", [list(self.cos.shape), list(self.sin.shape)],
                             f"arrays of the same shape as freq {list(self.freq.shape)}")
        self.periodic = bool(self.periodic)

    # ------------------------------------------------------------- basics
    @property
    def n_pieces(self) -> int:
        return self.knots.size - 1

    @property
    def degree(self) -> int:
        return self.poly.shape[1] - 1

    @property
    def span(self) -> float:
        """Length of the definition interval (the period of a periodic law)."""
        return float(self.knots[-1] - self.knots[0])

    @property
    def has_trig(self) -> bool:
        return bool(np.any(self.cos != 0) or np.any(self.sin != 0))

    def _locate(self, t, side: str):
        t = np.asarray(t, dtype=float)
        t0, t1 = self.knots[0], self.knots[-1]
        if self.periodic:
            tt = t0 + np.mod(t - t0, t1 - t0)
            if side == "left":      # the end of the cycle belongs to the last piece
                tt = np.where(tt == t0, t1, tt)
        else:
            bad = (t < t0 - 1e-12 * max(1.0, abs(t0))) | (t > t1 + 1e-12 * max(1.0, abs(t1)))
            if np.any(bad):
                raise ModelError(WHERE, "t", float(np.asarray(t)[bad].flat[0]),
                                 f"a value in [{t0:g}, {t1:g}] (the law is not periodic)")
            tt = np.clip(t, t0, t1)
        if side == "right":
            i = np.searchsorted(self.knots, tt, side="right") - 1
        elif side == "left":
            i = np.searchsorted(self.knots, tt, side="left") - 1
        else:
            raise ModelError(WHERE, "side", side, "'right' | 'left'")
        i = np.clip(i, 0, self.n_pieces - 1)
        return i, tt - self.knots[i]

    def piece_value(self, i, s, derivative: int = 0):
        """Derivative ``derivative`` of piece ``i`` at local coordinate ``s`` (arrays broadcast)."""
        m = int(derivative)
        if m < 0:
            raise ModelError(WHERE, "derivative", derivative, "an integer >= 0")
        i = np.asarray(i)
        s = np.asarray(s, dtype=float)
        out = np.zeros(np.broadcast(i, s).shape)
        for j in range(m, self.degree + 1):
            out = out + self.poly[i, j] * (math.factorial(j) / math.factorial(j - m)) * s ** (j - m)
        for h in range(self.freq.shape[1]):
            w = self.freq[i, h]
            ph = w * s + m * math.pi / 2
            out = out + w**m * (self.cos[i, h] * np.cos(ph) + self.sin[i, h] * np.sin(ph))
        return out

    def __call__(self, t, derivative: int = 0, side: str = "right"):
        """x^(derivative)(t); at a knot ``side`` picks the piece that starts ('right') or ends ('left') there."""
        i, s = self._locate(t, side)
        return self.piece_value(i, s, derivative)

    def midpoint_value(self, t, derivative: int = 0):
        """Mean of the left and right limits (the value a Fourier series converges to)."""
        return 0.5 * (self(t, derivative, "right") + self(t, derivative, "left"))

    # ------------------------------------------------------- discontinuities
    def jumps(self, derivative: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """(knots, x^(m)(t+0) - x^(m)(t-0)) at the interior knots, and at knots[0] (the cycle
        wrap) for a periodic law."""
        ks = self.knots[1:-1]
        right = self.piece_value(np.arange(1, self.n_pieces), 0.0, derivative)
        left = self.piece_value(np.arange(0, self.n_pieces - 1), np.diff(self.knots)[:-1], derivative)
        t, d = list(ks), list(right - left)
        if self.periodic:
            first = float(self.piece_value(0, 0.0, derivative))
            last = float(self.piece_value(self.n_pieces - 1, self.knots[-1] - self.knots[-2], derivative))
            t, d = [self.knots[0]] + t, [first - last] + d
        return np.asarray(t, dtype=float), np.asarray(d, dtype=float)

    def scale_of(self, derivative: int = 0, samples_per_piece: int = 64) -> float:
        """max |x^(m)| sampled on every piece (a magnitude for relative jump thresholds)."""
        s = np.linspace(0.0, 1.0, samples_per_piece)
        vals = [self.piece_value(i, s * (self.knots[i + 1] - self.knots[i]), derivative) for i in range(self.n_pieces)]
        return float(np.max(np.abs(np.concatenate(vals))))

    def continuity(self, max_order: int = 4, rtol: float = 1e-9) -> int:
        """Highest m such that x, x', ..., x^(m) have no jumps (-1 if x itself jumps)."""
        for m in range(max_order + 1):
            _, d = self.jumps(m)
            if d.size and np.max(np.abs(d)) > rtol * max(self.scale_of(m), 1e-300):
                return m - 1
        return max_order

    # ------------------------------------------------------- transformations
    def derivative(self, m: int = 1) -> "PiecewiseLaw":
        """The law of x^(m) (same knots)."""
        if m < 0:
            raise ModelError(WHERE, "derivative", m, "an integer >= 0")
        poly, cos, sin = self.poly.copy(), self.cos.copy(), self.sin.copy()
        for _ in range(m):
            d = poly.shape[1] - 1
            poly = poly[:, 1:] * np.arange(1, d + 1) if d > 0 else np.zeros((poly.shape[0], 1))
            cos, sin = self.freq * sin, -self.freq * cos
        if poly.shape[1] == 0:
            poly = np.zeros((self.n_pieces, 1))
        return PiecewiseLaw(self.knots.copy(), poly, self.freq.copy(), cos, sin, self.periodic,
                            f"{self.name}^({m})" if self.name else "")

    def stretched(self, *, start: float | None = None, time_scale: float = 1.0, value_scale: float = 1.0,
                  value_offset: float = 0.0, periodic: bool | None = None) -> "PiecewiseLaw":
        """x_new(t) = value_offset + value_scale x(t0 + (t - start)/time_scale): knots mapped to
        start + time_scale (knots - t0).  Used for phase -> time (time_scale = 1/omega0) and to place a
        normalised rise over an angle beta (time_scale = beta)."""
        if not (time_scale > 0 and math.isfinite(time_scale)):
            raise ModelError(WHERE, "time_scale", time_scale, "a finite number > 0")
        start = self.knots[0] if start is None else float(start)
        knots = start + time_scale * (self.knots - self.knots[0])
        powers = time_scale ** -np.arange(self.degree + 1, dtype=float)
        poly = self.poly * powers * value_scale
        poly[:, 0] += value_offset
        return PiecewiseLaw(knots, poly, self.freq / time_scale, self.cos * value_scale, self.sin * value_scale,
                            self.periodic if periodic is None else periodic, self.name)

    def in_time(self, omega0: float, t0: float = 0.0) -> "PiecewiseLaw":
        """The time law x(t) = Pi(phi0 + omega0 (t - t0)) for a cam turning at omega0 [rad/s] ((2.13),
        phi' = omega0 constant): derivative m scales by omega0^m."""
        if not (omega0 > 0 and math.isfinite(omega0)):
            raise ModelError(WHERE, "omega0", omega0, "a finite angular speed > 0 (rad/s)")
        return self.stretched(start=t0, time_scale=1.0 / omega0)

    @staticmethod
    def concatenate(laws: list["PiecewiseLaw"], periodic: bool = False, name: str = "") -> "PiecewiseLaw":
        """Join laws whose intervals follow each other (each law's first knot = previous law's last)."""
        if not laws:
            raise ModelError(WHERE, "pieces", [], "at least one law")
        for a, b in zip(laws, laws[1:]):
            if abs(a.knots[-1] - b.knots[0]) > 1e-12 * max(1.0, abs(a.knots[-1])):
                raise ModelError(WHERE, "knots", [float(a.knots[-1]), float(b.knots[0])],
                                 "contiguous pieces (each law starting where the previous one ends)")
        D = max(l.degree for l in laws)
        H = max(l.freq.shape[1] for l in laws)
        knots = [laws[0].knots[0]]
        poly, freq, cos, sin = [], [], [], []
        for l in laws:
            knots.extend(l.knots[1:])
            poly.append(np.pad(l.poly, ((0, 0), (0, D - l.degree))))
            for dst, src in ((freq, l.freq), (cos, l.cos), (sin, l.sin)):
                dst.append(np.pad(src, ((0, 0), (0, H - src.shape[1]))))
        return PiecewiseLaw(np.asarray(knots), np.vstack(poly), np.vstack(freq), np.vstack(cos), np.vstack(sin),
                            periodic, name)

    # ------------------------------------------------------- scipy interop
    @classmethod
    def from_ppoly(cls, pp, periodic: bool = False, name: str = "") -> "PiecewiseLaw":
        """From a scipy ``PPoly`` (coefficients c[m, i] of (x - x_i)^(k-m), highest power first)."""
        c = np.asarray(pp.c, dtype=float)
        if c.ndim != 2:
            raise ModelError(WHERE, "ppoly", list(c.shape), "a scalar-valued PPoly (c of shape (k, m))")
        return cls(np.asarray(pp.x, dtype=float), c[::-1].T.copy(), periodic=periodic, name=name)

    def to_ppoly(self):
        """scipy ``PPoly`` of the polynomial part (only for laws without sinusoidal terms)."""
        from scipy.interpolate import PPoly

        if self.has_trig:
            raise ModelError(WHERE, "cos/sin", "non-zero", "no sinusoidal terms (PPoly holds polynomials only)")
        return PPoly(self.poly[:, ::-1].T.copy(), self.knots, extrapolate=False)

    @classmethod
    def tabulated(cls, t, x, *, periodic: bool = False, bc_type: str | None = None, name: str = "") -> "PiecewiseLaw":
        """A C2 cubic spline through the table (scipy ``CubicSpline``); ``periodic`` needs x[0] == x[-1]
        and uses periodic end conditions (default 'not-a-knot' otherwise)."""
        from scipy.interpolate import CubicSpline

        t = np.asarray(t, dtype=float)
        x = np.asarray(x, dtype=float)
        if t.ndim != 1 or t.size < 3 or not np.all(np.diff(t) > 0):
            raise ModelError(WHERE, "t", t.tolist()[:6], "at least 3 strictly increasing abscissae")
        if x.shape != t.shape or not np.all(np.isfinite(x)):
            raise ModelError(WHERE, "x", np.shape(x), f"{t.size} finite values (one per abscissa)")
        if periodic and abs(x[0] - x[-1]) > 1e-12 * max(1.0, np.max(np.abs(x))):
            raise ModelError(WHERE, "x", [float(x[0]), float(x[-1])], "x[0] == x[-1] for a periodic table")
        bc = bc_type or ("periodic" if periodic else "not-a-knot")
        if periodic:
            x = x.copy()
            x[-1] = x[0]
        return cls.from_ppoly(CubicSpline(t, x, bc_type=bc), periodic=periodic, name=name)

    # -------------------------------------------------- exact propagation
    def exogenous(self, i: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(A, e0, r) with e' = A e, e(0) = e0 and x(t_i + s) = r . e(s) on piece ``i``.

        e = [1, s, s^2/2!, ..., s^D/D!, cos w_1 s, sin w_1 s, ...]; derivative m of x is r A^m e.
        """
        if not 0 <= i < self.n_pieces:
            raise ModelError(WHERE, "piece", i, f"an index in [0, {self.n_pieces - 1}]")
        D, H = self.degree, self.freq.shape[1]
        n = D + 1 + 2 * H
        A = np.zeros((n, n))
        e0 = np.zeros(n)
        r = np.zeros(n)
        e0[0] = 1.0
        for j in range(1, D + 1):
            A[j, j - 1] = 1.0
        r[:D + 1] = self.poly[i] * np.array([math.factorial(j) for j in range(D + 1)], dtype=float)
        for h in range(H):
            c, s_ = D + 1 + 2 * h, D + 2 + 2 * h
            w = self.freq[i, h]
            A[c, s_], A[s_, c] = -w, w
            e0[c] = 1.0
            r[c], r[s_] = self.cos[i, h], self.sin[i, h]
        return A, e0, r

    # ----------------------------------------------------------- summaries
    def peak(self, derivative: int = 0, samples_per_piece: int = 400) -> tuple[float, float]:
        """(t, x^(m)(t)) where |x^(m)| is largest: dense sampling refined by a bounded scalar search."""
        from scipy.optimize import minimize_scalar

        best = (float(self.knots[0]), 0.0)
        for i in range(self.n_pieces):
            L = self.knots[i + 1] - self.knots[i]
            s = np.linspace(0.0, L, samples_per_piece)
            v = self.piece_value(i, s, derivative)
            j = int(np.argmax(np.abs(v)))
            cand = (float(s[j]), float(v[j]))
            if 0 < j < s.size - 1:
                res = minimize_scalar(lambda u: -abs(float(self.piece_value(i, u, derivative))),
                                      bounds=(s[j - 1], s[j + 1]), method="bounded", options={"xatol": 1e-12 * L})
                val = float(self.piece_value(i, res.x, derivative))
                if abs(val) >= abs(cand[1]):
                    cand = (float(res.x), val)
            if abs(cand[1]) > abs(best[1]):
                best = (float(self.knots[i] + cand[0]), cand[1])
        return best

    def sample(self, n: int = 1000, derivative: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """(t, x^(m)(t)) on n points of [knots[0], knots[-1]] (right limits at the knots)."""
        t = np.linspace(self.knots[0], self.knots[-1], int(n))
        vals = self(t[:-1], derivative)
        last = self(t[-1:], derivative, side="left")
        return t, np.concatenate([vals, last])

    def to_dict(self) -> dict:
        return {"name": self.name, "knots": self.knots.tolist(), "poly": self.poly.tolist(),
                "freq": self.freq.tolist(), "cos": self.cos.tolist(), "sin": self.sin.tolist(),
                "periodic": self.periodic, "continuity": self.continuity()}
