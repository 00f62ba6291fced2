"""Transfer-matrix analysis of a single-connected chain with branches (§10.1-10.3, 10.6).

A :class:`Chain` is a list of elements (:mod:`discrete.transfer.elements`) from the input
section 0 to the output section, with a boundary condition at each end ("clamped": a = 0,
"free": Q = 0; the four boundary cases of §10.2 are the four combinations).

Numerics (why not the literal product Gamma = Gamma_n ... Gamma_1 of (10.18)):

* **Normalised propagation.**  The book propagates one boundary vector (10.19); for long
  chains its entries still grow like |eta|^n (10.31) and overflow for n in the hundreds.
  Here every section carries the *line* alpha a + beta Q = gamma of states compatible with
  everything on the input side (a Riccati/impedance form).  It is rescaled by a positive
  factor after each element, so it never overflows, and a branch is combined without
  division, so the poles of J*(p) (10.16) are harmless: the end value
  f(p) = alpha_end (free end) or beta_end (clamped end) is continuous, bounded by 1 and
  vanishes exactly at the natural frequencies ("normalised boundary residual").
* **Root counting (Wittrick-Williams).**  The number of natural frequencies below p is the
  number of negative pivots of the condensed dynamic stiffness along the chain plus the
  clamped-end eigenvalue counts J0 of members (continuous shaft segments) and branches
  (mechanisms, each condensed the same way from its far end).  Bisection on this count finds
  every root, however crowded (the n lower roots of a regular drive condense just below the
  partial frequency k), and never mistakes a pole for a root.
* **Forced response** (10.22)-(10.27): the same line sweep carries the loads in gamma, the end
  condition fixes the end state, and the states are recovered backwards with the stored lines
  (two equations per section, the better-conditioned pair), i.e. a stable version of the
  two-run superposition (10.26)-(10.27).  Complex elements (10.63)-(10.66) are allowed.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import ModelError, SolverError
from .elements import Branch, Ground, Inertia, Load, Member, Ratio

BOUNDARIES = ("clamped", "free")
EPS = np.finfo(float).eps


@dataclass
class Chain:
    elements: list
    start: str = "clamped"
    end: str = "free"

    def __post_init__(self):
        self.elements = list(self.elements)
        for key in ("start", "end"):
            if getattr(self, key) not in BOUNDARIES:
                raise ModelError("chain", key, getattr(self, key), "'clamped' | 'free'")
        if not self.elements:
            raise ModelError("chain", "elements", [], "at least one element")
        if self.start == "clamped" and self.end == "clamped" and not any(isinstance(e, Member) for e in self.elements):
            raise ModelError("chain", "elements", "no member", "an elastic member between two clamped ends")
        known = (Member, Inertia, Ground, Load, Branch, Ratio)
        for i, e in enumerate(self.elements):
            if not isinstance(e, known):
                raise ModelError("chain", f"elements[{i}]", type(e).__name__,
                                 "Spring, Damper, Shaft, Parallel, Inertia, Ground, Load, Branch or Ratio")
        if self.end == "clamped" and not isinstance(self.elements[-1], Member):
            raise ModelError("chain", "elements[-1]", type(self.elements[-1]).__name__,
                             "an elastic member (Spring/Shaft/Damper) next to a clamped end")

    @property
    def real(self) -> bool:
        return all(getattr(e, "real", True) for e in self.elements)


# ----------------------------------------------------------- element matrices
def element_matrix(e, p: float) -> np.ndarray:
    """2x2 transfer matrix of one element at frequency p (a branch as its shunt J*(p) (10.15))."""
    if isinstance(e, Member):
        A, B, C, D = (np.asarray(v).item() for v in e.T(np.array([p])))
        return np.array([[A, B], [C, D]])
    if isinstance(e, Ratio):
        return np.array([[e.ratio, 0.0], [0.0, 1.0 / e.ratio]])
    if isinstance(e, Load):
        return np.eye(2)
    if isinstance(e, Branch):
        s = _condense_stiffness(e, np.array([p]), {})[0][0]
    else:
        s = e.shunt(np.array([p]))[0]
    return np.array([[1.0, 0.0], [s, 1.0]])


def naive_product(chain: Chain, p: float) -> np.ndarray:
    """The literal Gamma = Gamma_n ... Gamma_1 (10.6), for comparison only (overflows for long chains)."""
    G = np.eye(2)
    with np.errstate(over="ignore", invalid="ignore"):
        for e in chain.elements:
            G = element_matrix(e, p) @ G
    return G


# ----------------------------------------------------------- counting sweep
def _condense_stiffness(br: Branch, p, cache):
    """(node stiffness of the branch at its attachment, clamped-attachment eigen count)."""
    key = (id(br), p.ctypes.data, p.size)
    if key in cache:
        return cache[key]
    k0 = np.zeros(p.shape) if br.end == "free" else np.full(p.shape, np.inf)
    k, cnt, _ = _stiffness_sweep(br.elements, p, k0, reverse=True, cache=cache)
    cache[key] = (k, cnt)
    return k, cnt


def _stiffness_sweep(elements, p, k, *, reverse: bool, cache):
    cnt = np.zeros(p.shape, dtype=int)
    piv = np.full(p.shape, np.inf)
    seq = reversed(elements) if reverse else elements
    memo = cache.setdefault(("members", p.ctypes.data, p.size), {})   # repeated (identical) elements
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for e in seq:
            if isinstance(e, Member):
                key = id(e)
                if key not in memo:
                    if not e.real:
                        raise ModelError("chain", "element", type(e).__name__,
                                         "undamped elements for natural frequencies (dampers/complex stiffness only "
                                         "in forced response)")
                    memo[key] = (*e.stiffness(p), e.det_stiffness(p), e.count(p))
                s11, s12, s22, det, c_e = memo[key]
                cnt = cnt + c_e
                fin = np.isfinite(k)
                piv = np.where(fin, k + s11, np.inf)
                # an exactly zero pivot (p exactly at a pole, e.g. p = k) takes its left limit
                piv = np.where(piv == 0, EPS * (np.abs(s11) + 1e-300), piv)
                cnt = cnt + (piv < 0)
                # condensed stiffness s22 - s12^2/piv written as (s22 k + det S)/piv: no cancellation
                # when the node is soft (p -> 0: spring c k/(k + c))
                k = np.where(fin, (s22 * k + det) / piv, s22)
            elif isinstance(e, Ratio):
                k = k * e.ratio**2 if reverse else k / e.ratio**2
            elif isinstance(e, Branch):
                kb, cb = _condense_stiffness(e, p, cache)
                k = k + kb
                cnt = cnt + cb
            elif isinstance(e, (Inertia, Ground)):
                key = id(e)
                if key not in memo:
                    if not e.real:
                        raise ModelError("chain", "element", type(e).__name__, "undamped elements for natural frequencies")
                    memo[key] = e.shunt(p)
                k = k + memo[key]
    return k, cnt, piv


def _count_scalar(chain: Chain, p: float) -> int:
    """count_below for one frequency: the same recurrence on Python floats, with the element
    values (few distinct objects in a regular chain) evaluated once by the vector methods."""
    pa = np.array([p])
    cache: dict = {}
    vals: dict = {}
    k = math.inf if chain.start == "clamped" else 0.0
    cnt = 0
    for e in chain.elements:
        key = id(e)
        if key not in vals:
            if isinstance(e, Member):
                if not e.real:
                    raise ModelError("chain", "element", type(e).__name__, "undamped elements for natural frequencies")
                s11, s12, s22 = (float(v[0]) for v in e.stiffness(pa))
                vals[key] = ("m", s11, s22, float(e.det_stiffness(pa)[0]), int(e.count(pa)[0]))
            elif isinstance(e, Ratio):
                vals[key] = ("r", e.ratio**2)
            elif isinstance(e, Branch):
                kb, cb = _condense_stiffness(e, pa, cache)
                vals[key] = ("s", float(kb[0]), int(cb[0]))
            elif isinstance(e, (Inertia, Ground)):
                if not e.real:
                    raise ModelError("chain", "element", type(e).__name__, "undamped elements for natural frequencies")
                vals[key] = ("s", float(e.shunt(pa)[0]), 0)
            else:
                vals[key] = ("l",)
        v = vals[key]
        if v[0] == "m":
            cnt += v[4]
            if math.isfinite(k):
                piv = k + v[1]
                if piv == 0.0:
                    piv = EPS * (abs(v[1]) + 1e-300)
                cnt += piv < 0
                k = (v[2] * k + v[3]) / piv
            else:
                k = v[2]
        elif v[0] == "r":
            k = k / v[1]
        elif v[0] == "s":
            k = k + v[1]
            cnt += v[2]
    if chain.end == "free" and math.isfinite(k) and k < 0:
        cnt += 1
    return cnt


def count_below(chain: Chain, p) -> np.ndarray:
    """Number of natural frequencies strictly below each p (Wittrick-Williams count)."""
    if np.ndim(p) == 0:
        return np.array([_count_scalar(chain, float(p))])
    p = np.atleast_1d(np.asarray(p, dtype=float))
    k0 = np.full(p.shape, np.inf) if chain.start == "clamped" else np.zeros(p.shape)
    k, cnt, _ = _stiffness_sweep(chain.elements, p, k0, reverse=False, cache={})
    if chain.end == "free":
        cnt = cnt + (np.isfinite(k) & (k < 0))
    return cnt


# ----------------------------------------------------------- line sweep
def _norm(al, be, ga):
    s = np.sqrt(np.abs(al) ** 2 + np.abs(be) ** 2)
    s = np.where(s > 0, s, 1.0)
    return al / s, be / s, ga / s


def _shunt_line(al, be, ga, s, M, bl, forward):
    """Combine a node's line with its shunt s a, load M and branch line bl = (ab, bb, gb)."""
    ab, bb, gb = bl
    if forward:   # Q_R = Q_L + s a - Q_b - M
        return _norm(bb * (al - be * s) - be * ab, be * bb, bb * (ga - be * M) - be * gb)
    # reverse: Q_L from Q_R
    return _norm(bb * (al + be * s) + be * ab, be * bb, bb * (ga + be * M) + be * gb)


def _member_line(al, be, ga, T, forward):
    A, B, C, D = T
    if forward:   # [al, be] T^-1
        return _norm(al * D - be * C, -al * B + be * A, ga)
    return _norm(al * A + be * C, al * B + be * D, ga)


def _branch_line(br: Branch, p, store=None):
    """Line of the branch at its attachment, swept from its far end (reverse orientation)."""
    one = np.ones(p.shape, dtype=complex)
    if br.end == "free":
        line = (0 * one, one, br.load * one)
    else:
        line = (one, 0 * one, 0 * one)
    lines = [line]
    for e in reversed(br.elements):
        line = _apply(e, line, p, forward=False)
        lines.append(line)
    if store is not None:
        store[id(br)] = lines[::-1]   # lines[i] = line before element i (branch orientation)
    return line


def _apply(e, line, p, forward, store=None):
    al, be, ga = line
    if isinstance(e, Member):
        return _member_line(al, be, ga, e.T(p), forward)
    if isinstance(e, Ratio):
        r = e.ratio
        return _norm(al / r, be * r, ga) if forward else _norm(al * r, be / r, ga)
    zero, one = 0 * al, 0 * al + 1
    if isinstance(e, Load):
        return _shunt_line(al, be, ga, zero, e.M, (zero, one, zero), forward)
    if isinstance(e, Branch):
        return _shunt_line(al, be, ga, zero, 0.0, _branch_line(e, p, store), forward)
    return _shunt_line(al, be, ga, e.shunt(p), 0.0, (zero, one, zero), forward)


def _start_line(kind, shape):
    one = np.ones(shape, dtype=complex)
    return (one, 0 * one, 0 * one) if kind == "clamped" else (0 * one, one, 0 * one)


def boundary_residual(chain: Chain, p) -> np.ndarray:
    """Normalised end value f(p) (alpha_end for a free end, beta_end for a clamped one) of the
    load-free line sweep: continuous through the poles of J*(p), |f| <= 1, zero at the roots."""
    p = np.atleast_1d(np.asarray(p, dtype=float))
    line = _start_line(chain.start, p.shape)
    for e in chain.elements:
        line = _apply(e, line, p, forward=True)
    al, be, _ = line
    out = al if chain.end == "free" else be
    return out.real if chain.real else out


def propagate(chain: Chain, p: float, state=(0.0, 1.0)) -> tuple[np.ndarray, float]:
    """The book's vector propagation (10.19) of a start state, normalised after every element:
    returns (unit end state, log10 of the accumulated scale).  Branches act through J*(p)."""
    v = np.asarray(state, dtype=float)
    log10 = 0.0
    for e in chain.elements:
        v = element_matrix(e, p) @ v
        s = np.linalg.norm(v)
        if s == 0 or not np.isfinite(s):
            raise SolverError(f"propagation broke down at p = {p} (state {v})")
        v, log10 = v / s, log10 + np.log10(s)
    return v, log10


# ----------------------------------------------------------- roots
@dataclass
class TMRoots:
    """Natural frequencies of a chain found by count bisection (Wittrick-Williams)."""

    omega_rad_s: np.ndarray
    residuals: np.ndarray          # |f(p)| of the normalised end line at the root (<= 1)
    newton_rel: np.ndarray         # |f / (p f')| at the root: relative root error implied by the residual
    bracket_rel_width: np.ndarray  # final relative width of the bracket
    index: np.ndarray              # 1-based root number (count of roots below + 1)
    rigid: np.ndarray
    evaluations: int

    @property
    def frequencies_hz(self) -> np.ndarray:
        return self.omega_rad_s / (2 * np.pi)


def natural_frequencies(chain: Chain, n_roots: int | None = None, *, p_range: tuple[float, float] | None = None,
                        p_guess: float = 1.0, max_iter: int = 200) -> TMRoots:
    """The lowest ``n_roots`` natural frequencies, or all roots in ``p_range`` = (p_lo, p_hi)."""
    if not chain.real:
        raise ModelError("chain", "elements", "damped", "undamped elements for natural frequencies")
    evals = 0
    if p_range is not None:
        lo, hi = (float(v) for v in p_range)
        if not 0 <= lo < hi or not np.isfinite(hi):
            raise ModelError("scan", "p_range", p_range, "0 <= p_lo < p_hi (rad/s)")
        n_lo, n_hi = (int(v) for v in count_below(chain, np.array([lo, hi])))
        evals += 2
        if n_hi == n_lo:
            raise ModelError("scan", "p_range", list(p_range),
                             f"a range that brackets at least one natural frequency (none in [{lo:g}, {hi:g}] rad/s; "
                             f"{n_lo} below it)")
        index = np.arange(n_lo + 1, n_hi + 1)
    else:
        if isinstance(n_roots, bool) or not isinstance(n_roots, (int, np.integer)) or n_roots < 1:
            raise ModelError("[analysis]", "modes", n_roots, "an integer >= 1")
        lo, hi = 0.0, float(p_guess)
        for _ in range(2000):
            evals += 1
            if count_below(chain, hi)[0] >= n_roots:
                break
            hi *= 2.0
            if hi > 1e150:
                total = int(count_below(chain, 1e150)[0])
                raise ModelError("[analysis]", "modes", n_roots, f"at most {total} (the chain's number of DOFs)")
        index = np.arange(1, n_roots + 1)
    a = np.full(index.size, lo)
    b = np.full(index.size, hi)
    for _ in range(max_iter):
        mid = 0.5 * (a + b)
        n_mid = count_below(chain, mid)
        evals += 1
        above = n_mid >= index
        b = np.where(above, mid, b)
        a = np.where(above, a, mid)
        if np.all(b - a <= 4 * EPS * b) or np.all(b < 1e-12 * hi):
            break
    root = 0.5 * (a + b)
    rigid = b < 1e-9 * hi
    root[rigid] = 0.0
    pr = np.where(rigid, 1e-9 * hi, root)
    f0 = boundary_residual(chain, pr)
    h = 1e-7 * pr
    df = (boundary_residual(chain, pr + h) - boundary_residual(chain, pr - h)) / (2 * h)
    with np.errstate(invalid="ignore", divide="ignore"):
        width = np.where(root > 0, (b - a) / np.where(root > 0, root, 1.0), 0.0)
        newton = np.where(rigid, 0.0, np.abs(f0) / np.abs(df * pr))
    return TMRoots(omega_rad_s=root, residuals=np.abs(f0), newton_rel=newton, bracket_rel_width=width, index=index,
                   rigid=rigid, evaluations=evals + 3)


# ----------------------------------------------------------- mode shapes
def mode_shape(chain: Chain, p: float) -> ChainResponse:
    """Shape coefficients (§10.2) of the mode at the natural frequency ``p``: amplitudes at every
    section and at the far end of every branch, normalised to a unit amplitude at the free
    output end (the digest's corrected normalisation, case 2) or, for a clamped end, to a unit
    end force Q_n = 1.  ``p`` must be a root (e.g. from :func:`natural_frequencies`)."""
    w = np.atleast_1d(np.asarray(p, dtype=float))
    line = _start_line(chain.start, w.shape)
    lines, store = [line], {}
    for e in chain.elements:
        line = _apply(e, line, w, forward=True, store=store)
        lines.append(line)
    one = np.ones(w.shape, dtype=complex)
    a_end, Q_end = (one, 0 * one) if chain.end == "free" else (0 * one, one)
    r = _back_substitute(chain, w, lines, store, a_end, Q_end)
    r.a, r.Q = r.a.real, r.Q.real
    r.branch_a = {i: v.real for i, v in r.branch_a.items()}
    return r


# ----------------------------------------------------------- forced response
@dataclass
class ChainResponse:
    """Complex amplitudes at every section of the main chain (section i = before element i;
    the last one is the output end) and at the far end of every branch."""

    omega_rad_s: np.ndarray
    a: np.ndarray                  # (n_freq, n_sections)
    Q: np.ndarray
    branch_a: dict = field(default_factory=dict)   # element index -> (n_freq,) amplitude at the branch end

    def to_dict(self) -> dict:
        return {"omega_rad_s": self.omega_rad_s.tolist(), "a_real": self.a.real.tolist(),
                "a_imag": self.a.imag.tolist()}


def forced_response(chain: Chain, omegas) -> ChainResponse:
    """Steady-state complex amplitudes under the chain's loads (Load elements, branch loads)."""
    w = np.atleast_1d(np.asarray(omegas, dtype=float))
    line = _start_line(chain.start, w.shape)
    lines = [line]
    store: dict = {}
    for e in chain.elements:
        line = _apply(e, line, w, forward=True, store=store)
        lines.append(line)
    al, be, ga = line
    if chain.end == "free":
        bad = np.abs(al) < 1e3 * EPS
        a_end, Q_end = ga / np.where(bad, 1.0, al), 0 * ga
    else:
        bad = np.abs(be) < 1e3 * EPS
        a_end, Q_end = 0 * ga, ga / np.where(bad, 1.0, be)
    if np.any(bad):
        raise SolverError(f"undamped resonance at omega = {w[bad].tolist()} rad/s: the end condition is singular")
    return _back_substitute(chain, w, lines, store, a_end, Q_end)


def _back_substitute(chain, w, lines, store, a_end, Q_end) -> ChainResponse:
    """States at every section from the end state, using the stored lines (stable)."""
    n = len(chain.elements)
    A_out = np.zeros((w.size, n + 1), dtype=complex)
    Q_out = np.zeros_like(A_out)
    A_out[:, n], Q_out[:, n] = a_end, Q_end
    branch_a = {}
    a, Q = a_end, Q_end
    for i in range(n - 1, -1, -1):
        e = chain.elements[i]
        al, be, ga = lines[i]
        if isinstance(e, Member):
            A, B, C, D = e.T(w)
            a1, Q2 = D * a - B * Q, -C * a + A * Q
            use_a = np.abs(be) >= np.abs(al)
            a_p = np.where(use_a, a1, (ga - be * Q2) / np.where(use_a, 1.0, al))
            Q_p = np.where(use_a, (ga - al * a1) / np.where(use_a, be, 1.0), Q2)
        elif isinstance(e, Ratio):
            a_p, Q_p = a / e.ratio, Q * e.ratio
        else:
            a_p = a
            s = e.shunt(w) if isinstance(e, (Inertia, Ground)) else 0.0
            M = e.M if isinstance(e, Load) else 0.0
            if isinstance(e, Branch):
                ab, bb, gb = store[id(e)][0]
                use_b = np.abs(bb) >= np.abs(be)
                Qb_branch = (gb - ab * a) / np.where(use_b, bb, 1.0)
                Q_left = (ga - al * a) / np.where(use_b, 1.0, be)
                Q_p = np.where(use_b, Q - s * a + Qb_branch + M, Q_left)
                Qb = Q_p - Q + s * a - M
                branch_a[i] = _branch_end(e, a, Qb, w)
            else:
                Q_p = Q - s * a + M
        a, Q = a_p, Q_p
        A_out[:, i], Q_out[:, i] = a, Q
    return ChainResponse(omega_rad_s=w, a=A_out, Q=Q_out, branch_a=branch_a)


def _branch_end(br: Branch, a, Q, w):
    """Propagate a known attachment state outward through a (short) branch."""
    for e in br.elements:
        if isinstance(e, Member):
            A, B, C, D = e.T(w)
            a, Q = A * a + B * Q, C * a + D * Q
        elif isinstance(e, Ratio):
            a, Q = a * e.ratio, Q / e.ratio
        elif isinstance(e, (Inertia, Ground)):
            Q = Q + e.shunt(w) * a
        elif isinstance(e, Load):
            Q = Q - e.M
        else:
            ab, bb, gb = _branch_line(e, w)
            Q = Q - (gb - ab * a) / bb
    return a
