"""References for parametric vibrations (textbook ch. 7, seed 001 §7.1-7.3), independent of the
Floquet integration in :mod:`discrete.linear.parametric`.

Conventions (the book's, checked against (7.31)): one DOF, ``q'' + 2 n q' + k0^2 (1 - eps sin
Omega t) q = 0``, ``n = zeta k0`` and, for the dissipation coefficient psi,
``zeta = delta = psi / (4 pi)`` (``2 n0 = 0.5 psi k0 / pi`` in (7.31); the book's energy
balance uses Delta E- = 0.5 psi c A^2 with lambda = psi/2, not psi = 1 - exp(-2 lambda)).

Methods:

* Hill's infinite determinant, truncated and checked for convergence: at a tongue edge the
  equation has a solution of period T (multiplier +1) or 2T (-1), q = sum c_m exp(i m Omega t / 2)
  with m even or odd; substituting gives a linear eigenproblem in the unknown parameter
  (k0^2 / Omega^2 for undamped edges, eps for damped thresholds).
* scipy.special.mathieu_a / mathieu_b (characteristic values of the Mathieu equation
  y'' + (a - 2 q cos 2x) y = 0): with x = Omega t / 2 + pi/4, a = 4 k0^2 / Omega^2,
  q = 2 k0^2 eps / Omega^2 (the sign of q only swaps a_s and b_s for odd s).
* The energy method of §7.3: (7.27)-(7.28) eps* = psi / pi, (7.30) A* = 8 |P| / (pi c0 eps),
  with a quadrature check of the energy integrals (note the printed Delta E+ lacks sin Omega t).
* The pendulum-rod of Fig. 7.5 as a rigid body with exact kinematics, for time integration.
* The conditional-oscillator transformation (7.10)-(7.12) (with the corrected (7.11): n q1, not
  n q) that turns a variable-inertia equation into a Hill equation without damping term.
"""
from __future__ import annotations

import math

import numpy as np
import scipy.integrate as si
import scipy.linalg as sla
import scipy.optimize as so
from scipy.special import mathieu_a, mathieu_b

from discrete.linalg import single_threaded_blas


# ------------------------------------------------------------------ energy method (§7.3)
def zeta_from_psi(psi: float) -> float:
    """Viscous ratio of the book's dissipation coefficient: zeta = delta = psi / (4 pi) (7.31)."""
    return psi / (4 * math.pi)


def energy_threshold(psi: float) -> float:
    """(7.28): eps* = psi / pi (first-order energy balance at Omega = 2 k0)."""
    return psi / math.pi


def friction_critical_amplitude(P: float, c0: float, eps: float) -> float:
    """(7.30): A* = 8 |P| / (pi c0 eps) -- below it Coulomb friction P stops the principal
    parametric resonance, above it the amplitude grows (a critical amplitude, not depth)."""
    return 8 * abs(P) / (math.pi * c0 * eps)


def energy_input_per_cycle(A: float, alpha: float, *, eps: float, c0: float, k0: float) -> float:
    """Delta E+ = eps c0 int_0^T y y' sin(Omega t) dt over T = 2 pi / k0 with y = A sin(k0 t + alpha)
    and Omega = 2 k0, by adaptive quadrature (the book prints the integrand without sin Omega t).
    Closed form (§7.3): 0.5 pi eps c0 A^2 cos 2 alpha."""
    def integrand(t):
        y = A * math.sin(k0 * t + alpha)
        v = A * k0 * math.cos(k0 * t + alpha)
        return eps * c0 * y * v * math.sin(2 * k0 * t)

    return si.quad(integrand, 0.0, 2 * math.pi / k0, epsabs=0.0, epsrel=1e-13, limit=200)[0]


def coulomb_loss_per_cycle(A: float, *, P: float, k0: float) -> float:
    """Delta E- = int_0^T |P| |y'| dt for y = A sin(k0 t) (5.70): 4 |P| A, by quadrature."""
    return si.quad(lambda t: abs(P) * abs(A * k0 * math.cos(k0 * t)), 0.0, 2 * math.pi / k0,
                   points=[math.pi / (2 * k0), 3 * math.pi / (2 * k0)], epsabs=0.0, epsrel=1e-13)[0]


def friction_critical_amplitude_by_energy(P: float, c0: float, eps: float, k0: float = 1.0) -> float:
    """A* from the energy integrals themselves: the amplitude at which the largest input over the
    phase alpha (max_alpha Delta E+) equals the Coulomb loss, found by root finding."""
    best = so.minimize_scalar(lambda a: -energy_input_per_cycle(1.0, a, eps=eps, c0=c0, k0=k0),
                              bounds=(-1.0, 1.0), method="bounded", options={"xatol": 1e-10})
    gain = -best.fun                                # per unit A^2
    loss = coulomb_loss_per_cycle(1.0, P=P, k0=k0)  # per unit A
    return so.brentq(lambda A: gain * A * A - loss * A, 1e-9 * loss / gain + 1e-300, 1e3 * loss / gain, xtol=1e-15)


# ---------------------------------------------------------------- Mathieu (scipy.special)
def mathieu_edges(eps: float, s: int, k0: float = 1.0) -> tuple[float, float]:
    """Undamped edges (Omega_low, Omega_high) of tongue s (centre 2 k0 / s) from the Mathieu
    characteristic values: 4 k0^2 / Omega^2 = a_s(q) or b_s(q), q = eps (4 k0^2 / Omega^2) / 2."""
    out = []
    for f in (mathieu_a, mathieu_b):
        u = so.brentq(lambda u: u - f(s, eps * u / 2.0), 0.25 * s * s, 4.0 * s * s, xtol=1e-15, rtol=1e-15)
        out.append(2.0 * k0 / math.sqrt(u))
    return min(out), max(out)


# -------------------------------------------------------------------- Hill's determinant
def fourier_coefficients(func, n_harmonics: int, n_samples: int = 512) -> np.ndarray:
    """Complex Fourier coefficients g_l, l = -L..L, of a real 2 pi-periodic function of theta
    (FFT of samples; spectrally accurate for analytic functions)."""
    th = np.arange(n_samples) * (2 * math.pi / n_samples)
    c = np.fft.fft(func(th)) / n_samples
    ls = np.arange(-n_harmonics, n_harmonics + 1)
    return c[ls % n_samples]


def _toeplitz(coef: np.ndarray, ms: np.ndarray) -> np.ndarray:
    """Matrix (g_{(m - m')/2}) over the half-integer harmonics m/2, m in ``ms`` (same parity)."""
    L = (coef.size - 1) // 2
    d = (ms[:, None] - ms[None, :]) // 2
    out = np.zeros(d.shape, dtype=complex)
    ok = np.abs(d) <= L
    out[ok] = coef[d[ok] + L]
    return out


def hill_edges(h_coef: np.ndarray, r_coef: np.ndarray | None = None, *, parity: int, n_terms: int = 20,
               k0: float = 1.0) -> np.ndarray:
    """Undamped tongue edges of  q'' + (a h(theta) + r(theta)) q = 0  (primes: d/dtheta,
    theta = Omega t, a = k0^2 / Omega^2, h > 0) from Hill's determinant.

    Solutions with multiplier +1 (``parity = 0``: m even) or -1 (``parity = 1``: m odd) exist
    where (D/4 - R) c = a H c, D = diag(m^2), H, R the Toeplitz matrices of h, r -- a
    symmetric-definite eigenproblem (H is Hermitian positive definite since h > 0).
    Returns the edges Omega (rad/s, descending a) for a > 0."""
    if parity == 1:
        ms = np.arange(-(2 * n_terms - 1), 2 * n_terms, 2)
    else:
        ms = np.arange(-2 * n_terms, 2 * n_terms + 1, 2)
    H = _toeplitz(h_coef, ms)
    R = _toeplitz(r_coef, ms) if r_coef is not None else np.zeros_like(H)
    A = np.diag(ms**2 / 4.0).astype(complex) - R
    with single_threaded_blas():
        a = sla.eigh(A, H, eigvals_only=True)
    a = a[a > 1e-12]
    return np.sort(k0 / np.sqrt(a))


def mathieu_hill_edges(eps: float, *, parity: int, n_terms: int = 20, k0: float = 1.0) -> np.ndarray:
    """Edges for k^2(t) = k0^2 (1 - eps sin Omega t) (7.25): h = 1 - eps sin theta, r = 0."""
    # h(theta) = 1 - eps sin theta = 1 + (i eps/2) e^{i theta} - (i eps/2) e^{-i theta}
    h = np.array([-1j * eps / 2, 1.0, 1j * eps / 2], dtype=complex)
    return hill_edges(h, parity=parity, n_terms=n_terms, k0=k0)


def hill_damped_threshold(omega: float, *, zeta: float, k0: float = 1.0, n_terms: int = 20) -> float:
    """Smallest depth eps at which q'' + 2 zeta k0 q' + k0^2 (1 - eps sin Omega t) q = 0 has a
    solution with multiplier -1 at the given Omega (the edge of an odd tongue), from Hill's
    determinant as the generalised eigenproblem A c = eps B c:
    A = diag(a - m^2/4 + i m zeta sqrt(a)), B = a (e^{i theta} coefficient shifts of sin), a = k0^2/Omega^2.
    nan if no real positive eigenvalue."""
    a = (k0 / omega) ** 2
    ms = np.arange(-(2 * n_terms - 1), 2 * n_terms, 2)
    A = np.diag(a - ms**2 / 4.0 + 1j * ms * zeta * math.sqrt(a))
    B = np.zeros((ms.size, ms.size), dtype=complex)
    # a * sin(theta) c: coefficient of e^{i m theta/2} gets (c_{m-2} - c_{m+2}) / (2 i)
    for i in range(ms.size):
        if i - 1 >= 0:
            B[i, i - 1] = a / 2j
        if i + 1 < ms.size:
            B[i, i + 1] = -a / 2j
    with single_threaded_blas():
        ev = sla.eigvals(A, B)
    ev = ev[np.isfinite(ev)]
    real = ev[(np.abs(ev.imag) <= 1e-9 * np.abs(ev)) & (ev.real > 0)].real
    return float(real.min()) if real.size else math.nan


def hill_damped_edges(eps: float, *, zeta: float, k0: float = 1.0, n_terms: int = 20,
                      bracket: tuple[float, float] | None = None) -> tuple[float, float]:
    """Edges (Omega_low, Omega_high) of the damped principal tongue at depth eps: roots of
    hill_damped_threshold(Omega) = eps on either side of the tongue tip."""
    lo, hi = bracket or (1.5 * k0, 2.5 * k0)
    tip = so.minimize_scalar(lambda w: hill_damped_threshold(w, zeta=zeta, k0=k0, n_terms=n_terms),
                             bounds=(1.9 * k0, 2.1 * k0), method="bounded", options={"xatol": 1e-12})
    f = lambda w: hill_damped_threshold(w, zeta=zeta, k0=k0, n_terms=n_terms) - eps  # noqa: E731
    return (so.brentq(f, lo, tip.x, xtol=1e-14, rtol=1e-15), so.brentq(f, tip.x, hi, xtol=1e-14, rtol=1e-15))


def hill_damped_tip(*, zeta: float, k0: float = 1.0, n_terms: int = 20) -> tuple[float, float]:
    """(Omega, eps) of the tip of the damped principal tongue (minimum of the threshold over Omega)."""
    r = so.minimize_scalar(lambda w: hill_damped_threshold(w, zeta=zeta, k0=k0, n_terms=n_terms),
                           bounds=(1.9 * k0, 2.1 * k0), method="bounded", options={"xatol": 1e-12})
    return float(r.x), float(r.fun)


# ------------------------------------------------- variable inertia: conditional oscillator
def inertia_hill_terms(eps: float, form: str, n_harmonics: int = 60):
    """Fourier coefficients (h, r) of the Hill equation q1'' + (a h + r) q1 = 0 (theta = Omega t,
    a = c0 / (J0 Omega^2)) equivalent to the variable-inertia equation with J = J0 (1 - eps sin theta):

    * ``newton``:    J q'' + c0 q = 0                         -> h = J0/J, r = 0;
    * ``momentum``:  (J q')' + c0 q = 0                       -> r = J'^2/(4 J^2) - J''/(2 J);
    * ``programme``: J q'' + J' q' + (c0 + J''/2) q = 0  (7.7) -> r = J'^2/(4 J^2).

    From (7.10)-(7.12): q = q1 exp(-int n), 2 n = J'/J, k1^2 = k^2 - n^2 - n'; the factor
    exp(-int n) = sqrt(J(0)/J(t)) is periodic, so the multipliers of q and q1 coincide."""
    j = lambda th: 1.0 - eps * np.sin(th)         # noqa: E731
    dj = lambda th: -eps * np.cos(th)             # noqa: E731
    ddj = lambda th: eps * np.sin(th)             # noqa: E731
    h = fourier_coefficients(lambda th: 1.0 / j(th), n_harmonics)
    if form == "newton":
        r = None
    elif form == "momentum":
        r = fourier_coefficients(lambda th: dj(th) ** 2 / (4 * j(th) ** 2) - ddj(th) / (2 * j(th)), n_harmonics)
    elif form == "programme":
        r = fourier_coefficients(lambda th: dj(th) ** 2 / (4 * j(th) ** 2), n_harmonics)
    else:
        raise ValueError(form)
    return h, r


# ------------------------------------------------------------- pendulum-rod (Fig. 7.5)
def pendulum_rod_depth(*, m: float, x0: float, l: float, c0: float, omega: float) -> float:
    """(7.31): eps = m x0 Omega^2 / (l c0); at Omega = 2 k0 it is 4 x0 / l."""
    return m * x0 * omega**2 / (l * c0)


def pendulum_rod_critical_ratio(psi: float) -> float:
    """The book's stability condition 4 x0 / l < psi / pi, i.e. x0 / l < psi / (4 pi)."""
    return psi / (4 * math.pi)


def pendulum_rod_rhs(*, m: float, l: float, c0: float, b: float, x0: float, omega: float):
    """Right-hand side of the rigid rod of Fig. 7.5 with exact kinematics, state (alpha, alpha').

    Massless rod of length l, hinged at a base that moves along the rod's rest direction,
    x(t) = x0 sin Omega t; end mass m at height y = l sin alpha on a vertical spring c0 and
    dashpot b.  Moments about the hinge in the base frame (transport inertia force -m x''
    horizontal, at height l sin alpha):
        m l^2 alpha'' = -(c0 l sin alpha + b l cos alpha alpha') l cos alpha + m x'' l sin alpha.
    For small alpha this is m y'' + b y' + c0 (1 + eps sin Omega t) y = 0 with
    eps = m x0 Omega^2 / (l c0): (7.31) up to the sign of the pulsation (a half-period shift,
    the hinge on the other side), which does not change the multipliers."""
    def rhs(t, s):
        al, om = s
        xdd = -x0 * omega**2 * math.sin(omega * t)
        acc = (-(c0 * l * math.sin(al) + b * l * math.cos(al) * om) * l * math.cos(al)
               + m * xdd * l * math.sin(al)) / (m * l * l)
        return [om, acc]

    return rhs


# --------------------------------------------- Coulomb friction + pulsating spring (7.30)
def coulomb_parametric_turning_points(A0: float, *, phase: float, P: float, c0: float, m: float, eps: float,
                                      omega: float, t_end: float) -> dict:
    """Independent time-domain reference for (7.30): m y'' + c0 (1 - eps sin(Omega t + phase)) y =
    -P sign(y') with true stick (static limit = kinetic level P), from rest at y = A0.

    Slip pieces by DOP853 (rtol 1e-11) with the velocity zero located as an event; at each stop
    the body sticks if |c(t) y| <= P, else it reverses; during stick the breakaway |c(t) y| = P
    is bracketed on a grid of 1/64 of the pulsation period and refined by Brent's method (stick is
    permanent if no breakaway occurs within one pulsation period).  Returns the turning points
    (t, y) and the final mode ("stick" or "slip")."""
    c = lambda t: c0 * (1.0 - eps * math.sin(omega * t + phase))   # noqa: E731
    t, y, v = 0.0, float(A0), 0.0
    turns_t, turns_y = [0.0], [y]
    mode = "stick" if abs(c(t) * y) <= P else "slip"
    s = -math.copysign(1.0, c(t) * y)
    period = 2 * math.pi / omega
    while t < t_end:
        if mode == "slip":
            def stop(tt, x):
                return x[1]
            stop.terminal, stop.direction = True, -s
            sgn = s
            sol = si.solve_ivp(lambda tt, x: [x[1], (-c(tt) * x[0] - P * sgn) / m], (t, t_end), [y, v],
                               method="DOP853", rtol=1e-11, atol=1e-14 * max(abs(A0), 1e-300), events=stop)
            if sol.status == 0:
                y, v, t = sol.y[0, -1], sol.y[1, -1], t_end
                break
            t, y, v = sol.t_events[0][0], sol.y_events[0][0][0], 0.0
            turns_t.append(t)
            turns_y.append(y)
            if abs(c(t) * y) <= P:
                mode = "stick"
            else:
                s = -math.copysign(1.0, c(t) * y)
        else:
            g = lambda tt: abs(c(tt) * y) - P                       # noqa: E731
            grid = t + np.linspace(0.0, period, 65)
            vals = np.array([g(tt) for tt in grid])
            hit = np.flatnonzero(vals[1:] > 0)
            if hit.size == 0:
                break                                               # permanent stick
            k = hit[0] + 1
            t = so.brentq(g, grid[k - 1], grid[k], xtol=1e-14) if vals[k - 1] < 0 else grid[k - 1]
            mode, s = "slip", -math.copysign(1.0, c(t) * y)
    return {"t": np.array(turns_t), "y": np.array(turns_y), "mode": mode, "t_final": t}
