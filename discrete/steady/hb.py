"""Harmonic balance with alternating frequency-time (AFT) evaluation of the nonlinear forces.

Unknowns: Fourier coefficients ``Q`` (n, 2H+1) of the free DOFs in ``theta = (omega/nu) t``
(nu = subharmonic order), columns ``[a0, a1, b1, a2, b2, ...]`` for
``q = a0 + sum_k a_k cos k theta + b_k sin k theta``.  The residual of

    M q'' + C q' + K q - f(t) - sum_i g_i F_i(s_i, s_i') = 0

is sampled at N >= 4H+2 equidistant instants, and projected back on the harmonics (Galerkin).  The
Jacobian with respect to Q is assembled exactly from the time-domain derivatives (AFT), the one with
respect to omega by a central difference.

Stability: Floquet multipliers of the variational equation ``M dq'' + (C - dF/dv) dq' + (K - dF/dq) dq = 0``
along the HB orbit, integrated over one period by classical RK4 (``floquet_hb``): stable when all
|multiplier| < 1 (+ 1e-6).
"""
from __future__ import annotations

import os

import numpy as np

from ..linalg.expm import expm_batch
from ..errors import ModelError, SolverError
from .harmonics import basis as _basis
from .harmonics import grid_tables, uniform_basis


class HBModel:
    """Residual and Jacobian of harmonic balance for a :class:`PeriodicSystem`.

    Evaluation (:meth:`evaluate_residual`): the linear part is applied in coefficient space
    (``K Q + W C Q D + W^2 M Q D^2``, W = omega/nu: exact, the sampled basis is orthogonal for
    N > 2H); only the element coordinates ``s_e = g_e . q + s_e(t)`` are sampled, their laws
    evaluated at the N instants and projected back.  The Jacobian block of an element is the Galerkin
    matrix of multiplication by dF/ds (dF/ds') on the grid -- ``T(c)[k, l] = sum_n Pm[n, k] c_n
    G[l, n]`` -- formed from the DFT of c by the product-to-sum rules (O(H^2) after one FFT, equal to
    the sampled sums), the frequency derivative ``dR/domega`` analytically from the same samples.
    Everything that depends on the model only (bases, exogenous terms by powers of omega, index maps)
    is built once."""

    def __init__(self, system, harmonics: int = 5, nu: int = 1, samples: int | None = None, kinks: str = "exact",
                 compiled: bool | None = None):
        self.s = system
        self.H = int(harmonics)
        self.nu = int(nu)
        self.samples = samples             # as asked (None: the defaults below)
        H = self.H
        if kinks not in ("exact", "sampled"):
            raise ValueError(f"kinks = {kinks!r}: 'exact' | 'sampled'")
        self.kinks = kinks
        # piecewise-affine laws (gaps, stops, one-sided springs) integrated exactly over their crossings
        # (piecewise.py) unless kinks = "sampled"; the others are sampled (AFT)
        laws = [el.piecewise_law() if kinks == "exact" else None for el in system.elements]
        # discontinuous (friction sign) or kinked (sampled one-sided, gap) forces: AFT sampling error ~ 1/N
        # resp. 1/N^2, so these get a denser default grid -- with kinks = "exact" only where needed: the
        # rough laws are evaluated on the dense grid (N_fine) at the evaluations where their samples on the
        # HB grid (N) are not exact (Element.sampled_exactly: a saturated clutch is a polynomial law)
        smooth = min((2 if law is not None else el.smoothness for el, law in zip(system.elements, laws)), default=2)
        #: whether a kinked or discontinuous law is sampled (not integrated exactly): the branch's w(s) then
        #: has kinks of its own (it zig-zags), and a fold is the extremum of its values (hb_curve.fold_point)
        self.samples_kinks = smooth < 2
        if samples:
            N = N_fine = int(samples)
        elif kinks == "exact":
            N, N_fine = default_samples(H, 2), default_samples(H, smooth)
        else:
            N = N_fine = default_samples(H, smooth)
        self.N = N
        self.N_fine = N_fine
        # the grid's tables (basis, derivatives, projection, Jacobian block maps): shared by every model on
        # this (H, N) grid, read-only
        t = grid_tables(H, N)
        th, G, D = t.theta, t.G, t.D
        self.G, self.D, self.theta = G, D, th
        self.W = t.W
        self.Pm = t.Pm             # (N, 2H+1): R = r @ Pm
        self.DG, self.DDG, self.DD = t.DG, t.DDG, t.DD
        self.m = 2 * H + 1
        self.nq = system.n * self.m
        self._grid = system.grid_parts(th, self.nu)
        g = self._grid
        self._fP = tuple(f @ self.Pm for f in (g.fa, g.fb, g.fc, g.fd))   # projected forcing by powers of omega
        # which exogenous terms are present (most models: a harmonic force or driver only)
        self._forcing_terms = [(k, None) for k, f in enumerate(self._fP) if np.any(f)]
        self._exo = tuple(bool(np.any(a)) for a in (g.sa, g.sb, g.sda, g.sdb))
        self._gg = np.einsum("ei,ej->eij", system.Gf, system.Gf)
        self._galerkin_maps = t.galerkin_maps
        # the element blocks of the Jacobian by DOF pair: c_ij = sum_e g_ei g_ej dF_e (pairs i <= j
        # touched by an element; (j, i) gets the same block)
        iu, ju = np.triu_indices(system.n)
        touched = np.any(self._gg[:, iu, ju] != 0, axis=0)
        iu, ju = iu[touched], ju[touched]
        self._pair_weights = np.ascontiguousarray(self._gg[:, iu, ju].T)          # (pairs, n_el)
        low = iu != ju
        self._pair_rows = np.concatenate([iu, ju[low]])
        self._pair_cols = np.concatenate([ju, iu[low]])
        self._pair_src = np.concatenate([np.arange(iu.size), np.flatnonzero(low)])
        self._block_map = t.block_map
        self._bases = {}
        self._lin = (None, None, None, None)
        self._setup_piecewise(laws)
        # hook (hb_kernel.py): the whole evaluation in one compiled call (compiled_evaluation: for models whose
        # numpy evaluation is expensive; compiled = True: whenever possible, False: never); decided at the
        # first evaluation (numba is imported then)
        self._compile_mode = compiled
        self._compiled = None if compiled is not False and COMPILED else False

    def _setup_piecewise(self, laws):
        """The elements whose laws are integrated exactly (:mod:`.piecewise`): those with a piecewise-affine
        law whose exogenous coordinate is a trigonometric polynomial of degree <= H (no drift)."""
        from .piecewise import ExactProjection

        g = self._grid
        self._rough = [e for e, (el, law) in enumerate(zip(self.s.elements, laws))
                       if law is None and el.smoothness < 2] if self.N_fine > self.N else []
        self.fine_evaluations = 0
        self._go_fine = np.zeros(len(self.s.elements), bool)
        pw = []
        for e, law in enumerate(laws):
            if law is None:
                continue
            parts = [g.sa[e] @ self.Pm, g.sda[e] @ self.Pm, g.sdb[e] @ self.Pm]
            back = [p @ self.G for p in parts]
            scale = max(1.0, *(float(np.max(np.abs(x))) for x in (g.sa[e], g.sda[e], g.sdb[e])))
            if np.any(g.sb[e] != 0) or max(float(np.max(np.abs(b - x))) for b, x in
                                             zip(back, (g.sa[e], g.sda[e], g.sdb[e]))) > 1e-12 * scale:
                continue
            pw.append((e, ExactProjection(law, self.H), *parts))
        self._pw = pw
        done = {p[0] for p in pw}
        self._sampled = [e for e in range(len(self.s.elements)) if e not in done]
        self._pw_jump = False

    def exogenous_series(self, e: int):
        """The exogenous parts (sa, sb, sda, sdb) of element e's coordinate as real series in theta
        (projections of the grid parts: exact for the harmonic drivers, whose degree nu <= H; a drift
        term t in sb is not periodic and is projected like the rest)."""
        key = ("exo", e)
        v = self._bases.get(key)
        if v is None:
            g = self._grid
            v = self._bases[key] = tuple(x[e] @ self.Pm for x in (g.sa, g.sb, g.sda, g.sdb))
        return v

    def constant_coefficients(self, X, omega) -> bool:
        """Whether the variational equation along the orbit X has coefficients constant between the
        crossings of the exactly integrated laws: every sampled law's dF/ds and dF/ds' are the same at all
        HB samples (a polynomial law of degree <= 3, exact on the grid, whose derivative -- a polynomial
        of the coordinates of degree <= 2H -- takes one value at more than 4H points is constant)."""
        s = self.s
        A = s.Gf @ np.asarray(X, float).reshape(s.n, self.m)
        S, Sd, _ = self._element_coordinates(A, omega)
        for e in self._sampled:
            el = s.elements[e]
            if e in self._rough and not el.sampled_exactly(S[e], Sd[e], s.eps):
                return False
            _, dFs, dFv = el.smooth_force(S[e], Sd[e], s.eps)
            if np.ptp(dFs) != 0 or np.ptp(dFv) != 0:
                return False
        return True

    def rough_exact(self, X, omega) -> bool:
        """Whether every rough (discontinuous, sampled) law is exact on the HB grid along the orbit X."""
        A = self.s.Gf @ np.asarray(X, float).reshape(self.s.n, self.m)
        S, Sd, _ = self._element_coordinates(A, omega)
        return all(self.s.elements[e].sampled_exactly(S[e], Sd[e], self.s.eps) for e in self._rough)

    def rough_exact_batch(self, e: int, S, Sd) -> np.ndarray:
        """Element.sampled_exactly of element e on many orbits' samples S, Sd (P, N) (compiled when the
        model's evaluation is)."""
        ck = self._kernel()
        if ck:
            from .hb_kernel import exact_on_samples_batch

            return exact_on_samples_batch(int(ck.codes[e]), ck.par[e], np.ascontiguousarray(Sd, float))
        el = self.s.elements[e]
        return np.array([el.sampled_exactly(a, b, self.s.eps) for a, b in zip(S, Sd)], bool)

    def _kernel(self):
        """The compiled evaluation (hb_kernel.CompiledHB) or False; built at the first use."""
        if self._compiled is None:
            self._compiled = compiled_evaluation(self, force=self._compile_mode is True)
        return self._compiled

    def pw_projections(self, k: int, Cs, Cv, S, J: int):
        """The k-th exactly integrated law (``_pw[k]``) along P orbits: its projections on harmonics 0..J
        (P, 2J+1) and the period means of dF/ds, dF/ds' (P,) from the series Cs, Cv (P, 2H+1) of s, s' and
        the samples S (P, N) of s (compiled when the model's evaluation is)."""
        i, proj = self._pw[k][0], self._pw[k][1]
        ck = self._kernel()
        if ck:
            from .hb_kernel import pw_projections

            nb = ck.nbrk[i]
            return pw_projections(np.ascontiguousarray(Cs, float), np.ascontiguousarray(Cv, float),
                                  np.ascontiguousarray(S, float), ck.brk[i, :nb], ck.pab[i, 0, :nb + 1],
                                  ck.pab[i, 1, :nb + 1], ck.pab[i, 2, :nb + 1], bool(ck.pflags[i, 0]), self.H, int(J))
        P = Cs.shape[0]
        F = np.zeros((P, 2 * J + 1))
        ms, mv = np.zeros(P), np.zeros(P)
        for i in range(P):
            r = proj.evaluate(Cs[i], Cv[i], S[i], J=J, jac=True)
            F[i] = r["F"]
            ms[i], mv[i] = r["spec_s"][0].real, r["spec_v"][0].real
        return F, ms, mv

    def crossing_phases(self, Xs):
        """Per orbit (Xs: (P, n, 2H+1)), the crossing phases of its exactly integrated laws (sorted per law)."""
        A = self.s.Gf @ Xs                                       # (P, nel, m)
        P = Xs.shape[0]
        ck = self._kernel()
        per = []
        for e, proj, sa, _, _ in self._pw:
            if ck:
                from .hb_kernel import crossing_phases

                nb = ck.nbrk[e]
                off = np.zeros(P + 1, np.int64)
                flat = crossing_phases(np.ascontiguousarray(A[:, e]), np.ascontiguousarray(sa), ck.brk[e, :nb],
                                       self.G, off)
                per.append([flat[off[p]:off[p + 1]] for p in range(P)])
            else:
                from .piecewise import crossings

                per.append([crossings(A[p, e] + sa, (A[p, e] + sa) @ self.G, proj.law.breaks)[0] for p in range(P)])
        return [np.concatenate([c[p] for c in per]) if per else np.zeros(0) for p in range(P)]

    @property
    def exact_elements(self) -> list:
        """Indices of the elements whose laws are integrated exactly (no sampling)."""
        return [p[0] for p in self._pw]

    def times(self, omega):
        return self.theta * self.nu / omega

    def states(self, X, omega):
        n = self.s.n
        Q = X.reshape(n, 2 * self.H + 1)
        Om = omega / self.nu
        return Q @ self.G, Om * (Q @ self.DG), Om * Om * (Q @ self.DDG)

    # ------------------------------------------------------------ residual, Jacobians
    def _linear_jacobians(self):
        """kron(K, I), kron(C, D^T), kron(M, (D^2)^T) of the current K, C, M (rebuilt if replaced)."""
        s = self.s
        key = self._lin
        if key[0] is not s.K or key[1] is not s.C or key[2] is not s.M:
            I = np.eye(self.m)
            self._lin = (s.K, s.C, s.M, (np.kron(s.K, I), np.kron(s.C, self.D.T), np.kron(s.M, self.DD.T)))
        return self._lin[3]

    def galerkin(self, c):
        """Galerkin matrices ``T(c) = Pm^T diag(c) G^T`` (k, m, m) of sampled functions c (k, N): from
        the DFT of c by cos a cos b = (cos(a-b) + cos(a+b))/2 etc."""
        i1, i2, c1, c2 = self._galerkin_maps
        j = np.arange(2 * self.H + 1)
        F = np.fft.rfft(c, axis=-1)[..., j] if 2 * self.H <= self.N // 2 else np.fft.fft(c, axis=-1)[..., j % self.N]
        V = np.concatenate([F.real, -F.imag], axis=-1)
        return (0.5 * self.W)[:, None] * (c1 * V[..., i1] + c2 * V[..., i2])

    def element_blocks(self, cs, cv, Om):
        """``T(cs) + Om T(cv) D^T`` (k, m, m) for sampled dF/ds, dF/ds' sums cs, cv (k, N): one FFT
        and one sparse map of the DFT sums (four entries per matrix entry, :func:`.harmonics.block_maps`)."""
        return self.spectral_blocks(self._dft(np.concatenate([cs, cv])), cs.shape[0], Om)

    def spectral_blocks(self, F, k, Om):
        """:meth:`element_blocks` from the DFT sums ``F`` (2k, 2H+1) of dF/ds (first k rows) and dF/ds'
        (the sums over the N samples, or N times the exact Fourier coefficients)."""
        U = np.empty((k, 4 * self.m))
        m = self.m
        U[:, :m], U[:, m:2 * m] = F.real[:k], -F.imag[:k]
        U[:, 2 * m:3 * m], U[:, 3 * m:] = Om * F.real[k:], -Om * F.imag[k:]
        return (self._block_map @ U.T).T.reshape(k, m, m)

    def _dft(self, c):
        """sum_n c_n exp(-i j theta_n), j = 0 .. 2H, of sampled functions c (k, N)."""
        if 2 * self.H <= self.N // 2:
            return np.fft.rfft(c, axis=-1)[:, :self.m]
        return np.fft.fft(c, axis=-1)[:, np.arange(self.m) % self.N]

    def evaluate_residual(self, X, omega, jac=True, dw=False):
        """(R, J or None, dR/domega or None) at coefficients X and frequency omega (class docstring)."""
        ck = self._kernel()
        if ck:
            return ck(X, omega, jac, dw)
        s = self.s
        n, m, nu = s.n, self.m, self.nu
        Q = X.reshape(n, m)
        Om = omega / nu
        QD = Q @ self.D
        QDD = QD @ self.D
        R = s.K @ Q + Om * (s.C @ QD) + (Om * Om) * (s.M @ QDD)
        fa, fb, fc, fd = self._fP
        for part, scale in self._forcing_terms:
            R -= (fa, fb, fc, fd)[part] * (1.0, 1.0 / omega, omega, omega * omega)[part]
        nel = len(s.elements)
        if nel and (self._pw or self._rough):
            return self._evaluate_piecewise(Q, QD, QDD, R, omega, jac, dw)
        if nel:
            g = self._grid
            S, Sd, ADG = self._element_coordinates(s.Gf @ Q, omega)
            F, dFs, dFv = s.element_laws(S, Sd)
            R -= s.Gf.T @ (F @ self.Pm)
        Rw = None
        if dw:
            Rw = (s.C @ QD + (2 * Om) * (s.M @ QDD)) / nu
            for part, _ in self._forcing_terms:
                if part:
                    Rw -= (None, -fb / omega ** 2, fc, (2 * omega) * fd)[part]
            if nel:
                dSd = ADG / nu + g.sdb if self._exo[3] else ADG / nu
                dS = dFv * dSd
                if self._exo[1]:
                    dS = dS - dFs * g.sb / omega ** 2
                Rw -= s.Gf.T @ (dS @ self.Pm)
            Rw = Rw.ravel()
        J = None
        if jac:
            JK, JC, JM = self._linear_jacobians()
            J = JK + Om * JC + (Om * Om) * JM
            if nel and self._pair_src.size:
                B = self.element_blocks(self._pair_weights @ dFs, self._pair_weights @ dFv, Om)
                if n == 1:
                    J -= B[0]
                else:
                    J = J.reshape(n, m, n, m)
                    J[self._pair_rows, :, self._pair_cols, :] -= B[self._pair_src]
                    J = J.reshape(n * m, n * m)
        return R.ravel(), J, Rw

    def _element_coordinates(self, A, omega):
        """Samples (S, Sd, d Sd/d omega at fixed coefficients) of the element coordinates on the grid."""
        g = self._grid
        Om = omega / self.nu
        nel = A.shape[0]
        SG = np.concatenate([A, A @ self.D]) @ self.G          # [A G; A D G]
        S, ADG = SG[:nel], SG[nel:]
        if self._exo[0]:
            S = S + g.sa
        if self._exo[1]:
            S = S + g.sb / omega
        Sd = Om * ADG
        if self._exo[2]:
            Sd = Sd + g.sda
        if self._exo[3]:
            Sd = Sd + omega * g.sdb
        return S, Sd, ADG

    def element_projection(self, X, omega, jac=True, dw=False, J=None):
        """The Galerkin projection (nel, 2J+1) of every element force on harmonics 0..J (default H; the
        sampled elements need 2J < N), and with ``jac`` the spectra (N-scaled DFT sums (nel, 2H+1)) of
        dF/ds and dF/ds' and the moving-boundary matrices {element: (m, m)}; with ``dw`` the projection of
        dF/domega at fixed coefficients (nel, m)."""
        s = self.s
        n, m, nu = s.n, self.m, self.nu
        Q = np.asarray(X, float).reshape(n, m)
        Om = omega / nu
        A = s.Gf @ Q
        S, Sd, ADG = self._element_coordinates(A, omega)
        nel = A.shape[0]
        Jh = self.H if J is None else int(J)
        Fp = np.zeros((nel, 2 * Jh + 1))
        Fw = np.zeros((nel, m)) if dw else None
        spec_s = spec_v = None
        jumps = {}
        if jac:
            spec_s = np.zeros((nel, m), complex)
            spec_v = np.zeros((nel, m), complex)
        # a rough law found not exact on the HB grid at the last evaluation goes to the dense grid directly
        # (and back to the HB grid once its dense samples show it exact)
        fine_now = [e for e in self._rough if self._go_fine[e]]
        smp = [e for e in self._sampled if e not in fine_now] if fine_now else self._sampled
        for e in fine_now:
            exact = self._fine_element(e, A[e], omega, Jh, jac, dw, Fp, Fw, spec_s, spec_v)
            self._go_fine[e] = not exact
        if smp:
            F = np.empty((len(smp), self.N))
            dFs, dFv = np.empty_like(F), np.empty_like(F)
            for r, e in enumerate(smp):
                F[r], dFs[r], dFv[r] = s.elements[e].smooth_force(S[e], Sd[e], s.eps)
            if Jh == self.H:
                Fp[smp] = F @ self.Pm
            else:
                Fp[smp] = _real_series(np.fft.rfft(F, axis=-1)[:, :Jh + 1], self.N)
            if dw:
                dSd = ADG[smp] / nu + self._grid.sdb[smp] if self._exo[3] else ADG[smp] / nu
                dS = dFv * dSd
                if self._exo[1]:
                    dS = dS - dFs * self._grid.sb[smp] / omega ** 2
                Fw[smp] = dS @ self.Pm
            if jac:
                sp = self._dft(np.concatenate([dFs, dFv]))
                spec_s[smp], spec_v[smp] = sp[:len(smp)], sp[len(smp):]
            for e in self._rough:          # not exact on this grid: the dense grid for this element
                if e in smp and not s.elements[e].sampled_exactly(S[e], Sd[e], s.eps):
                    self._fine_element(e, A[e], omega, Jh, jac, dw, Fp, Fw, spec_s, spec_v)
                    self._go_fine[e] = True
        for e, proj, sa, sda, sdb in self._pw:
            Cs = A[e] + sa
            AD = A[e] @ self.D
            Cv = Om * AD + sda + omega * sdb
            out = proj.evaluate(Cs, Cv, S[e], J=Jh, Cw=(AD / nu + sdb) if dw else None, jac=jac)
            Fp[e] = out["F"]
            if dw:
                Fw[e] = out["Fw"]
            if jac:
                spec_s[e], spec_v[e] = self.N * out["spec_s"], self.N * out["spec_v"]
                if out["jump"] is not None:
                    jumps[e] = out["jump"]
        return Fp, spec_s, spec_v, jumps, Fw

    def _fine_element(self, e, Ae, omega, Jh, jac, dw, Fp, Fw, spec_s, spec_v) -> bool:
        """Element e's projections, spectra (scaled to the HB grid's sums) and dF/domega from the dense grid;
        returns whether its law is exact on samples there (it would be on the HB grid too)."""
        s = self.s
        Nf = self.N_fine
        self.fine_evaluations += 1
        G, DG = self.basis(Nf)
        g = self.grid(Nf)
        Om = omega / self.nu
        Sd_ = Ae @ DG
        S = Ae @ G + g.sa[e] + g.sb[e] / omega
        Sd = Om * Sd_ + g.sda[e] + omega * g.sdb[e]
        F, dFs, dFv = s.elements[e].smooth_force(S, Sd, s.eps)
        Fs = np.fft.rfft(F)
        Fp[e] = _real_series(Fs[:Jh + 1], Nf)
        if dw:
            dS = dFv * (Sd_ / self.nu + g.sdb[e]) - dFs * g.sb[e] / omega ** 2
            Fw[e] = _real_series(np.fft.rfft(dS)[:self.H + 1], Nf)
        if jac:
            scale = self.N / Nf
            spec_s[e] = np.fft.rfft(dFs)[:self.m] * scale
            spec_v[e] = np.fft.rfft(dFv)[:self.m] * scale
        return s.elements[e].sampled_exactly(S, Sd, s.eps)

    def _evaluate_piecewise(self, Q, QD, QDD, R, omega, jac, dw):
        """:meth:`evaluate_residual` with exactly integrated elements (R: the linear part and forcing)."""
        s = self.s
        n, m, nu = s.n, self.m, self.nu
        Om = omega / nu
        Fp, spec_s, spec_v, jumps, Fw = self.element_projection(Q, omega, jac=jac, dw=dw)
        R -= s.Gf.T @ Fp
        Rw = None
        if dw:
            Rw = (s.C @ QD + (2 * Om) * (s.M @ QDD)) / nu
            fa, fb, fc, fd = self._fP
            for part, _ in self._forcing_terms:
                if part:
                    Rw -= (None, -fb / omega ** 2, fc, (2 * omega) * fd)[part]
            Rw -= s.Gf.T @ Fw
            Rw = Rw.ravel()
        J = None
        if jac:
            JK, JC, JM = self._linear_jacobians()
            J = JK + Om * JC + (Om * Om) * JM
            if self._pair_src.size:
                P = self._pair_weights
                B = self.spectral_blocks(np.concatenate([P @ spec_s, P @ spec_v]), P.shape[0], Om)
                for e, Bj in jumps.items():
                    B += P[:, e][:, None, None] * Bj[None]
                if n == 1:
                    J -= B[0]
                else:
                    J = J.reshape(n, m, n, m)
                    J[self._pair_rows, :, self._pair_cols, :] -= B[self._pair_src]
                    J = J.reshape(n * m, n * m)
        return R.ravel(), J, Rw

    def residual(self, X, omega, jac=True):
        R, J, _ = self.evaluate_residual(X, omega, jac=jac)
        return (R, J) if jac else R

    def residual_omega(self, X, omega):
        """dR/domega (analytic: the omega-dependence of the linear part, the forcing and the element
        velocities at fixed coefficients)."""
        return self.evaluate_residual(X, omega, jac=False, dw=True)[2]

    def solve(self, X0, omega, tol=1e-10, maxit=40):
        """Newton at fixed omega; returns (X, iterations)."""
        X = np.array(X0, float)
        scale = max(np.max(np.abs(X)), 1e-300)
        for it in range(1, maxit + 1):
            R, J = self.residual(X, omega)
            try:
                dX = np.linalg.solve(J, -R)
            except np.linalg.LinAlgError as exc:
                raise SolverError(f"HB Jacobian singular at omega = {omega!r}") from exc
            if not np.all(np.isfinite(dX)):
                raise SolverError(f"HB Newton diverged at omega = {omega!r}")
            lam = 1.0
            nR = np.linalg.norm(R)
            while lam > 1e-3:
                Xn = X + lam * dX
                if np.linalg.norm(self.residual(Xn, omega, jac=False)) < (1 - 0.25 * lam) * nR or nR == 0:
                    break
                lam *= 0.5
            X = Xn
            scale = max(np.max(np.abs(X)), 1e-300)
            if np.max(np.abs(lam * dX)) <= tol * scale:
                return X, it
        raise SolverError(f"HB Newton did not converge at omega = {omega!r} in {maxit} iterations")

    def linear_guess(self, omega):
        """One-harmonic (plus mean) solution of the linear part with the element stiffnesses of the
        current (engaged) state ignored: a starting guess."""
        s = self.s
        n = s.n
        X = np.zeros((n, 2 * self.H + 1))
        t = self.times(omega)
        f, _, _ = s.forcing(t, omega)
        Fc = f @ self.Pm
        Om = omega / self.nu
        k = self.nu
        if 2 * k <= 2 * self.H:
            Z = s.K - (k * Om) ** 2 * s.M + 1j * k * Om * s.C
            amp = np.linalg.solve(Z, Fc[:, 2 * k - 1] - 1j * Fc[:, 2 * k])
            X[:, 2 * k - 1] = amp.real
            X[:, 2 * k] = -amp.imag
        try:
            X[:, 0] = np.linalg.solve(s.K, Fc[:, 0])
        except np.linalg.LinAlgError:
            pass
        return X.ravel()

    def basis(self, points: int):
        """(G, D G) sampled at ``points`` equidistant phases (cached)."""
        b = self._bases.get(points)
        if b is None:
            G = uniform_basis(self.H, points)
            b = self._bases[points] = (G, self.D @ G)
        return b

    def grid(self, points: int):
        """The exogenous terms (:meth:`PeriodicSystem.grid_parts`) at ``points`` equidistant phases (cached)."""
        key = ("grid", points)
        g = self._bases.get(key)
        if g is None:
            g = self._bases[key] = self.s.grid_parts(2 * np.pi * np.arange(points) / points, self.nu)
        return g

    def evaluate(self, X, omega, points=None):
        """Time series (t, q, v) over one period at ``points`` equidistant instants."""
        n = self.s.n
        P = points or self.N
        G, DG = self.basis(P)
        th = 2 * np.pi * np.arange(P) / P
        Q = X.reshape(n, 2 * self.H + 1)
        Om = omega / self.nu
        return th / Om, Q @ G, Om * (Q @ DG)


#: DRIVEFEM_JIT=0: every HB evaluation by numpy (the reference path of the compiled kernel); unset, 1 or
#: always (a synonym kept for scripts that set it): the compiled kernel for every model it can evaluate (a
#: Python session: numba's load is paid once); =large: only for models with n (2H+1) >=
#: COMPILED_MIN_UNKNOWNS (the ``drivefem`` command's default: a one-shot process, see compiled_evaluation)
#: (0 is read when this module is imported, large at every decision: the program sets it at start)
COMPILED = os.environ.get("DRIVEFEM_JIT", "1") != "0"
#: the values DRIVEFEM_JIT may take (anything else: a ModelError naming the variable)
JIT_VALUES = ("0", "1", "large", "always")


def jit_setting() -> str:
    """DRIVEFEM_JIT as set (``1`` when unset), checked against :data:`JIT_VALUES`."""
    value = os.environ.get("DRIVEFEM_JIT", "1")
    if value not in JIT_VALUES:
        raise ModelError("environment", "DRIVEFEM_JIT", value,
                         "0 (no compiled kernel), 1 or always (the HB kernel wherever it applies: the default) or "
                         "large (the HB kernel for large models only)")
    return value


#: the compiled kernel for models with at least this many HB unknowns n (2H+1) (see compiled_evaluation)
COMPILED_MIN_UNKNOWNS = 120


def compiled_evaluation(model: HBModel, force: bool = False):
    """The compiled evaluation of ``model`` (:class:`.hb_kernel.CompiledHB`), or False (numpy then).

    Decided per model and the DRIVEFEM_JIT setting, never by what ran before in the process (a curve's
    numbers must not depend on it): the kernel whenever numba is installed, every law of the model is
    compiled or exactly integrated and DRIVEFEM_JIT is not 0 -- except under ``large``, which keeps it to
    models with n (2H+1) >= ``COMPILED_MIN_UNKNOWNS`` (the dense Jacobian's assembly).  ``force``: whenever
    possible, whatever the setting.

    Why: the kernel evaluates a one-DOF Duffing oscillator (H = 7) in ~8 us against ~42 us by numpy, an
    exactly integrated piecewise law in 15-50 us against ~200 us to 2 ms, a rough law on the dense grid
    (friction) in ~0.1 ms against ~1.2 ms.  Its cost is numba's load, once per process: ~0.2 s for the
    cubic-law kernel, ~0.5 s with the piecewise and friction laws (measured on a quiet machine).  A Python
    session pays it once for all its curves (a Duffing curve: 0.28 s the first time, 16 ms after, against
    0.08 s and 32 ms by numpy).  The ``drivefem`` program's analysis commands run one analysis per process: they set
    DRIVEFEM_JIT=large (unless set), where a one-DOF curve never pays the load back (the fresh stop took
    1.35 s with the kernel, 0.86 s without).  Both paths agree to ~1e-12 in every evaluation; a curve's
    derived quantities (a branch point located to its bisection's resolution) may differ by more
    (docs/steady.md)."""
    large = model.nq >= COMPILED_MIN_UNKNOWNS
    if jit_setting() == "large" and not (force or large):
        return False
    try:
        from .hb_kernel import JIT, CompiledHB
    except ImportError:
        return False
    if not JIT:
        return False
    return CompiledHB.build(model) or False


def default_samples(H: int, smoothness: int) -> int:
    """Default AFT samples per period for H harmonics and the roughest sampled law (0: discontinuous,
    1: kinked, 2: smooth)."""
    if smoothness == 0:
        return max(1024, 16 * H)
    if smoothness == 1:
        return max(256, 16 * H)
    return max(64, 8 * H + 4)


def _real_series(F, N):
    """Real series [c0, a1, b1, ..] (the Galerkin projection) from the DFT sums F (k, J+1) of N samples."""
    out = np.empty(F.shape[:-1] + (2 * F.shape[-1] - 1,))
    out[..., 0] = F[..., 0].real / N
    out[..., 1::2] = 2.0 * F[..., 1:].real / N
    out[..., 2::2] = -2.0 * F[..., 1:].imag / N
    return out


def floquet_hb(model: HBModel, X, omega, steps: int | None = None):
    """Floquet multipliers of the variational equation along the HB orbit.

    The period is split into ``steps`` intervals; on each the Jacobian is frozen at the midpoint and the
    interval's transition matrix is ``expm(A_mid h)`` (exponential midpoint rule, 2nd order), computed
    for all intervals at once; the ordered product is formed by pairwise (tree) multiplication.
    """
    return floquet_hb_batch(model, [X], [omega], steps)[0]


def floquet_hb_batch(model: HBModel, Xs, omegas, steps: int | None = None, chunk_entries: int = 1 << 22):
    """:func:`floquet_hb` at many orbits at once (multipliers (P, 2n)): the midpoint Jacobians of all
    orbits are sampled together, their exponentials formed in one batch (closed form
    ``e^tau (cosh d I + sinh d / d (A - tau I))`` for 2x2 blocks, the [6/6] Pade of
    :func:`~discrete.linalg.expm_batch` otherwise) and the ordered products by pairwise multiplication
    in the same order as the single-orbit rule."""
    s = model.s
    n, m, nel = s.n, model.m, len(s.elements)
    Xs = np.asarray(Xs, float).reshape(-1, n, m)
    omegas = np.asarray(omegas, float).ravel()
    if steps is not None or not Xs.shape[0]:
        return _floquet_steps(model, Xs, omegas, steps, chunk_entries)
    if model._pw:
        # piecewise-constant coefficients (every exactly integrated law between its crossings, and every
        # sampled law whose dF/ds, dF/ds' samples are constant: a saturated clutch): the exponentials of
        # the crossing-cut intervals are exact, however few -- eight uniform intervals then suffice
        ck = model._kernel()
        const = ck.constant_coefficients(Xs, omegas) if ck else \
            np.array([model.constant_coefficients(X, w) for X, w in zip(Xs, omegas)])
        if np.any(const):
            out = np.empty((Xs.shape[0], 2 * n), complex)
            out[const] = _floquet_steps(model, Xs[const], omegas[const], 8, chunk_entries)
            if not np.all(const):
                out[~const] = _floquet_default(model, Xs[~const], omegas[~const], chunk_entries)
            return out
    return _floquet_default(model, Xs, omegas, chunk_entries)


def _floquet_default(model, Xs, omegas, chunk_entries):
    """max(512, 2 N) intervals; the dense grid's for the orbits whose rough laws are not exact on the HB grid."""
    if not model._rough:
        return _floquet_steps(model, Xs, omegas, None, chunk_entries)
    n = model.s.n
    fine = np.array([not model.rough_exact(X, w) for X, w in zip(Xs, omegas)])
    if np.any(fine) and not np.all(fine):
        out = np.empty((Xs.shape[0], 2 * n), complex)
        out[fine] = _floquet_steps(model, Xs[fine], omegas[fine], max(512, 2 * model.N_fine), chunk_entries)
        out[~fine] = _floquet_steps(model, Xs[~fine], omegas[~fine], max(512, 2 * model.N), chunk_entries)
        return out
    return _floquet_steps(model, Xs, omegas, max(512, 2 * (model.N_fine if np.any(fine) else model.N)),
                          chunk_entries)


def _floquet_steps(model, Xs, omegas, steps, chunk_entries):
    """The batch with ``steps`` uniform intervals (default max(512, 2 N)), cut at crossings."""
    s = model.s
    n = s.n
    M = steps or max(512, 2 * model.N)
    key = ("mid", M)
    mid = model._bases.get(key)
    if mid is None:
        th = (2 * np.pi * np.arange(2 * M) / (2 * M))[1::2]
        G = _basis(model.H, th)
        mid = model._bases[key] = (G, model.D @ G, s.grid_parts(th, model.nu))
    G, DG, grid = mid
    Minv = np.linalg.inv(s.M)
    d = 2 * n
    split = bool(model._pw)        # exactly integrated laws: intervals split at their crossings
    if split and Xs.shape[0]:
        cuts = _crossing_phases(model, Xs)
        has = np.array([c.size > 0 for c in cuts])
        if not np.all(has):        # orbits without a crossing: the uniform intervals are exact already
            out = np.empty((Xs.shape[0], d), complex)
            out[~has] = _floquet_uniform(model, Xs[~has], omegas[~has], M, chunk_entries)
            if np.any(has):
                out[has] = _floquet_core(model, Xs[has], omegas[has], M, chunk_entries, True,
                                         [c for c, f in zip(cuts, has) if f])
            return out
        return _floquet_core(model, Xs, omegas, M, chunk_entries, True, cuts)
    return _floquet_core(model, Xs, omegas, M, chunk_entries, split)


def _floquet_uniform(model, Xs, omegas, M, chunk_entries):
    return _floquet_core(model, Xs, omegas, M, chunk_entries, False)


def _crossing_phases(model, Xs):
    """Per orbit, the crossing phases of its exactly integrated laws (:meth:`HBModel.crossing_phases`)."""
    return model.crossing_phases(Xs)


def _floquet_core(model, Xs, omegas, M, chunk_entries, split, cuts=None):
    s = model.s
    n, m, nel = s.n, model.m, len(s.elements)
    G, DG, grid = model._bases[("mid", M)]
    Minv = np.linalg.inv(s.M)
    d = 2 * n
    P = max(1, int(chunk_entries // ((M + (8 if split else 0)) * d * d)))
    out = np.empty((Xs.shape[0], d), complex)
    for c0 in range(0, Xs.shape[0], P):
        Q, w = Xs[c0:c0 + P], omegas[c0:c0 + P]
        Om = w / model.nu
        h = 2 * np.pi * model.nu / w / M
        Mp = M
        if split:
            # the piecewise-affine laws' coefficients are constant between crossings: the uniform
            # intervals are cut at the crossings (zero-length padding intervals are identities), so
            # the midpoint exponentials of such a law are exact
            S, Sd, hh = _split_coordinates(model, Q, w, M, None if cuts is None else cuts[c0:c0 + P])
            Mp = hh.shape[1]
            _, dFs, dFv = s.element_laws(np.moveaxis(S, 1, 0), np.moveaxis(Sd, 1, 0))
        elif nel:
            A = s.Gf @ Q                                          # (P, nel, m)
            S = A @ G + grid.sa + grid.sb / w[:, None, None]
            Sd = Om[:, None, None] * (A @ DG) + grid.sda + w[:, None, None] * grid.sdb
            _, dFs, dFv = s.element_laws(np.moveaxis(S, 1, 0), np.moveaxis(Sd, 1, 0))   # (nel, P, M)
        if d == 2:        # one DOF: the 2x2 blocks as component arrays (P, M)
            k = s.K[0, 0] - (np.tensordot(model._gg[:, 0, 0], dFs, 1) if nel else 0.0)
            c = s.C[0, 0] - (np.tensordot(model._gg[:, 0, 0], dFv, 1) if nel else 0.0)
            shape = (Q.shape[0], Mp)         # (k and c are scalars without elements)
            if split:
                E = _expm2_runs(hh, -Minv[0, 0] * k * hh, -Minv[0, 0] * c * hh)
            else:
                E = _expm2_runs(h, np.broadcast_to(-Minv[0, 0] * k * h[:, None], shape),
                                np.broadcast_to(-Minv[0, 0] * c * h[:, None], shape))
            while E[0].shape[1] > 1:
                if E[0].shape[1] % 2:
                    one = np.ones((Q.shape[0], 1))
                    E = tuple(np.concatenate([x, v * one], axis=1) for x, v in zip(E, (1.0, 0.0, 0.0, 1.0)))
                a, b, c_, d_ = E
                E = (a[:, 1::2] * a[:, 0::2] + b[:, 1::2] * c_[:, 0::2], a[:, 1::2] * b[:, 0::2] + b[:, 1::2] * d_[:, 0::2],
                     c_[:, 1::2] * a[:, 0::2] + d_[:, 1::2] * c_[:, 0::2], c_[:, 1::2] * b[:, 0::2] + d_[:, 1::2] * d_[:, 0::2])
            Mono = np.stack([np.stack([E[0][:, 0], E[1][:, 0]], -1), np.stack([E[2][:, 0], E[3][:, 0]], -1)], -2)
            out[c0:c0 + P] = _multipliers(Mono)
            continue
        # the interval matrices depend on (h, dF_e/ds, dF_e/ds') only: piecewise-linear laws (contact on/off)
        # and saturated friction (tanh' = 0 while slipping) repeat them exactly -- exponentiate each once
        hcol = hh.reshape(-1, 1) if split else np.repeat(h, M)[:, None]
        keys = np.concatenate([hcol] + ([dFs.reshape(nel, -1).T, dFv.reshape(nel, -1).T] if nel else []), axis=1)
        first, inv = _unique_rows(keys)
        uk = keys[first]
        hu, fs, fv = uk[:, 0], uk[:, 1:1 + nel], uk[:, 1 + nel:]
        Kq = s.K - np.einsum("eij,ue->uij", model._gg, fs)
        Cv = s.C - np.einsum("eij,ue->uij", model._gg, fv)
        hb3 = hu[:, None, None]
        Y = np.zeros((hu.size, d, d))
        Y[:, :n, n:] = np.eye(n) * hb3
        Y[:, n:, :n] = -(Minv @ Kq) * hb3
        Y[:, n:, n:] = -(Minv @ Cv) * hb3
        E = expm_batch(Y)[inv.ravel()].reshape(Q.shape[0], Mp, d, d)
        while E.shape[1] > 1:           # ordered product E[M-1] ... E[1] E[0]
            if E.shape[1] % 2:
                E = np.concatenate([E, np.broadcast_to(np.eye(d), (E.shape[0], 1, d, d))], axis=1)
            E = E[:, 1::2] @ E[:, 0::2]
        out[c0:c0 + P] = _multipliers(E[:, 0])
    return out


def _multipliers(mono: np.ndarray) -> np.ndarray:
    """Eigenvalues of a batch of monodromy matrices; NaN for one that overflowed (a period the midpoint rule
    does not resolve: stability unknown, so the orbit is not reported stable and its max |mu| is null)."""
    out = np.full(mono.shape[:-1], np.nan, complex)
    ok = np.all(np.isfinite(mono), axis=(-2, -1))
    if np.any(ok):
        out[ok] = np.linalg.eigvals(mono[ok])
    return out


def _split_coordinates(model: HBModel, Q, w, M: int, cuts=None):
    """Element coordinates (S, Sd: (P, nel, M')) at the midpoints of the M uniform intervals of each
    orbit cut at the crossings of its exactly integrated laws, and the intervals' durations hh (P, M')
    (orbits with fewer crossings padded with zero-length intervals at the period's end).  The uniform
    midpoints' values come from the cached midpoint basis; only the sub-intervals of the cut ones are
    evaluated afresh."""
    from .piecewise import basis_at

    s = model.s
    P = Q.shape[0]
    A = s.Gf @ Q                                              # (P, nel, m)
    nel = A.shape[1]
    G, DG, grid = model._bases[("mid", M)]
    cuts = _crossing_phases(model, Q) if cuts is None else cuts
    if model._kernel():
        return _split_compiled(model, Q, A, w, M, cuts)
    extra = max((c.size for c in cuts), default=0)
    Mp = M + extra
    Om = w / model.nu
    S0 = A @ G + grid.sa + grid.sb / w[:, None, None]                        # (P, nel, M)
    Sd0 = Om[:, None, None] * (A @ DG) + grid.sda + w[:, None, None] * grid.sdb
    S = np.empty((P, nel, Mp))
    Sd = np.empty((P, nel, Mp))
    hh = np.zeros((P, Mp))
    h = 2 * np.pi / M
    for p, c in enumerate(cuts):
        c = np.sort(c)
        j = np.minimum((c / h).astype(int), M - 1)
        cut = np.unique(j)
        # sub-intervals of the cut intervals: boundaries = interval ends and the crossings inside
        bnd = np.sort(np.concatenate([cut * h, (cut + 1) * h, c]))
        owner = np.minimum(((bnd[:-1] + bnd[1:]) * 0.5 / h).astype(int), M - 1)
        keep = np.isin(owner, cut) & (bnd[1:] > bnd[:-1])
        lo, hi, owner = bnd[:-1][keep], bnd[1:][keep], owner[keep]
        mids = 0.5 * (lo + hi)
        Bm = basis_at(model.H, mids)                                         # (k, m)
        g = s.grid_parts(mids, model.nu)
        Ss = A[p] @ Bm.T + g.sa + g.sb / w[p]
        Sds = Om[p] * (A[p] @ (Bm @ model.D.T).T) + g.sda + w[p] * g.sdb
        # merge: the uniform intervals not cut, then the sub-intervals, in phase order
        unc = np.setdiff1d(np.arange(M), cut, assume_unique=True)
        ph = np.concatenate([(unc + 0.5) * h, mids])
        order = np.argsort(ph, kind="stable")
        n_ = order.size
        S[p, :, :n_] = np.concatenate([S0[p][:, unc], Ss], axis=1)[:, order]
        Sd[p, :, :n_] = np.concatenate([Sd0[p][:, unc], Sds], axis=1)[:, order]
        hh[p, :n_] = np.concatenate([np.full(unc.size, h), hi - lo])[order]
        if n_ < Mp:                                  # zero-length padding: identities
            S[p, :, n_:] = S[p, :, n_ - 1:n_]
            Sd[p, :, n_:] = Sd[p, :, n_ - 1:n_]
    hh *= (model.nu / w)[:, None]
    return S, Sd, hh


def _split_compiled(model: HBModel, Q, A, w, M: int, cuts):
    """:func:`_split_coordinates` with the intervals laid out by the compiled hb_kernel.split_layout and
    the sub-intervals of all orbits evaluated at once."""
    from .hb_kernel import split_layout
    from .piecewise import basis_at

    s = model.s
    P, nel = A.shape[0], A.shape[1]
    G, DG, grid = model._bases[("mid", M)]
    off = np.zeros(P + 1, np.int64)
    off[1:] = np.cumsum([c.size for c in cuts])
    flat = np.concatenate(cuts) if P else np.zeros(0)
    uni, idx, dur, mids, orbit = split_layout(np.ascontiguousarray(flat, float), off, M)
    Om = w / model.nu
    S0 = A @ G + grid.sa + grid.sb / w[:, None, None]                        # (P, nel, M)
    Sd0 = Om[:, None, None] * (A @ DG) + grid.sda + w[:, None, None] * grid.sdb
    Mp = uni.shape[1]
    S = np.empty((P, Mp, nel))
    Sd = np.empty((P, Mp, nel))
    pp = np.broadcast_to(np.arange(P)[:, None], uni.shape)
    S[uni] = S0.transpose(0, 2, 1)[pp[uni], idx[uni]]
    Sd[uni] = Sd0.transpose(0, 2, 1)[pp[uni], idx[uni]]
    if mids.size:
        Bm = basis_at(model.H, mids)                                         # (K, m)
        g = s.grid_parts(mids, model.nu)
        Ak = A[orbit]                                                        # (K, nel, m)
        Ss = np.einsum("kem,km->ke", Ak, Bm) + g.sa.T + g.sb.T / w[orbit, None]
        Sds = Om[orbit, None] * np.einsum("kem,km->ke", Ak, Bm @ model.D.T) + g.sda.T + w[orbit, None] * g.sdb.T
        S[~uni] = Ss[idx[~uni]]
        Sd[~uni] = Sds[idx[~uni]]
    hh = dur * (model.nu / w)[:, None]
    return S.transpose(0, 2, 1), Sd.transpose(0, 2, 1), hh


def _unique_rows(keys):
    """(first, inverse) of the distinct rows of a float array (rows = keys[first][inverse]): by a 64-bit
    hash of the rows' bit patterns (one integer sort instead of a lexicographic one), verified exactly;
    a collision falls back on numpy's row-wise unique."""
    bits = np.ascontiguousarray(keys).view(np.uint64)
    hsh = np.zeros(bits.shape[0], np.uint64)
    with np.errstate(over="ignore"):
        for j in range(bits.shape[1]):
            hsh = (hsh ^ bits[:, j]) * np.uint64(0x100000001B3) + np.uint64(j + 1)
    _, first, inv = np.unique(hsh, return_index=True, return_inverse=True)
    inv = inv.ravel()
    if np.array_equal(bits[first][inv], bits):
        return first, inv
    _, first, inv = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    return first, inv.ravel()


def _expm2_parts(a, b, c, d):
    """exp of the 2x2 matrices [[a, b], [c, d]] (component arrays) in closed form: with tau = tr/2
    and x = ((a - d)/2)^2 + b c, exp = e^tau (ch I + sh (Y - tau I)), ch = cosh sqrt(x),
    sh = sinh sqrt(x) / sqrt(x) (cos, sin for x < 0; their Taylor series for |x| < 1e-2, truncation
    < 1e-20).  Returns the components (e11, e12, e21, e22)."""
    tau = 0.5 * (a + d)
    x = (0.5 * (a - d)) ** 2 + b * c
    small = np.abs(x) < 1e-2
    pos = x > 0
    r = np.sqrt(np.abs(x))
    if np.all(~pos | small):          # oscillatory (or nearly critical) everywhere: no hyperbolic branch
        ch, sh = np.cos(r), np.sin(r)
    else:
        ch = np.where(pos, np.cosh(r), np.cos(r))
        sh = np.where(pos, np.sinh(r), np.sin(r))
    sh = sh / np.where(small, 1.0, r)
    if np.any(small):
        xs = x[small]
        ch[small] = 1 + xs * (1 / 2 + xs * (1 / 24 + xs * (1 / 720 + xs * (1 / 40320 + xs / 3628800))))
        sh[small] = 1 + xs * (1 / 6 + xs * (1 / 120 + xs * (1 / 5040 + xs * (1 / 362880 + xs / 39916800))))
    et = np.exp(tau)
    esh = et * sh
    return et * (ch + sh * (a - tau)), esh * b, esh * c, et * (ch + sh * (d - tau))


def _expm2_runs(h, c, d):
    """exp of the one-DOF interval matrices [[0, h], [c, d]] (h (P,) or (P, M), c and d (P, M)) as component
    arrays (P, M), each run of equal consecutive intervals exponentiated once: saturated friction
    (tanh' = 0 while slipping) and a contact on or off repeat the matrices exactly (seed 002's
    benchmark branch: 393 runs in 294 912 intervals).  Runs are found on the bit patterns, so the
    result is bit for bit the one of :func:`_expm2_parts` on every interval (finite inputs); with
    more runs than half the intervals (smooth laws) every interval is exponentiated directly."""
    P, M = c.shape
    new = np.ones((P, M), bool)
    c, d = np.ascontiguousarray(c), np.ascontiguousarray(d)
    cb, db = c.view(np.uint64), d.view(np.uint64)
    new[:, 1:] = (cb[:, 1:] != cb[:, :-1]) | (db[:, 1:] != db[:, :-1])
    if np.ndim(h) == 2:
        h = np.ascontiguousarray(h)
        hb = h.view(np.uint64)
        new[:, 1:] |= hb[:, 1:] != hb[:, :-1]
    first = np.flatnonzero(new.ravel())
    if first.size > P * M // 2:
        hh = np.broadcast_to(h if np.ndim(h) == 2 else h[:, None], (P, M))
        return _expm2_parts(np.zeros_like(hh), hh, c, d)
    length = np.diff(first, append=P * M)
    hr = (h.ravel() if np.ndim(h) == 2 else np.repeat(h, M))[first]
    parts = _expm2_parts(np.zeros_like(hr), hr, c.ravel()[first], d.ravel()[first])
    return tuple(np.repeat(p, length).reshape(P, M) for p in parts)


def _expm2(Y):
    """exp of 2x2 matrices (..., 2, 2) by :func:`_expm2_parts`."""
    E = np.empty_like(Y)
    E[..., 0, 0], E[..., 0, 1], E[..., 1, 0], E[..., 1, 1] = _expm2_parts(Y[..., 0, 0], Y[..., 0, 1], Y[..., 1, 0], Y[..., 1, 1])
    return E


def backbone(model: HBModel, A: float, omega0: float, X0=None, tol=1e-12, maxit=50):
    """Free undamped periodic orbit of peak amplitude A of DOF 0 by HB (no forcing, C ignored):
    phase fixed by b1 = 0 of DOF 0 (q even in t), amplitude condition q_0(0) = sum a_k = A.
    Unknowns: the coefficients (b1 of DOF 0 removed) and omega.  Returns (omega, X)."""
    s = model.s
    n, m = s.n, 2 * model.H + 1
    C_save = s.C
    s.C = np.zeros_like(C_save)
    try:
        if X0 is None:
            X0 = np.zeros(n * m)
            X0[1] = A
        X = np.array(X0, float)
        w = float(omega0)
        ib1 = 2
        amp_idx = [0] + [2 * k - 1 for k in range(1, model.H + 1)]
        for it in range(maxit):
            R, J = model.residual(X, w)
            Rw = model.residual_omega(X, w)
            # replace equation ib1 (sin-1 of DOF 0) by the amplitude condition; drop unknown b1
            R2 = R.copy()
            R2[ib1] = X[amp_idx].sum() - A
            J2 = np.hstack([J, Rw[:, None]])
            J2[ib1, :] = 0.0
            J2[ib1, amp_idx] = 1.0
            keep = [j for j in range(n * m + 1) if j != ib1]
            du = np.linalg.solve(J2[:, keep], -R2)
            step = np.zeros(n * m + 1)
            step[keep] = du
            X = X + step[:-1]
            X[ib1] = 0.0
            w = w + step[-1]
            if np.max(np.abs(step)) <= tol * max(1.0, abs(A), abs(w)):
                return w, X
        raise SolverError(f"HB backbone did not converge at A = {A!r}")
    finally:
        s.C = C_save


START_EVALUATIONS = 500_000     # right-hand sides of the time integration that starts HB (then a solver failure)


def time_guess(model: HBModel, omega, periods: int = 60, y0=None):
    """Starting coefficients from time integration of the same (smooth/penalty) model: ``periods``
    forcing periods from rest (or y0) with DOP853, then the last period projected on the harmonics."""
    from scipy.integrate import solve_ivp

    s = model.s
    n = s.n
    T = 2 * np.pi * model.nu / omega
    ode = s.ode(omega)
    calls = [0]

    def fun(t, y):           # the stiffness at the amplitude reached is not known beforehand: count the work
        calls[0] += 1
        if calls[0] > START_EVALUATIONS:
            raise SolverError(f"the time integration for the start used its {START_EVALUATIONS} right-hand-side "
                              f"evaluations at t = {t:.6g} s of {periods} periods: the model is too stiff for "
                              "DOP853 at the amplitude reached (a huge stiffness or nonlinear coefficient, a tiny "
                              "inertia)")
        return ode(t, y)

    y = np.zeros(2 * n) if y0 is None else np.asarray(y0, float)
    t1 = (periods - 1) * T
    sol = solve_ivp(fun, (0.0, t1), y, method="DOP853", rtol=1e-8, atol=1e-12, max_step=T / 32)
    t_last = t1 + model.theta / (omega / model.nu)
    sol2 = solve_ivp(fun, (t1, t1 + T), sol.y[:, -1], method="DOP853", rtol=1e-10, atol=1e-13,
                     t_eval=t_last, max_step=T / 32)
    q = sol2.y[:n]
    return (q @ model.Pm).ravel()
