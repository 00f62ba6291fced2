"""Finite-element models of shafts, rods and beams (scikit-fem), modal and harmonic analysis.

The analyses of an assembled :class:`~discrete.linear_system.LinearSystem` live in
:mod:`discrete.linear` (fem assembles, discrete solves); their public names are re-exported here.
"""
from discrete.linear import (Damping, HarmonicResult, ModalResult, ReducedModel, frf, harmonic_response,
                             modal_analysis, reduce, static_deflection)

from .assembly import FEModel, assemble
from .model import PointAttachment, Segment, ShaftModel, Support
from .sections import Material, Section

__all__ = ["FEModel", "assemble", "ShaftModel", "Segment", "Support", "PointAttachment",
           "ModalResult", "modal_analysis", "Damping", "HarmonicResult", "harmonic_response", "frf",
           "ReducedModel", "reduce", "static_deflection", "Material", "Section"]
