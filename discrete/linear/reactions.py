"""Element forces and constraint reactions of a harmonic response (textbook §6.4-6.6: transmitted
forces, support and driver reactions).

* Constraint reactions, for any :class:`LinearSystem`: with D(omega) = K + i H - omega^2 M + i omega C
  (the same damping options as :func:`discrete.linear.harmonic.harmonic_response`), the equations of
  all DOFs read D Q = F + R, where R is non-zero only at constrained DOFs (supports, drivers):
  R_b = (D Q)_b - F_b is the force (torque) the support or driver exerts on the system.  The force on
  the support/foundation is -R_b.
* Element forces: a linear link with deformation s = g . q (e.g. r_b x_b - r_a x_a of a lumped spring or
  damper) carries the complex force P = (k + i h + i omega c) s (tension positive; h = 2 delta k is the
  hysteretic loss stiffness, delta = psi/(4 pi)).  It pushes its end a along +r_a P and its end b along
  -r_b P; a link with an end on the fixed frame transmits ``ground_factor`` * P to it.  Sign: P is the
  tension -- the convention of the section loads of FE shafts (N = E A u', T = G J theta': the b side
  acting on the a side); the named outputs of a model file report an element's force on its end b,
  F = -P (docs/outputs.md, "Sign conventions").
  :func:`lumped_links` builds the links of a :class:`discrete.lumped.LumpedModel`.

Amplitudes are complex with the convention of :mod:`discrete.linear.harmonic`: x(t) = Re(X e^{i omega t}).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..errors import ModelError
from ..linear_system import LinearSystem
from .harmonic import Damping, HarmonicResult

WHERE = "reactions"


def dynamic_stiffness(system: LinearSystem, omega: float, damping: Damping | None = None) -> sp.csr_matrix:
    """D(omega) = K + i H - omega^2 M + i omega C with the damping option applied as in harmonic_response."""
    damping = damping or Damping()
    C, H = system.C, system.H
    if damping.type == "rayleigh":
        C = C + damping.alpha * system.M + damping.beta * system.K
    elif damping.type == "hysteretic":
        H = H + 2 * damping.delta * system.K
    elif damping.type == "none":
        C, H = C * 0, H * 0
    elif damping.type == "modal":
        raise ModelError("[damping]", "type", "modal", "viscous | rayleigh | hysteretic | none (modal damping has no "
                         "matrix form, so reactions cannot be recovered from it)")
    return (system.K + 1j * H - omega**2 * system.M + 1j * omega * C).tocsr()


@dataclass
class Reactions:
    omega_rad_s: np.ndarray
    values: np.ndarray          # (n_freq, n_constrained) complex: force of the support/driver on the system
    labels: list[str]
    equilibrium_residual: float  # max over frequencies of |(D Q - F)_free| / (|D| |Q| + |F|)

    @property
    def amplitude(self) -> np.ndarray:
        return np.abs(self.values)

    def to_dict(self) -> dict:
        return {"omega_rad_s": self.omega_rad_s.tolist(), "labels": list(self.labels),
                "amplitude": self.amplitude.T.tolist(), "real": self.values.real.T.tolist(),
                "imag": self.values.imag.T.tolist(), "equilibrium_residual": self.equilibrium_residual}


def _full_response(system: LinearSystem, Q) -> np.ndarray:
    Q = np.asarray(Q, dtype=complex)
    if Q.ndim == 1:
        Q = Q[None, :]
    if Q.ndim != 2 or Q.shape[1] != system.n_dofs:
        raise ModelError(WHERE, "response", list(np.shape(Q)), f"complex amplitudes of all {system.n_dofs} DOFs "
                         "(shape (n_frequencies, n_dofs))")
    return Q


def constraint_reactions(system: LinearSystem, omegas, Q, *, force=None, damping: Damping | None = None) -> Reactions:
    """R_b = (D Q)_b - F_b at every constrained DOF, for the responses Q (n_freq, n_dofs) at ``omegas``.

    Also reports the equilibrium residual of the free rows (a check that Q solves the same system)."""
    omegas = np.atleast_1d(np.asarray(omegas, dtype=float))
    Q = _full_response(system, Q)
    if Q.shape[0] != omegas.size:
        raise ModelError(WHERE, "omegas", omegas.size, f"one frequency per response row ({Q.shape[0]})")
    F = np.zeros(system.n_dofs, dtype=complex) if force is None else np.asarray(force, dtype=complex)
    if F.shape != (system.n_dofs,):
        raise ModelError(WHERE, "force", list(F.shape), f"a vector of {system.n_dofs} entries")
    b, f = system.constrained, system.free
    R = np.zeros((omegas.size, b.size), dtype=complex)
    res = 0.0
    for j, w in enumerate(omegas):
        D = dynamic_stiffness(system, w, damping)
        DQ = D @ Q[j]
        R[j] = DQ[b] - F[b]
        scale = abs(D).max() * np.max(np.abs(Q[j]), initial=0.0) + np.max(np.abs(F), initial=0.0)
        if f.size and scale > 0:
            res = max(res, float(np.max(np.abs(DQ[f] - F[f])) / scale))
    return Reactions(omega_rad_s=omegas, values=R, labels=[system.label(int(i)) for i in b], equilibrium_residual=res)


def reactions_from_result(system: LinearSystem, result: HarmonicResult, *, force=None,
                          damping: Damping | None = None) -> Reactions:
    """Reactions for a :class:`HarmonicResult` computed with outputs = all DOFs (the default) and the
    same ``force`` and ``damping``."""
    if list(result.outputs) != system.labels():
        raise ModelError(WHERE, "outputs", list(result.outputs)[:4], "a harmonic result with every DOF as an output "
                         "(call harmonic_response with outputs=None)")
    return constraint_reactions(system, result.omega_rad_s, result.response, force=force, damping=damping)


# ---------------------------------------------------------------- elements
@dataclass
class LinkElement:
    """A linear link acting on s = g . q with force (k + i h + i omega c) s."""

    name: str
    g: np.ndarray
    k: float = 0.0
    c: float = 0.0
    h: float = 0.0
    ground_factor: float = 0.0     # force on the fixed frame = ground_factor * P (0: not grounded)

    def __post_init__(self):
        self.g = np.asarray(self.g, dtype=float)
        for key in ("k", "c", "h"):
            v = getattr(self, key)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.floating)) or not (math.isfinite(v) and v >= 0):
                raise ModelError(f"link {self.name!r}", key, v, "a finite number >= 0")


@dataclass
class ElementForces:
    omega_rad_s: np.ndarray
    values: np.ndarray            # (n_freq, n_links) complex force amplitudes (tension positive)
    names: list[str]
    foundation: np.ndarray        # (n_freq,) complex total force on the fixed frame from grounded links

    @property
    def amplitude(self) -> np.ndarray:
        return np.abs(self.values)

    def to_dict(self) -> dict:
        return {"omega_rad_s": self.omega_rad_s.tolist(), "names": list(self.names),
                "amplitude": self.amplitude.T.tolist(), "real": self.values.real.T.tolist(),
                "imag": self.values.imag.T.tolist(), "foundation_amplitude": np.abs(self.foundation).tolist()}


def element_forces(links: list[LinkElement], omegas, Q) -> ElementForces:
    """Complex force of every link for the responses Q (n_freq, n_dofs) at ``omegas``."""
    omegas = np.atleast_1d(np.asarray(omegas, dtype=float))
    Q = np.asarray(Q, dtype=complex)
    if Q.ndim == 1:
        Q = Q[None, :]
    if not links:
        raise ModelError(WHERE, "links", [], "at least one link element")
    G = np.array([ln.g for ln in links])
    if Q.ndim != 2 or Q.shape[0] != omegas.size or G.shape[1] != Q.shape[1]:
        raise ModelError(WHERE, "response", list(np.shape(Q)),
                         f"shape ({omegas.size}, {G.shape[1]}): one row per frequency, one column per DOF")
    s = Q @ G.T
    k = np.array([ln.k for ln in links])
    c = np.array([ln.c for ln in links])
    h = np.array([ln.h for ln in links])
    P = s * (k + 1j * h + 1j * np.multiply.outer(omegas, c))
    gf = np.array([ln.ground_factor for ln in links])
    return ElementForces(omega_rad_s=omegas, values=P, names=[ln.name for ln in links], foundation=P @ gf)


def lumped_links(model) -> list[LinkElement]:
    """Springs (k, hysteretic h = 2 delta k from psi) and dampers (c) of a
    :class:`discrete.lumped.LumpedModel`, in the coordinates of ``model.linear_system()``."""
    from ..lumped import GROUND

    names = model.names
    idx = {n: i for i, n in enumerate(names)}
    _, T = model.transformation()
    out = []
    for kind, items in (("spring", model.springs), ("damper", model.dampers)):
        for i, ln in enumerate(items, 1):
            g = np.zeros(len(names))
            (a, b), (ra, rb) = ln.between, ln.ratios
            if a != GROUND:
                g[idx[a]] -= ra
            if b != GROUND:
                g[idx[b]] += rb
            gf = ra if a == GROUND else (-rb if b == GROUND else 0.0)
            name = f"{kind} {i} ({a}-{b})"
            if kind == "spring":
                out.append(LinkElement(name, g @ T, k=ln.value, h=ln.value * 2 * ln.psi / (4 * math.pi), ground_factor=gf))
            else:
                out.append(LinkElement(name, g @ T, c=ln.value, ground_factor=gf))
    return out
