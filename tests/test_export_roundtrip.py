"""Export: mode shapes and time histories to VTU/XDMF/PVD and back, tables, bad input."""
import json

import numpy as np
import pytest

from discrete.errors import ModelError
from fem import assemble, modal_analysis
from fem.output.mesh import read_modes, read_time_history, write_modes, write_time_history
from fem.output.tablefile import read_columns, write_columns, write_modal_table
from validation.builders import uniform

L = 1.2


@pytest.fixture(scope="module", params=["euler-bernoulli", "timoshenko", "torsion", "axial"])
def fe_modes(request):
    if request.param in ("torsion", "axial"):
        model = uniform(request.param, L, 9, d=0.04, supports=[(0.0, "clamped")])
    else:
        model = uniform("bending", L, 9, d=0.04, theory=request.param, supports=[(0.0, "clamped")])
    fe = assemble(model)
    return fe, modal_analysis(fe.system, 3)


@pytest.mark.parametrize("suffix", [".vtu", ".xdmf"])
def test_modes_round_trip_exact(fe_modes, tmp_path, suffix):
    fe, res = fe_modes
    back = read_modes(write_modes(fe, res, tmp_path / f"modes{suffix}"))
    assert back["n_modes"] == 3
    np.testing.assert_array_equal(back["frequencies_hz"], res.frequencies_hz)
    np.testing.assert_array_equal(back["points"][:, 0], fe.mesh.nodes)
    assert np.all(back["points"][:, 1:] == 0.0)
    for field in fe.model.fields:
        for r in range(3):
            np.testing.assert_array_equal(back["fields"][field][:, r], fe.nodal_values(res.shapes[:, r], field)[1])


def test_vectors_for_paraview(fe_modes, tmp_path):
    """Bending writes w as the y component of 'displacement'; torsion theta as the x
    component of 'rotation'; axial u as the x component of 'displacement'."""
    fe, res = fe_modes
    back = read_modes(write_modes(fe, res, tmp_path / "m.vtu"))
    prim = fe.model.fields[0]
    vals = back["fields"][prim][:, 0]
    vec, comp = {"w": ("displacement", 1), "theta": ("rotation", 0), "u": ("displacement", 0)}[prim]
    np.testing.assert_array_equal(back["fields"][vec][:, comp, 0], vals)


def test_pyvista_reads_vtu(fe_modes, tmp_path):
    pv = pytest.importorskip("pyvista")
    fe, res = fe_modes
    mesh = pv.read(write_modes(fe, res, tmp_path / "m.vtu"))
    assert mesh.n_points == fe.mesh.nodes.size and mesh.n_cells == fe.mesh.n_elements
    prim = fe.model.fields[0]
    np.testing.assert_array_equal(mesh.point_data[f"mode2_{prim}"], fe.nodal_values(res.shapes[:, 1], prim)[1])
    np.testing.assert_array_equal(np.asarray(mesh.field_data["frequencies_hz"]), res.frequencies_hz)


@pytest.mark.parametrize("suffix", [".xdmf", ".pvd"])
def test_time_history_round_trip(tmp_path, suffix):
    fe = assemble(uniform("bending", L, 6, d=0.04, supports=[(0.0, "clamped")]))
    res = modal_analysis(fe.system, 2)
    t = np.linspace(0.0, 0.01, 7)
    Q = np.outer(np.cos(res.omega_rad_s[0] * t), res.shapes[:, 0]) + np.outer(np.sin(3 * t), res.shapes[:, 1])
    back = read_time_history(write_time_history(fe, t, Q, tmp_path / f"hist{suffix}"))
    np.testing.assert_array_equal(back["t"], t)
    for k in (0, 3, 6):
        np.testing.assert_array_equal(back["fields"]["w"][k], fe.nodal_values(Q[k], "w")[1])


def test_tables_csv_json(tmp_path):
    fe = assemble(uniform("torsion", L, 6, d=0.04, supports=[(0.0, "clamped")]))
    res = modal_analysis(fe.system, 3)
    c = read_columns(write_modal_table(res, tmp_path / "t.csv"))
    np.testing.assert_array_equal(c["f_hz"], res.frequencies_hz)
    np.testing.assert_array_equal(c["mode"], [1, 2, 3])
    j = json.loads(write_modal_table(res, tmp_path / "t.json").read_text())
    assert j["omega_rad_s"] == res.omega_rad_s.tolist()
    with pytest.raises(ModelError, match="equal length"):
        write_columns({"a": [1, 2], "b": [1]}, tmp_path / "x.csv")


def test_bad_input(tmp_path):
    fe = assemble(uniform("torsion", L, 6, d=0.04, supports=[(0.0, "clamped")]))
    res = modal_analysis(fe.system, 2)
    with pytest.raises(ModelError, match=r"\.vtu or \.xdmf"):
        write_modes(fe, res, tmp_path / "modes.png")
    blocker = tmp_path / "a_file"
    blocker.write_text("not a directory")
    with pytest.raises(ModelError, match="output directory"):
        write_modes(fe, res, blocker / "sub" / "modes.vtu")
    other = assemble(uniform("torsion", L, 8, d=0.04, supports=[(0.0, "clamped")]))
    with pytest.raises(ModelError, match="same model"):
        write_modes(other, res, tmp_path / "m.vtu")
    with pytest.raises(ModelError, match="shape"):
        write_time_history(fe, [0.0, 1.0], np.zeros((3, fe.system.n_dofs)), tmp_path / "h.xdmf")
    with pytest.raises(ModelError, match="increasing"):
        write_time_history(fe, [1.0, 0.0], np.zeros((2, fe.system.n_dofs)), tmp_path / "h.xdmf")
    with pytest.raises(ModelError, match="existing"):
        read_modes(tmp_path / "missing.vtu")
