"""Analyses of a :class:`~discrete.linear_system.LinearSystem`: modal (sparse shift-invert, certified
seeded path), harmonic response (sinusoidal and periodic loads), static deflection, modal reduction
(Craig-Bampton), reactions and element forces, and parametric resonance (Floquet charts)."""
from .harmonic import Damping, HarmonicResult, frf, harmonic_response
from .modal import ModalResult, modal_analysis
from .parametric import (DampingThreshold, FloquetResult, Modulation, ParametricProblem, StabilityChart,
                         TongueBoundaries, damping_threshold, floquet, stability_chart, tongue_boundaries)
from .periodic_forced import PeriodicLoad, PeriodicResponse, periodic_response
from .reactions import constraint_reactions, element_forces, lumped_links, reactions_from_result
from .reduction import ReducedModel, elastic_flexibility, reduce
from .static import static_deflection

__all__ = ["Damping", "HarmonicResult", "frf", "harmonic_response", "ModalResult", "modal_analysis",
           "ReducedModel", "elastic_flexibility", "reduce", "static_deflection", "Modulation", "ParametricProblem",
           "floquet", "stability_chart", "tongue_boundaries", "damping_threshold", "FloquetResult", "StabilityChart",
           "DampingThreshold", "TongueBoundaries", "PeriodicLoad", "PeriodicResponse", "periodic_response",
           "constraint_reactions", "reactions_from_result", "element_forces", "lumped_links"]
