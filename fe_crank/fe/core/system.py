"""One assembled, supported elastic system: stiffness, constraints, reduction, reactions.

The full vector of nodal displacements u (interleaved, 3 per P2 node) is written as
u = P q, where q holds the free nodal dofs and the free dofs of each coupling's reference
point; held dofs are simply absent from q.  The reduced stiffness is K_r = P^T (K + K_s) P
(K elastic, K_s foundations), symmetric positive definite when the supports remove every
rigid-body mode.  Loads: f_r = P^T f + (generalised loads at reference dofs).

The determinate throw on symmetry components (:func:`determinate_system`,
:func:`symmetric_system`): when the mesh states mirror planes, the symmetry is verified on
the P2 nodes and elements and the components are factorised on the fundamental part
(``fe.core.symmetric``); the System has the same face as the full model's: ``solve``,
``reactions``, ``equilibrium_error`` (the point dofs' reactions from the full stiffness's
rows at the six point dofs, assembled on the elements around them: a row of K at node i
has terms of the elements of i only), ``n_dof`` (the full model's unknowns),
``factorisation.free()``, ``timings``.  Whenever the symmetric path does not apply it says
why in the log and the full model is solved instead, never a wrong answer.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from skfem import Basis, Mesh

from fe_crank.errors import MeshError, SolverError
from fe_crank.fe.core.assembly import assemble_stiffness
from fe_crank.fe.core.determinate import DeterminateSupport, determinate_support
from fe_crank.fe.core.equilibrium import EquilibriumChecks, RefLoads
from fe_crank.fe.core.stress import elements_of_nodes
from fe_crank.fe.core.supports import (
    REF_DOFS,
    Coupling,
    Foundation,
    assemble_foundation_matrix,
    boundary_facets,
    cell_basis,
    coupling_rows,
    face_centroid,
    rigid_body_modes,
)
from fe_crank.fe.core.symmetric import SymmetricSolver, build_symmetric_solver, mesh_mirror
from fe_crank.fe.linalg.choice import choose_method
from fe_crank.fe.linalg.factorise import Factorisation, factorise

log = logging.getLogger(__name__)

EQUILIBRIUM_TOL = 1e-6


@dataclass
class System(EquilibriumChecks):
    """Assembled and factorised system; see module docstring.  Build with :func:`build_system`."""

    mesh: Mesh
    basis: Basis
    K_rows: sp.csr_matrix  # rows of the elastic stiffness at constrained dofs
    rows: np.ndarray  # those dofs (coupling slaves and held dofs)
    Ks: sp.csr_matrix  # foundations (full)
    P: sp.csr_matrix  # full <- reduced
    foundations: tuple[Foundation, ...]
    couplings: tuple[Coupling, ...]
    ref_points: dict[str, np.ndarray]
    ref_columns: dict[str, dict[str, int]]  # coupling -> ref dof name -> reduced column (free only)
    slave_dofs: dict[str, np.ndarray]  # coupling -> scalar dofs
    dirichlet_dofs: np.ndarray  # full vector dofs held at zero
    foundation_dofs: dict[str, np.ndarray]  # foundation boundary -> scalar dofs
    factorisation: Factorisation | SymmetricSolver  # SymmetricSolver: the one of ``symmetric``
    point_dofs: np.ndarray = field(default_factory=lambda: np.zeros(0, int))  # single vector dofs held
    determinate: DeterminateSupport | None = None  # reactions applied as loads (fe.core.determinate)
    timings: dict[str, float] = field(default_factory=dict)
    symmetric: SymmetricSolver | None = None  # solved on symmetry components (symmetric_system)

    @property
    def n_dof(self) -> int:
        """Number of unknowns actually solved for."""
        return self.P.shape[1]

    @property
    def points(self) -> np.ndarray:
        """Coordinates (3, N) of the P2 nodes (scalar dofs)."""
        return self.basis.doflocs

    def reduce(self, f: np.ndarray, ref_loads: RefLoads | None = None) -> np.ndarray:
        """Reduced load vector P^T f plus generalised loads at free reference dofs."""
        fr = self.P.T @ f
        for name, load in (ref_loads or {}).items():
            cols = self.ref_columns[name]
            for k, dof in enumerate(REF_DOFS):
                if load[k] != 0.0:
                    if dof not in cols:
                        raise SolverError(f"load component {dof} applied at coupling {name!r} where it is held")
                    fr[cols[dof]] += load[k]
        return fr

    def solve(self, f: np.ndarray, ref_loads: Sequence[RefLoads | None] | None = None) -> np.ndarray:
        """Full displacement vectors for load vectors f (n_full,) or (n_full, k)."""
        F = f[:, None] if f.ndim == 1 else f
        if self.determinate is not None:  # the statically determinate reactions as loads
            F = self.determinate.self_equilibrated(F)[0]
        if self.symmetric is not None:  # determinate only: no reference loads
            U = self.symmetric.solve(F)
            return U[:, 0] if f.ndim == 1 else U
        refs: Sequence[RefLoads | None] = ref_loads or [None] * F.shape[1]
        Fr = np.column_stack([self.reduce(F[:, k], refs[k]) for k in range(F.shape[1])])
        Q = self.factorisation.solve(Fr)
        U = self.P @ Q
        return U[:, 0] if f.ndim == 1 else U


def build_system(
    mesh,
    youngs_modulus: float,
    poisson_ratio: float,
    *,
    foundations=(),
    couplings=(),
    dirichlet=(),
    held_dofs=(),
    determinate=None,
    solver: str = "auto",
    intorder: int = 2,
    basis: Basis | None = None,
) -> System:
    """Assemble K (vectorised), the supports and the transformation; factorise once.

    ``held_dofs``: single vector dofs (3 node + component) held at zero.
    ``determinate``: a ``DeterminateLayout`` -- statically determinate supports
    (``fe_crank.fe.core.determinate``): ``solve`` adds to every load its reactions and the six
    point constraints (added to ``held_dofs``) remove the rigid-body modes (or a built ``DeterminateSupport``).

    Raises MeshError for a missing named boundary or a node claimed by two constraints,
    SolverError when the factorisation fails (e.g. a rigid-body mode left free).
    """
    timings = {}
    t0 = time.perf_counter()
    if basis is None:
        basis = cell_basis(mesh, intorder)
    sup = None
    if determinate is not None:
        sup = determinate if isinstance(determinate, DeterminateSupport) else determinate_support(basis, determinate)
        held_dofs = np.concatenate([np.asarray(held_dofs, dtype=int), sup.held])
    K = assemble_stiffness(basis, youngs_modulus, poisson_ratio)
    n = K.shape[0]
    N = basis.N
    Ks = sp.csr_matrix((n, n))
    fdofs = {}
    for fd in foundations:
        Ks = Ks + assemble_foundation_matrix(mesh, fd)
        fdofs[fd.boundary] = basis.get_dofs(boundary_facets(mesh, fd.boundary, "a bearing support")).all()
    timings["assembly"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    owner = np.full(N, -1)
    held = np.zeros(n, bool)
    ddofs = []
    for d in dirichlet:
        s = basis.get_dofs(boundary_facets(mesh, d.boundary, "a fixed support")).all()
        vd = (3 * s[:, None] + np.array(d.components)[None, :]).ravel()
        held[vd] = True
        ddofs.append(vd)
    point_dofs = np.unique(np.asarray(held_dofs, dtype=int))
    held[point_dofs] = True
    slave, refp = {}, {}
    for ci, c in enumerate(couplings):
        facets = boundary_facets(mesh, c.boundary, "an end-face coupling")
        s = basis.get_dofs(facets).all()
        if np.any(owner[s] >= 0) or np.any(held.reshape(-1, 3)[s]):
            raise MeshError(f"boundary {c.boundary!r}: nodes already belong to another coupling or fixed set")
        owner[s] = ci
        slave[c.boundary] = s
        refp[c.boundary] = np.asarray(c.ref_point, float) if c.ref_point is not None else face_centroid(mesh, facets)
        bad = set(c.fixed) - set(REF_DOFS)
        if bad:
            raise MeshError(f"coupling {c.boundary!r}: unknown dofs {sorted(bad)}; pick from {REF_DOFS}")
    is_slave = np.repeat(owner >= 0, 3)
    free = np.flatnonzero(~is_slave & ~held)
    p_rows = [free]  # the entries of P
    p_cols = [np.arange(free.size)]
    p_vals = [np.ones(free.size)]
    ncol = free.size
    refcols = {}
    for c in couplings:
        s = slave[c.boundary]
        T = coupling_rows(basis.doflocs[:, s] - refp[c.boundary][:, None])  # (ns, 3, 6)
        cmap = {}
        for k, dof in enumerate(REF_DOFS):
            if dof in c.fixed:
                continue
            cmap[dof] = ncol
            r = (3 * s[:, None] + np.arange(3)).ravel()
            v = T[:, :, k].ravel()
            nz = v != 0.0
            p_rows.append(r[nz])
            p_cols.append(np.full(nz.sum(), ncol))
            p_vals.append(v[nz])
            ncol += 1
        refcols[c.boundary] = cmap
    P = sp.csr_matrix((np.concatenate(p_vals), (np.concatenate(p_rows), np.concatenate(p_cols))), shape=(n, ncol))
    method = choose_method(solver, ncol)
    direct = method in ("pardiso", "pardiso_ooc", "cholmod")
    Kr = _reduced(K, Ks, P, free, direct=direct)
    rows = np.union1d(np.flatnonzero(is_slave), np.flatnonzero(held))
    K_rows = K[rows]
    del K  # the full matrix is not kept: memory for the factor
    timings["constraints"] = time.perf_counter() - t0

    near_null = None
    if method == "amg":
        B = rigid_body_modes(basis.doflocs)
        near_null = _reduce_modes(B, free, refcols, refp)
    t0 = time.perf_counter()
    fac = factorise(Kr, solver, near_nullspace=near_null, upper=direct)
    del Kr
    timings["factorisation"] = time.perf_counter() - t0
    return System(
        mesh=mesh,
        basis=basis,
        K_rows=K_rows,
        rows=rows,
        Ks=Ks.tocsr(),
        P=P,
        foundations=tuple(foundations),
        couplings=tuple(couplings),
        ref_points=refp,
        ref_columns=refcols,
        slave_dofs=slave,
        dirichlet_dofs=np.concatenate(ddofs) if ddofs else np.zeros(0, int),
        foundation_dofs=fdofs,
        factorisation=fac,
        timings=timings,
        point_dofs=point_dofs,
        determinate=sup,
    )


def _reduced(K, Ks, P, free, *, direct: bool):
    """K_r = P^T (K + K_s) P; for a direct solver its upper triangle only (all it reads),
    so that the full reduced matrix never exists next to the factor.

    Without couplings P only selects the free dofs (ascending) and K_r is the principal
    submatrix K[free, free] (+ K_s likewise), taken by indexing: the same entries as the
    sparse products (each a single term times 1.0), without their cost; explicit zeros
    are dropped as the products drop them, so the pattern, hence PARDISO's ordering and
    its factor, are the same.
    """
    if P.shape[1] == free.size:  # no coupling columns: P is the selection of ``free``
        A = K if Ks.nnz == 0 else K + Ks
        if direct:
            A = sp.triu(A, format="csr")  # the triangle of a principal submatrix is the submatrix of the triangle
        Kr = A[free][:, free].tocsr()
    else:
        # Both products in CSR: ``P.T`` is CSC, and CSC @ CSR would first convert all of
        # K + K_s to CSC.  Each entry is the same sum in the same order (ascending inner
        # index, with P^T's and the intermediate's indices sorted) as the CSC products.
        PT = P.T.tocsr()
        PT.sort_indices()
        M = PT @ (K + Ks)
        M.sort_indices()
        Kr = (M @ P).tocsr()
        del M
        if direct:
            Kr = sp.triu(Kr, format="csr")
    Kr.eliminate_zeros()
    Kr.sort_indices()
    return Kr


def _reduce_modes(B, free, refcols, refp) -> np.ndarray:
    """Rigid-body modes in reduced coordinates: free nodal rows, and (u0, theta) at references."""
    Br = np.zeros((free.size + sum(len(c) for c in refcols.values()), 6))
    Br[: free.size] = B[free]
    for name, cmap in refcols.items():
        at_ref = rigid_body_modes(refp[name][:, None])  # (3, 6): u0 of each mode
        for dof, col in cmap.items():
            k = REF_DOFS.index(dof)
            if k < 3:
                Br[col] = at_ref[k]
            else:
                Br[col, k] = 1.0
    return Br


# -- the determinate throw on symmetry components (module docstring) --


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
    basis = cell_basis(mesh, intorder)  # the whole mesh's P2 basis, built once (fe.core.bases)
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
