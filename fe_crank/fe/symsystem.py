"""A :class:`~fe_crank.fe.system.System` of the determinate throw solved on symmetry components.

``build_system`` calls :func:`symmetric_system` when the mesh states mirror planes: the
symmetry is verified on the P2 nodes and elements (``fe.symmetry``), the components are
factorised on the fundamental part (``fe.symsolve``), and the result has the same face
as the full model's System: ``solve``, ``reactions``, ``equilibrium_error`` (the point
dofs' reactions from the full stiffness's rows at the six point dofs, assembled on the
elements around them: a row of K at node i has terms of the elements of i only),
``n_dof`` (the full model's unknowns), ``factorisation.free()``, ``timings``.  Whenever
the symmetric path does not apply it says why in the log and returns None: the full
model is solved instead, never a wrong answer.
"""

from __future__ import annotations

import logging
import time

import numpy as np
import scipy.sparse as sp
from skfem import Basis

from fe_crank.fe.assembly import assemble_stiffness
from fe_crank.fe.bases import cell_basis
from fe_crank.fe.determinate import determinate_support
from fe_crank.fe.stress import elements_of_nodes
from fe_crank.fe.symmetry import mesh_mirror
from fe_crank.fe.symsolve import build_symmetric_solver
from fe_crank.fe.system import System, build_system

log = logging.getLogger(__name__)


def stiffness_rows(basis, youngs_modulus: float, poisson_ratio: float, rows: np.ndarray) -> sp.csr_matrix:
    """Rows ``rows`` (vector dofs) of the full stiffness K, (len(rows), 3 N), assembled on the
    elements that contain their nodes only."""
    elements = elements_of_nodes(basis.element_dofs, np.unique(rows // 3), basis.N)
    sub = Basis(
        basis.mesh, basis.elem, mapping=basis.mapping, quadrature=(basis.X, basis.W), dofs=basis.dofs, elements=elements
    )
    return assemble_stiffness(sub, youngs_modulus, poisson_ratio)[rows].tocsr()


def selection(n: int, held: np.ndarray) -> sp.csr_matrix:
    """P (n, n - len(held)): the full vector <- the dofs not in ``held`` (unique, sorted), in
    ascending order; built as CSR directly (row i holds one 1 in column
    (number of kept dofs before i)), the matrix the COO route with ``setdiff1d`` gives."""
    keep = np.ones(n, bool)
    keep[held] = False
    indptr = np.zeros(n + 1, np.int64)
    np.cumsum(keep, out=indptr[1:])
    m = int(indptr[-1])
    return sp.csr_matrix((np.ones(m), np.arange(m), indptr), shape=(n, m))


def determinate_system(
    mesh, youngs_modulus: float, poisson_ratio: float, layout, axes=(), *, solver: str = "auto", intorder: int = 2
) -> System:
    """The System of the determinate supports ``layout``: on the symmetry components across
    ``axes`` (the mesh's stated mirror planes) where they verify, else the full model."""
    t0 = time.perf_counter()
    basis = cell_basis(mesh, intorder)  # the whole mesh's P2 basis, built once (fe.bases)
    sup = determinate_support(basis, layout)
    if axes:
        system = symmetric_system(basis, sup, youngs_modulus, poisson_ratio, axes, solver, t0)
        if system is not None:
            return system
    t_pre = time.perf_counter() - t0
    system = build_system(
        mesh, youngs_modulus, poisson_ratio, determinate=sup, solver=solver, intorder=intorder, basis=basis
    )
    system.timings["assembly"] += t_pre
    return system


def symmetric_system(
    basis, sup, youngs_modulus: float, poisson_ratio: float, axes, solver: str, t_start: float
) -> System | None:
    """The determinate ``System`` solved on the symmetry components across ``axes``, or None
    (logged why)."""
    mirror = mesh_mirror(basis.mesh, basis, axes)
    if mirror is None:
        return None
    t_pre = time.perf_counter() - t_start  # basis and determinate supports
    solver_ = build_symmetric_solver(basis, mirror, youngs_modulus, poisson_ratio, sup.held, solver)
    if solver_ is None:
        return None
    t0 = time.perf_counter()
    rows = np.unique(sup.held)
    K_rows = stiffness_rows(basis, youngs_modulus, poisson_ratio, rows)
    n = 3 * basis.N
    P = selection(n, rows)
    t = solver_.timings
    timings = {
        "assembly": t_pre + t["assembly"],
        "constraints": t["constraints"] + time.perf_counter() - t0,
        "factorisation": t["factorisation"],
    }
    log.info("fe-crank: %s", solver_.description)
    return System(
        mesh=basis.mesh,
        basis=basis,
        K_rows=K_rows,
        rows=rows,
        Ks=sp.csr_matrix((n, n)),
        P=P,
        foundations=(),
        couplings=(),
        ref_points={},
        ref_columns={},
        slave_dofs={},
        dirichlet_dofs=np.zeros(0, int),
        foundation_dofs={},
        factorisation=solver_,
        point_dofs=rows,
        determinate=sup,
        timings=timings,
        symmetric=solver_,
    )
