"""Sparse matrix-vector products by MKL's inspector-executor sparse BLAS, where MKL is installed.

ARPACK's shift-invert run on a large model (:func:`discrete.linear.modal._eigsh`) multiplies by
the mass matrix about three times per solve (the M-inner products of its Lanczos vectors: 100
products for 34 solves on the 104 400-DOF solid).  scipy's CSR product runs on one core: 9-14 ms
for that M (6.2 M entries); MKL's ``mkl_sparse_d_mv`` on two threads takes 4.2 ms (measured).
MKL is the library PARDISO already loaded (:func:`discrete.linalg.sparse_direct.mkl_library`), so
this costs no dependency.  The products agree with scipy's to rounding (1.7e-16 relative here):
it is used only where PARDISO factorises, above every model of the validation catalogue.
"""
from __future__ import annotations

import ctypes
import weakref

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import SolverError
from .sparse_direct import mkl_library

_INDEX_ZERO = 0                 # SPARSE_INDEX_BASE_ZERO
_NON_TRANSPOSE = 10             # SPARSE_OPERATION_NON_TRANSPOSE
_GENERAL = 20                   # SPARSE_MATRIX_TYPE_GENERAL
_EXPECTED_CALLS = 1000          # the hint for mkl_sparse_set_mv_hint
_STATUS = {1: "not initialized", 2: "allocation failed", 3: "invalid value", 4: "execution failed",
           5: "internal error", 6: "not supported"}      # sparse_status_t


class _Descr(ctypes.Structure):
    """MKL's ``struct matrix_descr`` (type, fill mode, diagonal type), passed by value."""
    _fields_ = [("type", ctypes.c_int), ("mode", ctypes.c_int), ("diag", ctypes.c_int)]


def _prototypes(lib) -> None:
    vp = ctypes.c_void_p
    lib.mkl_sparse_d_create_csr.argtypes = [ctypes.POINTER(vp), ctypes.c_int, ctypes.c_int, ctypes.c_int,
                                            vp, vp, vp, vp]
    lib.mkl_sparse_set_mv_hint.argtypes = [vp, ctypes.c_int, _Descr, ctypes.c_int]
    lib.mkl_sparse_optimize.argtypes = [vp]
    lib.mkl_sparse_d_mv.argtypes = [ctypes.c_int, ctypes.c_double, vp, _Descr, vp, ctypes.c_double, vp]
    lib.mkl_sparse_destroy.argtypes = [vp]
    for fn in ("mkl_sparse_d_create_csr", "mkl_sparse_set_mv_hint", "mkl_sparse_optimize", "mkl_sparse_d_mv",
               "mkl_sparse_destroy"):
        getattr(lib, fn).restype = ctypes.c_int


class MklMatrix:
    """A CSR matrix handed to MKL (its arrays kept alive here), with ``matvec``; MKL's handle is
    released when this object is garbage-collected."""

    def __init__(self, A: sp.spmatrix, lib):
        A = sp.csr_matrix(A, dtype=float)
        self.shape = A.shape
        self.indptr = np.ascontiguousarray(A.indptr, dtype=np.int32)
        self.indices = np.ascontiguousarray(A.indices, dtype=np.int32)
        self.data = np.ascontiguousarray(A.data)
        self.lib = lib
        self.descr = _Descr(_GENERAL, 0, 0)
        self.handle = ctypes.c_void_p()
        status = lib.mkl_sparse_d_create_csr(ctypes.byref(self.handle), _INDEX_ZERO, self.shape[0], self.shape[1],
                                             self.indptr.ctypes.data, self.indptr[1:].ctypes.data,
                                             self.indices.ctypes.data, self.data.ctypes.data)
        if status:
            raise RuntimeError(f"mkl_sparse_d_create_csr: {_STATUS.get(status, status)}")
        weakref.finalize(self, lib.mkl_sparse_destroy, self.handle)
        lib.mkl_sparse_set_mv_hint(self.handle, _NON_TRANSPOSE, self.descr, _EXPECTED_CALLS)
        lib.mkl_sparse_optimize(self.handle)

    def matvec(self, x: np.ndarray) -> np.ndarray:
        x = np.ascontiguousarray(x, dtype=float).reshape(-1)
        y = np.empty(self.shape[0])
        status = self.lib.mkl_sparse_d_mv(_NON_TRANSPOSE, 1.0, self.handle, self.descr, x.ctypes.data, 0.0,
                                          y.ctypes.data)
        if status:
            raise SolverError(f"MKL sparse matrix-vector product failed ({_STATUS.get(status, status)}, "
                              f"{self.shape[0]} x {self.shape[1]} matrix, {self.data.size} entries)")
        return y


def mkl_operator(A: sp.spmatrix) -> spla.LinearOperator | None:
    """``A`` as a LinearOperator whose products run in MKL's sparse BLAS, or None when MKL is not
    installed (or refuses the matrix): the caller then uses ``A`` itself.  MKL's LP64 interface
    (32-bit indices), as for PARDISO."""
    lib = mkl_library()
    if lib is None:
        return None
    try:
        _prototypes(lib)
        mat = MklMatrix(A, lib)
    except (AttributeError, RuntimeError, OSError, TypeError, ctypes.ArgumentError):
        return None
    return spla.LinearOperator(A.shape, matvec=mat.matvec, dtype=float)
