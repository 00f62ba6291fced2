"""Geared multi-shaft drive trains (docs/geared.md): several FE shafts or rotors, rotational bodies,
gear meshes and couplings, in every analysis of the package."""
from .assembly import TrainSystem, assemble_train
from .connections import Connection, GearMesh, ShaftCoupling
from .model import Port, Train, TrainBody, TrainShaft
from .modal import TrainModes, train_campbell, train_modes

__all__ = ["Connection", "GearMesh", "Port", "ShaftCoupling", "Train", "TrainBody", "TrainModes", "TrainShaft",
           "TrainSystem", "assemble_train", "train_campbell", "train_modes"]
