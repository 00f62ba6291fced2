"""Named outputs of FE shafts, rods, beams and rotors (docs/outputs.md): the section loads of the shaft at
the stations a designer checks and the reactions of supports, springs, bearings and pedestals, as columns
of a :class:`fem.loads.analyses.NamedOutputs` for each analysis of an FE, hybrid or rotor file.

* Section loads (:func:`fem.loads.section_loads`, sign convention in docs/outputs.md): one column per
  quantity and station, ``shaft.<quantity>@x=<x>`` (``-``/``+`` for the two sides of a jump).  Default
  stations: the segment ends, supports, point attachments, loads, bearings, discs, element and driver
  attachments (up to :data:`MAX_ELEMENT_MARKS` of them), the mid-spans between supports (bending), both
  sides where a load may jump, plus the node where each quantity peaks over the whole result.  With
  ``[[output]]`` tables: exactly the stations asked for (``x``, ``quantity`` torque | moment | force
  (axial) | shear, ``side``, ``components`` y/z of a rotor).
* Reactions: ``<support>.reaction`` of every [[support]] DOF and spring to ground of an FE file
  (:func:`fem.loads.support_reactions`), ``<bearing>.force_y|z`` (``force_x`` of a thrust bearing) and
  ``<pedestal>.force_y|z`` of a rotor (:func:`fem.loads.rotor_reactions`); hybrid files take their
  support and driver reactions from the drive's load map (:mod:`fem.loads.hybrid`).

The values are those of :func:`fem.loads.section_loads` for the state of the analysis: a mode shape as
written in ``mode_shapes`` (lambda = i omega_n, or the rotor's complex eigenvalue), the complex amplitudes
of a forced response, or a time history (hybrid runs: accelerations from the solved equations of motion,
:func:`fem.loads.drive.time_signals`; rotor run-ups: the reduced coordinates' rates differentiated).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from discrete.errors import ModelError
from discrete.loads import Channel

from .elements import ElementSet
from .motion import ElementDamping, motion
from .names import SHAFT, bearing_names, section_name, support_name
from .recovery import end_forces, node_stations, station_values
from .section import elements_of

#: columns (frequencies, modes, samples) recovered at a time: bounds the element end forces held in memory
CHUNK = 1024
#: hybrid runs: nodes with elements attached are default stations while there are at most this many
MAX_ELEMENT_MARKS = 8
#: [[output]] quantity words of section loads -> the section quantities they name (components y, z of rotors)
SECTION_WORDS = {"torque": ("torque",), "force": ("axial_force",), "moment": ("bending_moment",),
                 "shear": ("shear_force",)}
UNIT = {"torque": "N m", "axial_force": "N", "bending_moment": "N m", "shear_force": "N"}   # = section.UNITS
ROTATIONS = ("theta", "w_x", "phi", "v_x", "theta_y", "theta_z")


@dataclass
class Columns:
    """Named columns of one source: ``channels`` and ``values`` (n_channels, n_columns of the analysis),
    ``notes`` (what they leave out or how they are scaled), ``order`` ({name: [[output]] index})."""

    channels: list = field(default_factory=list)
    values: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    order: dict = field(default_factory=dict)

    def add(self, channel: Channel, values, table: int | None = None) -> None:
        self.channels.append(channel)
        self.values.append(np.asarray(values))
        if table is not None:
            self.order[channel.name] = table

    def array(self, m: int) -> np.ndarray:
        return np.array(self.values).reshape(len(self.channels), m) if self.channels else np.zeros((0, m))

    def __iadd__(self, other: "Columns") -> "Columns":
        for c, v in zip(other.channels, other.values):
            self.add(c, v)
        self.order.update(other.order)
        self.notes += [n for n in other.notes if n not in self.notes]
        return self


def is_section_output(t) -> bool:
    """An ``[[output]]`` table that asks for a section load (x on the shaft, torque | moment | force | shear)."""
    return getattr(t, "x", None) is not None and t.quantity in SECTION_WORDS


# ------------------------------------------------------------------ stations
def _station_x(es: ElementSet, stations) -> np.ndarray:
    element, xi, _ = stations
    return es.x0[element] + xi * es.length[element]


def _nearest(xs: np.ndarray, marks) -> np.ndarray:
    """Stations whose x is the node nearest to one of the marks."""
    keep = np.zeros(xs.size, dtype=bool)
    for m in marks:
        keep |= np.isclose(xs, xs[np.argmin(np.abs(xs - m))], rtol=0, atol=1e-12 * max(1.0, abs(m)))
    return keep


def _chunks(es: ElementSet, q, stations, *, n_t: int | None = None, omega=None, eigenvalue=None, qd=None,
            qdd=None, damping=None, speed=0.0):
    """{quantity: (n_x, n_columns of the chunk)} for consecutive chunks of the columns of q.  ``q``, ``qd``,
    ``qdd`` are arrays (n_dofs, n_t) or callables of a slice of columns (with ``n_t``), so that a long
    history is never expanded to every DOF at once."""
    if not callable(q):
        q = np.asarray(q)
        q = q[:, None] if q.ndim == 1 else q
        n_t = q.shape[1]
    dmp = damping if isinstance(damping, ElementDamping) else ElementDamping.of(damping)
    element, xi, side = stations
    used, rows = np.unique(element, return_inverse=True)

    def cut(v, sl):
        if callable(v):
            return v(sl)
        return v[..., sl] if v is not None and np.ndim(v) >= 1 and np.shape(v)[-1] == n_t else v

    for a in range(0, n_t, CHUNK):
        sl = slice(a, a + CHUNK)
        mo = motion(es.n_dofs, cut(q, sl), cut(qd, sl), cut(qdd, sl), cut(omega, sl), cut(eigenvalue, sl))
        f = end_forces(es, mo, dmp, speed=cut(speed, sl), elements=used)
        yield station_values(es, f, mo, dmp, element, xi, side, speed=cut(speed, sl), rows=rows)


def _values(es: ElementSet, q, stations, **state) -> dict:
    parts = list(_chunks(es, q, stations, **state))
    return {k: np.concatenate([p[k] for p in parts], axis=1) for k in parts[0]}


#: default stations: the values at every node are kept from the peak search while stations x columns stay
#: within this (one pass over the columns), else recovered again at the chosen stations
KEEP_ALL = 4_000_000


def default_stations(es: ElementSet, q, jumps, marks, **state):
    """(stations, values) at the node stations at the marks (both sides where a load may jump), plus the
    station where each quantity's largest |value| over all columns occurs (found chunk by chunk)."""
    stations = node_stations(es, jumps)
    keep = _nearest(_station_x(es, stations), marks)
    peak, parts, n = None, [], 0
    for part in _chunks(es, q, stations, **state):
        a = np.stack([np.abs(v).max(axis=1) for v in part.values()])      # (n_quantities, n_x)
        peak = a if peak is None else np.maximum(peak, a)
        n += next(iter(part.values())).shape[1]
        if parts is not None:
            parts.append(part)
            if n * stations[0].size > KEEP_ALL:
                parts = None
    keep[np.argmax(peak, axis=1)] = True
    chosen = tuple(v[keep] for v in stations)
    if parts is None:
        return chosen, _values(es, q, chosen, **state)
    return chosen, {k: np.concatenate([p[k][keep] for p in parts], axis=1) for k in parts[0]}


def _quantities_of(es: ElementSet, t, table: str) -> list[str]:
    """The section quantities an [[output]] table names in this model."""
    base = SECTION_WORDS[t.quantity]
    have = list(es.quantities)
    out = []
    for q in base:
        if q in have:
            out.append(q)
            continue
        comps = getattr(t, "components", None) or ["y", "z"]
        for c in comps:
            if c not in ("y", "z"):
                raise ModelError(table, "components", t.components, "['y'], ['z'] or ['y', 'z'] (the planes of a "
                                 "rotor's bending moments and shear forces)")
            if f"{q}_{c}" in have:
                out.append(f"{q}_{c}")
    if not out:
        raise ModelError(table, "quantity", t.quantity, "a section load of this model: " + " | ".join(
            w for w, qs in SECTION_WORDS.items() if any(q in have or f"{q}_y" in have for q in qs)))
    return out


def section_columns(es: ElementSet, q, *, jumps, marks, tables=(), **state) -> Columns:
    """The section-load columns of the state(s) q: at the default stations, or (``tables``: [(index,
    [[output]] table)] asking for section loads) exactly at the stations asked for."""
    out = Columns()
    note = ElementDamping.of(state.get("damping")).note if not isinstance(state.get("damping"), ElementDamping) else ""
    if note:
        out.notes.append(note)
    if tables:
        asks = []
        for i, t in tables:
            where = f"[[output]] #{i}"
            qs = _quantities_of(es, t, where)
            side = t.side or "right"
            e, xi = es.locate(float(t.x), side, where="x")
            asks.append((i, t, qs, e, xi, side))
        stations = (np.array([a[3] for a in asks]), np.array([a[4] for a in asks]),
                    np.array([a[5] for a in asks], dtype=object))
        vals = _values(es, q, stations, **state)
        for k, (i, t, qs, e, xi, side) in enumerate(asks):
            x = float(es.x0[e] + xi * es.length[e])
            for qn in qs:
                comp = qn.rsplit("_", 1)[1] if qn.endswith(("_y", "_z")) else None
                name = (t.name + (f".{comp}" if comp and len(qs) > 1 else "")) if t.name else \
                    section_name(qn, x, t.side)
                out.add(_section_channel(name, qn, x, side, {"x": t.x, "quantity": t.quantity}), vals[qn][k], i)
        return out
    stations, vals = default_stations(es, q, jumps, marks, **state)
    xs = _station_x(es, stations)
    sides = stations[2]
    both = {round(float(x), 12) for x, s in zip(xs, sides) if s == "left"} & \
        {round(float(x), 12) for x, s in zip(xs, sides) if s == "right"}
    for qn in vals:
        for k, (x, s) in enumerate(zip(xs, sides)):
            x = float(x)
            name = section_name(qn, x, s if round(x, 12) in both else None)
            out.add(_section_channel(name, qn, x, str(s)), vals[qn][k])
    return out


def _section_channel(name: str, qn: str, x: float, side: str, output: dict | None = None) -> Channel:
    base = qn.rsplit("_", 1)[0] if qn.endswith(("_y", "_z")) else qn
    word = {"torque": "torque", "axial_force": "force", "bending_moment": "moment", "shear_force": "force"}[base]
    info = {"x": x, "side": side, "section_quantity": qn}
    if output:
        info["output"] = output
    return Channel(name, word, UNIT[base], "section", SHAFT, info=info)


# ------------------------------------------------------------------ reactions and FE DOFs
def fe_reaction_columns(fe, doc, reactions: dict, tables=()) -> Columns:
    """Named reaction columns of an FE file from :func:`fem.loads.support_reactions`' dict: every
    [[support]] (its name, else ``support[<i>] x=<x>``, the DOF where it holds several) and every
    [[point]] spring to ground (``point[<i>] x=<x>``)."""
    system = fe.system
    labels = system.labels()
    supports = list(enumerate(getattr(doc, "support", ()) or (), 1))
    points = list(enumerate(getattr(doc, "point", ()) or (), 1))
    tol = 1e-9 * max(fe.model.length, 1e-300)
    named = []
    for label, val in reactions.items():
        j = labels.index(label.split(":", 1)[1] if label.startswith("spring:") else label)
        x, fld = float(system.dof_x[j]), str(system.dof_field[j])
        at = [(i, t) for i, t in supports if abs(t.x - x) <= tol]
        if at:
            i, t = at[0]
            held = sum(1 for lb in reactions if abs(system.dof_x[labels.index(lb.split(":", 1)[-1])] - x) <= tol)
            name = support_name(i, t, fld if held > 1 else None)
        else:
            i = next((i for i, p in points if abs(p.x - x) <= tol), 0)
            name = f"point[{i}] x={x:g}" + (f" {fld}" if len(fe.model.fields) > 1 else "")
        named.append((name, fld, x, val))
    out = Columns()
    for name, fld, x, val in named:
        unit = "N m" if fld in ROTATIONS else "N"
        out.add(Channel(f"{name}.reaction", "reaction", unit, "support", name, info={"x": x, "dof": fld}), val)
    return _select_reactions(out, tables)


def _select_reactions(cols: Columns, tables) -> Columns:
    """All reaction columns (no [[output]] tables), or those the tables ask for (support = <name>, or x =
    <x> with quantity reaction), under the tables' names."""
    if not tables:
        return cols
    out = Columns()
    for i, t in tables:
        where = f"[[output]] #{i}"
        if t.support is not None:
            hit = [k for k, c in enumerate(cols.channels) if c.where == t.support or c.where.startswith(t.support + " ")]
            key, val = "support", t.support
        elif t.x is not None and t.quantity == "reaction":
            hit = [k for k, c in enumerate(cols.channels) if abs(c.info.get("x", np.inf) - t.x) <= 1e-9 * max(abs(t.x), 1.0)]
            key, val = "x", t.x
        else:
            continue
        if not hit:
            known = sorted({c.where for c in cols.channels})
            raise ModelError(where, key, val, ("a support or bearing: one of " + ", ".join(map(repr, known))) if known
                             else "a support or bearing (this model has none)")
        for k in hit:
            c = cols.channels[k]
            suffix = c.name[len(c.where):]                      # ".reaction", ".force_y", ...
            name = (t.name + (suffix if len(hit) > 1 else "")) if t.name else c.name
            out.add(Channel(name, c.quantity, c.unit, c.source, c.where, info={**c.info, "output": {key: val}}),
                    cols.values[k], i)
    return out


def node_columns(system, tables, mo) -> Columns:
    """[[output]] tables at an FE node (x, with displacement | velocity | acceleration): the DOF's motion
    (``dof`` or ``components``; default the primary field)."""
    out = Columns()
    fields = system.fields()
    for i, t in tables:
        if t.x is None or t.quantity not in ("displacement", "velocity", "acceleration"):
            continue
        comps = t.components or [t.dof or fields[0]]
        for comp in comps:
            j = system.dof_index(field=comp, x=t.x, where=f"[[output]] #{i}")
            series = {"displacement": mo.q, "velocity": mo.qd, "acceleration": mo.qdd}[t.quantity][j]
            where = f"x={t.x:g}" + (f" {comp}" if comp != fields[0] or t.components else "")
            name = (t.name + (f".{comp}" if t.components else "")) if t.name else f"{where}.{t.quantity}"
            kind = "rotation" if comp in ROTATIONS else "translation"
            from discrete.loads import unit_of

            out.add(Channel(name, t.quantity, unit_of(t.quantity, kind), "node", where,
                            info={"output": {"x": t.x, "dof": comp}}), series, i)
    return out


def check_tables(tables, kind: str) -> None:
    """What an [[output]] table may ask for in an FE or rotor file (one line per misuse)."""
    for i, t in tables:
        where = f"[[output]] #{i}"
        for key in ("element", "body", "between"):
            if getattr(t, key) is not None:
                raise ModelError(where, key, getattr(t, key), f"x = .. or support = .. in a {kind} file (elements, "
                                 "bodies and relative motions are outputs of lumped and hybrid files)")
        if kind == "rotor" and t.x is not None and not is_section_output(t):
            raise ModelError(where, "quantity", t.quantity, "torque | moment | force | shear at x in a rotor file "
                             "(orbits are [[unbalance_response.probe]] tables)")


# ------------------------------------------------------------------ marks and jumps
def fe_marks(fe, extra=()) -> list:
    """Segment ends, points, supports (and ``extra``), and mid-spans between supports (bending)."""
    model = fe.model
    ends = np.concatenate(([0.0], np.cumsum([s.length for s in model.segments])))
    marks = list(ends) + [p.x for p in model.points] + [s.x for s in model.supports] + list(extra)
    if model.physics == "bending":
        sup = sorted({s.x for s in model.supports})
        marks += [0.5 * (a + b) for a, b in zip(sup[:-1], sup[1:])]
    return marks


def fe_jumps(fe, extra_dofs=()) -> np.ndarray:
    """DOFs where a section load of the FE model may jump: supports, springs, points, loads."""
    from .reactions import spring_stiffness

    sys_ = fe.system
    es = elements_of(fe)
    M_nodal = (sys_.M - es.assembled(es.M)) if es.M is not None else sys_.M
    mass = np.flatnonzero(np.abs(M_nodal.diagonal()) > 1e-12 * max(abs(sys_.M).max(), 1e-300))
    return np.unique(np.concatenate([sys_.constrained, list(spring_stiffness(fe)), mass,
                                     np.asarray(list(extra_dofs), dtype=int)]).astype(int))


def rotor_jumps(rs, extra_dofs=()) -> np.ndarray:
    """DOFs where a rotor's section loads may jump: discs, couplings, bearings, supports, loads."""
    es = elements_of(rs)
    nodal_M = rs.M - es.assembled(es.M)
    nodal_K = rs.K0 - es.assembled(es.K)
    scale_m, scale_k = max(abs(rs.M).max(), 1e-300), max(abs(rs.K0).max(), 1e-300)
    dofs = set(np.flatnonzero(np.abs(nodal_M.diagonal()) > 1e-12 * scale_m).tolist())
    dofs |= set(np.flatnonzero(np.abs(nodal_K.diagonal()) > 1e-12 * scale_k).tolist())
    dofs |= set(rs.constrained.tolist()) | set(np.asarray(list(extra_dofs), dtype=int).tolist())
    for b in rs.rotor.bearings:
        node = rs.node(b.x)
        dofs |= {int(rs.node_dofs[f][node]) for f in ("v", "w")}
    return np.asarray(sorted(dofs), dtype=int)


def rotor_marks(rs) -> list:
    r = rs.rotor
    return [d.x for d in r.discs] + [b.x for b in r.bearings] + [0.0, r.length]


def rotor_reaction_columns(rs, reactions: dict, tables=()) -> Columns:
    """Named reaction columns of a rotor from :func:`fem.loads.rotor_reactions`' dict: ``<bearing>.force_y``
    (``force_z``, ``force_x``), ``<pedestal>.force_y|z`` (the ground on the pedestal), ``support[<i>] x=<x>
    <dof>.reaction`` (rigid supports)."""
    out = Columns()
    names = bearing_names(rs.rotor)
    for k, b in enumerate(rs.rotor.bearings):
        key = f"{b.name or f'bearing {k + 1}'}@x={b.x:g}"
        for comp in ("y", "z", "x"):
            v = reactions.get(f"{key}:F_{comp}")
            if v is not None:
                out.add(Channel(f"{names[k]}.force_{comp}", "reaction", "N", "bearing", names[k],
                                info={"x": float(b.x)}), v)
    for p in rs.rotor.pedestals:
        for comp in ("y", "z"):
            out.add(Channel(f"{p.name}.force_{comp}", "reaction", "N", "pedestal", p.name), reactions[f"pedestal {p.name}:F_{comp}"])
    for i, s in enumerate(rs.rotor.supports, 1):
        for d in s.dofs:
            v = reactions.get(f"{d}@x={float(s.x):.6g}")
            if v is not None:
                where = f"support[{i}] x={s.x:g}"
                out.add(Channel(f"{where} {d}.reaction", "reaction", "N m" if d in ROTATIONS else "N", "support",
                                where, info={"x": float(s.x), "dof": d}), v)
    return _select_reactions(out, tables)


# ------------------------------------------------------------------ hybrid time histories
def hybrid_damping(study, res) -> tuple[ElementDamping, list]:
    """The element damping of a hybrid run's FE part (Rayleigh, the equivalent viscous form of psi) and
    the notes on what the section loads leave out."""
    model = study.hybrid
    alpha, beta = model.rayleigh
    notes = []
    psi = res.compiled.damping_report
    omega_ref = None
    if psi is not None and psi.method == "equivalent":
        omega_ref = psi.omega_ref
    elif psi is not None and psi.method == "modal":
        notes.append("the modal viscous form of psi has no element form: its damping forces are not in the section "
                     "loads")
    if res.compiled.elements and res.solver.element_forces is None:
        notes.append("accelerations from the recorded velocities (the regularised integrator records no element "
                     "forces): the inertia part of the section loads is accurate to the sampling of the run")
    if res.compiled.reduced is not None:
        notes.append(f"reduced FE part ({res.compiled.reduced.T.shape[1]} coordinates): the field is the reduction's "
                     "expansion, so nodal equilibrium of the section loads holds in the projected sense")
    return ElementDamping(alpha=alpha, beta=beta, viscous_loss_omega=omega_ref), notes


def hybrid_marks(study) -> tuple[list, list]:
    """(marks, jump DOFs) of a hybrid file: the FE marks plus the nodes where elements (up to
    :data:`MAX_ELEMENT_MARKS`; distributed friction is left to the peak) and drivers act."""
    fe = study.fe_model
    comp = study.compiled
    sys_ = fe.system
    element_x = sorted({float(sys_.dof_x[j]) for j in comp.coupling})
    drivers = study.hybrid.drivers
    attached = (element_x if len(element_x) <= MAX_ELEMENT_MARKS else []) + [d.ref.x for d in drivers]
    dofs = list(comp.coupling) + [sys_.dof_index(field=d.ref.dof or fe.model.fields[0], x=d.ref.x) for d in drivers]
    return fe_marks(fe, attached), dofs
