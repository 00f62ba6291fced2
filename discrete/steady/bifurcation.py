"""Bifurcations of periodic orbits along a continued branch: classification by test functions, location
on the branch, and the directions of branch switching.

Test functions (Kuznetsov, *Elements of Applied Bifurcation Theory*, 3rd ed., §10.2; Govaerts 2000),
evaluated at every branch point from the Floquet multipliers mu_i and the continuation's bordered
Jacobian:

* **fold** (limit point): a real multiplier through +1 *and* the frequency component of the tangent
  changes sign -- located by Newton on the minimally extended system (:func:`~.continuation.locate_fold`);
* **branch point** (a symmetry-breaking pitchfork or a transcritical point): a real multiplier through +1
  without a fold; the algebraic test ``psi_BP = det [Jx Jw; t^T]`` (t the oriented tangent) changes sign
  there and not at a fold -- located by the Illinois (regula falsi) method on psi_BP along the branch
  segment, each trial point corrected on the plane orthogonal to the segment;
* **period doubling** (flip): ``psi_PD = prod (mu_i + 1)`` changes sign (a real multiplier through -1);
* **Neimark-Sacker** (torus): ``psi_NS = prod_{i<j} (mu_i mu_j - 1)`` changes sign and the pair with
  mu_i mu_j closest to 1 is complex (a real pair with mu_i mu_j = 1 is a neutral saddle, not a bifurcation).

PD and NS are located like BP, on their test function (multipliers of the corrected orbit).

Branch switching: at a branch point the null space of ``[Jx Jw]`` is two-dimensional; the direction of
the other branch is the unit vector of that space orthogonal to the branch's tangent (its two smallest
right singular vectors).  A period doubling of an orbit of period T is a branch point of the same orbit
written with period 2T (every odd harmonic of omega/2 zero): :func:`embed_doubled` maps HB coefficients
to that representation, where the period-doubled branch is switched onto like any branch point.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import SolverError
from .continuation import correct_on_plane

KINDS = ("fold", "branch_point", "period_doubling", "neimark_sacker")
LABELS = {"fold": "fold", "branch_point": "branch point", "period_doubling": "period doubling",
          "neimark_sacker": "Neimark-Sacker"}


@dataclass
class Bifurcation:
    """A bifurcation on a branch: its type, frequency and response, the critical multiplier, the test
    function that located it and whether the location converged (else: interpolated between points)."""

    kind: str
    omega: float
    response: float = float("nan")
    multiplier: complex | None = None
    test: str = ""
    located: bool = True
    index: int = -1                     # branch points index, index + 1 bracket it
    x: np.ndarray | None = field(default=None, repr=False)
    note: str = ""
    harmonics: int | None = None        # HB: the harmonics it was located with
    model: object = field(default=None, repr=False, compare=False)   # HB: the model of x
    check: tuple = (None, None)         # HB: (omega re-located with more harmonics, those harmonics)

    def to_dict(self) -> dict:
        d = {"type": self.kind, "omega_rad_s": float(self.omega),
             "response": None if not np.isfinite(self.response) else float(self.response),
             "test_function": self.test, "located": bool(self.located)}
        if self.multiplier is not None and np.isfinite(self.multiplier):
            d["critical_multiplier"] = {"re": float(np.real(self.multiplier)), "im": float(np.imag(self.multiplier))}
        if self.harmonics is not None:
            d["harmonics"] = int(self.harmonics)
        if self.check[1] is not None:
            w, H = self.check
            d["omega_check_rad_s"] = None if w is None else float(w)
            d["check_harmonics"] = int(H)
            d["estimate"] = None if w is None else float(abs(w - self.omega) / abs(self.omega))
        if self.note:
            d["note"] = self.note
        return d

    def line(self, ref: float | None = None) -> str:
        z = f" (z = {self.omega / ref:.6g})" if ref else ""
        mu = ""
        if self.multiplier is not None and np.isfinite(self.multiplier):
            m = self.multiplier
            mu = f", critical multiplier {m.real:.4g}" + (f" {'+' if m.imag >= 0 else '-'} {abs(m.imag):.4g}i" if abs(m.imag) > 1e-9 else "")
        where = "" if self.located else " (interpolated between branch points)"
        return (f"{LABELS[self.kind]} at omega = {self.omega:.8g} rad/s{z}, response = {self.response:.6g}{mu}"
                f"{where}{'; ' + self.note if self.note else ''}")


# ------------------------------------------------------------------ test functions
def _sign_of_product(terms) -> float:
    """sign of Re prod(terms) for terms closed under conjugation (the product is real)."""
    terms = np.asarray(terms, complex)
    if terms.size == 0:
        return 1.0
    if np.any(terms == 0):
        return 0.0
    return float(np.sign(np.cos(np.sum(np.angle(terms)))))


def psi_plus(mu) -> float:
    """prod (mu_i - 1): a real multiplier through +1 changes its sign (value, real)."""
    return float(np.real(np.prod(np.asarray(mu, complex) - 1.0)))


def psi_pd(mu) -> float:
    """prod (mu_i + 1): a real multiplier through -1 changes its sign."""
    return float(np.real(np.prod(np.asarray(mu, complex) + 1.0)))


_TRIU: dict = {}


def _pairs(mu):
    mu = np.asarray(mu, complex)
    ij = _TRIU.get(mu.size)
    if ij is None:
        ij = _TRIU[mu.size] = np.triu_indices(mu.size, 1)
    i, j = ij
    return mu[i] * mu[j] - 1.0, i, j


def psi_ns(mu) -> float:
    """prod_{i<j} (mu_i mu_j - 1): a complex pair through the unit circle changes its sign."""
    t, _, _ = _pairs(mu)
    return float(np.real(np.prod(t))) if t.size else 1.0


def ns_pair_complex(mu) -> bool:
    """Whether the pair with mu_i mu_j closest to 1 is a complex-conjugate pair (an NS, not a neutral saddle)."""
    t, i, j = _pairs(mu)
    if t.size == 0:
        return False
    k = int(np.argmin(np.abs(t)))
    mu = np.asarray(mu, complex)
    return abs(mu[i[k]].imag) > 1e-9 * max(1.0, abs(mu[i[k]])) and abs(mu[i[k]] - np.conj(mu[j[k]])) < \
        1e-6 * max(1.0, abs(mu[i[k]]))


def critical(mu, kind: str):
    """The multiplier that crosses the unit circle for a bifurcation of ``kind``."""
    mu = np.asarray(mu, complex)
    if kind in ("fold", "branch_point"):
        return complex(mu[np.argmin(np.abs(mu - 1.0))])
    if kind == "period_doubling":
        return complex(mu[np.argmin(np.abs(mu + 1.0))])
    cand = mu[np.abs(mu.imag) > 1e-12]
    if cand.size == 0:
        return complex(mu[np.argmin(np.abs(np.abs(mu) - 1.0))])
    return complex(cand[np.argmin(np.abs(np.abs(cand) - 1.0))])


def detect(mus, bp_signs, fold_index) -> list:
    """[(index, kind, test name)] of the intervals (points index, index + 1) of a branch where a test
    function changes sign.  ``mus``: multipliers per point (None where not computed); ``bp_signs``: the
    sign of psi_BP per point (None: not available); ``fold_index``: the intervals with a fold."""
    out = []
    folds = set(fold_index)
    n = len(mus)
    # the test functions once per point (signs; None where the multipliers were not computed)
    spd = [None if mu is None else np.sign(psi_pd(mu)) for mu in mus]
    sns = [None if mu is None else np.sign(psi_ns(mu)) for mu in mus]
    spl = [None if mu is None else np.sign(psi_plus(mu)) for mu in mus]
    for i in range(n - 1):
        a, b = mus[i], mus[i + 1]
        if a is None or b is None:
            continue
        if spd[i] * spd[i + 1] < 0:
            out.append((i, "period_doubling", "psi_PD = prod(mu + 1)"))
        if sns[i] * sns[i + 1] < 0 and (ns_pair_complex(a) or ns_pair_complex(b)):
            out.append((i, "neimark_sacker", "psi_NS = prod(mu_i mu_j - 1)"))
    bp = set()
    if bp_signs is not None:
        for i in range(n - 1):
            sa, sb = bp_signs[i], bp_signs[i + 1]
            if sa is not None and sb is not None and sa * sb < 0 and i not in folds:
                bp.add(i)
                out.append((i, "branch_point", "psi_BP = det [Jx Jw; t]"))
    # a real multiplier through +1 that neither a fold nor an algebraic branch point explains
    for i in range(n - 1):
        a, b = mus[i], mus[i + 1]
        if a is None or b is None or i in folds or i in bp:
            continue
        if spl[i] * spl[i + 1] < 0 and not ({i - 1, i + 1} & (folds | bp)):
            out.append((i, "branch_point", "psi_+ = prod(mu - 1)"))
    return sorted(out)


# ------------------------------------------------------------------ location
def hermite_point(ua, ub, ta, tb, length, sig):
    """The point at the fraction ``sig`` in [0, 1] of the cubic Hermite curve between the branch points ua
    and ub (scaled variables) with unit tangents ta, tb and chord ``length``."""
    s2, s3 = sig * sig, sig * sig * sig
    return ((2 * s3 - 3 * s2 + 1) * ua + (s3 - 2 * s2 + sig) * length * np.asarray(ta)
            + (-2 * s3 + 3 * s2) * ub + (s3 - s2) * length * np.asarray(tb))


def locate_on_segment(psi, fun, xa, wa, xb, wb, xscale, wscale, fa=None, fb=None, tol=1e-8, maxit=60,
                      ta=None, tb=None):
    """The root of ``psi(x, w)`` between the branch points a and b: Illinois on the fraction sigma of the
    segment, each trial point corrected on the plane orthogonal to the segment through the predictor at
    sigma -- the cubic Hermite curve of the two points and their scaled tangents ta, tb if given, else
    the chord.  Returns (x, w, sigma, converged)."""
    xs = np.asarray(xscale, float)
    ua = np.concatenate([np.asarray(xa, float) / xs, [wa / wscale]])
    ub = np.concatenate([np.asarray(xb, float) / xs, [wb / wscale]])
    d = ub - ua
    nd = np.linalg.norm(d)
    if nd == 0:
        return np.asarray(xa, float), wa, 0.0, False
    d /= nd
    cache = {}

    def at(sig):
        if sig == 0.0:
            return np.asarray(xa, float), wa
        if sig == 1.0:
            return np.asarray(xb, float), wb
        if ta is not None and tb is not None:
            u = hermite_point(ua, ub, ta, tb, nd, sig)
        else:
            u = ua + sig * (ub - ua)
        x, w, _ = correct_on_plane(fun, u[:-1] * xs, u[-1] * wscale, d, xs, wscale, tol=1e-8)
        return x, w

    def f(sig):
        x, w = at(sig)
        v = psi(x, w)
        cache[sig] = (x, w)
        return v

    a, b = 0.0, 1.0
    fa_ = f(0.0) if fa is None else fa
    fb_ = f(1.0) if fb is None else fb
    if not (np.isfinite(fa_) and np.isfinite(fb_)) or fa_ * fb_ > 0:
        return np.asarray(xa, float), wa, 0.0, False
    side, c = 0, 0.5
    for _ in range(maxit):
        c = (fa_ * b - fb_ * a) / (fa_ - fb_) if fa_ != fb_ else 0.5 * (a + b)
        if not a < c < b:
            c = 0.5 * (a + b)
        try:
            fc = f(c)
        except (SolverError, np.linalg.LinAlgError):
            # the plane corrector is singular at a branch point itself: close to it, the bracket is the answer
            near = [k for k in cache if a <= k <= b]
            if near and b - a <= 1e-3:
                c = min(near, key=lambda k: abs(k - 0.5 * (a + b)))
                x, w = cache[c]
                return x, w, c, True
            c = 0.5 * (a + b)
            try:
                fc = f(c)
            except (SolverError, np.linalg.LinAlgError):
                return np.asarray(xa, float) if c < 0.5 else np.asarray(xb, float), wa if c < 0.5 else wb, c, False
        if fc == 0:
            break
        if fc * fb_ > 0:                # Illinois: halve the retained end's value on a repeated side
            b, fb_ = c, fc
            if side == -1:
                fa_ *= 0.5
            side = -1
        else:
            a, fa_ = c, fc
            if side == 1:
                fb_ *= 0.5
            side = 1
        if b - a <= tol:
            break
    else:
        x, w = cache[c]
        return x, w, c, False
    x, w = cache[c]
    return x, w, c, True


def _bordered(fun, x, w, t, xscale, wscale):
    xs = np.asarray(xscale, float)
    n = xs.size
    _, Jx, Jw = fun(x, w)
    A = np.zeros((n + 1, n + 1))
    A[:n, :n] = Jx * xs[None, :]
    A[:n, n] = Jw * wscale
    A[n] = t
    return np.linalg.slogdet(A)


def bordered_det(fun, x, w, t, xscale, wscale, log_ref: float = 0.0) -> float:
    """psi_BP = det [Jx Jw; t] in the scaled variables (t the oriented scaled tangent), divided by
    exp(log_ref) (a reference |det|, e.g. at the segment's start: the same root, no overflow)."""
    sgn, logdet = _bordered(fun, x, w, t, xscale, wscale)
    return float(sgn * np.exp(logdet - log_ref))


def log_abs_det(fun, x, w, t, xscale, wscale) -> float:
    """log |det [Jx Jw; t]| (the reference of :func:`bordered_det`)."""
    sgn, logdet = _bordered(fun, x, w, t, xscale, wscale)
    return float(logdet) if sgn != 0 and np.isfinite(logdet) else 0.0


def switch_direction(fun, x, w, t, xscale, wscale):
    """The scaled direction of the other branch through the branch point (x, w): the unit vector of the
    two-dimensional null space of [Jx Jw] (its two smallest right singular vectors) orthogonal to the
    scaled tangent t of the known branch; with the ratio of the two smallest singular values (small at a
    genuine branch point)."""
    xs = np.asarray(xscale, float)
    n = xs.size
    _, Jx, Jw = fun(x, w)
    A = np.hstack([Jx * xs[None, :], (Jw * wscale)[:, None]])
    _, sv, Vt = np.linalg.svd(A)
    V = Vt[-2:].T                         # (n+1, 2): null space of the n x (n+1) matrix (2 smallest)
    tp = V @ (V.T @ t)
    tp /= max(np.linalg.norm(tp), 1e-300)
    other = V[:, 0] - tp * (tp @ V[:, 0])
    if np.linalg.norm(other) < 1e-8:
        other = V[:, 1] - tp * (tp @ V[:, 1])
    other /= np.linalg.norm(other)
    ratio = sv[-1] / sv[-2] if sv.size >= 2 and sv[-2] > 0 else 0.0
    return other, ratio


def embed_doubled(X, n: int, H: int):
    """HB coefficients (n, 2H+1) of period T as coefficients (n, 4H+1) of the same orbit written with
    period 2T (harmonic k of omega/nu -> harmonic 2k of omega/(2 nu))."""
    X = np.asarray(X, float).reshape(n, 2 * H + 1)
    Y = np.zeros((n, 4 * H + 1))
    Y[:, 0] = X[:, 0]
    k = np.arange(1, H + 1)
    Y[:, 2 * (2 * k) - 1] = X[:, 2 * k - 1]
    Y[:, 2 * (2 * k)] = X[:, 2 * k]
    return Y.ravel()


def pad_harmonics(X, n: int, H: int, H_new: int):
    """HB coefficients (n, 2H+1) padded with zero harmonics to H_new (or truncated)."""
    X = np.asarray(X, float).reshape(n, 2 * H + 1)
    Y = np.zeros((n, 2 * H_new + 1))
    k = min(H, H_new)
    Y[:, :2 * k + 1] = X[:, :2 * k + 1]
    return Y.ravel()
