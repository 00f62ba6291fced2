"""The load map of a hybrid model file (:func:`hybrid_loads`): the named coordinates are the solved ones
(the FE part, full or reduced, then the lumped bodies), so the residual of a held coordinate is the row
of the compiled equations of motion -- the reaction of a [[driver]] or [[support]] at its FE DOF (of the
reduced model when the FE part is reduced: Craig-Bampton keeps those DOFs physical).  Links are the
[[spring]] and [[damper]] tables, elements and applied loads those of the compiled problem."""
from __future__ import annotations

import numpy as np

from discrete.errors import ModelError
from discrete.loads import Coordinates, ElementSpec, LinkSpec, SourceSpec, build

from ..hybrid.build import NodeRef, fe_dof
from .names import force_name, link_name, node_name, support_name

ROTATION = {"theta", "w_x", "phi", "v_x"}
TRANSLATION = {"u", "w", "v"}


def _dense(A) -> np.ndarray:
    return np.asarray(A.toarray() if hasattr(A, "toarray") else A, dtype=float)


def hybrid_loads(doc, fe, compiled, system=None, *, extra_C=None, extra_H=None, hysteretic: bool = False,
                 sources=None, undamped: bool = False):
    """:class:`discrete.loads.DriveLoads` of a hybrid file: ``fe`` its FE model, ``compiled`` its compiled
    problem (``system``: the solved linear system, default the compiled one)."""
    comp = compiled
    sys_ = comp.system if system is None else system
    n = sys_.n_dofs
    names = []
    bodies = [b.name for b in doc.body]
    nr = comp.n_fe
    motion = []
    for i in range(n):
        if i >= nr:
            names.append(bodies[i - nr])
            motion.append(None)
        else:
            names.append(sys_.label(i))
            fld = sys_.dof_field[i]
            motion.append("rotation" if fld in ROTATION else "translation" if fld in TRANSLATION else None)
    links = []
    springs = list(enumerate(doc.spring, 1))
    dampers = list(enumerate(doc.damper, 1))
    for (table, i, t), g in zip([("spring", i, t) for i, t in springs] + [("damper", i, t) for i, t in dampers],
                                comp.spring_g):
        k = t.k if table == "spring" else 0.0
        links.append(LinkSpec(link_name(table, i, t), table, np.asarray(g, float), k=k, c=t.c,
                              info={"between": [_end(e) for e in t.between]}))
    held = []
    fem_model = fe
    for i, t in enumerate(doc.driver, 1):
        j = fe_dof(fem_model, NodeRef(x=t.x, dof=t.dof), f"[[driver]] #{i}")
        held.append((t.name or node_name("driver", i, t.x, t.dof), "driver", comp.held[j]))
    taken = {h for _, _, h in held}
    for i, t in enumerate(doc.support, 1):
        js = [j for j, s in comp.held.items() if s not in taken
              and abs(fem_model.system.dof_x[j] - t.x) <= 1e-9 * max(fem_model.model.length, 1e-300)]
        for j in js:
            fld = fem_model.system.dof_field[j]
            name = support_name(i, t, fld if len(js) > 1 else None)
            held.append((name, "support", comp.held[j]))
    coords = Coordinates(names=names, T=np.eye(n), solved=list(range(n)), M=_dense(sys_.M), C=_dense(sys_.C),
                         K=_dense(sys_.K), H=_dense(sys_.H), motion=motion, extra_C=extra_C, extra_H=extra_H,
                         held=held)
    el_tables = _element_tables(doc, comp)
    elements = [ElementSpec(el, np.asarray(el.g, float), table, info={"kind": el.kind})
                for el, table in zip(comp.elements, el_tables)]
    if sources is None:
        sources = [SourceSpec(force_name(i, t), np.asarray(F.g, float)) for (i, t), F in
                   zip(enumerate(doc.force, 1), comp.forces)]
    else:
        sources = [SourceSpec(name, np.eye(n)[j]) for name, j in sources]
    if undamped:
        for ln in links:
            ln.c = 0.0

    def locate(end) -> np.ndarray:
        if isinstance(end, str):
            g = np.zeros(n)
            if end == "ground":
                return g
            if end not in bodies:
                raise ModelError("[[output]]", "body", end, "a [[body]] name (" + ", ".join(map(repr, bodies))
                                 + ") or an FE node { x = .., dof = .. }" if bodies else "an FE node { x = .., dof = .. }")
            g[nr + bodies.index(end)] = 1.0
            return g
        j = fe_dof(fem_model, NodeRef(x=end.x, dof=end.dof), "[[output]]")
        return comp.fe_row(j)

    def end_motion(end):
        if isinstance(end, str):
            return None
        fld = end.dof or fem_model.model.fields[0]
        return "rotation" if fld in ROTATION else "translation" if fld in TRANSLATION else None

    loads = build(coords, links, elements, sources, hysteretic=hysteretic)
    loads.locate = locate
    loads.end_motion = end_motion
    return loads


def _end(e):
    return e if isinstance(e, str) else {"x": e.x, "dof": e.dof}


def _element_tables(doc, comp) -> list[str]:
    """The model-file table of every compiled element, in their order (distributed friction: its table)."""
    from ..modelfile.build.elements import element_tables

    out = [table for table, _, _, _ in element_tables(doc)]
    out += ["distributed_friction"] * (len(comp.elements) - len(out))
    return out
