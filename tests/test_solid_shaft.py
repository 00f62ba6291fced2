"""3D solid shafts: geometry, rigid modes, supports/attachments against 1D models,
classification, mesh import through meshio, bad input."""
import math

import numpy as np
import pytest

from discrete.errors import ModelError
from fem import PointAttachment, Section, Segment, ShaftModel, assemble, modal_analysis
from fem.solid import ShaftMeshSpec, build_solid, solid_from_mesh, solid_modal
from validation.builders import STEEL, uniform


def _volume(solid):
    from skfem import Functional, asm

    @Functional
    def one(w):
        return 1.0 + 0.0 * w.x[0]

    return asm(one, solid.basis)


def test_stepped_hollow_geometry_is_exact_to_quadratic_order():
    """Volume of a stepped shaft with a bore: the quadratic geometry puts the arcs on the
    circles, so the error is that of quadratic arcs (~(2 pi/N)^4/N) not of polygons (~1 %)."""
    segs = [Segment(0.2, 2, Section.tube(0.06, 0.02), STEEL),
            Segment(0.3, 3, Section.tube(0.1, 0.02), STEEL),
            Segment(0.1, 1, Section.tube(0.06, 0.02), STEEL)]
    solid = build_solid(ShaftModel("bending", segs), ShaftMeshSpec(n_quarter=3))
    exact = math.pi / 4 * ((0.06**2 - 0.02**2) * 0.3 + (0.1**2 - 0.02**2) * 0.3)
    assert abs(_volume(solid) / exact - 1) < 5e-4


def test_free_free_has_six_rigid_modes():
    solid = build_solid(uniform("bending", 0.4, 3, d=0.05), ShaftMeshSpec(n_quarter=2))
    res = solid_modal(solid, 8)
    assert res.rigid_body_modes == 6 and res.kinds[:6] == ["rigid"] * 6
    assert res.omega_rad_s[6] > 0 and res.reliable.all()


def test_torsion_with_disc_matches_1d():
    """A clamped shaft with a disc (polar inertia) at the tip: the smeared disc inertia
    reproduces a rigid disc in rotation, and circular torsion is exact in 3D, so the 3D
    torsion mode equals the 1D one to the mesh error."""
    pts = [PointAttachment(x=0.5, inertia=0.02)]
    sup = [(0.0, "clamped")]
    one_d = modal_analysis(assemble(uniform("torsion", 0.5, 40, d=0.04, supports=sup, points=pts)).system, 1)
    solid = build_solid(uniform("torsion", 0.5, 6, d=0.04, supports=sup, points=pts), ShaftMeshSpec(n_quarter=2))
    res = solid_modal(solid, 6)
    tors = res.frequencies_hz[np.array(res.kinds) == "torsion"]
    assert tors[0] == pytest.approx(one_d.frequencies_hz[0], rel=1e-4)


def test_tip_mass_and_spring_support_bending():
    """Tip mass and a transverse spring support shift the bending frequency like in the
    Timoshenko model (within the 3D clamp/mesh difference of a slender shaft, 1 %)."""
    kw = dict(d=0.04, supports=[(0.0, "clamped"), (0.6, "spring", 2e5, 0.0)], points=[{"x": 0.6, "mass": 1.5}])
    ti = modal_analysis(assemble(uniform("bending", 0.6, 40, theory="timoshenko", **kw)).system, 1)
    solid = build_solid(uniform("bending", 0.6, 12, **kw), ShaftMeshSpec(n_quarter=2))
    res = solid_modal(solid, 4)
    bend = res.frequencies_hz[np.array(res.kinds) == "bending"]
    assert bend[0] == pytest.approx(ti.frequencies_hz[0], rel=1e-2)
    bare = solid_modal(build_solid(uniform("bending", 0.6, 12, d=0.04, supports=[(0.0, "clamped")]),
                                   ShaftMeshSpec(n_quarter=2)), 2)
    assert bend[0] != pytest.approx(bare.frequencies_hz[0], rel=0.05)


def test_classification_of_a_stubby_shaft():
    solid = build_solid(uniform("bending", 0.3, 6, d=0.1, supports=[(0.0, "clamped")]), ShaftMeshSpec(n_quarter=2))
    res = solid_modal(solid, 6)
    assert res.kinds[:2] == ["bending", "bending"] and res.kinds[2] == "torsion"
    assert "axial" in res.kinds
    assert np.all(res.shares.max(axis=1) > 0.8)
    d = res.to_dict()
    assert d["kinds"] == res.kinds and len(d["shares"]["torsion"]) == 6


def test_mesh_import_hex_and_tet(tmp_path):
    """Users' meshes through meshio: the package's own mesh written as straight-sided
    hexahedra (VTU and Gmsh) and read back gives identical modes in both formats; the same
    geometry split into tetrahedra with P2 fields agrees within 2 % (straight-edged P2
    tetrahedra are slightly stiffer); the polygonal (octagonal) section makes both about
    5 % softer than the curved model, so the import really uses the file's geometry."""
    import meshio

    model = uniform("bending", 0.4, 6, d=0.05, supports=[(0.0, "clamped")])
    solid = build_solid(model, ShaftMeshSpec(n_quarter=2))
    curved = solid_modal(solid, 3).frequencies_hz
    pts, cells = solid.export_points_cells()
    meshio.write(tmp_path / "shaft.vtu", meshio.Mesh(pts, cells))
    meshio.write(tmp_path / "shaft.msh", meshio.Mesh(pts, cells), file_format="gmsh22", binary=False)
    f_vtu = solid_modal(solid_from_mesh(tmp_path / "shaft.vtu", STEEL, clamped_at=(0.0,)), 3).frequencies_hz
    f_msh = solid_modal(solid_from_mesh(tmp_path / "shaft.msh", STEEL, clamped_at=(0.0,)), 3).frequencies_hz
    np.testing.assert_allclose(f_msh, f_vtu, rtol=1e-10)
    assert np.all((f_vtu / curved > 0.9) & (f_vtu / curved < 0.99))
    tet = solid.volume_grid().triangulate()
    meshio.write(tmp_path / "tet.vtu", meshio.Mesh(np.asarray(tet.points), [("tetra", tet.cells_dict[10])]))
    f_tet = solid_modal(solid_from_mesh(tmp_path / "tet.vtu", STEEL, clamped_at=(0.0,)), 3).frequencies_hz
    np.testing.assert_allclose(f_tet, f_vtu, rtol=2e-2)


def test_bad_input(tmp_path):
    explicit = ShaftModel("bending", [Segment(1.0, 4, Section(A=1e-3, I=1e-7, J=2e-7, Ip=2e-7), STEEL)])
    with pytest.raises(ModelError, match="circle' or 'tube'"):
        build_solid(explicit)
    with pytest.raises(ModelError, match="n_quarter"):
        ShaftMeshSpec(n_quarter=0)
    with pytest.raises(ModelError, match="one element count per segment"):
        build_solid(uniform("bending", 1.0, 4), ShaftMeshSpec(axial_per_segment=[1, 2]))
    with pytest.raises(ModelError, match="existing mesh file"):
        solid_from_mesh(tmp_path / "nope.msh", STEEL)


def test_solid_export_modes_and_history(tmp_path):
    """3D modes and a 3D time history go through the same export functions as 1D models."""
    from fem.output.mesh import read_modes, read_time_history, write_modes, write_time_history

    solid = build_solid(uniform("bending", 0.3, 3, d=0.1, supports=[(0.0, "clamped")]), ShaftMeshSpec(n_quarter=2))
    res = solid_modal(solid, 3)
    back = read_modes(write_modes(solid, res, tmp_path / "solid.vtu"))
    np.testing.assert_array_equal(back["fields"]["displacement"][:, :, 2], solid.displacement_field(res.shapes[:, 2]))
    np.testing.assert_array_equal(back["frequencies_hz"], res.frequencies_hz)
    assert "hexahedron" in back["cells"]
    t = np.array([0.0, 1e-4])
    h = read_time_history(write_time_history(solid, t, np.vstack([res.shapes[:, 0], -res.shapes[:, 0]]),
                                             tmp_path / "run.pvd"))
    np.testing.assert_array_equal(h["fields"]["displacement"][1], -solid.displacement_field(res.shapes[:, 0]))
