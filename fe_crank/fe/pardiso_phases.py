"""MKL PARDISO's factorisation as its two phases, so that each is timed (and the ordering reused).

Phase 11 is the analysis (fill-reducing reordering, METIS nested dissection by default,
and the symbolic factorisation), phase 22 the numerical factorisation; together they are
phase 12, what ``PyPardisoSolver.factorize`` runs (Intel oneMKL reference, ``pardiso``
phase).
"""

from __future__ import annotations

import time

import numpy as np
import scipy.sparse as sp


def pardiso_factorize(solver, A: sp.csr_matrix) -> float:
    """``PyPardisoSolver.factorize`` as its two phases, 11 (analysis: fill-reducing ordering
    and symbolic factorisation) then 22 (numerical factorisation), the same work as its
    phase 12; returns the seconds of the analysis."""
    solver._check_A(A)
    solver.factorized_A = solver._hash_csr_matrix(A)  # ``solve`` then reuses the factor (phase 33)
    b = np.zeros((A.shape[0], 1))
    t0 = time.perf_counter()
    solver.set_phase(11)
    solver._call_pardiso(A, b)
    t_analysis = time.perf_counter() - t0
    solver.set_phase(22)
    solver._call_pardiso(A, b)
    return t_analysis


class SharedAnalysis:
    """One MKL PARDISO handle for up to ``maxfct`` matrices of one sparsity pattern: the
    analysis (phase 11) runs once, each matrix is factorised by phase 22 under its own
    number ``mnum`` and solved by phase 33 with it (PARDISO's ``maxfct``/``mnum``: "maximum
    number of factors with identical sparsity structure that must be kept in memory at
    the same time"; Intel oneMKL reference, ``pardiso`` parameters).

    ``solver``: a ``pypardiso.PyPardisoSolver`` whose handle ``pt`` is unused, with its
    ``iparm`` set; ``A``: the common pattern (CSR upper triangle, sorted).
    """

    def __init__(self, solver, A: sp.csr_matrix, maxfct: int):
        self.solver = solver
        self.maxfct = int(maxfct)
        self.n = A.shape[0]
        self.ia = A.indptr.astype(np.int32) + 1  # 1-based (iparm(35) = 0)
        self.ja = A.indices.astype(np.int32) + 1
        self.live: set[int] = set()
        t0 = time.perf_counter()
        self.call(1, 11, A.data, np.zeros((self.n, 1)))
        self.analysis_time = time.perf_counter() - t0

    def call(self, mnum: int, phase: int, data: np.ndarray, b: np.ndarray) -> np.ndarray:
        """One call of ``pardiso`` on matrix ``mnum`` (1..maxfct) with values ``data``."""
        import ctypes

        from pypardiso.pardiso_wrapper import PyPardisoError

        s = self.solver
        b = np.asfortranarray(b, dtype=float)
        x = np.zeros_like(b)
        err = ctypes.c_int32(0)
        i32, f64 = ctypes.POINTER(ctypes.c_int32), ctypes.POINTER(ctypes.c_double)
        data = np.ascontiguousarray(data, dtype=float)
        s._mkl_pardiso(
            s.pt.ctypes.data_as(ctypes.POINTER(s._pt_type[0])),
            ctypes.byref(ctypes.c_int32(self.maxfct)),
            ctypes.byref(ctypes.c_int32(mnum)),
            ctypes.byref(ctypes.c_int32(s.mtype)),
            ctypes.byref(ctypes.c_int32(phase)),
            ctypes.byref(ctypes.c_int32(self.n)),
            data.ctypes.data_as(f64),
            self.ia.ctypes.data_as(i32),
            self.ja.ctypes.data_as(i32),
            s.perm.ctypes.data_as(i32),
            ctypes.byref(ctypes.c_int32(1 if b.ndim == 1 else b.shape[1])),
            s.iparm.ctypes.data_as(i32),
            ctypes.byref(ctypes.c_int32(0)),
            b.ctypes.data_as(f64),
            x.ctypes.data_as(f64),
            ctypes.byref(err),
        )
        if err.value != 0:
            raise PyPardisoError(err.value)
        return np.ascontiguousarray(x)

    def factor(self, mnum: int, A: sp.csr_matrix) -> SharedMember:
        """Phase 22 of matrix ``mnum`` (values of ``A``, the common pattern)."""
        if not (np.array_equal(A.indptr + 1, self.ia) and np.array_equal(A.indices + 1, self.ja)):
            raise ValueError("a matrix of another sparsity pattern cannot share the analysis")
        self.call(mnum, 22, A.data, np.zeros((self.n, 1)))
        self.live.add(mnum)
        return SharedMember(self, mnum)

    def release(self, mnum: int) -> None:
        """Phase 0 (this factor's memory); phase -1 (everything) with the last one."""
        if mnum not in self.live:
            return
        self.live.discard(mnum)
        empty = np.zeros(0)
        self.call(mnum, 0 if self.live else -1, empty, np.zeros((0, 1)))


class SharedMember:
    """What ``Factorisation`` calls on a PARDISO factor (``solve(A, B)``, ``free_memory``)."""

    def __init__(self, shared: SharedAnalysis, mnum: int):
        self.shared, self.mnum = shared, mnum

    def solve(self, A: sp.csr_matrix, B: np.ndarray) -> np.ndarray:
        return self.shared.call(self.mnum, 33, A.data, B)

    def free_memory(self, everything: bool = False) -> None:
        self.shared.release(self.mnum)
