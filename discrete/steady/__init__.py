"""Nonlinear steady-state forced response: shooting with the exact event-driven integrator and
Floquet multipliers, harmonic balance with AFT, pseudo-arc-length continuation with folds, stability,
and the textbook's quick estimates (harmonic linearisation, energy balance).  See docs/steady.md.

Entry points: :func:`run_forced` (model dict with ``[steady]`` -> :class:`AFCResult`),
:func:`is_nonlinear_forced`, :func:`write_csv`, :func:`plot_afc`, ``TOP_LEVEL_KEYS``.
"""
from .afc import (TOP_LEVEL_KEYS, AFCResult, SteadyModel, is_nonlinear_forced, parse_steady, plot_afc,
                  run_forced, write_csv)
from .continuation import Branch, arclength
from .hb import HBModel, backbone, floquet_hb
from .shooting import ShootingModel
from .system import Cubic, PeriodicSystem
from . import estimates

__all__ = ["TOP_LEVEL_KEYS", "AFCResult", "SteadyModel", "is_nonlinear_forced", "parse_steady", "plot_afc",
           "run_forced", "write_csv", "Branch", "arclength", "HBModel", "backbone", "floquet_hb",
           "ShootingModel", "Cubic", "PeriodicSystem", "estimates"]
