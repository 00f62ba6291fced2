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


def selected(study, loads, order: dict | None = None):
    """The file's [[output]] channels (or the defaults) of ``loads`` (``order``: see
    :func:`fem.loads.select.outputs_map`)."""
    return outputs_map(getattr(study.doc, "output", ()), loads, order)


# ------------------------------------------------------------------ time domain
def time_signals(study, res) -> dict:
    """The signals every output of a run is a function of, at every recorded instant: ``t``, ``x``, ``v``,
    ``a`` (the solved coordinates, drivers included), ``F`` (each element's force along s) and ``f`` (the
    applied loads), and ``notes``.  The event solver records a and f; the Moreau-Jean scheme records
    each step's mean impulse / dt as F, and a comes from the equations of motion with it; the regularised
    integrator records no element forces: a is the recorded velocity differentiated (second order), and
    the element forces are unknown (``F`` None)."""
    solver = res.solver if study.kind == "hybrid" else res
    loads = study.time_loads
    a, f_app, F = solver.acceleration, solver.applied, solver.element_forces
    notes = []
    problem = None
    if a is None or f_app is None:
        problem = study.compiled.problem if study.kind == "hybrid" else study.problem_spec().problem()
    if F is None and loads.elements:
        t = solver.t
        a = np.gradient(solver.v, t, axis=1, edge_order=2) if t.size > 2 else np.zeros_like(solver.v)
        f_app = problem.recover(t, solver.x, solver.v, np.zeros((len(loads.elements), t.size)))[1]
        notes.append("the regularised integrator records no element forces: the element forces, and the loads "
                     "that depend on them, are not outputs of this run; accelerations are the recorded velocities "
                     "differentiated")
    elif a is None:                       # Moreau-Jean: from the equations with the recorded forces
        F = np.zeros((0, solver.t.size)) if F is None else F
        a, f_app = problem.recover(solver.t, solver.x, solver.v, F)
    return {"t": solver.t, "x": solver.x, "v": solver.v, "a": a, "F": F, "f": f_app, "notes": notes,
            "events": solver.events}


def simulation_outputs(study, res, order: dict | None = None):
    """(named outputs, signals) of a simulation result (lumped: the solver's result; hybrid: its
    ``solver``); the signals are :func:`time_signals`'."""
    loads = study.time_loads
    lm = selected(study, loads, order)
    sig = time_signals(study, res)
    F = sig["F"]
    if F is None:                         # no element forces recorded: the outputs that need them are left out
        keep = [c.name for k, c in enumerate(lm.channels) if not np.any(lm.Fe[k])]
        lm = lm.take(keep)
        F = np.zeros((len(loads.elements), sig["t"].size))
    out = time_outputs(lm, sig["t"], sig["x"], sig["v"], sig["a"], F, sig["f"], loads, sig["events"])
    out.notes += sig["notes"]
    return out, sig


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


def modal_outputs_of(study, model: LinearModel, res, order: dict | None = None):
    """The load shape of every selected output for each mode shape of ``res`` (the linearised model)."""
    lm = selected(study, model.loads, order).substituted(*model.lin.element_rows(None))
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


def forced_outputs_of_study(study, res):
    """The named outputs of a lumped file's linear forced response ``res`` (complex amplitudes, element
    loads included): the linearised system with the motors' complex stiffness, the [[load]] tables as
    applied loads, the damping of the analysis (Rayleigh, hysteretic) in the reactions and gear forces."""
    from ..modelfile.build import linear as build_linear

    from discrete.linear.periodic_forced import PeriodicForcedResult

    if study.kind != "lumped" or res.full is None or isinstance(res, PeriodicForcedResult):
        return None                       # a periodic response: its harmonics are not one forced response
    system = study.linear_model.system
    if getattr(study.doc, "motor", None):
        system = study._with_motors(system)
    base = study.linear_system()
    damping = build_linear.damping(study.doc.damping)
    n = base.n_dofs
    Ks = system.K.toarray()[:n, :n]
    extra_C = extra_H = None
    if damping.type == "rayleigh":
        extra_C = damping.alpha * base.M.toarray() + damping.beta * Ks
    elif damping.type == "hysteretic":
        extra_H = 2 * damping.delta * Ks
    sources = linear_sources(study, base)
    loads = drive_loads(study, linear=True, system=base, extra_C=extra_C, extra_H=extra_H, hysteretic=True,
                        sources=sources, undamped=damping.type == "none")
    model = LinearModel(study, base, loads)
    if damping.type == "none":
        model.lin.Lv = 0.0 * model.lin.Lv
    out = forced_outputs_of(study, model, res, sources)
    if damping.type == "modal":
        out.notes.append("modal damping has no matrix form: the reactions and gear forces leave out its forces "
                         "(the element deflections and forces are exact)")
    return out
