"""A train as a nonsmooth problem for the time simulation and the steady states.

Pipeline (at the train's operating speed Omega; each shaft at Omega_i = ratio_i Omega)::

    shafts: own LinearSystem (bearings at their speed), gyroscopic Omega_i G_i
        --[Craig-Bampton per shaft: boundary = connection, driver, load, bearing, pedestal and
           ground-spring DOFs and the held DOFs; n fixed-interface modes]-->
    + bodies + the connections' linear remainders (K += k g g^T, C += c g g^T)
    + the connections' nonsmooth elements (s = g . x; gap/backlash, slip friction, periodic mesh stiffness)
    + the static transmission error as prescribed exogenous coordinates (s = g . q - e(t))
    + [[driver]] motions and [[force]] loads
    --> discrete.nonsmooth.ProblemSpec

Every coordinate becomes T^T g in the reduced coordinates (exact: g . (T z) = (T^T g) . z), the full
train DOFs are T z.  Matrices are projected as they are (T^T A T, not symmetrised): cross-coupled bearing
coefficients and the gyroscopic matrix keep their skew parts.  With the bearing, pedestal and ground-spring
DOFs on the boundary every rigid motion of a shaft lies in the span of its basis, so each shaft's force
balance holds in the reduced model as in the full one.

``eliminate_rigid``: a train whose rotation is free (no held or driven rotation: the gears turn freely
with the meshes unstrained) has a rigid-body motion R (K R = 0, C R = 0, g . R = 0 for every coordinate).
Its elastic motion is exactly the motion M-orthogonal to R, q = T_r y with R^T M q = 0 (one DOF eliminated
per rigid motion, solved from the constraint), whatever the loads (an unbalanced mean torque accelerates
the rigid train and leaves the vibration periodic): the steady states (HB, shooting) and the Floquet
analysis need that, their zeroth harmonic is otherwise singular.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from discrete.errors import ModelError
from discrete.linear.reduction import reduce
from discrete.linear_system import LinearSystem
from discrete.nonsmooth import ExternalForce, MotionLaw, Problem
from discrete.nonsmooth.problem import ProblemSpec

from .assembly import TrainSystem
from .forced import TrainLoad, rigid_candidates
from .loads import bearing_terms


@dataclass
class ReductionSpec:
    """Craig-Bampton per shaft: ``modes`` fixed-interface modes (``shaft_modes`` per shaft name)."""

    modes: int = 6
    shaft_modes: dict = field(default_factory=dict)
    static_correction: bool = True
    threshold: float = 0.95


@dataclass
class TrainDriver:
    """A prescribed motion of train DOF ``dof``."""

    dof: int
    law: MotionLaw


@dataclass
class CompiledTrain:
    """The nonsmooth problem of a train and the maps back to the train's DOFs."""

    ts: TrainSystem
    speed: float
    system: LinearSystem
    T: np.ndarray                     # train DOFs = T @ x[:n_red] (before the rigid elimination)
    n_red: int
    elements: list
    drivers: dict
    forces: list
    x0: np.ndarray
    v0: np.ndarray
    probes: list                      # (connection, label, g over the compiled DOFs, k, c, train-space Coord);
    #                                   k None: an element (its force is the solver's)
    exo: dict                         # STE key -> compiled DOF
    reports: dict                     # shaft -> reduction report
    load_vectors: list = field(default_factory=list)   # train-space unit vectors of the forces, in order
    driver_dofs: list = field(default_factory=list)    # train DOFs with a prescribed motion
    Tr: np.ndarray | None = None      # compiled DOFs before elimination = Tr @ compiled DOFs after it
    warnings: list = field(default_factory=list)

    def spec(self) -> ProblemSpec:
        return ProblemSpec(system=self.system, elements=self.elements, drivers=self.drivers, forces=self.forces,
                           x0=self.x0, v0=self.v0)

    @property
    def problem(self) -> Problem:
        return self.spec().problem()

    def full(self, x: np.ndarray) -> np.ndarray:
        """Train DOF vectors (n_train, m) from compiled states x (n_compiled, m)."""
        x = np.asarray(x)
        if self.Tr is not None:
            x = self.Tr @ x
        return self.T @ x[: self.n_red]

    def uncompiled(self, x: np.ndarray) -> np.ndarray:
        """Compiled DOFs before the rigid elimination (the probes' space)."""
        x = np.asarray(x)
        return self.Tr @ x if self.Tr is not None else x


def _boundary_dofs(ts: TrainSystem, parts_dofs: set) -> set:
    """Connection/driver/load DOFs plus every bearing, pedestal and ground-spring DOF."""
    out = set(parts_dofs)
    for bt in bearing_terms(ts, 0.0) if not ts.speed_dependent else []:
        out |= set(bt.shaft_dofs) | set(bt.pedestal_dofs or ())
        if bt.axial_dof is not None and (bt.k_axial or bt.c_axial):
            out.add(bt.axial_dof)
    if ts.speed_dependent:
        for b in ts.blocks:
            if b.rs is None:
                continue
            for br in b.rs.rotor.bearings:
                node = b.rs.node(br.x)
                out |= {b.offset + int(b.rs.node_dofs["v"][node]), b.offset + int(b.rs.node_dofs["w"][node])}
    for b in ts.blocks:
        if b.rs is not None:
            ped = np.flatnonzero(np.isin(b.rs.dof_field, ("pedestal_v", "pedestal_w")))
            out |= {b.offset + int(j) for j in ped}
        else:
            m = b.fe.model
            prim, rot = m.fields[0], (m.fields[1] if len(m.fields) > 1 else None)
            for p in list(m.points) + [s for s in m.supports if s.type == "spring"]:
                if p.k:
                    out.add(b.offset + b.local_dof(p.x, prim, ""))
                if getattr(p, "kr", 0.0) and rot is not None:
                    out.add(b.offset + b.local_dof(p.x, rot, ""))
    return out


def _shaft_system(ts: TrainSystem, b, speed: float) -> tuple[LinearSystem, sp.csr_matrix]:
    """(the shaft's LinearSystem at its own speed (C without gyroscopics), its G scaled by ratio * speed)."""
    s = abs(b.ratio) * float(speed)
    cand = rigid_candidates(ts)[b.offset:b.offset + b.n]
    cand = cand[:, np.any(cand != 0, axis=0)]
    if b.rs is not None:
        base = b.rs.system_at(s)
        G = b.ratio * float(speed) * b.rs.G
    else:
        base = b.fe.system
        G = sp.csr_matrix((b.n, b.n))
    sysb = LinearSystem(M=base.M, K=base.K, C=base.C, H=base.H, dof_field=base.dof_field, dof_x=base.dof_x,
                        dof_name=ts.dof_name[b.offset:b.offset + b.n], constrained=base.constrained,
                        rigid_modes=cand if cand.shape[1] else None, title=b.name, physics=base.physics)
    return sysb, sp.csr_matrix(G)


def compile_train(ts: TrainSystem, speed: float = 0.0, *, reduction: ReductionSpec | None = None,
                  drivers: list[TrainDriver] = (), loads: list[TrainLoad] = (),
                  eliminate_rigid: bool = False, linear: bool = False, start: str = "rest") -> CompiledTrain:
    """The nonsmooth problem of ``ts`` at the reference ``speed`` (see the module docstring); ``linear``: the
    connections in their declared linear state instead (no elements, no transmission error: the Floquet
    analysis of the mean train); ``start``: "rest" (the bodies' x0, v0) or "static" (the static state under the
    constant loads, every contact element on the side the loads press it to: :func:`static_start`)."""
    speed = float(speed)
    n = ts.n_dofs
    warnings = list(ts.warnings)
    # ---------------------------------------------------------------- the connections' parts
    lin, parts, exos = [], [], []
    for c in ts.train.connections:
        if linear:
            lin += [(c, cd) for cd in c.linear_part(ts)]
            continue
        lc, pc, _ = c.nonsmooth(ts, speed)
        lin += [(c, cd) for cd in lc]
        parts += [(c, p) for p in pc]
        exos += [(c, ex) for ex in c.excitations(ts, speed)]
    exo_keys = [ex.key for _, ex in exos]
    dofs = set()
    for _, cd in lin:
        dofs |= set(cd.idx.tolist())
    for _, p in parts:
        dofs |= set(p.coord.idx.tolist())
    drv_full = {}
    for i, d in enumerate(drivers, 1):
        if d.dof in drv_full:
            raise ModelError(f"[[driver]] #{i}", "at", ts.label(d.dof), "a DOF not driven by another [[driver]]")
        if d.dof in set(ts.constrained.tolist()):
            raise ModelError(f"[[driver]] #{i}", "at", ts.label(d.dof), "a DOF not held by a support")
        drv_full[d.dof] = d.law
    dofs |= set(drv_full)
    dofs |= {ld.dof for ld in loads}
    boundary_all = _boundary_dofs(ts, dofs)
    # ---------------------------------------------------------------- reduction per shaft
    blocks_T, blocks_sys, reports = [], [], {}
    for b in ts.blocks:
        sysb, Gb = _shaft_system(ts, b, speed)
        local = np.array(sorted(j - b.offset for j in boundary_all if b.offset <= j < b.offset + b.n), dtype=int)
        local = np.setdiff1d(local, sysb.constrained)
        held_drv = np.array(sorted(j - b.offset for j in drv_full if b.offset <= j < b.offset + b.n), dtype=int)
        if reduction is None:
            T = np.eye(b.n)
            con = np.union1d(sysb.constrained, held_drv)
            labels = (sysb.dof_field, sysb.dof_x, sysb.dof_name)
        else:
            nm = reduction.shaft_modes.get(b.name, reduction.modes)
            sysr = LinearSystem(M=sysb.M, K=sysb.K, C=sysb.C, H=sysb.H, dof_field=sysb.dof_field, dof_x=sysb.dof_x,
                                dof_name=sysb.dof_name, constrained=np.union1d(sysb.constrained, held_drv),
                                rigid_modes=sysb.rigid_modes, title=b.name, physics=sysb.physics)
            red = reduce(sysr, local, nm, static_correction=reduction.static_correction,
                         threshold=reduction.threshold)
            T = red.T
            con = red.system.constrained
            labels = (red.system.dof_field, red.system.dof_x,
                      np.array([f"{b.name}:{nmx}" if str(nmx).startswith("eta") else nmx
                                for nmx in red.system.dof_name], dtype=object))
            reports[b.name] = red.report()
            warnings += [f"shaft {b.name!r}: {w}" for w in red.warnings]
        Tm = sp.csr_matrix(T)
        mats = {k: np.asarray((Tm.T @ sp.csr_matrix(A) @ Tm).toarray()) for k, A in
                (("M", sysb.M), ("K", sysb.K), ("C", sysb.C), ("H", sysb.H), ("G", Gb))}
        blocks_T.append(T)
        blocks_sys.append((mats, con, labels))
    nb = len(ts.train.bodies)
    sizes = [T.shape[1] for T in blocks_T]
    n_red = sum(sizes) + nb
    n_exo = len(exo_keys)
    N = n_red + n_exo
    T = np.zeros((n, n_red))
    M, K, C, H = (np.zeros((N, N)) for _ in range(4))
    fields = np.empty(N, dtype=object)
    xs = np.full(N, np.nan)
    names = np.empty(N, dtype=object)
    constrained = []
    off = 0
    for b, Tb, (mats, con, (f_, x_, n_)) in zip(ts.blocks, blocks_T, blocks_sys):
        k = Tb.shape[1]
        T[b.offset:b.offset + b.n, off:off + k] = Tb
        sl = slice(off, off + k)
        M[sl, sl], K[sl, sl] = mats["M"], mats["K"]
        C[sl, sl], H[sl, sl] = mats["C"] + mats["G"], mats["H"]
        fields[sl], xs[sl], names[sl] = f_, x_, n_
        constrained += [off + int(j) for j in con]
        off += k
    for i, bd in enumerate(ts.train.bodies):
        j = off + i
        T[ts.body_offset + i, j] = 1.0
        M[j, j] = bd.inertia
        fields[j], names[j] = "theta", bd.name
    for i, key in enumerate(exo_keys):
        j = n_red + i
        fields[j], names[j] = "e", key
        constrained.append(j)
    exo_index = {key: n_red + i for i, key in enumerate(exo_keys)}

    def gvec(cd, extra=None) -> np.ndarray:
        g = np.zeros(N)
        g[:n_red] = T[cd.idx].T @ cd.val
        for key, coeff in (extra or {}).items():
            if key in exo_index:
                g[exo_index[key]] += coeff
        return g

    probes = []
    for c, cd in lin:
        g = gvec(cd, {ex.key: -1.0 for cc, ex in exos if cc is c and cd.label == "line of action"})
        if cd.k:
            K += cd.k * np.outer(g, g)
        if cd.c:
            C += cd.c * np.outer(g, g)
        probes.append((c, cd.label, g, cd.k, cd.c, cd))
    elements = []
    for c, p in parts:
        g = gvec(p.coord, p.extra)
        elements.append(p.cls(p.name, g, **p.kwargs))
        probes.append((c, p.name, g, None, None, p.coord))
    # drivers and loads on the compiled DOFs
    def compiled_index(j: int, where: str) -> int:
        """The compiled DOF of a kept (boundary) train DOF: its row of T is a unit row."""
        col = np.flatnonzero(T[j])
        if col.size != 1 or T[j, col[0]] != 1.0:       # pragma: no cover - drivers are on the boundary
            raise ModelError(where, "at", ts.label(j), "a DOF kept by the reduction")
        return int(col[0])

    drv = {}
    for j, law in drv_full.items():
        k = compiled_index(j, "[[driver]]")
        drv[k] = law
        if k not in constrained:
            constrained.append(k)
    for i, (c, ex) in enumerate(exos):
        drv[exo_index[ex.key]] = MotionLaw(amplitude=ex.amplitude, omega=ex.omega, phase=ex.phase)
    forces, load_vectors = [], []
    for ld in loads:
        e = np.zeros(n)
        e[ld.dof] = 1.0
        load_vectors.append(e)
        g = np.zeros(N)
        g[:n_red] = T[ld.dof]
        w = ld.frequency(ts, speed) if ld.amplitude else 0.0
        forces.append(ExternalForce(g=g, value=ld.value, amplitude=ld.amplitude, omega=w, phase=ld.phase))
    x0 = np.zeros(N)
    v0 = np.zeros(N)
    for i, bd in enumerate(ts.train.bodies):
        x0[n_red - nb + i], v0[n_red - nb + i] = bd.x0, bd.v0
    system = LinearSystem(M=sp.csr_matrix(M), K=sp.csr_matrix(K), C=sp.csr_matrix(C), H=sp.csr_matrix(H),
                          dof_field=fields, dof_x=xs, dof_name=names, constrained=np.array(sorted(constrained), int),
                          title=ts.title, physics="train (compiled)")
    comp = CompiledTrain(ts=ts, speed=speed, system=system, T=T, n_red=n_red, elements=elements, drivers=drv,
                         forces=forces, x0=x0, v0=v0, probes=probes, exo=exo_index, reports=reports,
                         load_vectors=load_vectors, driver_dofs=sorted(drv_full), warnings=warnings)
    if start == "static":
        comp.x0 = static_start(comp)
    if eliminate_rigid:
        _eliminate_rigid(comp)
    return comp


def static_start(comp: CompiledTrain, max_iter: int = 30) -> np.ndarray:
    """The static state of the compiled system under the constant parts of the loads and the drivers'
    positions at t = 0, with every clearance element in the mode its coordinate falls in (an active-set
    iteration from the elements engaged without clearance); a free rotation is fixed by the minimum-norm
    solution (least squares).  The start of a run that begins in the loaded state instead of at rest."""
    sys_ = comp.system
    N = sys_.n_dofs
    f, c = sys_.free, sys_.constrained
    K = np.asarray(sys_.K.toarray())
    rhs0 = np.zeros(N)
    for F in comp.forces:
        rhs0 += F.g * (F.value + F.amplitude * np.sin(F.phase))
    xc = np.zeros(N)
    for j, law in comp.drivers.items():
        xc[j] = law.offset + law.amplitude * np.sin(law.phase)
    bounded = [(i, el) for i, el in enumerate(comp.elements) if hasattr(el, "lower") and hasattr(el, "upper")
               and hasattr(el, "k")]
    modes = {i: None for i, _ in bounded}            # None: engaged without clearance (first pass)
    x = np.zeros(N)
    for _ in range(max_iter):
        A = K.copy()
        rhs = rhs0.copy()
        for i, el in bounded:
            m = modes[i]
            if m == 0:
                continue
            bound = 0.0 if m is None else (el.upper if m == 1 else el.lower)
            A += el.k * np.outer(el.g, el.g)
            rhs += el.k * bound * el.g
        x = xc.copy()
        x[f] = np.linalg.lstsq(A[np.ix_(f, f)], (rhs - A @ xc)[f], rcond=1e-12)[0]
        new = {}
        first = all(m is None for m in modes.values())
        for i, el in bounded:
            s_ = float(el.g @ x)
            if first:      # the side each contact is pressed to with no clearance: that flank closes
                up, lo = np.isfinite(el.upper), np.isfinite(el.lower)
                new[i] = (1 if s_ > 0 else 0) if (up and not lo) else ((-1 if s_ < 0 else 0) if (lo and not up)
                                                                        else (1 if s_ > 0 else -1))
            else:
                new[i] = 1 if s_ > el.upper else (-1 if s_ < el.lower else 0)
        if new == modes:
            break
        modes = new
    return x


def _eliminate_rigid(comp: CompiledTrain) -> None:
    """Remove the free rigid-body motions (module docstring) in place."""
    sys_ = comp.system
    N = sys_.n_dofs
    f = sys_.free
    M, K, C = (np.asarray(A.toarray()) for A in (sys_.M, sys_.K, sys_.C))
    G = np.array([p[2] for p in comp.probes] + [el.g for el in comp.elements]).reshape(-1, N)
    cand = rigid_candidates(comp.ts)
    # candidates in compiled coordinates (least squares on the reduced part; exact when in the span)
    Rc = np.zeros((N, cand.shape[1]))
    if cand.shape[1]:
        Rc[:comp.n_red] = np.linalg.lstsq(comp.T, cand, rcond=None)[0]
        ok = np.linalg.norm(comp.T @ Rc[:comp.n_red] - cand, axis=0) <= 1e-9 * np.maximum(np.linalg.norm(cand, axis=0), 1)
        Rc = Rc[:, ok]
    if not Rc.shape[1]:
        comp.warnings.append("no free rigid-body motion to eliminate")
        return
    scale = max(np.abs(K).max(), 1e-300)
    A = np.vstack([K @ Rc / scale, C @ Rc / max(np.abs(C).max(), 1e-300), G @ Rc / max(np.abs(G).max(initial=0), 1e-300)
                   if G.size else np.zeros((0, Rc.shape[1])), Rc[sys_.constrained]])
    _, s, Vt = np.linalg.svd(A, full_matrices=True)
    s = np.concatenate([s, np.zeros(Vt.shape[0] - s.size)])
    null = Vt[s <= 1e-9 * max(s.max(initial=0.0), 1.0)].T
    if null.shape[1] == 0:
        comp.warnings.append("no free rigid-body motion to eliminate")
        return
    R = Rc @ null
    B = R.T @ M                                     # the constraints B q = 0 (zero momentum)
    if np.abs(B[:, sys_.constrained]).max(initial=0.0) > 1e-12 * np.abs(B).max():
        raise ModelError("[train]", "rigid-body motion", "free", "a free rigid-body motion that no driven or held "
                         "DOF moves with through its inertia (a driver on a DOF coupled by mass to the free train)")
    Bf = B[:, f]
    _, _, piv = sla.qr(Bf, pivoting=True)
    pivots = f[piv[:R.shape[1]]]
    rest = np.setdiff1d(np.arange(N), pivots)
    Tr = np.zeros((N, rest.size))
    Tr[rest, np.arange(rest.size)] = 1.0
    Bp, Brest = B[:, pivots], B[:, rest]
    Tr[pivots] = -np.linalg.solve(Bp, Brest)
    new = {k: Tr.T @ A_ @ Tr for k, A_ in (("M", M), ("K", K), ("C", C), ("H", np.asarray(sys_.H.toarray())))}
    con = np.searchsorted(rest, sys_.constrained)
    comp.system = LinearSystem(M=new["M"], K=new["K"], C=new["C"], H=new["H"], dof_field=sys_.dof_field[rest],
                               dof_x=sys_.dof_x[rest], dof_name=sys_.dof_name[rest], constrained=con,
                               title=sys_.title, physics=sys_.physics + ", rigid motion eliminated")
    comp.elements = [type(el)(**{**_fields(el), "g": Tr.T @ el.g}) for el in comp.elements]
    comp.forces = [ExternalForce(g=Tr.T @ fo.g, value=fo.value, amplitude=fo.amplitude, omega=fo.omega, phase=fo.phase)
                   for fo in comp.forces]
    comp.drivers = {int(np.searchsorted(rest, j)): law for j, law in comp.drivers.items()}
    comp.x0 = np.linalg.lstsq(Tr, comp.x0, rcond=None)[0]
    comp.v0 = np.linalg.lstsq(Tr, comp.v0, rcond=None)[0]
    comp.Tr = Tr
    comp.warnings.append(f"{R.shape[1]} free rigid-body motion(s) eliminated (zero total momentum): DOF(s) "
                         + ", ".join(f"{sys_.dof_name[j]}.{sys_.dof_field[j]}" for j in pivots)
                         + " follow from the others")


def _fields(el) -> dict:
    from dataclasses import fields as dc_fields

    return {f.name: getattr(el, f.name) for f in dc_fields(el)}
