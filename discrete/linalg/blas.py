"""One-thread BLAS for the small dense kernels of the iterative eigen-solvers.

Lanczos and block inverse iteration multiply n x q blocks with q ~ 20: BLAS threads only
add synchronisation, and numpy and scipy each load their own OpenBLAS, whose spinning
threads compete for the cores.  Measured on the 2-core test machine: ARPACK 11 ms with one
thread against 100 ms with two (2000 DOFs); a 21 x 2000 by 2000 x 21 product inside the
seeded solver 0.05 ms against 1.1 ms.  The controller is built once (~ms of library
introspection); entering the limit then costs microseconds.
"""
from __future__ import annotations

from functools import lru_cache

from threadpoolctl import ThreadpoolController


@lru_cache(maxsize=1)
def _controller() -> ThreadpoolController:
    return ThreadpoolController()


def single_threaded_blas():
    """Context manager: BLAS of every loaded library limited to one thread."""
    return _controller().limit(limits=1, user_api="blas")
