"""The load map of a lumped or hybrid drive (:class:`~.channels.LoadMap`): every element's deflection and
force, every gear pair's force, every driver's and support's reaction, from the drive's description in
its *named* coordinates.

Named coordinates (``x_n``, one per body, driver and -- hybrid -- solved FE coordinate) map to the
solved coordinates q by ``x_n = T q`` (a rigid gear ``x_b = u x_a`` makes x_b a dependent row of T).
In named coordinates the equations of motion read

    M a_n + C v_n + K x_n = G_s f_app + G_e f_el + H lam + (reactions at held coordinates)

(``M, C, K``: the named bodies' inertias and the links; ``G_e``, ``G_s``: the elements' and the applied
loads' coordinate vectors; ``H``: one column ``e_b - u e_a`` per gear, ``lam`` the gear force on its
driven body).  The residual ``r = M a_n + C v_n + K x_n - G_s f_app - G_e f_el`` is linear in the
signals of :class:`~.channels.LoadMap`, so are

* the gear forces: the rows of the gear-driven bodies, ``H_dep lam = r_dep`` (a unit triangular system:
  each driven body has one gear);
* the reactions at held coordinates (drivers; hybrid: supports too): ``R_h = r_h - (H lam)_h``.

Global damping that belongs to no link (Rayleigh, psi turned viscous in the time domain, the modal form)
is given in solved coordinates (``extra_C``) and acts on each solved coordinate's own named row; it is
reported as ``<coordinate>.damping_force`` so that every body's balance closes.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import ModelError
from .channels import Channel, LoadMap, unit_of


@dataclass
class Coordinates:
    """Named coordinates: ``names`` (n_named), ``T`` (n_named x n): x_n = T q; ``solved`` (n): the named
    row of each solved coordinate; ``motion``: "rotation" | "translation" | None per named coordinate;
    ``M``, ``C``, ``K`` (n_named x n_named; ``H`` the hysteretic loss stiffness, linear analyses only):
    the residual's matrices; ``extra_C`` / ``extra_H`` (n x n): damping in solved coordinates beyond the
    links; ``gears``: (name, index a, index b, ratio u) with x_b = u x_a; ``held``: (name, source, index)
    of the drivers and supports whose reactions are reported."""

    names: list
    T: np.ndarray
    solved: list
    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    H: np.ndarray | None = None
    motion: list | None = None
    extra_C: np.ndarray | None = None
    extra_H: np.ndarray | None = None
    gears: list = field(default_factory=list)
    held: list = field(default_factory=list)
    Mdot: np.ndarray | None = None
    """d M / dt of the named coordinates (a variable inertia M + t Mdot, seed 004; its reactive damping
    is part of ``C``)."""

    @property
    def n(self) -> int:
        return self.T.shape[1]

    def motion_of(self, g) -> str | None:
        """The kind of motion of a coordinate vector g (named): the common kind of its entries, else None."""
        if self.motion is None:
            return None
        kinds = {self.motion[i] for i in np.flatnonzero(np.asarray(g))}
        return kinds.pop() if len(kinds) == 1 else None

    def acts_on(self, g) -> dict:
        return {self.names[i]: float(g[i]) for i in np.flatnonzero(np.asarray(g))}


@dataclass
class LinkSpec:
    """A linear link (spring with its parallel dashpot, damper): force ``-(k s + c s' (+ i h s))`` on
    ``s = g . x_n``."""

    name: str
    source: str
    g: np.ndarray
    k: float = 0.0
    c: float = 0.0
    h: float = 0.0
    info: dict = field(default_factory=dict)


@dataclass
class ElementSpec:
    """A nonsmooth element (the solver's element, its protocol gives the outputs) and its named g."""

    element: object
    g: np.ndarray
    source: str
    info: dict = field(default_factory=dict)


@dataclass
class SourceSpec:
    """An applied load (a [[force]] table): its named coordinate vector."""

    name: str
    g: np.ndarray


@dataclass
class DriveLoads:
    """A drive's load map with what built it: ``coords``, ``links``, ``elements`` (in the solver's
    order: column j of ``Fe`` is element j) and ``sources`` (column k of ``Fa``), and ``residual``: the
    rows of r (the balance of every named coordinate) for the checks."""

    map: LoadMap
    coords: Coordinates
    links: list
    elements: list
    sources: list
    residual: dict
    locate: object = None          # end -> named coordinate vector (an [[output]]'s body or between end)
    end_motion: object = None      # end -> "rotation" | "translation" | None (the kind of its coordinate)

    def motion_of_ends(self, ends) -> str | None:
        """The common kind of motion of the ends (None: unknown or mixed)."""
        if self.end_motion is None:
            return None
        kinds = {self.end_motion(e) for e in ends if not (isinstance(e, str) and e == "ground")}
        return kinds.pop() if len(kinds) == 1 else None

    def named_vector(self, end) -> np.ndarray:
        """The named coordinate vector of a body / driver name (lumped) or an end the builder knows."""
        if self.locate is not None:
            return self.locate(end)
        g = np.zeros(len(self.coords.names))
        if end == "ground":
            return g
        if not isinstance(end, str):                # an FE node { x, dof } in a file without an FE shaft
            raise ModelError("[[output]]", "x", getattr(end, "x", end), "a body or driver name: FE nodes (x = ..) "
                             "are outputs of FE and hybrid files; bodies here: " + ", ".join(map(repr, self.coords.names)))
        if end not in self.coords.names:
            raise ModelError("[[output]]", "body", end, "one of " + ", ".join(map(repr, self.coords.names)))
        g[self.coords.names.index(end)] = 1.0
        return g


def _rows(n: int, n_el: int, n_src: int, rows: int, dtype=float) -> dict:
    return {k: np.zeros((rows, m), dtype=dtype) for k, m in (("X", n), ("V", n), ("A", n), ("Fe", n_el),
                                                              ("Fa", n_src))}


def build(coords: Coordinates, links: list, elements: list, sources: list, *, hysteretic: bool = False
          ) -> DriveLoads:
    """The default channels: each link's deflection and force, each element's outputs (its protocol's
    ``outputs``), each gear pair's force, each held coordinate's reaction, and the damping force of each
    solved coordinate with damping beyond the links.  ``hysteretic``: include the links' loss stiffness
    ``i h`` and ``H`` (a frequency response); time histories never do (psi is viscous there)."""
    n, T = coords.n, coords.T
    n_el, n_src, nn = len(elements), len(sources), len(coords.names)
    cplx = hysteretic and (any(ln.h for ln in links) or (coords.H is not None and np.any(coords.H))
                           or (coords.extra_H is not None and np.any(coords.extra_H)))
    dtype = complex if cplx else float
    lm = LoadMap.empty(n, n_el, n_src)
    for ln in links:
        gT = ln.g @ T
        motion = coords.motion_of(ln.g)
        info = dict(ln.info)
        lm.add(Channel(f"{ln.name}.deflection", "deflection", unit_of("deflection", motion), ln.source, ln.name,
                       info=info), X=gT)
        X = -ln.k * gT - (1j * ln.h * gT if hysteretic and ln.h else 0.0)
        lm.add(Channel(f"{ln.name}.force", "force", unit_of("force", motion), ln.source, ln.name,
                       acts_on=coords.acts_on(ln.g), info=info), X=X, V=-ln.c * gT)
    for j, es in enumerate(elements):
        el = es.element
        gT = es.g @ T
        motion = coords.motion_of(es.g)
        for q in el.outputs:
            if q == "force":
                e = np.zeros(n_el)
                e[j] = 1.0
                lm.add(Channel(f"{el.name}.force", "force", unit_of("force", motion), es.source, el.name,
                               acts_on=coords.acts_on(es.g), info=dict(es.info)), Fe=e)
            else:
                a, b, c = el.output_law(q)
                lm.add(Channel(f"{el.name}.{q}", q, unit_of(q, motion), es.source, el.name, info=dict(es.info)),
                       X=a * gT, V=b * gT, offset=c)
    for k, src in enumerate(sources):
        e = np.zeros(n_src)
        e[k] = 1.0
        lm.add(Channel(f"{src.name}.force", "force", unit_of("force", coords.motion_of(src.g)), "force", src.name,
                       acts_on=coords.acts_on(src.g), info={"note": "applied load ([[force]])"}), Fa=e)
    # the residual r of every named coordinate
    R = _rows(n, n_el, n_src, nn, dtype)
    R["A"] = coords.M @ T
    if coords.Mdot is not None and np.any(coords.Mdot):
        R["At"] = coords.Mdot @ T
    R["V"] = coords.C @ T
    R["X"] = (coords.K @ T).astype(dtype)
    if hysteretic and coords.H is not None and np.any(coords.H):
        R["X"] = R["X"] + 1j * (coords.H @ T)
    for j, es in enumerate(elements):
        R["Fe"][:, j] = -es.g
    for k, src in enumerate(sources):
        R["Fa"][:, k] = -src.g
    if coords.extra_C is not None and np.any(coords.extra_C):
        for j, row in enumerate(coords.solved):
            R["V"][row] += coords.extra_C[j]
            if np.any(coords.extra_C[j]):
                motion = coords.motion[row] if coords.motion else None
                lm.add(Channel(f"{coords.names[row]}.damping_force", "force", unit_of("force", motion), "damping",
                               coords.names[row], acts_on={coords.names[row]: 1.0},
                               info={"note": "damping beyond the [[damper]] and spring tables ([damping], psi)"}),
                       V=-coords.extra_C[j])
    if hysteretic and coords.extra_H is not None and np.any(coords.extra_H):
        for j, row in enumerate(coords.solved):
            R["X"][row] += 1j * coords.extra_H[j]
    # gears: H_dep lam = r_dep
    lam = None
    if coords.gears:
        ng = len(coords.gears)
        Hm = np.zeros((nn, ng))
        for k, (_, a, b, u) in enumerate(coords.gears):
            Hm[b, k] += 1.0
            Hm[a, k] -= u
        dep = [b for _, _, b, _ in coords.gears]
        Hinv = np.linalg.inv(Hm[dep])
        lam = {key: Hinv @ R[key][dep] for key in R}
        for k, (name, a, b, u) in enumerate(coords.gears):
            motion = coords.motion[b] if coords.motion else None
            lm.add(Channel(f"{name}.force", "force", unit_of("force", motion), "gear", name,
                           acts_on={coords.names[b]: 1.0, coords.names[a]: -u},
                           info={"between": [coords.names[a], coords.names[b]], "ratio": u,
                                 "note": "the force on the driven body; the driving one receives -ratio times it"}),
                   **{key: lam[key][k] for key in lam})
        for key in R:
            R[key] = R[key] - Hm @ lam[key]
    for name, source, h in coords.held:
        motion = coords.motion[h] if coords.motion else None
        lm.add(Channel(f"{name}.reaction", "reaction", unit_of("reaction", motion), source, name,
                       acts_on={coords.names[h]: 1.0}), **{key: R[key][h] for key in R})
    return DriveLoads(lm, coords, links, elements, sources, R)


# ------------------------------------------------------------------ linear analyses
@dataclass
class Linearised:
    """The elements of a drive in a linear analysis: the linearisation of each (``states``, one
    :class:`~discrete.nonsmooth.elements.base.Linearisation` per element), the added stiffness and
    damping in solved coordinates, the solved coordinates held, and the element forces as rows of the
    motion (``Lx``, ``Lv``, ``La``; frequency-dependent ones through :meth:`element_rows`)."""

    states: list
    K: np.ndarray
    C: np.ndarray
    held: list
    Lx: np.ndarray
    Lv: np.ndarray
    La: np.ndarray
    Lf: np.ndarray
    dynamic: list

    def element_rows(self, omega: float | None = None):
        """(Lx, Lv, La, Lf): f_el = Lx q + Lv q' + La q'' + Lf f_app, at the angular frequency omega (a
        motor's complex stiffness: -Z(omega) s; None: without it, as the undamped modes see it)."""
        if not self.dynamic or omega is None:
            return self.Lx, self.Lv, self.La, self.Lf
        Lx = self.Lx.astype(complex)
        for j, gq, lin in self.dynamic:
            Lx[j] = -lin.dynamic_stiffness(omega) * gq
        return Lx, self.Lv, self.La, self.Lf

    def records(self, elements) -> list[dict]:
        """What the linear analysis did with each element (printed and in the JSON)."""
        out = []
        for es, lin in zip(elements, self.states):
            el = es.element
            out.append({"element": el.name, "kind": es.source, "state": lin.state,
                        "declared": el.linearise is not None, "note": lin.note})
        return out


def linearise(loads: DriveLoads, free: np.ndarray) -> Linearised:
    """Each element in its declared (or default) linear state: stiffness and damping along its s
    (added to the solved K, C), or held (the one free solved coordinate it moves is constrained; its
    force is then that coordinate's constraint force).  ``free``: the solved coordinates not held by
    drivers or supports."""
    coords, R = loads.coords, loads.residual
    n = coords.n
    n_el = len(loads.elements)
    T = coords.T
    K, C = np.zeros((n, n)), np.zeros((n, n))
    Lx, Lv, La = np.zeros((n_el, n)), np.zeros((n_el, n)), np.zeros((n_el, n))
    Lf = np.zeros((n_el, len(loads.sources)))
    states, held, dynamic, holds = [], [], [], []
    free = set(int(j) for j in free)
    for j, es in enumerate(loads.elements):
        el = es.element
        lin = el.linearised()
        states.append(lin)
        gq = es.g @ T
        if lin.hold:
            moved = [i for i in np.flatnonzero(gq) if int(i) in free]
            where = f"[[{es.source}]] {el.name!r}"
            if len(moved) != 1:
                raise ModelError(where, "linearise", lin.state, "a state without a constraint for an element that "
                                 f"moves {len(moved)} free coordinates (a hold in a linear analysis constrains one "
                                 "coordinate): " + " | ".join(repr(s) for s in el.linear_states if s != lin.state))
            if moved[0] in held:
                raise ModelError(where, "linearise", lin.state, "a state without a constraint: another element "
                                 f"already holds {coords.names[coords.solved[moved[0]]]!r}")
            held.append(int(moved[0]))
            holds.append(j)
            continue
        K += lin.k * np.outer(gq, gq)
        C += lin.c * np.outer(gq, gq)
        Lx[j] = -lin.k * gq
        Lv[j] = -lin.c * gq
        if lin.Z is not None:
            dynamic.append((j, gq, lin))
    # a held element's force: the balance of the coordinate it holds, T^T r = 0 on that row
    for j in holds:
        gq = loads.elements[j].g @ T
        i = held[holds.index(j)]
        rows = {key: (T.T @ R[key])[i] for key in ("X", "V", "A", "Fe", "Fa")}
        fe = rows["Fe"].copy()
        fe[j] = 0.0                              # its own force moved to the left: -g_i F_j + rest = 0
        if any(fe[k] != 0 for k in holds if k != j):
            raise ModelError(f"[[{loads.elements[j].source}]] {loads.elements[j].element.name!r}", "linearise",
                             states[j].state, "one held element per coordinate (two constraints share one)")
        Lx[j] = (rows["X"] + fe @ Lx) / gq[i]
        Lv[j] = (rows["V"] + fe @ Lv) / gq[i]
        La[j] = (rows["A"] + fe @ La) / gq[i]
        Lf[j] = (rows["Fa"] + fe @ Lf) / gq[i]
    return Linearised(states, K, C, held, Lx, Lv, La, Lf, dynamic)
