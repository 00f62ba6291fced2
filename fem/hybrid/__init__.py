"""Hybrid continuous-lumped simulation: FE shafts, rods and beams (full or modally reduced) coupled
to lumped bodies and nonsmooth elements (friction, one-sided springs, gaps, impacts, distributed
dry friction), integrated by the exact event-driven solver or the Moreau-Jean time stepper.
See docs/hybrid.md.

Entry points: :func:`is_hybrid`, :func:`run_model_file` (parsed TOML dict -> :class:`HybridResult`),
:func:`write_csv`, :func:`plot_result`; from Python :class:`HybridModel` + :func:`run` or
:func:`compile_hybrid` (the Problem for the solvers).
"""
from .build import (Body, CompiledHybrid, DriverSpec, ElementSpec, ForceSpec, HybridModel, NodeRef, ReductionSpec,
                    Spring, compile_hybrid)
from .distributed import distributed_friction, tributary_weights
from .io import plot_result, write_csv
from .modelfile import is_hybrid, parse_hybrid
from .run import HybridResult, run, run_model_file

__all__ = ["is_hybrid", "run_model_file", "write_csv", "plot_result", "HybridResult", "HybridModel", "run",
           "compile_hybrid", "parse_hybrid", "CompiledHybrid", "NodeRef", "Body", "Spring", "ElementSpec",
           "ForceSpec", "DriverSpec", "ReductionSpec", "distributed_friction", "tributary_weights"]
