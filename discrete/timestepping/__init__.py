"""Time stepping for many nonsmooth elements (Moreau-Jean scheme with per-step friction/impact
resolution by projected Gauss-Seidel).  numpy/scipy only; works on any LinearSystem."""
from .moreau import SteppingResult, StepOptions, simulate_timestepping

__all__ = ["SteppingResult", "StepOptions", "simulate_timestepping"]
