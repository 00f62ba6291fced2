"""Time simulation of a train: the compiled nonsmooth problem (:mod:`.compile`) integrated by the event
solver (exact backlash and slip events) or Moreau-Jean, and the loads along the way.

Loads at every recorded instant, in the train's DOFs (full field T x): the force of every connection by its
own law (mesh force: compression of the drive flank positive; the solver's element forces and the linear
remainders), the reaction of every bearing and support, and the force balance of every shaft and body
(:mod:`.loads`): the inertia forces come from the equations of motion of the compiled system at the
sample (M a = f(t) - K x - C v + sum g F), so the balance checks that every force is accounted for.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from .compile import CompiledTrain
from .loads import balance, bearing_terms, internal_matrices, point_springs, rigid_directions


@dataclass
class TrainSimulation:
    """A train's time history: the solver's result (``result``: compiled DOFs), the compiled train and the
    loads (computed on demand)."""

    result: object
    compiled: CompiledTrain
    warnings: list = field(default_factory=list)

    @property
    def t(self) -> np.ndarray:
        return self.result.t

    def __getattr__(self, name):
        """The solver's result fields (period, events, energy_error, x, v, names, ...) are the train's."""
        if name.startswith("_") or name in ("result", "compiled", "warnings"):
            raise AttributeError(name)
        return getattr(self.result, name)

    @cached_property
    def _states(self):
        """(x, v, a) of the compiled system (all DOFs, drivers included) at every sample."""
        c, r = self.compiled, self.result
        p = c.spec().problem()
        x, v = np.asarray(r.x), np.asarray(r.v)
        t = np.asarray(r.t)
        M, K, C = (np.asarray(A.toarray()) for A in (c.system.M, c.system.K, c.system.C))
        f = np.zeros_like(x)
        for F in c.forces:
            f += np.outer(F.g, F.value + F.amplitude * np.sin(F.omega * t + F.phase))
        Fel = np.asarray(getattr(r, "element_forces", np.zeros((0, t.size))))
        for el, Fe in zip(c.elements, Fel):
            f += np.outer(el.g, Fe)
        a = np.zeros_like(x)
        con = c.system.constrained
        for j in con:
            law = c.drivers.get(int(j))
            if law is not None:
                a[j] = -law.amplitude * law.omega ** 2 * np.sin(law.omega * t + law.phase)
        fr = c.system.free
        rhs = f - K @ x - C @ v - M[:, con] @ a[con]
        a[fr] = np.linalg.solve(M[np.ix_(fr, fr)], rhs[fr])
        del p
        return x, v, a, f

    @cached_property
    def field(self) -> tuple:
        """(q, v, a) in the train's DOFs (n_train, n_samples)."""
        x, v, a, _ = self._states
        c = self.compiled
        return c.full(x), c.full(v), c.full(a)

    def exo_values(self) -> dict:
        """{transmission-error key: (e(t), e'(t))} at the samples."""
        c, t = self.compiled, np.asarray(self.result.t)
        out = {}
        for key, j in c.exo.items():
            law = c.drivers.get(j) if c.Tr is None else None
            if law is None:
                continue
            out[key] = (law.amplitude * np.sin(law.omega * t + law.phase),
                        law.amplitude * law.omega * np.cos(law.omega * t + law.phase))
        return out

    def connection_forces(self) -> dict:
        """{connection name: force history} by the connection's own law (meshes: compression positive;
        couplings: per direction, the springs and dampers plus, on the torsion, the solver's force of a
        backlash or slip element)."""
        ts = self.compiled.ts
        q, v, _ = self.field
        t = np.asarray(self.result.t)
        out = {}
        exo = self.exo_values()
        elements = None
        for conn in ts.train.connections:
            if hasattr(conn, "mesh_force"):
                out[conn.name] = conn.mesh_force(ts, q, v, t, exo, self.compiled.speed)
                continue
            linear, parts, _ = conn.nonsmooth(ts, self.compiled.speed)
            for cd in linear:
                out[f"{conn.name}:{cd.label}"] = -cd.k * cd.of(q) - cd.c * cd.of(v)
            for part in parts:
                elements = self.element_forces() if elements is None else elements
                key = f"{conn.name}:{part.coord.label}"
                out[key] = out.get(key, 0.0) + elements[part.name]
        return out

    def element_forces(self) -> dict:
        """{element name: the solver's force along its coordinate} (compiled elements)."""
        r = self.result
        return {el.name: np.asarray(F) for el, F in zip(self.compiled.elements, getattr(r, "element_forces", []))}

    def bearing_forces(self) -> dict:
        """{bearing label: (3, n_samples) force on the shaft (F_y, F_z, F_x)}."""
        ts = self.compiled.ts
        q, v, _ = self.field
        return {bt.label: bt.force(q, v) for bt in bearing_terms(ts, self.compiled.speed)}

    @cached_property
    def force_balance(self):
        """:class:`fem.train.loads.Balance` of every shaft and body at every sample."""
        c = self.compiled
        ts = c.ts
        x, v, a, f = self._states
        q, qd, qdd = self.field
        Kint, Cint = internal_matrices(ts)
        bear = np.zeros_like(q)
        for bt in bearing_terms(ts, c.speed):
            fb = bt.force(q, qd)
            bear[bt.shaft_dofs[0]] += fb[0]
            bear[bt.shaft_dofs[1]] += fb[1]
            if bt.axial_dof is not None:
                bear[bt.axial_dof] += fb[2]
        conn = {}
        xu, vu = c.uncompiled(x), c.uncompiled(v)
        el_forces = self.element_forces()
        for cn, label, g, k, cc, cd in c.probes:
            F = el_forces[label] if k is None else -k * (g @ xu) - cc * (g @ vu)
            vec = conn.setdefault(f"{cn.name}:{label}", np.zeros_like(q))
            np.add.at(vec, cd.idx, np.outer(cd.val, F))
        t = np.asarray(self.result.t)
        applied = np.zeros_like(q)
        for e, F in zip(c.load_vectors, c.forces):
            applied += np.outer(e, F.value + F.amplitude * np.sin(F.omega * t + F.phase))
        inertia = -(ts.M @ qdd)
        damping = -(Cint @ qd) - c.speed * (ts.G @ qd)
        elastic = -(Kint @ q)
        springs = -(point_springs(ts) @ q)
        tot = inertia + damping + elastic + springs + bear + sum(conn.values(), np.zeros_like(q)) + applied
        held = np.zeros_like(q)
        hold = np.union1d(ts.constrained, np.asarray(c.driver_dofs, dtype=int))
        held[hold] = -tot[hold]
        return balance(ts, rigid_directions(ts), {"inertia": inertia, "damping": damping, "elastic": elastic,
                                                  "springs": springs, "bearings": bear, **conn,
                                                  "applied": applied, "supports": held})

    def section_loads(self, shaft: str, x=None):
        """:class:`fem.loads.SectionLoads` along ``shaft`` at every sample (fem.loads, time-history recovery
        with the velocities and the accelerations of the equations of motion)."""
        from .loads import shaft_section_loads

        q, qd, qdd = self.field
        return shaft_section_loads(self.compiled.ts, shaft, q, qd=qd, qdd=qdd, speed=self.compiled.speed, x=x)

    def to_dict(self) -> dict:
        d = self.result.to_dict()
        cf = self.connection_forces()
        d["connection_forces"] = {k: {"max": float(np.max(v)), "min": float(np.min(v)),
                                      "mean": float(np.mean(v))} for k, v in cf.items()}
        d["bearing_forces"] = {k: {"max_radial": float(np.max(np.hypot(v[0], v[1]))), "max_axial": float(np.max(np.abs(v[2])))}
                               for k, v in self.bearing_forces().items()}
        d["force_balance"] = self.force_balance.to_dict()
        d["reduction"] = self.compiled.reports
        d["warnings"] = list(d.get("warnings", [])) + [w for w in self.warnings if w not in d.get("warnings", [])]
        return d

