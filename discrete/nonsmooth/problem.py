"""A :class:`LinearSystem` plus nonsmooth elements, drivers and forces, compiled for the solvers.

Equations (free DOFs q, constrained/driver DOFs x_c(t) prescribed):

    M(t) q'' + (C + C_r) q' + K q = -B e(t) + F_ext e(t) + sum_i g_i F_i + sum_k g_k lam_k

with ``M(t) = M + t Mdot`` (variable mass, seed 004 (1): Newton form with the reactive
damping ``C_r = epsilon Mdot``), ``e(t) = [1, t, sin w1 t, cos w1 t, ...]`` the exogenous basis
(``e' = E e``) in which driver motions and external forces are exact linear combinations, and
``lam_k`` the constraint forces of sticking frictions / persistent contacts.  In every mode in
which all active laws are affine and M is constant, the augmented state ``z = [q, v, e]``
obeys ``z' = A z`` exactly, so a piece is propagated by ``expm(A tau)``.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import ModelError
from ..linear_system import LinearSystem


@dataclass
class MotionLaw:
    """Prescribed motion x(t) = offset + velocity t + amplitude sin(omega t + phase)."""

    offset: float = 0.0
    velocity: float = 0.0
    amplitude: float = 0.0
    omega: float = 0.0
    phase: float = 0.0


@dataclass
class ExternalForce:
    """Force along g: value + amplitude sin(omega t + phase)."""

    g: np.ndarray
    value: float = 0.0
    amplitude: float = 0.0
    omega: float = 0.0
    phase: float = 0.0


def _dense(A):
    return np.asarray(A.toarray() if hasattr(A, "toarray") else A, dtype=float)


class Problem:
    """Compiled problem: matrices on the free DOFs, exogenous basis, elements with split gradients."""

    def __init__(self, system: LinearSystem, elements=(), drivers: dict | None = None, forces=(),
                 mass_rate=None, reactive=None, x0=None, v0=None):
        self.system = system
        n = system.n_dofs
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
            el.g = np.asarray(el.g, dtype=float)
            if el.g.shape != (n,):
                raise ModelError(f"element {el.name!r}", "g", el.g.shape, f"a vector of {n} DOF coefficients")
        # exogenous basis
        oms = sorted({float(d.omega) for d in drivers.values() if d.amplitude != 0 and d.omega != 0}
                     | {float(F.omega) for F in self.forces if F.amplitude != 0 and F.omega != 0})
        self.omegas = oms
        ne = 2 + 2 * len(oms)
        self.ne = ne
        E = np.zeros((ne, ne))
        E[1, 0] = 1.0
        for k, w in enumerate(oms):
            E[2 + 2 * k, 3 + 2 * k] = w
            E[3 + 2 * k, 2 + 2 * k] = -w
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
        self.P = P
        M, K, C = _dense(system.M), _dense(system.K), _dense(system.C)
        self.Mfull, self.Kfull, self.Cfull = M, K, C
        # rigid motions of the full elastic system (null space of K): removed before forming the
        # elastic energy, so that a drifting drive (x = V t) does not cancel digits in x^T K x
        lamK, vecK = np.linalg.eigh(0.5 * (K + K.T)) if n else (np.zeros(0), np.zeros((0, 0)))
        tolK = 1e-12 * (np.max(np.abs(lamK)) if lamK.size else 0.0)
        self._Krigid = vecK[:, np.abs(lamK) <= tolK]
        self.M0 = M[np.ix_(f, f)]
        self.K = K[np.ix_(f, f)]
        self.C = C[np.ix_(f, f)]
        self.Mdot = np.zeros_like(self.M0) if mass_rate is None else _dense(mass_rate)[np.ix_(f, f)]
        self.Cr = np.zeros_like(self.M0) if reactive is None else _dense(reactive)[np.ix_(f, f)]
        Pc = P[c]
        # coupling of free DOFs to driver motion (moved to the right-hand side)
        self.B = K[np.ix_(f, c)] @ Pc + C[np.ix_(f, c)] @ Pc @ E + M[np.ix_(f, c)] @ Pc @ E @ E
        Fx = np.zeros((self.nf, ne))
        for F in self.forces:
            Fx += np.outer(np.asarray(F.g, float)[f], row(F))
        self.Fx = Fx
        self.time_invariant = not np.any(self.Mdot)
        # element gradients split into free part and the exogenous part (drivers)
        self.gf = [el.g[f] for el in self.elements]
        self.ge = [el.g @ P for el in self.elements]
        self.gve = [ge @ E for ge in self.ge]
        self.gae = [ge @ E @ E for ge in self.ge]
        self.affine = all(el.affine for el in self.elements)
        x0 = np.zeros(n) if x0 is None else np.asarray(x0, float)
        v0 = np.zeros(n) if v0 is None else np.asarray(v0, float)
        self.q0, self.v0 = x0[f].copy(), v0[f].copy()
        self.names = [str(system.dof_name[i]) if system.dof_name[i] else system.label(i) for i in range(n)]
        # a time scale: highest natural frequency of the linear part (for step limits)
        try:
            lam = np.linalg.eigvals(np.linalg.solve(self.M0, self.K + sum(
                el.stiffness() * np.outer(gf, gf) for el, gf in zip(self.elements, self.gf) if el.stiffness() > 0)))
            self.omega_max = float(np.sqrt(np.max(np.abs(lam)))) if lam.size else 0.0
        except np.linalg.LinAlgError:
            self.omega_max = 0.0
        self.omega_max = max([self.omega_max] + [abs(w) for w in oms])

    # ------------------------------------------------------------------ basics
    def basis(self, t) -> np.ndarray:
        e = np.zeros(self.ne)
        e[0], e[1] = 1.0, t
        for k, w in enumerate(self.omegas):
            e[2 + 2 * k], e[3 + 2 * k] = np.sin(w * t), np.cos(w * t)
        return e

    def mass(self, t) -> np.ndarray:
        return self.M0 + t * self.Mdot

    def full_state(self, q, v, e):
        """Full-DOF positions and velocities (drivers included) for column arrays q, v, e."""
        x = self.P @ e
        xd = self.P @ (self.E @ e)
        x[self.f] += q
        xd[self.f] += v
        return x, xd

    def coords(self, i, q, v, e):
        return self.gf[i] @ q + self.ge[i] @ e, self.gf[i] @ v + self.gve[i] @ e

    def constraint_rows(self, mode):
        return [i for i, el in enumerate(self.elements) if el.is_constraint(mode[i])]

    def mode_affine(self, mode) -> bool:
        return self.time_invariant and self.affine

    # ------------------------------------------------------------ evaluation
    def evaluate(self, t, q, v, e, mode):
        """Right-hand side, element forces, constraint forces and guards for column arrays.

        q, v: (nf, m); e: (ne, m).  Returns dict with ``a`` (nf, m), ``F`` (n_el, m) the element
        forces along s (constraint forces included for constrained elements), ``lam``
        (rows of :meth:`constraint_rows`), ``s``, ``sd`` (n_el, m), ``guards`` (ng, m) and
        ``tags`` (list of (element index, tag)), each guard admissible when >= 0.
        """
        q, v, e = np.atleast_2d(q), np.atleast_2d(v), np.atleast_2d(e)
        m = q.shape[1]
        e0 = e[0]
        nel = len(self.elements)
        s = np.zeros((nel, m))
        sd = np.zeros((nel, m))
        F = np.zeros((nel, m))
        rhs = -self.K @ q - (self.C + self.Cr) @ v - self.B @ e + self.Fx @ e
        for i, el in enumerate(self.elements):
            s[i], sd[i] = self.coords(i, q, v, e)
            f = el.force(mode[i], s[i], sd[i], e0, t)
            if f is not None:
                F[i] = f
            rhs += np.outer(self.gf[i], F[i])
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
        g = np.array(guards) if guards else np.zeros((0, m))
        return {"a": a, "F": F, "lam": lam, "s": s, "sd": sd, "guards": g, "tags": tags, "rows": rows}

    def linear_maps(self, mode):
        """For an affine, time-invariant mode: z' = A z, guards = Cg z, F = Fm z, s = Sm z, sd = Sdm z."""
        nz = 2 * self.nf + self.ne
        I = np.eye(nz)
        q, v, e = I[:self.nf], I[self.nf:2 * self.nf], I[2 * self.nf:]
        out = self.evaluate(0.0, q, v, e, mode)
        A = np.vstack([v, out["a"], self.E @ e])
        return A, out["guards"], out["tags"], out["F"], out["s"], out["sd"]

    # ---------------------------------------------------------------- energy
    def energy(self, t, q, v, e, mode):
        """Mechanical energy: kinetic of free DOFs + elastic of all springs + element potentials."""
        x, _ = self.full_state(q, v, e)
        return self.linear_energy(t, x, v) + self.potential_energy(q, e, mode)

    def linear_energy(self, t, x, v):
        """Kinetic energy of the free DOFs and elastic energy of the springs, for full-DOF
        positions x and free velocities v (columns: states)."""
        if self._Krigid.shape[1]:
            x = x - self._Krigid @ (self._Krigid.T @ x)
        return 0.5 * np.sum(v * (self.mass(t) @ v), axis=0) + 0.5 * np.sum(x * (self.Kfull @ x), axis=0)

    def potential_energy(self, q, e, mode):
        """Potential energy of the conservative elements in ``mode``."""
        E = 0.0
        for i, el in enumerate(self.elements):
            if el.has_potential:
                s = self.gf[i] @ q + self.ge[i] @ e
                E = E + el.potential(s, mode[i])
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
        * ``contacts``: constraint forces of persistent contacts (zero for fixed stops).
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

    def problem(self, omega: float | None = None) -> Problem:
        """The Problem, every harmonic driver and force at ``omega`` (None: as given)."""
        drivers, forces = self.drivers, self.forces
        if omega is not None:
            drivers = {j: replace(d, omega=float(omega)) if d.amplitude != 0 else d for j, d in drivers.items()}
            forces = [replace(f, omega=float(omega)) if f.amplitude != 0 else f for f in forces]
        return Problem(self.system, [replace(el) for el in self.elements], drivers=drivers, forces=forces,
                       mass_rate=self.mass_rate, reactive=self.reactive, x0=self.x0, v0=self.v0)
