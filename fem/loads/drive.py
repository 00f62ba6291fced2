"""Loads and named outputs of a :class:`fem.study.Study` (lumped and hybrid files): the drive's load map
for the time domain and for the linear analyses, the linearised system of the linear analyses (each
nonsmooth element in its declared state), and the named outputs of each analysis."""
from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from discrete.linear_system import LinearSystem
from discrete.loads import linearise

from .analyses import forced_outputs, modal_outputs, time_outputs
from .select import outputs_map


def drive_loads(study, linear: bool = False, system=None, *, extra_C=None, extra_H=None, hysteretic=False,
                sources=None, undamped: bool = False):
    """The :class:`discrete.loads.DriveLoads` of a lumped or hybrid study: time domain (the solved system
    of the simulation, psi viscous) or ``linear`` (``system``: the linear analyses' system; ``sources``:
    their applied loads instead of the [[force]] tables)."""
    if sources is not None:               # linear loads: (name, solved DOF, amplitude, omega^2) -> sources
        sources = [(name, dof) for name, dof, _, _ in sources]
    if study.kind == "lumped":
        from .lumped import lumped_loads

        spec = study.problem_spec(refuse=not linear)
        sys_ = system if system is not None else (study.linear_system() if linear else spec.system)
        loads = lumped_loads(study.doc, study.lumped, spec, sys_, extra_C=extra_C, extra_H=extra_H,
                             hysteretic=hysteretic, sources=sources, undamped=undamped)
    else:
        from .hybrid import hybrid_loads

        loads = hybrid_loads(study.doc, study.hybrid.fe, study.compiled, system, extra_C=extra_C, extra_H=extra_H,
                             hysteretic=hysteretic, sources=sources, undamped=undamped)
    return loads


def selected(study, loads):
    """The file's [[output]] channels (or the defaults) of ``loads``."""
    return outputs_map(getattr(study.doc, "output", ()), loads)


# ------------------------------------------------------------------ time domain
def simulation_outputs(study, res):
    """The named outputs of a simulation result (lumped: the solver's result; hybrid: its ``solver``)."""
    solver = res.solver if study.kind == "hybrid" else res
    loads = study.time_loads
    lm = selected(study, loads)
    a, f_app = solver.acceleration, solver.applied
    F = solver.element_forces
    if F is None:
        F = np.zeros((len(loads.elements), solver.t.size))
    if a is None:                         # regularised / Moreau-Jean: from the equations with the recorded forces
        problem = study.compiled.problem if study.kind == "hybrid" else study.problem_spec().problem()
        a, f_app = problem.recover(solver.t, solver.x, solver.v, F)
    return time_outputs(lm, solver.t, solver.x, solver.v, a, F, f_app, loads, solver.events)


# ------------------------------------------------------------------ linear analyses
class LinearModel:
    """The linear analyses' model of a lumped or hybrid study: ``system`` with every nonsmooth element
    in its declared linear state (``lin``: the :class:`discrete.loads.Linearised`), ``loads`` its load map
    (element forces still as signals: :meth:`load_map` substitutes them), ``records`` what was done with
    each element."""

    def __init__(self, study, base: LinearSystem, loads):
        self.loads = loads
        lin = linearise(loads, base.free)
        self.lin = lin
        self.records = lin.records(loads.elements)
        if not (np.any(lin.K) or np.any(lin.C) or lin.held):
            self.system = base
            return
        K = base.K + sp.csr_matrix(lin.K)
        C = base.C + sp.csr_matrix(lin.C)
        con = np.union1d(base.constrained, np.array(lin.held, dtype=int))
        rigid = None
        n = base.n_dofs
        if n <= 2000:
            free = np.setdiff1d(np.arange(n), con)
            ns = sla.null_space(K.toarray()[np.ix_(free, free)], rcond=1e-10) if free.size else np.zeros((0, 0))
            rigid = np.zeros((n, ns.shape[1]))
            rigid[free] = ns
        self.system = LinearSystem(M=base.M, K=K, C=C, H=base.H, G=base.G, dof_field=base.dof_field,
                                   dof_x=base.dof_x, dof_name=base.dof_name, constrained=con, rigid_modes=rigid,
                                   title=base.title, physics=base.physics)

    def load_map(self, omega: float | None = None, loads=None):
        """The selected channels with the element forces written as the linearised laws (at omega)."""
        lm = loads.map if loads is not None else self.loads.map
        return lm.substituted(*self.lin.element_rows(omega))


def modal_outputs_of(study, model: LinearModel, res):
    lm = selected(study, model.loads).substituted(*model.lin.element_rows(None))
    n = model.loads.coords.n
    return modal_outputs(lm, res.omega_rad_s, np.asarray(res.shapes)[:n])


def linear_sources(study, system) -> list:
    """The [[load]] tables of a linear forced analysis as applied-load sources: (name, solved DOF, complex
    amplitude, scaled by omega^2)."""
    import math

    from ..modelfile.build.linear import _locate

    out = []
    for i, t in enumerate(getattr(study.doc, "load", ()), 1):
        if t.waveform is not None:
            continue
        dof = _locate(system, t, f"[[load]] #{i}", "body")
        where = t.body if t.body is not None else f"x={t.x:g}" + (f" {t.dof}" if t.dof else "")
        out.append((f"load[{i}] {where}", dof, t.amplitude * np.exp(1j * math.radians(t.phase_deg)),
                    t.scaling == "omega2"))
    return out


def forced_outputs_of(study, model: LinearModel, res, sources):
    """Complex amplitudes of the outputs of a linear forced response (``res.full``: all DOFs;
    ``sources``: :func:`linear_sources`)."""
    n = model.loads.coords.n
    Q = np.asarray(res.full)[:, :n]
    sel = selected(study, model.loads)

    def loads_at(w):
        return np.array([a * (w * w if w2 else 1.0) for _, _, a, w2 in sources], dtype=complex) if sources else None

    def lm_at(w):
        return sel.substituted(*model.lin.element_rows(w))

    return forced_outputs(lm_at, res.omega_rad_s, Q, loads_at)
