"""Discrete nonsmooth dynamics: exact event-driven simulation of lumped drives with Coulomb friction
(stick-slip, static > kinetic, moving counter-surface, restick rules), one-sided springs, gaps,
impacts with restitution and variable mass; a regularised/penalty alternative; periodic-regime
detection and energy balance.  See docs/discrete.md.

Entry points: :func:`simulate` (any :class:`~discrete.linear_system.LinearSystem` + elements via
:class:`Problem`), :func:`simulate_spec` (one entry for the event, Moreau-Jean and regularised
integrators); model files go through :mod:`fem.modelfile`.
"""
from .elements import ELEMENT_TYPES, Cubic, Element, Friction, Gap, Impact, OneSided
from .methods import simulate_spec
from .periodic import detect_period
from .problem import ExternalForce, MotionLaw, Problem, ProblemSpec
from .regularised import simulate_regularised
from .result import Event, SimulationResult
from .solver import Options, simulate

__all__ = ["simulate_spec", "ProblemSpec", "simulate", "simulate_regularised", "Options",
           "Problem", "MotionLaw", "ExternalForce", "Element", "ELEMENT_TYPES", "Friction", "OneSided", "Gap", "Impact", "Cubic", "SimulationResult",
           "Event", "detect_period"]
