"""3D continuum (solid) shafts: the same :class:`fem.model.ShaftModel` description meshed
with quadratic hexahedra, assembled with scikit-fem into a :class:`LinearSystem`.

Supports and attachments map onto the cross-section at their ``x``:

* ``clamped``: every displacement DOF of the section is held (the textbook clamp, no warping);
* ``pinned``: the transverse displacements u_y, u_z of the section are held (a bearing
  that lets the section rotate in bending and move axially; it also holds torsion);
* ``spring``: ``k`` spread uniformly over the section as a distributed spring: transverse
  for bending, axial for axial, torsional (tangential, k/J per area) for torsion models;
  ``kr`` (bending) as an axial spring density kr/I, i.e. a rotational spring;
* point attachments: mass m as surface density m/A (all directions), ``inertia`` as a
  tangential density I_p/J (torsion models: polar inertia) or an axial density I_d/I
  (bending models: diametral inertia), i.e. a rigid disc of the given inertia smeared
  over the section.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from discrete.errors import ModelError
from discrete.linear_system import LinearSystem

from ..mesh import build_line_mesh
from ..model import ShaftModel
from . import forms
from .mesh import ShaftMeshSpec, stepped_shaft_hex

#: skfem hexahedron vertex order -> VTK_HEXAHEDRON order
SKFEM_TO_VTK_HEX = [7, 4, 1, 5, 6, 2, 0, 3]


@dataclass
class SolidModel:
    """An assembled 3D solid model: mesh, vector basis, linear system, section data."""

    mesh: object
    basis: object
    system: LinearSystem
    length: float
    element: str
    model: ShaftModel | None = None
    cell_type: str = "hexahedron"

    @property
    def n_dofs(self) -> int:
        return self.system.n_dofs

    @property
    def vertices(self) -> np.ndarray:
        """(n_vertices, 3) coordinates of the mesh vertices (the corners of the cells)."""
        return self.basis.doflocs[:, self.basis.nodal_dofs[0]].T.copy()

    def displacement_field(self, q: np.ndarray) -> np.ndarray:
        """(n_vertices, 3) displacement at the mesh vertices for a full-length DOF vector."""
        nd = self.basis.nodal_dofs[0]
        Ns = self.basis.N
        q = np.asarray(q)
        return np.column_stack([q[a * Ns + nd] for a in range(3)])

    # ---------------------------------------------------------- export / rendering
    def export_points_cells(self):
        t = self.mesh.t
        if self.cell_type == "hexahedron":
            t = t[SKFEM_TO_VTK_HEX]
        return self.vertices, [(self.cell_type, t.T.copy())]

    def mode_point_data(self, modal):
        points, cells = self.export_points_cells()
        data = {f"mode{r + 1}_displacement": self.displacement_field(modal.shapes[:, r])
                for r in range(modal.shapes.shape[1])}
        return points, cells, data

    def volume_grid(self):
        """Linear cells on the vertices (pyvista UnstructuredGrid)."""
        import pyvista as pv

        points, cells = self.export_points_cells()
        ctype = {"hexahedron": pv.CellType.HEXAHEDRON, "tetra": pv.CellType.TETRA}[self.cell_type]
        return pv.UnstructuredGrid({ctype: cells[0][1]}, points)

    def quadratic_grid(self):
        """Quadratic cells (27-node hexahedra / 10-node tetrahedra) on all scalar DOF nodes, in
        VTK's node order (matched geometrically through the element mapping), for curved
        surfaces in pictures."""
        import pyvista as pv

        if self.cell_type == "hexahedron":
            corners = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
            edges = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
            faces = [(0, 4, 7, 3), (1, 2, 6, 5), (0, 1, 5, 4), (3, 2, 6, 7), (0, 1, 2, 3), (4, 5, 6, 7)]
            ref = np.vstack([corners, [corners[list(e)].mean(0) for e in edges],
                             [corners[list(f)].mean(0) for f in faces], [[0.5, 0.5, 0.5]]])
            ctype = pv.CellType.TRIQUADRATIC_HEXAHEDRON
        else:
            corners = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
            edges = [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)]
            ref = np.vstack([corners, [corners[list(e)].mean(0) for e in edges]])
            ctype = pv.CellType.QUADRATIC_TETRA
        phys = self.mesh._mapping().F(ref.T)                  # (3, E, n_ref)
        edofs = self.basis.element_dofs                       # (n_loc, E)
        locs = self.basis.doflocs[:, edofs]                   # (3, n_loc, E)
        d = ((phys[:, :, :, None] - locs.transpose(0, 2, 1)[:, :, None, :]) ** 2).sum(axis=0)   # (E, n_ref, n_loc)
        pick = np.argmin(d, axis=2)
        cells = np.take_along_axis(edofs.T, pick, axis=1)
        return pv.UnstructuredGrid({ctype: cells}, self.basis.doflocs.T.copy())

    def surface_with_displacement(self, q: np.ndarray, subdivision: int = 2):
        """Outer surface (PolyData, curved cells subdivided) carrying the point array
        ``displacement`` of the full-length DOF vector ``q``."""
        grid = self.quadratic_grid()
        Ns = self.basis.N
        q = np.asarray(q)
        grid.point_data["displacement"] = np.column_stack([q[a * Ns: (a + 1) * Ns] for a in range(3)])
        return grid.extract_surface(nonlinear_subdivision=subdivision, algorithm="dataset_surface")

    def surface_edges_with_displacement(self, q: np.ndarray):
        """Edges of the linear surface cells (the mesh lines a viewer sees) with ``displacement``."""
        grid = self.volume_grid()
        grid.point_data["displacement"] = self.displacement_field(q)
        return grid.extract_surface(algorithm="dataset_surface").extract_all_edges()


# -------------------------------------------------------------------- build
def _lame(E: float, G: float) -> tuple[float, float]:
    nu = E / (2 * G) - 1
    return G, E * nu / ((1 + nu) * (1 - 2 * nu))


def _section_radii(model: ShaftModel) -> tuple[np.ndarray, np.ndarray]:
    outer, inner = [], []
    for i, s in enumerate(model.segments, 1):
        sec = s.section
        if sec.shape not in ("circle", "tube") or sec.d is None:
            raise ModelError(f"[[segment]] #{i} section", "shape", sec.shape,
                             "'circle' or 'tube' for a 3D solid model (explicit A, I, J have no geometry)")
        outer.append(0.5 * sec.d)
        inner.append(0.5 * sec.d * sec.inner_to_outer)
    return np.asarray(outer), np.asarray(inner)


def build_solid(model: ShaftModel, spec: ShaftMeshSpec | None = None) -> SolidModel:
    """Mesh and assemble the 3D solid version of ``model`` with 27-node quadratic
    hexahedra on a quadratic (exact-circle) geometry.  ``model.physics`` only selects how
    springs and attachment inertias act; the solid itself carries all motions."""
    spec = spec or ShaftMeshSpec()
    if spec.axial_per_segment is not None:
        if len(spec.axial_per_segment) != len(model.segments):
            raise ModelError("solid mesh", "axial_per_segment", spec.axial_per_segment,
                             f"one element count per segment ({len(model.segments)})")
        model_for_mesh = dataclasses.replace(model, segments=[dataclasses.replace(s, elements=int(n)) for s, n in
                                                                zip(model.segments, spec.axial_per_segment)])
    else:
        model_for_mesh = model
    if any(s.rho_extra for s in model.segments):
        raise ModelError("solid model", "rho_extra", [s.rho_extra for s in model.segments],
                         "0 for a 3D solid (model attached parts as [[point]] attachments)")
    outer, inner = _section_radii(model)
    line = build_line_mesh(model_for_mesh)
    mesh, seg = stepped_shaft_hex(line.nodes, line.elem_segment, outer, inner, spec.n_quarter, spec.radial)
    mats = [s.material for s in model.segments]
    solid = assemble_solid(mesh, np.array([_lame(m.E, m.G)[0] for m in mats])[seg],
                           np.array([_lame(m.E, m.G)[1] for m in mats])[seg],
                           np.array([m.rho for m in mats])[seg], title=model.title)
    proven = solid.system.mass_semidefinite_reason
    K, M, held, mass_terms_ok = _attachments(model, solid, outer, inner)
    if proven and mass_terms_ok:
        proven += "; point masses and inertias >= 0 as section integrals with facet weights >= 0"
    solid.system = _system(solid.basis, K, M, held, model.title, proven if all(mass_terms_ok) else None)
    solid.model = model
    solid.length = model.length
    return solid


def _system(basis, K, M, held, title, mass_reason: str | None = None) -> LinearSystem:
    """The solid's LinearSystem; ``mass_reason``: why M is positive semi-definite by construction
    (recorded with it, :meth:`LinearSystem.prove_mass_semidefinite`), None if not proven."""
    Ns = basis.N
    comp = np.repeat(np.arange(3), Ns)
    doflocs = np.tile(basis.doflocs, 3)
    system = LinearSystem(M=M, K=K, dof_field=np.array(["u_x", "u_y", "u_z"], dtype=object)[comp],
                          dof_x=doflocs[0].copy(), constrained=held, rigid_modes=_rigid_modes(doflocs, comp, held),
                          title=title, physics="solid (3D elasticity)")
    if mass_reason:
        system.prove_mass_semidefinite(mass_reason)
    return system


def assemble_solid(mesh, mu, lam, rho, title: str = "", cell_type: str = "hexahedron") -> SolidModel:
    """Elasticity and consistent mass of a 3D mesh (per-element Lame constants and density),
    quadratic elements (27-node hexahedra or 10-node tetrahedra), no constraints."""
    from skfem import Basis, ElementHex2, ElementTetP2, asm

    elem = ElementHex2() if cell_type == "hexahedron" else ElementTetP2()
    basis = Basis(mesh, elem, intorder=4)
    K = forms.elasticity_matrix(basis, np.asarray(mu, float), np.asarray(lam, float))
    nq = basis.X.shape[-1]
    Ms = asm(forms.scalar_mass, basis, rho=np.repeat(np.asarray(rho, float)[:, None], nq, axis=1))
    M = sp.block_diag([Ms, Ms, Ms], format="csr")
    x = basis.doflocs[0]
    # M = sum over quadrature points of rho_q dx_q phi_q phi_q^T, dx = |det J| x weight: a sum of
    # positive semi-definite terms (modal_analysis then skips its Sylvester count of M)
    proven = np.all(np.asarray(rho, float) >= 0) and np.all(basis.dx >= 0)
    system = _system(basis, K, M, np.zeros(0, dtype=int), title,
                     f"consistent mass of {type(elem).__name__} elements: densities >= 0 and quadrature weights x "
                     "|det J| >= 0" if proven else None)
    return SolidModel(mesh=mesh, basis=basis, system=system, length=float(x.max() - x.min()), element=type(elem).__name__,
                      cell_type=cell_type)


def _rigid_modes(doflocs: np.ndarray, comp: np.ndarray, held: np.ndarray) -> np.ndarray:
    """The six rigid-body motions (three translations, three rotations), restricted to the
    combinations that vanish at every held DOF."""
    import scipy.linalg as sla

    x, y, z = doflocs
    R = np.zeros((comp.size, 6))
    for c in range(3):
        R[comp == c, c] = 1.0
    # rotation about x: (0, -z, y); about y: (z, 0, -x); about z: (-y, x, 0)
    R[comp == 1, 3], R[comp == 2, 3] = -z[comp == 1], y[comp == 2]
    R[comp == 0, 4], R[comp == 2, 4] = z[comp == 0], -x[comp == 2]
    R[comp == 0, 5], R[comp == 1, 5] = -y[comp == 0], x[comp == 1]
    if held.size:
        R = R @ sla.null_space(R[held], rcond=1e-10)
    return R


def _section_facets(mesh, x: float, tol: float):
    return mesh.facets_satisfying(lambda p: np.abs(p[0] - x) < tol)


def _attachments(model, solid, outer, inner):
    """Supports and point attachments of ``model`` on the sections of ``solid``."""
    from skfem import FacetBasis, asm

    basis, mesh = solid.basis, solid.mesh
    K, M = solid.system.K.tocsr(), solid.system.M.tocsr()
    L = model.length
    tol = 1e-9 * L
    Ns = basis.N
    xdof = np.tile(basis.doflocs[0], 3)
    comp = np.repeat(np.arange(3), Ns)
    held = []
    mass_terms_ok = []                   # per mass term added: coefficients and facet weights >= 0
    ends = np.concatenate(([0.0], np.cumsum([s.length for s in model.segments])))

    def section_props(x):
        k = int(np.clip(np.searchsorted(ends, x, side="right") - 1, 0, len(model.segments) - 1))
        ro, ri = outer[k], inner[k]
        if 0 < k and abs(x - ends[k]) < tol:          # at a step use the smaller section
            ro = min(ro, outer[k - 1])
        Id = math.pi * (ro**4 - ri**4) / 4
        return math.pi * (ro**2 - ri**2), Id, 2 * Id

    def section_matrix(x, area=0.0, axial=0.0, transverse=0.0, tangential=0.0, terms_ok=None):
        """Vector matrix of int (area u.v + axial u_x v_x + transverse (u_y v_y + u_z v_z)
        + tangential (u.e_theta)(v.e_theta)) over the cross-section at x."""
        facets = mesh.facets_satisfying(lambda p: np.abs(p[0] - x) < tol)
        if facets.size == 0:
            raise ModelError("solid model", "x", x, "a position on a mesh section")
        fb = FacetBasis(mesh, basis.elem, facets=facets, intorder=4)
        if terms_ok is not None:        # a mass term: positive semi-definite (e.g. not a section area < 0 at a step)?
            coefficients = np.array([area, axial, transverse, tangential], float)
            terms_ok.append(bool(np.all(fb.dx >= 0) and np.all(np.isfinite(coefficients)) and np.all(coefficients >= 0)))
        xg = np.asarray(fb.global_coordinates())
        y, z = xg[1], xg[2]
        r2 = y * y + z * z + 1e-300

        def blk(c):
            return asm(forms.weighted_product, fb, c=c).tocsr()

        one = np.ones_like(y)
        blocks = {(0, 0): blk((area + axial) * one)}
        if tangential:
            blocks[(1, 1)] = blk((area + transverse) * one + tangential * z * z / r2)
            blocks[(2, 2)] = blk((area + transverse) * one + tangential * y * y / r2)
            blocks[(1, 2)] = blocks[(2, 1)] = blk(-tangential * y * z / r2)
        else:
            blocks[(1, 1)] = blocks[(2, 2)] = blk((area + transverse) * one)
        return forms.vector_block(blocks, Ns)

    def spring(x, k, kr):
        A, Id, J = section_props(x)
        return section_matrix(x, transverse=k / A if model.physics == "bending" else 0.0,
                              axial=(k / A if model.physics == "axial" else 0.0) + kr / Id,
                              tangential=k / J if model.physics == "torsion" else 0.0)

    for s in model.supports:
        at = np.abs(xdof - s.x) < tol
        if s.type == "clamped":
            held += np.flatnonzero(at).tolist()
        elif s.type == "pinned":
            held += np.flatnonzero(at & (comp > 0)).tolist()
        else:
            K = K + spring(s.x, s.k, s.kr)
    for p in model.points:
        A, Id, J = section_props(p.x)
        if p.mass or p.inertia:
            M = M + section_matrix(p.x, area=p.mass / A,
                                   tangential=p.inertia / J if model.physics == "torsion" else 0.0,
                                   axial=p.inertia / Id if model.physics == "bending" else 0.0, terms_ok=mass_terms_ok)
        if p.k or p.kr:
            K = K + spring(p.x, p.k, p.kr)
    return sp.csr_matrix(K), sp.csr_matrix(M), np.unique(np.asarray(held, dtype=int)), mass_terms_ok
