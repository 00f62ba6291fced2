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


def crossings(C, samples, breaks, tol: float = 1e-14, maxit: int = 30):
    """Roots of ``s(theta) = b`` over one period for every break b of the trigonometric polynomial with
    real coefficients C, sampled at ``samples`` (N equidistant phases from 0).  Returns (theta in
    [0, 2 pi) sorted, break index, s_theta at the root) -- bracketed by the sample signs and by the
    samples' local extrema (module docstring), polished by safeguarded Newton to ``tol`` rad."""
    C = np.asarray(C, float)
    S = np.asarray(samples, float)
    B = np.asarray(breaks, float)
    N = S.size
    h = TWO_PI / N
    nxt = np.concatenate([S[1:], S[:1]])
    above = S[:, None] > B[None, :]                     # (N, breaks)
    ab_next = nxt[:, None] > B[None, :]
    n, bi = np.nonzero(above != ab_next)
    lo, hi = n * h, (n + 1) * h
    flo, fhi = S[n] - B[bi], nxt[n] - B[bi]
    # a contact shorter than a sample interval: a local extremum of the samples within the reach of the
    # curvature bound (|s - s_n| <= max|s''| h^2 / 2 near an extremum) of a break it does not cross
    k = np.arange(1, (C.size - 1) // 2 + 1)
    reach = 0.5 * h * h * float(np.sum(k * k * (np.abs(C[1::2]) + np.abs(C[2::2]))))
    near = np.abs(S[:, None] - B[None, :]) <= reach
    if np.any(near):
        prev = np.concatenate([S[-1:], S[:-1]])
        ab_prev = prev[:, None] > B[None, :]
        ext = ((S >= prev) & (S >= nxt))[:, None] & ~above & ~ab_next & ~ab_prev \
            | ((S <= prev) & (S <= nxt))[:, None] & above & ab_next & ab_prev
        ne, be = np.nonzero(ext & near)
        if ne.size:
            th = ne * h
            for _ in range(3):                     # Newton on s_theta = 0 from the extreme sample
                d1, d2 = trig_eval(C, th, 1), trig_eval(C, th, 2)
                ok = d2 != 0
                th = np.where(ok, th - np.where(ok, d1 / np.where(ok, d2, 1.0), 0.0), th)
                th = np.clip(th, (ne - 1) * h, (ne + 1) * h)
            v = trig_eval(C, th) - B[be]
            cross = (v > 0) != above[ne, be]
            if np.any(cross):
                e, t, b2, v2 = ne[cross], th[cross], be[cross], v[cross]
                lo = np.concatenate([lo, (e - 1) * h, t])
                hi = np.concatenate([hi, t, (e + 1) * h])
                flo = np.concatenate([flo, prev[e] - B[b2], v2])
                fhi = np.concatenate([fhi, v2, nxt[e] - B[b2]])
                bi = np.concatenate([bi, b2, b2])
    if lo.size == 0:
        return np.zeros(0), np.zeros(0, int), np.zeros(0)
    bv = B[bi]
    den = np.where(fhi != flo, fhi - flo, 1.0)
    th = np.clip(lo - flo * (hi - lo) / den, lo, hi)
    for _ in range(maxit):
        f, d1 = _value_slope(C, th)
        f -= bv
        same = (f > 0) == (flo > 0)
        lo = np.where(same, th, lo)
        flo = np.where(same, f, flo)
        hi = np.where(same, hi, th)
        ok = d1 != 0
        tn = th - f / np.where(ok, d1, 1.0)
        bad = ~ok | ~(tn >= lo) | ~(tn <= hi)
        if np.any(bad):
            tn = np.where(bad, 0.5 * (lo + hi), tn)
        step = np.max(np.abs(tn - th))
        th = tn
        if step <= tol:
            break
    th = np.mod(th, TWO_PI)
    order = np.argsort(th)
    return th[order], bi[order], d1[order]


def pieces(C, samples, law: PiecewiseAffineLaw):
    """The partition of the period by the law's pieces: (crossing phases, their break index, s_theta
    there, piece index of the interval after each crossing).  Without crossings the phases are empty and
    the single piece is returned as a one-element array."""
    th, bi, d1 = crossings(C, samples, law.breaks)
    if th.size == 0:
        return th, bi, d1, np.array([int(law.piece(np.asarray(samples)[0]))])
    after = np.where(d1 > 0, bi + 1, bi)
    before = np.where(d1 > 0, bi, bi + 1)
    if not np.array_equal(after, np.roll(before, -1)):     # inconsistent order: read the piece at midpoints
        mid = 0.5 * (th + np.append(th[1:], th[0] + TWO_PI))
        after = law.piece(trig_eval(C, mid))
    return th, bi, d1, after


def indicator_spectra(th, after, n_pieces: int, J: int):
    """X[p, j] = 1/(2 pi) int_{piece p} e^{-i j theta} d theta, j = 0..J, for the partition (th, after)."""
    X = np.zeros((n_pieces, J + 1), complex)
    if th.size == 0:
        X[int(after[0]), 0] = 1.0
        return X
    j = np.arange(1, J + 1)
    E = np.exp(-1j * np.multiply.outer(th, j))                  # (nc, J)
    Eb = np.roll(E, -1, axis=0)
    length = np.append(np.diff(th), th[0] + TWO_PI - th[-1])
    chi = (Eb - E) / (-TWO_PI * 1j * j)
    np.add.at(X[:, 1:], after, chi)
    np.add.at(X[:, 0], after, length / TWO_PI)
    return X


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
        Cs, Cv: real series (2H+1) of s and s' (in theta)."""
        H = self.H
        J = H if J is None else int(J)
        th, bi, d1, after = pieces(Cs, samples, self.law)
        Jx = max(J + H, 2 * H)
        X = indicator_spectra(th, after, self.P, Jx)              # (P, Jx + 1), j >= 0
        Xf = np.concatenate([np.conj(X[:, H:0:-1]), X], axis=1)    # d = -H .. Jx
        cs, cv = to_complex(Cs), to_complex(Cv)
        T = Xf[:, self._toeplitz_index(J)]                         # (P, J+1, 2H+1)
        u = self.b[:, None] * cs[None, :] + self.c[:, None] * cv[None, :]
        Fc = self.a @ X[:, :J + 1] + np.einsum("pjl,pl->j", T, u)
        out = {"F": to_real(Fc)}
        if Cw is not None:
            cw = to_complex(Cw)
            Tw = T[:, :H + 1] if J >= H else Xf[:, self._toeplitz_index(H)]
            out["Fw"] = to_real(np.einsum("pjl,pl->j", Tw, self.c[:, None] * cw[None, :]))
        if jac:
            out["spec_s"] = self.b @ X[:, :2 * H + 1]
            out["spec_v"] = self.c @ X[:, :2 * H + 1]
            out["jump"] = None
            if th.size:
                before = np.roll(after, 1)
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
