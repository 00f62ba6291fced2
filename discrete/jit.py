"""numba's ``njit`` for the compiled kernels (discrete/nonsmooth/kernel.py: the event-driven solver;
discrete/steady/hb_kernel.py and condense_kernel.py: harmonic balance), or a decorator that leaves the
function as plain Python -- the same source, the same results, slower -- when numba is not installed or
``DRIVEFEM_JIT=0``.  ``JIT`` says which."""
from __future__ import annotations

import os

try:
    if os.environ.get("DRIVEFEM_JIT", "1") == "0":
        raise ImportError("disabled by DRIVEFEM_JIT=0")
    from numba import njit
    JIT = True
except ImportError:              # plain Python
    JIT = False

    def njit(*args, **kwargs):
        """A stand-in for numba.njit (with or without options): the function itself."""
        return (lambda f: f) if not args or not callable(args[0]) else args[0]

__all__ = ["JIT", "njit"]
