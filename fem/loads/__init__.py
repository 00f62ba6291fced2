"""Loads as named outputs (docs/outputs.md: names, sign conventions, JSON/CSV/HDF5 layout; docs/loads.md:
the section-load recovery).

Section loads of FE shafts, rods, beams and rotors (the Python API):

* :func:`section_loads` -- torque, axial force, bending moment and shear force along an assembled
  :class:`fem.FEModel` (or a rotor's :class:`~fem.rotor.RotorSystem`: :func:`rotor_section_loads`, bending
  moments and shear forces in both planes, torque and axial force with ``dofs = "full"``), recovered from
  the element equations including inertia, for a static, harmonic, modal or time-history state;
* :func:`support_reactions` -- the forces of supports, springs to ground and rotor bearings on the structure;
* :class:`SectionLoads` -- the result (stations x, quantities, units, side of each value).

One concept per module: :mod:`.elements` (what an element is to the recovery), :mod:`.shaft_elements` and
:mod:`.rotor_elements` (building them), :mod:`.motion` (the state), :mod:`.recovery` (end forces and
values inside elements), :mod:`.section` and :mod:`.reactions` (the public functions); :mod:`.names`
(the names of a model file's things in the outputs); :mod:`.lumped`, :mod:`.hybrid` and :mod:`.drive`
(the load map of a lumped or hybrid drive, :mod:`discrete.loads`, and the linearised model of its linear
analyses); :mod:`.select` (``[[output]]`` tables of drive outputs); :mod:`.shaft` (section-load and
reaction columns of FE shafts and rotors: default and ``[[output]]`` stations); :mod:`.analyses` (the
table of named columns, :class:`~fem.loads.analyses.NamedOutputs`, and its derived quantities);
:mod:`.steady` (outputs along a [steady] curve); :mod:`.study` (what each analysis of a model file
reports: :func:`fem.loads.study.outputs`, behind ``Study.outputs``).
"""
from .reactions import rotor_reactions, support_reactions
from .section import UNITS, SectionLoads, elements_of, rotor_section_loads, section_loads

__all__ = ["SectionLoads", "section_loads", "rotor_section_loads", "support_reactions", "rotor_reactions",
           "elements_of", "UNITS"]
