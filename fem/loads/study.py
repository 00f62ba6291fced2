"""What each analysis of a model file reports as internal loads (docs/loads.md, JSON key ``section_loads``).

* modal (FE, hybrid FE part, rotor): the load shapes of every mode at every node -- the section
  loads of the mode shape as the analysis returns it (FE: mass-normalised, q = phi eta with the modal
  coordinate eta in kg^1/2 m; rotor: scaled to a largest DOF amplitude of 1), with lambda = i omega_n
  (rotor: the complex eigenvalue at the analysis speed);
* forced (FE, rotor unbalance response): complex amplitudes per frequency (speed) at every node, or at
  the key stations when nodes x frequencies exceed :data:`NODE_BUDGET`; reactions of supports, springs
  and bearings per frequency;
* simulate (hybrid): time histories at the key stations -- segment boundaries, attachments (points,
  supports, drivers, elements, forces), mid-spans between supports (bending) -- plus the node where
  each quantity peaks; reactions of the FE supports and drivers.

At a node where a section load may jump (an attachment), both sides are reported (``side``).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .elements import ElementSet
from .motion import ElementDamping, motion
from .recovery import end_forces, node_stations, station_values
from .section import UNITS, SectionLoads, elements_of

#: forced responses: every node while stations x frequencies stays within this (JSON size), else key stations
NODE_BUDGET = 5_000
#: hybrid runs: nodes with elements attached are key stations while there are at most this many
MAX_ELEMENT_MARKS = 8
CONVENTION = ("section load at x: force and moment of the material on the +x side acting on the material on the -x "
              "side (moment vectors by the right-hand rule; plane beams in the x-y plane: shear along +w, bending "
              "moment conjugate to the slope, M = E I w''); reactions: force or moment of the support on the structure")


@dataclass
class StudyLoads:
    """Section loads and reactions of one analysis' result, as written to the JSON (module notes)."""

    section: SectionLoads
    stations: str
    reactions: dict = field(default_factory=dict)
    normalisation: str | None = None
    t: np.ndarray | None = None
    notes: list = field(default_factory=list)

    @property
    def finite(self) -> bool:
        """Whether every value and reaction is finite (a model at the edge of double precision may overflow
        here while its analysis did not)."""
        arrays = list(self.section.quantities.values()) + [np.asarray(v) for v in self.reactions.values()]
        return all(np.all(np.isfinite(a)) for a in arrays)

    def to_dict(self) -> dict:
        """The JSON form: complex values for harmonic amplitudes and damped (rotor) modes, real ones for
        undamped modes (``omega_rad_s``) and time histories."""
        s = self.section
        lam = np.asarray(s.parameter) if s.kind == "modal" else None
        undamped = lam is not None and not np.any(lam.real) and not any(np.any(np.imag(v)) for v in s.quantities.values())
        real = s.kind in ("time", "static") or undamped
        values = {k: (v.real if real else v) for k, v in s.quantities.items()}
        d = {"quantities": list(values), "units": dict(s.units), "kind": s.kind, "stations": self.stations,
             "x": s.x, "side": [str(v) for v in s.side], "values": values, "convention": CONVENTION,
             "normalisation": self.normalisation}
        if s.kind == "harmonic":
            d["omega_rad_s"] = s.parameter
        elif undamped:
            d["omega_rad_s"] = lam.imag
        elif lam is not None:
            d["eigenvalues"] = lam
        if self.t is not None:
            d["t"] = self.t
        labels = list(self.reactions)
        d["reactions"] = {"labels": labels, "units": [_reaction_unit(k) for k in labels],
                          "values": [np.real(self.reactions[k]) if real else self.reactions[k] for k in labels]}
        d["notes"] = list(dict.fromkeys(list(s.notes) + list(self.notes)))
        return d


def _reaction_unit(label: str) -> str:
    field_name = label.split(":")[-1].split("@")[0].split()[-1]        # "driver theta@x=0" -> "theta"
    return "N·m" if field_name.startswith(("theta", "w_x", "phi")) else "N"


# ------------------------------------------------------------------ stations
def _nearest(xs: np.ndarray, marks) -> np.ndarray:
    """Stations whose x is the node nearest to one of the marks."""
    keep = np.zeros(xs.size, dtype=bool)
    for m in marks:
        keep |= np.isclose(xs, xs[np.argmin(np.abs(xs - m))], rtol=0, atol=1e-12 * max(1.0, abs(m)))
    return keep


def _station_x(es: ElementSet, stations) -> np.ndarray:
    element, xi, _ = stations
    return es.x0[element] + xi * es.length[element]


def _key_stations(es: ElementSet, q, stations, marks, **state):
    """The stations at the marks, plus the one where each quantity's largest |value| over all columns
    occurs (found chunk by chunk: the values at every station are never held for every column)."""
    keep = _nearest(_station_x(es, stations), marks)
    peak = None
    for part in _chunks(es, q, stations, **state):
        a = np.stack([np.abs(v).max(axis=1) for v in part.values()])      # (n_quantities, n_x)
        peak = a if peak is None else np.maximum(peak, a)
    keep[np.argmax(peak, axis=1)] = True
    return tuple(v[keep] for v in stations)


def _fe_marks(fe, extra=()) -> tuple[list, str]:
    model = fe.model
    ends = np.concatenate(([0.0], np.cumsum([s.length for s in model.segments])))
    marks = list(ends) + [p.x for p in model.points] + [s.x for s in model.supports] + list(extra)
    what = "segment ends, attachments"
    if model.physics == "bending":
        sup = sorted({s.x for s in model.supports})
        marks += [0.5 * (a + b) for a, b in zip(sup[:-1], sup[1:])]
        what += ", mid-spans between supports"
    return marks, what


def _fe_jumps(fe, extra_dofs=()) -> np.ndarray:
    """DOFs where a section load of the FE model may jump: supports, springs, points, loads."""
    from .reactions import spring_stiffness

    sys_ = fe.system
    M_nodal = (sys_.M - elements_of(fe).assembled(elements_of(fe).M)) if elements_of(fe).M is not None else sys_.M
    mass = np.flatnonzero(np.abs(M_nodal.diagonal()) > 1e-12 * max(abs(sys_.M).max(), 1e-300))
    return np.unique(np.concatenate([sys_.constrained, list(spring_stiffness(fe)), mass,
                                     np.asarray(list(extra_dofs), dtype=int)]).astype(int))


# ------------------------------------------------------------------ analyses
def study_loads(study, result):
    """The :class:`StudyLoads` of ``result`` (an analysis of ``study``), or None where the kind of model
    or analysis has no FE section loads (lumped and drive files, nonlinear steady states)."""
    from discrete.linear.harmonic import HarmonicResult
    from discrete.linear.modal import ModalResult

    if study.kind == "rotor":
        from ..rotor.modal import RotorModes
        from ..rotor.response import UnbalanceResponse

        if isinstance(result, RotorModes):
            return _rotor_modal(study, result)
        if isinstance(result, UnbalanceResponse):
            return _rotor_forced(study, result)
        return None
    if study.kind == "fe":
        if isinstance(result, ModalResult):
            return _fe_modal(study.fe_model, result.shapes, result.omega_rad_s)
        if isinstance(result, HarmonicResult):
            return _fe_forced(study, result)
        return None
    if study.kind == "hybrid":
        from ..hybrid.run import HybridResult

        if isinstance(result, ModalResult):
            comp = study.compiled
            shapes = np.asarray(comp.T @ result.shapes[:comp.n_fe])
            out = _fe_modal(study.fe_model, shapes, result.omega_rad_s)
            out.notes.append("the modes of the hybrid model (FE part reduced)" if comp.reduced is not None else
                             "the modes of the hybrid model (FE part full)")
            return out
        if isinstance(result, HybridResult):
            return hybrid_loads(study, result)
    return None


def _fe_modal(fe, shapes: np.ndarray, omegas: np.ndarray) -> StudyLoads:
    es = elements_of(fe)
    stations = node_stations(es, _fe_jumps(fe))
    lam = 1j * np.asarray(omegas, dtype=float)
    sl = _at(es, shapes, stations, eigenvalue=lam)
    return StudyLoads(section=sl, stations="every node (both sides where a load may jump)",
                      normalisation="mode shapes mass-normalised (phi^T M phi = 1): loads per unit modal coordinate "
                                    "eta (q = phi eta, eta in kg^0.5 m)")


#: columns (frequencies, modes, samples) recovered at a time: bounds the element end forces held in memory
CHUNK = 128


def _chunks(es: ElementSet, q, stations, *, omega=None, eigenvalue=None, qd=None, qdd=None, damping=None,
            speed=0.0):
    """{quantity: (n_x, n_columns of the chunk)} for consecutive chunks of the columns of q."""
    q = np.asarray(q)
    q2 = q[:, None] if q.ndim == 1 else q
    n_t = q2.shape[1]
    dmp = damping if isinstance(damping, ElementDamping) else ElementDamping.of(damping)
    element, xi, side = stations
    used, rows = np.unique(element, return_inverse=True)

    def cut(v, sl):
        return v[..., sl] if v is not None and np.ndim(v) >= 1 and np.shape(v)[-1] == n_t else v

    for a in range(0, n_t, CHUNK):
        sl = slice(a, a + CHUNK)
        mo = motion(es.n_dofs, q2[:, sl], cut(qd, sl), cut(qdd, sl), cut(omega, sl), cut(eigenvalue, sl))
        f = end_forces(es, mo, dmp, speed=cut(speed, sl), elements=used)
        yield station_values(es, f, mo, dmp, element, xi, side, speed=cut(speed, sl), rows=rows)


def _at(es: ElementSet, q, stations, *, omega=None, eigenvalue=None, damping=None, **state) -> SectionLoads:
    """The section loads at ``stations`` for every column of q (recovered chunk by chunk)."""
    parts = list(_chunks(es, q, stations, omega=omega, eigenvalue=eigenvalue, damping=damping, **state))
    vals = {k: np.concatenate([p[k] for p in parts], axis=1) for k in parts[0]}
    dmp = damping if isinstance(damping, ElementDamping) else ElementDamping.of(damping)
    kind = "harmonic" if omega is not None else "modal" if eigenvalue is not None else \
        ("time" if state.get("qd") is not None or state.get("qdd") is not None else "static")
    parameter = None if omega is None and eigenvalue is None else np.atleast_1d(omega if omega is not None else eigenvalue)
    element, xi, side = stations
    return SectionLoads(x=_station_x(es, stations), quantities=vals, units={k: UNITS[k] for k in vals}, side=side,
                        element=element, kind=kind, parameter=parameter, notes=[dmp.note] if dmp.note else [])


def _fe_forced(study, res) -> StudyLoads:
    from ..modelfile.build import linear as build_linear
    from .reactions import support_reactions

    fe = study.fe_model
    if res.full is None:
        return None
    system = fe.system
    spec = build_linear.forced_spec(study.doc, system)
    damping = build_linear.damping(study.doc.damping)
    om = res.omega_rad_s
    F = spec.force[:, None] + (om**2)[None, :] * (spec.force_w2[:, None] if spec.force_w2 is not None else 0.0)
    loaded = np.flatnonzero(np.any(F != 0, axis=1))
    es = elements_of(fe)
    stations = node_stations(es, _fe_jumps(fe, loaded))
    Q = res.full.T
    what = "every node (both sides where a load may jump)"
    if stations[0].size * om.size > NODE_BUDGET:
        marks, kinds = _fe_marks(fe, system.dof_x[loaded])
        stations = _key_stations(es, Q, stations, marks, omega=om, damping=damping)
        what = f"key stations ({kinds}, and where each quantity peaks): nodes x frequencies > {NODE_BUDGET}"
    full = _at(es, Q, stations, omega=om, damping=damping)
    reactions = support_reactions(fe, Q, omega=om, force=F, damping=damping)
    return StudyLoads(section=full, stations=what, reactions=reactions,
                      notes=["complex amplitudes, x(t) = Re(X e^{i omega t}), one column per frequency"])


# ------------------------------------------------------------------ rotors
def _rotor_jumps(rs) -> np.ndarray:
    """DOFs where a rotor's section loads may jump: discs, couplings, bearings, supports."""
    es = elements_of(rs)
    nodal_M = rs.M - es.assembled(es.M)
    nodal_K = rs.K0 - es.assembled(es.K)
    scale_m, scale_k = max(abs(rs.M).max(), 1e-300), max(abs(rs.K0).max(), 1e-300)
    dofs = set(np.flatnonzero(np.abs(nodal_M.diagonal()) > 1e-12 * scale_m).tolist())
    dofs |= set(np.flatnonzero(np.abs(nodal_K.diagonal()) > 1e-12 * scale_k).tolist())
    dofs |= set(rs.constrained.tolist())
    for b in rs.rotor.bearings:
        node = rs.node(b.x)
        dofs |= {int(rs.node_dofs[f][node]) for f in ("v", "w")}
    return np.asarray(sorted(dofs), dtype=int)


def _rotor_modal(study, res) -> StudyLoads:
    rs = study.rotor
    es = elements_of(rs)
    stations = node_stations(es, _rotor_jumps(rs))
    sl = _at(es, res.shapes, stations, eigenvalue=res.eigenvalues, speed=float(res.speed_rad_s))
    return StudyLoads(section=sl, stations="every node (both sides where a load may jump)",
                      normalisation="mode shapes scaled to a largest DOF amplitude of 1 (m or rad): loads per unit "
                                    "of that amplitude, q = Re(phi e^{lambda t})",
                      notes=[f"modes at the speed {res.speed_rad_s:g} rad/s (gyroscopic moments included)"])


def _rotor_forced(study, res) -> StudyLoads:
    from ..modelfile.build import rotor as build_rotor
    from ..rotor.response import unbalance_load
    from .reactions import rotor_reactions

    rs = study.rotor
    es = elements_of(rs)
    w = res.speeds_rad_s
    Fu = unbalance_load(rs, build_rotor.response_spec(study.doc).unbalances)
    jumps = np.union1d(_rotor_jumps(rs), np.flatnonzero(Fu))
    stations = node_stations(es, jumps)
    Q = res.response.T
    what = "every node (both sides where a load may jump)"
    if stations[0].size * w.size > NODE_BUDGET:
        marks = [d.x for d in rs.rotor.discs] + [b.x for b in rs.rotor.bearings] + [0.0, rs.rotor.length]
        stations = _key_stations(es, Q, stations, marks, omega=w, speed=w)
        what = f"discs, bearings, ends and where each quantity peaks: nodes x speeds > {NODE_BUDGET}"
    sl = _at(es, Q, stations, omega=w, speed=w)
    reactions = rotor_reactions(rs, Q, omega=w, force=Fu[:, None] * (w**2)[None, :])
    return StudyLoads(section=sl, stations=what, reactions=reactions,
                      notes=["synchronous complex amplitudes at each speed (omega = spin speed), "
                             "y(t) = Re(Y e^{i Omega t}); bearing forces are the bearings' forces on the shaft"])


# ------------------------------------------------------------------ hybrid time histories
def hybrid_states(study, res) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Full FE q, q', q'' (n_fe, n_samples) at the samples of a hybrid result.  The accelerations come from
    the solved system's equations of motion at each record: M a = f(t) + sum g_i F_i - C v - K x on the free
    DOFs with the recorded element forces F_i (constraint forces in stick and persistent contact; the
    Moreau-Jean scheme records each step's mean impulse / dt) and the drivers' prescribed accelerations.  The
    regularised integrator records no element forces: its accelerations are the recorded velocities
    differentiated (second order, central), which its smooth solution allows."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla

    comp = res.compiled
    sol = res.solver
    idx = res.sample_index if res.sample_index is not None else np.searchsorted(sol.t, res.t)
    system = comp.system
    x, v, t = sol.x[:, idx], sol.v[:, idx], sol.t[idx]
    T, n_fe = comp.T, comp.n_fe
    if comp.elements and sol.element_forces is None:     # the regularised integrator records no element forces
        a = np.gradient(sol.v, sol.t, axis=1, edge_order=2)[:, idx] if sol.t.size > 2 else np.zeros_like(v)
        return np.asarray(T @ x[:n_fe]), np.asarray(T @ v[:n_fe]), np.asarray(T @ a[:n_fe])
    n = system.n_dofs
    a = np.zeros_like(x)
    for j, law in comp.drivers.items():
        a[j] = -law.amplitude * law.omega**2 * np.sin(law.omega * t + law.phase)
    rhs = -(system.K @ x) - (system.C @ v)
    for F in comp.forces:
        rhs += np.outer(F.g, F.value + F.amplitude * np.sin(F.omega * t + F.phase))
    if comp.elements and sol.element_forces is not None:
        G = np.array([el.g for el in comp.elements])
        rhs += G.T @ sol.element_forces[:, idx]
    f, c = system.free, system.constrained
    M = sp.csr_matrix(system.M)
    rhs_f = rhs[f] - (M[f][:, c] @ a[c] if c.size else 0.0)
    a[f] = spla.splu(sp.csc_matrix(M[f][:, f])).solve(np.asarray(rhs_f, dtype=float)).reshape(f.size, -1)
    return np.asarray(T @ x[:n_fe]), np.asarray(T @ v[:n_fe]), np.asarray(T @ a[:n_fe])


def hybrid_loads(study, res) -> StudyLoads:
    """Time histories of the FE part's section loads at the key stations of a hybrid run."""
    from .reactions import support_reactions

    fe = study.fe_model
    model = study.hybrid
    comp = res.compiled
    q, qd, qdd = hybrid_states(study, res)
    sys_ = fe.system
    element_x = sorted({float(fe.system.dof_x[j]) for j in comp.coupling})
    # elements at many nodes (distributed friction): their nodes are not all key stations, the peak is
    attached = (element_x if len(element_x) <= MAX_ELEMENT_MARKS else []) + [d.ref.x for d in model.drivers]
    attached_dofs = list(comp.coupling) + [sys_.dof_index(field=d.ref.dof or fe.model.fields[0], x=d.ref.x)
                                           for d in model.drivers]
    es = elements_of(fe)
    stations = node_stations(es, _fe_jumps(fe, attached_dofs))
    alpha, beta = model.rayleigh
    notes = []
    psi = comp.damping_report
    omega_ref = None
    if psi is not None and psi.method == "equivalent":
        omega_ref = psi.omega_ref
    elif psi is not None and psi.method == "modal":
        notes.append("the modal viscous form of psi has no element form: its damping forces are not in the section "
                     "loads")
    dmp = ElementDamping(alpha=alpha, beta=beta, viscous_loss_omega=omega_ref)
    marks, kinds = _fe_marks(fe, attached)
    stations = _key_stations(es, q, stations, marks, qd=qd, qdd=qdd, damping=dmp)
    sl = _at(es, q, stations, qd=qd, qdd=qdd, damping=dmp)
    reactions = support_reactions(fe, q, qd=qd, qdd=qdd, damping=_rayleigh(alpha, beta))
    driven = attached_dofs[len(comp.coupling):]
    if driven:                 # the torque / force each driver puts into the FE shaft
        C = sys_.C + alpha * sys_.M + beta * sys_.K
        rows = np.asarray(driven, dtype=int)
        R = (sys_.K[rows] @ q + C[rows] @ qd + sys_.M[rows] @ qdd)
        for k, j in enumerate(rows):
            reactions["driver " + sys_.label(int(j))] = R[k]
    if comp.elements and res.solver.element_forces is None:
        notes.append("accelerations from the recorded velocities (the regularised integrator records no element "
                     "forces): the inertia part is accurate to the sampling of the run")
    if comp.reduced is not None:
        notes.append(f"reduced FE part ({comp.reduced.T.shape[1]} coordinates): the field is the reduction's "
                     "expansion, so nodal equilibrium holds in the projected sense (exact for the full model)")
    return StudyLoads(section=sl, stations=f"key stations ({kinds}, attachments of elements and drivers, and where "
                                            "each quantity peaks)", reactions=reactions, t=res.t, notes=notes)


def _rayleigh(alpha, beta):
    from discrete.linear import Damping

    return Damping(type="rayleigh", alpha=alpha, beta=beta) if (alpha or beta) else None
