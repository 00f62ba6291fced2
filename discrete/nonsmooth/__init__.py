"""Discrete nonsmooth dynamics: exact event-driven simulation of lumped drives with Coulomb friction
(stick-slip, static > kinetic, moving counter-surface, restick rules), one-sided springs, gaps,
impacts with restitution and variable mass; a regularised/penalty alternative; periodic-regime
detection and energy balance.  See docs/discrete.md.

Entry points: :func:`run_model_file` (parsed TOML dict -> :class:`SimulationResult`),
:func:`simulate` (any :class:`~discrete.linear_system.LinearSystem` + elements via :class:`Problem`),
:func:`write_csv`, :func:`plot_result`.
"""
from .elements import Friction, Gap, Impact, OneSided
from .io import write_csv
from .model import TOP_LEVEL_KEYS, build_problem, run_model_file
from .periodic import detect_period
from .plots import plot_result
from .problem import ExternalForce, MotionLaw, Problem
from .regularised import simulate_regularised
from .result import Event, SimulationResult
from .solver import Options, simulate

__all__ = ["TOP_LEVEL_KEYS", "run_model_file", "build_problem", "simulate", "simulate_regularised", "Options",
           "Problem", "MotionLaw", "ExternalForce", "Friction", "OneSided", "Gap", "Impact", "SimulationResult",
           "Event", "write_csv", "plot_result", "detect_period"]
