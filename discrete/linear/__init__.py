"""Analyses of a :class:`~discrete.linear_system.LinearSystem`: modal (sparse shift-invert, certified
seeded path), harmonic response, static deflection and modal reduction (Craig-Bampton)."""
from .harmonic import Damping, HarmonicResult, frf, harmonic_response
from .modal import ModalResult, modal_analysis
from .reduction import ReducedModel, elastic_flexibility, reduce
from .static import static_deflection

__all__ = ["Damping", "HarmonicResult", "frf", "harmonic_response", "ModalResult", "modal_analysis",
           "ReducedModel", "elastic_flexibility", "reduce", "static_deflection"]
