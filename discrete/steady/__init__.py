"""Nonlinear steady-state forced response: shooting with the exact event-driven integrator and
Floquet multipliers, harmonic balance with AFT, pseudo-arc-length continuation with folds, stability,
and the textbook's quick estimates (harmonic linearisation, energy balance).  See docs/steady.md.

Entry points: :class:`SteadyModel` (a problem factory + :class:`SteadySettings`) and :func:`afc`
(its amplitude-frequency curve, an :class:`AFCResult`).
"""
from .afc import AFCResult, SteadyModel, SteadySettings, afc
from .continuation import Branch, arclength
from .hb import HBModel, backbone, floquet_hb
from .shooting import ShootingModel
from ..nonsmooth.elements import Cubic
from .system import PeriodicSystem
# estimates (scipy.optimize, ~0.09 s to import) is a submodule loaded on use: discrete.steady.estimates

__all__ = ["AFCResult", "SteadyModel", "SteadySettings", "afc", "Branch", "arclength",
           "HBModel", "backbone", "floquet_hb", "ShootingModel", "Cubic", "PeriodicSystem", "estimates"]
