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
    solver.factorized_A = solver._hash_csr_matrix(A)   # ``solve`` then reuses the factor (phase 33)
    b = np.zeros((A.shape[0], 1))
    t0 = time.perf_counter()
    solver.set_phase(11)
    solver._call_pardiso(A, b)
    t_analysis = time.perf_counter() - t0
    solver.set_phase(22)
    solver._call_pardiso(A, b)
    return t_analysis
