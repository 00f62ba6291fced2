"""Linear algebra shared by every analysis: BLAS-thread control, the matrix exponential of small
pieces, and the shifted/seeded sparse eigen-solvers (numpy + scipy + threadpoolctl only)."""
from .blas import single_threaded_blas
from .expm import expm_batch
from .seeded import SeededSolution, seeded_eigenpairs
from .shifted import ShiftedSolver, is_diagonal

__all__ = ["single_threaded_blas", "expm_batch", "SeededSolution", "seeded_eigenpairs", "ShiftedSolver",
           "is_diagonal"]
