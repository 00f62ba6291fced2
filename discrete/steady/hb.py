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

import numpy as np

from ..linalg.expm import expm_batch
from ..errors import SolverError


class HBModel:
    """Residual and Jacobian of harmonic balance for a :class:`PeriodicSystem`."""

    def __init__(self, system, harmonics: int = 5, nu: int = 1, samples: int | None = None):
        self.s = system
        self.H = int(harmonics)
        self.nu = int(nu)
        H = self.H
        # discontinuous (friction sign) or kinked (one-sided, gap) forces: AFT sampling error ~ 1/N
        # resp. 1/N^2, so these get a denser default grid
        smooth = min((el.smoothness for el in system.elements), default=2)
        N = samples or (max(1024, 16 * H) if smooth == 0 else max(256, 16 * H) if smooth == 1 else max(64, 8 * H + 4))
        self.N = N
        th = 2 * np.pi * np.arange(N) / N
        G = np.ones((2 * H + 1, N))
        D = np.zeros((2 * H + 1, 2 * H + 1))
        for k in range(1, H + 1):
            G[2 * k - 1] = np.cos(k * th)
            G[2 * k] = np.sin(k * th)
            D[2 * k, 2 * k - 1] = k       # d/dtheta: a_k' = k b_k, b_k' = -k a_k   (Qd = Q @ D)
            D[2 * k - 1, 2 * k] = -k
        W = np.full(2 * H + 1, 2.0 / N)
        W[0] = 1.0 / N
        self.G, self.D, self.theta = G, D, th
        self.Pm = G.T * W          # (N, 2H+1): R = r @ Pm
        self.DG = D @ G
        self.DDG = D @ D @ G
        self.nq = system.n * (2 * H + 1)

    def times(self, omega):
        return self.theta * self.nu / omega

    def states(self, X, omega):
        n = self.s.n
        Q = X.reshape(n, 2 * self.H + 1)
        Om = omega / self.nu
        return Q @ self.G, Om * (Q @ self.DG), Om * Om * (Q @ self.DDG)

    def residual(self, X, omega, jac=True):
        s = self.s
        n = s.n
        t = self.times(omega)
        q, v, a = self.states(X, omega)
        Fs, Fq, Fv = s.rhs_terms(t, q, v, omega)
        r = s.M @ a + s.C @ v + s.K @ q - Fs
        R = (r @ self.Pm).ravel()
        if not jac:
            return R
        Om = omega / self.nu
        m = 2 * self.H + 1
        J = np.zeros((n * m, n * m))
        Jq = s.K[:, :, None] - Fq
        Jv = s.C[:, :, None] - Fv
        PmT = self.Pm.T
        for i in range(n):
            for j in range(n):
                blk = (PmT * Jq[i, j]) @ self.G.T + Om * (PmT * Jv[i, j]) @ self.DG.T \
                    + Om * Om * s.M[i, j] * (PmT @ self.DDG.T)
                J[i * m:(i + 1) * m, j * m:(j + 1) * m] = blk
        return R, J

    def residual_omega(self, X, omega):
        h = 1e-6 * omega
        return (self.residual(X, omega + h, jac=False) - self.residual(X, omega - h, jac=False)) / (2 * h)

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

    def evaluate(self, X, omega, points=None):
        """Time series (t, q, v) over one period at ``points`` equidistant instants."""
        n = self.s.n
        H = self.H
        P = points or self.N
        th = 2 * np.pi * np.arange(P) / P
        G = np.ones((2 * H + 1, P))
        for k in range(1, H + 1):
            G[2 * k - 1] = np.cos(k * th)
            G[2 * k] = np.sin(k * th)
        Q = X.reshape(n, 2 * H + 1)
        Om = omega / self.nu
        return th / Om, Q @ G, Om * (Q @ self.D @ G)


def floquet_hb(model: HBModel, X, omega, steps: int | None = None):
    """Floquet multipliers of the variational equation along the HB orbit.

    The period is split into ``steps`` intervals; on each the Jacobian is frozen at the midpoint and the
    interval's transition matrix is ``expm(A_mid h)`` (exponential midpoint rule, 2nd order), computed
    for all intervals at once; the ordered product is formed by pairwise (tree) multiplication.
    """
    s = model.s
    n = s.n
    M = steps or max(512, 2 * model.N)
    T = 2 * np.pi * model.nu / omega
    t, q, v = model.evaluate(X, omega, points=2 * M)
    t, q, v = t[1::2], q[:, 1::2], v[:, 1::2]
    _, Fq, Fv = s.rhs_terms(t, q, v, omega)
    Minv = np.linalg.inv(s.M)
    A = np.zeros((M, 2 * n, 2 * n))
    A[:, :n, n:] = np.eye(n)
    A[:, n:, :n] = -np.einsum("ij,jkm->mik", Minv, s.K[:, :, None] - Fq)
    A[:, n:, n:] = -np.einsum("ij,jkm->mik", Minv, s.C[:, :, None] - Fv)
    E = expm_batch(A * (T / M))
    while E.shape[0] > 1:           # ordered product E[M-1] ... E[1] E[0]
        if E.shape[0] % 2:
            E = np.concatenate([E, np.eye(2 * n)[None]], axis=0)
        E = E[1::2] @ E[0::2]
    return np.linalg.eigvals(E[0])


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


def time_guess(model: HBModel, omega, periods: int = 60, y0=None):
    """Starting coefficients from time integration of the same (smooth/penalty) model: ``periods``
    forcing periods from rest (or y0) with DOP853, then the last period projected on the harmonics."""
    from scipy.integrate import solve_ivp

    s = model.s
    n = s.n
    T = 2 * np.pi * model.nu / omega
    fun = s.ode(omega)
    y = np.zeros(2 * n) if y0 is None else np.asarray(y0, float)
    t1 = (periods - 1) * T
    sol = solve_ivp(fun, (0.0, t1), y, method="DOP853", rtol=1e-8, atol=1e-12, max_step=T / 32)
    t_last = t1 + model.theta / (omega / model.nu)
    sol2 = solve_ivp(fun, (t1, t1 + T), sol.y[:, -1], method="DOP853", rtol=1e-10, atol=1e-13,
                     t_eval=t_last, max_step=T / 32)
    q = sol2.y[:n]
    return (q @ model.Pm).ravel()
