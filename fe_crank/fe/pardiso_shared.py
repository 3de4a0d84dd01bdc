"""The component factors of a symmetric throw on one MKL PARDISO handle (``fe.symsolve``).

Every component matrix has the pattern of the part's stiffness, so one handle holds all
their factors (``maxfct`` = 2^k): the analysis (phase 11) runs once and each component only
needs its numerical factorisation (phase 22) (``pardiso_phases.SharedAnalysis``; Intel
oneMKL reference, ``pardiso`` parameters ``maxfct``/``mnum``).
"""

from __future__ import annotations

import copy
import time
from typing import Any

import numpy as np
import scipy.sparse as sp

from fe_crank.errors import SolverError
from fe_crank.fe.pardiso_phases import SharedAnalysis
from fe_crank.fe.solvers import Factorisation

#: a loaded PyPardisoSolver to copy (``Any``: pypardiso has no type information)
_TEMPLATE: dict[str, Any] = {}


def pardiso_solver() -> Any:
    """A fresh PyPardisoSolver (SPD) with MKL's defaults for a real SPD matrix stated (MKL reads
    user iparm values only with iparm(1) = 1; as ``pardiso_ooc.out_of_core``).  Typed ``Any``:
    pypardiso has no type information."""
    import pypardiso

    if "solver" not in _TEMPLATE:  # finding and loading mkl_rt takes ~0.6 s: once per process
        _TEMPLATE["solver"] = pypardiso.PyPardisoSolver(mtype=2, size_limit_storage=0)
    solver = copy.copy(_TEMPLATE["solver"])
    solver.pt = np.zeros_like(solver.pt)  # a handle of its own
    solver.iparm = np.zeros_like(solver.iparm)
    solver.iparm[0] = 1
    solver.iparm[1] = 2  # METIS nested dissection
    solver.iparm[9] = 8
    solver.iparm[17] = -1
    return solver


def factorise_shared(matrices: list[sp.csr_matrix]) -> list[Factorisation]:
    """The component matrices (one pattern) factorised on one PARDISO handle: one analysis."""
    from pypardiso.pardiso_wrapper import PyPardisoError

    out = []
    try:
        shared = SharedAnalysis(pardiso_solver(), matrices[0], len(matrices))
        for k, A in enumerate(matrices):
            t0 = time.perf_counter()
            member = shared.factor(k + 1, A)
            fac = Factorisation(
                matrix=None,
                method="pardiso",
                setup_time=time.perf_counter() - t0,
                analysis_time=shared.analysis_time if k == 0 else 0.0,
            )
            fac._impl, fac._upper, fac._diag = member, A, A.diagonal()
            fac.own_external()
            out.append(fac)
    except PyPardisoError as exc:
        raise SolverError(f"PARDISO factorisation of a symmetry component failed: {exc}") from exc
    return out
