"""Hybrid continuous-lumped simulation: FE shafts, rods and beams (full or modally reduced) coupled
to lumped bodies and nonsmooth elements (friction, one-sided springs, gaps, impacts, distributed
dry friction), integrated by the exact event-driven solver or the Moreau-Jean time stepper.
See docs/hybrid.md.

From Python: :class:`HybridModel` + :func:`run`, or :func:`compile_hybrid` (the problem for the
solvers); model files go through :mod:`fem.modelfile`.
"""
from .build import (Body, CompiledHybrid, DriverSpec, ElementSpec, ForceSpec, HybridModel, NodeRef, ReductionSpec,
                    Spring, compile_hybrid)
from .distributed import distributed_friction, tributary_weights
from .run import HybridResult, run

__all__ = ["HybridResult", "HybridModel", "run",
           "compile_hybrid", "CompiledHybrid", "NodeRef", "Body", "Spring", "ElementSpec",
           "ForceSpec", "DriverSpec", "ReductionSpec", "distributed_friction", "tributary_weights"]
