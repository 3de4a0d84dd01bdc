"""Mirror symmetry of a P2 mesh and the determinate throw solved on its symmetry components.

**The reflection group.**  A reflection across the plane x_a = 0 (``a`` = 0 for x = 0,
2 for z = 0) acts on an interleaved nodal vector as (R v)[3 p(i) + c] = s_c v[3 i + c], with p the node
permutation (node i's mirror image is node p(i)) and s_c = -1 for c = a, +1 otherwise.
R is orthogonal and an involution.  On a mesh that maps onto itself under R (and one
homogeneous material) the stiffness commutes with it, K R = R K, so with k planes the
space of nodal vectors splits into 2^k invariant components, one per character
e = (e_a) in {+1, -1}^k (R_a v = e_a v for every plane):

    v_e = 2^-k sum_g chi_e(g) (g v),  summed over the 2^k products g of the reflections,
    chi_e(g) = prod of e_a over the reflections in g,

and K u = f splits into K u_e = f_e (Zienkiewicz & Taylor, The Finite Element Method,
vol. 1, the section on symmetry and repeatability; the projection is that of the group
representation theory of the reflections).  Each component is solved on the
fundamental part of the mesh (below).

**The solve on the components.**  With k verified mirror planes (``mesh_mirror``) the
self-equilibrated load f (the determinate reactions applied as loads, ``DeterminateSupport.self_equilibrated``)
splits into 2^k components f_e.  Each is solved on the fundamental part Q (the elements
whose centroid has x_a > 0 for every plane a; the other parts are its images), with the
displacement restricted to the component by the plane conditions: for a node on plane a,
u_a = 0 where the component is symmetric about it (e_a = +1) and the two in-plane
components are zero where it is antisymmetric (e_a = -1).  With T the expansion of the
part's unknowns q to the full vector (u = sum_g chi_e(g) g q), K = sum_g g K_Q g and
T^T f = 2^k (f_e at Q's nodes with a node on m planes weighted by 2^-m), so the
Galerkin equations T^T K T q = T^T f are

    K_Q q = W f_e,   W = diag(2^-m_i)  (a node on one plane carries half its load, on two a quarter)

-- the full model's energy is 2^k times the part's.  The component's share of the six
rigid-body modes (a translation along the plane's normal and the two rotations about
in-plane axes are antisymmetric about it, the rest symmetric) is left free by the plane
conditions; f_e is orthogonal to it (f is self-equilibrated and the projection is
orthogonal), so it is removed by holding as many single dofs of the part (picked by
pivoted QR, as ``determinate.point_constraints``), which then carry round-off only.
The components are summed, u = sum_e T_e q_e, and the rigid motion that makes the full
model's six held point dofs zero is taken off: u then equals the full model's solution,
not only its stresses.

Every component matrix keeps the pattern of the part's stiffness (all 3 n_Q dofs: the
constrained ones become rows with a unit diagonal and explicit-zero couplings), so one
MKL PARDISO handle holds all their factors (``maxfct`` = 2^k): the analysis (phase 11,
the METIS reordering and the symbolic factorisation) runs once and each component only
needs its numerical factorisation (phase 22) (``fe.linalg.factorise.factorise_shared``).

A component is factorised when a load first has a part in it (``ComponentFactors``).
Loads symmetric about every plane (the centrifugal load of a mirrored throw) have no part
in the other components but round-off (about 1e-15 of the load: the assembly sums in
another order on the mirror images): those components are then left out (``ROUND_OFF``;
their solution would be round-off of the displacement) and only the symmetric one is
factorised.  Otherwise every component with a part that is not exactly zero is solved for
all the loads, round-off and all.  The PARDISO analysis runs with the first factorisation, on the first
component's matrix whichever component that is, so every factor is the one an eager
factorisation of all components gives.

The System of a throw built on these components: ``fe.core.system.symmetric_system``.
"""

from __future__ import annotations

import itertools
import logging
import time
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
from scipy.spatial import cKDTree

from fe_crank.errors import SolverError
from fe_crank.fe.core.assembly import part_stiffness, upper_triangle
from fe_crank.fe.core.supports import rigid_body_modes
from fe_crank.fe.linalg.choice import DESCRIPTIONS, choose_method
from fe_crank.fe.linalg.factorise import Factorisation, SharedAnalysis, factorise, pardiso_solver, shared_member

log = logging.getLogger(__name__)

#: coordinates closer than this fraction of the model size are the same point (round-off)
MATCH_TOL = 1e-10
AXIS_NAMES = {0: "x", 1: "y", 2: "z"}


@dataclass(frozen=True)
class Mirror:
    """The verified reflections of a mesh.  ``perm[a]`` (N,): node image under plane a."""

    axes: tuple[int, ...]
    perm: dict[int, np.ndarray]
    on_plane: dict[int, np.ndarray]  # (N,) bool: node on plane a (its own image)

    @property
    def group(self) -> list[tuple[tuple[int, ...], np.ndarray, np.ndarray]]:
        """Every product g of the reflections: (the planes in it, node permutation, signs (3,))."""
        out = []
        n = next(iter(self.perm.values())).size
        for k in range(len(self.axes) + 1):
            for sub in itertools.combinations(self.axes, k):
                p = np.arange(n)
                s = np.ones(3)
                for a in sub:
                    p = self.perm[a][p]
                    s[a] = -s[a]
                out.append((sub, p, s))
        return out

    @property
    def characters(self) -> list[dict[int, int]]:
        """The 2^k components, e.g. {0: +1, 2: -1}: symmetric about x = 0, antisymmetric about z = 0."""
        return [dict(zip(self.axes, e)) for e in itertools.product((1, -1), repeat=len(self.axes))]

    def describe(self) -> str:
        return " and ".join(f"{AXIS_NAMES[a]} = 0" for a in self.axes)


def character_of(chars: dict[int, int], planes: tuple[int, ...]) -> int:
    """chi_e(g) for g the product of the reflections ``planes``."""
    return int(np.prod([chars[a] for a in planes])) if planes else 1


def reflect(v: np.ndarray, perm: np.ndarray, signs: np.ndarray) -> np.ndarray:
    """g v for interleaved nodal vector(s) v (3 N,) or (3 N, k)."""
    V = v.reshape(perm.size, 3, -1)
    out = np.empty_like(V)
    out[perm] = V * signs[None, :, None]
    return out.reshape(v.shape)


def component(v: np.ndarray, mirror: Mirror, chars: dict[int, int]) -> np.ndarray:
    """v_e = 2^-k sum_g chi_e(g) (g v) (module doc)."""
    out = np.zeros_like(v)
    for planes, p, s in mirror.group:
        out += character_of(chars, planes) * reflect(v, p, s)
    return out / 2 ** len(mirror.axes)


def verify_mirror(points: np.ndarray, element_nodes: np.ndarray, axes) -> tuple[Mirror | None, str]:
    """Check that the nodes ``points`` (3, N) and elements (all their P2 nodes, (10, ne): the
    image of an element's edge node must be the edge node of its image) map onto themselves
    across each plane x_a = 0 of ``axes``; returns (Mirror, "") or (None, the reason it does not).

    Nodes are matched by coordinates to ``MATCH_TOL`` of the model size (a k-d tree); the
    map must be a permutation, fix exactly the nodes on the plane, and take the set of
    elements onto itself; no element may be its own image (it would straddle the plane,
    and the mesh would not split into mirror halves).
    """
    axes = tuple(sorted({int(a) for a in axes}))
    if not axes:
        return None, "the mesh states no mirror plane"
    bad = [a for a in axes if a not in (0, 1, 2)]
    if bad:
        return None, f"unknown mirror axes {bad}"
    x = np.asarray(points, float)
    N = x.shape[1]
    scale = float(np.ptp(x, axis=1).max()) or 1.0
    tol = MATCH_TOL * scale
    tree = cKDTree(x.T)
    el = np.sort(np.asarray(element_nodes), axis=0)
    keys = _element_keys(el, N)
    perm, on = {}, {}
    for a in axes:
        y = x.copy()
        y[a] = -y[a]
        d, idx = tree.query(y.T, distance_upper_bound=tol)
        name = f"{AXIS_NAMES[a]} = 0"
        if np.any(~np.isfinite(d)):
            return None, (
                f"{np.count_nonzero(~np.isfinite(d))} of {N} nodes have no mirror image across "
                f"{name} within {MATCH_TOL:g} of the model size"
            )
        if np.any(idx[idx] != np.arange(N)):
            return None, f"the node map across {name} is not an involution (coincident nodes?)"
        fixed = idx == np.arange(N)
        if np.any(fixed != (np.abs(x[a]) <= tol)):
            return None, f"nodes off the plane {name} map onto themselves (coincident nodes?)"
        mapped = _element_keys(np.sort(idx[el], axis=0), N)
        if not np.array_equal(np.sort(mapped), np.sort(keys)):
            return None, f"the elements do not map onto elements across {name}"
        if np.any(mapped == keys):
            return None, f"elements straddle the plane {name} (their own mirror images)"
        perm[a], on[a] = idx, fixed
    return Mirror(axes=axes, perm=perm, on_plane=on), ""


def _element_keys(el: np.ndarray, N: int) -> np.ndarray:
    """One key per element from its sorted nodes (m, ne): the m node numbers as bytes (exact)."""
    words = np.ascontiguousarray(el.T.astype(np.int64))
    return words.view(np.dtype((np.void, 8 * el.shape[0]))).ravel()


def mesh_mirror(mesh, basis, axes) -> Mirror | None:
    """The verified mirror of ``basis`` (its P2 nodes) across ``axes``, or None (logged why)."""
    if not axes:
        return None
    mirror, why = verify_mirror(basis.doflocs, basis.element_dofs, axes)
    if mirror is None:
        log.warning(
            "fe-crank: the mesh was meant to be mirror-symmetric (%s) but is not: %s; solving the full model",
            ", ".join(f"{AXIS_NAMES.get(a, a)} = 0" for a in axes),
            why,
        )
    return mirror


#: direct methods the components are solved with (AMG-CG and out-of-core PARDISO: full model)
METHODS = ("pardiso", "cholmod", "superlu")
#: one PARDISO analysis for every component (module doc); False: each its own (for comparison)
SHARE_ORDERING = True
#: the parts of the loads outside the symmetric component no larger than this fraction of
#: each load's largest entry are the round-off of loads symmetric about every plane: only
#: the symmetric component is then factorised and solved (module doc)
ROUND_OFF = 1e-12


def mode_characters(axes) -> np.ndarray:
    """(6, k) character of each rigid-body mode (tx, ty, tz, rx, ry, rz) under each reflection:
    translation along the plane's normal -1, in-plane +1; rotation about the normal +1,
    about an in-plane axis -1 (a rotation vector is axial: it flips where a polar one does not)."""
    out = np.ones((6, len(axes)), int)
    for j, a in enumerate(axes):
        for m in range(3):
            out[m, j] = -1 if m == a else 1
            out[3 + m, j] = 1 if m == a else -1
    return out


class ComponentFactors:
    """The component matrices (upper triangles of one pattern), each factorised when first
    asked for: on one PARDISO handle (``share``: one analysis, on the first matrix) or
    each on its own (``fe.linalg.factorise.factorise``)."""

    def __init__(self, matrices: list[sp.csr_matrix], method: str, share: bool):
        self.matrices: list[sp.csr_matrix | None] = list(matrices)
        self.method, self.share = method, share
        self.factors: list[Factorisation | None] = [None] * len(matrices)
        self.sizes = [int(2 * A.nnz - A.shape[0]) for A in matrices]  # full symmetric non-zeros
        self.shared: SharedAnalysis | None = None
        self.seconds = 0.0  # analysis and numerical factorisations so far
        self.analysis_time = 0.0

    def done(self, i: int) -> bool:
        return self.factors[i] is not None

    def get(self, i: int) -> Factorisation:
        """Component ``i``'s factorisation, made now if it was not yet."""
        fac = self.factors[i]
        if fac is not None:
            return fac
        A = self.matrices[i]
        if A is None:
            raise SolverError(
                f"{self.method}: the factorisation was released (Factorisation.free); factorise again to solve"
            )
        t0 = time.perf_counter()
        if self.method == "pardiso" and self.share:
            from pypardiso.pardiso_wrapper import PyPardisoError

            try:
                if self.shared is None:
                    first = self.matrices[0]
                    assert first is not None  # released only all together
                    self.shared = SharedAnalysis(pardiso_solver(), first, len(self.matrices))
                    self.analysis_time = self.shared.analysis_time
                fac = shared_member(self.shared, i, A)
            except PyPardisoError as exc:
                raise SolverError(f"PARDISO factorisation of a symmetry component failed: {exc}") from exc
        else:
            if self.method == "superlu":  # SuperLU needs the whole matrix
                A = (A + A.T - sp.diags(A.diagonal())).tocsr()
            fac = factorise(A, self.method, upper=self.method != "superlu")
        self.seconds += time.perf_counter() - t0
        self.factors[i] = fac
        return fac

    def nnz(self, i: int) -> int:
        """Stored non-zeros of component ``i``'s full symmetric matrix."""
        fac = self.factors[i]
        return self.sizes[i] if fac is None else fac.nnz

    def free(self) -> None:
        """Release the factorisations made and the matrices; ``get`` raises afterwards."""
        for fac in self.factors:
            if fac is not None:
                fac.free()
        self.matrices = [None] * len(self.matrices)


@dataclass
class Component:
    chars: dict[int, int]
    constrained: np.ndarray  # (3 n_Q,) bool: plane conditions and held dofs
    held: np.ndarray  # local dofs held against the component's rigid modes
    factors: ComponentFactors = field(repr=False)
    index: int = 0

    @property
    def factor(self) -> Factorisation:
        """The component's factorisation (made when first asked for: ``ComponentFactors``)."""
        return self.factors.get(self.index)


@dataclass
class SymmetricSolver:
    """The component factorisations of one part; the face of ``Factorisation`` that the rest
    of the package reads (``method``, ``description``, ``nnz``, ``free``, ``setup_time``)."""

    mirror: Mirror
    nodes: np.ndarray  # (n_Q,) full node numbers of the part
    weights: np.ndarray  # (n_Q,) 2^-m, m = planes the node lies on
    components: list[Component]
    factors: ComponentFactors
    points: np.ndarray  # (3, N) all nodes
    held_full: np.ndarray  # (6,) the full model's point dofs
    method: str
    setup_time: float = 0.0
    note: str | None = None
    timings: dict[str, float] = field(default_factory=dict)
    released: bool = False

    @property
    def description(self) -> str:
        k = len(self.mirror.axes)
        d = DESCRIPTIONS.get(self.method, self.method)
        part = "half" if k == 1 else "quarter"
        s = (
            f"{d}; solved on {2**k} symmetry components of the {part} of the mesh (mirror plane{'s' if k > 1 else ''} "
            f"{self.mirror.describe()}, {3 * self.nodes.size} dofs each)"
        )
        return s if not self.note else f"{s} ({self.note})"

    @property
    def analysis_time(self) -> float:
        """PARDISO's analysis (phase 11), s; 0 before the first component is factorised."""
        return self.factors.analysis_time

    @property
    def nnz(self) -> int:
        return int(sum(self.factors.nnz(i) for i in range(len(self.components))))

    @property
    def factorised(self) -> int:
        """How many components have been factorised so far (loads with a part in them)."""
        return sum(self.factors.done(i) for i in range(len(self.components)))

    def free(self) -> None:
        """Release every component's factorisation (``Factorisation.free``); ``solve``
        raises ``SolverError`` afterwards."""
        self.factors.free()
        self.released = True

    def solve(self, F: np.ndarray) -> np.ndarray:
        """Full displacements (3 N, k) of self-equilibrated full loads F (3 N, k)."""
        if self.released:
            raise SolverError(
                f"{self.method}: the factorisation was released (Factorisation.free); factorise again to solve"
            )
        N = self.points.shape[1]
        k = F.shape[1]
        Fn = F.reshape(N, 3, k)
        Un = np.zeros((N, 3, k))
        group = self.mirror.group
        rhs = []  # (component, f_e at the part's nodes (3 n_Q, k))
        for comp in self.components:
            bn = np.zeros((self.nodes.size, 3, k))
            for planes, p, s in group:  # f_e at the part's nodes: 2^-k sum_g chi(g) (g f)
                bn += character_of(comp.chars, planes) * s[None, :, None] * Fn[p[self.nodes]]
            bn *= self.weights[:, None, None] / len(group)
            b = bn.reshape(-1, k)
            b[comp.constrained] = 0.0
            rhs.append((comp, b))
        for comp, b in _loaded(rhs, F):
            q = comp.factor.solve(b).reshape(self.nodes.size, 3, k)
            for planes, p, s in group:  # u_e = sum_g chi(g) g q, each image once
                Un[p[self.nodes]] += (
                    (character_of(comp.chars, planes) * self.weights)[:, None, None] * s[None, :, None] * q
                )
        U = Un.reshape(3 * N, k)
        _remove_rigid_fit(self.points, self.held_full, U)
        return U


def _loaded(rhs: list[tuple[Component, np.ndarray]], F: np.ndarray) -> list[tuple[Component, np.ndarray]]:
    """The components to solve of ``rhs`` (each component with its part of the loads F):
    the symmetric one alone when every other one's part is round-off (``ROUND_OFF`` of
    each load's largest entry: loads symmetric about every plane), else every component
    with a part that is not exactly zero."""
    scale = np.abs(F).max(axis=0) if F.size else np.zeros(F.shape[1])
    sym = [i for i, (c, _) in enumerate(rhs) if all(e == 1 for e in c.chars.values())]
    rest = [b for i, (_, b) in enumerate(rhs) if i not in sym]
    if sym and all(not np.any(np.abs(b).max(axis=0) > ROUND_OFF * scale) for b in rest if b.size):
        return [rhs[i] for i in sym if rhs[i][1].any()]
    return [(c, b) for c, b in rhs if b.any()]


#: nodes per block of the rigid-motion removal (a block's temporaries stay in cache)
RIGID_BLOCK = 8192


def _rigid_coefficients(x: np.ndarray, held: np.ndarray, U: np.ndarray) -> np.ndarray:
    """a (6, k): (u0, theta) of the rigid motion B a that equals U at the six held dofs."""
    nodes = held // 3
    Bh = rigid_body_modes(x[:, nodes]).reshape(len(held), 3, 6)[np.arange(len(held)), held % 3]
    return np.linalg.solve(Bh, U[held])


def _remove_rigid_fit(x: np.ndarray, held: np.ndarray, U: np.ndarray) -> None:
    """U -= B a in place, the rigid motion with (B a)[held] = U[held] (six held dofs):
    (0 + u0) + theta x x at every node, ``RIGID_BLOCK`` nodes at a time (no whole-size
    temporaries)."""
    a = _rigid_coefficients(x, held, U)
    N, k = x.shape[1], U.shape[1]
    Un3 = U.reshape(N, 3, k)
    theta = a[3:].T[:, None, :]
    for start in range(0, N, RIGID_BLOCK):
        sl = slice(start, min(start + RIGID_BLOCK, N))
        r = np.zeros((sl.stop - sl.start, 3, k))
        r += a[None, :3, :]
        r += np.cross(theta, x.T[None, sl, :]).transpose(1, 2, 0)
        Un3[sl] -= r


def pick_held(x: np.ndarray, free: np.ndarray, modes: list[int]) -> np.ndarray:
    """Local dofs (of the part's nodes x (3, n)) that remove the rigid modes ``modes``: the
    first pivots of a QR with column pivoting of the modes restricted to the free dofs."""
    if not modes:
        return np.zeros(0, int)
    B = rigid_body_modes(x)
    B[:, 3:] /= np.ptp(x, axis=1).max()  # rotations in length units
    B = B[:, modes]
    rows = np.flatnonzero(free)
    _, R, piv = sla.qr(B[rows].T, pivoting=True, mode="economic")
    r = len(modes)
    if abs(R[r - 1, r - 1]) < 1e-6 * abs(R[0, 0]):
        raise SolverError("cannot hold the rigid-body modes of a symmetry component (degenerate part?)")
    return rows[piv[:r]]


def build_symmetric_solver(
    basis,
    mirror: Mirror,
    youngs_modulus: float,
    poisson_ratio: float,
    held_full: np.ndarray,
    solver: str = "auto",
    *,
    share_ordering: bool | None = None,
) -> SymmetricSolver | None:
    """Assemble the part's stiffness once and factorise each component (module doc).

    Returns None (logged) when the method is not a direct one this path supports.
    """
    n_full = 3 * basis.N
    method = choose_method(solver, n_full)
    if method not in METHODS:
        log.info("fe-crank: the %s solver runs on the full model (symmetry components need a direct solver)", method)
        return None
    timings: dict[str, float] = {}
    t0 = time.perf_counter()
    x = basis.doflocs
    el = basis.element_dofs
    centroid = x[:, el[:4]].mean(axis=1)  # (3, ne)
    part = np.flatnonzero(np.all([centroid[a] > 0 for a in mirror.axes], axis=0))
    if part.size * 2 ** len(mirror.axes) != el.shape[1]:
        log.warning("fe-crank: the mirror halves do not partition the elements; solving the full model")
        return None
    nodes = np.unique(el[:, part])
    m = np.zeros(nodes.size, int)
    for a in mirror.axes:
        m += mirror.on_plane[a][nodes]
    weights = 0.5**m
    # the part's stiffness in its own numbering, from the whole basis's gradients (no basis
    # of its own, no whole-size matrix): the matrix K[ldofs][:, ldofs] of the part's elements
    K = part_stiffness(basis, part, nodes, youngs_modulus, poisson_ratio)
    Kq = upper_triangle(K)
    del K
    Kq.sort_indices()
    timings["assembly"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    mchars = mode_characters(mirror.axes)
    row_len = np.diff(Kq.indptr)
    spaces = []  # (characters, constrained dofs, held dofs) of each component
    for chars in mirror.characters:
        allowed = np.ones((nodes.size, 3), bool)
        for a, e in chars.items():
            on = mirror.on_plane[a][nodes]
            for c in range(3):
                if (c == a) != (e == -1):  # sign of component c under R_a != e_a
                    allowed[on, c] = False
        modes = [j for j in range(6) if all(mchars[j, i] == chars[a] for i, a in enumerate(mirror.axes))]
        held = pick_held(x[:, nodes], allowed.ravel(), modes)
        cons = ~allowed.ravel()
        cons[held] = True
        spaces.append((chars, cons, held))
    timings["constraints"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    share = SHARE_ORDERING if share_ordering is None else share_ordering
    matrices = []
    for i, (_, cons, _) in enumerate(spaces):
        A = Kq if i == len(spaces) - 1 else Kq.copy()  # the last one takes the part's own
        cut = np.repeat(cons, row_len) | cons[A.indices]  # row or column held
        A.data[cut] = 0.0  # explicit zeros: the pattern stays
        diag = A.indptr[:-1]  # upper triangle, sorted: diagonal first
        if not np.array_equal(A.indices[diag], np.arange(A.shape[0])):
            raise SolverError("the part's stiffness lacks a diagonal entry")
        A.data[diag[cons]] = 1.0
        matrices.append(A)
    del Kq
    factors = ComponentFactors(matrices, method, share)
    comps = [Component(chars, cons, held, factors, i) for i, (chars, cons, held) in enumerate(spaces)]
    timings["factorisation"] = time.perf_counter() - t0  # the matrices; each factor when first needed
    return SymmetricSolver(
        mirror=mirror,
        nodes=nodes,
        weights=weights,
        components=comps,
        factors=factors,
        points=x,
        held_full=np.asarray(held_full, int),
        method=method,
        setup_time=timings["factorisation"],
        timings=timings,
    )
