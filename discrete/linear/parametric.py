"""Parametric vibrations (textbook ch. 7): Floquet multipliers of a linear system with periodic
stiffness and inertia, stability charts in the (depth, Omega) plane, tongue edges and damping
thresholds.

The equations, on the free DOFs of a :class:`~discrete.linear_system.LinearSystem`::

    K(t) = K0 - eps * sum_j d_j P_j sin(h_j Omega t + phi_j)          (stiffness, (7.1)-(7.2))
    M(t) = M0 - eps * sum_j d_j Q_j sin(h_j Omega t + phi_j)          (reduced inertia, (7.3)-(7.7))

    M(t) q'' + (C + a dM/dt) q' + (K(t) + b d2M/dt2 / 2) q = 0

with the sign of the book's (7.1), c(t) = c0 - dc sin(Omega t) (a phase shift of pi turns it
into the other sign).  ``eps`` is the depth of pulsation (the chart's vertical axis); each
:class:`Modulation` carries its own relative depth ``d``, harmonic ``h``, phase ``phi`` and part
``P`` (or ``Q``) of the matrix that pulsates (default: the whole K0 or M0).  The inertia terms
follow ``inertia_form``:

* ``"programme"`` (default): a = b = 1, the linearisation about the programme motion (7.7),
  ``J* q'' + (b0 + J*' w0) q' + c0 (1 + w0^2 J*'' / (2 c0)) q = 0``: with phi* = w0 t the book's
  J*' w0 = dJ/dt and J*'' w0^2 = d2J/dt2;
* ``"momentum"``: a = 1, b = 0, ``(M q')' + C q' + K q = 0``;
* ``"newton"``: a = b = 0, ``M(t) q'' + C q' + K q = 0``.

Damping (``discrete.linear.harmonic.Damping``; the energy-dissipation coefficient psi of the
book converts to the viscous ratio zeta = delta = psi/(4 pi), as in (7.31)
``2 n0 = 0.5 psi k0 / pi``): the model's dampers C, plus the hysteretic matrix H of elements
with psi converted mode by mode to the viscous damping that dissipates the same energy per cycle
at the mode's own frequency (modal b_r = h_r / omega_r, the construction (9.14)-(9.18)); type
``rayleigh`` adds alpha M0 + beta K0, ``modal`` a ratio zeta in every mode of the mean system,
``hysteretic`` a uniform psi (zeta = psi/(4 pi) in every mode); ``none`` drops all damping.

Coordinates.  The analysis runs in the mass-normalised modal coordinates theta of the mean
system (K0, M0) with the state y = [theta, theta'/omega_r]: an exact similarity of [q, q'] when all
modes are kept (multipliers unchanged), in which the unperturbed motion is a set of rotations --
well scaled even when the natural frequencies spread over decades.  Systems with more than
``DENSE_MAX`` free DOFs (FE models) must be projected on their lowest ``modes`` (Galerkin; converge
by raising ``modes``; the cost grows with (omega_max / Omega) * modes^3).

Monodromy matrix.  y' = A(t) y is integrated over one period T = 2 pi / Omega by the sixth-order
Magnus integrator with three Gauss-Legendre nodes (Blanes, Casas & Ros, BIT 40 (2000) 434;
Blanes et al., Phys. Rep. 470 (2009) §5): one matrix exponential per step of an exponent built
from A at the nodes and two nested commutators.  Why this method: it is exact for a constant A at
any step (the pulsation sets the error, not the natural frequencies alone); it stays in the Lie
group of the equation (for an undamped stiffness-modulated system the monodromy is symplectic to
round-off, so stable multipliers stay on the unit circle, and det Phi = exp(int tr A) holds for any
system); and a fixed step vectorises over a whole grid of (eps, Omega) points and over the steps.
Its error expansion is even in the step, so each monodromy is computed with N and 2N steps and the
difference / 63 estimates the error of the finer one (``error_estimate``, relative to ||Phi||);
steps are doubled until it is below ``tolerance`` (or stops decreasing: round-off).  The initial
N keeps the rotation omega_max T / N of the fastest mode below 1 rad (measured: the error is
still in the asymptotic sixth-order regime there).  ``liouville_residual`` =
|ln|det Phi| - int_0^T tr A dt| is the Liouville/Abel identity, with the trace integral computed
independently of the integrator (closed form for a constant M, spectrally accurate periodic
trapezoid otherwise).  Because the Magnus exponents keep the trace exactly, this residual
measures round-off in the exponentials and products, not the truncation error, which
``error_estimate`` measures.

Stability: max |multiplier| < 1 + ``stability_margin`` (default 1e-6: an undamped stable point has
|rho| = 1 to round-off, sqrt of round-off at a tongue edge).  Tongue edges are located by root
finding along Omega on det(Phi + I) (a real multiplier through -1: the odd tongues
Omega ~ 2 k/s, s = 1, 3, ..., (7.26), where the book's "stability" means instability),
det(Phi - I) (through +1: even s) or, for complex crossings (combination resonances of MDOF
systems), on max|rho| - 1 - margin.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.optimize as so
import scipy.sparse as sp

from ..linalg.expm import expm_batch
from ..errors import ModelError, SolverError
from ..linalg.blas import single_threaded_blas
from ..linear_system import LinearSystem
from .harmonic import Damping
from .modal import modal_analysis

TARGETS = ("stiffness", "inertia")
INERTIA_FORMS = ("programme", "momentum", "newton")
DENSE_MAX = 60
WHERE = "[analysis] parametric"

_S15 = math.sqrt(15.0)
_NODES = (0.5 - _S15 / 10.0, 0.5, 0.5 + _S15 / 10.0)      # Gauss-Legendre nodes on [0, 1]
_MIN_STEPS = 8
_MAX_STEPS = 1 << 14
_CHUNK_ELEMENTS = 1 << 20                                 # doubles per work array of the integrator


# ----------------------------------------------------------------------------- input
@dataclass
class Modulation:
    """One pulsating term: ``-eps * depth * part * sin(harmonic * Omega t + phase)`` added to K
    (``target = "stiffness"``, part in N/m or N m/rad) or to M (``"inertia"``, kg or kg m^2).

    ``part``: full-size matrix (all DOFs, sparse or dense, symmetric) of the pulsating part;
    ``None`` = the whole K or M of the system.  ``depth``: relative depth (dimensionless; the
    analysis depth eps multiplies it).  ``harmonic``: integer >= 1.  ``phase``: rad.
    """

    target: str = "stiffness"
    depth: float = 1.0
    harmonic: int = 1
    phase: float = 0.0
    part: object = None
    label: str = ""

    def __post_init__(self):
        where = f"[[modulation]] {self.label}".rstrip()
        if self.target not in TARGETS:
            raise ModelError(where, "target", self.target, " | ".join(map(repr, TARGETS)))
        _finite(self.depth, "depth", where)
        _finite(self.phase, "phase", where)
        if (isinstance(self.harmonic, bool) or not isinstance(self.harmonic, (int, np.integer))
                or self.harmonic < 1):
            raise ModelError(where, "harmonic", self.harmonic, "an integer >= 1 (sin(harmonic * Omega t + phase))")

    def to_dict(self) -> dict:
        return {"target": self.target, "depth": float(self.depth), "harmonic": int(self.harmonic),
                "phase": float(self.phase), "part": "whole matrix" if self.part is None else "given matrix",
                "label": self.label}


def _finite(value, key, where):
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not math.isfinite(value):
        raise ModelError(where, key, value, "a finite number")
    return float(value)


def _positive(value, key, where=WHERE, unit=""):
    v = _finite(value, key, where)
    if not v > 0:
        raise ModelError(where, key, value, "a number > 0" + (f" ({unit})" if unit else ""))
    return v


def _count(value, key, lo, where=WHERE):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < lo:
        raise ModelError(where, key, value, f"an integer >= {lo}")
    return int(value)


def _none_if_nan(d: dict) -> dict:
    return {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in d.items()}


# --------------------------------------------------------------------------- results
@dataclass
class FloquetResult:
    """Floquet analysis at one point (eps, Omega).  ``monodromy`` acts on the state
    y = [theta, theta'/omega_r] in the modal coordinates of the mean system (see the module
    docstring; :meth:`ParametricProblem.physical_monodromy` maps it back to [q, q'])."""

    omega_rad_s: float               # excitation frequency Omega
    depth: float                     # depth of pulsation eps
    period_s: float                  # T = 2 pi / Omega
    multipliers: np.ndarray          # (2n,) complex eigenvalues of the monodromy matrix
    monodromy: np.ndarray            # (2n, 2n)
    rho_max: float                   # max |multiplier|
    stable: bool                     # rho_max < 1 + stability_margin
    error_estimate: float            # estimated relative error of the monodromy (step halving)
    converged: bool                  # error_estimate <= tolerance
    liouville_residual: float        # |ln|det Phi| - int tr A dt|
    liouville_reference: float       # int_0^T tr A dt
    n_steps: int
    stability_margin: float

    @property
    def growth_rate(self) -> float:
        """Largest characteristic exponent ln(rho_max) / T in 1/s (negative: decay)."""
        return math.log(self.rho_max) / self.period_s

    def to_dict(self) -> dict:
        return {"omega_rad_s": self.omega_rad_s, "depth": self.depth, "period_s": self.period_s,
                "multipliers_real": self.multipliers.real.tolist(), "multipliers_imag": self.multipliers.imag.tolist(),
                "rho_max": self.rho_max, "growth_rate_1_s": self.growth_rate, "stable": bool(self.stable),
                "error_estimate": self.error_estimate, "converged": bool(self.converged),
                "liouville_residual": self.liouville_residual, "liouville_reference": self.liouville_reference,
                "n_steps": self.n_steps, "stability_margin": self.stability_margin}


@dataclass
class DampingThreshold:
    """Smallest depth of the principal tongue of one mode (Omega ~ 2 omega_r): the book's
    eps* = psi/pi (7.28) for one DOF, here computed from the multipliers."""

    mode: int                        # 1-based mode number of the mean system
    natural_omega_rad_s: float       # omega_r of the mean system
    omega_centre_rad_s: float        # 2 omega_r
    depth_at_centre: float           # eps* at Omega = 2 omega_r (nan: none below the depth limit)
    omega_at_minimum_rad_s: float    # Omega of the tongue tip (lowest eps*)
    depth_minimum: float             # eps* at the tongue tip
    zeta: float                      # equivalent viscous ratio of the mode (psi / (4 pi) for psi)
    energy_estimate: float           # (7.28) generalised: 4 zeta / kappa_r (nan where not defined)
    max_error_estimate: float = 0.0  # worst monodromy error estimate met in the root searches
    note: str = ""

    def to_dict(self) -> dict:
        return _none_if_nan(dict(self.__dict__))


@dataclass
class TongueBoundaries:
    """Instability intervals along Omega at one depth, edges located by root finding."""

    depth: float
    omega_low_rad_s: np.ndarray      # (k,) lower edges
    omega_high_rad_s: np.ndarray     # (k,) upper edges
    crossing: list[str]              # per interval: "-1", "+1" or "complex" (how the multiplier leaves)
    centre: list[str]                # nearest predicted centre, e.g. "2 w1/1"
    clipped: list[str]               # "" or "low" / "high": the interval runs past the scanned range
    omega_range_rad_s: tuple[float, float]
    n_samples: int
    max_error_estimate: float = 0.0  # worst monodromy error estimate met in sampling and root finding

    def to_dict(self) -> dict:
        return {"depth": self.depth, "omega_low_rad_s": self.omega_low_rad_s.tolist(),
                "omega_high_rad_s": self.omega_high_rad_s.tolist(), "crossing": list(self.crossing),
                "centre": list(self.centre), "clipped": list(self.clipped),
                "omega_range_rad_s": list(self.omega_range_rad_s), "n_samples": self.n_samples,
                "max_error_estimate": self.max_error_estimate}


@dataclass
class StabilityChart:
    """Scan of the (eps, Omega) plane; arrays are (n_depth, n_omega)."""

    depth: np.ndarray
    omega_rad_s: np.ndarray
    rho_max: np.ndarray
    stable: np.ndarray
    growth_rate: np.ndarray          # ln(rho_max) / T, 1/s
    error_estimate: np.ndarray
    liouville_residual: np.ndarray
    natural_omega_rad_s: np.ndarray  # modes of the mean system
    centres: list[dict]              # predicted tongue centres 2 w_r / s and (w_r + w_q) / s in range
    thresholds: list[DampingThreshold]
    boundaries: list[TongueBoundaries]
    damping: str
    inertia_form: str
    modulations: list[dict]
    depth_limit: float               # K(t), M(t) stay positive definite for eps below this
    stability_margin: float
    tolerance: float
    n_dofs: int                      # size of the analysed system (free DOFs or modes)
    projected: bool                  # True: Galerkin on the lowest n_dofs modes
    warnings: list[str] = field(default_factory=list)

    def to_dict(self) -> dict:
        return {"depth": self.depth.tolist(), "omega_rad_s": self.omega_rad_s.tolist(),
                "rho_max": self.rho_max.tolist(), "stable": self.stable.tolist(),
                "growth_rate_1_s": self.growth_rate.tolist(), "error_estimate": self.error_estimate.tolist(),
                "liouville_residual": self.liouville_residual.tolist(),
                "max_error_estimate": float(np.max(self.error_estimate)),
                "max_liouville_residual": float(np.max(self.liouville_residual)),
                "natural_omega_rad_s": self.natural_omega_rad_s.tolist(), "centres": list(self.centres),
                "thresholds": [t.to_dict() for t in self.thresholds],
                "boundaries": [b.to_dict() for b in self.boundaries], "damping": self.damping,
                "inertia_form": self.inertia_form, "modulations": list(self.modulations),
                "depth_limit": self.depth_limit if math.isfinite(self.depth_limit) else None,
                "stability_margin": self.stability_margin, "tolerance": self.tolerance, "n_dofs": self.n_dofs,
                "projected": self.projected, "warnings": list(self.warnings)}


# --------------------------------------------------------------------------- problem
class ParametricProblem:
    """The periodic system in the modal coordinates of its mean system, ready for Floquet
    analysis.  Build once with :meth:`build`; the public functions accept either a problem or
    (system, modulations, damping, ...) and build it."""

    def __init__(self, lam, C, parts_K, parts_M, form, damping_desc, kappa, shapes, n_dofs, projected, labels):
        self.lam = lam                          # omega_r^2 of the mean system
        self.omega_modes = np.sqrt(lam)
        self.n = lam.size
        self.C = C                              # modal damping matrix (n, n)
        self.parts_K = parts_K                  # list of (d * Phi^T P Phi, harmonic, phase)
        self.parts_M = parts_M
        self.form = form
        self.damping = damping_desc
        self.zeta_modes = np.diag(C) / (2 * self.omega_modes)
        self.kappa = kappa                      # first-harmonic stiffness overlap per mode (nan: undefined)
        self.shapes = shapes                    # mass-normalised modes on the free DOFs (n_free, n)
        self.n_dofs = n_dofs
        self.projected = projected
        self.modulation_labels = labels
        w = self.omega_modes
        # scaled-state blocks (no inertia modulation): -W^-1 K(t) = -(W - eps W^-1 S_K(t)), -W^-1 C W
        self._GC = C / w[:, None] * w[None, :]
        self._GK = [(X / w[:, None], h, ph) for X, h, ph in parts_K]
        self.depth_limit = self._depth_limit()
        self.worst_error = 0.0                  # largest error estimate of the monodromies since reset

    # ........................................................... construction
    @classmethod
    def build(cls, system: LinearSystem, modulations, *, damping: Damping | None = None,
              inertia_form: str = "programme", modes: int | None = None) -> "ParametricProblem":
        """``system``: the linear system (free DOFs are analysed, constrained ones held);
        ``modulations``: list of :class:`Modulation`; ``damping``: Damping (default: the
        model's dampers and element psi); ``inertia_form``: see the module docstring;
        ``modes``: project on the lowest modes (required above ``DENSE_MAX`` free DOFs)."""
        if not isinstance(system, LinearSystem):
            raise ModelError(WHERE, "system", type(system).__name__, "a discrete.linear_system.LinearSystem")
        if inertia_form not in INERTIA_FORMS:
            raise ModelError(WHERE, "inertia_form", inertia_form, " | ".join(map(repr, INERTIA_FORMS)))
        damping = damping if damping is not None else Damping("viscous")
        if not isinstance(damping, Damping):
            raise ModelError(WHERE, "damping", damping, "a discrete.linear.harmonic.Damping")
        if isinstance(modulations, Modulation):
            modulations = [modulations]
        modulations = list(modulations or [])
        if not modulations:
            raise ModelError(WHERE, "modulation", [], "at least one [[modulation]] (a pulsating stiffness or inertia)")
        for i, m in enumerate(modulations, 1):
            if not isinstance(m, Modulation):
                raise ModelError(WHERE, f"modulation #{i}", m, "a Modulation(target, depth, harmonic, phase, part)")
        if system.G.nnz:
            raise ModelError(WHERE, "G", "gyroscopic matrix", "a system without gyroscopic terms "
                             "(parametric analysis of spinning rotors is not supported)")
        n = system.n_free
        if n == 0:
            raise ModelError(WHERE, "system", "no free DOFs", "a system with at least one free DOF")
        f = system.free
        K, M = system.free_block(system.K), system.free_block(system.M)
        C, H = system.free_block(system.C), system.free_block(system.H)
        parts = []
        for i, m in enumerate(modulations, 1):
            where = f"[[modulation]] #{i}" + (f" ({m.label})" if m.label else "")
            if m.part is None:
                P = K if m.target == "stiffness" else M
            else:
                shape = getattr(m.part, "shape", None)
                if shape != (system.n_dofs, system.n_dofs):
                    raise ModelError(where, "part", f"matrix of shape {shape}",
                                     f"a ({system.n_dofs}, {system.n_dofs}) matrix over all DOFs of the system")
                P = sp.csr_matrix(m.part, dtype=float)[f][:, f]
                big = abs(P).max() if P.nnz else 0.0
                if not np.all(np.isfinite(P.data)) or (P.nnz and abs(P - P.T).max() > 1e-12 * big):
                    raise ModelError(where, "part", "non-symmetric or non-finite matrix", "a finite symmetric matrix")
            parts.append((m, sp.csr_matrix(P)))
        if modes is not None and (isinstance(modes, bool) or not isinstance(modes, (int, np.integer))
                                  or not 1 <= modes <= n):
            raise ModelError(WHERE, "modes", modes, f"an integer from 1 to {n} (the number of free DOFs)")
        if n > DENSE_MAX and modes is None:
            raise ModelError(WHERE, "modes", None, f"an integer number of modes: a system with {n} free DOFs "
                             f"(more than {DENSE_MAX}) is projected on the lowest modes of the mean system")
        if modes is None:
            Md = M.toarray()
            try:
                np.linalg.cholesky(Md)
            except np.linalg.LinAlgError:
                raise ModelError(WHERE, "mass", "singular or indefinite", "a positive definite mass matrix on the "
                                 "free DOFs (every free DOF needs inertia)") from None
            lam, Phi = sla.eigh(K.toarray(), Md)
            projected = False
        else:
            res = modal_analysis(system, int(modes))
            if res.rigid_body_modes:
                _rigid_error(res.rigid_body_modes)
            lam, Phi = np.asarray(res.eigenvalues, dtype=float), res.shapes[f]
            projected = True
        scale = max(float(np.max(np.abs(lam))), 1e-300)
        if lam[0] <= 1e-10 * scale:
            _rigid_error(int(np.sum(lam <= 1e-10 * scale)))
        w = np.sqrt(lam)

        def modal(A):
            return Phi.T @ (A @ Phi)

        Cm = np.zeros((lam.size, lam.size))
        desc = damping.describe()
        if damping.type != "none":
            Cm = modal(C)
            b = np.zeros_like(w)
            if H.nnz:
                # hysteretic H of elements with psi -> equivalent modal viscous b_r = h_r / omega_r
                b = np.diag(modal(H)) / w
                desc += " + element psi (hysteretic H -> modal viscous h_r/omega_r)"
            if damping.type == "rayleigh":
                b = b + damping.alpha + damping.beta * lam
            elif damping.type == "modal":
                b = b + 2 * damping.zeta * w
            elif damping.type == "hysteretic":
                b = b + 2 * damping.delta * w
                desc += f" (equivalent viscous zeta = psi/(4 pi) = {damping.delta:.6g} per mode)"
            Cm = Cm + np.diag(b)
        parts_K, parts_M = [], []
        kappa = np.zeros(w.size, dtype=complex)
        kappa_defined = True
        for m, P in parts:
            Pm = modal(P)
            Pm = 0.5 * (Pm + Pm.T)
            (parts_K if m.target == "stiffness" else parts_M).append((m.depth * Pm, int(m.harmonic), float(m.phase)))
            if m.target == "stiffness" and m.harmonic == 1:
                kappa = kappa + m.depth * np.exp(1j * m.phase) * np.diag(Pm) / lam
            elif m.depth != 0:
                kappa_defined = False
        kappa = np.abs(kappa) if kappa_defined else np.full(w.size, np.nan)
        return cls(lam, Cm, parts_K, parts_M, inertia_form, desc, kappa, Phi, n_dofs=n, projected=projected,
                   labels=[m.to_dict() for m, _ in parts])

    # ......................................................... positivity limit
    def _depth_limit(self) -> float:
        """Largest eps for which K(t) and M(t) stay positive definite for all t (on the analysed
        coordinates: exact for the full basis, the Galerkin approximation when projected)."""
        lim = math.inf
        for base, parts in ((np.diag(self.lam), self.parts_K), (np.eye(self.n), self.parts_M)):
            if not parts:
                continue
            hmax = max(h for _, h, _ in parts)

            def lam_max(tau):
                S = sum(P * math.sin(h * tau + ph) for P, h, ph in parts)
                return float(sla.eigh(S, base, eigvals_only=True)[-1])

            taus = np.linspace(0.0, 2 * math.pi, 96 * hmax, endpoint=False)
            vals = np.array([lam_max(t) for t in taus])
            k = int(np.argmax(vals))
            d = taus[1] - taus[0]
            r = so.minimize_scalar(lambda t: -lam_max(t), bounds=(taus[k] - d, taus[k] + d), method="bounded",
                                   options={"xatol": 1e-10})
            top = max(vals[k], -r.fun)
            if top > 0:
                lim = min(lim, 1.0 / top)
        return lim

    def check_depth(self, depth, key="depth", where=WHERE) -> float:
        eps = _finite(depth, key, where)
        if eps < 0:
            raise ModelError(where, key, depth, "a number >= 0 (the depth of pulsation eps)")
        if not eps < self.depth_limit:
            which = "K" if not self.parts_M else ("M" if not self.parts_K else "K or M")
            raise ModelError(where, key, depth, f"0 <= {key} < {self.depth_limit:.6g}: at larger depth {which}(t) "
                             f"is not positive definite during the whole period")
        return eps

    # ...................................................... state matrices
    def _series(self, parts, tau, order=0):
        """sum_j X_j f(h_j tau + phi_j) over an array of phases (T,): shape (T, n, n); f = sin or
        its first (order 1) or second (order 2) derivative in tau."""
        out = 0.0
        for X, h, ph in parts:
            arg = h * tau + ph
            f = np.sin(arg) if order == 0 else (h * np.cos(arg) if order == 1 else -h * h * np.sin(arg))
            out = out + f[:, None, None] * X[None]
        return out

    def state_matrices(self, tau, eps: np.ndarray, omega: np.ndarray) -> np.ndarray:
        """A(t)/Omega = dy/dtau at phases tau = Omega t (array, T) for a batch of points (P,),
        y = [theta, theta'/omega_r]: shape (T, P, 2n, 2n)."""
        n, w = self.n, self.omega_modes
        tau = np.atleast_1d(np.asarray(tau, dtype=float))
        T, P = tau.size, eps.size
        e = eps[None, :, None, None]
        if not self.parts_M:
            GK = np.diag(w)[None, None]
            if self._GK:
                GK = GK - e * self._series(self._GK, tau)[:, None]
            GK = np.broadcast_to(GK, (T, P, n, n))
            GC = np.broadcast_to(self._GC, (T, P, n, n))
        else:
            Om = omega[None, :, None, None]
            Mt = np.eye(n) - e * self._series(self.parts_M, tau)[:, None]
            Kt = np.broadcast_to(np.diag(self.lam), (T, P, n, n))
            if self.parts_K:
                Kt = Kt - e * self._series(self.parts_K, tau)[:, None]
            Ct = np.broadcast_to(self.C, (T, P, n, n))
            if self.form in ("programme", "momentum"):
                Ct = Ct - e * Om * self._series(self.parts_M, tau, 1)[:, None]          # + dM/dt
            if self.form == "programme":
                Kt = Kt - 0.5 * e * Om**2 * self._series(self.parts_M, tau, 2)[:, None]  # + (1/2) d2M/dt2
            B = np.linalg.solve(Mt, np.concatenate(np.broadcast_arrays(Kt, Ct), axis=-1))
            GK = B[..., :n] / w[:, None]
            GC = B[..., n:] / w[:, None] * w[None, :]
        A = np.zeros((T, P, 2 * n, 2 * n))
        inv = (1.0 / omega)[None, :, None, None]
        A[..., :n, n:] = np.diag(w) * inv
        A[..., n:, :n] = -GK * inv
        A[..., n:, n:] = -GC * inv
        return A

    def trace_integral(self, eps: np.ndarray, omega: np.ndarray) -> np.ndarray:
        """int_0^T tr A dt for a batch (the Liouville/Abel reference), = -int tr(M^-1 C) dt:
        tr(M^-1 dM/dt) integrates to ln det M(T)/det M(0) = 0 exactly."""
        T = 2 * math.pi / omega
        if not self.parts_M:
            return -T * np.trace(self.C) * np.ones_like(eps)
        m = 256 * max(h for _, h, _ in self.parts_M)      # periodic analytic integrand: trapezoid
        taus = np.arange(m) * (2 * math.pi / m)
        S = self._series(self.parts_M, taus)
        total = np.zeros_like(eps)
        for i in range(eps.size):
            Mt = np.eye(self.n)[None] - eps[i] * S
            total[i] = np.trace(np.linalg.solve(Mt, np.broadcast_to(self.C, Mt.shape)), axis1=1, axis2=2).sum()
        return -T * total / m

    def physical_monodromy(self, Phi: np.ndarray) -> np.ndarray:
        """The monodromy on the state [q, q'] of the free DOFs (full basis only)."""
        if self.projected:
            raise ModelError(WHERE, "modes", self.n, "no projection (modes = None) to map the monodromy to the DOFs")
        V = self.shapes
        Tm = sla.block_diag(V, V * self.omega_modes[None, :])
        return Tm @ Phi @ np.linalg.inv(Tm)

    # .......................................................... monodromy
    def monodromy(self, eps, omega, *, tolerance: float = 1e-10, progress=None):
        """Monodromy matrices for a batch: (Phi (P, 2n, 2n), error_estimate (P,), n_steps (P,));
        ``progress(k)``: called after each chunk with the k points it finished (reporting only)."""
        eps, omega = np.broadcast_arrays(np.atleast_1d(np.asarray(eps, dtype=float)),
                                         np.atleast_1d(np.asarray(omega, dtype=float)))
        eps, omega = eps.ravel().copy(), omega.ravel().copy()
        P, n2 = eps.size, 2 * self.n
        Phi = np.empty((P, n2, n2))
        err = np.empty(P)
        steps = np.empty(P, dtype=int)
        # initial steps: rotation of the fastest mode (raised by the pulsation) <= 1 rad per step, and at
        # least 8 steps per period of the highest harmonic of the pulsation (a coarser first grid can look
        # converged to the doubling test, whose error does not yet fall at the sixth-order rate)
        wmax = self.omega_modes.max() * math.sqrt(1.0 + (eps.max() if eps.size else 0.0))
        hmax = max([h for _, h, _ in self.parts_K + self.parts_M], default=1)
        with np.errstate(over="ignore"):
            N0 = np.maximum(max(_MIN_STEPS, 8 * hmax), np.ceil(2 * math.pi * wmax / omega))
        N0 = np.minimum(2 ** np.ceil(np.log2(np.minimum(N0, _MAX_STEPS))), _MAX_STEPS // 2).astype(int)
        chunk = max(1, _CHUNK_ELEMENTS // (32 * n2 * n2))
        for N in np.unique(N0):
            idx = np.flatnonzero(N0 == N)
            for start in range(0, idx.size, chunk):
                sel = idx[start:start + chunk]
                Phi[sel], err[sel], steps[sel] = self._converged(eps[sel], omega[sel], int(N), tolerance)
                if progress is not None:
                    progress(sel.size)
        bad = ~np.all(np.isfinite(Phi), axis=(1, 2))
        if np.any(bad):
            k = int(np.flatnonzero(bad)[0])
            rot = 2 * math.pi * wmax / omega[k]
            raise UnresolvedMonodromy(
                float(eps[k]), float(omega[k]),
                f"{WHERE}: the monodromy matrix at eps = {eps[k]:.6g}, Omega = {omega[k]:.6g} rad/s overflowed "
                f"({int(np.sum(bad))} of {P} points): with {int(steps[k])} steps (at most {_MAX_STEPS}) over one "
                f"period 2 pi/Omega the integrator cannot resolve the motion -- the fastest mode turns {rot:.3g} rad "
                f"in a period and the pulsation's highest harmonic is {hmax}; raise the start of the Omega range, "
                "lower the depth or the harmonic")
        if P:
            self.worst_error = max(self.worst_error, float(err.max()))
        return Phi, err, steps

    def _converged(self, eps, omega, N, tolerance):
        coarse = self._magnus(eps, omega, N)
        Phi, err = np.empty_like(coarse), np.full(eps.size, np.inf)
        steps = np.zeros(eps.size, dtype=int)
        prev = np.full(eps.size, np.inf)
        todo = np.arange(eps.size)
        while todo.size:
            fine = self._magnus(eps[todo], omega[todo], 2 * N)
            scale = np.maximum(np.abs(fine).max(axis=(1, 2)), 1e-300)
            e = np.abs(fine - coarse).max(axis=(1, 2)) / (63.0 * scale)
            Phi[todo], err[todo], steps[todo] = fine, e, 2 * N
            # done: converged, or no longer converging (round-off floor), or out of steps
            done = (e <= tolerance) | (e > 0.25 * prev[todo]) | (4 * N > _MAX_STEPS)
            prev[todo] = e
            todo, coarse = todo[~done], fine[~done]
            N *= 2
        return Phi, err, steps

    def _magnus(self, eps, omega, N):
        """Sixth-order Magnus integrator over tau in [0, 2 pi] with N steps (module docstring),
        vectorised over the points and over blocks of steps: the exponentials of a block are
        formed at once and multiplied by pairwise (tree) reduction, in step order."""
        P, n2 = eps.size, 2 * self.n
        h = 2 * math.pi / N
        block = max(1, min(N, _CHUNK_ELEMENTS // (P * n2 * n2)))
        Phi = None
        # an unresolved period can overflow: the product becomes non-finite, which monodromy() reports
        with single_threaded_blas(), np.errstate(over="ignore", invalid="ignore"):
            for k0 in range(0, N, block):
                ks = np.arange(k0, min(N, k0 + block))
                A1, A2, A3 = (self.state_matrices((ks + c) * h, eps, omega) for c in _NODES)
                a1 = h * A2
                a2 = (_S15 * h / 3.0) * (A3 - A1)
                a3 = (10.0 * h / 3.0) * (A3 - 2.0 * A2 + A1)
                del A1, A2, A3
                C1 = _comm(a1, a2)
                C2 = -_comm(a1, 2.0 * a3 + C1) / 60.0
                X = a1 + a3 / 12.0 + _comm(-20.0 * a1 - a3 + C1, a2 + C2) / 240.0
                E = _expm_batch(X.reshape(-1, n2, n2)).reshape(X.shape)
                while E.shape[0] > 1:                       # E[k] acts after E[k-1]
                    odd = E.shape[0] % 2
                    pairs = E[1::2] @ E[0:E.shape[0] - odd:2]
                    E = np.concatenate([pairs, E[-1:]]) if odd else pairs
                Phi = E[0] if Phi is None else E[0] @ Phi
        return Phi

    # ....................................................... single points
    def floquet(self, omega: float, depth: float, *, tolerance: float = 1e-10,
                stability_margin: float = 1e-6) -> FloquetResult:
        Om = _positive(omega, "omega", unit="rad/s")
        eps = self.check_depth(depth)
        Phi, err, steps = self.monodromy(eps, Om, tolerance=tolerance)
        mult = np.linalg.eigvals(Phi[0])
        rho = float(np.max(np.abs(mult)))
        ref = float(self.trace_integral(np.array([eps]), np.array([Om]))[0])
        res = abs(np.linalg.slogdet(Phi[0])[1] - ref)
        return FloquetResult(omega_rad_s=Om, depth=eps, period_s=2 * math.pi / Om, multipliers=mult,
                             monodromy=Phi[0], rho_max=rho, stable=bool(rho < 1 + stability_margin),
                             error_estimate=float(err[0]), converged=bool(err[0] <= tolerance),
                             liouville_residual=float(res), liouville_reference=ref, n_steps=int(steps[0]),
                             stability_margin=stability_margin)

    def indicators(self, eps, omega, tolerance=1e-10):
        """(rho_max, det(Phi + I), det(Phi - I)) for a batch; the determinants are positive where
        stable and change sign where a real multiplier crosses -1 or +1."""
        Phi, _, _ = self.monodromy(eps, omega, tolerance=tolerance)
        I = np.eye(Phi.shape[-1])
        rho = np.abs(np.linalg.eigvals(Phi)).max(axis=-1)
        return rho, np.linalg.det(Phi + I), np.linalg.det(Phi - I)


class UnresolvedMonodromy(SolverError):
    """The monodromy at (``eps``, ``omega``) overflowed: one period cannot be resolved within the step limit."""

    def __init__(self, eps: float, omega: float, message: str):
        super().__init__(message)
        self.eps, self.omega = eps, omega


def _rigid_error(count):
    raise ModelError(WHERE, "supports", f"{count} rigid-body mode(s)",
                     "a system without rigid-body modes: hold a driver or ground the chain (parametric "
                     "resonance is studied in the deformations about the programme motion, (7.4))")


def _comm(a, b):
    return a @ b - b @ a


def _expm_batch(X: np.ndarray) -> np.ndarray:
    """exp of a batch of matrices.  2 x 2: the Cayley-Hamilton closed form
    exp(X) = e^m [c(r) I + s(r) (X - m I)], m = tr X / 2, r = sqrt(|det(X - m I)|), c, s = cosh,
    sinh(r)/r or cos, sin(r)/r; used while r <= 2 (the cancellation in c + s (a - m) then costs at
    most a factor e^4 of round-off); other 2 x 2 exponents and larger matrices:
    :func:`discrete.linalg.expm_batch`."""
    if X.shape[-1] != 2:
        return expm_batch(X)
    a, b, c, d = X[:, 0, 0], X[:, 0, 1], X[:, 1, 0], X[:, 1, 1]
    m = 0.5 * (a + d)
    s2 = 0.25 * (a - d) ** 2 + b * c
    r = np.sqrt(np.abs(s2))
    with np.errstate(over="ignore", invalid="ignore"):      # r > 2 is replaced below
        ch = np.where(s2 >= 0, np.cosh(r), np.cos(r))
        safe = np.where(r == 0, 1.0, r)
        sh = np.where(r < 1e-4, 1.0 + s2 / 6.0 + s2 * s2 / 120.0, np.where(s2 >= 0, np.sinh(r), np.sin(r)) / safe)
        em = np.exp(m)
    E = np.empty_like(X)
    E[:, 0, 0] = em * (ch + sh * (a - m))
    E[:, 1, 1] = em * (ch + sh * (d - m))
    E[:, 0, 1] = em * sh * b
    E[:, 1, 0] = em * sh * c
    big = r > 2.0
    if np.any(big):
        E[big] = expm_batch(X[big])
    return E


# ------------------------------------------------------------------------ public API
def _problem(system, modulations, damping, inertia_form, modes) -> ParametricProblem:
    if isinstance(system, ParametricProblem):
        return system
    return ParametricProblem.build(system, modulations, damping=damping, inertia_form=inertia_form, modes=modes)


def _tolerances(tolerance, stability_margin):
    tol = _positive(tolerance, "tolerance")
    margin = _positive(stability_margin, "stability_margin")
    if tol > 1e-4:
        raise ModelError(WHERE, "tolerance", tolerance, "a number in (0, 1e-4] (relative monodromy error)")
    if margin > 1e-2:
        raise ModelError(WHERE, "stability_margin", stability_margin, "a number in (0, 1e-2]")
    return tol, margin


def floquet(system, modulations=None, *, omega: float, depth: float = 1.0, damping: Damping | None = None,
            inertia_form: str = "programme", modes: int | None = None, tolerance: float = 1e-10,
            stability_margin: float = 1e-6) -> FloquetResult:
    """Floquet multipliers at one point.

    ``system``: a LinearSystem (or a prepared :class:`ParametricProblem`); ``modulations``: list
    of :class:`Modulation`; ``omega``: excitation frequency Omega in rad/s (> 0); ``depth``: eps
    (dimensionless, 0 <= eps < depth limit); ``tolerance``: relative monodromy error target;
    ``stability_margin``: stable if max|rho| < 1 + margin.
    """
    prob = _problem(system, modulations, damping, inertia_form, modes)
    tol, margin = _tolerances(tolerance, stability_margin)
    return prob.floquet(omega, depth, tolerance=tol, stability_margin=margin)


def _omega_range(omega_min, omega_max, n_omega, key_n="n_omega"):
    lo = _positive(omega_min, "omega_min", unit="rad/s")
    hi = _positive(omega_max, "omega_max", unit="rad/s")
    if not hi > lo:
        raise ModelError(WHERE, "omega_max", omega_max, f"a number > omega_min = {lo:g} rad/s")
    return lo, hi, _count(n_omega, key_n, 2)


def tongue_boundaries(system, modulations=None, *, depth: float, omega_min: float, omega_max: float,
                      n_omega: int = 401, damping: Damping | None = None, inertia_form: str = "programme",
                      modes: int | None = None, tolerance: float = 1e-10,
                      stability_margin: float = 1e-6) -> TongueBoundaries:
    """Edges of the instability intervals along Omega (rad/s) at depth eps, by root finding.

    The indicators are sampled at ``n_omega`` points; every sign change is refined by Brent's
    method, and every local minimum of a positive det(Phi +- I) is searched for a thin tongue
    that falls between samples (the higher tongues are O(eps^s) wide).  Complex crossings
    (combination resonances) are found only where a sample falls inside them."""
    prob = _problem(system, modulations, damping, inertia_form, modes)
    tol, margin = _tolerances(tolerance, stability_margin)
    eps = prob.check_depth(depth)
    lo, hi, n_omega = _omega_range(omega_min, omega_max, n_omega)
    return _boundaries(prob, eps, lo, hi, n_omega, tol, margin)


def _boundaries(prob: ParametricProblem, eps, lo, hi, n, tol, margin) -> TongueBoundaries:
    prob.worst_error = 0.0
    om = np.linspace(lo, hi, n)
    rho, dm, dp = prob.indicators(np.full(n, eps), om, tol)
    unstable = rho >= 1 + margin

    def at(w, k):
        return prob.indicators(np.array([eps]), np.array([w]), tol)[k][0]

    def f_minus(w):
        return at(w, 1)

    def f_plus(w):
        return at(w, 2)

    def f_rho(w):
        return at(w, 0) - 1 - margin

    def root(fun, a, b):
        return so.brentq(fun, a, b, xtol=1e-13 * hi, rtol=1e-15)

    edges = set()
    for vals, fun in ((dm, f_minus), (dp, f_plus)):
        s = np.sign(vals)
        for i in np.flatnonzero(s[:-1] * s[1:] < 0):
            edges.add(root(fun, om[i], om[i + 1]))
        # thin tongues between samples: local minima of a positive indicator
        for i in range(1, n - 1):
            if 0 < vals[i] <= vals[i - 1] and vals[i] <= vals[i + 1]:
                r = so.minimize_scalar(fun, bounds=(om[i - 1], om[i + 1]), method="bounded",
                                       options={"xatol": 1e-12 * hi})
                if r.fun < 0:
                    edges.add(root(fun, om[i - 1], r.x))
                    edges.add(root(fun, r.x, om[i + 1]))
    # complex crossings not explained by a real multiplier
    for i in np.flatnonzero(unstable[:-1] != unstable[1:]):
        if not any(om[i] <= e <= om[i + 1] for e in edges):
            edges.add(root(f_rho, om[i], om[i + 1]))
    pts = [lo] + sorted(e for e in edges if lo < e < hi) + [hi]
    lows, highs, kinds, centres, clipped = [], [], [], [], []
    for a, b in zip(pts[:-1], pts[1:]):
        if b - a <= 1e-15 * hi:
            continue
        r, m_, p_ = prob.indicators(np.array([eps]), np.array([0.5 * (a + b)]), tol)
        if r[0] < 1 + margin:
            continue
        kind = "-1" if m_[0] < 0 else ("+1" if p_[0] < 0 else "complex")
        if highs and highs[-1] == a and kinds[-1] == kind:
            highs[-1] = b                      # one interval split by an edge of another indicator
            clipped[-1] = "high" if b == hi else clipped[-1]
            continue
        lows.append(a)
        highs.append(b)
        kinds.append(kind)
        centres.append(_nearest_centre(prob.omega_modes, 0.5 * (a + b)))
        clipped.append("low" if a == lo else ("high" if b == hi else ""))
    return TongueBoundaries(depth=eps, omega_low_rad_s=np.array(lows), omega_high_rad_s=np.array(highs),
                            crossing=kinds, centre=centres, clipped=clipped, omega_range_rad_s=(lo, hi),
                            n_samples=n, max_error_estimate=prob.worst_error)


def predicted_centres(omega_modes, omega_min, omega_max, s_max: int = 6) -> list[dict]:
    """Centres of the tongues (7.26): Omega = 2 w_r / s (principal for s = 1) and the combination
    resonances Omega = (w_r + w_q) / s, inside [omega_min, omega_max] (rad/s)."""
    out = []
    w = np.asarray(omega_modes, dtype=float)
    for r in range(w.size):
        for q in range(r, w.size):
            for s in range(1, s_max + 1):
                val = (w[r] + w[q]) / s
                if omega_min <= val <= omega_max:
                    lab = f"2 w{r + 1}/{s}" if q == r else f"(w{r + 1}+w{q + 1})/{s}"
                    out.append({"label": lab, "omega_rad_s": float(val), "mode": r + 1, "mode_2": q + 1, "s": s})
    return sorted(out, key=lambda d: d["omega_rad_s"])


def _nearest_centre(omega_modes, w) -> str:
    c = predicted_centres(omega_modes, 0.0, np.inf, s_max=12)
    k = int(np.argmin([abs(d["omega_rad_s"] - w) for d in c]))
    return c[k]["label"]


def damping_threshold(system, modulations=None, *, mode: int = 1, damping: Damping | None = None,
                      inertia_form: str = "programme", modes: int | None = None, tolerance: float = 1e-10,
                      stability_margin: float = 1e-6, search_minimum: bool = True) -> DampingThreshold:
    """Smallest depth eps* that destabilises the principal tongue of ``mode`` (1-based): at
    Omega = 2 omega_r (the book's (7.28) eps* = psi/pi for one DOF) and, with ``search_minimum``,
    at the tongue tip (min over Omega; slightly below 2 omega_r with damping)."""
    prob = _problem(system, modulations, damping, inertia_form, modes)
    tol, margin = _tolerances(tolerance, stability_margin)
    r = _count(mode, "mode", 1)
    if r > prob.omega_modes.size:
        raise ModelError(WHERE, "mode", mode, f"an integer from 1 to {prob.omega_modes.size}")
    return _threshold(prob, r, tol, search_minimum)


def _critical_depth(prob: ParametricProblem, w, tol, guess: float | None = None) -> float:
    """Lowest eps (first crossing found by doubling from 1e-3) at which max|rho| reaches 1 at
    Omega = w; nan if none below the depth limit.  ``guess``: a nearby threshold (tip search),
    tried first as a +-2 % bracket."""
    top = min(prob.depth_limit * (1 - 1e-9), 1e6)

    def g(e):
        Phi, _, _ = prob.monodromy(e, w, tolerance=tol)
        return float(np.abs(np.linalg.eigvals(Phi[0])).max()) - 1.0

    if guess is not None and math.isfinite(guess) and 0 < 1.02 * guess < top:
        a, b = 0.98 * guess, 1.02 * guess
        if g(a) < 0 <= g(b):
            return so.brentq(g, a, b, xtol=1e-14, rtol=1e-12)
    if g(0.0) >= 0:
        return 0.0
    e_prev, e = 0.0, min(top, 1e-3)
    while True:
        if g(e) >= 0:
            return so.brentq(g, e_prev, e, xtol=1e-14, rtol=1e-12)
        if e >= top:
            return math.nan
        e_prev, e = e, min(top, 2 * e)


def _critical_depths_coarse(prob: ParametricProblem, ws: np.ndarray, tol, rtol: float = 1e-4) -> np.ndarray:
    """Vectorised version of :func:`_critical_depth` to relative accuracy ~rtol (for locating a
    tongue tip): rho on a geometric depth grid for all Omega at once, then batched bisection.
    inf where no instability below the depth limit."""
    top = min(prob.depth_limit * (1 - 1e-9), 1e6)
    levels = 1e-3 * 2.0 ** np.arange(0, 64)
    levels = np.append(levels[levels < top], top)
    E, W = np.meshgrid(levels, ws, indexing="ij")
    rho, _, _ = prob.indicators(E.ravel(), W.ravel(), tol)
    unstable = (rho.reshape(E.shape) >= 1.0)
    found = unstable.any(axis=0)
    k = np.argmax(unstable, axis=0)
    hi = np.where(found, levels[k], np.inf)
    lo = np.where(found & (k > 0), levels[np.maximum(k - 1, 0)], 0.0)
    idx = np.flatnonzero(found)
    while idx.size and np.max((hi[idx] - lo[idx]) / hi[idx]) > rtol:
        mid = 0.5 * (lo[idx] + hi[idx])
        up = prob.indicators(mid, ws[idx], tol)[0] >= 1.0
        hi[idx[up]] = mid[up]
        lo[idx[~up]] = mid[~up]
    return hi


def _threshold(prob: ParametricProblem, r, tol, search_minimum) -> DampingThreshold:
    w_r = float(prob.omega_modes[r - 1])
    zeta = float(prob.zeta_modes[r - 1])
    kap = float(prob.kappa[r - 1])
    est = 4 * zeta / kap if math.isfinite(kap) and kap > 0 else math.nan
    centre = 2 * w_r
    prob.worst_error = 0.0
    try:
        e_c = _critical_depth(prob, centre, tol)
    except UnresolvedMonodromy as exc:      # the depth search reached depths the integrator cannot resolve
        return DampingThreshold(mode=r, natural_omega_rad_s=w_r, omega_centre_rad_s=centre, depth_at_centre=math.nan,
                                omega_at_minimum_rad_s=centre, depth_minimum=math.nan, zeta=zeta, energy_estimate=est,
                                max_error_estimate=prob.worst_error,
                                note=f"not determined: stable up to the depths tried, and at eps = {exc.eps:.4g} "
                                     f"(Omega = 2 omega_{r}) the monodromy overflows (one period not resolved within "
                                     f"{_MAX_STEPS} steps)")
    note = ""
    w_min, e_min = centre, e_c
    if e_c == 0.0:
        note = "undamped: the tongue reaches eps = 0 at its centre"
    elif not math.isfinite(e_c):
        note = f"no instability below the depth limit {prob.depth_limit:.6g} at Omega = 2 omega_{r}"
    elif search_minimum:
        # search 2 w_r +- w_r/4, but stay closer to this centre than to any other (s <= 2) centre
        others = [abs(c["omega_rad_s"] - centre) for c in predicted_centres(prob.omega_modes, 0.0, np.inf, s_max=2)
                  if c["label"] != f"2 w{r}/1"]
        half = min([0.25 * w_r] + [0.5 * d for d in others if d > 0])
        last = [e_c]

        def depth_at(w):                     # bracket each root from the previous one
            v = _critical_depth(prob, w, tol, guess=last[0])
            last[0] = v if math.isfinite(v) else last[0]
            return v

        # coarse scan, then Brent around the best sample (the tip can be much sharper than the window)
        grid = centre + half * np.linspace(-1.0, 1.0, 17)
        try:
            vals = _critical_depths_coarse(prob, grid, tol)
            k = int(np.argmin(vals))
            step = grid[1] - grid[0]
            res = so.minimize_scalar(depth_at, bounds=(grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]),
                                     method="bounded", options={"xatol": 1e-9 * centre})
        except UnresolvedMonodromy as exc:
            note = (f"tongue tip not searched: at eps = {exc.eps:.4g}, Omega = {exc.omega:.6g} rad/s the monodromy "
                    f"overflows (one period not resolved within {_MAX_STEPS} steps); the centre value stands")
        else:
            cand = [(vals[k], grid[k])] + ([(res.fun, res.x)] if math.isfinite(res.fun) else [])
            e_min, w_min = min(cand)
            e_min, w_min = float(e_min), float(w_min)
            if e_min > e_c:
                e_min, w_min = e_c, centre
            if k in (0, grid.size - 1) and abs(abs(w_min - centre) - half) < step:
                note = (f"tongue tip at the edge of the search window 2 omega_r +- {half:.4g} rad/s: "
                        "minimum not bracketed")
    return DampingThreshold(mode=r, natural_omega_rad_s=w_r, omega_centre_rad_s=centre, depth_at_centre=e_c,
                            omega_at_minimum_rad_s=w_min, depth_minimum=e_min, zeta=zeta, energy_estimate=est,
                            max_error_estimate=prob.worst_error, note=note)


def stability_chart(system, modulations=None, *, omega_min: float, omega_max: float, n_omega: int = 161,
                    depth_max: float, depth_min: float = 0.0, n_depth: int = 41, damping: Damping | None = None,
                    inertia_form: str = "programme", modes: int | None = None, boundaries_at=(),
                    boundary_samples: int = 401, thresholds: bool = True, tolerance: float = 1e-10,
                    stability_margin: float = 1e-6, progress=None) -> StabilityChart:
    """Scan of the (eps, Omega) plane: max |multiplier| on an n_depth x n_omega grid.

    ``omega_min``, ``omega_max``: rad/s (0 < min < max); ``n_omega`` >= 2; ``depth_min``,
    ``depth_max``: eps (0 <= min <= max < depth limit); ``n_depth`` >= 1; ``boundaries_at``: depths at
    which tongue edges are located by root finding (``boundary_samples`` Omega samples each);
    ``thresholds``: damping thresholds of the principal tongues whose centre 2 omega_r lies in the
    Omega range; ``progress``: called as ``progress(done, total)`` in steps of the work (grid
    points, then each boundary's samples and each threshold; reporting only, the results do not
    depend on it).  Other arguments as in :func:`floquet`.
    """
    prob = _problem(system, modulations, damping, inertia_form, modes)
    tol, margin = _tolerances(tolerance, stability_margin)
    lo, hi, n_omega = _omega_range(omega_min, omega_max, n_omega)
    n_depth = _count(n_depth, "n_depth", 1)
    samples = _count(boundary_samples, "boundary_samples", 2)
    dmin = prob.check_depth(depth_min, "depth_min")
    dmax = prob.check_depth(depth_max, "depth_max")
    if dmax < dmin:
        raise ModelError(WHERE, "depth_max", depth_max, f"a number >= depth_min = {dmin:g}")
    if n_depth > 1 and dmax == dmin:
        raise ModelError(WHERE, "n_depth", n_depth, "1 when depth_min == depth_max")
    if isinstance(boundaries_at, (int, float)) and not isinstance(boundaries_at, bool):
        boundaries_at = [boundaries_at]
    bdepths = [prob.check_depth(d, f"boundaries_at[{i}]") for i, d in enumerate(list(boundaries_at))]
    depth = np.linspace(dmin, dmax, n_depth) if n_depth > 1 else np.array([dmin])
    om = np.linspace(lo, hi, n_omega)
    E, W = np.meshgrid(depth, om, indexing="ij")
    n_thr = sum(1 for r in range(prob.omega_modes.size) if lo <= 2 * prob.omega_modes[r] <= hi) if thresholds else 0
    total = E.size + samples * len(bdepths) + samples * n_thr
    done = [0]

    def advance(k: int) -> None:
        if progress is not None:
            done[0] += k
            progress(done[0], total)

    Phi, err, _ = prob.monodromy(E.ravel(), W.ravel(), tolerance=tol, progress=advance)
    rho = np.abs(np.linalg.eigvals(Phi)).max(axis=-1).reshape(E.shape)
    ref = prob.trace_integral(E.ravel(), W.ravel())
    liou = np.abs(np.linalg.slogdet(Phi)[1] - ref).reshape(E.shape)
    err = err.reshape(E.shape)
    warnings = []
    if np.any(err > tol):
        warnings.append(f"{int(np.sum(err > tol))} grid points did not reach the tolerance {tol:g} "
                        f"(max estimate {err.max():.3g}: round-off floor or step limit {_MAX_STEPS})")
    ths = []
    if thresholds:
        for r in range(1, prob.omega_modes.size + 1):
            if lo <= 2 * prob.omega_modes[r - 1] <= hi:
                ths.append(_threshold(prob, r, tol, True))
                advance(samples)
    bnds = []
    for d in bdepths:
        bnds.append(_boundaries(prob, d, lo, hi, samples, tol, margin))
        advance(samples)
    return StabilityChart(depth=depth, omega_rad_s=om, rho_max=rho, stable=rho < 1 + margin,
                          growth_rate=np.log(rho) * W / (2 * math.pi), error_estimate=err, liouville_residual=liou,
                          natural_omega_rad_s=prob.omega_modes.copy(),
                          centres=predicted_centres(prob.omega_modes, lo, hi),
                          thresholds=ths, boundaries=bnds, damping=prob.damping, inertia_form=prob.form,
                          modulations=list(prob.modulation_labels), depth_limit=prob.depth_limit,
                          stability_margin=margin, tolerance=tol, n_dofs=prob.n, projected=prob.projected,
                          warnings=warnings)
