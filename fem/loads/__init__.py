"""Internal loads of FE shafts, rods, beams and rotors (docs/loads.md).

* :func:`section_loads` -- torque, axial force, bending moment and shear force along an assembled
  :class:`fem.FEModel` (or a rotor's :class:`~fem.rotor.RotorSystem`: :func:`rotor_section_loads`, bending
  moments and shear forces in both planes, torque and axial force with ``dofs = "full"``), recovered from
  the element equations including inertia, for a static, harmonic, modal or time-history state;
* :func:`support_reactions` -- the forces of supports, springs to ground and rotor bearings on the structure;
* :class:`SectionLoads` -- the result (stations x, quantities, units, side of each value).

The layers: :mod:`.elements` (what an element is to the recovery), :mod:`.shaft_elements` and
:mod:`.rotor_elements` (building them), :mod:`.motion` (the state), :mod:`.recovery` (end forces and
values inside elements), :mod:`.section` and :mod:`.reactions` (the public functions), :mod:`.study`
(what each analysis of a model file reports).
"""
from .reactions import rotor_reactions, support_reactions
from .section import UNITS, SectionLoads, elements_of, rotor_section_loads, section_loads

__all__ = ["SectionLoads", "section_loads", "rotor_section_loads", "support_reactions", "rotor_reactions",
           "elements_of", "UNITS"]
