"""The elements' laws over one Moreau-Jean step live with their elements
(:mod:`discrete.nonsmooth.elements`: the base :class:`StepLaw` in ``base.py``, each law in its
element's module); the names stay importable from here."""
from ..nonsmooth.elements.base import StepLaw
from ..nonsmooth.elements.contact import KelvinVoigtStep
from ..nonsmooth.elements.friction import CoulombStep
from ..nonsmooth.elements.gap import ClearanceSpringStep
from ..nonsmooth.elements.impact import UnilateralStep

__all__ = ["StepLaw", "CoulombStep", "ClearanceSpringStep", "UnilateralStep", "KelvinVoigtStep"]
