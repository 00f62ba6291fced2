"""Export of results to files: mode shapes and time histories to VTU/XDMF (meshio, for
ParaView/pyvista) with meshio.

1D models are written as polylines along the x axis (coordinates padded to 3D: y = z = 0)
with one point-data array per mode and per field (``mode3_w``, ``mode3_w_x``, ...), plus a
3-component ``mode3_displacement`` (bending: w along y; axial: u along x) and/or
``mode3_rotation`` (torsion: theta about x; bending: slope/phi about z) for ParaView's
"Warp By Vector".  3D solid models (:class:`fem.solid.SolidModel`) are written with their
tetrahedra/hexahedra and a ``mode3_displacement`` vector per mode.  Frequencies travel
with the mesh: VTU field data, XDMF grid-centred attributes.

Files are written exactly (VTU: binary, XDMF: XML text with 17 significant digits), so a
write/read round trip returns the original arrays to the last bit or within 1e-16.
"""
from __future__ import annotations

import json
import os
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from discrete.errors import ModelError

MODE_SUFFIXES = (".vtu", ".xdmf")
HISTORY_SUFFIXES = (".xdmf", ".pvd")


# ----------------------------------------------------------------- helpers
def ensure_directory(directory: str | Path, what: str = "output directory") -> Path:
    """Create ``directory`` (and parents) and check that it can be written; ModelError otherwise."""
    directory = Path(directory)
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ModelError(what, "path", str(directory), f"a directory that can be created ({exc.strerror})") from exc
    if not directory.is_dir() or not os.access(directory, os.W_OK | os.X_OK):
        raise ModelError(what, "path", str(directory), "a writable directory")
    return directory


def _check_suffix(path: Path, allowed: tuple[str, ...], what: str) -> None:
    if path.suffix.lower() not in allowed:
        raise ModelError(what, "path", str(path), "a file name ending in " + " or ".join(allowed))


def line_mesh_points(fe) -> np.ndarray:
    """Vertex coordinates of a 1D FE model padded to 3D: (n_nodes, 3) with y = z = 0."""
    x = np.asarray(fe.mesh.nodes, float)
    return np.column_stack([x, np.zeros_like(x), np.zeros_like(x)])


def _line_cells(n_points: int) -> list[tuple[str, np.ndarray]]:
    i = np.arange(n_points - 1)
    return [("line", np.column_stack([i, i + 1]))]


def _vectors(physics: str, values: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """3-component displacement/rotation vectors of one 1D mode from its nodal fields."""
    out = {}
    some = next(iter(values.values()))
    z = np.zeros_like(some)
    if "u" in values:
        out["displacement"] = np.column_stack([values["u"], z, z])
    if "w" in values:
        out["displacement"] = np.column_stack([z, values["w"], z])
        rot = values.get("w_x", values.get("phi"))
        if rot is not None:
            out["rotation"] = np.column_stack([z, z, rot])
    if "theta" in values:
        out["rotation"] = np.column_stack([values["theta"], z, z])
    return out


def _check_modes_fit(fe, modal) -> None:
    n = fe.system.n_dofs if hasattr(fe, "system") else fe.n_dofs
    if modal.shapes.shape[0] != n:
        raise ModelError("export", "modal", f"shapes with {modal.shapes.shape[0]} rows",
                         f"mode shapes of this model ({n} DOFs): run modal_analysis on the same model")


def mode_mesh(fe, modal) -> tuple[np.ndarray, list, dict[str, np.ndarray]]:
    """(points, cells, point_data) of all modes of ``modal`` on the mesh of ``fe``.

    ``fe`` is a 1D :class:`fem.assembly.FEModel` or a 3D :class:`fem.solid.SolidModel`
    (anything with a ``mode_point_data(modal)`` method)."""
    _check_modes_fit(fe, modal)
    if hasattr(fe, "mode_point_data"):
        return fe.mode_point_data(modal)
    points = line_mesh_points(fe)
    data: dict[str, np.ndarray] = {}
    for r in range(modal.shapes.shape[1]):
        values = {}
        for field in fe.model.fields:
            x, v = fe.nodal_values(modal.shapes[:, r], field)
            values[field] = np.asarray(v, float)
            data[f"mode{r + 1}_{field}"] = values[field]
        for name, vec in _vectors(fe.model.physics, values).items():
            data[f"mode{r + 1}_{name}"] = vec
    return points, _line_cells(points.shape[0]), data


# ------------------------------------------------------------------- modes
def write_modes(fe, modal, path: str | Path) -> Path:
    """Write all mode shapes of ``modal`` (computed on ``fe``) to ``path`` (.vtu or .xdmf)."""
    import meshio

    path = Path(path)
    _check_suffix(path, MODE_SUFFIXES, "mode-shape export")
    ensure_directory(path.parent)
    points, cells, point_data = mode_mesh(fe, modal)
    freqs = np.asarray(modal.frequencies_hz, float)
    omegas = np.asarray(modal.omega_rad_s, float)
    mesh = meshio.Mesh(points, cells, point_data=point_data)
    if path.suffix.lower() == ".vtu":
        meshio.write(path, mesh, file_format="vtu", binary=True)
        _vtu_add_field_data(path, {"frequencies_hz": freqs, "omega_rad_s": omegas})
    else:
        meshio.xdmf.write(path, mesh, data_format="XML")
        _xdmf_add_grid_attributes(path, {"frequencies_hz": freqs, "omega_rad_s": omegas})
    return path


def _vtu_add_field_data(path: Path, values: dict[str, np.ndarray]) -> None:
    """Add a FieldData block (meshio's VTU writer does not write field data) in ASCII
    with repr() values, which round-trip doubles exactly."""
    tree = ET.parse(path)
    grid = tree.getroot().find("UnstructuredGrid")
    block = ET.Element("FieldData")
    for name, arr in values.items():
        da = ET.SubElement(block, "DataArray", type="Float64", Name=name, NumberOfTuples=str(arr.size),
                           format="ascii")
        da.text = " ".join(repr(float(v)) for v in arr)
    grid.insert(0, block)
    tree.write(path, xml_declaration=True)


def _xdmf_add_grid_attributes(path: Path, values: dict[str, np.ndarray]) -> None:
    """Store mode metadata in the grid of an XDMF file as an ``Information`` element
    (Name = "drivefem", Value = JSON; floats written with repr(), exact).  The element's text
    is an empty XML tag so that meshio's reader, which parses it as gmsh tags, accepts it."""
    tree = ET.parse(path)
    grid = tree.getroot().find("Domain/Grid")
    info = ET.SubElement(grid, "Information", Name="drivefem",
                         Value=json.dumps({k: np.asarray(v, float).tolist() for k, v in values.items()}))
    info.text = "<drivefem/>"
    tree.write(path)


def _xdmf_grid_attributes(path: Path) -> dict[str, np.ndarray]:
    for info in ET.parse(path).getroot().iter("Information"):
        if info.get("Name") == "drivefem":
            return {k: np.asarray(v, float) for k, v in json.loads(info.get("Value")).items()}
    return {}


def read_modes(path: str | Path) -> dict:
    """Read a file written by :func:`write_modes`.

    Returns ``{"points": (n, 3), "frequencies_hz", "omega_rad_s", "n_modes",
    "fields": {name: (n_points, n_modes) or (n_points, 3, n_modes)}}``."""
    import meshio

    path = Path(path)
    _check_suffix(path, MODE_SUFFIXES, "mode-shape import")
    if not path.is_file():
        raise ModelError("mode-shape import", "path", str(path), "an existing .vtu or .xdmf file")
    mesh = meshio.read(path)
    meta = dict(mesh.field_data) if path.suffix.lower() == ".vtu" else _xdmf_grid_attributes(path)
    per_field: dict[str, dict[int, np.ndarray]] = {}
    for name, arr in mesh.point_data.items():
        if not name.startswith("mode"):
            continue
        head, _, field = name.partition("_")
        per_field.setdefault(field, {})[int(head[4:])] = np.asarray(arr, float)
    fields = {f: np.stack([d[k] for k in sorted(d)], axis=-1) for f, d in per_field.items()}
    freqs = np.asarray(meta.get("frequencies_hz", []), float).ravel()
    return {"points": np.asarray(mesh.points, float), "cells": {c.type: c.data for c in mesh.cells},
            "frequencies_hz": freqs, "omega_rad_s": np.asarray(meta.get("omega_rad_s", []), float).ravel(),
            "n_modes": int(freqs.size), "fields": fields}


# ----------------------------------------------------------- time histories
def _history_point_data(fe, q: np.ndarray) -> dict[str, np.ndarray]:
    if hasattr(fe, "displacement_field"):
        return {"displacement": fe.displacement_field(q)}
    return {field: np.asarray(fe.nodal_values(q, field)[1], float) for field in fe.model.fields}


def write_time_history(fe, t, Q, path: str | Path) -> Path:
    """Write the FE time history ``Q`` (n_times x n_dofs, full-length DOF vectors) at times
    ``t`` to ``path``: ``.xdmf`` (one temporal collection, XML data) or ``.pvd`` (a ParaView
    collection of one VTU file per step in ``<stem>_steps/``)."""
    import meshio

    path = Path(path)
    _check_suffix(path, HISTORY_SUFFIXES, "time-history export")
    t = np.asarray(t, float).ravel()
    Q = np.asarray(Q, float)
    n = fe.system.n_dofs if hasattr(fe, "system") else fe.n_dofs
    if Q.ndim != 2 or Q.shape != (t.size, n):
        raise ModelError("time-history export", "Q", f"array of shape {Q.shape}",
                         f"shape (len(t), n_dofs) = ({t.size}, {n})")
    if t.size and np.any(np.diff(t) <= 0):
        raise ModelError("time-history export", "t", "non-increasing times", "strictly increasing times")
    ensure_directory(path.parent)
    if hasattr(fe, "mode_point_data"):
        points, cells = fe.export_points_cells()
    else:
        points = line_mesh_points(fe)
        cells = _line_cells(points.shape[0])
    if path.suffix.lower() == ".xdmf":
        with meshio.xdmf.TimeSeriesWriter(path, data_format="XML") as writer:
            writer.write_points_cells(points, cells)
            for k in range(t.size):
                writer.write_data(float(t[k]), point_data=_history_point_data(fe, Q[k]))
        return path
    steps = ensure_directory(path.parent / f"{path.stem}_steps")
    root = ET.Element("VTKFile", type="Collection", version="0.1")
    coll = ET.SubElement(root, "Collection")
    for k in range(t.size):
        name = f"{path.stem}_{k:05d}.vtu"
        meshio.write(steps / name, meshio.Mesh(points, cells, point_data=_history_point_data(fe, Q[k])),
                     file_format="vtu", binary=True)
        ET.SubElement(coll, "DataSet", timestep=repr(float(t[k])), part="0", file=f"{steps.name}/{name}")
    ET.ElementTree(root).write(path, xml_declaration=True)
    return path


def read_time_history(path: str | Path) -> dict:
    """Read a file written by :func:`write_time_history`:
    ``{"t": (n_t,), "points": (n, 3), "fields": {name: (n_t, n_points[, 3])}}``."""
    import meshio

    path = Path(path)
    _check_suffix(path, HISTORY_SUFFIXES, "time-history import")
    if not path.is_file():
        raise ModelError("time-history import", "path", str(path), "an existing .xdmf or .pvd file")
    times, frames = [], []
    if path.suffix.lower() == ".xdmf":
        with meshio.xdmf.TimeSeriesReader(path) as reader:
            points, _ = reader.read_points_cells()
            for k in range(reader.num_steps):
                tk, pd, _ = reader.read_data(k)
                times.append(float(tk))
                frames.append(pd)
    else:
        points = None
        for ds in ET.parse(path).getroot().iter("DataSet"):
            m = meshio.read(path.parent / ds.get("file"))
            points = m.points if points is None else points
            times.append(float(ds.get("timestep")))
            frames.append(m.point_data)
    names = frames[0].keys() if frames else []
    return {"t": np.array(times), "points": np.asarray(points, float),
            "fields": {n: np.stack([np.asarray(f[n], float) for f in frames]) for n in names}}
