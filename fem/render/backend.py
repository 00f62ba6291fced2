"""Off-screen rendering backend: choose a VTK window that needs no X server and probe it.

VTK >= 9.4 wheels (the plain ``vtk`` wheel pulled in by pyvista) link no OpenGL or X
library; they pick the OpenGL window at run time.  Without a display we select:

* ``vtkOSOpenGLRenderWindow`` (Mesa OSMesa, software llvmpipe) when ``libOSMesa.so.8`` is
  installed -- one Debian package, the fewest system libraries::

      apt-get install --no-install-recommends libosmesa6

* otherwise ``vtkEGLRenderWindow`` (headless EGL through Mesa) when the EGL libraries are
  there (``libegl1 libegl-mesa0 libgl1-mesa-dri``, e.g. on machines with a desktop stack).

so VTK never tries to open an X connection.  ``DRIVEFEM_RENDER=off`` disables rendering
(data files are still written); a ``VTK_DEFAULT_OPENGL_WINDOW`` set by the user is respected.
"""
from __future__ import annotations

import ctypes
import os
import subprocess
import sys
from pathlib import Path

from discrete.errors import SolverError

APT_PACKAGES = ("libosmesa6",)
APT_HINT = "apt-get install --no-install-recommends " + " ".join(APT_PACKAGES)
EGL_APT_HINT = "apt-get install --no-install-recommends libegl1 libegl-mesa0 libgl1-mesa-dri"
PIP_HINT = "pip install pyvista imageio  (or: pip install 'drivefem[render]')"
OSMESA, EGL = "vtkOSOpenGLRenderWindow", "vtkEGLRenderWindow"

#: shared libraries each headless window loads, with the Debian package providing each
WINDOW_LIBRARIES = {
    OSMESA: (("libOSMesa.so.8", "libosmesa6"), ("libglapi.so.0", "libglapi-mesa")),
    EGL: (("libEGL.so.1", "libegl1"), ("libEGL_mesa.so.0", "libegl-mesa0"), ("libgbm.so.1", "libgbm1"),
          ("libglapi.so.0", "libglapi-mesa")),
}
DRI_DIRS = ("/usr/lib/x86_64-linux-gnu/dri", "/usr/lib/aarch64-linux-gnu/dri", "/usr/lib64/dri", "/usr/lib/dri")
HINTS = {OSMESA: APT_HINT, EGL: EGL_APT_HINT}

_PROBE = r"""
import pyvista as pv
p = pv.Plotter(off_screen=True, window_size=(48, 48))
p.add_mesh(pv.Sphere(radius=1.0), color=(1.0, 0.0, 0.0), lighting=False)
p.background_color = "white"
img = p.screenshot(return_img=True)
win = p.render_window.GetClassName() if getattr(p, "render_window", None) is not None else "VTK"
p.close()
red = ((img[..., 0] > 200) & (img[..., 1] < 60) & (img[..., 2] < 60)).sum()
print("PROBE", img.shape[0], img.shape[1], int(red), win)
"""

_STATE: dict = {}


class RenderUnavailable(SolverError):
    """Off-screen rendering cannot run on this machine (the message says what to install)."""


def _loads(lib: str) -> bool:
    try:
        ctypes.CDLL(lib)
        return True
    except OSError:
        return False


def headless_window() -> str:
    """The display-less VTK window to use here: OSMesa if its library loads, else EGL if
    its libraries load, else OSMesa (so the message names the smallest install)."""
    if _loads("libOSMesa.so.8"):
        return OSMESA
    if all(_loads(lib) for lib, _ in WINDOW_LIBRARIES[EGL]):
        return EGL
    return OSMESA


def configure_environment() -> None:
    """Select a display-less VTK window unless a display or an explicit choice exists."""
    os.environ.setdefault("PYVISTA_OFF_SCREEN", "true")
    if not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY"):
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", headless_window())


def _missing_system_library(window: str) -> tuple[str, str] | None:
    for lib, pkg in WINDOW_LIBRARIES.get(window, ()):
        if not _loads(lib):
            return lib, pkg
    if window == EGL and not any(Path(d, "swrast_dri.so").exists() for d in DRI_DIRS):
        return "swrast_dri.so (Mesa software driver)", "libgl1-mesa-dri"
    return None


def _diagnose() -> tuple[bool, str]:
    if os.environ.get("DRIVEFEM_RENDER", "").lower() in ("0", "off", "no", "false"):
        return False, "rendering disabled by DRIVEFEM_RENDER=off"
    try:
        import pyvista  # noqa: F401
        import vtkmodules  # noqa: F401
    except ImportError as exc:
        return False, f"off-screen rendering needs the Python packages pyvista and vtk ({exc}); install: {PIP_HINT}"
    configure_environment()
    window = os.environ.get("VTK_DEFAULT_OPENGL_WINDOW", "")
    hint = HINTS.get(window, APT_HINT)
    miss = _missing_system_library(window)
    if miss:
        lib, pkg = miss
        return False, (f"off-screen rendering needs the system library {lib} (Debian package {pkg}); "
                       f"install: {hint}")
    try:
        out = subprocess.run([sys.executable, "-c", _PROBE], capture_output=True, text=True, timeout=120,
                             env=dict(os.environ))
    except subprocess.TimeoutExpired:
        return False, f"off-screen rendering probe timed out; check the OpenGL libraries ({hint})"
    line = next((ln for ln in out.stdout.splitlines() if ln.startswith("PROBE")), None)
    if out.returncode != 0 or line is None:
        tail = (out.stderr.strip().splitlines() or ["no output"])[-1]
        return False, (f"off-screen rendering failed in VTK with {window or 'the default window'} ({tail}); "
                       f"on Debian install {APT_HINT} and leave DISPLAY unset "
                       f"(or set VTK_DEFAULT_OPENGL_WINDOW={OSMESA})")
    _, h, w, red, win = (line.split() + [""] * 5)[:5]
    if int(red) < 0.2 * int(h) * int(w):
        return False, f"off-screen rendering produced a blank image (window {win}); install {hint}"
    return True, f"off-screen rendering available ({win or 'VTK'}, no X server needed)"


def available(refresh: bool = False) -> tuple[bool, str]:
    """(True, description) if VTK can render off screen here, else (False, what is missing
    and how to install it).  Probed once per process in a subprocess (a broken OpenGL stack
    must not crash the caller)."""
    if refresh or "result" not in _STATE:
        _STATE["result"] = _diagnose()
    return _STATE["result"]


def require() -> None:
    ok, msg = available()
    if not ok:
        raise RenderUnavailable(msg)
