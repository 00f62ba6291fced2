"""Exact Galerkin integrals of piecewise-affine element laws for harmonic balance (no AFT sampling).

A gap, a one-sided spring or a Kelvin-Voigt stop has a law that is affine in (s, s') on each interval of
its coordinate s between the breaks b_i (``Element.piecewise_law``): ``F = a_p + b_p s + c_p s'`` on piece
p.  On an HB orbit s(theta) is a trigonometric polynomial of degree H, so the Galerkin projection

    F_j = 1/(2 pi) int_0^{2 pi} F(s(theta), s'(theta)) e^{-i j theta} d theta

is a sum over the intervals between the *crossings* theta_c (roots of s(theta) = b_i) of integrals of
trigonometric polynomials, in closed form: with ``X_p(j) = 1/(2 pi) int_{piece p} e^{-i j theta}`` (the
Fourier coefficients of the indicator of piece p, ``(e^{-i j theta_b} - e^{-i j theta_a}) / (-2 pi i j)``
per interval), ``F_j = sum_p a_p X_p(j) + sum_l (b_p s_l + c_p v_l) X_p(j - l)`` (s_l, v_l the complex
coefficients of s and s').  The crossings are bracketed on the HB sample grid (sign changes, and local
extrema of the samples whose true extremum, found by Newton on s_theta = 0, passes a break: a contact
shorter than a sample interval is not missed) and polished by safeguarded Newton on the polynomial to
1e-15 rad.  The residual is then exact up to rounding, whatever the number of samples, and smooth in
the coefficients: sampling a kink (error ~ 1/N^2, a Jacobian that jumps when a sample enters contact)
made discrete HB branches zig-zag with spurious folds near resonance.

Jacobian (exact): ``dF_j/dA_l`` = the Galerkin matrix of dF/ds = b_p (and of dF/ds' = c_p with the
derivative of the basis), whose spectrum is ``sum_p b_p X_p`` -- the same product-to-sum map as the
sampled AFT (:meth:`HBModel.element_blocks`) with this exact spectrum in place of the DFT of samples --
plus, where the law jumps across a crossing (a dashpot switched on at contact: ``F`` jumps by c s'),
the moving-boundary term ``-dF_c e^{-i j theta_c} phi_l(theta_c) / (2 pi s_theta(theta_c))``
(d theta_c / d A_l = -phi_l / s_theta).  Continuous laws have no such term.
"""
from __future__ import annotations

import numpy as np

from ..nonsmooth.elements.base import PiecewiseAffineLaw

TWO_PI = 2.0 * np.pi


def to_complex(C):
    """Complex coefficients c_l, l = -H..H (index l + H) of the real series [a0, a1, b1, ..., aH, bH]."""
    C = np.asarray(C, float)
    H = (C.shape[-1] - 1) // 2
    out = np.empty(C.shape[:-1] + (2 * H + 1,), complex)
    pos = 0.5 * (C[..., 1::2] - 1j * C[..., 2::2])
    out[..., H] = C[..., 0]
    out[..., H + 1:] = pos
    out[..., :H] = np.conj(pos[..., ::-1])
    return out


def to_real(F):
    """Real series [F0, 2 Re F1, -2 Im F1, ...] of the complex coefficients F_j, j = 0..J."""
    J = F.shape[-1] - 1
    out = np.empty(F.shape[:-1] + (2 * J + 1,))
    out[..., 0] = F[..., 0].real
    out[..., 1::2] = 2.0 * F[..., 1:].real
    out[..., 2::2] = -2.0 * F[..., 1:].imag
    return out


def trig_eval(C, theta, deriv: int = 0):
    """Values (deriv = 0), first or second theta-derivatives of the real series C at the phases theta."""
    C = np.asarray(C, float)
    H = (C.size - 1) // 2
    k = np.arange(1, H + 1)
    kt = np.multiply.outer(np.asarray(theta, float), k)
    c, s = np.cos(kt), np.sin(kt)
    a, b = C[1::2], C[2::2]
    if deriv == 0:
        return C[0] + c @ a + s @ b
    if deriv == 1:
        return c @ (k * b) - s @ (k * a)
    return -(c @ (k * k * a) + s @ (k * k * b))


def basis_at(H: int, theta):
    """[1, cos th, sin th, ..., cos H th, sin H th] at the phases theta: (len(theta), 2H+1)."""
    th = np.atleast_1d(np.asarray(theta, float))
    out = np.ones((th.size, 2 * H + 1))
    kt = np.multiply.outer(th, np.arange(1, H + 1))
    out[:, 1::2] = np.cos(kt)
    out[:, 2::2] = np.sin(kt)
    return out


def _value_slope(C, theta):
    """(s, s_theta) of the real series C at the phases theta (one cos/sin table)."""
    H = (C.size - 1) // 2
    k = np.arange(1, H + 1)
    kt = np.multiply.outer(theta, k)
    c, s = np.cos(kt), np.sin(kt)
    a, b = C[1::2], C[2::2]
    return C[0] + c @ a + s @ b, c @ (k * b) - s @ (k * a)


_NONE = (np.zeros(0), np.zeros(0, int), np.zeros(0))


def crossings(C, samples, breaks, tol: float = 1e-14, maxit: int = 30):
    """Roots of ``s(theta) = b`` over one period for every break b of the trigonometric polynomial with
    real coefficients C, sampled at ``samples`` (N equidistant phases from 0).  Returns (theta in
    [0, 2 pi) sorted, break index, s_theta at the root) -- bracketed by the sample signs and by the
    samples' local extrema (module docstring), polished by Newton (safeguarded by the bracket when plain
    Newton does not settle in three steps)."""
    C = np.asarray(C, float)
    S = np.asarray(samples, float)
    B = np.asarray(breaks, float)
    N = S.size
    h = TWO_PI / N
    H = (C.size - 1) // 2
    k = np.arange(1, H + 1)
    a, b = C[1::2], C[2::2]
    reach = 0.5 * h * h * float(k * k @ (np.abs(a) + np.abs(b)))
    lo_s, hi_s = S.min(), S.max()
    if np.all((B > hi_s + reach) | (B < lo_s - reach)):  # every break clear of the orbit: no crossing
        return _NONE
    Sc = np.concatenate([S, S[:1]])                      # closed: sample N is sample 0
    d = Sc[:, None] - B                                  # (N + 1, breaks)
    above = d > 0
    n, bi = np.nonzero(above[:-1] != above[1:])
    lo = n * h
    flo, fhi = d[n, bi], d[n + 1, bi]
    hi = lo + h
    # a contact shorter than a sample interval: a local extremum of the samples within the reach of the
    # curvature bound (|s - s_n| <= max|s''| h^2 / 2 near an extremum) of a break it does not cross
    if np.any(np.abs(d) <= reach):
        lo, hi, flo, fhi, bi = _grazing_brackets(C, S, B, h, reach, lo, hi, flo, fhi, bi)
    if lo.size == 0:
        return _NONE
    bv = B[bi]
    den = fhi - flo
    th = lo - flo * (hi - lo) / np.where(den != 0, den, 1.0)
    ka, kb = k * a, k * b
    c0 = C[0] - bv
    for it in range(3):                                  # plain Newton from the secant of the bracket
        kt = np.multiply.outer(th, k)
        cs, sn = np.cos(kt), np.sin(kt)
        d1 = cs @ kb - sn @ ka
        step = (c0 + cs @ a + sn @ b) / d1
        th = th - step
        big = np.max(np.abs(step))
        if it and big <= 1e-9:             # quadratic convergence: the error is now ~ step^2
            break
    if not (big <= 1e-9 and np.all(th >= lo - 1e-12) and np.all(th <= hi + 1e-12)):
        th = _bracketed_newton(C, bv, lo, hi, flo, tol, maxit)
        _, d1 = _value_slope(C, th)
    th = np.mod(th, TWO_PI)
    order = np.argsort(th)
    return th[order], bi[order], d1[order]


def _grazing_brackets(C, S, B, h, reach, lo, hi, flo, fhi, bi):
    """Add the brackets of a contact between two samples: a local extremum of the samples, on one side of
    a break with both neighbours, whose true extremum (Newton on s_theta = 0) crosses it."""
    prev, nxt = np.roll(S, 1), np.roll(S, -1)
    ext = ((S >= prev) & (S >= nxt)) | ((S <= prev) & (S <= nxt))
    side = S[:, None] > B
    same = (side == (prev[:, None] > B)) & (side == (nxt[:, None] > B))
    ne, be = np.nonzero(ext[:, None] & same & (np.abs(S[:, None] - B) <= reach))
    if ne.size == 0:
        return lo, hi, flo, fhi, bi
    th = ne * h
    for _ in range(3):                     # Newton on s_theta = 0 from the extreme sample
        d1, d2 = trig_eval(C, th, 1), trig_eval(C, th, 2)
        ok = d2 != 0
        th = np.clip(np.where(ok, th - d1 / np.where(ok, d2, 1.0), th), (ne - 1) * h, (ne + 1) * h)
    v = trig_eval(C, th) - B[be]
    cross = (v > 0) != side[ne, be]
    if not np.any(cross):
        return lo, hi, flo, fhi, bi
    e, t, b2, v2 = ne[cross], th[cross], be[cross], v[cross]
    return (np.concatenate([lo, (e - 1) * h, t]), np.concatenate([hi, t, (e + 1) * h]),
            np.concatenate([flo, prev[e] - B[b2], v2]), np.concatenate([fhi, v2, nxt[e] - B[b2]]),
            np.concatenate([bi, b2, b2]))


def _bracketed_newton(C, bv, lo, hi, flo, tol, maxit):
    """Newton on s(theta) = bv kept inside the brackets [lo, hi] (bisection when it leaves them)."""
    den = np.ones_like(lo)
    th = 0.5 * (lo + hi)
    for _ in range(maxit):
        f, d1 = _value_slope(C, th)
        f -= bv
        same = (f > 0) == (flo > 0)
        lo = np.where(same, th, lo)
        flo = np.where(same, f, flo)
        hi = np.where(same, hi, th)
        ok = d1 != 0
        tn = th - f / np.where(ok, d1, den)
        bad = ~ok | ~(tn >= lo) | ~(tn <= hi)
        if np.any(bad):
            tn = np.where(bad, 0.5 * (lo + hi), tn)
        step = np.max(np.abs(tn - th))
        th = tn
        if step <= tol:
            break
    return th


def pieces(C, samples, law: PiecewiseAffineLaw):
    """The partition of the period by the law's pieces: (crossing phases, their break index, s_theta
    there, piece index of the interval after each crossing).  Without crossings the phases are empty and
    the single piece is returned as a one-element array."""
    th, bi, d1 = crossings(C, samples, law.breaks)
    if th.size == 0:
        return th, bi, d1, np.array([int(law.piece(np.asarray(samples)[0]))])
    up = d1 > 0
    after = bi + up
    before = bi + ~up
    if after[-1] != before[0] or np.any(after[:-1] != before[1:]):   # inconsistent: read the piece at midpoints
        mid = 0.5 * (th + np.append(th[1:], th[0] + TWO_PI))
        after = law.piece(trig_eval(C, mid))
    return th, bi, d1, after


def interval_spectra(th, J: int):
    """chi[c, j] = 1/(2 pi) int_{theta_c}^{theta_{c+1}} e^{-i j theta} d theta, j = 0..J, of the intervals
    between consecutive crossings th (sorted; the last interval wraps around)."""
    j = np.arange(1, J + 1)
    E = np.exp(np.multiply.outer(np.append(th, th[0]), -1j * j))   # (nc + 1, J): the first again at the end
    chi = np.empty((th.size, J + 1), complex)
    chi[:, 1:] = (E[1:] - E[:-1]) * (1j / (TWO_PI * j))
    t2 = np.append(th, th[0] + TWO_PI)
    chi[:, 0] = (t2[1:] - t2[:-1]) / TWO_PI
    return chi


def indicator_spectra(th, after, n_pieces: int, J: int):
    """X[p, j] = 1/(2 pi) int_{piece p} e^{-i j theta} d theta, j = 0..J, for the partition (th, after)."""
    X = np.zeros((n_pieces, J + 1), complex)
    if th.size == 0:
        X[int(after[0]), 0] = 1.0
        return X
    chi = interval_spectra(th, J)
    for p in range(n_pieces):
        X[p] = chi[after == p].sum(axis=0)
    return X


def _continuous(a, b, breaks) -> bool:
    """Whether a + b s is continuous across every break (no jump term in the Jacobian)."""
    for i, x in enumerate(breaks):
        left, right = a[i] + b[i] * x, a[i + 1] + b[i + 1] * x
        if abs(left - right) > 1e-14 * max(abs(left), abs(right), 1e-300) and left != right:
            return False
    return True


class ExactProjection:
    """The exact Galerkin projection of one piecewise-affine element on H harmonics (module docstring)."""

    def __init__(self, law: PiecewiseAffineLaw, H: int):
        self.law = law
        self.H = int(H)
        self.a = np.asarray(law.a, float)
        self.b = np.asarray(law.b, float)
        self.c = np.asarray(law.c, float)
        self.P = self.a.size
        self._idx = {}
        self._to_c = to_complex(np.eye(2 * H + 1)).T            # complex coefficients c_l = _to_c @ C
        self._has_c = bool(np.any(self.c != 0))
        # a law that jumps across a break (a dashpot switched on at contact, or a discontinuous force)
        self._jumps = self._has_c or not _continuous(self.a, self.b, np.asarray(law.breaks, float))

    def _toeplitz_index(self, J):
        """index into X_full (d = -H .. J + H) of X(j - l), j = 0..J, l = -H..H."""
        t = self._idx.get(J)
        if t is None:
            H = self.H
            jj = np.arange(J + 1)[:, None]
            ll = np.arange(-H, H + 1)[None, :]
            t = self._idx[J] = jj - ll + H
        return t

    def evaluate(self, Cs, Cv, samples, J: int | None = None, Cw=None, jac: bool = True):
        """Projection of F on harmonics 0..J (default H) as a real series, and with ``jac`` the exact
        spectra (complex, j = 0..2H) of dF/ds and dF/ds' and the moving-boundary matrix (or None);
        ``Cw``: the real series of ds'/domega -> also dF/domega projected on 0..H.
        Cs, Cv: real series (2H+1) of s and s' (in theta).

        With the spectra of the piecewise-constant coefficients ``A = sum_p a_p X_p``, ``B = sum_p b_p X_p``
        (= the spectrum of dF/ds) and ``G = sum_p c_p X_p`` (of dF/ds'), ``F_j = A_j + sum_l B_{j-l} s_l +
        G_{j-l} v_l``: two Toeplitz products, whatever the number of pieces."""
        H = self.H
        J = H if J is None else int(J)
        th, bi, d1, after = pieces(Cs, samples, self.law)
        Jx = max(J + H, 2 * H)
        if th.size:
            ABG = np.stack([self.a[after], self.b[after], self.c[after]]) @ interval_spectra(th, Jx)   # (3, Jx+1)
        else:
            p = int(after[0])
            ABG = np.zeros((3, Jx + 1), complex)
            ABG[:, 0] = self.a[p], self.b[p], self.c[p]
        full = np.concatenate([np.conj(ABG[:, H:0:-1]), ABG], axis=1)    # d = -H .. Jx
        idx = self._toeplitz_index(J)
        Fc = ABG[0, :J + 1] + full[1][idx] @ (self._to_c @ Cs)
        if self._has_c:
            Gt = full[2][idx]
            Fc += Gt @ (self._to_c @ Cv)
        out = {"F": to_real(Fc)}
        if Cw is not None:
            if self._has_c:
                Gw = Gt[:H + 1] if J >= H else full[2][self._toeplitz_index(H)]
                out["Fw"] = to_real(Gw @ (self._to_c @ Cw))
            else:
                out["Fw"] = np.zeros(2 * H + 1)
        if jac:
            out["spec_s"] = ABG[1, :2 * H + 1]
            out["spec_v"] = ABG[2, :2 * H + 1]
            out["jump"] = None
            if th.size and self._jumps:
                before = np.append(after[-1:], after[:-1])
                s_c = np.asarray(self.law.breaks, float)[bi]
                v_c = trig_eval(Cv, th)
                dF = (self.a[before] - self.a[after]) + (self.b[before] - self.b[after]) * s_c \
                    + (self.c[before] - self.c[after]) * v_c
                if np.any(dF != 0):
                    phi = basis_at(H, th)                                       # (nc, m)
                    w = np.full(2 * H + 1, 2.0)
                    w[0] = 1.0
                    wt = -dF / (TWO_PI * d1)
                    out["jump"] = (w[:, None] * phi.T * wt[None, :]) @ phi      # (m, m)
        out["crossings"] = th
        return out
