"""gmsh's global state in a context manager, and gmsh models to scikit-fem meshes.

gmsh keeps one global model per process; :func:`gmsh_session` initialises it on
enter and finalises it on exit, also when an exception escapes, so a failed build
never leaks state into the next one.  :func:`model_to_skfem` turns the current
model's second-order tetrahedra into a scikit-fem :class:`~skfem.MeshTet2`
(isoparametric, quadratic geometry) whose ``boundaries`` and ``subdomains`` are
named after the model's physical groups.  Nothing gmsh-specific (tags, entity
numbers) leaves this module: only arrays and names.

Node order of the quadratic tetrahedron (gmsh reference manual, section "Node
ordering"; VTK ``VTK_QUADRATIC_TETRA``; scikit-fem ``RefTet.edges``)::

    corner nodes 0..3, then one node on each edge:
    gmsh       (0,1) (1,2) (2,0) (3,0) (3,2) (3,1)
    scikit-fem (0,1) (1,2) (0,2) (0,3) (1,3) (2,3)

so gmsh's nodes 8 and 9 are swapped (:data:`GMSH_TO_SKFEM_TET10`).  scikit-fem
issue #1179: reading tetra10/triangle6 through meshio drops the boundary tags, so
the triangle6 corner nodes are matched to mesh facets here directly.
"""

from __future__ import annotations

import contextlib
import threading
from collections.abc import Iterator
from dataclasses import dataclass
from types import ModuleType

import numpy as np

from fe_crank.errors import MeshError

#: Permutation taking gmsh's 10-node tetrahedron (element type 11) to scikit-fem's order.
GMSH_TO_SKFEM_TET10 = np.array([0, 1, 2, 3, 4, 5, 6, 7, 9, 8])

_TET4, _TET10, _TRI3, _TRI6 = 4, 11, 2, 9
#: the thread counts a session sets (to ``threads``, 1 by default: gmsh's meshers then do
#: not depend on the machine's load); the mesh cache key holds them (``mesh.cache``)
SESSION_OPTIONS: dict[str, float] = {
    "General.NumThreads": 1,
    "Mesh.MaxNumThreads1D": 1,
    "Mesh.MaxNumThreads2D": 1,
    "Mesh.MaxNumThreads3D": 1,
}
_LOCK = threading.Lock()
_OWNER: dict[str, int] = {}


@contextlib.contextmanager
def gmsh_session(*, threads: int = 1, verbosity: int = 2) -> Iterator[ModuleType]:
    """Initialise gmsh for the body of a ``with`` block and finalise it afterwards.

    Parameters
    ----------
    threads
        Fixed number of threads gmsh may use (meshing results then do not depend on
        the machine's load); 1 by default.
    verbosity
        gmsh's ``General.Verbosity`` (0 silent ... 5 debug); terminal output is off
        regardless, so nothing is printed.

    Yields
    ------
    module
        The ``gmsh`` module, ready to build a model.

    Raises
    ------
    MeshError
        If a session is already open in this thread (gmsh has one global state);
        sessions opened from other threads wait for it to close.

    Examples
    --------
    >>> with gmsh_session() as gmsh:
    ...     _ = gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    ...     gmsh.model.occ.synchronize()
    """
    import gmsh

    me = threading.get_ident()
    if _OWNER.get("thread") == me:
        raise MeshError(
            "a gmsh session is already open in this thread; gmsh has one global state, do not nest sessions"
        )
    _LOCK.acquire()  # other threads wait: gmsh is not thread-safe, sessions are serialised
    if gmsh.isInitialized():
        _LOCK.release()
        raise MeshError("gmsh is already initialised outside fe-crank; finalise it before opening a gmsh_session")
    _OWNER["thread"] = me
    try:
        gmsh.initialize(interruptible=False)
        try:
            gmsh.option.setNumber("General.Terminal", 0)
            gmsh.option.setNumber("General.Verbosity", verbosity)
            for name in SESSION_OPTIONS:
                gmsh.option.setNumber(name, threads)
            gmsh.model.add("fe_crank")
            yield gmsh
        finally:
            gmsh.finalize()
    finally:
        _OWNER.pop("thread", None)
        _LOCK.release()


@dataclass(frozen=True)
class _Groups:
    boundaries: dict[str, np.ndarray]
    subdomains: dict[str, np.ndarray]


def _group_name(gmsh, dim: int, tag: int) -> str:
    name = gmsh.model.getPhysicalName(dim, tag)
    return name if name else f"{dim}:{tag}"


def _elements_of(gmsh, dim: int, entity: int, wanted: tuple[int, ...]) -> list[tuple[int, np.ndarray, np.ndarray]]:
    types, tags, nodes = gmsh.model.mesh.getElements(dim, entity)
    out = []
    for etype, etags, enodes in zip(types, tags, nodes):
        if etype in wanted:
            n = len(etags)
            out.append(
                (int(etype), np.asarray(etags, dtype=np.int64), np.asarray(enodes, dtype=np.int64).reshape(n, -1))
            )
    return out


def model_to_skfem(*, dim: int = 3, orient: bool = True, volumes=None):
    """Convert the current gmsh model's quadratic tetrahedra to a scikit-fem ``MeshTet2``.

    The model must be meshed with element order 2 (``gmsh.model.mesh.setOrder(2)``).
    Every physical group of dimension 3 becomes a subdomain (array of element
    indices), every physical group of dimension 2 a boundary (array of facet
    indices into ``mesh.facets``), named by the group's name (``"dim:tag"`` when it
    has none).  Tetrahedra outside every volume group are kept (all volumes are
    converted).

    Parameters
    ----------
    dim
        Only 3 is supported (tetrahedra); other values raise ``MeshError``.
    orient
        Renumber negatively oriented tetrahedra (corner Jacobian determinant < 0)
        so that every element has a positive Jacobian at its corners.
    volumes
        The volume tags to convert (default: every volume); the physical groups must then
        lie on them.  The nodes are those of their tetrahedra, numbered in the same order
        as in the whole model's conversion.

    Returns
    -------
    skfem.MeshTet2
        Quadratic (isoparametric) mesh with ``boundaries`` and ``subdomains``.

    Raises
    ------
    MeshError
        No second-order tetrahedra, a boundary triangle that is not a mesh facet,
        or a degenerate element (zero Jacobian).
    """
    import gmsh
    from skfem import MeshTet2

    if dim != 3:
        raise MeshError(f"model_to_skfem: dim={dim} is not supported; only 3 (tetrahedra)")
    if not gmsh.isInitialized():
        raise MeshError("model_to_skfem: no gmsh session is open (use gmsh_session())")

    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    node_tags = np.asarray(node_tags, dtype=np.int64)
    coords = np.asarray(coords, dtype=float).reshape(-1, 3)
    lookup = np.full(int(node_tags.max()) + 1 if node_tags.size else 1, -1, dtype=np.int64)
    lookup[node_tags] = np.arange(node_tags.size)

    # all tetrahedra, volume by volume (so subdomains are index ranges)
    tets = []
    elem_tags = []
    linear_found = False
    wanted = None if volumes is None else {int(v) for v in volumes}
    chosen = [vol for _, vol in gmsh.model.getEntities(3) if wanted is None or vol in wanted]
    for vol in chosen:
        for etype, etags, enodes in _elements_of(gmsh, 3, vol, (_TET4, _TET10)):
            if etype == _TET4:
                linear_found = True
                continue
            tets.append(enodes)
            elem_tags.append(etags)
    if not tets:
        hint = " (the mesh is first order: call gmsh.model.mesh.setOrder(2))" if linear_found else ""
        raise MeshError("model_to_skfem: the gmsh model has no second-order tetrahedra" + hint)
    tet = np.vstack(tets)[:, GMSH_TO_SKFEM_TET10]
    elem_tag = np.concatenate(elem_tags)
    tet = lookup[tet]

    # compact numbering: corner nodes first (vertices), then mid-edge nodes
    corners = np.unique(tet[:, :4])
    mids = np.setdiff1d(np.unique(tet[:, 4:]), corners)
    new = np.full(coords.shape[0], -1, dtype=np.int64)
    new[corners] = np.arange(corners.size)
    new[mids] = corners.size + np.arange(mids.size)
    t = new[tet]
    doflocs = coords[np.concatenate([corners, mids])]

    # orientation: Jacobian determinant at the corners of the affine part
    p = doflocs
    d = np.einsum(
        "ij,ij->i",
        np.cross(p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]]),
        p[t[:, 3]] - p[t[:, 0]],
    )
    scale = np.max(np.ptp(doflocs, axis=0)) ** 3 if doflocs.size else 1.0
    if np.any(np.abs(d) <= 1e-14 * scale):
        raise MeshError(
            f"model_to_skfem: {int(np.sum(np.abs(d) <= 1e-14 * scale))} degenerate tetrahedra (zero volume)"
        )
    if orient and np.any(d < 0):
        neg = d < 0
        # swap corners 1 and 2: edges (0,1)<->(0,2), (1,3)<->(2,3)
        t[neg] = t[neg][:, [0, 2, 1, 3, 6, 5, 4, 7, 9, 8]]

    mesh = MeshTet2(doflocs.T.copy(), t.T.astype(np.int32).copy())

    # element tag -> element index, for subdomains
    order = np.argsort(elem_tag)
    sorted_tags = elem_tag[order]

    subdomains: dict[str, np.ndarray] = {}
    for gdim, gtag in gmsh.model.getPhysicalGroups(3):
        idx = []
        for ent in gmsh.model.getEntitiesForPhysicalGroup(gdim, gtag):
            for _, etags, _ in _elements_of(gmsh, 3, int(ent), (_TET10,)):
                pos = np.searchsorted(sorted_tags, etags)
                idx.append(order[pos])
        name = _group_name(gmsh, gdim, gtag)
        subdomains[name] = np.sort(np.concatenate(idx)).astype(np.int32) if idx else np.zeros(0, dtype=np.int32)

    # facets keyed by their sorted vertex triple
    facets = np.sort(mesh.facets, axis=0).T.astype(np.int64)
    nv = np.int64(mesh.nvertices)
    fkey = (facets[:, 0] * nv + facets[:, 1]) * nv + facets[:, 2]
    forder = np.argsort(fkey)
    fkey_sorted = fkey[forder]

    boundaries: dict[str, np.ndarray] = {}
    for gdim, gtag in gmsh.model.getPhysicalGroups(2):
        idx = []
        for ent in gmsh.model.getEntitiesForPhysicalGroup(gdim, gtag):
            for _, _, enodes in _elements_of(gmsh, 2, int(ent), (_TRI3, _TRI6)):
                tri = new[lookup[enodes[:, :3]]]
                if np.any(tri < 0):
                    raise MeshError(
                        f"model_to_skfem: boundary group {_group_name(gmsh, gdim, gtag)!r} has triangles "
                        "whose corners are not tetrahedron corners"
                    )
                tri = np.sort(tri, axis=1)
                key = (tri[:, 0] * nv + tri[:, 1]) * nv + tri[:, 2]
                pos = np.searchsorted(fkey_sorted, key)
                pos = np.minimum(pos, fkey_sorted.size - 1)
                if np.any(fkey_sorted[pos] != key):
                    raise MeshError(
                        f"model_to_skfem: boundary group {_group_name(gmsh, gdim, gtag)!r} has triangles "
                        "that are not facets of the tetrahedral mesh"
                    )
                idx.append(forder[pos])
        name = _group_name(gmsh, gdim, gtag)
        boundaries[name] = np.unique(np.concatenate(idx)).astype(np.int32) if idx else np.zeros(0, dtype=np.int32)

    groups = _Groups(boundaries, subdomains)
    out = mesh
    if groups.boundaries:
        out = out.with_boundaries(groups.boundaries)
    if groups.subdomains:
        out = out.with_subdomains(groups.subdomains)
    return out


def corner_jacobians(mesh) -> np.ndarray:
    """Signed Jacobian determinants of a ``MeshTet2`` at its quadrature points, per element.

    Returns an array ``(n_elements, n_points)`` of ``det(dx/dX)`` of the quadratic
    (isoparametric) map, evaluated at a degree-4 quadrature rule: an element with
    any value <= 0 is inverted or degenerate.
    """
    from skfem.quadrature import get_quadrature

    X, _ = get_quadrature(mesh.refdom, 4)
    X = np.hstack([X, np.array([[0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])])
    mapping = mesh._mapping()
    return np.asarray(mapping.detDF(X))
