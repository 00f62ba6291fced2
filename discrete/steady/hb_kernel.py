"""Compiled harmonic-balance evaluation: :meth:`HBModel.evaluate_residual` in one numba call.

The same equations and the same algorithms as the numpy code of :mod:`discrete.steady.hb` and
:mod:`discrete.steady.piecewise` (which stay the reference, and the path of laws the kernel does not
know), without the ~100 numpy calls per evaluation that dominate it on small models (~100 us for one DOF
and 15 harmonics, 5-15 us here):

* the linear part ``K Q + Om C Q D + Om^2 M Q D^2 - f`` and its Jacobian ``K x I + Om C x D^T + Om^2 M x
  (D^2)^T``;
* element coordinates on the HB grid ``s = A G + s_exo``, ``s' = Om A D G + s'_exo`` (A = Gf Q);
* sampled laws (:meth:`Element.compiled_law`): the cubic spring and the tanh-regularised friction with
  its power-law terms -- values, projection ``F Pm``, the DFT sums of dF/ds and dF/ds' over the samples
  (j = 0 .. 2H, direct sums from a cos/sin table), dF/domega; a friction law whose samples are not exact on
  the HB grid (``Element.sampled_exactly``: saturated, |w| >= 20 eps with one sign) is evaluated on the
  dense grid, as :meth:`HBModel.element_projection` does (``go_fine`` kept between calls the same way);
* piecewise-affine laws (:meth:`Element.piecewise_law`) integrated exactly (:mod:`.piecewise`): crossings
  bracketed on the samples (sign changes and grazing extrema), polished by Newton (bracketed Newton when
  plain Newton does not settle), the interval spectra, the two Toeplitz products, the moving-boundary
  matrix of a law that jumps;
* the element Jacobian blocks ``T(cs) + Om T(cv) D^T`` from the spectra by the product-to-sum maps of
  :func:`.harmonics.galerkin_maps`, summed per DOF pair with the elements' weights.

``DRIVEFEM_JIT=0`` runs the same source as plain Python (slow; for debugging).  Tests compare the kernel
with the numpy path on every kind of law (tests/test_hb_kernel.py).
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..jit import JIT, njit  # noqa: F401  (JIT: whether numba compiles this module)
from ..nonsmooth.elements.base import LAW_CUBIC, LAW_TANH_FRICTION
from .harmonics import galerkin_maps as _galerkin_maps
from .harmonics import grid_tables, uniform_dft_table

LAW_PIECEWISE = 3                # an exactly integrated piecewise-affine law
TWO_PI = 2.0 * np.pi


# ------------------------------------------------------------------ trigonometric series
@njit(cache=True)
def _series(C, th, deriv):
    """Value (deriv 0), first or second theta-derivative of the real series C at the phase th."""
    H = (C.size - 1) // 2
    v = C[0] if deriv == 0 else 0.0
    for k in range(1, H + 1):
        c = np.cos(k * th)
        s = np.sin(k * th)
        a, b = C[2 * k - 1], C[2 * k]
        if deriv == 0:
            v += a * c + b * s
        elif deriv == 1:
            v += k * (b * c - a * s)
        else:
            v -= k * k * (a * c + b * s)
    return v


@njit(cache=True)
def _coefficient(X, row, d):
    """X[row, d] of a real function's complex coefficients, for negative d as conj(X[row, -d])."""
    return X[row, d] if d >= 0 else np.conj(X[row, -d])


@njit(cache=True)
def _put_real(out, j, z):
    """Harmonic j of the real series [c0, a1, b1, ..] from its complex coefficient z (the period mean for
    j = 0, else a_j = 2 Re z, b_j = -2 Im z)."""
    if j == 0:
        out[0] = z.real
    else:
        out[2 * j - 1] = 2.0 * z.real
        out[2 * j] = -2.0 * z.imag


@njit(cache=True)
def _to_complex(C, H):
    """c_l, l = -H..H (index l + H), of the real series C (piecewise.to_complex)."""
    out = np.empty(2 * H + 1, np.complex128)
    out[H] = C[0]
    for k in range(1, H + 1):
        z = 0.5 * (C[2 * k - 1] - 1j * C[2 * k])
        out[H + k] = z
        out[H - k] = np.conj(z)
    return out


# ------------------------------------------------------------------ crossings of a piecewise law
@njit(cache=True)
def _crossings(C, S, B):
    """Roots of s(theta) = B[i] over one period (piecewise.crossings): (theta sorted in [0, 2 pi), break
    index, s_theta at the root)."""
    N = S.size
    nb = B.size
    h = TWO_PI / N
    H = (C.size - 1) // 2
    reach = 0.0
    for k in range(1, H + 1):
        reach += k * k * (abs(C[2 * k - 1]) + abs(C[2 * k]))
    reach *= 0.5 * h * h
    smin, smax = S.min(), S.max()
    clear = True
    for i in range(nb):
        if not (B[i] > smax + reach or B[i] < smin - reach):
            clear = False
    if clear:
        return np.zeros(0), np.zeros(0, np.int64), np.zeros(0)
    cap = 3 * N * nb + 4                     # sign changes <= N nb, grazing brackets <= 2 N nb
    lo = np.empty(cap)
    hi = np.empty(cap)
    flo = np.empty(cap)
    fhi = np.empty(cap)
    bi = np.empty(cap, np.int64)
    nc = 0
    near = False
    for n in range(N):
        s0 = S[n]
        s1 = S[(n + 1) % N]
        for i in range(nb):
            d0 = s0 - B[i]
            d1 = s1 - B[i]
            if abs(d0) <= reach:
                near = True
            if (d0 > 0) != (d1 > 0):
                lo[nc] = n * h
                hi[nc] = n * h + h
                flo[nc] = d0
                fhi[nc] = d1
                bi[nc] = i
                nc += 1
    if near:            # a contact shorter than a sample interval: extrema of the samples near a break
        n0 = nc
        ne_ = np.empty(N * nb, np.int64)
        be_ = np.empty(N * nb, np.int64)
        tt = np.empty(N * nb)
        vv = np.empty(N * nb)
        m = 0
        for n in range(N):
            sp, sn, sv = S[(n - 1) % N], S[(n + 1) % N], S[n]
            ext = (sv >= sp and sv >= sn) or (sv <= sp and sv <= sn)
            if not ext:
                continue
            for i in range(nb):
                side = sv > B[i]
                if side == (sp > B[i]) and side == (sn > B[i]) and abs(sv - B[i]) <= reach:
                    th = n * h
                    for _ in range(3):
                        d1 = _series(C, th, 1)
                        d2 = _series(C, th, 2)
                        if d2 != 0:
                            th = th - d1 / d2
                        th = min(max(th, (n - 1) * h), (n + 1) * h)
                    v = _series(C, th, 0) - B[i]
                    if (v > 0) != side:
                        ne_[m] = n
                        be_[m] = i
                        tt[m] = th
                        vv[m] = v
                        m += 1
        for r in range(m):
            n, i = ne_[r], be_[r]
            lo[nc] = (n - 1) * h
            hi[nc] = tt[r]
            flo[nc] = S[(n - 1) % N] - B[i]
            fhi[nc] = vv[r]
            bi[nc] = i
            nc += 1
        for r in range(m):
            n, i = ne_[r], be_[r]
            lo[nc] = tt[r]
            hi[nc] = (n + 1) * h
            flo[nc] = vv[r]
            fhi[nc] = S[(n + 1) % N] - B[i]
            bi[nc] = i
            nc += 1
        _ = n0
    if nc == 0:
        return np.zeros(0), np.zeros(0, np.int64), np.zeros(0)
    th = np.empty(nc)
    d1 = np.empty(nc)
    for c in range(nc):
        den = fhi[c] - flo[c]
        th[c] = lo[c] - flo[c] * (hi[c] - lo[c]) / (den if den != 0 else 1.0)
    big = np.inf
    for it in range(3):                      # plain Newton from the secant of the bracket
        big = 0.0
        for c in range(nc):
            f = _series(C, th[c], 0) - B[bi[c]]
            d = _series(C, th[c], 1)
            d1[c] = d
            step = f / d
            th[c] -= step
            if abs(step) > big or step != step:
                big = abs(step) if step == step else np.inf
        if it > 0 and big <= 1e-9:
            break
    ok = big <= 1e-9
    for c in range(nc):
        if not (th[c] >= lo[c] - 1e-12 and th[c] <= hi[c] + 1e-12):
            ok = False
    if not ok:                               # Newton kept inside the brackets (bisection when it leaves them)
        for c in range(nc):
            a, b, fa = lo[c], hi[c], flo[c]
            t = 0.5 * (a + b)
            bv = B[bi[c]]
            for _ in range(30):
                f = _series(C, t, 0) - bv
                d = _series(C, t, 1)
                if (f > 0) == (fa > 0):
                    a, fa = t, f
                else:
                    b = t
                tn = t - f / d if d != 0 else 0.5 * (a + b)
                if not (tn >= a and tn <= b):
                    tn = 0.5 * (a + b)
                step = abs(tn - t)
                t = tn
                if step <= 1e-14:
                    break
            th[c] = t
            d1[c] = _series(C, t, 1)
    for c in range(nc):
        th[c] = th[c] % TWO_PI
    order = np.argsort(th)
    return th[order], bi[order], d1[order]


@njit(cache=True)
def _piece(B, s):
    """Index of the piece of s (np.searchsorted(breaks, s, side='right'))."""
    p = 0
    while p < B.size and B[p] <= s:
        p += 1
    return p


@njit(cache=True)
def _pw_project(Cs, Cv, Cw, S, B, pa, pb, pc, has_c, jumps, H, J, jac, dw, Fout, Fwout, ss, sv, jump):
    """Exact projection of one piecewise-affine law (piecewise.ExactProjection.evaluate) on harmonics
    0..J: Fout (2J+1), Fwout (2H+1, with dw), the spectra ss, sv (j = 0..2H, not yet times N) and the
    moving-boundary matrix (added into ``jump``; returns whether there is one)."""
    m = 2 * H + 1
    th, bi, d1 = _crossings(Cs, S, B)
    nc = th.size
    P = pa.size
    Jx = max(J + H, 2 * H)
    ABG = np.zeros((3, Jx + 1), np.complex128)
    after = np.empty(nc, np.int64)
    if nc == 0:
        p = _piece(B, S[0])
        ABG[0, 0] = pa[p]
        ABG[1, 0] = pb[p]
        ABG[2, 0] = pc[p]
    else:
        consistent = True
        for c in range(nc):
            after[c] = bi[c] + (1 if d1[c] > 0 else 0)
        for c in range(nc):
            before_next = bi[(c + 1) % nc] + (0 if d1[(c + 1) % nc] > 0 else 1)
            if after[c] != before_next:
                consistent = False
        if not consistent:                   # read the piece at the midpoints
            for c in range(nc):
                t2 = th[c + 1] if c + 1 < nc else th[0] + TWO_PI
                after[c] = _piece(B, _series(Cs, 0.5 * (th[c] + t2), 0))
        for c in range(nc):
            ta = th[c]
            tb = th[c + 1] if c + 1 < nc else th[0]          # the exponentials wrap; the length does not
            p = after[c]
            if p < 0 or p >= P:
                continue
            chi0 = ((tb if c + 1 < nc else th[0] + TWO_PI) - ta) / TWO_PI
            ABG[0, 0] += pa[p] * chi0
            ABG[1, 0] += pb[p] * chi0
            ABG[2, 0] += pc[p] * chi0
            for j in range(1, Jx + 1):
                e = (np.exp(-1j * j * tb) - np.exp(-1j * j * ta)) * (1j / (TWO_PI * j))
                ABG[0, j] += pa[p] * e
                ABG[1, j] += pb[p] * e
                ABG[2, j] += pc[p] * e
    cs = _to_complex(Cs, H)
    cv = _to_complex(Cv, H)
    # F_j = A_j + sum_l B_{j-l} s_l + G_{j-l} v_l, with X_{-d} = conj(X_d)
    for j in range(J + 1):
        acc = ABG[0, j]
        for l in range(-H, H + 1):
            acc += _coefficient(ABG, 1, j - l) * cs[l + H]
            if has_c:
                acc += _coefficient(ABG, 2, j - l) * cv[l + H]
        _put_real(Fout, j, acc)
    if dw:
        for q in range(m):
            Fwout[q] = 0.0
        if has_c:
            cw = _to_complex(Cw, H)
            for j in range(H + 1):
                acc = 0j
                for l in range(-H, H + 1):
                    acc += _coefficient(ABG, 2, j - l) * cw[l + H]
                _put_real(Fwout, j, acc)
    has_jump = False
    if jac:
        for j in range(2 * H + 1):
            ss[j] = ABG[1, j]
            sv[j] = ABG[2, j]
        if nc and jumps:
            phi = np.empty(m)
            for c in range(nc):
                a_ = after[c]
                b_ = after[c - 1] if c > 0 else after[nc - 1]
                dF = (pa[b_] - pa[a_]) + (pb[b_] - pb[a_]) * B[bi[c]] + (pc[b_] - pc[a_]) * _series(Cv, th[c], 0)
                if dF == 0.0:
                    continue
                has_jump = True
                wt = -dF / (TWO_PI * d1[c])
                phi[0] = 1.0
                for k in range(1, H + 1):
                    phi[2 * k - 1] = np.cos(k * th[c])
                    phi[2 * k] = np.sin(k * th[c])
                for k in range(m):
                    wk = (1.0 if k == 0 else 2.0) * phi[k] * wt
                    for l in range(m):
                        jump[k, l] += wk * phi[l]
    return has_jump


# ------------------------------------------------------------------ sampled laws
@njit(cache=True)
def _law(code, par, s, sd, F, dFs, dFv):
    """A sampled law at the samples s, sd (Element.smooth_force of the codes of Element.compiled_law)."""
    N = s.size
    if code == LAW_CUBIC:
        k3 = par[0]
        for n in range(N):
            x = s[n]
            F[n] = -k3 * x ** 3
            dFs[n] = -3.0 * k3 * x ** 2
            dFv[n] = 0.0
    else:                                    # LAW_TANH_FRICTION
        a0, a1, a2, a3, v0, eps = par[0], par[1], par[2], par[3], par[4], par[5]
        for n in range(N):
            w = sd[n] - v0
            t = np.tanh(w / eps)
            f = -a0 * t - a1 * w
            d = -a0 * (1 - t ** 2) / eps - a1
            if a2:
                aw = abs(w)
                f = f - a2 * w * aw
                d = d - 2 * a2 * aw
            if a3:
                f = f - a3 * w * w * w
                d = d - 3 * a3 * w * w
            F[n] = f
            dFs[n] = 0.0
            dFv[n] = d


@njit(cache=True)
def _exact_on_samples(code, par, sd):
    """Element.sampled_exactly of a rough law on its samples (friction: saturated with one sign)."""
    if code != LAW_TANH_FRICTION or sd.size < 3:
        return code == LAW_CUBIC
    v0, eps = par[4], par[5]
    lo, hi = np.inf, -np.inf
    step = 0.0
    for n in range(sd.size):
        w = sd[n] - v0
        lo = min(lo, w)
        hi = max(hi, w)
        if n:
            step = max(step, abs(sd[n] - sd[n - 1]))
    return lo - step >= 20.0 * eps or hi + step <= -20.0 * eps


@njit(cache=True)
def exact_on_samples_batch(code, par, Sd):
    """_exact_on_samples of one law on many orbits' samples of s' (P, N)."""
    out = np.empty(Sd.shape[0], np.bool_)
    for p in range(Sd.shape[0]):
        out[p] = _exact_on_samples(code, par, Sd[p])
    return out


@njit(cache=True)
def _rows_times(a, G):
    """The samples a @ G (G: (m, N)) by rows of G, contiguous in memory; per sample the sum over k runs in
    the order of a dot product (k = 0, 1, ..), so the values are those of the column-wise loop."""
    m, N = G.shape
    out = np.zeros(N)
    for k in range(m):
        c = a[k]
        for n in range(N):
            out[n] += c * G[k, n]
    return out


@njit(cache=True)
def _sampled(code, par, Ae, ADe, G, Pm, Ecos, Esin, sa, sb, sda, sdb, omega, Om, nu, jac, dw, Fp, Fw, ss, sv):
    """Coordinates, law, projection, spectra (DFT sums over the N samples, j = 0..2H) and dF/domega of one
    sampled element on a grid (G: the basis there, Pm its projection, Ecos/Esin the DFT table); returns
    whether the law is exact on these samples."""
    m, N = G.shape
    H2 = Ecos.shape[0]
    S = _rows_times(Ae, G)
    ADG = _rows_times(ADe, G)
    Sd = np.empty(N)
    for n in range(N):
        S[n] = S[n] + sa[n] + sb[n] / omega
        Sd[n] = Om * ADG[n] + sda[n] + omega * sdb[n]
    F = np.empty(N)
    dFs = np.empty(N)
    dFv = np.empty(N)
    _law(code, par, S, Sd, F, dFs, dFv)
    for k in range(m):
        Fp[k] = 0.0
    for n in range(N):                        # by rows of Pm (contiguous), the sum over n in the same order
        f = F[n]
        for k in range(m):
            Fp[k] += f * Pm[n, k]
    if dw:
        for k in range(m):
            Fw[k] = 0.0
        for n in range(N):
            d = dFv[n] * (ADG[n] / nu + sdb[n]) - dFs[n] * sb[n] / omega ** 2
            for k in range(m):
                Fw[k] += d * Pm[n, k]
    if jac:
        for j in range(H2):
            cs = 0.0
            sn = 0.0
            cv = 0.0
            vn = 0.0
            for n in range(N):
                cs += dFs[n] * Ecos[j, n]
                sn += dFs[n] * Esin[j, n]
                cv += dFv[n] * Ecos[j, n]
                vn += dFv[n] * Esin[j, n]
            ss[j] = cs - 1j * sn
            sv[j] = cv - 1j * vn
    return _exact_on_samples(code, par, Sd)


# ------------------------------------------------------------------ the whole evaluation
@njit(cache=True)
def evaluate(Q, omega, nu, jac, dw, K, C, M, fP, fmask, Gf, Dm, G, Pm, Ecos, Esin, exo, codes, par,
             pws, brk, nbrk, pab, pflags, rough, go_fine, Gfine, Pmfine, Ecosf, Esinf, exof, pw_w, prow, pcol,
             psrc, i1, i2, c1, c2, W):
    """(R, J, Rw, fine evaluations) of the HB equations at coefficients Q (n, m) and omega: see the module
    docstring; every array as packed by :class:`CompiledHB`.  J (resp. Rw) is empty without jac (dw)."""
    n, m = Q.shape
    H = (m - 1) // 2
    nel = Gf.shape[0]
    N = G.shape[1]
    Om = omega / nu
    # linear part (coefficient space)
    QD = np.zeros((n, m))
    QDD = np.zeros((n, m))
    for i in range(n):
        for c in range(m):
            acc = 0.0
            for r in range(m):
                acc += Q[i, r] * Dm[r, c]
            QD[i, c] = acc
        for c in range(m):
            acc = 0.0
            for r in range(m):
                acc += QD[i, r] * Dm[r, c]
            QDD[i, c] = acc
    powers = (1.0, 1.0 / omega, omega, omega * omega)
    R = np.zeros((n, m))
    for i in range(n):
        for c in range(m):
            acc = 0.0
            for j in range(n):
                acc += K[i, j] * Q[j, c] + Om * C[i, j] * QD[j, c] + Om * Om * M[i, j] * QDD[j, c]
            for p in range(4):
                if fmask[p]:
                    acc -= fP[p, i, c] * powers[p]
            R[i, c] = acc
    Rw = np.zeros((n, m)) if dw else np.zeros((0, 0))
    if dw:
        dpow = (0.0, -1.0 / omega ** 2, 1.0, 2.0 * omega)
        for i in range(n):
            for c in range(m):
                acc = 0.0
                for j in range(n):
                    acc += (C[i, j] * QD[j, c] + 2.0 * Om * M[i, j] * QDD[j, c]) / nu
                for p in range(1, 4):
                    if fmask[p]:
                        acc -= fP[p, i, c] * dpow[p]
                Rw[i, c] = acc
    # elements
    Fp = np.zeros((nel, m))
    Fw = np.zeros((nel, m))
    spec_s = np.zeros((nel, 2 * H + 1), np.complex128)
    spec_v = np.zeros((nel, 2 * H + 1), np.complex128)
    jump = np.zeros((nel, m, m))
    has_jump = np.zeros(nel, np.bool_)
    fine_count = 0
    Nf = Gfine.shape[1]
    for e in range(nel):
        Ae = np.zeros(m)
        for i in range(n):
            g = Gf[e, i]
            if g != 0.0:
                for k in range(m):
                    Ae[k] += g * Q[i, k]
        ADe = np.zeros(m)
        for k in range(1, H + 1):             # A D: a_k' = k b_k, b_k' = -k a_k
            ADe[2 * k - 1] = k * Ae[2 * k]
            ADe[2 * k] = -k * Ae[2 * k - 1]
        code = codes[e]
        if code == LAW_PIECEWISE:
            Cs = Ae + pws[e, 0]
            Cv = Om * ADe + pws[e, 1] + omega * pws[e, 2]
            Cw = ADe / nu + pws[e, 2]
            S = _rows_times(Ae, G)
            for q in range(N):
                S[q] = S[q] + exo[0, e, q] + exo[1, e, q] / omega
            nb = nbrk[e]
            has_jump[e] = _pw_project(Cs, Cv, Cw, S, brk[e, :nb], pab[e, 0, :nb + 1], pab[e, 1, :nb + 1],
                                      pab[e, 2, :nb + 1], pflags[e, 0], pflags[e, 1], H, H, jac, dw, Fp[e],
                                      Fw[e], spec_s[e], spec_v[e], jump[e])
            for j in range(2 * H + 1):
                spec_s[e, j] *= N
                spec_v[e, j] *= N
        elif rough[e] and go_fine[e]:         # not exact on the HB grid at the last evaluation: dense grid
            fine_count += 1
            exact = _sampled(code, par[e], Ae, ADe, Gfine, Pmfine, Ecosf, Esinf, exof[0, e], exof[1, e], exof[2, e],
                             exof[3, e], omega, Om, nu, jac, dw, Fp[e], Fw[e], spec_s[e], spec_v[e])
            for j in range(2 * H + 1):
                spec_s[e, j] *= N / Nf
                spec_v[e, j] *= N / Nf
            go_fine[e] = not exact
        else:
            exact = _sampled(code, par[e], Ae, ADe, G, Pm, Ecos, Esin, exo[0, e], exo[1, e], exo[2, e], exo[3, e],
                             omega, Om, nu, jac, dw, Fp[e], Fw[e], spec_s[e], spec_v[e])
            if rough[e] and not exact:
                fine_count += 1
                _sampled(code, par[e], Ae, ADe, Gfine, Pmfine, Ecosf, Esinf, exof[0, e], exof[1, e], exof[2, e],
                         exof[3, e], omega, Om, nu, jac, dw, Fp[e], Fw[e], spec_s[e], spec_v[e])
                for j in range(2 * H + 1):
                    spec_s[e, j] *= N / Nf
                    spec_v[e, j] *= N / Nf
                go_fine[e] = True
    for e in range(nel):
        for i in range(n):
            g = Gf[e, i]
            if g != 0.0:
                for c in range(m):
                    R[i, c] -= g * Fp[e, c]
                    if dw:
                        Rw[i, c] -= g * Fw[e, c]
    if not jac:
        return R.ravel(), np.zeros((0, 0)), Rw.ravel(), fine_count
    # Jacobian: linear part, then the element blocks per DOF pair
    J = np.zeros((n * m, n * m))
    for i in range(n):                        # K x I + Om C x D^T + Om^2 M x (D^2)^T (D^2 = -diag(k^2))
        for j in range(n):
            k_, c_, m_ = K[i, j], Om * C[i, j], Om * Om * M[i, j]
            if k_ == 0.0 and c_ == 0.0 and m_ == 0.0:
                continue
            J[i * m, j * m] += k_
            for q in range(1, H + 1):
                a, b = i * m + 2 * q - 1, j * m + 2 * q - 1
                J[a, b] += k_ - m_ * q * q
                J[a + 1, b + 1] += k_ - m_ * q * q
                J[a, b + 1] += c_ * q
                J[a + 1, b] -= c_ * q
    npairs = pw_w.shape[0]
    L = 2 * H + 1
    Vs = np.empty(2 * L)
    Vv = np.empty(2 * L)
    B = np.empty((npairs, m, m))
    for p in range(npairs):
        for j in range(L):
            zs = 0j
            zv = 0j
            for e in range(nel):
                wgt = pw_w[p, e]
                if wgt != 0.0:
                    zs += wgt * spec_s[e, j]
                    zv += wgt * spec_v[e, j]
            Vs[j] = zs.real
            Vs[L + j] = -zs.imag
            Vv[j] = zv.real
            Vv[L + j] = -zv.imag
        T = np.empty((m, m))
        Tv = np.empty((m, m))
        for k in range(m):
            hk = 0.5 * W[k]
            for l in range(m):
                T[k, l] = hk * (c1[k, l] * Vs[i1[k, l]] + c2[k, l] * Vs[i2[k, l]])
                Tv[k, l] = hk * (c1[k, l] * Vv[i1[k, l]] + c2[k, l] * Vv[i2[k, l]])
        for k in range(m):
            B[p, k, 0] = T[k, 0]
            for q in range(1, H + 1):         # + Om T(cv) D^T: column 2q-1 <- -q col 2q, column 2q <- q col 2q-1
                B[p, k, 2 * q - 1] = T[k, 2 * q - 1] - Om * q * Tv[k, 2 * q]
                B[p, k, 2 * q] = T[k, 2 * q] + Om * q * Tv[k, 2 * q - 1]
        for e in range(nel):
            if has_jump[e] and pw_w[p, e] != 0.0:
                wgt = pw_w[p, e]
                for k in range(m):
                    for l in range(m):
                        B[p, k, l] += wgt * jump[e, k, l]
    for r in range(prow.size):
        i, j, p = prow[r], pcol[r], psrc[r]
        for k in range(m):
            for l in range(m):
                J[i * m + k, j * m + l] -= B[p, k, l]
    return R.ravel(), J, Rw.ravel(), fine_count


@njit(cache=True)
def pw_projections(Cs, Cv, S, B, pa, pb, pc, has_c, H, J):
    """The exact projections of one piecewise-affine law on harmonics 0..J along many orbits (Cs, Cv:
    (P, 2H+1) series of s and s', S: (P, N) the samples of s): (F (P, 2J+1), period means of dF/ds and of
    dF/ds' (P,)) -- the truncation estimate's high harmonics (truncation.py)."""
    P = Cs.shape[0]
    m = 2 * H + 1
    F = np.zeros((P, 2 * J + 1))
    ms = np.zeros(P)
    mv = np.zeros(P)
    Fw = np.zeros(m)
    ss = np.zeros(2 * H + 1, np.complex128)
    sv = np.zeros(2 * H + 1, np.complex128)
    jump = np.zeros((m, m))
    for p in range(P):
        _pw_project(Cs[p], Cv[p], Cv[p], S[p], B, pa, pb, pc, has_c, False, H, J, True, False, F[p], Fw, ss, sv,
                    jump)
        ms[p] = ss[0].real
        mv[p] = sv[0].real
    return F, ms, mv


@njit(cache=True)
def crossing_phases(A, sa, B, G, offsets):
    """The crossing phases of one piecewise-affine law along many orbits (A: (P, 2H+1) the element's
    coordinate series without its exogenous part sa, G the basis on the HB grid): all phases in one array,
    orbit p's in [offsets[p], offsets[p + 1])."""
    P, m = A.shape
    N = G.shape[1]
    out = np.empty(0)
    chunks = []
    for p in range(P):
        C = A[p] + sa
        S = _rows_times(C, G)
        th, _, _ = _crossings(C, S, B)
        chunks.append(th)
        offsets[p + 1] = offsets[p] + th.size
    out = np.empty(offsets[P])
    for p in range(P):
        out[offsets[p]:offsets[p + 1]] = chunks[p]
    return out


@njit(cache=True)
def series_extremes(C, P, iterations):
    """(max, min) of each real series C (k, 2H+1): grid extremes (P points) refined by Newton on y' = 0,
    kept within one grid step (measures.series_extremes)."""
    k, m = C.shape
    H = (m - 1) // 2
    h = TWO_PI / P
    ymax = np.empty(k)
    ymin = np.empty(k)
    cs = np.empty((P, H))
    sn = np.empty((P, H))
    for q in range(P):
        for j in range(H):
            cs[q, j] = np.cos((j + 1) * (q * h))
            sn[q, j] = np.sin((j + 1) * (q * h))
    for r in range(k):
        c = C[r]
        best_hi, best_lo = -np.inf, np.inf
        i_hi, i_lo = 0, 0
        for q in range(P):
            y = c[0]
            for j in range(H):
                y += c[2 * j + 1] * cs[q, j] + c[2 * j + 2] * sn[q, j]
            if y > best_hi:
                best_hi, i_hi = y, q
            if y < best_lo:
                best_lo, i_lo = y, q
        for which in range(2):
            t0 = (i_hi if which == 0 else i_lo) * h
            t = t0
            for _ in range(iterations):
                d1 = _series(c, t, 1)
                d2 = _series(c, t, 2)
                if d2 != 0:
                    t = t - d1 / d2
                t = min(max(t, t0 - h), t0 + h)
            y = _series(c, t, 0)
            if which == 0:
                ymax[r] = y if y > best_hi else best_hi
            else:
                ymin[r] = y if y < best_lo else best_lo
    return ymax, ymin


@njit(cache=True)
def split_layout(cuts, offsets, M):
    """The Floquet intervals of each orbit (hb._split_coordinates): the M uniform intervals, those that
    contain crossings (phases ``cuts[offsets[p]:offsets[p + 1]]``, sorted) replaced by their sub-intervals
    between the crossings, in phase order, padded to the longest orbit with zero-length copies of the last.
    Returns (uniform (P, Mp) bool, index (P, Mp): the uniform interval or the row of the sub-interval in
    mids, duration (P, Mp) in phase, mids (K,), their orbit (K,))."""
    P = offsets.size - 1
    h = TWO_PI / M
    extra = 0
    for p in range(P):
        extra = max(extra, offsets[p + 1] - offsets[p])
    Mp = M + extra
    uni = np.ones((P, Mp), np.bool_)
    idx = np.zeros((P, Mp), np.int64)
    dur = np.zeros((P, Mp))
    cap = 0
    for p in range(P):
        cap += 2 * (offsets[p + 1] - offsets[p]) + 1
    mids = np.empty(cap)
    orbit = np.empty(cap, np.int64)
    K = 0
    for p in range(P):
        c = np.sort(cuts[offsets[p]:offsets[p + 1]])
        nc = c.size
        cutmask = np.zeros(M, np.bool_)
        for q in range(nc):
            cutmask[min(int(c[q] / h), M - 1)] = True
        ncut = 0
        for j in range(M):
            if cutmask[j]:
                ncut += 1
        bnd = np.empty(2 * ncut + nc)
        r = 0
        for j in range(M):
            if cutmask[j]:
                bnd[r] = j * h
                bnd[r + 1] = (j + 1) * h
                r += 2
        for q in range(nc):
            bnd[r] = c[q]
            r += 1
        bnd = np.sort(bnd)
        # entries in phase order: (phase of the midpoint, uniform?, index or mid row, duration)
        ne = 0
        ph = np.empty(M + bnd.size)
        kind = np.empty(M + bnd.size, np.bool_)
        ix = np.empty(M + bnd.size, np.int64)
        du = np.empty(M + bnd.size)
        for j in range(M):
            if not cutmask[j]:
                ph[ne] = (j + 0.5) * h
                kind[ne] = True
                ix[ne] = j
                du[ne] = h
                ne += 1
        for q in range(bnd.size - 1):
            lo, hi = bnd[q], bnd[q + 1]
            own = min(int((lo + hi) * 0.5 / h), M - 1)
            if cutmask[own] and hi > lo:
                ph[ne] = 0.5 * (lo + hi)
                kind[ne] = False
                ix[ne] = K
                du[ne] = hi - lo
                mids[K] = 0.5 * (lo + hi)
                orbit[K] = p
                K += 1
                ne += 1
        order = np.argsort(ph[:ne], kind="mergesort")
        for q in range(ne):
            o = order[q]
            uni[p, q] = kind[o]
            idx[p, q] = ix[o]
            dur[p, q] = du[o]
        for q in range(ne, Mp):
            uni[p, q] = uni[p, ne - 1]
            idx[p, q] = idx[p, ne - 1]
            dur[p, q] = 0.0
    return uni, idx, dur, mids[:K], orbit[:K]


@njit(cache=True)
def constant_coefficients(Q, omegas, nu, Gf, G, exo, codes, par, rough):
    """HBModel.constant_coefficients of many orbits Q (P, n, 2H+1): every sampled law exact on the HB
    grid (rough ones: Element.sampled_exactly) with dF/ds and dF/ds' the same at all samples."""
    P, n, m = Q.shape
    H = (m - 1) // 2
    nel = Gf.shape[0]
    N = G.shape[1]
    out = np.ones(P, np.bool_)
    S = np.empty(N)
    Sd = np.empty(N)
    F = np.empty(N)
    dFs = np.empty(N)
    dFv = np.empty(N)
    for p in range(P):
        omega = omegas[p]
        Om = omega / nu
        for e in range(nel):
            if codes[e] == LAW_PIECEWISE:
                continue
            Ae = np.zeros(m)
            for i in range(n):
                if Gf[e, i] != 0.0:
                    for k in range(m):
                        Ae[k] += Gf[e, i] * Q[p, i, k]
            for q in range(N):
                x = 0.0
                y = 0.0
                for k in range(m):
                    x += Ae[k] * G[k, q]
                for kk in range(1, H + 1):
                    y += kk * Ae[2 * kk] * G[2 * kk - 1, q] - kk * Ae[2 * kk - 1] * G[2 * kk, q]
                S[q] = x + exo[0, e, q] + exo[1, e, q] / omega
                Sd[q] = Om * y + exo[2, e, q] + omega * exo[3, e, q]
            if rough[e] and not _exact_on_samples(codes[e], par[e], Sd):
                out[p] = False
                break
            _law(codes[e], par[e], S, Sd, F, dFs, dFv)
            if dFs.min() != dFs.max() or dFv.min() != dFv.max():
                out[p] = False
                break
    return out


# ------------------------------------------------------------------ packing
@lru_cache(maxsize=32)
def _kernel_tables(H: int, N: int) -> tuple:
    """(D, G, Pm, cos table, sin table, W) of the grid of N phases for H harmonics
    (:func:`.harmonics.grid_tables`, :func:`.harmonics.uniform_dft_table` with j = 0..2H) as the compiled
    functions take them: writable C-ordered copies (numba types a read-only array apart, and compiles
    again for it), made once per (H, N) and shared by the models on that grid -- nothing writes them."""
    t = grid_tables(H, N)
    C, S = uniform_dft_table(2 * H, N)
    return tuple(np.array(a, order="C") for a in (t.D, t.G, t.Pm, C, S, t.W))


class CompiledHB:
    """An :class:`~discrete.steady.hb.HBModel`'s data packed for :func:`evaluate`; :meth:`build` returns
    None when an element's law is neither compiled (``Element.compiled_law``) nor exactly integrated."""

    def __init__(self, hb, codes, par):
        s = hb.s
        H, m, N = hb.H, hb.m, hb.N
        nel = len(s.elements)
        self.hb = hb
        self.nu = float(hb.nu)
        self._args = None                      # packed at the first call (_pack)
        self._linear(s)
        self.fP = np.ascontiguousarray(np.stack(hb._fP))
        self.fmask = np.array([bool(np.any(f)) for f in hb._fP])
        self.Gf = np.ascontiguousarray(np.asarray(s.Gf, float).reshape(nel, s.n))
        self.Dm, self.G, self.Pm, self.Ecos, self.Esin, self.W = _kernel_tables(H, N)   # hb's grid: N phases
        g = hb._grid
        self.exo = np.ascontiguousarray(np.stack([g.sa, g.sb, g.sda, g.sdb]).reshape(4, nel, N))
        self.codes = np.asarray(codes, np.int64)
        self.par = np.zeros((nel, 8))
        for e, p in enumerate(par):
            self.par[e, :len(p)] = p
        pw = {p[0]: p for p in hb._pw}
        nb = max([len(p[1].law.breaks) for p in hb._pw] + [1])
        self.pws = np.zeros((nel, 3, m))
        self.brk = np.zeros((nel, nb))
        self.nbrk = np.zeros(nel, np.int64)
        self.pab = np.zeros((nel, 3, nb + 1))
        self.pflags = np.zeros((nel, 2), np.bool_)
        for e, (_, proj, sa, sda, sdb) in pw.items():
            self.pws[e] = (sa, sda, sdb)
            k = len(proj.law.breaks)
            self.nbrk[e] = k
            self.brk[e, :k] = proj.law.breaks
            self.pab[e, :, :k + 1] = (proj.a, proj.b, proj.c)
            self.pflags[e] = (proj._has_c, proj._jumps)
        self.rough = np.zeros(nel, np.bool_)
        self.rough[list(hb._rough)] = True
        Nf = hb.N_fine if hb._rough else 1
        if hb._rough:
            _, self.Gfine, self.Pmfine, self.Ecosf, self.Esinf, _ = _kernel_tables(H, Nf)
            gf = hb.grid(Nf)
            self.exof = np.ascontiguousarray(np.stack([gf.sa, gf.sb, gf.sda, gf.sdb]).reshape(4, nel, Nf))
        else:
            self.Gfine = np.zeros((m, 1))
            self.Pmfine = np.zeros((1, m))
            self.Ecosf = np.zeros((2 * H + 1, 1))
            self.Esinf = np.zeros((2 * H + 1, 1))
            self.exof = np.zeros((4, nel, 1))
        self.pw_w = np.ascontiguousarray(hb._pair_weights)
        self.prow = np.asarray(hb._pair_rows, np.int64)
        self.pcol = np.asarray(hb._pair_cols, np.int64)
        self.psrc = np.asarray(hb._pair_src, np.int64)
        i1, i2, c1, c2 = _galerkin_maps(H)
        self.i1, self.i2 = np.asarray(i1, np.int64), np.asarray(i2, np.int64)
        self.c1, self.c2 = np.asarray(c1, float), np.asarray(c2, float)

    def _linear(self, s):
        """K, C, M of the system (repacked when a caller replaces them, as hb.backbone does with C)."""
        self._src = (s.K, s.C, s.M)
        self.K, self.C, self.M = (np.ascontiguousarray(np.asarray(a, float)) for a in (s.K, s.C, s.M))

    @classmethod
    def build(cls, hb):
        """The packed model, or None if the kernel cannot evaluate every element of it."""
        s = hb.s
        exact = {p[0] for p in hb._pw}
        codes, par = [], []
        for e, el in enumerate(s.elements):
            if e in exact:
                codes.append(LAW_PIECEWISE)
                par.append(())
                continue
            law = el.compiled_law(s.eps)
            if law is None or law[0] not in (LAW_CUBIC, LAW_TANH_FRICTION):
                return None
            codes.append(law[0])
            par.append(law[1])
        if not codes:
            return None                       # a linear model: nothing to compile
        return cls(hb, codes, par)

    def constant_coefficients(self, Xs, omegas):
        """:meth:`HBModel.constant_coefficients` of the orbits Xs (P, n, 2H+1) at omegas, compiled."""
        hb = self.hb
        Q = np.ascontiguousarray(np.asarray(Xs, float).reshape(-1, hb.s.n, hb.m))
        return constant_coefficients(Q, np.ascontiguousarray(omegas, float), self.nu, self.Gf, self.G, self.exo,
                                     self.codes, self.par, self.rough)

    def _pack(self):
        """The arrays of :func:`evaluate` after Q, omega, nu, jac, dw, in its order (packed once per model and
        again when K, C or M are replaced: one tuple instead of 38 attribute look-ups per call)."""
        self._args = (self.K, self.C, self.M, self.fP, self.fmask, self.Gf, self.Dm, self.G, self.Pm, self.Ecos,
                      self.Esin, self.exo, self.codes, self.par, self.pws, self.brk, self.nbrk, self.pab, self.pflags,
                      self.rough, self.hb._go_fine, self.Gfine, self.Pmfine, self.Ecosf, self.Esinf, self.exof,
                      self.pw_w, self.prow, self.pcol, self.psrc, self.i1, self.i2, self.c1, self.c2, self.W)

    def __call__(self, X, omega, jac=True, dw=False):
        """(R, J or None, dR/domega or None), as :meth:`HBModel.evaluate_residual`."""
        hb = self.hb
        s = hb.s
        if s.K is not self._src[0] or s.C is not self._src[1] or s.M is not self._src[2] or self._args is None:
            self._linear(s)
            self._pack()
        Q = np.ascontiguousarray(np.asarray(X, float).reshape(s.n, hb.m))
        R, J, Rw, fine = evaluate(Q, float(omega), self.nu, bool(jac), bool(dw), *self._args)
        hb.fine_evaluations += fine
        return R, (J if jac else None), (Rw if dw else None)
