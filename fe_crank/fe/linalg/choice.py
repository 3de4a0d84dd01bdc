"""Which linear solver factorises the stiffness: the methods, their availability and ``auto``.

Methods
-------
``pardiso``  MKL PARDISO through pypardiso, symmetric positive-definite type (mtype 2)
             on the upper triangle; the factorisation is computed once (phase 12) and
             every right-hand side reuses it (phase 33).  Default where it imports.
``pardiso_ooc``  the same, out of core where the factor does not fit in memory (MKL
             PARDISO's iparm(60) = 1: in core if the factor fits ``MKL_PARDISO_OOC_MAX_CORE_SIZE``
             MB, default 60 % of the machine's memory, else its factor on disk in a temporary
             folder, ``FE_CRANK_OOC_DIR`` or the system's); ``auto`` takes it above
             ``OOC_MIN_DOF`` unknowns (the ``fine`` preset), so every smaller run is unchanged.
``cholmod``  CHOLMOD supernodal Cholesky (SuiteSparse) through cholespy, whose wheels bundle
             CHOLMOD, METIS and a reference BLAS (no system package); the lower
             triangle is factorised once and every right-hand side reuses it.  The
             fallback where pypardiso does not install (docs/performance.md).
``amg``      conjugate gradients preconditioned by pyamg smoothed aggregation with the
             rigid-body modes as near-nullspace (pure pip, low memory, slow per case).
``superlu``  SciPy SuperLU: always available; for small systems.

``auto`` picks pardiso, else cholmod, else SuperLU (small) or AMG-CG (large), and says so:
a fallback is logged as a warning and recorded in ``Factorisation.note``.
"""

from __future__ import annotations

from typing import Literal, get_args

from fe_crank.errors import InputError

#: the solvers a load case may name (``[fe] solver``)
SolverMethod = Literal["auto", "pardiso", "pardiso_ooc", "cholmod", "amg", "superlu"]
METHODS: tuple[SolverMethod, ...] = get_args(SolverMethod)
#: above this many unknowns ``auto`` lets PARDISO go out of core when its factor does not fit
#: (the ``fine`` preset, 2.9M DOF, needs ~27 GB in core; ``medium``, 1.0-1.15M DOF, 8 GB)
OOC_MIN_DOF = 1_500_000
SUPERLU_MAX_DOF = 60_000
DESCRIPTIONS = {
    "pardiso": "MKL PARDISO (pypardiso), sparse Cholesky, factorised once",
    "pardiso_ooc": "MKL PARDISO (pypardiso), sparse Cholesky, factorised once, out of core where the factor "
    "does not fit in memory",
    "cholmod": "CHOLMOD (SuiteSparse, via cholespy), supernodal Cholesky, factorised once",
    "superlu": "SciPy SuperLU, sparse LU, factorised once",
    "amg": "conjugate gradients with pyamg smoothed-aggregation preconditioner (rigid-body modes)",
}


def pardiso_available() -> bool:
    """True where pypardiso (and MKL) import."""
    try:
        import pypardiso  # noqa: F401
    except Exception:
        return False
    return True


def cholmod_available() -> bool:
    """True where cholespy (CHOLMOD) imports."""
    try:
        import cholespy  # noqa: F401
    except Exception:
        return False
    return True


def fallback_note(method: str, n_dof: int) -> str | None:
    """Why ``auto`` did not pick PARDISO, or None when it did (or a method was asked for)."""
    if method != "auto" or pardiso_available():
        return None
    chosen = choose_method("auto", n_dof)
    return (
        f"pypardiso (MKL PARDISO) is not installed; using {DESCRIPTIONS[chosen]} instead"
        + ("" if chosen == "cholmod" else ", much slower on large meshes")
        + ". Install it with: pip install pypardiso (x86-64)"
    )


def choose_method(method: str, n_dof: int) -> str:
    """Resolve ``auto``: pardiso where it imports (``pardiso_ooc`` above ``OOC_MIN_DOF``
    unknowns), else cholmod where cholespy imports, else SuperLU for small and AMG-CG for
    large systems."""
    if method not in METHODS:
        raise InputError(f"unknown solver {method!r}; pick one of {', '.join(METHODS)}", key="fe.solver")
    if method != "auto":
        if method == "pardiso_ooc" and not pardiso_available():
            raise InputError(
                "solver 'pardiso_ooc' needs pypardiso (MKL PARDISO): pip install pypardiso", key="fe.solver"
            )
        return method
    if pardiso_available():
        return "pardiso_ooc" if n_dof > OOC_MIN_DOF else "pardiso"
    if cholmod_available():
        return "cholmod"
    return "superlu" if n_dof <= SUPERLU_MAX_DOF else "amg"
