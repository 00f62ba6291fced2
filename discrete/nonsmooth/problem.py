"""A :class:`LinearSystem` plus nonsmooth elements, drivers and forces, compiled for the solvers.

Equations (free DOFs q, constrained/driver DOFs x_c(t) prescribed):

    M(t) q'' + (C + C_r) q' + K q = -B e(t) + F_ext e(t) + sum_i g_i F_i + sum_k g_k lam_k

with ``M(t) = M + t Mdot`` (variable mass, seed 004 (1): Newton form with the reactive
damping ``C_r = epsilon Mdot``), ``e(t) = [1, t, sin w1 t, cos w1 t, ..., u_1, u_2, ...]`` the
exogenous state (``e' = E e``) in which driver motions and external forces are exact linear
combinations (``u_k``: the sub-state of the k-th programme law, :mod:`.sources`), and ``lam_k``
the constraint forces of sticking frictions / persistent contacts.  Elements may carry internal
states ``w`` of their own (the motor torque of (5.54): ``w' `` affine in (s, s', w, e)).  In
every mode in which all active laws are affine, time-invariant and M is constant, the augmented
state ``z = [q, v, w, e]`` obeys ``z' = A z`` exactly, so a piece is propagated by
``expm(A tau)``.  The mode of the problem is the tuple of the element modes followed by the
piece index of every programme law (a knot is a time event that resets its sub-state).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from .. import checks
from ..errors import ModelError
from ..linear_system import LinearSystem
from ..motion.piecewise import PiecewiseLaw
from .sources import LawSource


@dataclass
class MotionLaw:
    """Prescribed motion x(t) = offset + velocity t + amplitude sin(omega t + phase)."""

    offset: float = 0.0
    velocity: float = 0.0
    amplitude: float = 0.0
    omega: float = 0.0
    phase: float = 0.0

    def __post_init__(self):
        where = "MotionLaw"
        for key in ("offset", "velocity", "amplitude", "phase"):
            setattr(self, key, checks.finite(where, key, getattr(self, key)))
        self.omega = checks.non_negative(where, "omega", self.omega, "angular frequency of the harmonic part, rad/s")


@dataclass
class ProgrammeMotion(MotionLaw):
    """Prescribed motion ``offset + velocity t + amplitude sin(omega t + phase) + law(t)`` with
    ``law`` a :class:`~discrete.motion.piecewise.PiecewiseLaw` in time (a cam law, a piecewise
    polynomial, a spline table): integrated exactly, its knots are time events (:mod:`.sources`)."""

    law: PiecewiseLaw | None = None

    def __post_init__(self):
        super().__post_init__()
        if not isinstance(self.law, PiecewiseLaw):
            raise ModelError("programme motion", "law", type(self.law).__name__,
                             "a discrete.motion.PiecewiseLaw in time (knots in s)")


@dataclass
class ExternalForce:
    """Force along g: value + amplitude sin(omega t + phase)."""

    g: np.ndarray
    value: float = 0.0
    amplitude: float = 0.0
    omega: float = 0.0
    phase: float = 0.0

    def __post_init__(self):
        where = "ExternalForce"
        self.g = checks.vector(where, "g", self.g, note="the force's direction coefficients on the DOFs")
        for key in ("value", "amplitude", "phase"):
            setattr(self, key, checks.finite(where, key, getattr(self, key)))
        self.omega = checks.non_negative(where, "omega", self.omega, "angular frequency of the harmonic part, rad/s")


def _dense(A):
    return np.asarray(A.toarray() if hasattr(A, "toarray") else A, dtype=float)


class Problem:
    """Compiled problem: matrices on the free DOFs, exogenous basis, elements with split gradients."""

    def __init__(self, system: LinearSystem, elements=(), drivers: dict | None = None, forces=(),
                 mass_rate=None, reactive=None, x0=None, v0=None):
        if not isinstance(system, LinearSystem):
            raise ModelError("Problem", "system", type(system).__name__, "a discrete.linear_system.LinearSystem")
        self.system = system
        n = system.n_dofs
        if drivers is not None and not isinstance(drivers, dict):
            raise ModelError("Problem", "drivers", type(drivers).__name__, "a dict {constrained DOF index: MotionLaw}")
        for j in (drivers or {}):
            checks.index("Problem", "drivers", j, n)
            if j not in set(system.constrained.tolist()):
                raise ModelError("Problem", "drivers", j, "the index of a constrained DOF (drivers move the "
                                 f"constrained DOFs of the system: {system.constrained.tolist()})")
        for i, F in enumerate(forces):
            if not isinstance(F, ExternalForce):
                raise ModelError("Problem", "forces", type(F).__name__, "a list of ExternalForce")
            if F.g.shape != (n,):
                raise ModelError(f"force #{i + 1}", "g", f"{F.g.size} coefficients", f"a vector of {n} DOF coefficients")
        x0 = None if x0 is None else checks.vector("Problem", "x0", x0, n, "initial positions of all DOFs")
        v0 = None if v0 is None else checks.vector("Problem", "v0", v0, n, "initial velocities of all DOFs")
        for key, A in (("mass_rate", mass_rate), ("reactive", reactive)):
            if A is not None:
                checks.real_matrix("Problem", key, A, (n, n))
                if not np.all(np.isfinite(_dense(A))):
                    raise ModelError("Problem", key, "inf/NaN entries", f"a finite real matrix of shape {(n, n)}")
        self.f = system.free
        self.c = system.constrained
        f, c = self.f, self.c
        self.nf = f.size
        drivers = dict(drivers or {})
        for j in c:
            drivers.setdefault(int(j), MotionLaw())
        self.drivers = drivers
        self.forces = list(forces)
        self.elements = list(elements)
        for el in self.elements:
            if not hasattr(el, "g") or not hasattr(el, "name"):
                raise ModelError("Problem", "elements", type(el).__name__, "a list of discrete.nonsmooth elements")
            el.g = checks.vector(f"element {el.name!r}", "g", el.g, n, "the element's coordinate s = g . x")
        self.names = [str(system.dof_name[i]) if system.dof_name[i] else system.label(i) for i in range(n)]
        for j, d in drivers.items():
            if not isinstance(d, MotionLaw):
                raise ModelError(f"driver {self.names[j]!r}", "law", type(d).__name__,
                                 "a MotionLaw or a ProgrammeMotion")
        # exogenous basis: [1, t, sin w1 t, cos w1 t, ...] then the sub-states of the programme laws
        oms = sorted({float(d.omega) for d in drivers.values() if d.amplitude != 0 and d.omega != 0}
                     | {float(F.omega) for F in self.forces if F.amplitude != 0 and F.omega != 0})
        self.omegas = oms
        nb = 2 + 2 * len(oms)
        self.nb = nb
        self.sources, self.source_slices, src_dof = [], [], []
        off = nb
        for j in sorted(drivers):
            if isinstance(drivers[j], ProgrammeMotion):
                src = LawSource(drivers[j].law, self.names[j])
                self.sources.append(src)
                self.source_slices.append(slice(off, off + src.size))
                src_dof.append(j)
                off += src.size
        ne = off
        self.ne = ne
        E = np.zeros((ne, ne))
        E[1, 0] = 1.0
        for k, w in enumerate(oms):
            E[2 + 2 * k, 3 + 2 * k] = w
            E[3 + 2 * k, 2 + 2 * k] = -w
        for src, sl in zip(self.sources, self.source_slices):
            E[sl, sl] = src.A
            E[sl, 0] = src.clock
        self.E = E

        def row(law):
            r = np.zeros(ne)
            r[0] += getattr(law, "offset", 0.0) if hasattr(law, "offset") else law.value
            r[1] += getattr(law, "velocity", 0.0)
            if law.amplitude != 0:
                if law.omega == 0:
                    r[0] += law.amplitude * np.sin(law.phase)
                else:
                    k = oms.index(float(law.omega))
                    r[2 + 2 * k] += law.amplitude * np.cos(law.phase)
                    r[3 + 2 * k] += law.amplitude * np.sin(law.phase)
            return r

        P = np.zeros((n, ne))          # full-DOF positions contributed by drivers: x_c = P[c] e
        for j, law in drivers.items():
            P[j] = row(law)
        for src, sl, j in zip(self.sources, self.source_slices, src_dof):
            P[j, sl] += src.r
        self.P = P
        M, K, C = _dense(system.M), _dense(system.K), _dense(system.C)
        self.Mfull, self.Kfull, self.Cfull = M, K, C
        self.M0 = M[np.ix_(f, f)]
        self.K = K[np.ix_(f, f)]
        self.C = C[np.ix_(f, f)]
        self.Mdot = np.zeros_like(self.M0) if mass_rate is None else _dense(mass_rate)[np.ix_(f, f)]
        self.Cr = np.zeros_like(self.M0) if reactive is None else _dense(reactive)[np.ix_(f, f)]
        Pc = P[c]
        # coupling of free DOFs to driver motion (moved to the right-hand side)
        self._couplings = (K[np.ix_(f, c)] @ Pc, C[np.ix_(f, c)] @ Pc, M[np.ix_(f, c)] @ Pc)
        self.B = self._couplings[0] + self._couplings[1] @ E + self._couplings[2] @ E @ E
        Fx = np.zeros((self.nf, ne))
        for F in self.forces:
            Fx += np.outer(np.asarray(F.g, float)[f], row(F))
        self.Fx = Fx
        # the value of every external force: force_rows @ e (one row per force)
        self.force_rows = np.array([row(F) for F in self.forces]).reshape(len(self.forces), ne)
        self.time_invariant = not np.any(self.Mdot)      # constant inertia
        # element gradients split into free part and the exogenous part (drivers)
        self.gf = [el.g[f] for el in self.elements]
        self.ge = [el.g @ P for el in self.elements]
        self.gve = [ge @ E for ge in self.ge]
        self.gae = [ge @ E @ E for ge in self.ge]
        self.n_el = len(self.elements)
        # elements whose law depends on t explicitly (a modulated spring): their pieces are numeric
        self.time_dependent = any(el.time_dependent for el in self.elements)
        self.affine = all(el.affine for el in self.elements) and not self.time_dependent
        # internal states of the elements (the motor torque): z = [q, v, w, e]
        self.state_slices, k = [], 0
        for el in self.elements:
            self.state_slices.append(slice(k, k + el.n_states))
            k += el.n_states
        self.nw = k
        self.stateful = [i for i, el in enumerate(self.elements) if el.n_states]
        self.w0 = np.concatenate([np.asarray(el.initial_states(), float).reshape(el.n_states)
                                  for el in self.elements]) if k else np.zeros(0)
        self.nz = 2 * self.nf + self.nw + ne
        extra = []
        for el in self.elements:
            for part in (el.work, el.time_work if el.time_dependent else None):
                if part and part != "conservative" and part not in self.WORK_PARTS and part not in extra:
                    extra.append(part)
        self.WORK_PARTS = Problem.WORK_PARTS + tuple(extra)
        x0 = np.zeros(n) if x0 is None else np.asarray(x0, float)
        v0 = np.zeros(n) if v0 is None else np.asarray(v0, float)
        self.q0, self.v0 = x0[f].copy(), v0[f].copy()

    # the time scales and the rigid motions are computed on first use (eigenvalue problems: a problem built
    # only to evaluate a recorded orbit, e.g. at every point of a frequency-response curve, never needs them)
    @cached_property
    def omega_max(self) -> float:
        """A time scale for step limits: the highest natural frequency of the linear part with every
        element's stiffness, or the fastest excitation, element or programme-law frequency (rad/s)."""
        try:
            lam = np.linalg.eigvals(np.linalg.solve(self.M0, self.K + sum(
                el.stiffness() * np.outer(gf, gf) for el, gf in zip(self.elements, self.gf) if el.stiffness() > 0)))
            linear = float(np.sqrt(np.max(np.abs(lam)))) if lam.size else 0.0
        except np.linalg.LinAlgError:
            linear = 0.0
        return max([linear] + [abs(w) for w in self.omegas] + [el.frequency() for el in self.elements]
                   + [src.max_frequency() for src in self.sources])

    @cached_property
    def rate_max(self) -> float:
        """max(omega_max, the fastest rate of the dissipative parts: :meth:`_fastest_rate`) (1/s)."""
        return max(self.omega_max, self._fastest_rate())

    @cached_property
    def _Krigid(self) -> np.ndarray:
        """The rigid motions of the full elastic system (null space of K, columns): removed before forming
        the elastic energy, so that a drifting drive (x = V t) does not cancel digits in x^T K x."""
        K = self.Kfull
        n = K.shape[0]
        lamK, vecK = np.linalg.eigh(0.5 * (K + K.T)) if n else (np.zeros(0), np.zeros((0, 0)))
        tolK = 1e-12 * (np.max(np.abs(lamK)) if lamK.size else 0.0)
        return vecK[:, np.abs(lamK) <= tolK]

    def retuned(self, omega: float, drivers: dict, forces: list) -> "Problem":
        """This problem with its harmonic drivers and forces replaced by ``drivers`` and ``forces``, the same
        ones at the frequency ``omega`` (what :meth:`ProblemSpec.problem` gives at another frequency), without
        rebuilding what does not depend on it: only the exogenous generator E, the driver coupling B and the
        elements' exogenous gradients are recomputed (the elements are copied).  The caller guarantees that
        every harmonic source of this problem was at one frequency and is now at ``omega`` (both non-zero),
        so the exogenous basis keeps its layout.  The frequency-free arrays (matrices, gradients, P, Fx,
        initial state) are shared with this problem, not copied: they are read, never written; the cached
        properties (time scales) are computed again."""
        new = object.__new__(Problem)
        cached = {k for k, v in vars(Problem).items() if isinstance(v, cached_property)} - {"_Krigid"}
        new.__dict__.update({k: v for k, v in self.__dict__.items() if k not in cached})
        new.drivers = {**self.drivers, **drivers}          # the constrained DOFs' default laws kept
        new.forces = list(forces)
        new.elements = [replace(el) for el in self.elements]
        new.omegas = [float(omega)]
        E = self.E.copy()
        E[2, 3], E[3, 2] = omega, -omega
        new.E = E
        K_, C_, M_ = self._couplings
        new.B = K_ + C_ @ E + M_ @ E @ E
        new.gve = [ge @ E for ge in self.ge]
        new.gae = [ge @ E @ E for ge in self.ge]
        return new

    def _fastest_rate(self) -> float:
        """The fastest rate (1/s) of the dissipative parts: the dampers (spectral radius of M^-1 C) and each
        element's own dynamics on its coordinate's effective inertia 1/(g M^-1 g) (a motor's torque state,
        :meth:`Element.rate`).  With ``omega_max`` it bounds the spectral radius of the pieces' state matrices,
        whose steps are 2 pi / (steps_per_period * radius): the time scale the step budget counts."""
        if not self.nf:
            return 0.0
        try:
            rate = float(np.max(np.abs(np.linalg.eigvals(np.linalg.solve(self.M0, self.C))))) if np.any(self.C) else 0.0
            for el, gf in zip(self.elements, self.gf):
                if np.any(gf):
                    rate = max(rate, el.rate(1.0 / float(gf @ np.linalg.solve(self.M0, gf))))
        except (np.linalg.LinAlgError, ZeroDivisionError):
            return 0.0
        return rate if math.isfinite(rate) else math.inf

    # ------------------------------------------------------------------ basics
    def basis(self, t) -> np.ndarray:
        """The exogenous state e at the absolute time t (programme laws: right-continuous at knots)."""
        e = np.zeros(self.ne)
        e[0], e[1] = 1.0, t
        for k, w in enumerate(self.omegas):
            e[2 + 2 * k], e[3 + 2 * k] = np.sin(w * t), np.cos(w * t)
        for src, sl in zip(self.sources, self.source_slices):
            e[sl] = src.at_time(t)[1]
        return e

    def basis_many(self, t) -> np.ndarray:
        """:meth:`basis` at every instant of ``t`` (columns, ``(ne, len(t))``): the harmonic rows as whole
        arrays (the same values as the scalar calls), the programme laws instant by instant."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        E = np.zeros((self.ne, t.size))
        E[0], E[1] = 1.0, t
        for k, w in enumerate(self.omegas):
            E[2 + 2 * k], E[3 + 2 * k] = np.sin(w * t), np.cos(w * t)
        if t.size:
            for src, sl in zip(self.sources, self.source_slices):
                E[sl] = np.array([src.at_time(tk)[1] for tk in t]).T.reshape(-1, t.size)
        return E

    def exogenous_after(self, e, t0, t1) -> np.ndarray:
        """e at t1 from e at t0 with no knot in between (closed forms; the base basis at t1)."""
        out = self.basis_base(t1)
        for src, sl in zip(self.sources, self.source_slices):
            out[sl] = src.advance(e[sl], t1 - t0)
        return out

    def basis_base(self, t) -> np.ndarray:
        """e at t with the programme sub-states left zero (filled by the caller)."""
        e = np.zeros(self.ne)
        e[0], e[1] = 1.0, t
        for k, w in enumerate(self.omegas):
            e[2 + 2 * k], e[3 + 2 * k] = np.sin(w * t), np.cos(w * t)
        return e

    def initial_state(self, t0: float = 0.0):
        """(z0 = [q0, v0, w0, e(t0)], the piece of every programme law at t0)."""
        e = self.basis_base(t0)
        pieces = []
        for src, sl in zip(self.sources, self.source_slices):
            i, u = src.at_time(t0)
            e[sl] = u
            pieces.append(i)
        return np.concatenate([self.q0, self.v0, self.w0, e]), tuple(pieces)

    def split(self, Z):
        """(q, v, w, e) parts of state vectors (rows of Z along its first axis)."""
        nf, nw = self.nf, self.nw
        return Z[:nf], Z[nf:2 * nf], Z[2 * nf:2 * nf + nw], Z[2 * nf + nw:]

    def mass(self, t) -> np.ndarray:
        return self.M0 if self.time_invariant else self.M0 + t * self.Mdot

    def full_state(self, q, v, e):
        """Full-DOF positions and velocities (drivers included) for column arrays q, v, e."""
        x = self.P @ e
        xd = self.P @ (self.E @ e)
        x[self.f] += q
        xd[self.f] += v
        return x, xd

    def full_acceleration(self, a, e):
        """Accelerations of all DOFs (drivers: their prescribed law) from the free ones ``a`` (columns)."""
        out = self.P @ (self.E @ (self.E @ e))
        out[self.f] += a
        return out

    def recover(self, t, x, xd, F) -> tuple[np.ndarray, np.ndarray]:
        """(accelerations of all DOFs, values of the external forces) at the instants ``t`` of a recorded
        history (columns: full-DOF positions ``x``, velocities ``xd``, element forces ``F`` along s):
        q'' from the equations of motion with the recorded element forces -- for an integrator that
        records no acceleration (regularised, Moreau-Jean: its forces are impulse / dt)."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        E = self.basis_many(t)
        f = self.f
        rhs = -self.K @ x[f] - (self.C + self.Cr) @ xd[f] - self.B @ E + self.Fx @ E
        if self.n_el:
            rhs = rhs + np.array(self.gf).T @ np.asarray(F).reshape(self.n_el, t.size)
        if self.time_invariant:
            a = np.linalg.solve(self.M0, rhs) if self.nf else rhs
        else:
            a = np.column_stack([np.linalg.solve(self.mass(tk), rhs[:, k]) for k, tk in enumerate(t)]) \
                if t.size else rhs
        return self.full_acceleration(a, E), self.force_rows @ E

    def coords(self, i, q, v, e):
        return self.gf[i] @ q + self.ge[i] @ e, self.gf[i] @ v + self.gve[i] @ e

    def constraint_rows(self, mode):
        return [i for i, el in enumerate(self.elements) if el.is_constraint(mode[i])]

    def mode_affine(self, mode) -> bool:
        return self.time_invariant and self.affine

    def actor_name(self, i: int) -> str:
        """Name of the element (i < n_el) or of the programme law (i >= n_el) of a guard tag."""
        return self.elements[i].name if i < self.n_el else self.sources[i - self.n_el].name

    def speed_scale(self) -> float:
        """The largest driver speed (constant, harmonic and programme parts)."""
        out = max((abs(d.velocity) + abs(d.amplitude * d.omega) for d in self.drivers.values()), default=0.0)
        return max([out] + [src.speed_scale() for src in self.sources])

    # --------------------------------------------------------- programme laws
    def knot(self, k: int, z: np.ndarray, piece: int):
        """The reset of programme law k at the end of ``piece``: (new z, next piece, jump of the
        driver's position, jump of its velocity)."""
        src = self.sources[k]
        nxt = src.next_piece(piece)
        z = z.copy()
        off = 2 * self.nf + self.nw
        sl = self.source_slices[k]
        z[off + sl.start:off + sl.stop] = src.resets[nxt]
        return z, nxt, float(src.jump_x[nxt]), float(src.jump_v[nxt])

    # ------------------------------------------------------------ evaluation
    def evaluate(self, t, q, v, e, mode, w=None):
        """Right-hand side, element forces, constraint forces and guards for column arrays.

        q, v: (nf, m); e: (ne, m); w: (nw, m) internal states (None: zeros).  Returns dict with
        ``a`` (nf, m), ``wd`` (nw, m) the internal state rates, ``F`` (n_el, m) the element
        forces along s (constraint forces included for constrained elements), ``lam`` (rows of
        :meth:`constraint_rows`), ``s``, ``sd`` (n_el, m), ``guards`` (ng, m) and ``tags``
        (list of (element index, tag); index n_el + k: the knot of programme law k), each guard
        admissible when >= 0.  ``t`` may be an array (one time per column) when M is constant.
        """
        q, v, e = np.atleast_2d(q), np.atleast_2d(v), np.atleast_2d(e)
        m = q.shape[1]
        w = np.zeros((self.nw, m)) if w is None else np.asarray(w).reshape(self.nw, m)
        e0 = e[0]
        nel = self.n_el
        s = np.zeros((nel, m))
        sd = np.zeros((nel, m))
        F = np.zeros((nel, m))
        rhs = -self.K @ q - (self.C + self.Cr) @ v - self.B @ e + self.Fx @ e
        for i, el in enumerate(self.elements):
            s[i], sd[i] = self.coords(i, q, v, e)
            if el.n_states:
                f = el.state_force(mode[i], s[i], sd[i], w[self.state_slices[i]], e0, t)
            else:
                f = el.force(mode[i], s[i], sd[i], e0, t)
            if f is not None:
                F[i] = f
            rhs += np.outer(self.gf[i], F[i])
        wd = np.zeros((self.nw, m))
        for i in self.stateful:
            sl = self.state_slices[i]
            wd[sl] = self.elements[i].state_rates(mode[i], s[i], sd[i], w[sl], e0, t)
        Mt = self.mass(t)
        rows = self.constraint_rows(mode)
        if rows:
            G = np.array([self.gf[i] for i in rows])
            r = -np.array([self.gae[i] for i in rows]) @ e
            MiG = np.linalg.solve(Mt, G.T)
            Mif = np.linalg.solve(Mt, rhs)
            S = G @ MiG
            try:
                lam = np.linalg.solve(S, r - G @ Mif)
            except np.linalg.LinAlgError:
                lam = np.linalg.lstsq(S, r - G @ Mif, rcond=None)[0]
            a = Mif + MiG @ lam
            for k, i in enumerate(rows):
                F[i] = lam[k]
        else:
            lam = np.zeros((0, m))
            a = np.linalg.solve(Mt, rhs)
        guards, tags = [], []
        for i, el in enumerate(self.elements):
            for value, tag in el.guards(mode[i], s[i], sd[i], F[i], e0, t):
                guards.append(value)
                tags.append((i, tag))
        for k, (src, sl) in enumerate(zip(self.sources, self.source_slices)):
            piece = mode[nel + k]
            if src.has_end(piece):            # the knot: sigma reaches the piece's length
                guards.append(src.lengths[piece] * e0 - e[sl.start])
                tags.append((nel + k, "knot"))
        g = np.array(guards) if guards else np.zeros((0, m))
        return {"a": a, "wd": wd, "F": F, "lam": lam, "s": s, "sd": sd, "guards": g, "tags": tags, "rows": rows}

    def linear_maps(self, mode):
        """For an affine, time-invariant mode: z' = A z, guards = Cg z, F = Fm z, s = Sm z, sd = Sdm z."""
        I = np.eye(self.nz)
        q, v, w, e = self.split(I)
        out = self.evaluate(0.0, q, v, e, mode, w)
        A = np.vstack([v, out["a"], out["wd"], self.E @ e])
        return A, out["guards"], out["tags"], out["F"], out["s"], out["sd"]

    # ---------------------------------------------------------------- energy
    def energy(self, t, q, v, e, mode):
        """Mechanical energy: kinetic of free DOFs + elastic of all springs + element potentials."""
        x, _ = self.full_state(q, v, e)
        return self.linear_energy(t, x, v) + self.potential_energy(q, e, mode, t)

    def linear_energy(self, t, x, v):
        """Kinetic energy of the free DOFs and elastic energy of the springs, for full-DOF
        positions x and free velocities v (columns: states)."""
        if self._Krigid.shape[1]:
            x = x - self._Krigid @ (self._Krigid.T @ x)
        return 0.5 * np.sum(v * (self.mass(t) @ v), axis=0) + 0.5 * np.sum(x * (self.Kfull @ x), axis=0)

    def potential_energy(self, q, e, mode, t=0.0):
        """Potential energy of the conservative elements in ``mode`` at time t (a time-dependent
        potential, the modulated spring's, needs t; t may be an array, one time per column)."""
        E = 0.0
        for i, el in enumerate(self.elements):
            if el.has_potential:
                s = self.gf[i] @ q + self.ge[i] @ e
                E = E + el.potential_at(s, mode[i], t)
        return E

    WORK_PARTS = ("drivers", "dampers", "variable_mass", "external", "friction", "elements", "contacts")

    def power_parts(self, t, q, v, e, mode, F, sd) -> dict:
        """Non-conservative power into the free system, by source, from the individual forces
        (not from M a), for column arrays:

        * ``drivers``: power of the prescribed motions through springs, dampers, inertia coupling
          and conservative elements attached to them;
        * ``dampers``: -x'^T C x' (all dampers, <= 0);
        * ``variable_mass``: reactive and mass-change terms of seed 004, (1/2 - eps) delta v^2;
        * ``external``: [[force]] tables;
        * ``friction``: friction forces (slip and stick) on the free DOFs;
        * ``elements``: elements without a potential (the smooth arctan gap), counted as work;
        * ``contacts``: constraint forces of persistent contacts (zero for fixed stops);
        * an element's own category (``motor``: the motor torque's power) and ``modulation``: the
          explicit time derivative of a time-dependent potential, dV/dt at fixed s (the work of
          the pulsation of a modulated spring) -- present only with such elements.
        """
        x, xd = self.full_state(q, v, e)
        c, f = self.c, self.f
        zero = 0.0 * v[0] if v.shape[0] else np.zeros(q.shape[1])
        out = {k: zero.copy() for k in self.WORK_PARTS}
        if c.size:
            out["drivers"] = (np.einsum("im,ij,jm->m", xd[c], self.Kfull[c], x)
                              + np.einsum("im,ij,jm->m", xd[c], self.Cfull[c], xd))
            ac = self.P[c] @ (self.E @ self.E @ e)
            out["drivers"] = out["drivers"] - np.einsum("im,ij,jm->m", v, self.Mfull[np.ix_(f, c)], ac)
        out["dampers"] = -np.einsum("im,ij,jm->m", xd, self.Cfull, xd)
        out["variable_mass"] = (-np.einsum("im,ij,jm->m", v, self.Cr, v)
                                + 0.5 * np.einsum("im,ij,jm->m", v, self.Mdot, v))
        out["external"] = np.einsum("im,im->m", v, self.Fx @ e)
        for i, el in enumerate(self.elements):
            Fc, Fn = el.split_force(mode[i], sd[i], F[i])
            if Fc is not None:       # a potential moved by the drivers: their work
                out["drivers"] = out["drivers"] - Fc * (self.gve[i] @ e)
            if Fn is not None:       # the rest of the force: work of its category on the free DOFs
                out[el.work] = out[el.work] + Fn * (self.gf[i] @ v)
            if el.time_dependent:    # dV/dt at fixed s
                s_i = self.gf[i] @ q + self.ge[i] @ e
                out[el.time_work] = out[el.time_work] + el.explicit_power(s_i, mode[i], t)
        return out

    def power(self, t, q, v, e, mode, F, sd):
        """Total non-conservative power (sum of :meth:`power_parts`)."""
        return sum(self.power_parts(t, q, v, e, mode, F, sd).values())


@dataclass
class ProblemSpec:
    """Everything of a :class:`Problem` but the forcing frequency: a steady-state continuation
    builds the problem at any frequency from it without rebuilding the model."""

    system: LinearSystem
    elements: list
    drivers: dict = field(default_factory=dict)
    forces: list = field(default_factory=list)
    mass_rate: object = None
    reactive: object = None
    x0: np.ndarray | None = None
    v0: np.ndarray | None = None
    damping_report: object = None        # how psi became viscous damping (discrete.linear.dissipation)
    layout: dict | None = None           # the builder's named coordinate vectors of elements and forces (loads)

    def problem(self, omega: float | None = None) -> Problem:
        """The Problem, every harmonic driver and force at ``omega`` (None: as given)."""
        return self._build(*self._sources_at(omega))

    def _build(self, drivers, forces) -> Problem:
        return Problem(self.system, [replace(el) for el in self.elements], drivers=drivers, forces=forces,
                       mass_rate=self.mass_rate, reactive=self.reactive, x0=self.x0, v0=self.v0)

    def problems(self, omegas) -> list[Problem]:
        """:meth:`problem` at each frequency of ``omegas`` (the points of a frequency-response curve): the
        first one built, the others retuned from it (:meth:`Problem.retuned`: the same values, ~10x less
        work) where its harmonic sources share one non-zero frequency."""
        out, base = [], None
        for w in omegas:
            drivers, forces = self._sources_at(w)
            if base is not None and w != 0:
                out.append(base.retuned(float(w), drivers, forces))
                continue
            p = self._build(drivers, forces)
            if len(p.omegas) == 1 and p.omegas[0] == float(w) and not p.sources:
                base = p
            out.append(p)
        return out

    def _sources_at(self, omega):
        """The drivers and forces with every harmonic one at ``omega`` (None: as given)."""
        drivers, forces = self.drivers, self.forces
        if omega is not None:
            drivers = {j: replace(d, omega=float(omega)) if d.amplitude != 0 else d for j, d in drivers.items()}
            forces = [replace(f, omega=float(omega)) if f.amplitude != 0 else f for f in forces]
        return drivers, forces
