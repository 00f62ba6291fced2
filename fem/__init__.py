"""Finite-element models of shafts, rods and beams (scikit-fem), modal and harmonic analysis.

The analyses of an assembled :class:`~discrete.linear_system.LinearSystem` live in
:mod:`discrete.linear` (fem assembles, discrete solves); their public names are re-exported here.
They are imported on first use (``from fem import modal_analysis`` works as before), so that the
command line's start and ``import fem.app.cli`` do not load scikit-fem and scipy up front.
"""
from discrete.lazy import lazy_exports as _lazy_exports

_EXPORTS = {**dict.fromkeys(["Damping", "HarmonicResult", "ModalResult", "ReducedModel", "frf",
                             "harmonic_response", "modal_analysis", "reduce", "static_deflection"], "discrete.linear"),
            **dict.fromkeys(["FEModel", "assemble"], "fem.assembly"),
            **dict.fromkeys(["SectionLoads", "section_loads", "support_reactions"], "fem.loads"),
            **dict.fromkeys(["PointAttachment", "Segment", "ShaftModel", "Support"], "fem.model"),
            **dict.fromkeys(["Material", "Section"], "fem.sections")}

__all__ = ["FEModel", "assemble", "ShaftModel", "Segment", "Support", "PointAttachment",
           "ModalResult", "modal_analysis", "Damping", "HarmonicResult", "harmonic_response", "frf",
           "ReducedModel", "reduce", "static_deflection", "Material", "Section", "SectionLoads", "section_loads",
           "support_reactions"]

__getattr__, __dir__ = _lazy_exports(__name__, _EXPORTS, globals())
