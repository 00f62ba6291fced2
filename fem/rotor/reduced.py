"""A reduced rotor for transient runs: modes at rest plus static attachment shapes at the contacts.

The basis T holds the lowest ``n_modes`` undamped modes of (K_s, M) at a reference speed (K_s the
symmetric part of the stiffness with the bearings at that speed) and the static responses
K_s^-1 e to unit loads on v and w of every node where a nonlinear element acts (rub, clearance),
M-orthonormalised and diagonalising K_s: T^T M T = I, T^T K_s T = diag(omega^2).  The reduced
equations of motion at the speed Omega are

    eta'' + (C(Omega) + Omega G) eta' + K(Omega) eta = T^T f(t),       q = T eta,

with C, G, K the full matrices projected once (tabulated bearings: one projected matrix per
coefficient, so K(Omega), C(Omega) are exact interpolations of the full ones at every speed).

The basis reports its restitution: the share of the static flexibility at every contact DOF it
restores (1 to round-off with the attachment shapes: the contact's quasi-static response is
exact), and the relative error of the reduced rotor's complex eigenvalues against the full
rotor's at the speeds asked for (:meth:`ReducedRotor.frequency_check`).
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from discrete.errors import ModelError
from discrete.linear.modal import modal_analysis

from .assembly import RotorSystem


@dataclass
class ReducedRotor:
    """The projected rotor: ``T`` (n_dofs x n) full DOFs = T eta; ``omega`` (n,) the basis'
    frequencies at rest (rad/s); ``contact_dofs`` the (v, w) DOF pairs of the attachment shapes;
    ``restitution`` the restored static flexibility per contact DOF; ``warnings``."""

    system: RotorSystem
    basis_system: RotorSystem | None
    T: np.ndarray
    omega: np.ndarray
    n_modes: int
    contact_dofs: np.ndarray
    restitution: np.ndarray
    reference_speed: float
    K0: np.ndarray
    C0: np.ndarray
    G: np.ndarray
    Kc: np.ndarray                 # (n_coef, n, n) projected bearing stiffness maps (tabulated bearings)
    Cc: np.ndarray
    warnings: list = field(default_factory=list)
    _interpolants: list | None = None

    @property
    def n(self) -> int:
        return self.T.shape[1]

    @property
    def basis_stiffness(self) -> np.ndarray:
        """T^T K_s T = diag(omega^2): the stiffness the basis was built on (projected)."""
        return np.diag(self.omega ** 2)

    def rows(self, dofs) -> np.ndarray:
        """Rows of T for full DOF indices: the reduced vectors b with q_j = b . eta."""
        return self.T[np.asarray(dofs, dtype=int)]

    def coefficients(self, speed: float) -> np.ndarray:
        """The tabulated bearings' coefficients at a speed (interpolants built once; the ramp's range
        is checked against the tables before a run)."""
        s = float(speed)
        return np.concatenate([t.values_at(s)[0] for t in self.system.tables])

    def matrices(self, speed: float) -> tuple[np.ndarray, np.ndarray]:
        """(K(Omega), C(Omega) + Omega G) of the reduced rotor."""
        K, C = self.K0, self.C0
        if self.Kc.shape[0]:
            c = self.coefficients(speed)
            K = K + np.tensordot(c, self.Kc, 1)
            C = C + np.tensordot(c, self.Cc, 1)
        return K, C + speed * self.G

    def stiffness_rate(self, speed: float, acceleration: float) -> np.ndarray:
        """dK/dt = dK/dOmega Omega' (tabulated bearings; central difference of the interpolated
        coefficients, exact for linear interpolation away from the table's nodes)."""
        if not self.Kc.shape[0] or acceleration == 0.0:
            return np.zeros_like(self.K0)
        g = self.system.tables[0].grid
        h = 1e-6 * max(abs(speed), float(g[-1] - g[0]))
        strict = [t for t in self.system.tables if t.extrapolate == "refuse"]     # the others extend past their ends
        lo = max([speed - h] + [float(t.grid[0]) for t in strict])
        hi = min([speed + h] + [float(t.grid[-1]) for t in strict])
        dc = (self.coefficients(hi) - self.coefficients(lo)) / (hi - lo)
        return np.tensordot(dc, self.Kc, 1) * acceleration

    def frequency_check(self, speed: float, n_compare: int) -> dict:
        """Complex eigenvalues of the reduced rotor against the full rotor's at ``speed``: the
        lowest ``n_compare`` pairs; relative error |lam_r - lam| / |lam| per mode.  With nonlinear
        bearings (a ``basis_system``), both sides carry their linearised coefficients."""
        from .modal import rotor_modes

        if self.basis_system is not None:
            return _linearised_check(self, speed, n_compare)
        full = rotor_modes(self.system, speed, n_compare)
        K, C = self.matrices(speed)
        n = self.n
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -C]])     # the reduced rotor is small: dense is fine
        lam = sla.eigvals(A)
        lam = lam[lam.imag >= 0]
        err = []
        top = float(np.abs(full.eigenvalues).max(initial=0.0))
        for lf in full.eigenvalues:            # rigid-body modes (lam = 0): relative to the largest compared
            err.append(float(np.min(np.abs(lam - lf)) / max(abs(lf), 1e-8 * top, 1e-300)))
        return {"speed_rad_s": float(speed), "full_eigenvalues_real": full.eigenvalues.real.tolist(),
                "full_eigenvalues_imag": full.eigenvalues.imag.tolist(), "relative_error": err,
                "max_relative_error": float(max(err)) if err else 0.0}

    def report(self) -> dict:
        return {"basis": int(self.n), "modes": int(self.n_modes), "attachment_shapes": int(self.n - self.n_modes),
                "highest_frequency_rad_s": float(self.omega.max()), "reference_speed_rad_s": self.reference_speed,
                "contact_dofs": [f"{self.system.dof_field[j]} at x = {self.system.dof_x[j]:g} m"
                                 for j in self.contact_dofs.ravel()],
                "restitution": [float(r) if np.isfinite(r) else None for r in self.restitution],
                "warnings": list(self.warnings)}


def _linearised_check(red: "ReducedRotor", speed: float, n_compare: int) -> dict:
    """:meth:`ReducedRotor.frequency_check` on the linearised rotor (``basis_system``), at the speed
    clipped into its bearing tables."""
    from .modal import rotor_modes

    bs = red.basis_system
    if bs.tables:
        lo, hi = max(t.grid[0] for t in bs.tables), min(t.grid[-1] for t in bs.tables)
        speed = float(min(max(speed, lo), hi))
    full = rotor_modes(bs, speed, n_compare)
    T = red.T
    K = T.T @ (bs.stiffness(speed) @ T)
    C = T.T @ ((bs.damping(speed) + speed * bs.G) @ T)
    n = red.n
    lam = sla.eigvals(np.block([[np.zeros((n, n)), np.eye(n)], [-K, -C]]))
    lam = lam[lam.imag >= 0]
    top = float(np.abs(full.eigenvalues).max(initial=0.0))
    err = [float(np.min(np.abs(lam - lf)) / max(abs(lf), 1e-8 * top, 1e-300)) for lf in full.eigenvalues]
    return {"speed_rad_s": float(speed), "linearised_bearings": True,
            "full_eigenvalues_real": full.eigenvalues.real.tolist(),
            "full_eigenvalues_imag": full.eigenvalues.imag.tolist(), "relative_error": err,
            "max_relative_error": float(max(err)) if err else 0.0}


def _symmetric(A: sp.spmatrix) -> sp.csr_matrix:
    return (0.5 * (A + A.T)).tocsr()


def _nonsingular(Kff, lu) -> bool:
    """Whether the free stiffness is nonsingular (a supported rotor; the symmetric part of a
    physical stiffness is then positive definite): no LU pivot below 1e-12 of the largest K_ii."""
    return bool(np.all(np.abs(lu.U.diagonal()) > 1e-12 * np.abs(Kff.diagonal()).max()))


def _require_definite(Kff) -> None:
    """A nonsingular free stiffness must also be positive definite for the basis by flexibility
    (Sylvester's inertia of its LDL^T, :func:`discrete.linear.modal._negative_count`): a bearing or
    seal with a negative direct stiffness can leave the rotor statically unstable, which the linear
    analyses report (negative w^2, growing modes) but a run-up's reduction cannot start from."""
    from discrete.linear.modal import _negative_count

    negative = _negative_count(Kff, definite=True)
    if negative is None and Kff.shape[0] <= 600:
        try:
            sla.cholesky(Kff.toarray())
            negative = 0
        except sla.LinAlgError:
            negative = 1
    if negative:
        raise ModelError("[rotor]", "stiffness at rest (bearings, seals, supports)", f"{negative} negative "
                         "direction(s)", "a rotor its bearings hold: the symmetric part of the stiffness positive "
                         "definite for a transient run (a negative direct stiffness such as kyy < 0 leaves the "
                         "rotor statically unstable; modal, campbell and stability accept it)")


def _modes_by_flexibility(Kff, Mff, lu, k: int) -> tuple[np.ndarray, np.ndarray]:
    """The lowest k modes of K phi = w^2 M phi as the largest mu = 1/w^2 of M phi = mu K phi: K is
    positive definite, M may be singular (massless shaft nodes have no finite mode and are never
    asked for).  Dense below 600 DOFs, else Lanczos in the K inner product (K factorised once)."""
    n = Kff.shape[0]
    if n <= 600:
        mu, V = sla.eigh(Mff.toarray(), Kff.toarray())
        order = np.argsort(mu)[::-1][:k]
        mu, V = mu[order], V[:, order]
    else:
        op = spla.LinearOperator((n, n), matvec=lu.solve, dtype=float)
        mu, V = spla.eigsh(Mff, k=min(k, n - 1), M=Kff, Minv=op, which="LA")
        order = np.argsort(mu)[::-1]
        mu, V = mu[order], V[:, order]
    finite = mu > 1e-12 * max(mu.max(initial=0.0), 1e-300)
    if not finite.any():
        raise ModelError("[rotor]", "mass", 0.0, "a rotor with some inertia for a transient run")
    return V[:, finite], 1.0 / mu[finite]


def reduce_rotor(rs: RotorSystem, contact_dofs, n_modes: int = 12, reference_speed: float = 0.0,
                 basis_system: RotorSystem | None = None, basis_speed: float | None = None) -> ReducedRotor:
    """The reduced rotor of ``rs``: ``n_modes`` modes at rest (bearings at ``reference_speed``)
    plus the static shapes of unit loads on the ``contact_dofs`` ((m, 2) pairs of v, w DOFs).

    ``basis_system``: the same rotor with its nonlinear bearings linearised (same DOFs), whose
    stiffness the basis is built on when ``rs`` omits them (a run-up applies their laws), at
    ``basis_speed`` (default: ``reference_speed``)."""
    contact_dofs = np.asarray(contact_dofs, dtype=int).reshape(-1, 2)
    bs = rs if basis_system is None else basis_system
    s_basis = reference_speed if basis_speed is None else basis_speed
    Ks = _symmetric(bs.stiffness(s_basis))
    base = bs.system_at(s_basis)
    free = base.free
    n_free = free.size
    if isinstance(n_modes, bool) or not isinstance(n_modes, (int, np.integer)) or not 1 <= n_modes <= n_free:
        raise ModelError("[run_up]", "modes", n_modes, f"an integer from 1 to {n_free} (the rotor's free DOFs)")
    Kff = base.free_block(Ks).tocsc()
    Mff = base.free_block(rs.M).tocsc()
    try:
        lu = spla.splu(Kff)
        positive = _nonsingular(Kff, lu)
    except RuntimeError:
        lu, positive = None, False
    warnings = []
    if positive:
        _require_definite(Kff)
        shapes_free, _ = _modes_by_flexibility(Kff, Mff, lu, int(n_modes))
        mode_shapes = np.zeros((rs.n_dofs, shapes_free.shape[1]))
        mode_shapes[free] = shapes_free
    else:                                   # a rotor without supports: rigid-body modes (discrete.linear.modal)
        modes = modal_analysis(replace(base, K=Ks), int(n_modes), tolerance=1e-6)
        warnings += list(modes.warnings)
        mode_shapes = modes.shapes
    shapes = [mode_shapes]
    attach = np.zeros((rs.n_dofs, contact_dofs.size))
    if contact_dofs.size:
        if not positive:
            warnings.append("the rotor has rigid-body modes (no support): no static attachment shapes, the "
                            "contact's static flexibility is restored by the modes only")
        else:
            pos = np.searchsorted(free, contact_dofs.ravel())
            B = np.zeros((n_free, pos.size))
            B[pos, np.arange(pos.size)] = 1.0
            attach[free] = lu.solve(B)
            shapes.append(attach)
    Phi = np.hstack(shapes)
    norms = np.sqrt(np.maximum(np.einsum("ij,ij->j", Phi, rs.M @ Phi), 0.0))
    Phi = Phi[:, norms > 0] / norms[norms > 0]          # unit mass norm: static shapes are ~1e-6 of the modes
    S = Phi.T @ (rs.M @ Phi)
    s, V = np.linalg.eigh(0.5 * (S + S.T))
    keep = s > 1e-10 * s.max()
    Phi = Phi @ (V[:, keep] / np.sqrt(s[keep]))
    Kr = Phi.T @ (Ks @ Phi)
    w2, Q = np.linalg.eigh(0.5 * (Kr + Kr.T))
    T = Phi @ Q
    w2 = np.maximum(w2, 0.0)
    # restitution: reduced static flexibility sum_r T_jr^2 / w_r^2 against the full K^-1_jj
    restitution = np.full(contact_dofs.size, np.nan)        # a free rotor: not defined (no static response)
    if contact_dofs.size and positive:
        elastic = w2 > 1e-12 * w2.max()
        full = attach[contact_dofs.ravel(), np.arange(contact_dofs.size)]
        red = (T[contact_dofs.ravel()][:, elastic] ** 2 / w2[elastic]).sum(axis=1)
        restitution = red / full
    P = lambda A: T.T @ (A @ T)                                       # noqa: E731
    Kc = Cc = np.zeros((0, T.shape[1], T.shape[1]))
    if rs.tables:
        columns = lambda B: (rs._from_data(np.asarray(B[:, j].todense()).ravel()) for j in range(B.shape[1]))  # noqa: E731
        Kc = np.stack([P(A) for A in columns(rs._Bk)])
        Cc = np.stack([P(A) for A in columns(rs._Bc)])
    K0, C0 = P(rs.K0), P(rs.C0)
    return ReducedRotor(system=rs, basis_system=basis_system, T=T, omega=np.sqrt(w2), n_modes=int(mode_shapes.shape[1]),
                        contact_dofs=contact_dofs, restitution=np.asarray(restitution), reference_speed=float(reference_speed),
                        K0=K0, C0=C0, G=P(rs.G), Kc=Kc, Cc=Cc, warnings=warnings)
