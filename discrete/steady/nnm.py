"""Nonlinear modes: backbone curves (amplitude-dependent frequency and damping) by the extended periodic
motion concept (EPMC, Krack 2015, J. Sound Vib. 339:  "Nonlinear modal analysis of nonconservative
systems: extension of the periodic motion concept").

The forcing is removed and the damping balanced by an artificial negative mass-proportional damping
``-xi M q'``; the periodic solutions of

    M q'' + (C - xi M) q' + K q - sum_e g_e F_e(s_e, s_e') = f_0           (f_0: the constant loads)

form the nonlinear mode: for each amplitude a the frequency omega(a) and the modal damping
``xi(a) = 2 D(a) omega(a)`` (D the damping ratio).  For a conservative system xi = 0 and the orbits are
the undamped nonlinear normal modes; for a one-DOF system with viscous damping c the term cancels it
exactly (xi = c / m) and the orbit is the undamped one.  Harmonic balance with AFT on the same element
laws as the forced curves (:class:`~discrete.steady.hb.HBModel` of the unforced system); unknowns: the
coefficients without ``a_1, b_1`` of the reference DOF (``b_1 = 0`` fixes the phase, ``a_1 = a`` the
amplitude), omega and xi.  The backbone is continued in a from the largest amplitude of a forced curve
downwards (secant predictor, Newton corrector, step halved on failure).

Exact references (validation case ``steady_backbones``): Duffing's free vibration (complete elliptic
integral), the backlash oscillator's piecewise-harmonic period, and the EPMC orbit of a Coulomb
oscillator (piecewise-linear half cycles, ``exp(pi xi / (2 omega_d)) = (A + F/k) / (A - F/k)``).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import ModelError, SolverError
from .hb import HBModel
from .system import GridParts


class FreeSystem:
    """The unforced autonomous part of a :class:`PeriodicSystem`: its matrices and elements with the
    constant loads and element offsets kept and every harmonic (or drift) excitation removed."""

    def __init__(self, system):
        self._full = system

    def __getattr__(self, name):
        return getattr(self._full, name)

    def grid_parts(self, theta, nu: int = 1) -> GridParts:
        g = self._full.grid_parts(theta, nu)

        def const(a):
            return np.broadcast_to(np.mean(a, axis=1, keepdims=True), a.shape).copy()

        zero_f = np.zeros_like(g.fa)
        zero_s = np.zeros_like(g.sa)
        return GridParts(fa=const(g.fa), fb=zero_f, fc=zero_f, fd=zero_f, sa=const(g.sa), sb=zero_s,
                         sda=const(g.sda), sdb=zero_s)

    def element_laws(self, S, Sd):
        return self._full.element_laws(S, Sd)


@dataclass
class Backbone:
    """A nonlinear mode: per point the reference DOF's first-harmonic amplitude ``a``, the frequency,
    the EPMC damping ``xi`` (1/s) and ratio ``D = xi / (2 omega)``, the orbit's coefficients."""

    amplitude: np.ndarray
    omega: np.ndarray
    xi: np.ndarray
    states: list = field(default_factory=list, repr=False)
    dof: str = ""
    method: str = ""
    completed: bool = True
    reason: str = ""
    response: np.ndarray | None = None     # the forced curve's response measure on each free orbit

    @property
    def damping_ratio(self) -> np.ndarray:
        return self.xi / (2.0 * self.omega)

    def to_dict(self) -> dict:
        return {"method": self.method, "dof": self.dof,
                "first_harmonic_amplitude": [float(x) for x in self.amplitude],
                "omega_rad_s": [float(x) for x in self.omega], "xi_1_s": [float(x) for x in self.xi],
                "damping_ratio": [float(x) for x in self.damping_ratio],
                "response": None if self.response is None else [float(x) for x in self.response],
                "n_points": int(self.omega.size), "completed": bool(self.completed), "reason": self.reason}


class EPMC:
    """Residual of the EPMC equations (module docstring) by harmonic balance on ``system``."""

    def __init__(self, system, harmonics: int = 7, samples: int | None = None, ref: int = 0, kinks: str = "exact"):
        if not 0 <= ref < system.n:
            raise ModelError("backbone", "dof", ref, f"a free DOF index 0 .. {system.n - 1}")
        self.s = system
        self.hb = HBModel(FreeSystem(system), harmonics=harmonics, nu=1, samples=samples, kinks=kinks)
        self.ref = int(ref)
        m = self.hb.m
        self.ia, self.ib = self.ref * m + 1, self.ref * m + 2
        self.keep = np.array([j for j in range(system.n * m) if j not in (self.ia, self.ib)])
        self._MD = np.kron(np.asarray(system.M, float), self.hb.D.T)     # d(M Q D)/dQ in the flat layout

    def full(self, u, a):
        X = np.zeros(self.s.n * self.hb.m)
        X[self.keep] = u[:-2]
        X[self.ia] = a
        return X

    def residual(self, u, a):
        """(R, J) in the unknowns u = [coefficients without a_1, b_1 of the reference DOF, omega, xi]."""
        X = self.full(u, a)
        w, xi = u[-2], u[-1]
        R, J, Rw = self.hb.evaluate_residual(X, w, jac=True, dw=True)
        MQD = self._MD @ X                              # velocity coefficients / Om, times M
        R = R - xi * w * MQD
        Jx = J - (xi * w) * self._MD
        A = np.empty((R.size, u.size))
        A[:, :-2] = Jx[:, self.keep]
        A[:, -2] = Rw - xi * MQD
        A[:, -1] = -w * MQD
        return R, A

    def solve(self, u0, a, tol=1e-11, maxit=30):
        u = np.array(u0, float)
        for it in range(1, maxit + 1):
            R, A = self.residual(u, a)
            try:
                du = np.linalg.solve(A, -R)
            except np.linalg.LinAlgError as exc:
                raise SolverError(f"EPMC Jacobian singular at amplitude {a!r}") from exc
            u = u + du
            if not np.all(np.isfinite(u)) or u[-2] <= 0:
                raise SolverError(f"EPMC Newton diverged at amplitude {a!r}")
            scale = max(np.max(np.abs(u[:-2])), abs(a))
            if np.max(np.abs(du[:-2])) <= tol * scale and abs(du[-2]) <= tol * u[-2] and \
                    abs(du[-1]) <= tol * max(abs(u[-1]), 1e-3 * u[-2]):
                return u, it
        raise SolverError(f"EPMC Newton did not converge at amplitude {a!r} in {maxit} iterations")

    def start(self, X, omega):
        """The unknowns of a periodic state X (e.g. a forced orbit) shifted in time so that b_1 = 0 and
        a_1 > 0 on the reference DOF: (u, a)."""
        m = self.hb.m
        Q = np.asarray(X, float).reshape(self.s.n, m).copy()
        phi = np.arctan2(Q[self.ref, 2], Q[self.ref, 1])
        for k in range(1, self.hb.H + 1):
            z = (Q[:, 2 * k - 1] - 1j * Q[:, 2 * k]) * np.exp(1j * k * phi)
            Q[:, 2 * k - 1], Q[:, 2 * k] = z.real, -z.imag
        a = float(Q[self.ref, 1])
        Xr = Q.ravel()
        return np.concatenate([Xr[self.keep], [omega, 0.0]]), a


def backbone(system, harmonics: int, amplitudes, X0, omega0, ref: int = 0, samples: int | None = None,
             names=None, min_step: float = 1e-3, kinks: str = "exact") -> Backbone:
    """The nonlinear mode of ``system`` through the reference DOF ``ref``, continued over the first-harmonic
    amplitudes ``amplitudes`` (in the given order) from the periodic state ``X0`` at ``omega0`` (any orbit
    near the mode, e.g. the peak of a forced curve).  Stops early (``completed = False``, ``reason``) when
    the step falls below ``min_step`` of the first one.  ``kinks``: as :class:`~discrete.steady.hb.HBModel`."""
    ep = EPMC(system, harmonics=harmonics, samples=samples, ref=ref, kinks=kinks)
    u, _ = ep.start(X0, omega0)
    amps = np.asarray(amplitudes, float)
    out_a, out_u = [], []
    reason, done = "", True
    i, a_prev = 0, None
    h0 = abs(amps[1] - amps[0]) if amps.size > 1 else 1.0
    target = amps[0]
    while i < amps.size:
        a = target
        if len(out_u) >= 2:                 # secant predictor in the amplitude
            f = (a - out_a[-1]) / (out_a[-1] - out_a[-2])
            guess = out_u[-1] + f * (out_u[-1] - out_u[-2])
        elif out_u:
            guess = out_u[-1]
        else:
            guess = u
        try:
            sol, _ = ep.solve(guess, a)
        except (SolverError, np.linalg.LinAlgError) as exc:
            if a_prev is None or abs(a - a_prev) < min_step * h0:
                done = False
                reason = (f"stopped at amplitude {a_prev if a_prev is not None else a:.6g} (asked down to "
                          f"{amps[-1]:.6g}): {exc}")
                break
            target = 0.5 * (a_prev + a)     # halve the step towards the next grid amplitude
            continue
        out_a.append(a)
        out_u.append(sol)
        a_prev = a
        if a == amps[i]:
            i += 1
        if i < amps.size:
            target = amps[i]
    if not out_u:
        raise SolverError(f"no nonlinear mode found at amplitude {amps[0]:.6g}: {reason}")
    U = np.array(out_u)
    label = names[ref] if names is not None else f"DOF {ref}"
    return Backbone(amplitude=np.array(out_a), omega=U[:, -2], xi=U[:, -1],
                    states=[ep.full(x, a) for x, a in zip(out_u, out_a)], dof=str(label),
                    method=f"EPMC by HB (H = {ep.hb.H}, N = {ep.hb.N}, AFT)", completed=done,
                    reason=reason or f"amplitudes {amps[0]:.6g} .. {amps[-1]:.6g} covered")


def afc_backbone(sm, result, points: int = 40) -> Backbone:
    """The nonlinear mode through the response DOF of a forced curve ``result`` of the steady model ``sm``
    (``[steady] backbone = true``), over the first-harmonic amplitudes of that DOF along the curve (from
    its largest down to its smallest, at least 2 % of the largest: below the curve's amplitudes a
    friction mode would stick, where the regularised law's mode means nothing), started from the curve's
    orbit of largest amplitude (HB curves) or from the linear mode nearest the peak (shooting curves);
    each free orbit also gets the curve's response measure, so that both can be drawn on one plot."""
    s, cfg = sm.system, sm.cfg
    if cfg.subharmonic != 1:
        raise ModelError("[steady]", "backbone", True, "subharmonic = 1 (the nonlinear mode of the period-1 response)")
    if sm.resp_dof is not None:
        ref = int(sm.resp_dof)
    else:
        ref = int(np.argmax(np.abs(s.Gf[sm.resp_el])))
    H = cfg.harmonics
    m = 2 * H + 1
    if not result.omega.size:
        raise SolverError("no backbone: the forced curve has no point")
    if result.method.startswith("hb"):
        from .bifurcation import pad_harmonics      # adaptive curves: states of several harmonic counts

        Q = np.array([pad_harmonics(x, s.n, (np.size(x) // s.n - 1) // 2, H) for x in result.states]).reshape(
            len(result.states), s.n, m)
        a1 = np.hypot(Q[:, ref, 1], Q[:, ref, 2])
        k = int(np.argmax(a1))
        X0, w0, a_max = Q[k].ravel(), float(result.omega[k]), float(a1[k])
        a_min = float(np.min(a1))
    else:
        if sm.resp_dof is None or cfg.measure not in ("amplitude", "peak", "h1", "max"):
            raise ModelError("[steady]", "backbone", True, "a body response measured by amplitude, peak, h1 or max "
                             "for the backbone of a shooting curve (its amplitude range)")
        k = int(np.nanargmax(result.response))
        a_max, w0 = float(result.response[k] * cfg.scale), float(result.omega[k])
        a_min = float(np.nanmin(result.response) * cfg.scale)
        M, K = np.asarray(s.M, float), np.asarray(s.K, float)
        lam, vec = np.linalg.eig(np.linalg.solve(M, K)) if s.n > 1 else (np.array([K[0, 0] / M[0, 0]]), np.ones((1, 1)))
        j = int(np.argmin(np.abs(np.sqrt(np.abs(lam.real)) - w0)))
        phi = vec[:, j].real / vec[ref, j].real
        X0 = np.zeros((s.n, m))
        X0[:, 1] = a_max * phi
        X0 = X0.ravel()
        if lam[j].real > 0:
            w0 = float(np.sqrt(lam[j].real))
    amps = np.linspace(a_max, max(a_min, 0.02 * a_max), int(points))
    names = [s.problem.names[j] for j in s.problem.f]
    bb = backbone(s, H, amps, X0, w0, ref=ref, samples=cfg.samples, names=names, kinks=cfg.kinks)
    ep = EPMC(s, harmonics=H, samples=cfg.samples, ref=ref, kinks=cfg.kinks)
    bb.response = np.array(sm.measure_hb(ep.hb, bb.states, bb.omega))
    return bb
