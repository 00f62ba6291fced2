"""Connection elements of a geared train, one module each (:mod:`.base`: the protocol)."""
from .base import Connection, Coord, ElementPart, Excitation
from .coupling import ShaftCoupling
from .mesh import GearMesh

__all__ = ["Connection", "Coord", "ElementPart", "Excitation", "GearMesh", "ShaftCoupling"]
