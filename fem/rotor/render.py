"""Off-screen 3D pictures of whirling rotor modes (pyvista; no display, no X server).

The deformed shaft at the phase theta of a complex mode phi is the centre line
(x, Re(V(x) e^{i theta}), Re(W(x) e^{i theta})), interpolated inside every element with the
element's own Timoshenko shape functions, drawn as a tube of the shaft's radius (enlarged for
display when the shaft is slender) and coloured by the local orbit size; discs are drawn
square to the deformed axis, the orbits of the nodes (ellipses traced over one period) as thin
lines, bearings as grey blocks.  ``render_whirl`` writes a PNG, ``render_whirl_gif`` one
period as an animated GIF (the phase advancing as e^{i omega t}: a forward mode turns the
same way as the spin, counter-clockwise looking from +x).  The backend selection (OSMesa or
EGL, no X server) is :mod:`fem.render.backend`'s.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from discrete.errors import ModelError

from ..render.backend import configure_environment, require
from . import elements as el
from .assembly import RotorSystem

WINDOW = (1200, 700)
DISPLAY_AMPLITUDE = 0.12     # largest whirl radius drawn as this fraction of the length
MIN_RADIUS = 0.012           # tube radius at least this fraction of the length
MAX_DISC = 0.22              # disc radius drawn at most this fraction of the length (a big fan would hide the shaft)
WHIRL_COLOUR = {"forward": (0.12, 0.47, 0.71), "backward": (0.84, 0.15, 0.16)}
PER_ELEMENT = 6
GIF_FRAMES = 24


def _centre_line(rs: RotorSystem, phi: np.ndarray, theta: float, scale: float):
    """Sampled (x, y, z) of the deformed axis and the orbit size at the samples."""
    nd = rs.node_dofs
    xi = np.linspace(0.0, 1.0, PER_ELEMENT + 1)[:-1]
    n0, n1 = rs.element_nodes[:, 0], rs.element_nodes[:, 1]
    Le = rs.node_x[n1] - rs.node_x[n0]
    Nd = el.shape_functions(Le, rs.shear_parameter, xi)[0]               # (E, Q, 4)
    e = np.exp(1j * theta)
    qy = np.stack([phi[nd["v"][n0]], phi[nd["theta_z"][n0]], phi[nd["v"][n1]], phi[nd["theta_z"][n1]]], axis=1)
    qz = np.stack([phi[nd["w"][n0]], -phi[nd["theta_y"][n0]], phi[nd["w"][n1]], -phi[nd["theta_y"][n1]]], axis=1)
    V = np.einsum("eqi,ei->eq", Nd, qy)
    W = np.einsum("eqi,ei->eq", Nd, qz)
    x = rs.node_x[n0][:, None] + Le[:, None] * xi[None, :]
    x, V, W = x.ravel(), V.ravel(), W.ravel()
    x = np.append(x, rs.node_x[n1[-1]])
    V = np.append(V, phi[nd["v"][n1[-1]]])
    W = np.append(W, phi[nd["w"][n1[-1]]])
    size = 0.5 * (np.abs(V + 1j * W) + np.abs(np.conj(V) + 1j * np.conj(W)))
    pts = np.column_stack([x, scale * (V * e).real, scale * (W * e).real])
    return pts, size * scale


def _radius_at(rs: RotorSystem, x: np.ndarray) -> np.ndarray:
    ends = np.concatenate(([0.0], np.cumsum([s.length for s in rs.rotor.segments])))
    r = np.zeros_like(x)
    for k, s in enumerate(rs.rotor.segments):
        inside = (x >= ends[k] - 1e-12) & (x <= ends[k + 1] + 1e-12)
        t = (x[inside] - ends[k]) / s.length
        r[inside] = [0.5 * s.outer_diameter(u) for u in t] if s.layers else 0.5 * (s.d + (s.outer_end - s.d) * t)
    return r


def _tube(points: np.ndarray, radius: np.ndarray, scalars: np.ndarray, n_theta: int = 24):
    """Tube around a 3D centre line (a StructuredGrid carrying the point array ``amplitude``)."""
    import pyvista as pv

    t = np.gradient(points, axis=0)
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    ref = np.array([0.0, 0.0, 1.0])
    e1 = np.cross(t, ref)
    e1 /= np.linalg.norm(e1, axis=1, keepdims=True)
    e2 = np.cross(t, e1)
    a = np.linspace(0, 2 * np.pi, n_theta + 1)[None, :, None]
    pts = points[:, None, :] + radius[:, None, None] * (np.cos(a) * e1[:, None, :] + np.sin(a) * e2[:, None, :])
    grid = pv.StructuredGrid(pts[..., 0], pts[..., 1], pts[..., 2])
    grid.point_data["amplitude"] = np.repeat(np.asarray(scalars, float)[:, None], n_theta + 1, axis=1).ravel(order="F")
    return grid


def _disc_mesh(centre, axis, radius, thickness):
    import pyvista as pv

    return pv.Cylinder(center=centre, direction=axis, radius=radius, height=thickness, resolution=48)


def _scene_parts(rs: RotorSystem, phi: np.ndarray, theta: float, scale: float):
    L = rs.rotor.length
    pts, size = _centre_line(rs, phi, theta, scale)
    rad = np.maximum(_radius_at(rs, pts[:, 0]), MIN_RADIUS * L)
    parts = {"shaft": _tube(pts, rad, size)}
    nd = rs.node_dofs
    e = np.exp(1j * theta)
    discs = []
    r_shaft = float(rad.max())
    for d in rs.rotor.discs:
        i = rs.node(d.x)
        c = np.array([d.x, scale * (phi[nd["v"][i]] * e).real, scale * (phi[nd["w"][i]] * e).real])
        # axis of the disc: the deformed tangent (theta_z = dv/dx, theta_y = -dw/dx)
        ax_ = np.array([1.0, scale * (phi[nd["theta_z"][i]] * e).real, -scale * (phi[nd["theta_y"][i]] * e).real])
        rd = np.sqrt(2 * d.Ip / d.mass) if d.mass > 0 and d.Ip > 0 else 2.5 * r_shaft
        discs.append(_disc_mesh(c, ax_, min(max(rd, 2.0 * r_shaft), MAX_DISC * L), max(0.015 * L, 0.5 * r_shaft)))
    parts["discs"] = discs
    return parts


def _orbit_lines(rs: RotorSystem, phi: np.ndarray, scale: float, n: int = 97):
    import pyvista as pv

    nd = rs.node_dofs
    t = np.exp(1j * np.linspace(0, 2 * np.pi, n))
    out = []
    step = max(1, rs.node_x.size // 16)
    picks = sorted(set(range(0, rs.node_x.size, step)) | {rs.node(d.x) for d in rs.rotor.discs})
    for i in picks:
        y, z = scale * (phi[nd["v"][i]] * t).real, scale * (phi[nd["w"][i]] * t).real
        out.append(pv.lines_from_points(np.column_stack([np.full(n, rs.node_x[i]), y, z])))
    return out


def _arc_arrow(x0: float, radius: float, sense: float, colour, start: float = 0.0):
    """A 3/4 circle about the +x axis at x0 with an arrowhead: ``sense`` +1 turns from +y towards +z
    (the spin's sense), -1 the other way."""
    import pyvista as pv

    a = start + sense * np.linspace(0.0, 1.5 * np.pi, 48)
    arc = np.column_stack([np.full(a.size, x0), radius * np.cos(a), radius * np.sin(a)])
    tangent = sense * np.array([0.0, -np.sin(a[-1]), np.cos(a[-1])])
    head = pv.Cone(center=arc[-1] + 0.18 * radius * tangent, direction=tangent, height=0.36 * radius,
                   radius=0.14 * radius, resolution=16)
    return [(pv.Spline(arc, 96).tube(radius=0.025 * radius), colour), (head, colour)]


def _direction_marks(rs: RotorSystem, phi: np.ndarray, scale: float, whirl: str):
    """The spin: a grey arc with an arrowhead about +x before the shaft's start; the whirl: a
    coloured arc (blue forward, red backward) around the shaft where the orbit is largest, turning
    the way the orbits run."""
    nd = rs.node_dofs
    V, W = phi[nd["v"]], phi[nd["w"]]
    i = int(np.argmax(np.abs(V) + np.abs(W)))
    L = rs.rotor.length
    r_tube = max(float(np.max(_radius_at(rs, rs.node_x))), MIN_RADIUS * L)
    marks = _arc_arrow(-0.06 * L, 2.2 * r_tube, 1.0, (0.3, 0.3, 0.3))
    if whirl in WHIRL_COLOUR:
        orbit = scale * float(np.abs(V[i]) + np.abs(W[i]))
        x = float(np.clip(rs.node_x[i], 0.04 * L, 0.96 * L))
        marks += _arc_arrow(x, orbit + 2.6 * r_tube, 1.0 if whirl == "forward" else -1.0, WHIRL_COLOUR[whirl],
                            start=0.25 * np.pi)
    return marks


def _bearings(rs: RotorSystem, r_shaft: float):
    import pyvista as pv

    L = rs.rotor.length
    h = 2.2 * r_shaft
    w = 0.02 * L
    return [pv.Box(bounds=(b.x - w / 2, b.x + w / 2, -h, h, -h - 1.5 * h, -h)) for b in rs.rotor.bearings]


def _scale(rs: RotorSystem, phi: np.ndarray) -> float:
    amp = np.abs(phi[rs.node_dofs["v"]]) + np.abs(phi[rs.node_dofs["w"]])
    big = float(amp.max())
    if big == 0:
        raise ModelError("render", "mode", 0, "a mode with lateral motion (this one is axial or torsional)")
    return DISPLAY_AMPLITUDE * rs.rotor.length / big


def _title(modes, r, model_title: str = "") -> str:
    ld = modes.log_decrement[r]
    w = modes.whirl[r]
    sense = {"forward": "FORWARD whirl (orbits turn with the spin)",
             "backward": "BACKWARD whirl (orbits turn against the spin)"}.get(w, f"{w} whirl")
    head = f"{model_title}\n" if model_title else ""
    return (f"{head}mode {r + 1}: {modes.omega_damped_rad_s[r]:.5g} rad/s ({modes.frequencies_hz[r]:.4g} Hz), {sense}, "
            f"log dec {ld:.3g}\nspeed {modes.speed_rad_s * 30 / np.pi:.0f} rev/min; grey arc: spin about +x; coloured arc: whirl "
            "direction; colour: orbit size; lines: orbits over one period")


def _plotter(window):
    import pyvista as pv

    configure_environment()
    p = pv.Plotter(off_screen=True, window_size=window)
    p.background_color = "white"
    return p


def _draw(p, rs, phi, theta, scale, title, font_size=11, whirl=""):
    parts = _scene_parts(rs, phi, theta, scale)
    vmax = float(parts["shaft"].point_data["amplitude"].max()) or 1.0
    actors = {"shaft": p.add_mesh(parts["shaft"], scalars="amplitude", cmap="plasma", clim=(0, vmax),
                                  show_scalar_bar=False, smooth_shading=True, specular=0.3)}
    actors["discs"] = [p.add_mesh(d, color=(0.35, 0.45, 0.6), smooth_shading=True, opacity=0.55) for d in parts["discs"]]
    for line in _orbit_lines(rs, phi, scale):
        p.add_mesh(line, color=(0.15, 0.15, 0.15), line_width=1.5)
    for mesh, colour in _direction_marks(rs, phi, scale, whirl):
        p.add_mesh(mesh, color=colour, smooth_shading=True)
    r_shaft = max(float(np.max(_radius_at(rs, rs.node_x))), MIN_RADIUS * rs.rotor.length)
    for b in _bearings(rs, r_shaft):
        p.add_mesh(b, color=(0.6, 0.6, 0.6), opacity=0.8)
    p.add_text(title, position="upper_left", font_size=font_size, color="black")
    return parts, actors


def _camera(p, rs):
    L = rs.rotor.length
    p.camera.focal_point = (0.5 * L, 0.0, 0.0)
    p.camera.position = (0.5 * L - 0.9 * L, -1.4 * L, 0.75 * L)
    p.camera.up = (0.0, 0.0, 1.0)
    p.enable_parallel_projection()
    p.reset_camera()
    p.camera.zoom(1.45)
    p.camera_set = True


def _check_mode(modes, r):
    if isinstance(r, bool) or not isinstance(r, (int, np.integer)) or not 0 <= r < modes.n_modes:
        raise ModelError("render", "mode", r, f"a mode index from 0 to {modes.n_modes - 1}")


def render_whirl(rs: RotorSystem, modes, r: int, path, *, theta: float = 0.0, title: str = "") -> Path:
    """PNG of mode ``r`` (0-based) of ``modes`` (a :class:`fem.rotor.modal.RotorModes` of ``rs``);
    ``title``: the model's, above the mode's description."""
    _check_mode(modes, r)
    require()
    import imageio.v2 as imageio

    phi = modes.shapes[:, r]
    scale = _scale(rs, phi)
    p = _plotter(WINDOW)
    try:
        _draw(p, rs, phi, theta, scale, _title(modes, r, title), whirl=modes.whirl[r])
        _camera(p, rs)
        img = np.asarray(p.screenshot(return_img=True))[..., :3]
    finally:
        p.close()
    path = Path(path)
    imageio.imwrite(path, img)
    return path


def render_whirl_gif(rs: RotorSystem, modes, r: int, path, *, frames: int = GIF_FRAMES, title: str = "") -> Path:
    """Animated GIF of one period of mode ``r``: the geometry is built once and its points
    updated per frame; the camera stays fixed."""
    _check_mode(modes, r)
    require()
    import imageio.v2 as imageio

    phi = modes.shapes[:, r]
    scale = _scale(rs, phi)
    p = _plotter((WINDOW[0] // 2, WINDOW[1] // 2))
    images = []
    try:
        parts, actors = _draw(p, rs, phi, 0.0, scale, _title(modes, r, title), font_size=7, whirl=modes.whirl[r])
        _camera(p, rs)
        for k in range(frames):
            theta = 2 * np.pi * k / frames
            now = _scene_parts(rs, phi, theta, scale)
            parts["shaft"].points = now["shaft"].points
            for d_old, d_new in zip(parts["discs"], now["discs"]):
                d_old.points = d_new.points
            p.render()
            images.append(np.asarray(p.screenshot(return_img=True))[..., :3])
    finally:
        p.close()
    path = Path(path)
    imageio.mimsave(path, images, duration=1.0 / 12, loop=0)
    return path
