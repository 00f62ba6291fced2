"""Geometry of rendered mode shapes (pyvista meshes only; no plotting here).

1D models: the shaft is drawn as a tube of its own (stepped) radius around the deformed
centre line, sampled inside the elements with the element's own interpolation (Hermite
cubic for Euler-Bernoulli, Lagrange P1/P2 otherwise), so coarse meshes still look smooth.
Bending displaces the centre line along y, axial motion along x (rings mark material
sections), torsion twists the cylinder surface about x (generator lines show the twist).
The amplitude is scaled for display: bending to 15 % of the length, axial to 5 %,
torsion to 60 degrees; the radius is enlarged for display when the shaft is very slender.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

DISPLAY_AMPLITUDE = {"bending": 0.15, "axial": 0.05, "torsion": math.radians(60.0)}
MIN_RADIUS = {"bending": 0.02, "axial": 0.03, "torsion": 0.05}   # fraction of the length


@dataclass
class ModeScene:
    """Everything to draw for one mode: meshes with their roles, the title, the view."""

    title: str
    view: str                                   # "xy" (bending) or "oblique"
    deformed: object                            # pyvista mesh coloured by "amplitude"
    undeformed: list = field(default_factory=list)   # faint reference geometry
    lines: list = field(default_factory=list)        # dark lines drawn on the deformed body
    markers: list = field(default_factory=list)      # supports / attachments (grey)
    scale: float = 1.0                          # display scale applied to the mode values
    amplitude_label: str = "amplitude"
    #: for scenes whose geometry is linear in the animation factor: (base points,
    #: displacement per unit factor) of each moving mesh (deformed first, then lines)
    linear_motion: list | None = None


# ------------------------------------------------------------ sampling
def sample_field(fe, q: np.ndarray, field: str, per_element: int = 8) -> tuple[np.ndarray, np.ndarray]:
    """(x, value) of ``field`` inside every element with the element's interpolation."""
    sys = fe.system
    xv, v = fe.nodal_values(q, field)
    if field == "w" and "w_x" in fe.model.fields:
        _, s = fe.nodal_values(q, "w_x")
        xs, vals = [], []
        for e in range(xv.size - 1):
            h = xv[e + 1] - xv[e]
            t = np.linspace(0.0, 1.0, per_element + 1)[:-1]
            h00, h10 = 2 * t**3 - 3 * t**2 + 1, t**3 - 2 * t**2 + t
            h01, h11 = -2 * t**3 + 3 * t**2, t**3 - t**2
            xs.append(xv[e] + h * t)
            vals.append(h00 * v[e] + h10 * h * s[e] + h01 * v[e + 1] + h11 * h * s[e + 1])
        return np.append(np.concatenate(xs), xv[-1]), np.append(np.concatenate(vals), v[-1])
    idx = np.flatnonzero(sys.dof_field == field)
    xa, va = sys.dof_x[idx], np.asarray(q)[idx]
    order = np.argsort(xa)
    xa, va = xa[order], va[order]
    if xa.size == 2 * xv.size - 1:   # P2: vertex, mid, vertex per element
        xs, vals = [], []
        for e in range(xv.size - 1):
            x0, xm, x1 = xa[2 * e: 2 * e + 3]
            f0, fm, f1 = va[2 * e: 2 * e + 3]
            t = np.linspace(x0, x1, per_element + 1)[:-1]
            l0 = (t - xm) * (t - x1) / ((x0 - xm) * (x0 - x1))
            lm = (t - x0) * (t - x1) / ((xm - x0) * (xm - x1))
            l1 = (t - x0) * (t - xm) / ((x1 - x0) * (x1 - xm))
            xs.append(t)
            vals.append(l0 * f0 + lm * fm + l1 * f1)
        return np.append(np.concatenate(xs), xa[-1]), np.append(np.concatenate(vals), va[-1])
    return xv, v


def segment_radii(model) -> tuple[np.ndarray, np.ndarray]:
    """Segment end coordinates (n+1,) and outer radius of each segment (n,)."""
    ends = np.concatenate(([0.0], np.cumsum([s.length for s in model.segments])))
    radii = []
    for s in model.segments:
        d = s.section.d
        if d is None:
            d = math.sqrt(4 * s.section.A / math.pi) if math.isfinite(s.section.A) else 0.02 * model.length
        radii.append(0.5 * d)
    return ends, np.asarray(radii)


def _with_steps(x: np.ndarray, values: list[np.ndarray], ends: np.ndarray, radii: np.ndarray):
    """Insert every segment end into the samples twice (left and right radius), so steps
    are drawn as vertical faces."""
    xs, vs, rs = [], [[] for _ in values], []
    for k in range(radii.size):
        a, b = ends[k], ends[k + 1]
        inside = (x > a + 1e-12 * ends[-1]) & (x < b - 1e-12 * ends[-1])
        xk = np.concatenate(([a], x[inside], [b]))
        xs.append(xk)
        rs.append(np.full(xk.size, radii[k]))
        for j, v in enumerate(values):
            vs[j].append(np.interp(xk, x, v))
    return np.concatenate(xs), [np.concatenate(v) for v in vs], np.concatenate(rs)


def tube(centre: np.ndarray, tangent: np.ndarray, radius: np.ndarray, scalars: np.ndarray,
         twist: np.ndarray | None = None, n_theta: int = 32):
    """Closed tube surface around a centre line in the xy plane (a StructuredGrid with the
    point array ``amplitude``); ``twist`` rotates each ring about the local axis."""
    import pyvista as pv

    t = tangent / np.linalg.norm(tangent, axis=1, keepdims=True)
    e1 = np.column_stack([-t[:, 1], t[:, 0], np.zeros(len(t))])
    e2 = np.array([0.0, 0.0, 1.0])
    a = np.linspace(0, 2 * np.pi, n_theta + 1)[None, :]
    if twist is not None:
        a = a + twist[:, None]
    pts = (centre[:, None, :] + radius[:, None, None] * (np.cos(a)[..., None] * e1[:, None, :]
                                                          + np.sin(a)[..., None] * e2[None, None, :]))
    grid = pv.StructuredGrid(pts[..., 0], pts[..., 1], pts[..., 2])
    grid.point_data["amplitude"] = np.repeat(np.asarray(scalars, float)[:, None], n_theta + 1, axis=1).ravel(order="F")
    return grid


def _polyline(points: np.ndarray):
    import pyvista as pv

    return pv.lines_from_points(points)


def _markers(model, ends, radii, y_at) -> list:
    """Grey blocks at supports (clamped: a wall; pinned/spring: a smaller block) and discs at
    point attachments, placed on the deformed centre line where that moves."""
    import pyvista as pv

    L, r = ends[-1], radii.max()
    out = []
    for s in model.supports:
        h = 3.0 * r if s.type == "clamped" else 1.6 * r
        wdt = 0.02 * L if s.type == "clamped" else 0.015 * L
        cx = s.x - wdt / 2 if s.x <= 0.5 * L else s.x + wdt / 2
        out.append(pv.Box(bounds=(cx - wdt / 2, cx + wdt / 2, -h, h, -h, h)))
    for p in model.points:
        rr = 1.8 * r if (p.inertia or p.mass) else 1.2 * r
        out.append(pv.Cylinder(center=(p.x, y_at(p.x), 0.0), direction=(1, 0, 0), radius=rr, height=0.012 * L))
    return out


def _model_title(model) -> str:
    """The model file's title as the picture's first line ("" without one)."""
    title = " ".join(str(getattr(model, "title", "") or "").split())
    return f"{title}\n" if title else ""


def mode_scene(fe, modal, r: int, kind: str | None = None, factor: float = 1.0) -> ModeScene:
    """The scene of mode ``r`` (0-based) of the 1D FE model ``fe``; ``factor`` multiplies
    the displayed deformation (animation phase), not the colours."""
    model = fe.model
    q = modal.shapes[:, r]
    L = model.length
    physics = model.physics
    ends, radii = segment_radii(model)
    enlarge = max(1.0, MIN_RADIUS[physics] * L / radii.max())
    radii_d = radii * enlarge
    field = model.fields[0]
    x, v = sample_field(fe, q, field)
    peak = float(np.max(np.abs(v))) or 1.0
    scale = DISPLAY_AMPLITUDE[physics] * (L if physics != "torsion" else 1.0) / peak
    amp = np.abs(v) / peak
    geo = scale * factor
    xs, (vs, amps), rs = _with_steps(x, [v, amp], ends, radii_d)
    freq = modal.frequencies_hz[r]
    label = {"bending": "w", "axial": "u", "torsion": "theta"}[physics]
    title = _model_title(model) + f"mode {r + 1}: f = {freq:.5g} Hz" + (f"  ({kind})" if kind else f"  ({physics})")
    if enlarge > 1.0:
        title += f"\nradius x{enlarge:.3g} for display"
    zeros = np.zeros_like(xs)
    straight = np.column_stack([xs, zeros, zeros])
    faint = [_polyline(np.array([[0.0, 0, 0], [L, 0, 0]]))]
    if physics == "bending":
        centre = np.column_stack([xs, geo * vs, zeros])
        slope = geo * np.interp(xs, x, np.gradient(v, x)) if x.size > 2 else np.zeros_like(xs)
        tangent = np.column_stack([np.ones_like(xs), slope, zeros])
        body = tube(centre, tangent, rs, amps)
        faint.append(tube(straight, np.column_stack([np.ones_like(xs), zeros, zeros]), rs, zeros, n_theta=16))
        lines = []
        return ModeScene(title=title, view="xy", deformed=body, undeformed=faint, lines=lines,
                         markers=_markers(model, ends, radii_d, lambda xp: geo * np.interp(xp, x, v)),
                         scale=scale, amplitude_label=f"amplitude of {label}")
    tangent = np.column_stack([np.ones_like(xs), zeros, zeros])
    if physics == "torsion":
        body = tube(straight, tangent, rs, amps, twist=geo * vs)
        lines, ghosts = [], []
        for a0 in np.linspace(0, 2 * np.pi, 12, endpoint=False):
            ang = a0 + geo * vs
            lines.append(_polyline(np.column_stack([xs, 1.01 * rs * np.cos(ang), 1.01 * rs * np.sin(ang)])))
            ghosts.append(_polyline(np.column_stack([xs, 1.02 * rs * np.cos(a0 + 0 * vs), 1.02 * rs * np.sin(a0 + 0 * vs)])))
        return ModeScene(title=title, view="oblique", deformed=body, undeformed=faint + ghosts, lines=lines,
                         markers=_markers(model, ends, radii_d, lambda xp: 0.0), scale=scale,
                         amplitude_label="twist angle theta")
    moved = np.column_stack([xs + geo * vs, zeros, zeros])
    body = tube(moved, tangent, rs, amps)
    lines, ghosts = [], []
    xn = fe.mesh.nodes
    stride = max(1, xn.size // 24)
    for xk in xn[::stride]:
        rk = np.interp(xk, xs, rs) * 1.03
        a = np.linspace(0, 2 * np.pi, 33)
        uk = geo * np.interp(xk, x, v)
        lines.append(_polyline(np.column_stack([np.full(33, xk + uk), rk * np.cos(a), rk * np.sin(a)])))
        ghosts.append(_polyline(np.column_stack([np.full(33, xk), rk * np.cos(a), rk * np.sin(a)])))
    return ModeScene(title=title, view="oblique", deformed=body, undeformed=faint + ghosts, lines=lines,
                     markers=_markers(model, ends, radii_d, lambda xp: 0.0), scale=scale, amplitude_label="amplitude of u")


def surface_grid_lines(surf, n_generators: int = 8, n_rings: int = 8):
    """Generator lines (constant angle about x) and rings (constant x) drawn on a shaft
    surface, carrying its point data; warped with the surface they show twist and bending."""
    import pyvista as pv

    p = surf.points
    theta = np.arctan2(p[:, 2], p[:, 1])
    parts = []
    for alpha in np.pi * np.arange(n_generators // 2) / (n_generators // 2):
        surf.point_data["_gen"] = np.sin(theta - alpha)
        parts.append(surf.contour(isosurfaces=[0.0], scalars="_gen"))
    x0, x1 = p[:, 0].min(), p[:, 0].max()
    surf.point_data["_x"] = p[:, 0]
    parts.append(surf.contour(isosurfaces=list(np.linspace(x0, x1, n_rings + 2)[1:-1]), scalars="_x"))
    for key in ("_gen", "_x"):
        del surf.point_data[key]
    lines = pv.merge([q for q in parts if q.n_points]) if any(q.n_points for q in parts) else pv.PolyData()
    if lines.n_points:           # lift the lines 1 % off the surface so they are not hidden in it
        pts = lines.points.copy()
        pts[:, 1:] *= 1.01
        lines.points = pts
    return lines


def solid_scene(solid, modal, r: int, kind: str | None = None, factor: float = 1.0) -> ModeScene:
    """Warped outer surface of a 3D solid model for mode ``r`` coloured by the displacement
    magnitude, with the (warped) surface mesh lines so that twist is visible, and the
    undeformed outline faint.  Display amplitude: 10 % of the length for the largest
    displacement."""
    q = modal.shapes[:, r]
    surf = solid.surface_with_displacement(q)
    edges = surface_grid_lines(surf)
    disp = np.asarray(surf.point_data["displacement"])
    mag = np.linalg.norm(disp, axis=1)
    peak = float(np.max(np.linalg.norm(solid.displacement_field(q), axis=1))) or 1.0
    scale = 0.1 * solid.length / peak
    warped = surf.copy()
    warped.points = surf.points + scale * factor * disp
    warped.point_data["amplitude"] = mag / peak
    lines = edges.copy()
    lines.points = edges.points + scale * factor * np.asarray(edges.point_data["displacement"])
    title = _model_title(solid.model) + f"mode {r + 1}: f = {modal.frequencies_hz[r]:.5g} Hz  ({kind or 'solid'})"
    motion = [(surf.points.copy(), scale * disp), (edges.points.copy(), scale * np.asarray(edges.point_data["displacement"]))]
    return ModeScene(title=title, view="oblique", deformed=warped, undeformed=[surf.copy()],
                     lines=[lines], scale=scale, amplitude_label="displacement magnitude", linear_motion=motion)
