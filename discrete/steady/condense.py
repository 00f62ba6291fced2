"""Exact dynamic condensation of harmonic balance onto the nonlinear DOFs.

The nonlinear element forces of a :class:`~discrete.steady.system.PeriodicSystem` act only on the DOFs
their directions ``g_e`` touch (the *coupling* DOFs c; the others are l).  Harmonic k of the HB
equations (:mod:`discrete.steady.hb`) is, with ``z = a_k - i b_k`` the complex coefficient of a DOF
(``q = Re(z e^{i k Om t})``, Om = omega / nu) and ``Z_k = K - (k Om)^2 M + i k Om C``:

    [Z_cc Z_cl] [z_c]   [f_c]   [sum_e g_e F_e,k]
    [Z_lc Z_ll] [z_l] = [f_l] + [       0       ]

so ``z_l = Z_ll^-1 (f_l - Z_lc z_c)`` exactly, and the HB unknowns reduce to the coupling DOFs' with the
linear part replaced by the Schur complement (the inverse of the receptance of the linear structure seen
from c) and the condensed forcing:

    S_k = Z_cc - Z_cl Z_ll^-1 Z_lc,     f~_k = f_c - Z_cl Z_ll^-1 f_l.

Both, and their derivatives in omega (``dS = dZ_cc - dZ_cl X - Y dZ_lc + Y dZ_ll X`` with
``X = Z_ll^-1 Z_lc``, ``Y = Z_cl Z_ll^-1``), are formed once per frequency from one factorisation of
``Z_ll`` per harmonic (batched; the last few frequencies are cached: the continuation's fixed-frequency
solves, landing and fold refinement reuse them).  The nonlinear part (AFT of the element laws, exact
Jacobian blocks) is the one of :class:`~discrete.steady.hb.HBModel`, evaluated on the coupling DOFs only
(:class:`CouplingSystem`: the same elements and exogenous coordinates, no linear matrices).  The
condensed solution, expanded by :meth:`CondensedHB.expand`, solves the full HB equations: the two
differ by round-off only (tests/test_steady_condense.py: 1e-10 on the hybrid AFC examples).

When it pays (:func:`condensation_rule`): the full HB Jacobian is dense (n (2H+1))^2 and its LU costs
(n (2H+1))^3 / 3 per Newton step; condensed, (n_c (2H+1))^3 / 3 plus (H+1) complex factorisations of
n_l x n_l (compiled: condense_kernel.py, ~15 us for H = 25).  ``[steady] condense = "auto"`` condenses
when n_c <= n / 2 and n (2H+1) >= 120 (measured per continuation point on chains of 2-4 bodies with one
cubic spring: equal cost at 93 and 102 unknowns, 15 % less at 124, half at the hybrid cantilever's
204), and
the linear part seen from c is regular at the start (the static ``K_ll`` is invertible: no rigid motion
of the linear DOFs with the coupling DOFs held).  ``"yes"`` forces it (an error if it is impossible),
``"no"`` switches it off.
"""
from __future__ import annotations

import numpy as np

from ..errors import ModelError, SolverError
from .hb import HBModel
from .system import GridParts

#: condense = "auto": the full system's HB size n (2H+1) from which condensation pays (measured, module doc)
AUTO_MIN_UNKNOWNS = 120


def coupling_dofs(system) -> np.ndarray:
    """The free DOFs touched by a nonlinear element direction (sorted indices)."""
    Gf = np.asarray(system.Gf, float).reshape(len(system.elements), system.n)
    return np.flatnonzero(np.any(Gf != 0.0, axis=0))


def condensation_rule(system, harmonics: int, mode: str = "auto") -> tuple[bool, str]:
    """(condense?, why) for ``[steady] condense = mode`` ("auto" | "yes" | "no") -- module docstring."""
    n = system.n
    c = coupling_dofs(system)
    nc = c.size
    m = 2 * int(harmonics) + 1
    if mode == "no":
        return False, "condense = \"no\""
    why_not = None
    if nc == 0:
        why_not = "the model has no nonlinear element"
    elif nc == n:
        why_not = f"every one of the {n} DOFs carries a nonlinear element"
    else:
        l = np.setdiff1d(np.arange(n), c)
        Kll = np.asarray(system.K, float)[np.ix_(l, l)]
        cond = np.linalg.cond(Kll) if l.size else 1.0
        if not np.isfinite(cond) or cond > 1e12:
            why_not = (f"the linear DOFs have a rigid motion with the {nc} nonlinear DOF(s) held (static K_ll "
                       f"singular, condition {cond:.2g})")
    if mode == "yes":
        if why_not is not None:
            raise ModelError("[steady]", "condense", "yes", f"'auto' or 'no' for this model ({why_not})")
        return True, f"condense = \"yes\": {n} -> {nc} DOFs"
    if why_not is not None:
        return False, why_not
    if nc > n / 2 or n * m < AUTO_MIN_UNKNOWNS:
        return False, (f"not worth it: {n} -> {nc} DOFs, {n * m} HB unknowns (auto condenses from "
                       f"{AUTO_MIN_UNKNOWNS} unknowns and at most half of the DOFs nonlinear)")
    return True, f"auto: {n} -> {nc} DOFs ({n * m} -> {nc * m} HB unknowns)"


class CouplingSystem:
    """The nonlinear part of a :class:`PeriodicSystem` on its coupling DOFs c: the element directions
    restricted to c, the elements' exogenous coordinates as they are, and no linear matrices or forcing
    (zero M, C, K, zero exogenous forces) -- an :class:`HBModel` of it evaluates exactly the element
    terms of the HB residual and Jacobian.  Everything else is the full system's."""

    def __init__(self, system, dofs):
        self._full = system
        self.dofs = np.asarray(dofs, int)
        self.n = int(self.dofs.size)
        z = np.zeros((self.n, self.n))
        self.M, self.C, self.K = z, z.copy(), z.copy()
        self.Gf = np.ascontiguousarray(np.asarray(system.Gf, float)[:, self.dofs])
        self.gf = [g[self.dofs] for g in system.gf]

    def __getattr__(self, name):          # elements, eps, element_laws, smooth_ok, ... of the full system
        return getattr(self._full, name)

    def grid_parts(self, theta, nu: int = 1) -> GridParts:
        g = self._full.grid_parts(theta, nu)
        zero = np.zeros((self.n, np.size(theta)))
        return GridParts(fa=zero, fb=zero, fc=zero, fd=zero, sa=g.sa, sb=g.sb, sda=g.sda, sdb=g.sdb)

    def element_laws(self, S, Sd):
        return self._full.element_laws(S, Sd)


class CondensedHB:
    """HB residual on the coupling DOFs with the exactly condensed linear part (module docstring); the
    interface of :class:`HBModel` that the continuation uses (``evaluate_residual``, ``residual``,
    ``solve``), plus :meth:`expand` / :meth:`restrict` between condensed and full coefficients."""

    def __init__(self, full: HBModel, cache: int = 4, compiled: bool = True):
        s = full.s
        self.full = full
        self.s = s
        self.H, self.nu, self.m, self.N = full.H, full.nu, full.m, full.N
        self.c = coupling_dofs(s)
        self.l = np.setdiff1d(np.arange(s.n), self.c)
        # the element part exactly as the full model evaluates it: the same grids (N, and N_fine for rough
        # laws) and the same kinks option (piecewise-affine laws integrated exactly over their crossings)
        # compiled or numpy as the full model is (hb.compiled_evaluation decides on the full model's size and
        # laws, and DRIVEFEM_JIT): the inner model and the condensation follow that one decision
        self._use_kernel = bool(compiled) and bool(full._kernel())
        self.inner = HBModel(CouplingSystem(s, self.c), harmonics=full.H, nu=full.nu, samples=full.samples,
                             kinks=full.kinks, compiled=self._use_kernel)
        H = self.H
        self.k = np.arange(H + 1)
        M, C, K = (np.asarray(a, float) for a in (s.M, s.C, s.K))
        self._MCK = (M[None], C[None], K[None])
        c, l = self.c, self.l
        self._ix = {"cc": np.ix_(c, c), "cl": np.ix_(c, l), "lc": np.ix_(l, c), "ll": np.ix_(l, l)}
        # Z^T = Z (symmetric M, C, K): Y = Z_cl Z_ll^-1 = X^T without a second (transposed) solve
        self._symmetric = all(np.array_equal(A, A.T) for A in (M, C, K))
        # exogenous forcing on the HB grid by powers of omega (system.grid_parts), as complex harmonics
        g = s.grid_parts(full.theta, full.nu)
        self._F = np.stack([self._complex(f @ full.Pm) for f in (g.fa, g.fb, g.fc, g.fd)])   # (4, H+1, n)
        self._cache: dict = {}
        self._cache_size = max(1, int(cache))
        self.compiled = self._use_kernel
        nc, m = self.c.size, self.m
        self.nq = nc * m
        # positions of the real 2x2 blocks [[Sr, Si], [-Si, Sr]] in the (nc, m, nc, m) Jacobian
        self._cos = 2 * self.k[1:] - 1
        self._sin = 2 * self.k[1:]

    # ------------------------------------------------------------ coefficient layouts
    def _complex(self, F):
        """(n, m) real coefficients [a0, a1, b1, ...] -> (H+1, n) complex z_k = a_k - i b_k (z_0 = a_0)."""
        Z = np.empty((self.H + 1, F.shape[0]), complex)
        Z[0] = F[:, 0]
        Z[1:] = (F[:, 1::2] - 1j * F[:, 2::2]).T
        return Z

    def _real(self, Z):
        """(H+1, n) complex harmonics -> (n, m) real coefficients (inverse of :meth:`_complex`)."""
        F = np.empty((Z.shape[1], self.m))
        F[:, 0] = Z[0].real
        F[:, 1::2] = Z[1:].real.T
        F[:, 2::2] = -Z[1:].imag.T
        return F

    # ------------------------------------------------------------ the condensed linear operator
    def operator(self, omega: float) -> dict:
        """S_k, dS_k/domega, f~_k, df~_k/domega (k = 0 .. H) and the expansion maps at ``omega`` (the
        compiled kernel of condense_kernel.py; :meth:`operator_numpy` is the same algebra batched)."""
        key = float(omega)
        op = self._cache.get(key)
        if op is not None:
            return op
        if not self.compiled:
            return self.operator_numpy(omega)
        from .condense_kernel import operator

        M, C, K = (A[0] for A in self._MCK)
        S, dS, ft, dft, X, wf, ok = operator(M, C, K, self.c, self.l, self._F, key, float(self.nu), self._symmetric)
        if not ok:
            raise SolverError(f"condensed HB: the linear part with the nonlinear DOFs held is singular at "
                              f"omega = {key!r} (a resonance of the linear structure): use condense = \"no\"")
        return self._store(key, S, dS, ft, dft, X if self.l.size else None, wf if self.l.size else None)

    def _store(self, key, S, dS, ft, dft, X, wf):
        if self.compiled:
            from .condense_kernel import real_jacobian

            J, finite = real_jacobian(S)
            finite = finite and bool(np.all(np.isfinite(ft)))
        else:
            J, finite = self._real_jacobian(S), bool(np.all(np.isfinite(S)) and np.all(np.isfinite(ft)))
        if not finite:
            raise SolverError(f"condensed HB: the condensed operator is not finite at omega = {key!r}")
        op = {"S": S, "dS": dS, "f": ft, "df": dft, "X": X, "wf": wf, "J": J}
        if len(self._cache) >= self._cache_size:
            del self._cache[next(iter(self._cache))]
        self._cache[key] = op
        return op

    def operator_numpy(self, omega: float) -> dict:
        """:meth:`operator` by batched numpy calls (the reference of the compiled kernel)."""
        key = float(omega)
        k = self.k[:, None, None]
        kO = k * (key / self.nu)
        Mf, Cf, Kf = self._MCK
        Zf = Kf - (kO * kO) * Mf + 1j * kO * Cf                             # (H+1, n, n)
        dZf = ((-2.0 * k * kO) * Mf + 1j * k * Cf) / self.nu

        def Z(name):
            return Zf[(slice(None),) + self._ix[name]]

        def dZ(name):
            return dZf[(slice(None),) + self._ix[name]]

        Fa, Fb, Fc, Fd = self._F
        F = Fa + Fb / key + key * Fc + key * key * Fd                       # (H+1, n)
        dF = -Fb / key ** 2 + Fc + 2.0 * key * Fd
        c, l = self.c, self.l
        Zcc, Zcl, Zlc = Z("cc"), Z("cl"), Z("lc")
        dZcc, dZcl, dZlc = dZ("cc"), dZ("cl"), dZ("lc")
        if l.size:
            Zll = Z("ll")
            dZll = dZ("ll")
            try:
                sol = np.linalg.solve(Zll, np.concatenate([Zlc, F[:, l, None]], axis=2))
                Yt = sol[..., :-1] if self._symmetric else np.linalg.solve(np.swapaxes(Zll, 1, 2),
                                                                           np.swapaxes(Zcl, 1, 2))
            except np.linalg.LinAlgError as exc:
                raise SolverError(f"condensed HB: the linear part with the nonlinear DOFs held is singular at "
                                  f"omega = {key!r} (a resonance of the linear structure): use condense = \"no\"") from exc
            X, wf = sol[..., :-1], sol[..., -1]
            Y = np.swapaxes(Yt, 1, 2)
            YdZll = Y @ dZll
            S = Zcc - Zcl @ X
            dS = dZcc - dZcl @ X - Y @ dZlc + YdZll @ X
            ft = F[:, c] - np.einsum("kij,kj->ki", Zcl, wf)
            dft = (dF[:, c] - np.einsum("kij,kj->ki", dZcl, wf) - np.einsum("kij,kj->ki", Y, dF[:, l])
                   + np.einsum("kij,kj->ki", YdZll, wf))
        else:
            X = wf = None
            S, dS, ft, dft = Zcc, dZcc, F[:, c], dF[:, c]
        return self._store(key, S, dS, ft, dft, X, wf)

    def _real_jacobian(self, S):
        """The real (nc m)^2 Jacobian of ``Re/-Im (S_k z_k)`` in the coefficients [a0, a1, b1, ...]."""
        nc, m = self.c.size, self.m
        J = np.zeros((nc, m, nc, m))
        Sr, Si = S.real, S.imag
        J[:, 0, :, 0] = Sr[0]
        ic, is_ = self._cos, self._sin
        J[:, ic, :, ic] = Sr[1:]
        J[:, ic, :, is_] = Si[1:]
        J[:, is_, :, ic] = -Si[1:]
        J[:, is_, :, is_] = Sr[1:]
        return J.reshape(nc * m, nc * m)

    # ------------------------------------------------------------ residual
    def evaluate_residual(self, X, omega, jac=True, dw=False):
        """(R, J or None, dR/domega or None) of the condensed HB equations at coefficients X (nc, m)."""
        op = self.operator(omega)
        nc = self.c.size
        Q = np.asarray(X, float).reshape(nc, self.m)
        R_nl, J_nl, Rw_nl = self.inner.evaluate_residual(X, omega, jac=jac, dw=dw)
        J = None if not jac else J_nl + op["J"]
        Rw = None
        if self.compiled:
            from .condense_kernel import linear_residual

            Q = np.ascontiguousarray(Q)
            R = R_nl + linear_residual(op["S"], op["f"], Q)
            if dw:
                Rw = Rw_nl + linear_residual(op["dS"], op["df"], Q)
            return R, J, Rw
        Zc = self._complex(Q)
        R = R_nl + self._real(np.einsum("kij,kj->ki", op["S"], Zc) - op["f"]).ravel()
        if dw:
            Rw = Rw_nl + self._real(np.einsum("kij,kj->ki", op["dS"], Zc) - op["df"]).ravel()
        return R, J, Rw

    def residual(self, X, omega, jac=True):
        R, J, _ = self.evaluate_residual(X, omega, jac=jac)
        return (R, J) if jac else R

    def residual_omega(self, X, omega):
        return self.evaluate_residual(X, omega, jac=False, dw=True)[2]

    def solve(self, X0, omega, tol=1e-10, maxit=40):
        """Newton at fixed omega (as :meth:`HBModel.solve`); returns (X, iterations)."""
        return HBModel.solve(self, X0, omega, tol=tol, maxit=maxit)

    # ------------------------------------------------------------ full <-> condensed
    def restrict(self, X_full):
        """The coupling DOFs' coefficients of full coefficients (n m,) -> (nc m,)."""
        return np.asarray(X_full, float).reshape(self.s.n, self.m)[self.c].ravel()

    def expand(self, X, omega):
        """Full coefficients (n m,) of condensed ones: ``z_l = Z_ll^-1 (f_l - Z_lc z_c)`` per harmonic."""
        op = self.operator(omega)
        nc = self.c.size
        Qc = np.asarray(X, float).reshape(nc, self.m)
        if self.compiled and self.l.size:
            from .condense_kernel import expand

            return expand(np.ascontiguousarray(Qc), self.c, self.l, op["X"], op["wf"]).ravel()
        Q = np.empty((self.s.n, self.m))
        Q[self.c] = Qc
        if self.l.size:
            Zl = op["wf"] - np.einsum("kij,kj->ki", op["X"], self._complex(Qc))
            Q[self.l] = self._real(Zl)
        return Q.ravel()

    def start(self, omega, fallback):
        """The converged condensed state at ``omega``: Newton from the restricted linear guess of the full
        model, else ``fallback()`` (a converged full state) restricted and polished."""
        try:
            return self.solve(self.restrict(self.full.linear_guess(omega)), omega)[0]
        except (SolverError, np.linalg.LinAlgError):
            return self.solve(self.restrict(fallback()), omega)[0]


def condensed_model(system, hb: HBModel, mode: str = "auto"):
    """(CondensedHB or None, why) for ``[steady] condense = mode`` (:func:`condensation_rule`)."""
    ok, why = condensation_rule(system, hb.H, mode)
    return (CondensedHB(hb) if ok else None), why


def arclength_scale(cond: CondensedHB, X0, omega, xs: float | None = None) -> np.ndarray:
    """Per-unknown scales of the condensed continuation that measure its arc length as the full HB
    continuation does (to first order, at the start frequency): the full continuation scales every
    coefficient by the largest full coefficient ``xs``; a condensed coefficient j moves the full state by
    ``E[:, j]`` (E = d expand / d X_c: the identity on c, ``-Z_ll^-1 Z_lc`` on l), so its scale is
    ``xs / |E[:, j]|`` (``xs``: given, or the largest coefficient of the expanded X0)."""
    if xs is None:
        xs = max(np.max(np.abs(cond.expand(X0, omega))), 1e-12)
    nc, m = cond.c.size, cond.m
    op = cond.operator(omega)
    w = np.ones((nc, m))
    if cond.l.size:
        Xk = op["X"]                                     # (H+1, nl, nc): z_l = wf - X z_c
        # a unit a_k (b_k) of DOF j changes z_l by -X[k][:, j] (resp. +i X[k][:, j]): |.|^2 over l, real layout
        col = np.sum(np.abs(Xk) ** 2, axis=1)            # (H+1, nc)
        w[:, 0] += col[0].real
        w[:, 1::2] += col[1:].T
        w[:, 2::2] += col[1:].T
    return (xs / np.sqrt(w)).ravel()
