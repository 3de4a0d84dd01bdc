"""Factorise (or precondition) a stiffness matrix once; solve many load cases against it.

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

Every solution is checked: finite, and relative residual ||K x - b|| / ||b|| below
``residual_tol``; otherwise :class:`~fe_crank.errors.SolverError`.
"""

from __future__ import annotations

import logging
import shutil
import time
import warnings
import weakref
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from fe_crank.errors import InputError, SolverError
from fe_crank.fe.pardiso_ooc import out_of_core
from fe_crank.fe.pardiso_phases import pardiso_factorize

METHODS = ("auto", "pardiso", "pardiso_ooc", "cholmod", "amg", "superlu")
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
log = logging.getLogger(__name__)
_warned: set[str] = set()


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


@dataclass
class Factorisation:
    """A matrix prepared for repeated solves.  ``solve(B)`` takes (n,) or (n, k)."""

    matrix: sp.csr_matrix | None
    method: str
    setup_time: float
    residual_tol: float = 1e-8
    _impl: object = field(default=None, repr=False)
    _near_null: np.ndarray | None = field(default=None, repr=False)
    amg_rtol: float = 1e-10
    amg_maxiter: int = 2000
    note: str | None = None  # why this method ran when ``auto`` fell back from PARDISO
    _nnz: int | None = field(default=None, repr=False)  # kept by ``free``
    _ooc_dir: str | None = field(default=None, repr=False)  # PARDISO's factor files (pardiso_ooc)
    analysis_time: float = 0.0  # PARDISO: its phase 1 (reordering, symbolic), part of setup_time
    _finalizer: object = field(default=None, repr=False, compare=False)

    def own_external(self) -> None:
        """Tie what PARDISO holds outside Python's memory (the factor in MKL's own memory,
        the out-of-core factor files) to this object's lifetime: released by ``free`` or,
        at the latest, when the object is garbage-collected.  Without it a process that
        solves several models (a batch, the convergence study) keeps every factor."""
        if self.method in ("pardiso", "pardiso_ooc") and self._finalizer is None:
            self._finalizer = weakref.finalize(self, _release_external, self._impl, self._ooc_dir)

    @property
    def description(self) -> str:
        """The solver in words, with the fallback note if any (for reports)."""
        d = DESCRIPTIONS.get(self.method, self.method)
        return d if not self.note else f"{d} ({self.note})"

    def solve(self, b: np.ndarray) -> np.ndarray:
        b = np.asarray(b, dtype=float)
        single = b.ndim == 1
        B = b[:, None] if single else b
        if not np.all(np.isfinite(B)):
            raise SolverError("load vector contains NaN or Inf")
        if self._impl is None:
            raise SolverError(
                f"{self.method}: the factorisation was released (Factorisation.free); factorise again to solve"
            )
        if self.method in ("pardiso", "pardiso_ooc"):
            X = self._solve_pardiso(B)
        elif self.method == "superlu":
            X = self._impl.solve(np.ascontiguousarray(B))
        elif self.method == "cholmod":
            B = np.ascontiguousarray(B)
            X = np.zeros_like(B)
            self._impl.solve(B, X)
        else:
            X = np.column_stack([self._solve_amg(B[:, k]) for k in range(B.shape[1])])
        X = np.asarray(X).reshape(B.shape)
        self._check(B, X)
        return X[:, 0] if single else X

    def _solve_pardiso(self, B):
        from pypardiso.pardiso_wrapper import PyPardisoError

        try:
            with warnings.catch_warnings():
                warnings.simplefilter("error")
                return self._impl.solve(self._upper, B)
        except (PyPardisoError, Warning) as exc:
            raise SolverError(f"PARDISO solve failed: {exc}") from exc

    def _solve_amg(self, b):
        if not np.any(b):
            return np.zeros_like(b)
        info = {"it": 0}

        def count(_):
            info["it"] += 1

        x, flag = spla.cg(
            self.matrix,
            b,
            rtol=self.amg_rtol,
            maxiter=self.amg_maxiter,
            M=self._impl.aspreconditioner(cycle="V"),
            callback=count,
        )
        if flag != 0:
            raise SolverError(
                f"AMG-preconditioned CG did not converge in {info['it']} iterations (rtol {self.amg_rtol:g})"
            )
        return x

    def _check(self, B, X):
        if not np.all(np.isfinite(X)):
            raise SolverError(f"{self.method}: solution contains NaN or Inf (singular or unsupported model?)")
        R = self._matvec(X) - B
        nb = np.linalg.norm(B, axis=0)
        nr = np.linalg.norm(R, axis=0)
        rel = np.where(nb > 0, nr / np.where(nb > 0, nb, 1.0), nr)
        tol = self.residual_tol if self.method != "amg" else max(self.residual_tol, 10 * self.amg_rtol)
        if np.any(rel > tol):
            raise SolverError(
                f"{self.method}: relative residual {rel.max():.3e} exceeds {tol:g} "
                "(singular stiffness: is the body supported against every rigid-body mode?)"
            )

    @property
    def nnz(self) -> int:
        """Stored non-zeros of the full symmetric matrix."""
        if self._nnz is not None:
            return self._nnz
        if self.matrix is not None:
            return int(self.matrix.nnz)
        return int(2 * self._upper.nnz - self._upper.shape[0])

    def _matvec(self, X):
        if self.matrix is not None:
            return self.matrix @ X
        U = self._upper  # pardiso/cholmod keep one triangle: K = U + U^T - D
        return U @ X + U.T @ X - self._diag[:, None] * X

    def free(self):
        """Release the factorisation's memory (PARDISO keeps it in MKL's own memory).
        The matrix goes too; the method, its description and ``nnz`` stay; ``solve``
        raises ``SolverError`` afterwards."""
        if self._impl is None:
            return
        self._nnz = self.nnz
        if self._finalizer is not None:
            self._finalizer()  # runs once: a later garbage collection does nothing
        elif self.method in ("pardiso", "pardiso_ooc"):
            _release_external(self._impl, self._ooc_dir)
        self._impl = None
        self.matrix = self._upper = self._diag = self._near_null = None


def _release_external(impl, ooc_dir: str | None) -> None:
    """Free a PARDISO factor (phase -1, or phase 0 of one member of a shared handle) and
    remove its out-of-core factor files."""
    impl.free_memory(everything=True)
    if ooc_dir is not None:
        shutil.rmtree(ooc_dir, ignore_errors=True)


def factorise(
    K: sp.spmatrix,
    method: str = "auto",
    *,
    near_nullspace: np.ndarray | None = None,
    residual_tol: float = 1e-8,
    amg_rtol: float = 1e-10,
    upper: bool = False,
) -> Factorisation:
    """Prepare the SPD matrix ``K`` for repeated solves with ``method`` (see module doc).

    ``near_nullspace`` (n, 6): rigid-body modes for smoothed aggregation (Vanek, Mandel &
    Brezina 1996); required for good AMG convergence in elasticity.
    ``upper``: ``K`` holds the upper triangle only (diagonal included), which is all the
    direct methods read; the caller can then drop the full matrix before the
    factorisation (``build_system`` does: about 1 GB less at the peak of a 1M-DOF run).
    Only for ``pardiso``, ``pardiso_ooc`` and ``cholmod``.
    """
    K = sp.csr_matrix(K)
    K.sort_indices()
    n = K.shape[0]
    if n == 0:
        raise SolverError("empty system: every degree of freedom is constrained")
    if np.any(np.diff(K.indptr) == 0):  # for an upper triangle: no diagonal and no coupling to later dofs
        raise SolverError("singular stiffness: a degree of freedom has no stiffness (empty row)")
    chosen = choose_method(method, n)
    if upper and chosen not in ("pardiso", "pardiso_ooc", "cholmod"):
        raise ValueError(f"an upper triangle cannot be factorised by {chosen}: it needs the whole matrix")
    note = fallback_note(method, n)
    if note and note not in _warned:  # once per process: batch runs solve many meshes
        _warned.add(note)
        log.warning("fe-crank: %s", note)
    t0 = time.perf_counter()
    fac = Factorisation(
        matrix=K, method=chosen, setup_time=0.0, residual_tol=residual_tol, amg_rtol=amg_rtol, note=note
    )
    if chosen in ("pardiso", "pardiso_ooc"):
        import pypardiso
        from pypardiso.pardiso_wrapper import PyPardisoError

        tri = K if upper else sp.triu(K, format="csr")
        tri.sort_indices()
        solver = pypardiso.PyPardisoSolver(mtype=2, size_limit_storage=0)
        if chosen == "pardiso_ooc":
            fac._ooc_dir = out_of_core(solver)
        try:
            fac.analysis_time = pardiso_factorize(solver, tri)
        except PyPardisoError as exc:
            raise SolverError(
                f"PARDISO factorisation failed (matrix not positive definite: unsupported rigid-body mode?): {exc}"
            ) from exc
        fac._impl = solver
        fac.own_external()
        fac._upper = tri
        fac._diag = K.diagonal()
        fac.matrix = None  # only the upper triangle is kept (memory)
    elif chosen == "cholmod":
        from cholespy import CholeskySolverD, MatrixType

        lower = K.T.tocsc() if upper else sp.tril(K, format="csc")  # CHOLMOD reads the lower triangle (stype -1)
        lower.sort_indices()
        try:
            fac._impl = CholeskySolverD(
                n,
                lower.indptr.astype(np.int32),
                lower.indices.astype(np.int32),
                np.ascontiguousarray(lower.data, dtype=float),
                MatrixType.CSC,
            )
        except Exception as exc:
            raise SolverError(
                f"CHOLMOD factorisation failed (matrix not positive definite: unsupported rigid-body mode?): {exc}"
            ) from exc
        fac._upper = lower.T.tocsr()  # the same triangle as CSR upper (for residuals)
        fac._diag = K.diagonal()
        fac.matrix = None
    elif chosen == "superlu":
        try:
            fac._impl = spla.splu(K.tocsc())
        except RuntimeError as exc:
            raise SolverError(f"SuperLU factorisation failed (singular stiffness): {exc}") from exc
    else:
        import pyamg

        B = near_nullspace if near_nullspace is not None else np.ones((n, 1))
        fac._impl = pyamg.smoothed_aggregation_solver(K, B=B, max_coarse=500)
        fac._near_null = B
    fac.setup_time = time.perf_counter() - t0
    return fac
