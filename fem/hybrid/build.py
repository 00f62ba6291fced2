"""Hybrid continuous-lumped problems: an FE system (full or modally reduced) plus lumped bodies,
springs and nonsmooth elements attached to FE nodes.

Pipeline::

    FE LinearSystem (full)  --[drivers: DOFs held with prescribed motion]-->
        --[reduction: Craig-Bampton / free-interface, coupling DOFs = element DOFs]-->
        --[append lumped bodies and springs]-->  discrete.nonsmooth.Problem

Every element is described by a vector ``g`` over the FE DOFs (its coordinate ``s = g . q``);
in a reduced model it becomes ``T^T g`` (exact: ``g . (T z) = (T^T g) . z``).  The expansion
matrix of the FE part is kept so that results carry the full FE field.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from discrete.errors import ModelError
from discrete.linear_system import LinearSystem
from discrete.nonsmooth import ExternalForce, MotionLaw, Problem
from discrete.nonsmooth.problem import ProblemSpec

from ..assembly import FEModel
from discrete.linear.reduction import ReducedModel, reduce


@dataclass
class NodeRef:
    """A DOF of the FE model (``x``, ``dof``) or a lumped body (``body``)."""

    x: float | None = None
    dof: str | None = None
    body: str | None = None


@dataclass
class Body:
    name: str
    inertia: float
    x0: float = 0.0
    v0: float = 0.0


@dataclass
class Spring:
    a: NodeRef | None        # None = ground
    b: NodeRef | None
    k: float = 0.0
    c: float = 0.0


@dataclass
class ElementSpec:
    """A nonsmooth element before its ``g`` is known: the constructor (Friction, Gap, ...),
    its keyword arguments, and the coordinate s = sum_k ratio_k * DOF_k."""

    cls: type
    kwargs: dict
    terms: list              # [(NodeRef, ratio)]


@dataclass
class ForceSpec:
    ref: NodeRef
    value: float = 0.0
    amplitude: float = 0.0
    omega: float = 0.0
    phase: float = 0.0


@dataclass
class DriverSpec:
    ref: NodeRef
    law: MotionLaw


@dataclass
class ReductionSpec:
    modes: int
    static_correction: bool = True
    threshold: float = 0.95


@dataclass
class HybridModel:
    """Everything a hybrid simulation needs, before compilation."""

    fe: FEModel
    bodies: list[Body] = field(default_factory=list)
    springs: list[Spring] = field(default_factory=list)
    elements: list[ElementSpec] = field(default_factory=list)
    forces: list[ForceSpec] = field(default_factory=list)
    drivers: list[DriverSpec] = field(default_factory=list)
    reduction: ReductionSpec | None = None
    initial_velocity: float = 0.0          # uniform velocity of the primary field (rigid translation)
    initial_field: np.ndarray | None = None   # full FE initial displacement / velocity vectors
    initial_field_velocity: np.ndarray | None = None
    rayleigh: tuple[float, float] = (0.0, 0.0)   # viscous C = alpha M + beta K on the FE part
    damping_table: object = None           # [damping]: how psi of the segments becomes viscous (time domain)
    forcing_omegas: tuple = ()             # frequencies of the harmonic forcing (the psi reference)
    initial_harmonic: bool = False         # start from the steady state of the linear FE model under the forces
    title: str = ""
    superelement_dofs: dict = field(default_factory=dict)   # "NAME:DOF" -> FE DOF index ([[superelement]])


@dataclass
class CompiledHybrid:
    """The problem handed to the solvers and the maps back to the FE field."""

    system: LinearSystem          # the (reduced) FE system plus lumped bodies
    T: np.ndarray | sp.spmatrix   # FE full DOFs = T @ (first n_fe_red DOFs of ``system``)
    n_fe: int                     # number of FE (reduced) DOFs at the start of ``system``
    reduced: ReducedModel | None
    restitution_report: dict | None
    warnings: list[str]
    elements: list
    drivers: dict
    forces: list
    x0: np.ndarray
    v0: np.ndarray
    coupling: np.ndarray = None
    damping_report: object = None         # how psi became viscous damping (time domain)
    spring_g: list = field(default_factory=list)   # coordinate vector of every [[spring]] / [[damper]] (outputs)
    held: dict = field(default_factory=dict)       # full FE DOF of a support or driver -> its solved coordinate
    _problem: Problem | None = None

    @property
    def problem(self) -> Problem:
        """The event-driven solver's :class:`Problem` (dense; built on first use)."""
        if self._problem is None:
            self._problem = Problem(self.system, self.elements, drivers=self.drivers, forces=self.forces,
                                    x0=self.x0, v0=self.v0)
        return self._problem

    def spec(self) -> ProblemSpec:
        """The problem without its forcing frequency fixed (time integrators, steady states)."""
        return ProblemSpec(system=self.system, elements=self.elements, drivers=self.drivers, forces=self.forces,
                           x0=self.x0, v0=self.v0, damping_report=self.damping_report)

    def fe_row(self, j: int) -> np.ndarray:
        """The row over the solved coordinates that gives the full FE DOF j (x_j = row . q)."""
        row = np.zeros(self.system.n_dofs)
        Tj = self.T[j]
        row[:self.n_fe] = np.asarray(Tj.toarray() if sp.issparse(Tj) else Tj).ravel()
        return row

    def field(self, x: np.ndarray) -> np.ndarray:
        """Full FE DOF vectors from system states: x is (n_dofs_system, n_times) -> (n_times, n_fe_full)."""
        return np.asarray((self.T @ np.asarray(x)[: self.n_fe]).T)


# -------------------------------------------------------------------- helpers
def fe_dof(fe: FEModel, ref: NodeRef, where: str) -> int:
    """Index of the FE DOF at ``ref.x`` with field ``ref.dof`` (default: the primary field)."""
    sys_ = fe.system
    fld = ref.dof or fe.model.fields[0]
    if fld not in fe.model.fields:
        raise ModelError(where, "dof", fld, "one of " + ", ".join(map(repr, fe.model.fields))
                         + f" (the DOFs of physics = {fe.model.physics!r})")
    L = fe.model.length
    if ref.x is None or not -1e-12 * L <= ref.x <= L * (1 + 1e-12):
        raise ModelError(where, "x", ref.x, f"a node position on the model, 0 <= x <= {L:g}")
    return sys_.dof_index(field=fld, x=ref.x, where=where)


# -------------------------------------------------------------------- compile
def compile_hybrid(model: HybridModel) -> CompiledHybrid:
    """Build the :class:`Problem` (full or reduced FE part plus lumped bodies)."""
    fe = model.fe
    base = fe.system
    nfe = base.n_dofs
    warn: list[str] = []
    # drivers: the driven FE DOFs become constrained (prescribed motion)
    drv_full: dict[int, MotionLaw] = {}
    for i, d in enumerate(model.drivers, 1):
        j = fe_dof(fe, d.ref, f"[[driver]] #{i}")
        if j in drv_full:
            raise ModelError(f"[[driver]] #{i}", "x", d.ref.x, "a DOF not driven by another [[driver]]")
        if j in set(base.constrained.tolist()):
            raise ModelError(f"[[driver]] #{i}", "x", d.ref.x,
                             f"a DOF not held by a [[support]] ({base.label(j)} is held at zero by a support "
                             "and cannot also be driven: remove the support or the driver)")
        drv_full[j] = d.law
    constrained = np.union1d(base.constrained, np.array(sorted(drv_full), dtype=int))
    alpha, beta = model.rayleigh
    Cfe = base.C + alpha * base.M + beta * base.K if (alpha or beta) else base.C
    system = LinearSystem(M=base.M, K=base.K, C=Cfe, H=base.H, dof_field=base.dof_field, dof_x=base.dof_x,
                          dof_name=base.dof_name, constrained=constrained,
                          rigid_modes=_rigid_after(base, constrained), title=base.title, physics=base.physics)
    held = set(constrained.tolist())
    names = [b.name for b in model.bodies]
    if len(set(names)) != len(names):
        raise ModelError("[[body]]", "name", names, "unique body names")

    def resolve(ref: NodeRef, where: str):
        """('fe', full index) or ('body', body index)."""
        if ref.body is not None and ref.body in model.superelement_dofs:   # a super-element DOF (fem/superelement.py)
            return ("fe", model.superelement_dofs[ref.body])
        if ref.body is not None:
            if ref.body not in names:
                raise ModelError(where, "body", ref.body, "one of " + ", ".join(map(repr, names)) if names
                                 else "a [[body]] name (no bodies defined)")
            return ("body", names.index(ref.body))
        return ("fe", fe_dof(fe, ref, where))

    el_terms = []
    for i, es in enumerate(model.elements, 1):
        where = f"[[{getattr(es.cls, 'kind', 'element')}]] {es.kwargs.get('name', i)!r}"
        terms = [(resolve(r, where), ratio) for r, ratio in es.terms]
        if all(kind == "fe" and j in held for (kind, j), _ in terms):
            (kind, j), _ = terms[0]
            raise ModelError(where, "x", es.terms[0][0].x,
                             f"a free DOF ({system.label(j)} is held by a support or driver, so the element "
                             "would never act)")
        el_terms.append(terms)
    f_terms = [resolve(fs.ref, f"[[force]] #{i}") for i, fs in enumerate(model.forces, 1)]
    s_terms = [[None if r is None else resolve(r, f"[[spring]] #{i}") for r in (s.a, s.b)]
               for i, s in enumerate(model.springs, 1)]
    coupling = set()
    for terms in el_terms:
        coupling |= {j for (kind, j), _ in terms if kind == "fe" and j not in held}
    for kind, j in f_terms:
        if kind == "fe" and j not in held:
            coupling.add(j)
    for pair in s_terms:
        coupling |= {r[1] for r in pair if r is not None and r[0] == "fe" and r[1] not in held}
    coupling = np.array(sorted(coupling), dtype=int)

    reduced = None
    report = None
    if model.reduction is not None:
        spec = model.reduction
        reduced = reduce(system, coupling, spec.modes, static_correction=spec.static_correction,
                         threshold=spec.threshold)
        if model.reduction.static_correction:
            kept = set(reduced.coupling.tolist())
            lost = [int(j) for j in coupling if int(j) not in kept]
            if lost:  # pragma: no cover - reduce keeps them by construction; guard the contract
                raise ModelError("[reduction]", "coupling DOF", system.label(lost[0]), "kept by the reduction")
        red_sys = reduced.system
        T = reduced.T
        report = reduced.report()
        report["restitution_by_dof"] = {system.label(int(j)): float(r) for j, r in zip(reduced.coupling, reduced.restitution)}
        warn += list(reduced.warnings)
        # map FE drivers into the reduced system (boundary DOFs keep their labels in order)
        Mred, Kred, Cred, Hred = red_sys.M, red_sys.K, red_sys.C, red_sys.H
        dof_field, dof_x, dof_name = red_sys.dof_field, red_sys.dof_x, red_sys.dof_name
        red_constrained = red_sys.constrained
        cl = red_sys.constrained.tolist()
        idx_map = {jf: cl[list(system.constrained).index(jf)] for jf in drv_full}
        held_map = {int(jf): cl[k] for k, jf in enumerate(system.constrained)}
    else:
        T = sp.identity(nfe, format="csr")
        Mred, Kred, Cred, Hred = system.M, system.K, system.C, system.H
        dof_field, dof_x, dof_name = system.dof_field, system.dof_x, system.dof_name
        red_constrained = system.constrained
        idx_map = {jf: jf for jf in drv_full}
        held_map = {int(jf): int(jf) for jf in system.constrained}
    nr = Mred.shape[0]
    nb = len(model.bodies)
    n = nr + nb
    # lumped bodies and springs
    M = sp.lil_matrix((n, n))
    M[:nr, :nr] = sp.csr_matrix(Mred)
    K = sp.lil_matrix((n, n))
    K[:nr, :nr] = sp.csr_matrix(Kred)
    C = sp.lil_matrix((n, n))
    C[:nr, :nr] = sp.csr_matrix(Cred)
    H = sp.lil_matrix((n, n))
    H[:nr, :nr] = sp.csr_matrix(Hred)
    for k, b in enumerate(model.bodies):
        M[nr + k, nr + k] = b.inertia

    Tt = T.T if sp.issparse(T) else T.T

    def gvec(terms) -> np.ndarray:
        g = np.zeros(n)
        for (kind, j), ratio in terms:
            if kind == "body":
                g[nr + j] += ratio
            else:
                e = np.zeros(nfe)
                e[j] = 1.0
                g[:nr] += ratio * np.asarray(Tt @ e).ravel()
        return g

    spring_g = []
    for (pair, s) in zip(s_terms, model.springs):
        g = gvec([(r, sgn) for r, sgn in zip(pair, (-1.0, 1.0)) if r is not None])
        spring_g.append(g)
        gg = sp.csr_matrix(np.outer(g, g))
        K = K + s.k * gg
        C = C + s.c * gg
    fields = np.concatenate([np.asarray(dof_field, dtype=object), np.full(nb, "x", dtype=object)])
    xs = np.concatenate([np.asarray(dof_x, float), np.full(nb, np.nan)])
    nm = np.concatenate([np.asarray(dof_name, dtype=object), np.array(names, dtype=object)])
    full_sys = LinearSystem(M=sp.csr_matrix(M), K=sp.csr_matrix(K), C=sp.csr_matrix(C), H=sp.csr_matrix(H),
                            dof_field=fields, dof_x=xs, dof_name=nm, constrained=red_constrained, title=model.title,
                            physics=system.physics)
    psi_report = None
    if full_sys.H.nnz and np.any(full_sys.H.data):
        from fem.modelfile.build.damping import psi_viscous

        full_sys, psi_report = psi_viscous(full_sys, model.damping_table, model.forcing_omegas)
        if psi_report is not None:
            warn += list(psi_report.warnings)
    elements = [es.cls(g=gvec(terms), **es.kwargs) for es, terms in zip(model.elements, el_terms)]
    forces = [ExternalForce(g=gvec([(ft, 1.0)]), value=fs.value, amplitude=fs.amplitude, omega=fs.omega, phase=fs.phase)
              for fs, ft in zip(model.forces, f_terms)]
    drivers = {idx_map[jf]: law for jf, law in drv_full.items()}
    # initial state: uniform velocity of the primary field, given FE fields, body states
    x0 = np.zeros(n)
    v0 = np.zeros(n)
    qf0 = np.zeros(nfe) if model.initial_field is None else np.asarray(model.initial_field, float)
    vf0 = np.zeros(nfe) if model.initial_field_velocity is None else np.asarray(model.initial_field_velocity, float)
    if model.initial_velocity:
        vf0 = vf0 + model.initial_velocity * (system.dof_field == fe.model.fields[0])
    if model.initial_harmonic:
        q_h, v_h = linear_steady_state(system, fe, model.forces, model.superelement_dofs)
        qf0, vf0 = qf0 + q_h, vf0 + v_h
    if np.any(qf0) or np.any(vf0):
        if reduced is None:
            x0[:nr], v0[:nr] = qf0, vf0
        else:
            Td = reduced.T
            x0[:nr] = np.linalg.lstsq(Td, qf0, rcond=None)[0]
            v0[:nr] = np.linalg.lstsq(Td, vf0, rcond=None)[0]
            resid = np.linalg.norm(Td @ v0[:nr] - vf0) / max(np.linalg.norm(vf0), 1e-300)
            if resid > 1e-6 and np.any(vf0):
                warn.append(f"the initial velocity field is represented by the reduced basis only to "
                            f"{resid:.2e} (relative least-squares residual)")
    for k, b in enumerate(model.bodies):
        x0[nr + k], v0[nr + k] = b.x0, b.v0
    return CompiledHybrid(system=full_sys, T=T, n_fe=nr, reduced=reduced, restitution_report=report,
                          damping_report=psi_report,
                          warnings=warn, elements=elements, drivers=drivers, forces=forces, x0=x0, v0=v0,
                          coupling=coupling, spring_g=spring_g, held=held_map)


def linear_steady_state(system: LinearSystem, fe: FEModel, forces: list, index: dict | None = None
                        ) -> tuple[np.ndarray, np.ndarray]:
    """Displacement and velocity at t = 0 of the steady response of the linear (undamped unless C is
    given) FE system to the harmonic forces ``F sin(omega t + phase)``: a starting state that removes
    the slowly decaying free transient of lightly damped nonsmooth runs."""
    f = system.free
    q = np.zeros(system.n_dofs)
    v = np.zeros(system.n_dofs)
    for i, F in enumerate(forces, 1):
        if not F.amplitude:
            continue
        if F.ref.body is not None and F.ref.body not in (index or {}):
            continue                     # a force on a lumped body: not part of the FE model's steady state
        j = index[F.ref.body] if F.ref.body is not None else fe_dof(fe, F.ref, f"[[force]] #{i}")
        rhs = np.zeros(system.n_dofs)
        rhs[j] = F.amplitude
        w = F.omega
        Z = sp.csc_matrix(system.free_block(system.K) - w * w * system.free_block(system.M)
                          + 1j * w * system.free_block(system.C))
        U = spla.spsolve(Z, rhs[f].astype(complex))      # u = Im(U e^{i(w t + phase)})
        ph = np.exp(1j * F.phase)
        q[f] += np.imag(U * ph)
        v[f] += np.imag(1j * w * U * ph)
    return q, v


def _rigid_after(base: LinearSystem, constrained: np.ndarray):
    R = base.rigid_modes
    if R is None or R.shape[1] == 0:
        return R
    if constrained.size == 0:
        return R
    N = sla.null_space(R[constrained], rcond=1e-12)
    return R @ N if N.size else R[:, :0]
