"""Harmonic (steady-state) response of a :class:`LinearSystem`.

Complex amplitudes Q with q(t) = Re(Q e^{i omega t}) solve

    (K + i H - omega^2 M + i omega C) Q = F

for force excitation F, and for kinematic excitation (prescribed harmonic motion U_b of
constrained DOFs, e.g. a moving support or a driver, §5.5) the free DOFs solve

    D_ff Q_f = F_f - D_fb U_b,   D = K + i H - omega^2 M + i omega C.

Damping conventions (design.md §3):
* ``viscous``: the model's dampers (C);
* ``rayleigh``: C += alpha M + beta K;
* ``modal``: ratio zeta per mode (modal superposition only);
* ``hysteretic``: complex stiffness c (1 + 2 i delta) with delta = psi / (4 pi) (the
  textbook's dissipation coefficient psi; the energy-balance resonance amplitude
  A = 2 pi F0 / (psi c) of §5.13 is then reproduced exactly).

Two methods: ``direct`` (sparse LU per frequency) and ``modal`` (superposition of the
lowest modes; with base motion the quasi-static part is included exactly, so truncation
only affects the dynamic part).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import ModelError, SolverError
from ..linear_system import LinearSystem

from .modal import ModalResult, as_linear_system, modal_analysis

DAMPING_TYPES = ("none", "viscous", "rayleigh", "modal", "hysteretic")
RELIABLE = 1e-6           # largest relative error estimate of a response that is reported as reliable
EPS = float(np.finfo(float).eps)


@dataclass
class Damping:
    type: str = "viscous"
    alpha: float = 0.0
    beta: float = 0.0
    zeta: float = 0.0
    psi: float = 0.0

    def __post_init__(self):
        where = "[damping]"
        if self.type not in DAMPING_TYPES:
            raise ModelError(where, "type", self.type, " | ".join(map(repr, DAMPING_TYPES)))
        for key in ("alpha", "beta", "zeta", "psi"):
            v = getattr(self, key)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) or not (0 <= v < np.inf):
                raise ModelError(where, key, v, "a finite real number >= 0")

    @property
    def delta(self) -> float:
        """Hysteretic delta = psi / (4 pi) of the complex stiffness c (1 + 2 i delta)."""
        return self.psi / (4 * math.pi)

    def describe(self) -> str:
        return {"none": "undamped", "viscous": "viscous (model dampers)",
                "rayleigh": f"Rayleigh C = {self.alpha:g} M + {self.beta:g} K",
                "modal": f"modal, zeta = {self.zeta:g}",
                "hysteretic": f"hysteretic, psi = {self.psi:g} (K (1 + 2 i delta), delta = psi/(4 pi) = {self.delta:.6g})",
                }[self.type]


@dataclass
class HarmonicResult:
    omega_rad_s: np.ndarray
    response: np.ndarray            # (n_freq, n_outputs) complex amplitudes
    outputs: list[str]
    method: str
    damping: str
    relative: np.ndarray | None = None   # relative response (output minus base motion) for kinematic excitation
    warnings: list[str] = field(default_factory=list)
    full: np.ndarray | None = field(default=None, repr=False)   # (n_freq, n_dofs): every DOF (section loads)
    error_estimate: np.ndarray | None = None   # (n_freq,) relative error of the response vector (module notes)

    @property
    def reliable(self) -> np.ndarray:
        """Per frequency: the error estimate is below :data:`RELIABLE` (False where the dynamic stiffness is
        singular to working precision: an undamped resonance, or omega = 0 of a free motion)."""
        if self.error_estimate is None:
            return np.ones(self.omega_rad_s.size, dtype=bool)
        return self.error_estimate <= RELIABLE

    @property
    def frequencies_hz(self) -> np.ndarray:
        return self.omega_rad_s / (2 * np.pi)

    @property
    def amplitude(self) -> np.ndarray:
        return np.abs(self.response)

    @property
    def phase_lag_deg(self) -> np.ndarray:
        """Lag gamma of the response behind the excitation, in [0, 360) degrees (q = A cos(omega t - gamma))."""
        return np.mod(-np.degrees(np.angle(self.response)), 360.0)

    def to_dict(self) -> dict:
        d = {"omega_rad_s": self.omega_rad_s.tolist(), "frequencies_hz": self.frequencies_hz.tolist(),
             "outputs": list(self.outputs), "method": self.method, "damping": self.damping,
             "amplitude": self.amplitude.T.tolist(), "phase_lag_deg": self.phase_lag_deg.T.tolist(),
             "real": self.response.real.T.tolist(), "imag": self.response.imag.T.tolist(),
             "warnings": list(self.warnings), "reliable": self.reliable.tolist()}
        if self.error_estimate is not None:
            d["error_estimate"] = self.error_estimate.tolist()
        if self.relative is not None:
            d["relative_amplitude"] = np.abs(self.relative).T.tolist()
        return d


def harmonic_response(system: LinearSystem, omegas, *, force: np.ndarray | None = None,
                      base_motion: dict[int, complex] | None = None, damping: Damping | None = None,
                      outputs: list[int] | None = None, method: str = "direct", n_modes: int | None = None,
                      modal: ModalResult | None = None, force_omega2: np.ndarray | None = None) -> HarmonicResult:
    """Steady-state complex amplitudes at DOFs ``outputs`` over the angular frequencies ``omegas``.

    ``force``: full-length complex load vector; ``force_omega2``: loads proportional to omega^2 (an
    unbalance m e: the load at omega is omega^2 force_omega2), added to ``force`` frequency by frequency;
    ``base_motion``: {constrained DOF index: complex amplitude}.  ``method``: ``direct`` or ``modal``
    (``n_modes`` lowest modes).  ``result.full`` keeps the amplitudes of every DOF.
    """
    system = as_linear_system(system, "harmonic_response")
    damping = Damping() if damping is None else damping
    if not isinstance(damping, Damping):
        raise ModelError("[damping]", "damping", type(damping).__name__, "a discrete.linear.Damping or None")
    omegas = _frequencies(omegas)
    if method not in ("direct", "modal"):
        raise ModelError("[analysis]", "method", method, "'direct' | 'modal'")
    if damping.type == "modal" and method != "modal":
        raise ModelError("[damping]", "type", "modal", "modal damping needs [analysis] method = 'modal'")
    n = system.n_dofs
    F = np.zeros(n, dtype=complex) if force is None else load_vector(force, n, "force", complex_ok=True)
    F2 = np.zeros(n, dtype=complex) if force_omega2 is None else load_vector(force_omega2, n, "force_omega2",
                                                                              complex_ok=True)
    Ub = np.zeros(system.constrained.size, dtype=complex)
    pos = {int(d): k for k, d in enumerate(system.constrained)}
    if base_motion is not None and not isinstance(base_motion, dict):
        raise ModelError("[[base_motion]]", "base_motion", type(base_motion).__name__,
                         "a dict {constrained DOF index: complex amplitude}")
    for dof, amp in (base_motion or {}).items():
        dof = dof_index(dof, n, "[[base_motion]] dof")
        if not isinstance(amp, (int, float, complex, np.number)) or isinstance(amp, bool) or not np.isfinite(amp):
            raise ModelError("[[base_motion]]", f"amplitude of DOF {dof}", amp, "a finite (complex) number")
        if int(dof) not in pos:
            raise ModelError("[[base_motion]]", "dof", system.label(int(dof)),
                             "a constrained DOF (a support or a driver): base motion moves a support")
        Ub[pos[int(dof)]] = amp
    if not np.any(F[system.free]) and not np.any(F2[system.free]) and not np.any(Ub):
        raise ModelError("[analysis]", "load", None, "at least one [[load]] or [[base_motion]] with a non-zero amplitude")
    outputs = list(range(n)) if outputs is None else [dof_index(i, n, "outputs") for i in np.atleast_1d(outputs)]
    if n_modes is not None and (isinstance(n_modes, bool) or not isinstance(n_modes, (int, np.integer))):
        raise ModelError("[analysis]", "modes", n_modes, f"an integer from 1 to {system.n_free}, or None")
    n_rigid = 0 if system.rigid_modes is None else system.rigid_modes.shape[1]
    if n_rigid and np.any(omegas == 0):
        raise ModelError("[analysis]", "frequencies", 0.0,
                         f"frequencies > 0: at omega = 0 the problem is static and this model has {n_rigid} "
                         "rigid-body mode(s) (under-constrained); add supports or start the sweep above 0")

    C = system.C.copy()
    H = system.H.copy()
    if damping.type == "rayleigh":
        C = C + damping.alpha * system.M + damping.beta * system.K
    elif damping.type == "hysteretic":
        H = H + 2 * damping.delta * system.K
    elif damping.type == "none":
        C, H = C * 0, H * 0
    if method == "direct":
        Q, err = _direct(system, omegas, F, F2, Ub, C, H)
        name = "direct sparse solve"
    else:
        if modal is None:
            k = n_modes or min(20, system.n_free)
            modal = modal_analysis(system, k)
        Q, err = _modal(system, omegas, F, F2, Ub, C, H, modal, damping)
        name = f"modal superposition ({modal.omega_rad_s.size} modes" + (", quasi-static base motion exact)" if np.any(Ub) else ")")
    desc = damping.describe()
    if system.H.nnz and damping.type != "none":
        desc += " + hysteretic (psi of segments/springs)"
    res = HarmonicResult(omega_rad_s=omegas, response=Q[:, outputs], outputs=[system.label(i) for i in outputs],
                         method=name, damping=desc, full=Q, error_estimate=err)
    res.warnings.extend(reliability_warnings(omegas, err))
    if np.any(Ub):
        ub_full = np.zeros(n, dtype=complex)
        ub_full[system.constrained] = Ub
        # relative motion: output minus the motion of the (first) moving support/driver of the same field
        moving = [d for d in system.constrained if ub_full[d] != 0]
        ref = []
        for i in outputs:
            same = [d for d in moving if system.dof_field[d] == system.dof_field[i]]
            ref.append(ub_full[same[0]] if same else 0.0)
        res.relative = res.response - np.asarray(ref)[None, :]
    return res


def reliability_warnings(omegas: np.ndarray, err: np.ndarray) -> list[str]:
    """One warning naming the frequencies whose response is not reliable (error estimate above :data:`RELIABLE`)."""
    bad = np.flatnonzero(~(err <= RELIABLE))
    if not bad.size:
        return []
    shown = ", ".join(f"{omegas[j]:.6g}" for j in bad[:5]) + (f" and {bad.size - 5} more" if bad.size > 5 else "")
    return [f"the response at omega = {shown} rad/s ({bad.size} of {omegas.size} frequencies) is NOT RELIABLE: "
            f"relative error estimate up to {float(np.max(err[bad])):.2g} (>= {RELIABLE:g}): the dynamic stiffness "
            "is singular to working precision there -- an undamped resonance, or omega = 0 of a motion nothing "
            "holds (a free body, a motor's rotor); add damping or supports, or move the frequency"]


def _norm1_estimate(apply, apply_h, n: int, iterations: int = 5) -> float:
    """||B||_1 of an operator given by ``apply`` (B v) and ``apply_h`` (B^H w): Hager's estimator with Higham's
    refinements (LAPACK xLACN2; Higham, Accuracy and Stability of Numerical Algorithms, Alg. 15.4), a lower
    bound that is almost always within a factor 3 of the norm, at 2-6 applications."""
    x = np.full(n, 1.0 / n, dtype=complex)
    y = apply(x)
    est = float(np.sum(np.abs(y)))
    if n == 1:
        return est
    for _ in range(iterations):
        xi = np.where(np.abs(y) > 0, y / np.where(np.abs(y) > 0, np.abs(y), 1.0), 1.0)
        z = apply_h(xi)
        j = int(np.argmax(np.abs(z)))
        if np.abs(z[j]) <= np.real(np.vdot(z, x)):
            break
        x = np.zeros(n, dtype=complex)
        x[j] = 1.0
        y = apply(x)
        new = float(np.sum(np.abs(y)))
        if new <= est:
            break
        est = new
    alt = np.array([(-1) ** i * (1 + i / (n - 1)) for i in range(n)], dtype=complex)
    return max(est, 2.0 * float(np.sum(np.abs(apply(alt)))) / (3 * n))


def _estimate(lu, D, x, rhs) -> float:
    """Relative error bound of the solution ``x`` of D x = rhs (LAPACK's forward error bound of xGERFS):
    || |D^-1| (|rhs - D x| + n eps |D| |x|) ||_inf / ||x||_inf, the norm estimated by :func:`_norm1_estimate`.
    It covers the solver's rounding and that of D's own entries (K - omega^2 M formed in working precision):
    of order 1 where D is singular to working precision (an undamped resonance hit, omega = 0 of a free motion),
    and componentwise, so that an FE model's spread of scales does not inflate it."""
    scale = float(np.max(np.abs(x))) if x.size else 0.0
    if scale == 0.0:
        return 0.0
    absD = abs(D)
    g = np.abs(rhs - D @ x) + (absD.getnnz(axis=1).max(initial=1) + 1) * EPS * (absD @ np.abs(x))
    with np.errstate(all="ignore"):
        est = _norm1_estimate(lambda v: g * lu.solve(np.asarray(v, complex), trans="H"),
                              lambda w: lu.solve(np.asarray(g * w, complex)), x.size)
        e = est / scale
    return float(e) if np.isfinite(e) else np.inf


def _frequencies(omegas) -> np.ndarray:
    """Angular frequencies as a float array: real, finite, >= 0, at least one."""
    try:
        arr = np.atleast_1d(np.asarray(omegas))
    except (TypeError, ValueError):
        arr = None
    if arr is None or arr.dtype.kind not in "iuf" or arr.ndim != 1:
        raise ModelError("[analysis]", "frequencies", omegas, "a non-empty 1-D list of real angular frequencies "
                         "(rad/s) >= 0")
    arr = arr.astype(float)
    if arr.size == 0 or not np.all(np.isfinite(arr)) or np.any(arr < 0):
        raise ModelError("[analysis]", "frequencies", arr.tolist(), "a non-empty list of finite frequencies >= 0")
    return arr


def dof_index(i, n: int, key: str) -> int:
    """A DOF index in 0 .. n-1 (an integer, not a bool or float), else a ModelError naming it and the range."""
    if isinstance(i, (bool, np.bool_)) or not isinstance(i, (int, np.integer)):
        raise ModelError("[analysis]", key, i, f"an integer DOF index from 0 to {n - 1}")
    if not 0 <= int(i) < n:
        raise ModelError("[analysis]", key, int(i), f"a DOF index from 0 to {n - 1} (the model has {n} DOFs)")
    return int(i)


def load_vector(force, n: int, key: str = "force", *, complex_ok: bool) -> np.ndarray:
    """A full-length finite load vector (complex where ``complex_ok``); never a silently dropped
    imaginary part, a NaN or a truncated/broadcast shape."""
    try:
        F = np.asarray(force)
    except (TypeError, ValueError):
        F = np.asarray(None, dtype=object)
    if F.dtype.kind not in ("iufc" if complex_ok else "iuf"):
        allowed = ("a real or complex" if complex_ok else "a real") + f" vector of {n} numbers"
        if F.dtype.kind == "c":
            allowed += (" (a static load has no phase: pass the real part explicitly, or use harmonic_response "
                        "for a complex amplitude)")
        raise ModelError("[analysis]", key, f"<{F.dtype} array>" if F.dtype.kind != "O" else type(force).__name__,
                         allowed)
    if F.shape != (n,):
        raise ModelError("[analysis]", key, f"shape {F.shape}", f"a full-length vector of shape ({n},), one entry per DOF")
    if not np.all(np.isfinite(F)):
        bad = int(np.flatnonzero(~np.isfinite(F))[0])
        raise ModelError("[analysis]", f"{key}[{bad}]", F[bad].item(), "finite numbers (no NaN or inf)")
    return F.astype(complex if complex_ok else float)


def _load_at(F, F2, w):
    """The load at omega: the constant part plus omega^2 times the unbalance part (F itself if there is none)."""
    return F + w * w * F2 if np.any(F2) else F


def _direct(system, omegas, F, F2, Ub, C, H):
    f, b = system.free, system.constrained
    Q = np.zeros((omegas.size, system.n_dofs), dtype=complex)
    err = np.zeros(omegas.size)
    K, M = system.K, system.M
    for j, w in enumerate(omegas):
        D = (K + 1j * H - w**2 * M + 1j * w * C).tocsr()
        rhs = _load_at(F, F2, w)[f] - (D[f][:, b] @ Ub if b.size else 0)
        Dff = sp.csc_matrix(D[f][:, f])
        try:
            lu = spla.splu(Dff)
        except RuntimeError as exc:
            raise SolverError(f"the dynamic stiffness is singular at omega = {w:g} rad/s (an undamped resonance "
                              f"or a free system at omega = 0): add damping or move the frequency") from exc
        rhs = np.asarray(rhs, dtype=complex)
        Q[j, f] = lu.solve(rhs)
        err[j] = _estimate(lu, Dff, Q[j, f], rhs)
        Q[j, b] = Ub
    return Q, err


def _modal(system, omegas, F, F2, Ub, C, H, modal: ModalResult, damping: Damping):
    """Superposition on the free DOFs.  With base motion, the free DOFs are split into the
    quasi-static part q_s = -K_ff^-1 K_fb U_b (exact) and a dynamic part expanded in modes."""
    f, b = system.free, system.constrained
    Phi = modal.shapes[f]
    lam = modal.eigenvalues
    Kff, Mff = system.free_block(system.K), system.free_block(system.M)
    Cff, Hff = C[f][:, f], H[f][:, f]
    c_modal = np.einsum("ij,ij->j", Phi, Cff @ Phi)
    h_modal = np.einsum("ij,ij->j", Phi, Hff @ Phi)
    Q = np.zeros((omegas.size, system.n_dofs), dtype=complex)
    err = np.zeros(omegas.size)
    qs = np.zeros(f.size, dtype=complex)
    if np.any(Ub):
        if modal.rigid_body_modes:
            raise ModelError("[[base_motion]]", "method", "modal",
                             "'direct' for base motion of a system with rigid-body modes")
        Kfb = system.K[f][:, b]
        qs = spla.spsolve(sp.csc_matrix(Kff), -(Kfb @ Ub))
    Mfb, Cfb, Hfb = system.M[f][:, b], C[f][:, b], H[f][:, b]
    for j, w in enumerate(omegas):
        rhs = _load_at(F, F2, w)[f].copy()
        if np.any(Ub):
            # remaining load on the dynamic part: inertia and damping of the quasi-static motion
            rhs = rhs - ((-w**2 * Mff + 1j * w * Cff + 1j * Hff) @ qs + (-w**2 * Mfb + 1j * w * Cfb + 1j * Hfb) @ Ub)
        modal_force = Phi.T @ rhs
        if damping.type == "modal":
            denom = lam - w**2 + 2j * damping.zeta * w * np.sqrt(np.clip(lam, 0, None)) + 1j * h_modal
        else:
            denom = lam - w**2 + 1j * w * c_modal + 1j * h_modal
        if np.any(denom == 0):
            raise SolverError(f"undamped resonance at omega = {w:g} rad/s in modal superposition: add damping")
        Q[j, f] = qs + Phi @ (modal_force / denom)
        Q[j, b] = Ub
        # each modal amplitude f_r / denom_r carries the rounding of denom_r = lam_r - w^2 + ...: a relative
        # error eps (|lam_r| + w^2) / |denom_r|, of order 1 at an undamped resonance
        load = np.abs(modal_force) > 0
        err[j] = float(np.max(EPS * (np.abs(lam) + w * w) / np.abs(denom), where=load, initial=0.0))
    return Q, err


def frf(system: LinearSystem, omegas, *, drive: int, response: int, damping: Damping | None = None,
        method: str = "direct", n_modes: int | None = None) -> np.ndarray:
    """Receptance H(omega) = Q_response / F_drive for a unit force at DOF ``drive``."""
    system = as_linear_system(system, "frf")
    drive = dof_index(drive, system.n_dofs, "drive")
    response = dof_index(response, system.n_dofs, "response")
    F = np.zeros(system.n_dofs, dtype=complex)
    F[drive] = 1.0
    return harmonic_response(system, omegas, force=F, damping=damping, outputs=[response], method=method,
                             n_modes=n_modes).response[:, 0]
