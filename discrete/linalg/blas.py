"""One-thread BLAS for the small dense kernels of the iterative eigen-solvers.

Lanczos and block inverse iteration multiply n x q blocks with q ~ 20: BLAS threads only
add synchronisation, and numpy and scipy each load their own OpenBLAS, whose spinning
threads compete for the cores.  Measured on the 2-core test machine: ARPACK 11 ms with one
thread against 100 ms with two (2000 DOFs); a 21 x 2000 by 2000 x 21 product inside the
seeded solver 0.05 ms against 1.1 ms.  The controller is built once (~ms of library
introspection); entering the limit then costs microseconds.
"""
from __future__ import annotations

import os
from contextlib import nullcontext
from functools import lru_cache


@lru_cache(maxsize=1)
def _controller():
    """The threadpoolctl controller, imported and built on first use (its import costs ~35 ms of every
    command's start-up, and most commands never limit BLAS)."""
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


#: the environment variables that fix the BLAS libraries' thread counts when they load
_THREAD_VARS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS")


def _one_thread_already() -> bool:
    """Whether the environment already loads every BLAS with one thread (OpenBLAS and OpenMP set to 1, MKL
    and BLIS unset or 1): then there is nothing to limit (and the controller's ~8 ms of library
    introspection is saved)."""
    env = os.environ
    return (env.get("OPENBLAS_NUM_THREADS") == "1" and env.get("OMP_NUM_THREADS") == "1"
            and all(env.get(v, "1") == "1" for v in _THREAD_VARS[2:]))


def single_threaded_blas(keep_mkl: bool = False):
    """Context manager: BLAS of every loaded library limited to one thread.

    ``keep_mkl``: MKL keeps its threads (the OpenBLAS libraries are limited).  MKL's thread
    count is also PARDISO's: a shift-invert run on a PARDISO factorisation streams its factor
    through memory twice per solve, and one thread instead of two made the solves of the
    104 400-DOF solid 0.15 s instead of 0.08 s each (measured)."""
    if _one_thread_already():
        return nullcontext()
    if keep_mkl:
        return _controller().select(internal_api=["openblas", "blis", "flexiblas"]).limit(limits=1)
    return _controller().limit(limits=1, user_api="blas")
