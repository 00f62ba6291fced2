"""The state a section load is recovered from: static, harmonic, modal or a time history.

Every case becomes three arrays (n_dofs, n_t) -- displacements q, velocities q', accelerations
q'' -- and the factor of the loss stiffness H:

* static: q (q' = q'' = 0);
* harmonic at omega (complex amplitudes, q(t) = Re(Q e^{i omega t})): q' = i omega Q,
  q'' = -omega^2 Q, and the loss stiffness enters as i H Q (complex stiffness, delta = psi/(4 pi));
* modal, a mode q = phi e^{lambda t} (``eigenvalue`` lambda; lambda = i omega_n for an undamped
  mode): q' = lambda phi, q'' = lambda^2 phi (no loss stiffness: the modes do not see H);
* time history: q, q', q'' as given (H has no time-domain meaning; its viscous equivalent is part
  of the damping, see :class:`ElementDamping`).

``omega`` and ``eigenvalue`` may be one number or one per column of q.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from discrete.errors import ModelError

WHERE = "section loads"


@dataclass
class Motion:
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    loss: complex                 # factor of H q: 1j (harmonic) or 0
    kind: str                     # static | harmonic | modal | time
    single: bool                  # q was one vector: results are (n_x,) not (n_x, 1)
    parameter: np.ndarray | None  # omega (harmonic) or eigenvalue (modal) per column


def _columns(name: str, a, n: int) -> np.ndarray:
    try:
        arr = np.asarray(a)
    except (TypeError, ValueError):
        arr = np.asarray(None, dtype=object)
    if arr.dtype.kind not in "iufc" or arr.ndim not in (1, 2) or arr.shape[0] != n:
        raise ModelError(WHERE, name, f"<{arr.dtype} array of shape {arr.shape}>" if arr.dtype.kind != "O"
                         else type(a).__name__, f"a real or complex array of shape ({n},) or ({n}, n_t): one row "
                         "per DOF of the model")
    if not np.all(np.isfinite(arr)):
        raise ModelError(WHERE, name, "NaN/inf entries", "finite numbers")
    arr = arr.astype(complex if arr.dtype.kind == "c" else float)
    return arr[:, None] if arr.ndim == 1 else arr


def _per_column(name: str, value, t: int, *, complex_ok: bool) -> np.ndarray:
    arr = np.atleast_1d(np.asarray(value))
    if arr.dtype.kind not in ("iufc" if complex_ok else "iuf") or arr.ndim != 1 or arr.size not in (1, t) \
            or not np.all(np.isfinite(arr)):
        raise ModelError(WHERE, name, value, f"one finite {'(complex) ' if complex_ok else ''}number or one per "
                         f"column of q ({t})")
    return np.broadcast_to(arr, (t,)).astype(complex if arr.dtype.kind == "c" else float)


def motion(n: int, q, qd=None, qdd=None, omega=None, eigenvalue=None) -> Motion:
    """The :class:`Motion` of the module notes for a model with ``n`` DOFs."""
    Q = _columns("q", q, n)
    single = np.ndim(q) == 1
    t = Q.shape[1]
    if omega is not None and eigenvalue is not None:
        raise ModelError(WHERE, "eigenvalue", eigenvalue, "either omega (harmonic) or eigenvalue (a mode), not both")
    if (omega is not None or eigenvalue is not None) and (qd is not None or qdd is not None):
        raise ModelError(WHERE, "qd", "given", "no qd/qdd with omega or eigenvalue (they follow from q)")
    if omega is not None:
        w = _per_column("omega", omega, t, complex_ok=False)
        if np.any(w < 0):
            raise ModelError(WHERE, "omega", omega, "angular frequencies >= 0 (rad/s)")
        Q = Q.astype(complex)
        return Motion(Q, 1j * w * Q, -(w**2) * Q, 1j, "harmonic", single, w)
    if eigenvalue is not None:
        lam = _per_column("eigenvalue", eigenvalue, t, complex_ok=True).astype(complex)
        Q = Q.astype(complex)
        return Motion(Q, lam * Q, lam**2 * Q, 0.0, "modal", single, lam)
    Qd = np.zeros_like(Q) if qd is None else _columns("qd", qd, n)
    Qdd = np.zeros_like(Q) if qdd is None else _columns("qdd", qdd, n)
    if Qd.shape != Q.shape or Qdd.shape != Q.shape:
        raise ModelError(WHERE, "qd", f"shapes {Qd.shape}, {Qdd.shape}", f"the shape of q {Q.shape}")
    kind = "static" if qd is None and qdd is None else "time"
    return Motion(Q, Qd, Qdd, 0.0, kind, single, None)


@dataclass
class ElementDamping:
    """The damping inside the elements: Rayleigh C_e = alpha M_e + beta K_e, the material's loss
    stiffness H_e times ``loss_scale`` (0: damping "none") plus ``added_loss`` K_e (global hysteretic
    psi: 2 delta = psi / (2 pi)), and, in the time domain, the equivalent viscous H_e / omega_ref
    (``viscous_loss_omega``, (9.3)).  ``note``: what is not represented (modal damping)."""

    alpha: float = 0.0
    beta: float = 0.0
    loss_scale: float = 1.0
    added_loss: float = 0.0
    viscous_loss_omega: float | None = None
    note: str = ""

    @classmethod
    def of(cls, damping=None, *, alpha: float = 0.0, beta: float = 0.0) -> "ElementDamping":
        """From a :class:`discrete.linear.Damping` (the harmonic analysis' option; None: the model's own)."""
        if damping is None:
            return cls(alpha=alpha, beta=beta)
        from discrete.linear import Damping

        if not isinstance(damping, Damping):
            raise ModelError(WHERE, "damping", type(damping).__name__, "a discrete.linear.Damping or None")
        if damping.type == "none":
            return cls(loss_scale=0.0)
        if damping.type == "rayleigh":
            return cls(alpha=damping.alpha, beta=damping.beta)
        if damping.type == "hysteretic":
            return cls(added_loss=2.0 * damping.psi / (4.0 * math.pi))
        if damping.type == "modal":
            return cls(note=f"modal damping (zeta = {damping.zeta:g}) has no element form: the section loads and "
                            "reactions are the elastic and inertia forces; the damping force (at most 2 zeta "
                            "omega/omega_r of the elastic force of mode r) is not in them, and equilibrium holds up to it")
        return cls()
