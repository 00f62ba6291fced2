"""Off-screen rendering of mode shapes with pyvista/VTK (no display, no X server).

Entry points: :func:`render_modes` (PNG per mode, GIF on request, 1D and 3D models),
:func:`available` (whether VTK can render here, else what to install),
:func:`render_study` (what ``drivefem render`` runs: data files first, then images).
"""
from .backend import APT_HINT, APT_PACKAGES, RenderUnavailable, available, configure_environment
from .images import mode_indices, render_image, render_modes
from .command import render_study

__all__ = ["available", "render_modes", "render_image", "render_study", "RenderUnavailable",
           "mode_indices", "configure_environment", "APT_HINT", "APT_PACKAGES"]
