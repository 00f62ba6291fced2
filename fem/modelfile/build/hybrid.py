"""Hybrid model files -> :class:`fem.hybrid.HybridModel`: the FE shaft (assembled once) plus lumped
bodies, springs, drivers, nonsmooth elements, forces, distributed friction, reduction, Rayleigh
damping and the initial state (see docs/hybrid.md)."""
from __future__ import annotations

from discrete.errors import ModelError
from discrete.nonsmooth import MotionLaw

from ...assembly import assemble
from ...hybrid.build import (Body, DriverSpec, ElementSpec, ForceSpec, HybridModel, NodeRef, ReductionSpec, Spring,
                             fe_dof)
from ...hybrid.distributed import distributed_friction
from ..schema.lumped import NodeEnd
from .damping import linear_damping
from .elements import element_tables
from .lumped import forcing_omegas
from .fe import shaft_model


def _ref(t, where: str) -> NodeRef:
    """A single place: a lumped body (body = ..) or an FE DOF (x, dof)."""
    if t.body is not None:
        return NodeRef(body=t.body)
    if t.x is None:
        raise ModelError(where, "x", None, "the node position x = .. (with dof = ..) or body = \"name\" (required)")
    return NodeRef(x=t.x, dof=t.dof)


def _end(end, where: str):
    if isinstance(end, NodeEnd):
        return NodeRef(x=end.x, dof=end.dof)
    return None if end == "ground" else NodeRef(body=end)


def _terms(t, where: str) -> list:
    """Coordinate s of an element: sum of (NodeRef, ratio)."""
    if t.between is not None:
        ra, rb = t.ratios if t.ratios is not None else (1.0, 1.0)
        out = [(ref, r) for ref, r in zip((_end(e, where) for e in t.between), (-ra, rb)) if ref is not None]
        if not out:
            raise ModelError(where, "between", ["ground", "ground"], "at least one end that is not the ground")
        return out
    return [(_ref(t, where), 1.0 if t.ratio is None else t.ratio)]


def superelements(doc, fe):
    """The shaft's system joined with the ``[[superelement]]`` parts (fem/superelement.py), and the index of
    their DOFs by ``NAME:DOF``; the description files are found relative to the model file."""
    from pathlib import Path

    from ...superelement import join, read_superelement

    src = getattr(doc, "__source__", None)
    root = Path(src).parent if src is not None else Path.cwd()
    parts, seen = [], {}
    bodies = {b.name for b in doc.body}
    for i, t in enumerate(doc.superelement, 1):
        w = f"[[superelement]] #{i}"
        if t.name in seen:
            raise ModelError(w, "name", t.name, f"a name not used by [[superelement]] #{seen[t.name]}")
        seen[t.name] = i
        se = read_superelement(root / t.file, name=t.name, where=w)
        clash = sorted(bodies & {f"{t.name}:{d}" for d in se.dofs})
        if clash:
            raise ModelError(w, "name", t.name, f"a name whose DOFs are not [[body]] names ({clash[0]!r})")
        joined = {}
        for j in t.join:
            if j.dof not in se.dofs:
                raise ModelError(f"{w} join", "dof", j.dof, "one of the super-element's DOFs: "
                                 + ", ".join(map(repr, se.dofs[:8])) + (" ..." if se.n > 8 else ""))
            joined[j.dof] = fe_dof(fe, NodeRef(x=j.x, dof=j.field), f"{w} join")
        if len(set(joined.values())) != len(joined):
            raise ModelError(f"{w} join", "x", [j.x for j in t.join], "distinct shaft DOFs for distinct "
                             "super-element DOFs")
        parts.append((se, joined))
    return join(fe.system, parts)


def hybrid_model(doc) -> HybridModel:
    """The :class:`HybridModel` of a hybrid model file."""
    seen = {}
    for i, s in enumerate(doc.support, 1):
        if s.x in seen:
            raise ModelError(f"[[support]] #{i}", "x", s.x, f"a position without another support (contradictory "
                             f"supports: [[support]] #{seen[s.x]} is already at x = {s.x})")
        seen[s.x] = i
    fe = assemble(shaft_model(doc))
    grav = doc.constants.g
    model = HybridModel(fe=fe, title=doc.title)
    if doc.superelement:
        fe.system, model.superelement_dofs = superelements(doc, fe)
    for i, b in enumerate(doc.body, 1):
        if b.inertia_rate or b.reactive:
            key = "inertia_rate" if b.inertia_rate else "reactive"
            raise ModelError(f"[[body]] #{i}", key, getattr(b, key), "0 in hybrid models (variable mass is "
                             "available in lumped models)")
        model.bodies.append(Body(name=b.name, inertia=b.inertia, x0=b.x0, v0=b.v0))
    bodies = {b.name: b for b in model.bodies}
    links = [(f"[[spring]] #{i}", t, t.k, t.c) for i, t in enumerate(doc.spring, 1)]
    links += [(f"[[damper]] #{i}", t, 0.0, t.c) for i, t in enumerate(doc.damper, 1)]
    for w, t, k, c in links:
        if w.startswith("[[spring]]") and t.modulation is not None:
            raise ModelError(w, "modulation", t.modulation.model_dump(), "no modulation in hybrid models (a "
                             "pulsating spring is available in lumped models)")
        if w.startswith("[[spring]]") and t.psi:
            raise ModelError(w, "psi", t.psi, "0 in hybrid models (give segment psi or [damping])")
        if k == 0 and c == 0:
            raise ModelError(w, "k", 0.0, "a stiffness k > 0 and/or a damping c > 0")
        if any(abs(abs(r) - 1.0) > 0 for r in t.ratios):
            raise ModelError(w, "ratios", list(t.ratios), "[1, 1] in hybrid models")
        a, b = (_end(e, w) for e in t.between)
        if a is None and b is None:
            raise ModelError(w, "between", ["ground", "ground"], "at least one end that is not the ground")
        model.springs.append(Spring(a=a, b=b, k=k, c=c))
    for i, t in enumerate(doc.driver, 1):
        w = f"[[driver]] #{i}"
        if t.inertia:
            raise ModelError(w, "inertia", t.inertia, "0 in hybrid models (a driver prescribes an FE DOF)")
        if t.x is None:
            raise ModelError(w, "x", None, "the driven FE node x = .. (with dof = ..) (required key missing)")
        if t.programme is not None:
            raise ModelError(w, "programme", t.programme.law, "no programme law in hybrid models (programme "
                             "motion is available in lumped models)")
        model.drivers.append(DriverSpec(ref=NodeRef(x=t.x, dof=t.dof), law=MotionLaw(
            offset=t.offset, velocity=t.velocity, amplitude=t.amplitude, omega=t.omega, phase=t.phase)))

    def weight(t, where):
        b = bodies.get(t.body)
        if b is None:
            raise ModelError(where, "body", t.body, "a lumped [[body]] for normal = \"weight\"")
        return grav * b.inertia, b.inertia, 0.0

    names: set[str] = set()
    for table, i, t, name in element_tables(doc):
        where = f"[[{table}]] #{i}"
        cls, kw, flip = t.element(where, "hybrid", weight)
        if t.linearise is not None:
            kw.setdefault("linearise", t.linearise)
        terms = _terms(t, where)
        names.add(name)
        model.elements.append(ElementSpec(cls, dict(name=name, **kw), [(r, -x) for r, x in terms] if flip else terms))
    for i, t in enumerate(doc.force, 1):
        w = f"[[force]] #{i}"
        if t.between is not None:
            raise ModelError(w, "between", t.between, "x = .. or body = .. (a force acts on one place)")
        value = t.value
        if t.gravity:
            b = bodies.get(t.body)
            if b is None:
                raise ModelError(w, "body", t.body, "a lumped [[body]] for gravity = true")
            value -= grav * b.inertia
        model.forces.append(ForceSpec(ref=_ref(t, w), value=value, amplitude=t.amplitude, omega=t.omega,
                                      phase=t.phase))
    for i, t in enumerate(doc.distributed_friction, 1):
        w = f"[[distributed_friction]] #{i}"
        name = t.name or f"distributed{i}"
        if name in names:
            raise ModelError(w, "name", name, "a name not used by another element")
        names.add(name)
        specs = distributed_friction(fe, name=name, dof=t.dof, x_from=0.0 if t.from_ is None else t.from_,
                                     x_to=fe.model.length if t.to is None else t.to, intensity=t.intensity,
                                     static_intensity=t.static_intensity, mu=t.mu, radius=t.radius, g=grav, where=w)
        names.update(s.kwargs["name"] for s in specs)
        model.elements += specs
    if doc.reduction is not None:
        r = doc.reduction
        model.reduction = ReductionSpec(modes=r.modes, static_correction=r.static_correction, threshold=r.threshold)
    model.damping_table = doc.damping
    model.forcing_omegas = tuple(forcing_omegas(doc))
    if doc.damping is not None:
        kind = doc.damping.kind
        if kind == "modal":
            linear_damping(fe.system, doc.damping)          # the refusal, with its message
        if kind == "none":
            raise ModelError("[damping]", "type", "none", "'rayleigh', 'hysteretic' or 'viscous' in a hybrid model "
                             "(remove the dampers and psi values to run it undamped)")
        if kind == "hysteretic":
            fe.system = linear_damping(fe.system, doc.damping)
        model.rayleigh = (doc.damping.alpha, doc.damping.beta)
    model.initial_velocity = doc.initial.velocity
    model.initial_harmonic = doc.initial.state == "linear_steady_state"
    return model
