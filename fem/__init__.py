"""Finite-element models of shafts, rods and beams (scikit-fem), modal and harmonic analysis."""
from .assembly import FEModel, assemble
from .model import PointAttachment, Segment, ShaftModel, Support
from .modal import ModalResult, modal_analysis
from .sections import Material, Section

__all__ = ["FEModel", "assemble", "ShaftModel", "Segment", "Support", "PointAttachment",
           "ModalResult", "modal_analysis", "Material", "Section"]
