"""The bases of one mesh: a robust curved mapping, one dof numbering, cell and facet bases.

* :class:`RobustIsoparametric` -- scikit-fem's isoparametric mapping with a Newton
  inverse started from the straight-sided element, and memos that let a basis compute
  its inverse Jacobian and its facet inverse once;
* :func:`mesh_dofs` -- the P2 dof numbering of a mesh, built once (with the mesh's edge
  and facet tables made by integer keys, :func:`prime_edge_tables`);
* :func:`cell_basis`, :func:`facet_basis` -- the scalar P2 basis of the whole mesh and a
  basis on a set of facets, both on that mapping and numbering.

A mesh's mapping and dof numberings are kept in :class:`MeshCache` tables beside the mesh,
not on it.  The tables hold their entries weakly: an entry lives as long as a basis (or
anyone else) holds it.  Each entry holds its mesh (scikit-fem's mappings and ``Dofs`` keep
the mesh they were built on), so a table keyed weakly by the mesh would keep every mesh
alive; and scikit-fem's meshes, dataclasses compared by value, cannot be dictionary keys.
The tables are therefore keyed by the mesh's identity, which cannot be reused while an
entry (holding the mesh) is alive.

Every number is bit for bit that of the basis scikit-fem builds from scratch on the same
mapping (tests/fe/test_fe_mapping.py).
"""

from __future__ import annotations

import weakref
from typing import Generic, TypeVar

import numpy as np
from skfem import CellBasis, ElementTetP2, FacetBasis, Mesh
from skfem.assembly import Dofs
from skfem.mapping import MappingIsoparametric

from fe_crank.errors import MeshError
from fe_crank.fe.core.assembly import unique_inverse


class InverseMapError(Exception):
    """The reference coordinates of a point could not be found (degenerate or folded element)."""


class RobustIsoparametric(MappingIsoparametric):
    """``invF`` by Newton's method from the affine (vertex) inverse, without clipping.

    scikit-fem's own inverse starts every point at (1/2, 1/2, 1/2), outside the
    reference tetrahedron, and clips each iterate to the unit cube; on curved
    elements an iterate can stick at a cube corner (seen on the inline-4 journal:
    a good element, Jacobian ratio 0.69, residual 18 mm after 50 iterations).
    Started from the inverse of the straight-sided element the iteration is within
    the sagitta of the answer and converges quadratically.

    Two memos make a basis cheaper without changing a bit of it: ``invDF`` keeps its
    last result (a basis asks for the same inverse Jacobian once per shape function,
    ten times for P2), and ``invF`` keeps its last answer (a ``FacetBasis`` inverts the
    same points twice, for the basis and for the normals, with equal element lists on
    boundary facets).  Both compare their arguments by identity (the arrays are held,
    so an identity cannot be reused) and the element lists by value; ``clear_memo``
    drops them, and the Jacobian cache of the parent class, once a basis is built.
    """

    def __init__(self, mesh, elem, bndelem=None) -> None:
        super().__init__(mesh, elem, bndelem)
        self._facet_nodes_cache: np.ndarray | None = None
        self.clear_memo()

    def clear_memo(self) -> None:
        # (argument, element list, result) of the last call; None: nothing kept
        self._invdf_memo: tuple[np.ndarray, np.ndarray | None, np.ndarray] | None = None
        self._invf_memo: tuple[np.ndarray, np.ndarray | None, np.ndarray] | None = None
        self._cache: dict[int, np.ndarray] = {}  # the parent's Jacobians, by a hash of (i, j, X, tind)

    @staticmethod
    def _same(a, b) -> bool:
        if a is None or b is None:
            return a is b
        return a is b or (a.shape == b.shape and np.array_equal(a, b))

    def invDF(self, X, tind=None):
        memo = self._invdf_memo
        if memo is not None and memo[0] is X and self._same(memo[1], tind):
            return memo[2]
        out = super().invDF(X, tind)
        self._invdf_memo = (X, tind, out)
        return out

    def invF(self, x, tind=None, newton_max_iters=50, newton_tol=1e-12):
        memo = self._invf_memo
        if memo is not None and memo[0] is x and self._same(memo[1], tind):
            return memo[2]
        X = self._newton_inverse(x, tind, newton_max_iters, newton_tol)
        self._invf_memo = (x, tind, X)
        return X

    def _newton_inverse(self, x, tind, newton_max_iters, newton_tol):
        mesh_ = self.mesh
        t = mesh_.t[:4] if tind is None else mesh_.t[:4, tind]
        P = mesh_.p[:, t]  # (3, 4, ne)
        A = np.stack([P[:, 1] - P[:, 0], P[:, 2] - P[:, 0], P[:, 3] - P[:, 0]], axis=1)  # (3, 3, ne)
        try:
            Ainv = np.linalg.inv(A.transpose(2, 0, 1))  # (ne, 3, 3)
        except np.linalg.LinAlgError:
            raise InverseMapError("a degenerate element (vertices in one plane)") from None
        X = np.einsum("eij,jeq->ieq", Ainv, x - P[:, 0][:, :, None])
        h = np.linalg.norm(A, axis=0).max(axis=0)  # (ne,) longest edge from vertex 0
        for _ in range(newton_max_iters):
            r = x - self.F(X, tind)
            dX = np.einsum("ijeq,jeq->ieq", self.invDF(X, tind), r)
            X = X + dX
            if np.abs(dX).max() < newton_tol:
                break
        with np.errstate(invalid="ignore", divide="ignore"):
            r = np.abs(x - self.F(X, tind)).max(axis=(0, 2)) / h
        if not np.all(r < 1e-9):
            raise InverseMapError(f"Newton's method did not converge (relative residual {np.nanmax(r):.1e})")
        return X

    def _facet_nodes(self):
        """Global nodes of every facet (6, n_facets), vertices then edge nodes: what the
        parent's ``bndmap``/``bndJ`` stack on every call, stacked once here."""
        fn = self._facet_nodes_cache
        if fn is None:
            m = self.mesh
            prime_edge_tables(m)
            fn = np.vstack((m.facets, m.dofs.edge_dofs[0, m.f2e]))
            self._facet_nodes_cache = fn
        return fn

    def bndmap(self, i, X, find=None):
        if len(self.mesh.dofs.facet_dofs) > 0 or len(self.mesh.dofs.edge_dofs) == 0:
            return super().bndmap(i, X, find)
        p = self.mesh.doflocs
        facets = self._facet_nodes()
        out = np.zeros((facets.shape[1] if find is None else len(find), X.shape[-1]))
        for itr in range(facets.shape[0]):
            phi, _ = self.bndelem.lbasis(X, itr)
            out += p[i, facets[itr, :] if find is None else facets[itr, find]][:, None] * phi
        return out

    def bndJ(self, i, j, X, find=None):
        if len(self.mesh.dofs.facet_dofs) > 0 or len(self.mesh.dofs.edge_dofs) == 0:
            return super().bndJ(i, j, X, find)
        p = self.mesh.doflocs
        facets = self._facet_nodes()
        out = np.zeros((facets.shape[1] if find is None else len(find), X.shape[-1]))
        for itr in range(facets.shape[0]):
            _, dphi = self.bndelem.lbasis(X, itr)
            out += p[i, facets[itr, :] if find is None else facets[itr, find]][:, None] * dphi[j]
        return out


_V = TypeVar("_V")


class MeshCache(Generic[_V]):
    """Values computed from a mesh, by the mesh's identity and a key, held weakly (module
    docstring): ``get`` returns the value while someone holds it, else builds it again."""

    def __init__(self) -> None:
        self._values: weakref.WeakValueDictionary[tuple[int, object], _V] = weakref.WeakValueDictionary()

    def get(self, mesh: Mesh, key: object, build) -> _V:
        """The value of ``(mesh, key)``; ``build()`` makes it when none is held."""
        value = self._values.get((id(mesh), key))
        if value is None:
            value = build()
            self._values[(id(mesh), key)] = value
        return value


#: the robust mapping of each curved mesh, and each mesh's dof numbering by element type
_MAPPINGS: MeshCache[RobustIsoparametric] = MeshCache()
_DOFS: MeshCache[Dofs] = MeshCache()


def robust_mapping(mesh: Mesh) -> RobustIsoparametric | None:
    """The mesh's isoparametric mapping with a robust inverse (one per mesh while it is
    held, :class:`MeshCache`), or None if affine."""
    if mesh.affine:
        return None
    return _MAPPINGS.get(mesh, None, lambda: RobustIsoparametric(mesh, mesh.elem(), mesh.bndelem))


def _entity_table(rows: np.ndarray, tuples) -> tuple[np.ndarray, np.ndarray]:
    """scikit-fem's ``Mesh.build_entities(rows, tuples)`` (sorted): the distinct vertex
    tuples (k, n), each sorted and in lexicographic order, and the map (len(tuples),
    n_rows) into them, from one integer key per tuple (sum_i v_i nv^(k-1-i), whose
    order is the lexicographic one) instead of ``np.unique(axis=1)``."""
    indexing = np.hstack([rows[list(ix)] for ix in tuples])
    s = np.sort(indexing, axis=0)
    k = s.shape[0]
    nv = int(s.max()) + 1 if s.size else 1
    key = np.zeros(s.shape[1], dtype=np.int64)
    for r in range(k):
        key = key * nv + s[r]
    uniq, inv = unique_inverse(key, nv**k)
    out = np.empty((k, uniq.size), dtype=indexing.dtype)
    for r in range(k - 1, -1, -1):
        uniq, out[r] = np.divmod(uniq, nv)
    return np.ascontiguousarray(out), inv.reshape(len(tuples), rows.shape[1])


def prime_edge_tables(mesh) -> None:
    """Fill a tetrahedral mesh's lazily built ``facets``/``t2f``, ``edges``/``t2e`` and
    ``f2e`` (the numbering of the P2 edge nodes and of the facets' edges) with
    :func:`_entity_table`: the same arrays scikit-fem builds (tested), at a fraction of
    the cost of its ``np.unique(axis=1)``.  Meshes whose vertex numbers do not fit the
    integer keys (more than 2^21 vertices) keep scikit-fem's own build."""
    if mesh.t.shape[0] != 4 or int(mesh.t.max()) >= 2**21:
        return
    if not hasattr(mesh, "_facets"):
        mesh._facets, mesh._t2f = _entity_table(mesh.t, mesh.elem.refdom.facets)
    if not hasattr(mesh, "_edges"):
        mesh._edges, mesh._t2e = _entity_table(mesh.t, mesh.elem.refdom.edges)
    if not hasattr(mesh, "_f2e"):
        mesh._f2e = _entity_table(mesh.facets, mesh.bndelem.refdom.facets)[1]


def mesh_dofs(mesh: Mesh, elem) -> Dofs:
    """The global numbering of ``elem`` on ``mesh``, one per mesh and element type while it
    is held (:class:`MeshCache`).

    ``Dofs(mesh, elem)`` is deterministic; every basis of the mesh built through
    :func:`cell_basis` and :func:`facet_basis` shares this one (scikit-fem would rebuild
    it, and the whole mesh's dof locations, for each facet basis).
    """

    def build() -> Dofs:
        prime_edge_tables(mesh)
        return Dofs(mesh, elem)

    return _DOFS.get(mesh, (type(elem), type(getattr(elem, "elem", None))), build)


def cell_basis(mesh, intorder: int = 2, elem=None) -> CellBasis:
    """The scalar P2 ``Basis`` of the whole mesh (the stiffness's and the body loads').

    The same numbers as ``Basis(mesh, ElementTetP2(), intorder=intorder)``: on a curved
    mesh it uses the mesh's :class:`RobustIsoparametric` mapping, whose ``invDF`` memo
    computes the inverse Jacobian once instead of once per shape function, and the dof
    numbering of :func:`mesh_dofs`.
    """
    elem = ElementTetP2() if elem is None else elem
    mapping = robust_mapping(mesh)
    basis = CellBasis(mesh, elem, mapping=mapping, intorder=intorder, dofs=mesh_dofs(mesh, elem))
    if mapping is not None:
        mapping.clear_memo()
    return basis


def facet_basis(mesh, elem, facets, intorder: int, what: str) -> FacetBasis:
    """``FacetBasis`` on ``facets`` of a (possibly curved) mesh; a failed inverse map is a MeshError.

    On a curved (isoparametric) mesh the reference coordinates of the facet quadrature
    points come from a Newton iteration (see ``robust_mapping``), which can only fail on
    folded or nearly degenerate elements: a property of the mesh, reported as such.
    The dof numbering is the mesh's shared one (:func:`mesh_dofs`) and the global dof
    locations are not computed (the cell basis has them): the cost is that of the facets.
    """
    mapping = robust_mapping(mesh)
    try:
        return FacetBasis(
            mesh,
            elem,
            mapping=mapping,
            facets=facets,
            intorder=intorder,
            dofs=mesh_dofs(mesh, elem),
            disable_doflocs=True,
        )
    except (InverseMapError, np.linalg.LinAlgError) as exc:
        raise MeshError(
            f"{what}: the curved elements under the surface are too distorted to map its "
            f"quadrature points ({exc}); remesh with a finer or better-shaped mesh"
        ) from None
    finally:
        if mapping is not None:
            mapping.clear_memo()
