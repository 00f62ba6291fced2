"""Transfer-matrix method and regular-structure closed forms for drives (textbook ch. 10).

numpy/scipy only (``discrete`` never imports ``fem``).
"""
from .chain import (Chain, ChainResponse, TMRoots, boundary_residual, count_below, element_matrix,
                    forced_response, mode_shape, naive_product, natural_frequencies, propagate)
from .elements import (Branch, Damper, Ground, Inertia, Load, Member, Ratio, Shaft, Spring, chain_product, connection,
                       damper_matrix, inertia_matrix, mechanism_branch, mechanism_matrix, parallel, spring_matrix)
from .parallel_chains import Parallel
from .regular import BOOK_CASE, BOUNDARY_CASES, RegularDrive, gammas, pass_band, rigid_ratios

__all__ = ["Chain", "ChainResponse", "TMRoots", "boundary_residual", "count_below", "element_matrix",
           "forced_response", "mode_shape", "naive_product", "natural_frequencies", "propagate", "Branch", "Damper", "Ground",
           "Inertia", "Load", "Member", "Parallel", "Ratio", "Shaft", "Spring", "chain_product", "connection", "damper_matrix",
           "inertia_matrix", "mechanism_branch", "mechanism_matrix", "parallel", "spring_matrix", "BOOK_CASE",
           "BOUNDARY_CASES", "RegularDrive", "gammas", "pass_band", "rigid_ratios"]
