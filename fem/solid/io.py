"""Users' own 3D meshes through meshio (Gmsh .msh, VTU, XDMF, ...): tetrahedra (4 or 10
nodes, P2 fields on straight-sided tetrahedra) or hexahedra (8 nodes, 27-node quadratic
fields).  The shaft axis is x; supports and attachments act on the sections at their x
like in :func:`fem.solid.build_solid`."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from discrete.errors import ModelError

from ..sections import Material


def solid_from_mesh(source, material: Material, clamped_at: tuple[float, ...] = (), title: str = ""):
    """A :class:`SolidModel` from a meshio mesh or file; ``clamped_at``: x positions of
    clamped sections (every node within 1e-9 L of the plane is held)."""
    import meshio
    from skfem import MeshHex1, MeshHex2, MeshTet1

    from .model import _lame, _system, assemble_solid

    if isinstance(source, (str, Path)):
        if not Path(source).is_file():
            raise ModelError("solid mesh import", "path", str(source), "an existing mesh file meshio can read")
        try:
            source = meshio.read(source)
        except Exception as exc:  # meshio raises several types for unreadable files
            raise ModelError("solid mesh import", "path", str(source), f"a mesh file meshio can read ({exc})") from exc
    blocks = {c.type: c.data for c in source.cells}
    pts = np.asarray(source.points, float)
    if pts.shape[1] != 3:
        raise ModelError("solid mesh import", "points", f"{pts.shape[1]}D", "3D coordinates")
    if "tetra" in blocks or "tetra10" in blocks:
        t = blocks.get("tetra", blocks.get("tetra10", np.zeros((0, 4), int))[:, :4])
        used = np.unique(t)
        remap = -np.ones(pts.shape[0], dtype=int)
        remap[used] = np.arange(used.size)
        mesh, ctype = MeshTet1(np.ascontiguousarray(pts[used].T), np.ascontiguousarray(remap[t].T)), "tetra"
    elif "hexahedron" in blocks:
        from .model import SKFEM_TO_VTK_HEX

        t = blocks["hexahedron"]
        vtk_to_skfem = np.argsort(SKFEM_TO_VTK_HEX)
        used = np.unique(t)
        remap = -np.ones(pts.shape[0], dtype=int)
        remap[used] = np.arange(used.size)
        mesh, ctype = MeshHex2.from_mesh(MeshHex1(np.ascontiguousarray(pts[used].T), np.ascontiguousarray(remap[t][:, vtk_to_skfem].T))), "hexahedron"
    else:
        raise ModelError("solid mesh import", "cells", sorted(blocks), "tetra, tetra10 or hexahedron cells")
    n = mesh.t.shape[1]
    mu, lam = _lame(material.E, material.G)
    solid = assemble_solid(mesh, np.full(n, mu), np.full(n, lam), np.full(n, material.rho), title=title, cell_type=ctype)
    tol = 1e-9 * solid.length
    xdof = np.tile(solid.basis.doflocs[0], 3)
    held = np.flatnonzero(np.any([np.abs(xdof - x) < tol for x in clamped_at], axis=0)) if clamped_at else np.zeros(0, int)
    solid.system = _system(solid.basis, solid.system.K, solid.system.M, held, title,
                           solid.system.mass_semidefinite_reason)     # the same M, with supports now
    return solid
