"""Loads of lumped and hybrid drives as named outputs: element deflections and forces, gear forces,
driver and support reactions, as linear functionals of the motion (:mod:`.channels`), built from a
drive's named coordinates (:mod:`.build`); the linearisation of the nonsmooth elements in the linear
analyses (:func:`.build.linearise`).  docs/outputs.md describes the outputs and their conventions."""
from .build import Coordinates, DriveLoads, ElementSpec, LinkSpec, Linearised, SourceSpec, build, linearise
from .channels import (FORCES, MOTIONS, QUANTITIES, Channel, LoadMap, amplitude_summary, summaries, summary, time_mean,
                       unit_of)

__all__ = ["Channel", "LoadMap", "Coordinates", "LinkSpec", "ElementSpec", "SourceSpec", "DriveLoads", "Linearised",
           "build", "linearise", "summary", "summaries", "amplitude_summary", "time_mean", "unit_of", "QUANTITIES",
           "FORCES", "MOTIONS"]
