"""The motor as a model element: the dynamic characteristic (5.54) as a first-order state.

    omega_d = omega_d0 [1 - nu (M + T M')]      (5.54), (3.15)
    <=>  T M' + M = (1 - omega_d/omega_d0)/nu   (the torque M is one more state of the drive)

omega_d0: ideal no-load speed [rad/s]; nu: slope of the static characteristic [1/(N m)];
T: electromagnetic time constant [s] (T = 0: the static characteristic).

* :meth:`DynamicMotor.from_catalogue` -- induction motor from catalogue data (§5.10):
  s_k = (1 - omega_n/omega_d0)(xi + sqrt(xi^2 + 1)), T = 1/(2 pi f_c s_k), nu = s_k/(2 M_n xi).
* Rotor J alone (5.55)-(5.58): Delta omega'' + 2 n Delta omega' + k^2 Delta omega = W(t) with n = 1/(2T),
  k^2 = 1/(nu T J omega_d0) (the book prints "k^2 omega_d" in (5.58): the term is k^2 Delta omega),
  k_1 = sqrt(k^2 - n^2); aperiodic for T <= T* = nu omega_d0 J/4; k_1 is largest, 1/(nu omega_d0 J), at
  T** = nu omega_d0 J/2.
* Equivalent mechanical model (§5.10, (10.65)): a damper b = 1/(nu omega_d0) in series with a spring
  c = 1/(nu omega_d0 T) between stator and rotor (a Maxwell element).  For small harmonic motion
  Delta phi of the rotor the motor torque is Delta M = -Z(omega) Delta phi with the complex
  stiffness to ground  Z(omega) = i omega b / (1 + i omega T)  (:meth:`DynamicMotor.complex_stiffness`).
* :func:`with_motor` adds the Maxwell node to a :class:`LinearSystem` (zero inertia) for forced analysis;
  :func:`motor_modes` solves the drive-with-motor eigenproblem in first-order form
  (states q, q' of the free DOFs and the motor torque) as a generalised problem A z = s B z
  (no inverse of M is formed).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from ..errors import ModelError
from ..linear_system import LinearSystem

WHERE = "motor"


def _pos(value, key: str, where: str = WHERE) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)) or not (math.isfinite(value) and value > 0):
        raise ModelError(where, key, value, "a finite number > 0")
    return float(value)


@dataclass(frozen=True)
class CatalogueData:
    """Catalogue data of an induction motor (§5.10) and the derived critical slip."""

    f_mains: float            # mains frequency [Hz]
    pole_pairs: int
    speed_nominal: float      # nominal speed omega_n [rad/s]
    torque_nominal: float     # M_n [N m]
    torque_ratio: float       # xi = M_max / M_n

    @property
    def omega0(self) -> float:
        """Synchronous (ideal no-load) speed 2 pi f_c / p [rad/s]."""
        return 2 * math.pi * self.f_mains / self.pole_pairs

    @property
    def critical_slip(self) -> float:
        """s_k = (1 - omega_n/omega_d0)(xi + sqrt(xi^2 + 1))."""
        xi = self.torque_ratio
        return (1 - self.speed_nominal / self.omega0) * (xi + math.sqrt(xi * xi + 1))


@dataclass(frozen=True)
class DynamicMotor:
    """Dynamic characteristic T M' + M = (1 - omega/omega0)/nu (5.54)."""

    omega0: float     # ideal no-load speed (rad/s)
    nu: float         # slope of the static characteristic (1/(N m))
    T: float          # electromagnetic time constant (s)

    def __post_init__(self):
        for key in ("omega0", "nu", "T"):
            v = getattr(self, key)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.floating)) or not (math.isfinite(v) and v > 0):
                raise ModelError(WHERE, key, v, "a number > 0")

    # ------------------------------------------------------------ catalogue
    @classmethod
    def from_catalogue(cls, *, f_mains: float, pole_pairs: int, speed_nominal: float, torque_nominal: float,
                       torque_ratio: float) -> "DynamicMotor":
        """T = 1/(2 pi f_c s_k), nu = s_k/(2 M_n xi) from catalogue data (§5.10)."""
        where = "motor catalogue"
        f = _pos(f_mains, "f_mains", where)
        if isinstance(pole_pairs, bool) or not isinstance(pole_pairs, (int, np.integer)) or pole_pairs < 1:
            raise ModelError(where, "pole_pairs", pole_pairs, "an integer >= 1")
        cat = CatalogueData(f, int(pole_pairs), _pos(speed_nominal, "speed_nominal", where),
                            _pos(torque_nominal, "torque_nominal", where), _pos(torque_ratio, "torque_ratio", where))
        if not cat.speed_nominal < cat.omega0:
            raise ModelError(where, "speed_nominal", speed_nominal,
                             f"a speed below the synchronous speed 2 pi f/p = {cat.omega0:.6g} rad/s")
        sk = cat.critical_slip
        return cls(omega0=cat.omega0, nu=sk / (2 * cat.torque_nominal * cat.torque_ratio), T=1 / (2 * math.pi * f * sk))

    # ---------------------------------------------------------- the law
    def static_torque(self, omega):
        """M on the static characteristic (T = 0): (1 - omega/omega0)/nu."""
        return (1 - np.asarray(omega, dtype=float) / self.omega0) / self.nu

    def torque_rate(self, M, omega):
        """M' = ((1 - omega/omega0)/nu - M)/T (the state equation of the motor torque)."""
        return (self.static_torque(omega) - np.asarray(M, dtype=float)) / self.T

    def steady_speed(self, load_torque: float) -> float:
        """omega* = omega0 (1 - nu M_c*) (5.57)."""
        return self.omega0 * (1 - self.nu * load_torque)

    def state_row(self) -> dict:
        """Coefficients of M' = a_M M + a_w omega + a_0 (for an exact integrator's augmented state):
        a_M = -1/T, a_w = -1/(nu T omega0), a_0 = 1/(nu T)."""
        return {"M": -1 / self.T, "omega": -1 / (self.nu * self.T * self.omega0), "const": 1 / (self.nu * self.T)}

    # --------------------------------------------------- mechanical model
    @property
    def b(self) -> float:
        """Damper of the Maxwell model b = 1/(nu omega0) [N m s/rad]."""
        return 1.0 / (self.nu * self.omega0)

    @property
    def c(self) -> float:
        """Spring of the Maxwell model c = 1/(nu omega0 T) [N m/rad]."""
        return 1.0 / (self.nu * self.omega0 * self.T)

    def complex_stiffness(self, omega):
        """Z(omega) = i omega b/(1 + i omega T): Delta M = -Z Delta phi for rotor motion Re(Delta phi e^{i omega t})."""
        w = np.asarray(omega, dtype=float)
        return 1j * w * self.b / (1 + 1j * w * self.T)

    # ---------------------------------------------------- rotor J alone
    def rotor_constants(self, J: float) -> dict:
        """n, k, k_1, T*, T**, k_1max of (5.58) and the text after it, for the reduced inertia J."""
        J = _pos(J, "J")
        n = 0.5 / self.T
        k2 = 1 / (self.nu * self.T * J * self.omega0)
        return {"n": n, "k": math.sqrt(k2), "delta": n / math.sqrt(k2),
                "k1": math.sqrt(k2 - n * n) if k2 > n * n else 0.0, "aperiodic": bool(k2 <= n * n),
                "T_star": 0.25 * self.nu * self.omega0 * J, "T_star2": 0.5 * self.nu * self.omega0 * J,
                "k1_max": 1 / (self.nu * self.omega0 * J)}

    def partial_frequency(self, J: float) -> float:
        """p0 = sqrt(k^2 - n^2) (NaN when aperiodic) -- §10.6."""
        r = self.rotor_constants(J)
        return float("nan") if r["aperiodic"] else r["k1"]

    def flywheel_min_inertia(self, omega: float) -> float:
        """J > 2/(omega^2 omega0 nu T): the forcing frequency stays above sqrt(2) k_1 (§5.10)."""
        return 2 / (_pos(omega, "omega") ** 2 * self.omega0 * self.nu * self.T)

    def nonuniformity(self, omega, M_D):
        """chi = |nu M_D (1 + i omega T)| (the book prints (1 + i T), dimensionally wrong)."""
        return np.abs(self.nu * np.asarray(M_D) * (1 + 1j * np.asarray(omega) * self.T))

    def to_dict(self) -> dict:
        return {"omega0": self.omega0, "nu": self.nu, "T": self.T, "b": self.b, "c": self.c}


# ------------------------------------------------------------- linear systems
def _dof(system: LinearSystem, dof: int) -> int:
    if isinstance(dof, bool) or not isinstance(dof, (int, np.integer)) or not 0 <= dof < system.n_dofs:
        raise ModelError(WHERE, "dof", dof, f"a DOF index in [0, {system.n_dofs - 1}]")
    if int(dof) in set(system.constrained.tolist()):
        raise ModelError(WHERE, "dof", system.label(int(dof)), "a free DOF (the rotor), not a constrained one")
    return int(dof)


def with_motor(system: LinearSystem, dof: int, motor: DynamicMotor) -> LinearSystem:
    """A copy of ``system`` with the motor's Maxwell element between ground and the rotor DOF ``dof``:
    one extra DOF z (no inertia), spring c from z to the rotor, damper b from z to ground (10.65).
    For harmonic analysis only (the extra DOF has no mass)."""
    g = np.zeros(system.n_dofs)
    g[_dof(system, dof)] = 1.0
    return with_motor_along(system, g, motor.omega0, motor.nu, motor.T)


def with_motor_along(system: LinearSystem, g, omega0: float, nu: float, T: float,
                     name: str = "motor") -> LinearSystem:
    """A copy of ``system`` with a motor acting along the coordinate s = g . q (a [[motor]] of a model file):
    for T > 0 the Maxwell element of (10.65) -- an extra massless DOF z, spring c = 1/(nu omega0 T) between s
    and z, damper b = 1/(nu omega0) from z to ground, i.e. the complex stiffness Z = i omega b/(1 + i omega T)
    along s; for T = 0 (the static characteristic) the damper b along s itself.  For harmonic analysis only."""
    g = np.asarray(g, float).ravel()
    n = system.n_dofs
    if g.shape != (n,) or not np.all(np.isfinite(g)) or not np.any(g):
        raise ModelError(WHERE, "g", f"shape {g.shape}", f"a finite, nonzero coordinate vector of {n} entries")
    b = 1.0 / (_pos(nu, "nu") * _pos(omega0, "omega0"))
    gs = sp.csr_matrix(g[:, None])                       # g as a sparse column: no dense n x n products
    if T == 0:
        return LinearSystem(M=system.M, K=system.K, C=system.C + b * (gs @ gs.T), H=system.H, G=system.G,
                            dof_field=system.dof_field, dof_x=system.dof_x, dof_name=system.dof_name,
                            constrained=system.constrained, rigid_modes=None, title=system.title,
                            physics=system.physics)
    c = b / _pos(T, "T")
    ge = sp.vstack([gs, sp.csr_matrix([[-1.0]])], format="csr")

    def grow(A):
        return sp.block_diag([A, sp.csr_matrix((1, 1))], format="csr")

    K = grow(system.K) + c * (ge @ ge.T)
    C = grow(system.C) + sp.csr_matrix(([b], ([n], [n])), shape=(n + 1, n + 1))
    return LinearSystem(M=grow(system.M), K=K.tocsr(), C=C.tocsr(), H=grow(system.H),
                        G=grow(system.G), dof_field=np.append(system.dof_field, "motor"),
                        dof_x=np.append(system.dof_x, np.nan), dof_name=np.append(system.dof_name, f"{name}_maxwell"),
                        constrained=system.constrained, rigid_modes=None, title=system.title, physics=system.physics)


@dataclass
class MotorModes:
    """Eigenvalues s of the drive with the motor torque as a state (first-order form)."""

    eigenvalues: np.ndarray       # complex, sorted by |Im| then Re
    residuals: np.ndarray         # ||(A - s B) v|| / ((||A|| + |s| ||B||) ||v||)

    @property
    def damped_frequencies(self) -> np.ndarray:
        """|Im s| [rad/s] (0 for aperiodic roots)."""
        return np.abs(self.eigenvalues.imag)

    @property
    def decay_rates(self) -> np.ndarray:
        return -self.eigenvalues.real

    def oscillatory(self, rtol: float = 1e-9) -> np.ndarray:
        """Roots with Im s > 0 (one per oscillatory mode)."""
        s = self.eigenvalues
        return s[s.imag > rtol * np.maximum(np.abs(s), 1e-300)]

    def to_dict(self) -> dict:
        return {"eigenvalues_real": self.eigenvalues.real.tolist(), "eigenvalues_imag": self.eigenvalues.imag.tolist(),
                "residuals": self.residuals.tolist()}


MAX_DENSE = 2000


def motor_modes(system: LinearSystem, dof: int, motor: DynamicMotor) -> MotorModes:
    """Eigenvalues of  M q'' + C q' + K q = e_dof M_m,  T M_m' + M_m = -q'_dof/(nu omega0)  (the motor
    law linearised about a steady state) on the free DOFs: A z = s B z with z = (q, q', M_m),
    B = diag(I, M, T).  Dense (intended for lumped drives; refused above 2000 free DOFs)."""
    dof = _dof(system, dof)
    f = system.free
    nf = f.size
    if nf > MAX_DENSE:
        raise ModelError(WHERE, "system", f"{nf} free DOFs", f"at most {MAX_DENSE} free DOFs (reduce the model first)")
    M = system.free_block(system.M).toarray()
    K = system.free_block(system.K).toarray()
    C = system.free_block(system.C).toarray()
    j = int(np.flatnonzero(f == dof)[0])
    N = 2 * nf + 1
    A = np.zeros((N, N))
    B = np.zeros((N, N))
    I = np.eye(nf)
    A[:nf, nf:2 * nf] = I
    A[nf:2 * nf, :nf] = -K
    A[nf:2 * nf, nf:2 * nf] = -C
    A[nf + j, -1] = 1.0
    A[-1, nf + j] = -1.0 / (motor.nu * motor.omega0)
    A[-1, -1] = -1.0
    B[:nf, :nf] = I
    B[nf:2 * nf, nf:2 * nf] = M
    B[-1, -1] = motor.T
    s, V = sla.eig(A, B)
    keep = np.isfinite(s)
    s, V = s[keep], V[:, keep]
    nA, nB = np.linalg.norm(A, 2), np.linalg.norm(B, 2)
    res = np.array([np.linalg.norm(A @ V[:, i] - s[i] * (B @ V[:, i])) / ((nA + abs(s[i]) * nB) * np.linalg.norm(V[:, i]))
                    for i in range(s.size)])
    order = np.lexsort((s.real, np.round(np.abs(s.imag), 9)))
    return MotorModes(eigenvalues=s[order], residuals=res[order])
