"""PNG and GIF files of mode shapes, drawn off screen with pyvista from :mod:`.scene`."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from discrete.errors import ModelError

from .backend import configure_environment, require
from .scene import ModeScene, mode_scene, solid_scene

WINDOW = (1200, 600)
CMAP = "plasma"
GIF_FRAMES = 24


def _is_solid(fe) -> bool:
    return hasattr(fe, "surface_with_displacement")


def mode_indices(modal, modes) -> list[int]:
    """0-based indices of the requested 1-based ``modes`` (None: all computed modes)."""
    n = modal.omega_rad_s.size
    if modes is None:
        return list(range(n))
    if isinstance(modes, (int, np.integer)):
        modes = list(range(1, int(modes) + 1))
    out = []
    for m in modes:
        if isinstance(m, bool) or not isinstance(m, (int, np.integer)) or not 1 <= m <= n:
            raise ModelError("render", "mode", m, f"a mode number from 1 to {n} (the modes computed)")
        out.append(int(m) - 1)
    return out


def _scene(fe, modal, r, kinds, factor=1.0) -> ModeScene:
    kind = kinds[r] if kinds is not None else None
    if _is_solid(fe):
        return solid_scene(fe, modal, r, kind, factor)
    return mode_scene(fe, modal, r, kind, factor)


def _new_plotter():
    import pyvista as pv

    configure_environment()
    p = pv.Plotter(off_screen=True, window_size=WINDOW)
    p.background_color = "white"
    return p


def _draw(p, scene: ModeScene, clim=(0.0, 1.0), font_size: int = 12) -> dict:
    """Add the scene's meshes to plotter ``p``; returns the actors of the moving parts."""
    for m in scene.undeformed:
        p.add_mesh(m, color=(0.55, 0.55, 0.55), opacity=0.25, line_width=1.5, smooth_shading=True)
    actors = {"deformed": p.add_mesh(scene.deformed, scalars="amplitude", cmap=CMAP, clim=clim,
                                     show_scalar_bar=False, smooth_shading=True, specular=0.3)}
    for k, m in enumerate(scene.lines):
        actors[f"line{k}"] = p.add_mesh(m, color=(0.1, 0.1, 0.1), line_width=2.5 if m.n_cells < 2000 else 1.0,
                                        opacity=1.0 if m.n_cells < 2000 else 0.5)
    for m in scene.markers:
        p.add_mesh(m, color=(0.45, 0.45, 0.45), opacity=0.9)
    p.add_text(scene.title + f"\ncolour: {scene.amplitude_label} (normalised)", position="upper_left",
               font_size=font_size, color="black")
    return actors


def _camera(p, scene: ModeScene) -> None:
    """Bending: looking down z with parallel projection, the shaft filling 90 % of the width
    (so image columns map linearly to x and rows to w); otherwise an oblique view."""
    w, h = p.window_size
    if scene.view == "xy":
        p.view_xy()
        p.enable_parallel_projection()
        p.reset_camera()
        x0, x1, y0, y1, _, _ = scene.deformed.bounds
        for m in scene.undeformed:
            x0, x1 = min(x0, m.bounds[0]), max(x1, m.bounds[1])
        half_h = max(0.5 * (x1 - x0) / 0.9 * h / w, 1.35 * max(abs(y0), abs(y1)))
        p.camera.focal_point = (0.5 * (x0 + x1), 0.0, 0.0)
        p.camera.position = (0.5 * (x0 + x1), 0.0, 10.0 * (x1 - x0))
        p.camera.parallel_scale = half_h
    else:
        p.camera_position = "xz"
        p.camera.azimuth = -25
        p.camera.elevation = 25
        p.enable_parallel_projection()
        p.reset_camera()
        p.camera.zoom(1.7)
    p.camera_set = True      # keep pyvista from resetting the camera at the first render


def render_image(fe, modal, r: int, kinds=None) -> np.ndarray:
    """RGB image (H, W, 3) of mode ``r`` (0-based)."""
    p = _new_plotter()
    try:
        scene = _scene(fe, modal, r, kinds)
        _draw(p, scene)
        _camera(p, scene)
        return np.asarray(p.screenshot(return_img=True))[..., :3]
    finally:
        p.close()


def _write_gif(fe, modal, r, kinds, path: Path) -> Path:
    """Animated GIF of one period (GIF_FRAMES frames): the meshes are drawn once and their
    points updated per frame; the camera stays where the full-amplitude pose put it."""
    import imageio.v2 as imageio
    import pyvista as pv

    configure_environment()
    p = pv.Plotter(off_screen=True, window_size=(WINDOW[0] // 2, WINDOW[1] // 2))
    p.background_color = "white"
    scene = _scene(fe, modal, r, kinds, 1.0)
    _draw(p, scene, font_size=9)
    _camera(p, scene)
    moving = [scene.deformed] + list(scene.lines) + list(scene.markers)
    frames = []
    for k in range(GIF_FRAMES):
        factor = float(np.cos(2 * np.pi * k / GIF_FRAMES))
        if scene.linear_motion is not None:
            for m, (base, delta) in zip(moving, scene.linear_motion):
                m.points = base + factor * delta
        else:
            now = _scene(fe, modal, r, kinds, factor)
            for m, n in zip(moving, [now.deformed] + list(now.lines) + list(now.markers)):
                m.points = n.points
        p.render()
        frames.append(np.asarray(p.screenshot(return_img=True))[..., :3])
    p.close()
    imageio.mimsave(path, frames, duration=1.0 / 12, loop=0)
    return path


def render_modes(fe, modal, out_dir, modes=None, gif: bool = False, kinds=None, prefix: str = "mode",
                 progress=None) -> list[Path]:
    """One PNG per mode (``mode01.png`` ...) and, with ``gif``, an animated GIF per mode.

    ``fe``: a 1D :class:`fem.assembly.FEModel` or a 3D :class:`fem.solid.SolidModel`;
    ``modes``: 1-based mode numbers (default: all computed); ``kinds``: optional labels per
    mode for the titles (3D models use their own classification by default); ``progress``: called
    as ``progress(done, total)`` after each picture.
    Raises :class:`fem.render.RenderUnavailable` if VTK cannot render here."""
    from ..output.mesh import ensure_directory

    idx = mode_indices(modal, modes)
    out = ensure_directory(out_dir, "render output directory")
    if kinds is None and _is_solid(fe) and hasattr(modal, "kinds"):
        kinds = modal.kinds
    require()
    import imageio.v2 as imageio

    paths = []
    total = len(idx) * (2 if gif else 1)
    for r in idx:      # a fresh plotter per image: as fast as reusing one, and no stale camera state
        path = out / f"{prefix}{r + 1:02d}.png"
        imageio.imwrite(path, render_image(fe, modal, r, kinds))
        paths.append(path)
        if progress is not None:
            progress(len(paths), total)
    if gif:
        for r in idx:
            paths.append(_write_gif(fe, modal, r, kinds, out / f"{prefix}{r + 1:02d}.gif"))
            if progress is not None:
                progress(len(paths), total)
    return paths
