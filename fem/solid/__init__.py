"""3D continuum (solid) models of shafts: quadratic hexahedra from the same ShaftModel
description as the beam models, modes classified as bending/torsion/axial, and import of
users' own meshes through meshio."""
from .classify import KINDS, SolidModalResult, classify, solid_modal
from .io import solid_from_mesh
from .mesh import ShaftMeshSpec, stepped_shaft_hex
from .model import SolidModel, assemble_solid, build_solid

SolidShaft = build_solid

__all__ = ["SolidModel", "SolidShaft", "build_solid", "assemble_solid", "ShaftMeshSpec", "stepped_shaft_hex",
           "solid_modal", "SolidModalResult", "classify", "KINDS", "solid_from_mesh"]
