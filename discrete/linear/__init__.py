"""Analyses of a :class:`~discrete.linear_system.LinearSystem`: modal (sparse shift-invert, certified
seeded path), harmonic response (sinusoidal and periodic loads), static deflection, modal reduction
(Craig-Bampton), reactions and element forces, and parametric resonance (Floquet charts)."""
# public names imported on first use (discrete.lazy): a caller of one analysis does not load the others
# (parametric -> scipy.optimize, ~0.1-0.2 s of the command line's start-up)
from ..lazy import lazy_exports as _lazy_exports

_EXPORTS = {
    "Damping": "discrete.linear.harmonic",
    "HarmonicResult": "discrete.linear.harmonic",
    "frf": "discrete.linear.harmonic",
    "harmonic_response": "discrete.linear.harmonic",
    "ModalResult": "discrete.linear.modal",
    "modal_analysis": "discrete.linear.modal",
    "DampingThreshold": "discrete.linear.parametric",
    "FloquetResult": "discrete.linear.parametric",
    "Modulation": "discrete.linear.parametric",
    "ParametricProblem": "discrete.linear.parametric",
    "StabilityChart": "discrete.linear.parametric",
    "TongueBoundaries": "discrete.linear.parametric",
    "damping_threshold": "discrete.linear.parametric",
    "floquet": "discrete.linear.parametric",
    "stability_chart": "discrete.linear.parametric",
    "tongue_boundaries": "discrete.linear.parametric",
    "PeriodicLoad": "discrete.linear.periodic_forced",
    "PeriodicResponse": "discrete.linear.periodic_forced",
    "periodic_response": "discrete.linear.periodic_forced",
    "constraint_reactions": "discrete.linear.reactions",
    "element_forces": "discrete.linear.reactions",
    "lumped_links": "discrete.linear.reactions",
    "reactions_from_result": "discrete.linear.reactions",
    "ReducedModel": "discrete.linear.reduction",
    "elastic_flexibility": "discrete.linear.reduction",
    "reduce": "discrete.linear.reduction",
    "static_deflection": "discrete.linear.static",
}

__all__ = ["Damping", "HarmonicResult", "frf", "harmonic_response", "ModalResult", "modal_analysis",
           "ReducedModel", "elastic_flexibility", "reduce", "static_deflection", "Modulation", "ParametricProblem",
           "floquet", "stability_chart", "tongue_boundaries", "damping_threshold", "FloquetResult", "StabilityChart",
           "DampingThreshold", "TongueBoundaries", "PeriodicLoad", "PeriodicResponse", "periodic_response",
           "constraint_reactions", "reactions_from_result", "element_forces", "lumped_links"]

__getattr__, __dir__ = _lazy_exports(__name__, _EXPORTS, globals())
