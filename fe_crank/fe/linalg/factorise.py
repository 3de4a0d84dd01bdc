"""The linear algebra of the FE stage: factorise (or precondition) a stiffness matrix once,
solve many load cases against it.

The method (``fe.linalg.choice``: MKL PARDISO in or out of core, CHOLMOD, AMG-CG, SuperLU)
is resolved by :func:`~fe_crank.fe.linalg.choice.choose_method`; a fallback of ``auto`` is
logged as a warning (once per process) and recorded in ``Factorisation.note``.

Every solution is checked: finite, and relative residual ||K x - b|| / ||b|| below
``residual_tol``; otherwise :class:`~fe_crank.errors.SolverError`.

**MKL PARDISO's phases.**  Its factorisation runs as its two phases, so that each is timed
(and the ordering reused): phase 11 is the analysis (fill-reducing reordering, METIS
nested dissection by default, and the symbolic factorisation), phase 22 the numerical
factorisation; together they are phase 12, what ``PyPardisoSolver.factorize`` runs (Intel
oneMKL reference, ``pardiso`` phase).

**Out of core** (``[fe] solver = "pardiso_ooc"``, and ``auto`` above
``solver_choice.OOC_MIN_DOF`` unknowns): the factor is kept in files when it does not fit the
in-core budget.  MKL takes its out-of-core settings from environment variables only
(``MKL_PARDISO_OOC_PATH``, ``MKL_PARDISO_OOC_MAX_CORE_SIZE``, ``MKL_PARDISO_OOC_KEEP_FILE``;
Intel oneMKL reference, "PARDISO OOC"), so :func:`out_of_core` is the one place where the
package sets process environment, and only when the out-of-core solver is chosen.

**Bit-identical on every run.**  With its default settings MKL PARDISO's threaded
factorisation is not reproducible: the same matrix factorised twice in one process gives
solutions that differ in their last bits (measured from 19k unknowns up), which can move
a hot-spot node or flip a verdict at a limit.  Every handle is therefore made in MKL's
conditional numerical reproducibility mode for a fixed thread count, ``iparm(34) =
CNR_THREADS`` (Intel oneMKL reference, ``pardiso`` iparm; nested dissection by
``iparm(2) = 2``, not the parallel ``3``, which excludes that mode): the result is then the
same on every run and whatever number of threads MKL actually runs (1 and 2 threads
measured equal), on the same processor family and MKL version.

**One handle for the components of a symmetric throw** (``fe.core.symmetric``): every component
matrix has the pattern of the part's stiffness, so one handle holds all their factors
(``maxfct`` = 2^k): the analysis (phase 11) runs once and each component only needs its
numerical factorisation (phase 22) (:class:`SharedAnalysis`, :func:`factorise_shared`; Intel
oneMKL reference, ``pardiso`` parameters ``maxfct``/``mnum``).
"""

from __future__ import annotations

import logging
import os
import shutil
import tempfile
import time
import warnings
import weakref
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from fe_crank.errors import SolverError
from fe_crank.fe.linalg.choice import DESCRIPTIONS, choose_method, fallback_note

log = logging.getLogger(__name__)
_warned: set[str] = set()


@dataclass
class Factorisation:
    """A matrix prepared for repeated solves.  ``solve(B)`` takes (n,) or (n, k)."""

    matrix: sp.csr_matrix | None
    method: str
    setup_time: float
    residual_tol: float = 1e-8
    # the third-party solver (pypardiso's PyPardisoSolver or a shared handle's member, cholespy's
    # CholeskySolverD, SciPy's SuperLU, pyamg's MultilevelSolver): untyped packages
    _impl: Any = field(default=None, repr=False)
    _near_null: np.ndarray | None = field(default=None, repr=False)
    amg_rtol: float = 1e-10
    amg_maxiter: int = 2000
    note: str | None = None  # why this method ran when ``auto`` fell back from PARDISO
    _nnz: int | None = field(default=None, repr=False)  # kept by ``free``
    _ooc_dir: str | None = field(default=None, repr=False)  # PARDISO's factor files (pardiso_ooc)
    analysis_time: float = 0.0  # PARDISO: its phase 1 (reordering, symbolic), part of setup_time
    _finalizer: weakref.finalize | None = field(default=None, repr=False, compare=False)
    # what a direct method keeps of the matrix (residuals: K = U + U^T - D): its upper triangle U
    # and its diagonal D
    _upper: sp.csr_matrix | None = field(default=None, repr=False, compare=False)
    _diag: np.ndarray | None = field(default=None, repr=False, compare=False)

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

    def _solve_pardiso(self, B: np.ndarray) -> np.ndarray:
        from pypardiso.pardiso_wrapper import PyPardisoError

        try:
            with warnings.catch_warnings():
                warnings.simplefilter("error")
                return self._impl.solve(self._upper, B)
        except (PyPardisoError, Warning) as exc:
            raise SolverError(f"PARDISO solve failed: {exc}") from exc

    def _solve_amg(self, b: np.ndarray) -> np.ndarray:
        if not np.any(b):
            return np.zeros_like(b)
        info = {"it": 0}

        def count(_: np.ndarray) -> None:
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

    def _check(self, B: np.ndarray, X: np.ndarray) -> None:
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
        assert self._upper is not None  # a direct method keeps the triangle in place of the matrix
        return int(2 * self._upper.nnz - self._upper.shape[0])

    def _matvec(self, X: np.ndarray) -> np.ndarray:
        if self.matrix is not None:
            return self.matrix @ X
        U = self._upper  # pardiso/cholmod keep one triangle: K = U + U^T - D
        assert U is not None and self._diag is not None  # kept in place of the matrix
        return U @ X + U.T @ X - self._diag[:, None] * X

    def free(self) -> None:
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


def _release_external(impl: Any, ooc_dir: str | None) -> None:
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
        from pypardiso.pardiso_wrapper import PyPardisoError

        tri = K if upper else sp.triu(K, format="csr")
        tri.sort_indices()
        solver = pardiso_solver()
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


# -- MKL PARDISO's phases (module docstring) --


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


# -- PARDISO out of core --

#: in-core budget of an out-of-core factorisation, share of the machine's memory
OOC_CORE_SHARE = 0.6
#: the thread count of MKL PARDISO's reproducible mode, iparm(34): fixed, so that the
#: results do not depend on the machine's cores (module docstring)
CNR_THREADS = 2


def out_of_core(solver) -> str:
    """Switch a PyPardisoSolver made by :func:`pardiso_solver` (its iparm stated) to MKL
    PARDISO's out-of-core mode; returns the folder of its factor files.  iparm(60) = 1: in
    core when the factor fits ``MKL_PARDISO_OOC_MAX_CORE_SIZE`` MB, else out of core
    (Intel oneMKL reference, ``pardiso`` iparm).  ``MKL_PARDISO_OOC_PATH`` is a prefix: it
    must end with a separator to put the files into the folder.
    """
    folder = tempfile.mkdtemp(prefix="fe-crank-pardiso-", dir=os.environ.get("FE_CRANK_OOC_DIR") or None)
    os.environ["MKL_PARDISO_OOC_PATH"] = os.path.join(folder, "")
    if "MKL_PARDISO_OOC_MAX_CORE_SIZE" not in os.environ:
        os.environ["MKL_PARDISO_OOC_MAX_CORE_SIZE"] = str(int(OOC_CORE_SHARE * _memory_bytes() / 2**20))
    os.environ.setdefault("MKL_PARDISO_OOC_KEEP_FILE", "0")  # files deleted when the factor is released
    solver.iparm[59] = 1
    return folder


def _memory_bytes() -> int:
    """Physical memory of the machine (bytes)."""
    return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")


# -- the components of a symmetric throw on one PARDISO handle --


#: a loaded PyPardisoSolver to copy (``Any``: pypardiso has no type information)
def new_pardiso() -> Any:
    """``PyPardisoSolver(mtype=2, size_limit_storage=0)`` (a handle and iparm of its own), with
    the MKL library pypardiso found for the first solver of the process named for the next
    ones by pypardiso's own setting ``PYPARDISO_MKL_RT``: without it pypardiso's constructor
    searches the Python prefix for ``mkl_rt`` with a recursive glob each time (about 1 s).
    A path the user set is kept.  Typed ``Any``: pypardiso has no type information."""
    import pypardiso

    solver = pypardiso.PyPardisoSolver(mtype=2, size_limit_storage=0)
    found = getattr(solver.libmkl, "_name", None)
    if "PYPARDISO_MKL_RT" not in os.environ and isinstance(found, str) and os.path.isfile(found):
        os.environ["PYPARDISO_MKL_RT"] = found
    return solver


def pardiso_solver() -> Any:
    """A fresh PyPardisoSolver (SPD) with its iparm stated, in MKL's reproducible mode.

    MKL reads user iparm values only when iparm(1) = 1 (otherwise it fills in its defaults
    and ignores the rest), so the defaults of a real SPD matrix are stated (Intel oneMKL
    reference, ``pardiso`` iparm): iparm(2) = 2 nested dissection (METIS), iparm(10) = 8
    pivot perturbation 1e-8 (unused without pivoting), iparm(18) = -1 report the factor's
    non-zeros; and iparm(34) = ``CNR_THREADS`` (module docstring).  Typed ``Any``: pypardiso
    has no type information."""
    solver = new_pardiso()
    solver.iparm[0] = 1
    solver.iparm[1] = 2  # METIS nested dissection
    solver.iparm[9] = 8
    solver.iparm[17] = -1
    solver.iparm[33] = CNR_THREADS  # reproducible results (module docstring)
    return solver


def shared_member(shared: SharedAnalysis, k: int, A: sp.csr_matrix) -> Factorisation:
    """Matrix ``k`` (0-based; ``A``, the common pattern) factorised on the handle ``shared``
    (phase 22 under number k + 1).  Raises pypardiso's ``PyPardisoError``."""
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
    return fac


def factorise_shared(matrices: list[sp.csr_matrix]) -> list[Factorisation]:
    """The component matrices (one pattern) factorised on one PARDISO handle: one analysis."""
    from pypardiso.pardiso_wrapper import PyPardisoError

    try:
        shared = SharedAnalysis(pardiso_solver(), matrices[0], len(matrices))
        return [shared_member(shared, k, A) for k, A in enumerate(matrices)]
    except PyPardisoError as exc:
        raise SolverError(f"PARDISO factorisation of a symmetry component failed: {exc}") from exc
