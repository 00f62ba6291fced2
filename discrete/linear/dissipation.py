"""Hysteretic damping psi in the time domain: the textbook's viscous equivalents (§9.1, (9.3), (9.14)-(9.18)).

A spring or segment with the dissipation coefficient psi carries the loss stiffness
``H_e = 2 delta K_e = psi K_e / (2 pi)`` (``delta = psi / (4 pi)``, :mod:`discrete.linear_system`).  In a
harmonic analysis ``i H`` is exact; a time integrator needs a viscous matrix C.  The book gives two:

``equivalent`` -- (9.3) ``b = psi c / (2 pi omega)`` per element at a stated reference frequency:

    C = H / omega_ref.

At ``omega_ref`` it dissipates exactly what ``i H`` dissipates (``i omega_ref C = i H``): the harmonic
response at ``omega_ref`` is unchanged.  A mode r of frequency omega_r is damped as if its
coefficient were ``psi_r* omega_r / omega_ref`` (more above the reference, less below; the report
lists it mode by mode).

``modal`` -- (9.14)-(9.18).  With mode shapes beta (9.11) the reduced coefficient of mode r is

    psi_r* = sum_j psi_j c_j beta_jr^2 / sum_j c_j beta_jr^2 = 2 pi phi_r^T H phi_r / phi_r^T K phi_r    (9.14)

(the sum over elements of psi_e times the mode's strain energy in element e, over its total strain
energy; ``phi^T H phi = sum_e psi_e phi^T K_e phi / (2 pi)``), the modal viscous coefficient
``b_r* = psi_r* c_r* / (2 pi k_r)`` (9.15), and back in the original coordinates (9.18)

    b = (beta^T)^-1 b* beta^-1 = M Phi diag(psi_r* omega_r / (2 pi)) Phi^T M = M Phi diag(h_r / omega_r) Phi^T M,

with mass-normalised ``Phi`` and ``h_r = phi_r^T H phi_r``: since ``beta^T M beta = diag(a_r*)``,
``beta^-1 = diag(1/a_r*) beta^T M``, and ``b_r*/a_r* = psi_r* omega_r/(2 pi)`` for ``phi_r = beta_r/sqrt(a_r*)``.
Every included mode then decays with its own psi_r*, at its own frequency; the modes are not coupled
by dissipation (the book's assumption after (9.12)); the largest coupling that H has and C drops,
``max |phi_r^T H phi_s| / sqrt(h_r h_s)``, is reported.  Modes not included are either completed by
the stiffness-proportional remainder ``P^T H P / omega_c`` (``P = I - Phi Phi^T M`` removes the
included modes, ``omega_c`` is the first excluded frequency), or -- on request only -- left undamped
(``completion = "none"``, reported).  The remainder leaves the included modes untouched (``P Phi = 0``)
and gives every excluded mode s (``P phi_s = phi_s`` by M-orthogonality) the coefficient
``psi_s* omega_s / omega_c``: the first excluded mode exactly its psi*, higher ones more, in proportion
to frequency like a Rayleigh ``beta K`` term; the coupling among excluded modes is kept, that between
included and excluded modes dropped.

Constraints: the modes are those with every constrained DOF (supports, drivers) held.  The modal
matrix acts on the motion relative to the quasi-static position of the driven system,
``u = q_f + K_ff^-1 K_fc q_c`` (the constraint modes of Craig-Bampton), so a rigid motion of the
drive train (a driver at constant speed) is not braked: ``C_full = L^T C_u L``, ``L = [I, K_ff^-1 K_fc]``.
The quasi-static deformation between several drivers is not damped by the modal form (it is by the
equivalent form).

Convention (the digest's caution): the book's (9.3) implies ``delta = n/k = psi/(4 pi)`` at
``omega_ref = k``, i.e. the logarithmic decrement ``lambda = 2 pi delta / sqrt(1 - delta^2) ~ psi/2``,
and the energy lost per cycle ``Delta E/E = 1 - exp(-2 lambda) = psi - psi^2/2 + O(psi^3)`` -- psi to
first order.  It is not the exact free-decay definition ``psi = 1 - (A2/A1)^2`` of (4.16) (that one
would give ``lambda = -ln(1 - psi)/2``); the frequency-domain complex stiffness ``c (1 + 2 i delta)``
uses the same ``delta = psi/(4 pi)``, so the time and frequency domains agree at omega_ref.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from ..errors import ModelError
from ..linalg.shifted import is_diagonal
from ..linalg.sparse_direct import SingularMatrixError, factorize
from ..linear_system import LinearSystem
from .modal import ModalResult, modal_analysis

METHODS = ("equivalent", "modal")
COMPLETIONS = ("stiffness", "none")
#: the modal matrix is dense on the free DOFs: refused above this size (use "equivalent", sparse)
MODAL_DENSE_MAX = 4000
#: without ``n_modes`` the modal form uses every mode up to this many free DOFs, else DEFAULT_MODES + completion
ALL_MODES_MAX = 200
DEFAULT_MODES = 20
#: modes listed in the report of the equivalent form (without ``n_modes``)
REPORT_MODES = 6
CONVENTION = ("(9.3) b = psi c/(2 pi omega): delta = psi/(4 pi) at the reference frequency, log decrement "
              "lambda = psi/2 and Delta E/E = psi to first order (not psi = 1 - (A2/A1)^2 of (4.16))")


@dataclass
class PsiRepresentation:
    """What a time-domain run represents of the model's psi (returned with the viscous matrix).

    Per mode (the lowest ``omega_rad_s.size`` flexible modes, constrained DOFs held): ``psi_star``
    the book's reduced coefficient (9.14), ``psi_represented`` the coefficient the viscous matrix
    gives that mode at its own frequency (2 pi phi^T C phi / omega_r), ``zeta`` its viscous ratio
    (phi^T C phi / (2 omega_r)); ``coupling`` the largest modal coupling of H that C drops."""

    method: str                       # "equivalent" | "modal" | "none" (the model has no psi)
    omega_ref: float | None = None    # rad/s (equivalent)
    omega_ref_source: str = ""        # "given" | "forcing frequency" | "first natural frequency"
    omega_rad_s: np.ndarray = field(default_factory=lambda: np.zeros(0))
    psi_star: np.ndarray = field(default_factory=lambda: np.zeros(0))
    psi_represented: np.ndarray = field(default_factory=lambda: np.zeros(0))
    zeta: np.ndarray = field(default_factory=lambda: np.zeros(0))
    n_modes_used: int = 0             # modes in the modal matrix (modal)
    n_free: int = 0
    rigid_modes: int = 0
    completion: str = ""              # "stiffness" | "none" | "complete (all modes)" (modal)
    completion_omega: float | None = None
    coupling: float = 0.0
    dense: bool = False               # the viscous matrix is dense on the free DOFs (modal)
    convention: str = CONVENTION
    warnings: list[str] = field(default_factory=list)

    def describe(self) -> str:
        if self.method == "none":
            return "no psi in the model"
        if self.method == "equivalent":
            return (f"psi -> equivalent viscous C = H/omega_ref (9.3), omega_ref = {self.omega_ref:.6g} rad/s "
                    f"({self.omega_ref_source})")
        if self.completion == "stiffness":
            tail = f", higher modes: stiffness-proportional remainder H/omega_c, omega_c = {self.completion_omega:.6g} rad/s"
        elif self.completion == "none":
            tail = ", higher modes: undamped (completion = 'none')"
        else:
            tail = " (all modes)"
        return f"psi -> modal viscous matrix (9.14)-(9.18), {self.n_modes_used} mode(s){tail}"

    def to_dict(self) -> dict:
        return {"method": self.method, "description": self.describe(), "omega_ref": self.omega_ref,
                "omega_ref_source": self.omega_ref_source, "omega_rad_s": self.omega_rad_s.tolist(),
                "psi_star": self.psi_star.tolist(), "psi_represented": self.psi_represented.tolist(),
                "zeta": self.zeta.tolist(), "n_modes_used": self.n_modes_used, "n_free": self.n_free,
                "rigid_modes": self.rigid_modes, "completion": self.completion,
                "completion_omega": self.completion_omega, "coupling": float(self.coupling), "dense": self.dense,
                "convention": self.convention, "warnings": list(self.warnings)}


# ------------------------------------------------------------------ the two forms
def equivalent_viscous(system: LinearSystem, omega_ref: float) -> sp.csr_matrix:
    """(9.3) for every element at once: ``C = H / omega_ref`` (full size, constrained DOFs included:
    each element's damper acts on its own deformation, so rigid motions are not braked)."""
    if isinstance(omega_ref, bool) or not isinstance(omega_ref, (int, float, np.integer, np.floating)) \
            or not (math.isfinite(omega_ref) and omega_ref > 0):
        raise ModelError("[damping]", "omega_ref", omega_ref, "a reference frequency > 0 (rad/s)")
    return sp.csr_matrix(system.H / float(omega_ref))


def modal_psi(system: LinearSystem, modal: ModalResult) -> np.ndarray:
    """(9.14) per mode: ``psi_r* = 2 pi phi_r^T H phi_r / phi_r^T K phi_r`` (NaN for rigid-body modes)."""
    f = system.free
    Phi = modal.shapes[f]
    h = np.einsum("ij,ij->j", Phi, system.free_block(system.H) @ Phi)
    k = np.einsum("ij,ij->j", Phi, system.free_block(system.K) @ Phi)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(modal.rigid, np.nan, 2 * np.pi * h / k)


def modal_viscous_matrix(system: LinearSystem, modal: ModalResult, c_modal, *, remainder=None) -> np.ndarray:
    """Full-size dense viscous matrix with modal coefficients ``c_modal`` (mass-normalised modes of
    ``modal``): ``C_u = M Phi diag(c) Phi^T M (+ remainder)`` on the free DOFs, extended to the
    constrained DOFs as ``L^T C_u L`` (motion relative to the quasi-static driven position).

    ``remainder``: an extra free-DOF matrix (the completion) added to ``C_u``.  Also serves a
    modal ratio zeta in the time domain (``c_r = 2 zeta omega_r``)."""
    f, cdofs = system.free, system.constrained
    Phi = modal.shapes[f]
    U = system.free_block(system.M) @ Phi
    Cu = (U * np.asarray(c_modal, float)) @ U.T
    if remainder is not None:
        Cu = Cu + remainder
    Cu = 0.5 * (Cu + Cu.T)
    n = system.n_dofs
    C = np.zeros((n, n))
    C[np.ix_(f, f)] = Cu
    if cdofs.size:
        G = _quasi_static(system)              # u = q_f + G q_c
        if np.any(G):
            CuG = Cu @ G
            C[np.ix_(f, cdofs)] = CuG
            C[np.ix_(cdofs, f)] = CuG.T
            C[np.ix_(cdofs, cdofs)] = G.T @ CuG
    return C


def _quasi_static(system: LinearSystem) -> np.ndarray:
    """``G = K_ff^-1 K_fc``: the free DOFs follow ``-G q_c`` quasi-statically when the constrained DOFs
    move (min-norm solution where K_ff is singular: K_fc lies in its range for a PSD K)."""
    Kfc = sp.csr_matrix(system.K[system.free][:, system.constrained]).toarray()
    if not np.any(Kfc):
        return Kfc
    Kff = system.free_block(system.K)
    n_rigid = 0 if system.rigid_modes is None else system.rigid_modes.shape[1]
    if n_rigid == 0:
        try:
            lu = factorize(Kff)
            if lu.pivot_ratio > 1e3 * np.finfo(float).eps:
                return np.asarray(lu.solve(Kfc)).reshape(Kfc.shape)
        except SingularMatrixError:
            pass
    return sla.lstsq(Kff.toarray(), Kfc, cond=1e-12)[0]


# ------------------------------------------------------------------ entry point for the builders
def time_domain_psi(system: LinearSystem, method: str = "equivalent", omega_ref=None, n_modes: int | None = None, *,
                    forcing_omegas=(), completion: str = "stiffness",
                    where: str = "[damping]") -> tuple[sp.csr_matrix, PsiRepresentation]:
    """The viscous matrix ``C_extra`` (full size, to add to ``system.C``) representing the model's psi
    (``system.H``) in a time-domain run, and the report of what it represents.

    ``method``: ``"equivalent"`` (9.3), C = H/omega_ref, or ``"modal"`` (9.14)-(9.18).
    ``omega_ref`` (equivalent): a number > 0 (rad/s), ``"forcing"`` (the single frequency of the
    harmonic forcing/driving ``forcing_omegas``), ``"first_mode"`` (the lowest natural frequency); None
    takes the forcing frequency if there is exactly one (with a warning) and is otherwise an error --
    psi is never dropped silently.  ``n_modes`` (modal): modes in the modal matrix (default: all up to
    :data:`ALL_MODES_MAX` free DOFs, else :data:`DEFAULT_MODES`); in the equivalent form the number of
    modes listed in the report.  ``completion`` (modal): ``"stiffness"`` or ``"none"`` for the modes not
    included.  A system without psi returns a zero matrix and ``method = "none"``."""
    if method not in METHODS:
        raise ModelError(where, "psi_time", method, " | ".join(map(repr, METHODS)))
    if completion not in COMPLETIONS:
        raise ModelError(where, "psi_completion", completion, " | ".join(map(repr, COMPLETIONS)))
    n = system.n_dofs
    H = sp.csr_matrix(system.H)
    if H.nnz == 0 or not np.any(H.data):
        return sp.csr_matrix((n, n)), PsiRepresentation(method="none", n_free=system.n_free)
    asym = abs(H - H.T).max()
    if asym > 1e-12 * abs(H).max():
        raise ValueError(f"time_domain_psi: the loss stiffness H is not symmetric (|H - H^T| = {asym:.3g})")
    n_massive = _n_massive(system)
    if method == "modal":
        return _modal_form(system, n_modes, completion, n_massive, where)
    return _equivalent_form(system, omega_ref, n_modes, forcing_omegas, n_massive, where)


def _n_massive(system: LinearSystem) -> int:
    M = system.free_block(system.M)
    return int(np.count_nonzero(M.diagonal() > 0)) if is_diagonal(M) else system.n_free


def _check_modes(n_modes, n_massive: int, where: str) -> int:
    if isinstance(n_modes, bool) or not isinstance(n_modes, (int, np.integer)) or not 1 <= n_modes <= n_massive:
        raise ModelError(where, "psi_modes", n_modes, f"an integer from 1 to {n_massive} (the DOFs with inertia)")
    return int(n_modes)


def _modes(system: LinearSystem, k: int) -> ModalResult:
    return modal_analysis(system, k)


def _report_modes(rep: PsiRepresentation, system: LinearSystem, modal: ModalResult, C_free, n_keep: int):
    """Fill the per-mode columns (flexible modes only, the first ``n_keep`` of them)."""
    flex = np.flatnonzero(~modal.rigid)[:n_keep]
    f = system.free
    Phi = modal.shapes[f][:, flex]
    w = modal.omega_rad_s[flex]
    c = np.einsum("ij,ij->j", Phi, C_free @ Phi)
    rep.omega_rad_s = w
    rep.psi_star = modal_psi(system, modal)[flex]
    rep.psi_represented = 2 * np.pi * c / w
    rep.zeta = c / (2 * w)
    rep.rigid_modes = int(modal.rigid.sum())
    W = Phi.T @ (system.free_block(system.H) @ Phi)
    d = np.sqrt(np.clip(np.diag(W), 0, None))
    scale = np.outer(d, d)
    off = np.abs(W - np.diag(np.diag(W)))
    rep.coupling = float(np.max(np.divide(off, scale, out=np.zeros_like(off), where=scale > 0))) if w.size > 1 else 0.0


def _equivalent_form(system, omega_ref, n_modes, forcing_omegas, n_massive, where):
    warnings = []
    n_list = min(REPORT_MODES, n_massive) if n_modes is None else _check_modes(n_modes, n_massive, where)
    modal = None
    forcing = sorted({abs(float(w)) for w in forcing_omegas if w and math.isfinite(w)})
    if isinstance(omega_ref, str):
        if omega_ref == "forcing":
            if len(forcing) != 1:
                raise ModelError(where, "omega_ref", "forcing", _forcing_allowed(forcing))
            omega, source = forcing[0], "forcing frequency"
        elif omega_ref == "first_mode":
            modal = _modes(system, min(n_list + _rigid_count(system), n_massive))
            flex = modal.omega_rad_s[~modal.rigid]
            if flex.size == 0:
                raise ModelError(where, "omega_ref", "first_mode", "a number > 0 (rad/s): the model has no "
                                 "flexible mode (only rigid-body motion)")
            omega, source = float(flex[0]), "first natural frequency"
        else:
            raise ModelError(where, "omega_ref", omega_ref, "a number > 0 (rad/s), 'forcing' or 'first_mode'")
    elif omega_ref is None:
        if len(forcing) != 1:
            raise ModelError(where, "omega_ref", None,
                             "a reference frequency for psi_time = 'equivalent' ((9.3) b = psi c/(2 pi omega) needs "
                             "one): a number > 0 (rad/s), 'forcing' or 'first_mode' -- "
                             + ("the model has no harmonic forcing to take it from" if not forcing else
                                f"the forcing has several frequencies {forcing}") + "; or psi_time = 'modal'")
        omega, source = forcing[0], "forcing frequency"
        warnings.append(f"omega_ref not given: psi represented at the forcing frequency {omega:.6g} rad/s "
                        "((9.3) with omega = the forcing frequency)")
    else:
        omega, source = omega_ref, "given"
    C = equivalent_viscous(system, omega)
    omega = float(omega)
    rep = PsiRepresentation(method="equivalent", omega_ref=omega, omega_ref_source=source, n_free=system.n_free,
                            warnings=warnings)
    if modal is None:
        modal = _modes(system, min(n_list + _rigid_count(system), n_massive))
    _report_modes(rep, system, modal, system.free_block(C), n_list)
    far = rep.omega_rad_s[(rep.omega_rad_s > 2 * omega) | (rep.omega_rad_s < 0.5 * omega)]
    if far.size:
        rep.warnings.append(f"{far.size} of the listed modes lie outside [omega_ref/2, 2 omega_ref]: (9.3) damps "
                            "each mode with psi* omega_r/omega_ref (see psi_represented); psi_time = 'modal' "
                            "gives every mode its own psi*")
    return C, rep


def _rigid_count(system: LinearSystem) -> int:
    return 0 if system.rigid_modes is None else int(system.rigid_modes.shape[1])


def _forcing_allowed(forcing) -> str:
    if not forcing:
        return "a number > 0 (rad/s) or 'first_mode': the model has no harmonic forcing to take it from"
    return f"a number > 0 (rad/s) or 'first_mode': the forcing has several frequencies {forcing}"


def _modal_form(system, n_modes, completion, n_massive, where):
    nf = system.n_free
    if nf > MODAL_DENSE_MAX:
        raise ModelError(where, "psi_time", "modal", f"'equivalent' (sparse C = H/omega_ref) for models with more "
                         f"than {MODAL_DENSE_MAX} free DOFs (this one: {nf}), or a [reduction]: the modal matrix "
                         "M Phi diag Phi^T M is dense")
    n_rigid = _rigid_count(system)
    if n_modes is None:
        k = n_massive if n_massive <= ALL_MODES_MAX else min(DEFAULT_MODES + n_rigid, n_massive)
    else:
        k = min(_check_modes(n_modes, n_massive, where) + n_rigid, n_massive)
    extra = 1 if k < n_massive else 0           # the first excluded mode: completion frequency, and reported
    modal = _modes(system, k + extra)
    keep = np.arange(k)
    flex_all = ~modal.rigid
    w_all = modal.omega_rad_s
    f = system.free
    Hff = system.free_block(system.H)
    Phi = modal.shapes[f]
    h = np.einsum("ij,ij->j", Phi, Hff @ Phi)
    c_modal = np.where(flex_all, h / np.where(flex_all, w_all, 1.0), 0.0)       # (9.15)-(9.18): h_r / omega_r
    sub = ModalResult(omega_rad_s=w_all[keep], eigenvalues=modal.eigenvalues[keep], shapes=modal.shapes[:, keep],
                      residuals=modal.residuals[keep], rayleigh_rel_diff=modal.rayleigh_rel_diff[keep],
                      precision_bound=modal.precision_bound[keep], rigid=modal.rigid[keep], n_dofs=modal.n_dofs,
                      method=modal.method, shift=modal.shift, tolerance=modal.tolerance)
    warnings = list(modal.warnings)
    remainder, omega_c = None, None
    if k >= n_massive:
        tail = "complete (all modes)"
    elif completion == "stiffness":
        omega_c = float(w_all[k])
        U = system.free_block(system.M) @ Phi[:, keep]
        V = Hff @ Phi[:, keep]
        Wk = Phi[:, keep].T @ V
        remainder = (Hff.toarray() - U @ V.T - V @ U.T + U @ Wk @ U.T) / omega_c
        tail = "stiffness"
    else:
        tail = "none"
        warnings.append(f"completion = 'none': the modes above mode {k} (omega > {w_all[k - 1]:.6g} rad/s) carry "
                        "no damping from psi")
    C = modal_viscous_matrix(system, sub, c_modal[keep], remainder=remainder)
    rep = PsiRepresentation(method="modal", n_free=nf, n_modes_used=int(np.count_nonzero(flex_all[keep])),
                            completion=tail, completion_omega=omega_c, dense=True, warnings=warnings)
    _report_modes(rep, system, modal, C[np.ix_(f, f)], modal.omega_rad_s.size)
    return sp.csr_matrix(C), rep
