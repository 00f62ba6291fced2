"""Assemble a :class:`~fem.rotor.model.Rotor` into sparse M, K, C, G and the speed-dependent bearings.

The equations of motion at the spin speed Omega (rad/s) are

    M q'' + (C(Omega) + Omega G) q' + K(Omega) q = f(t)

(the :class:`~discrete.linear_system.LinearSystem` convention C + Omega G), with K and C
depending on Omega only through tabulated bearings.  Every matrix is stored on one sparsity
pattern (the union of all of them), so K(Omega) and C(Omega) at any speed are the constant data
plus a sparse map of the interpolated bearing coefficients: no re-assembly per speed, and the
solvers' orderings and band structures are computed once.

DOF numbering is node-major (all DOFs of node 0, then node 1, ...; a coupling cuts the shaft
into two nodes at the same x), pedestal DOFs (``pedestal_v``, ``pedestal_w``) come last.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from discrete.errors import ModelError
from discrete.linear_system import LinearSystem

from . import elements as el
from .model import BEARING_COEFFICIENTS, Rotor, damping_not_dissipative
from .tables import SpeedTable


@dataclass
class RotorSystem:
    """An assembled rotor: DOF map, constant matrices and the speed-dependent bearing maps.

    ``system_at(speed)`` gives the :class:`LinearSystem` at a speed; ``dof(x, field)`` and
    ``node(x)`` look DOFs up by position (for loads, probes, and nonlinear elements acting on
    the rotor)."""

    rotor: Rotor
    node_x: np.ndarray                       # (n_nodes,) x of every shaft node
    node_dofs: dict                          # field -> (n_nodes,) DOF index
    M: sp.csr_matrix
    K0: sp.csr_matrix                        # shaft, couplings, pedestals, constant bearings
    C0: sp.csr_matrix
    G: sp.csr_matrix
    dof_field: np.ndarray
    dof_x: np.ndarray
    dof_name: np.ndarray
    constrained: np.ndarray
    element_load: np.ndarray                 # (E, 4): int (rho A + m_extra) N_d dx per element (gravity)
    element_nodes: np.ndarray                # (E, 2) node indices
    axial_load: np.ndarray                   # (E, 2): int (rho A + m_extra) N dx of the axial rod (gravity along x)
    lumped_mass: dict                        # DOF -> lumped translational mass on it (discs, couplings, pedestals)
    shear_parameter: np.ndarray              # (E,) Phi = 12 E I / (kappa G A L^2) of each element
    tables: list = field(default_factory=list)
    _Bk: sp.csr_matrix | None = None         # pattern data <- table stiffness coefficients
    _Bc: sp.csr_matrix | None = None
    _pattern: sp.csr_matrix | None = None
    _workspace: object = None                # the modal solver's reusable structures (fem.rotor.modal)
    _pattern_data: dict = field(default_factory=dict, repr=False)   # id -> (K0 or C0, its data on the pattern)

    # ------------------------------------------------------------------ sizes and lookup
    @property
    def n_dofs(self) -> int:
        return self.M.shape[0]

    @property
    def speed_dependent(self) -> bool:
        return bool(self.tables)

    @property
    def fields(self) -> tuple[str, ...]:
        return self.rotor.fields

    def node(self, x: float, where: str = "") -> int:
        """Index of the shaft node at x (the left end of a coupling when two nodes share x)."""
        L = self.rotor.length
        k = int(np.argmin(np.abs(self.node_x - x)))
        if abs(self.node_x[k] - x) > 1e-9 * L:
            raise ModelError(where, "x", x, f"a node position in [0, {L:g}] m (nearest node at x = {self.node_x[k]:.6g})")
        return k

    def dof(self, x: float, field: str, where: str = "") -> int:
        """Global index of DOF ``field`` (v, w, theta_y, theta_z, u, theta_x) of the node at x."""
        if field not in self.node_dofs:
            raise ModelError(where, "dof", field, "one of " + ", ".join(map(repr, self.node_dofs)))
        return int(self.node_dofs[field][self.node(x, where)])

    @property
    def shaft_nodes_lateral(self) -> tuple[np.ndarray, np.ndarray]:
        """(v indices, w indices) of all shaft nodes."""
        return self.node_dofs["v"], self.node_dofs["w"]

    # ------------------------------------------------------------------ speed-dependent parts
    def coefficients(self, speeds) -> np.ndarray:
        """(n_speeds, 8 * n_tables) interpolated coefficients of the tabulated bearings."""
        s = np.atleast_1d(np.asarray(speeds, dtype=float))
        if not self.tables:
            return np.zeros((s.size, 0))
        c = np.hstack([t.at(s, check=False) for t in self.tables])
        # the damping check of extrapolated and smoothing-spline values, all tables at once; the
        # offending table's own check names it
        checked = [j for j, t in enumerate(self.tables) if t.needs_damping_check(s)]
        if checked:
            vals = c.reshape(s.size, len(self.tables), 8)[:, checked, :].reshape(-1, 8).T
            if damping_not_dissipative(vals) is not None:
                for j in checked:
                    self.tables[j].at(s)
        return c

    def stiffness_data(self, speeds, coefficients: np.ndarray | None = None) -> np.ndarray:
        """(n_speeds, nnz) data of K(speed) on the common pattern (``coefficients``: those of
        :meth:`coefficients` at ``speeds`` when the caller has them already)."""
        c = self.coefficients(speeds) if coefficients is None else coefficients
        base = self._on_pattern(self.K0)
        return base[None, :] + (self._Bk @ c.T).T if self.tables else np.repeat(base[None, :], c.shape[0], 0)

    def damping_data(self, speeds, coefficients: np.ndarray | None = None) -> np.ndarray:
        c = self.coefficients(speeds) if coefficients is None else coefficients
        base = self._on_pattern(self.C0)
        return base[None, :] + (self._Bc @ c.T).T if self.tables else np.repeat(base[None, :], c.shape[0], 0)

    @property
    def pattern(self) -> sp.csr_matrix:
        """The common sparsity pattern (CSR, sorted indices) of M, K, C, G at every speed."""
        return self._pattern

    def _on_pattern(self, A: sp.csr_matrix) -> np.ndarray:
        """A's data on the common pattern; cached for the constant matrices (K0, C0: read at every
        speed), keyed by the matrix object."""
        hit = self._pattern_data.get(id(A))
        if hit is not None and hit[0] is A:
            return hit[1]
        data = _data_on(self._pattern, A)
        if A is self.K0 or A is self.C0:
            data.flags.writeable = False
            self._pattern_data[id(A)] = (A, data)        # holding A keeps its id unique
        return data

    def _from_data(self, data: np.ndarray) -> sp.csr_matrix:
        P = self._pattern
        return sp.csr_matrix((data, P.indices, P.indptr), shape=P.shape)

    def stiffness(self, speed: float = 0.0) -> sp.csr_matrix:
        return self.K0 if not self.tables else self._from_data(self.stiffness_data(speed)[0])

    def damping(self, speed: float = 0.0) -> sp.csr_matrix:
        return self.C0 if not self.tables else self._from_data(self.damping_data(speed)[0])

    def stiffness_and_damping(self, speed: float = 0.0) -> tuple[sp.csr_matrix, sp.csr_matrix]:
        """K(speed) and C(speed), the bearing tables evaluated once for both."""
        if not self.tables:
            return self.K0, self.C0
        c = self.coefficients(speed)
        return (self._from_data(self.stiffness_data(speed, c)[0]), self._from_data(self.damping_data(speed, c)[0]))

    def system_at(self, speed: float = 0.0) -> LinearSystem:
        """The linear system M q'' + (C + speed G) q' + K q = f at ``speed`` (rad/s): K and C
        carry the bearings interpolated at that speed (constant bearings: any speed)."""
        speed = float(speed)
        return LinearSystem(M=self.M, K=self.stiffness(speed), C=self.damping(speed), G=self.G,
                            dof_field=self.dof_field, dof_x=self.dof_x, dof_name=self.dof_name,
                            constrained=self.constrained, title=self.rotor.title, physics="rotor")

    # ------------------------------------------------------------------ loads
    def gravity_load(self, g=(0.0, 0.0, -9.81)) -> np.ndarray:
        """Consistent load vector of the weight of shaft, discs, coupling halves and pedestals for
        the acceleration of gravity ``g`` = (g_x, g_y, g_z) in m/s^2 (default: -z is down)."""
        gx, gy, gz = (float(v) for v in g)
        f = np.zeros(self.n_dofs)
        n0, n1 = self.element_nodes[:, 0], self.element_nodes[:, 1]
        fe = self.element_load
        nd = self.node_dofs
        # plane x-y: (v, theta_z) as is; plane x-z: S (w, theta_y)
        for comp, gg, disp, rot, sign in ((0, gy, "v", "theta_z", 1.0), (1, gz, "w", "theta_y", -1.0)):
            if gg:
                np.add.at(f, nd[disp][n0], gg * fe[:, 0])
                np.add.at(f, nd[rot][n0], sign * gg * fe[:, 1])
                np.add.at(f, nd[disp][n1], gg * fe[:, 2])
                np.add.at(f, nd[rot][n1], sign * gg * fe[:, 3])
        for i, m in self.lumped_mass.items():
            if self.dof_field[i] in ("v", "pedestal_v"):
                f[i] += m * gy
            elif self.dof_field[i] in ("w", "pedestal_w"):
                f[i] += m * gz
            elif self.dof_field[i] == "u":
                f[i] += m * gx
        if gx and "u" in nd:
            np.add.at(f, nd["u"][n0], gx * self.axial_load[:, 0])
            np.add.at(f, nd["u"][n1], gx * self.axial_load[:, 1])
        return f

    def total_mass(self) -> float:
        """Mass of shaft (with added mass), discs, coupling halves (pedestals excluded), kg."""
        shaft = float(self.element_load[:, 0].sum() + self.element_load[:, 2].sum())
        r = self.rotor
        return shaft + sum(d.mass for d in r.discs) + sum(c.mass for c in r.couplings)


def _data_on(P: sp.csr_matrix, A: sp.spmatrix) -> np.ndarray:
    """Values of A at the stored positions of the pattern P (A's pattern must be inside P's)."""
    A = sp.csr_matrix(A)
    A.sum_duplicates()
    n = P.shape[1]
    pr = np.repeat(np.arange(P.shape[0]), np.diff(P.indptr))
    pkeys = pr.astype(np.int64) * n + P.indices
    ar = np.repeat(np.arange(A.shape[0]), np.diff(A.indptr))
    akeys = ar.astype(np.int64) * n + A.indices
    pos = np.searchsorted(pkeys, akeys)
    if akeys.size and (pos.max() >= pkeys.size or np.any(pkeys[np.minimum(pos, pkeys.size - 1)] != akeys)):
        raise ValueError("matrix pattern is not contained in the common pattern")
    out = np.zeros(pkeys.size, dtype=A.dtype)
    np.add.at(out, pos, A.data)
    return out


_COLUMNS = ("L", "E", "G", "rho", "kappa", "d0", "d1", "di0", "di1", "mx", "seg")


def _section_columns(cols: dict, length: float, n: int, d0: float, d1: float, di0: float, di1: float, mat,
                     kappa: float | None) -> None:
    """Append one section's per-element columns (n equal elements over ``length``) to ``cols``."""
    t = np.arange(n + 1) / n
    d = d0 + (d1 - d0) * t
    di = di0 + (di1 - di0) * t
    nu = mat.E / (2.0 * mat.G) - 1.0
    if kappa is not None:
        kap = np.full(n, float(kappa))
    else:   # Cowper for the hollow circle with the element's mean diameter ratio
        m = 0.5 * (di[:-1] + di[1:]) / (0.5 * (d[:-1] + d[1:]))
        m2 = m * m
        kap = 6 * (1 + nu) * (1 + m2) ** 2 / ((7 + 6 * nu) * (1 + m2) ** 2 + (20 + 12 * nu) * m2)
    cols["L"].append(np.full(n, length / n))
    cols["E"].append(np.full(n, mat.E))
    cols["G"].append(np.full(n, mat.G))
    cols["rho"].append(np.full(n, mat.rho))
    cols["kappa"].append(kap)
    cols["d0"].append(d[:-1])
    cols["d1"].append(d[1:])
    cols["di0"].append(di[:-1])
    cols["di1"].append(di[1:])


def _segment_arrays(rotor: Rotor):
    """Per-element arrays of the segments' own sections: length, E, G, rho, kappa, diameters at
    both ends, added mass, segment number."""
    cols = {k: [] for k in _COLUMNS}
    for i, s in enumerate(rotor.segments):
        _section_columns(cols, s.length, s.elements, s.d, s.outer_end, s.di, s.bore_end, s.material,
                         s.shear_coefficient)
        cols["mx"].append(np.full(s.elements, s.added_mass_per_length))
        cols["seg"].append(np.full(s.elements, i))
    return {k: np.concatenate(v) for k, v in cols.items()}


def _layer_arrays(rotor: Rotor):
    """Per-element arrays of the segments' further layers (None without layers), with ``elem``
    (the global element each layer element lies on) and ``structural`` (False: mass only)."""
    cols = {k: [] for k in _COLUMNS + ("elem", "structural")}
    first = np.concatenate(([0], np.cumsum([s.elements for s in rotor.segments])))
    for i, s in enumerate(rotor.segments):
        for lay in s.layers:
            n = s.elements
            _section_columns(cols, s.length, n, lay.d, lay.outer_end, lay.di, lay.bore_end, lay.material,
                             lay.shear_coefficient)
            cols["mx"].append(np.zeros(n))
            cols["seg"].append(np.full(n, i))
            cols["elem"].append(first[i] + np.arange(n))
            cols["structural"].append(np.full(n, not lay.mass_only))
    if not cols["L"]:
        return None
    return {k: np.concatenate(v) for k, v in cols.items()}


def assemble_rotor(rotor: Rotor, *, nonlinear_bearings: str = "linearised") -> RotorSystem:
    """Assemble ``rotor`` (see the module notes for the DOF numbering and the pattern).

    Bearings computed from their geometry (``nonlinear`` True: :mod:`fem.rotor.bearings`) enter
    with their linearised coefficient tables (``nonlinear_bearings = "linearised"``, every linear
    analysis) or not at all (``"omitted"``: a run-up applies their nonlinear laws instead); a
    bearing that draws its static load from the rotor's weight gets it first."""
    if nonlinear_bearings not in ("linearised", "omitted"):
        raise ValueError(f"nonlinear_bearings = {nonlinear_bearings!r}: 'linearised' or 'omitted'")
    if nonlinear_bearings == "linearised" and any(getattr(b, "needs_weight_load", False) for b in rotor.bearings):
        from .bearings.static_load import weight_reactions

        for b, load in zip(rotor.bearings, weight_reactions(rotor, assemble_rotor)):
            if getattr(b, "needs_weight_load", False):
                b.set_weight_load(load)
    fields = rotor.fields
    nf = len(fields)
    # ---------------------------------------------------------------- nodes (couplings cut the shaft)
    coupling_x = sorted(c.x for c in rotor.couplings)
    node_x, elem_nodes = [0.0], []
    x0 = 0.0
    L_total = rotor.length
    for s in rotor.segments:
        if x0 > 0 and any(abs(x0 - cx) <= 1e-9 * L_total for cx in coupling_x):
            node_x.append(x0)              # the right end of the coupling: a new node at the same x
        for k in range(1, s.elements + 1):
            elem_nodes.append((len(node_x) - 1, len(node_x)))
            node_x.append(x0 + s.length * k / s.elements)
        x0 += s.length
    node_x = np.asarray(node_x)
    elem_nodes = np.asarray(elem_nodes)
    n_nodes = node_x.size
    node_dofs = {f: np.arange(n_nodes) * nf + j for j, f in enumerate(fields)}
    n_shaft = n_nodes * nf
    ped_names = [p.name for p in rotor.pedestals]
    ped_dofs = {name: (n_shaft + 2 * i, n_shaft + 2 * i + 1) for i, name in enumerate(ped_names)}
    n = n_shaft + 2 * len(ped_names)
    dof_field = np.empty(n, dtype=object)
    dof_x = np.empty(n)
    dof_name = np.full(n, "", dtype=object)
    for f, idx in node_dofs.items():
        dof_field[idx] = f
        dof_x[idx] = node_x
    for p in rotor.pedestals:
        iv, iw = ped_dofs[p.name]
        dof_field[iv], dof_field[iw] = "pedestal_v", "pedestal_w"
        dof_name[iv] = dof_name[iw] = p.name
        dof_x[iv] = dof_x[iw] = next(b.x for b in rotor.bearings if b.pedestal == p.name)

    def node_at(x):
        return int(np.argmin(np.abs(node_x - x)))       # the first (left) of two coupled nodes

    # ---------------------------------------------------------------- shaft elements
    a = _segment_arrays(rotor)
    Kp, MT, MR, P, phi = el.plane_matrices(a["L"], a["E"], a["G"], a["rho"], a["kappa"], a["d0"], a["d1"],
                                           a["di0"], a["di1"], a["mx"])
    Kl, Ml, Gl = el.lateral_matrices(Kp, MT, MR, P)
    n0, n1 = elem_nodes[:, 0], elem_nodes[:, 1]
    nd = node_dofs
    edofs = np.stack([nd["v"][n0], nd["theta_z"][n0], nd["v"][n1], nd["theta_z"][n1],
                      nd["w"][n0], nd["theta_y"][n0], nd["w"][n1], nd["theta_y"][n1]], axis=1)
    rows = [np.repeat(edofs, 8, axis=1).ravel()]
    cols = [np.tile(edofs, (1, 8)).ravel()]
    kvals, mvals, gvals = [Kl.ravel()], [Ml.ravel()], [Gl.ravel()]
    cvals = [np.zeros(Kl.size)]
    # element load vectors for gravity: int (rho A + m_extra) N_d dx
    Nd = el.shape_functions(a["L"], phi)[0]
    A_g, I_g, Ip_g = el.section_at(a["d0"], a["d1"], a["di0"], a["di1"], el.XI)
    line_mass = a["rho"][:, None] * A_g + a["mx"][:, None]
    element_load = np.einsum("eq,eqi->ei", line_mass * (el.WG[None, :] * a["L"][:, None]), Nd)
    N_lin = np.stack([1 - el.XI, el.XI], axis=-1)
    axial_load = np.einsum("eq,qi->ei", line_mass * (el.WG[None, :] * a["L"][:, None]), N_lin)
    if rotor.dofs == "full":
        Ka, Ma = el.rod_matrices(a["L"], a["E"][:, None] * A_g, line_mass)
        Kt, Mt = el.rod_matrices(a["L"], a["G"][:, None] * Ip_g, a["rho"][:, None] * Ip_g)
        for Ke, Me, f in ((Ka, Ma, "u"), (Kt, Mt, "theta_x")):
            e2 = np.stack([nd[f][n0], nd[f][n1]], axis=1)
            rows.append(np.repeat(e2, 2, axis=1).ravel())
            cols.append(np.tile(e2, (1, 2)).ravel())
            kvals.append(Ke.ravel())
            mvals.append(Me.ravel())
            gvals.append(np.zeros(Ke.size))
            cvals.append(np.zeros(Ke.size))
    lay = _layer_arrays(rotor)
    if lay is not None:
        # each layer: a Timoshenko element of its own on the same nodes (own Phi and interpolation),
        # its matrices added to the element's (ROSS's convention for shaft elements sharing a node);
        # mass-only layers add M and G (translation, rotary and polar inertia) and no K
        e = lay["elem"]
        st = lay["structural"].astype(float)
        Kq, MTq, MRq, Pq, phq = el.plane_matrices(lay["L"], lay["E"], lay["G"], lay["rho"], lay["kappa"], lay["d0"],
                                                  lay["d1"], lay["di0"], lay["di1"], lay["mx"])
        Kq *= st[:, None, None]
        Klq, Mlq, Glq = el.lateral_matrices(Kq, MTq, MRq, Pq)
        rows.append(np.repeat(edofs[e], 8, axis=1).ravel())
        cols.append(np.tile(edofs[e], (1, 8)).ravel())
        kvals.append(Klq.ravel())
        mvals.append(Mlq.ravel())
        gvals.append(Glq.ravel())
        cvals.append(np.zeros(Klq.size))
        Ndq = el.shape_functions(lay["L"], phq)[0]
        A_q, _, Ip_q = el.section_at(lay["d0"], lay["d1"], lay["di0"], lay["di1"], el.XI)
        mass_q = lay["rho"][:, None] * A_q
        wq = el.WG[None, :] * lay["L"][:, None]
        np.add.at(element_load, e, np.einsum("eq,eqi->ei", mass_q * wq, Ndq))
        np.add.at(axial_load, e, np.einsum("eq,qi->ei", mass_q * wq, N_lin))
        if rotor.dofs == "full":
            Kaq, Maq = el.rod_matrices(lay["L"], (st * lay["E"])[:, None] * A_q, mass_q)
            Ktq, Mtq = el.rod_matrices(lay["L"], (st * lay["G"])[:, None] * Ip_q, lay["rho"][:, None] * Ip_q)
            for Ke, Me, f in ((Kaq, Maq, "u"), (Ktq, Mtq, "theta_x")):
                e2 = np.stack([nd[f][n0[e]], nd[f][n1[e]]], axis=1)
                rows.append(np.repeat(e2, 2, axis=1).ravel())
                cols.append(np.tile(e2, (1, 2)).ravel())
                kvals.append(Ke.ravel())
                mvals.append(Me.ravel())
                gvals.append(np.zeros(Ke.size))
                cvals.append(np.zeros(Ke.size))

    # ---------------------------------------------------------------- lumped items
    extra = {"K": [], "C": [], "M": [], "G": []}          # (i, j, value)
    lumped_mass = {}

    def add(kind, i, j, v):
        if v:
            extra[kind].append((int(i), int(j), float(v)))

    def spring(kind, i, j, k):
        """A spring (or damper) k between DOFs i and j (j = None: to ground)."""
        add(kind, i, i, k)
        if j is not None:
            add(kind, j, j, k)
            add(kind, i, j, -k)
            add(kind, j, i, -k)

    def disc(node, mass, Id, Ip):
        for f in ("v", "w"):
            add("M", nd[f][node], nd[f][node], mass)
            lumped_mass[int(nd[f][node])] = lumped_mass.get(int(nd[f][node]), 0.0) + mass
        for f in ("theta_y", "theta_z"):
            add("M", nd[f][node], nd[f][node], Id)
        add("G", nd["theta_y"][node], nd["theta_z"][node], Ip)
        add("G", nd["theta_z"][node], nd["theta_y"][node], -Ip)
        if rotor.dofs == "full":
            add("M", nd["u"][node], nd["u"][node], mass)
            lumped_mass[int(nd["u"][node])] = lumped_mass.get(int(nd["u"][node]), 0.0) + mass
            add("M", nd["theta_x"][node], nd["theta_x"][node], Ip)

    for d in rotor.discs:
        disc(node_at(d.x), d.mass, d.Id, d.Ip)
    for c in rotor.couplings:
        left = node_at(c.x)
        right = left + 1
        for node in (left, right):
            disc(node, 0.5 * c.mass, 0.5 * c.Id, 0.5 * c.Ip)
        for f in ("v", "w"):
            spring("K", nd[f][left], nd[f][right], c.k_lateral)
            spring("C", nd[f][left], nd[f][right], c.c_lateral)
        for f in ("theta_y", "theta_z"):
            spring("K", nd[f][left], nd[f][right], c.k_angular)
            spring("C", nd[f][left], nd[f][right], c.c_angular)
        if rotor.dofs == "full":
            spring("K", nd["u"][left], nd["u"][right], c.k_axial)
            spring("K", nd["theta_x"][left], nd["theta_x"][right], c.k_torsion)
    for p in rotor.pedestals:
        iv, iw = ped_dofs[p.name]
        add("M", iv, iv, p.mass)
        add("M", iw, iw, p.mass)
        lumped_mass[iv] = lumped_mass.get(iv, 0.0) + p.mass
        lumped_mass[iw] = lumped_mass.get(iw, 0.0) + p.mass
        spring("K", iv, None, p.kyy)
        spring("K", iw, None, p.kzz)
        spring("C", iv, None, p.cyy)
        spring("C", iw, None, p.czz)

    # bearings: force on the shaft -K d with d = q_shaft - q_pedestal; pedestal gets +K d
    table_entries = []                # (table number, coefficient slot, i, j, sign)
    tables = []
    for b_no, b in enumerate(rotor.bearings, 1):
        if nonlinear_bearings == "omitted" and getattr(b, "nonlinear", False):
            continue
        node = node_at(b.x)
        shaft = (nd["v"][node], nd["w"][node])
        ped = ped_dofs[b.pedestal] if b.pedestal is not None else None
        incid = []       # (dof of d_a, sign) lists per direction a
        for a_ in range(2):
            lst = [(shaft[a_], 1.0)]
            if ped is not None:
                lst.append((ped[a_], -1.0))
            incid.append(lst)
        coeff_slots = {"kyy": (0, 0), "kyz": (0, 1), "kzy": (1, 0), "kzz": (1, 1),
                       "cyy": (0, 0), "cyz": (0, 1), "czy": (1, 0), "czz": (1, 1)}
        tab = b.table()
        if b.speed_dependent:
            t_no = len(tables)
            kind = getattr(b, "kind", "bearing")
            number = b_no if kind == "bearing" else \
                sum(getattr(c, "kind", "bearing") == kind for c in rotor.bearings[:b_no])
            tables.append(SpeedTable(index=number, grid=b.speed_grid,
                                     values=np.stack([tab[k] for k in BEARING_COEFFICIENTS]),
                                     interpolation=b.interpolation, extrapolate=b.extrapolate, name=b.name, x=b.x,
                                     table=f"rotor.{kind}"))
        for slot, key in enumerate(BEARING_COEFFICIENTS):
            r_, c_ = coeff_slots[key]
            for (i, si) in incid[r_]:
                for (j, sj) in incid[c_]:
                    if b.speed_dependent:
                        table_entries.append((t_no, slot, i, j, si * sj))
                    else:
                        add("K" if key[0] == "k" else "C", i, j, si * sj * tab[key][0])
        if rotor.dofs == "full":
            spring("K", nd["u"][node], None, b.k_axial)
            spring("C", nd["u"][node], None, b.c_axial)

    def build(kind, vals_list):
        r = np.concatenate(rows + [np.array([e[0] for e in extra[kind]], dtype=int)])
        c = np.concatenate(cols + [np.array([e[1] for e in extra[kind]], dtype=int)])
        v = np.concatenate(vals_list + [np.array([e[2] for e in extra[kind]], dtype=float)])
        A = sp.csr_matrix((v, (r, c)), shape=(n, n))
        A.sum_duplicates()
        return A

    K0, M, C0, G = build("K", kvals), build("M", mvals), build("C", cvals), build("G", gvals)
    # the common pattern: union of all matrices and the table entries, every position stored
    te = np.array([(e[2], e[3]) for e in table_entries], dtype=int).reshape(-1, 2)
    ones = [sp.csr_matrix((np.ones(X.nnz), X.indices, X.indptr), shape=(n, n)) for X in (K0, M, C0, G)]
    ones.append(sp.csr_matrix((np.ones(te.shape[0]), (te[:, 0], te[:, 1])), shape=(n, n)))
    pattern = sp.csr_matrix(sum(abs(o) for o in ones))
    pattern.sum_duplicates()
    pattern.sort_indices()
    pattern.data[:] = 1.0
    Bk = Bc = None
    if tables:
        npos = pattern.nnz
        pr = np.repeat(np.arange(n), np.diff(pattern.indptr)).astype(np.int64) * n + pattern.indices
        pos = np.searchsorted(pr, te[:, 0].astype(np.int64) * n + te[:, 1])
        col = np.array([8 * e[0] + e[1] for e in table_entries])
        sign = np.array([e[4] for e in table_entries])
        B = sp.csr_matrix((sign, (pos, col)), shape=(npos, 8 * len(tables)))
        stiff_cols = np.zeros(8 * len(tables), dtype=bool)
        for t in range(len(tables)):
            stiff_cols[8 * t: 8 * t + 4] = True
        Bk = sp.csr_matrix(B.multiply(stiff_cols[None, :]))
        Bc = sp.csr_matrix(B.multiply(~stiff_cols[None, :]))
    constrained = []
    for s in rotor.supports:
        node = node_at(s.x)
        constrained += [int(nd[f][node]) for f in s.dofs]
    out = RotorSystem(rotor=rotor, node_x=node_x, node_dofs=node_dofs, M=M, K0=K0, C0=C0, G=G, dof_field=dof_field,
                      dof_x=dof_x, dof_name=dof_name, constrained=np.unique(np.asarray(constrained, dtype=int)),
                      element_load=element_load, element_nodes=elem_nodes, axial_load=axial_load,
                      lumped_mass=lumped_mass, shear_parameter=phi, tables=tables, _Bk=Bk, _Bc=Bc, _pattern=pattern)
    return out
