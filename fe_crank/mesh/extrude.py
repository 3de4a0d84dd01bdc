"""Round shaft pieces meshed by extruding a quadratic triangle mesh of their cross-section.

The pieces of the whole shaft beyond the throws (the outer halves of the end journals)
must join a throw's end face node to node, so they are built from that face's own P2
triangles (``face_disc``): layers of triangular prisms, each split into three tetrahedra
by the rule "the diagonal of every side quadrilateral runs from the bottom vertex of larger
number to the top vertex of smaller number", which two prisms sharing a side apply alike,
so the mesh is conforming.  Mid-edge nodes: an edge inside a layer plane takes the face's
own mid-edge node (on the circle for rim edges), a vertical edge its midpoint, a diagonal
edge the face's mid-edge node of the edge below it at mid-height, so rim edges lie on the
cylinder: the isoparametric geometry is the exact cylinder wherever the face's is.

``Disc`` holds the cross-section; boundaries of the extruded mesh: ``end_1`` (first
level), ``end_2`` (last level), ``surface`` (lateral).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.errors import MeshError
from fe_crank.mesh.mirror import FLIP_TET10


@dataclass(frozen=True)
class Disc:
    """A P2 triangle mesh in a plane z = const: ``xy`` (n, 2) nodes (vertices first, then
    one node per edge), ``tri`` (k, 3) vertex numbers, ``edges`` (m, 2) vertex numbers with
    ``mid`` (m,) the node of each edge; ``nv`` vertices."""

    xy: np.ndarray
    tri: np.ndarray
    edges: np.ndarray
    mid: np.ndarray
    nv: int


def face_disc(mesh, boundary: str) -> Disc:
    """The P2 triangles of a planar named face of a ``MeshTet2`` as a ``Disc`` (its nodes
    in the order: the face's vertices by increasing mesh number, then its edges' nodes)."""
    if boundary not in (mesh.boundaries or {}):
        raise MeshError(f"the mesh has no face {boundary!r} to extrude")
    facets = np.asarray(mesh.boundaries[boundary])
    tri_v = mesh.facets[:, facets].T  # (k, 3) vertex numbers
    verts = np.unique(tri_v)
    f2e = mesh.f2e[:, facets].T  # (k, 3) edge numbers
    edges_all = np.unique(f2e)
    e_v = mesh.edges[:, edges_all].T  # (m, 2)
    nv = verts.size
    xyz = np.asarray(mesh.doflocs)
    if np.ptp(xyz[2, verts]) > 1e-9 * max(1.0, np.ptp(xyz[:2, verts])):
        raise MeshError(f"the face {boundary!r} is not plane z = const")
    loc = np.searchsorted(verts, tri_v)
    e_loc = np.searchsorted(verts, e_v)
    xy = np.vstack([xyz[:2, verts].T, xyz[:2, mesh.nvertices + edges_all].T])
    return Disc(xy=xy, tri=loc, edges=e_loc, mid=nv + np.arange(edges_all.size), nv=nv)


def _edge_index(edges: np.ndarray, nv: int):
    key = np.minimum(edges[:, 0], edges[:, 1]) * nv + np.maximum(edges[:, 0], edges[:, 1])
    order = np.argsort(key)

    def find(a, b):
        k = np.minimum(a, b) * nv + np.maximum(a, b)
        pos = np.searchsorted(key[order], k)
        return order[pos]

    return find


def round_disc(radius: float, size: float) -> Disc:
    """A P2 triangle mesh of a disc (gmsh, element edge about ``size``), for round shafts
    built of extruded pieces alone."""
    from fe_crank.gmsh_io import gmsh_session

    with gmsh_session() as gmsh:
        gmsh.model.occ.addDisk(0.0, 0.0, 0.0, radius, radius)
        gmsh.model.occ.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        gmsh.option.setNumber("Mesh.MeshSizeMin", 0.5 * size)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.model.mesh.generate(2)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        _, _, conn = gmsh.model.mesh.getElements(2)
    pos = {int(t): i for i, t in enumerate(tags)}
    tri6 = np.array([pos[int(t)] for t in conn[0]]).reshape(-1, 6)  # corners, then (0,1) (1,2) (2,0)
    xyz = xyz.reshape(-1, 3)
    verts = np.unique(tri6[:, :3])
    vmap = np.full(xyz.shape[0], -1)
    vmap[verts] = np.arange(verts.size)
    tri = vmap[tri6[:, :3]]
    e = np.vstack([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    mids = np.concatenate([tri6[:, 3], tri6[:, 4], tri6[:, 5]])
    key = np.minimum(e[:, 0], e[:, 1]) * verts.size + np.maximum(e[:, 0], e[:, 1])
    _, first = np.unique(key, return_index=True)
    edges, mid_nodes = e[first], mids[first]
    xy = np.vstack([xyz[verts, :2], xyz[mid_nodes, :2]])
    return Disc(xy=xy, tri=tri, edges=edges, mid=verts.size + np.arange(edges.shape[0]), nv=verts.size)


def extrude(disc: Disc, levels, bands: dict[str, tuple[float, float]] | None = None) -> object:
    """Tetrahedral P2 mesh (``skfem.MeshTet2``) of the disc extruded through the z
    ``levels`` (increasing); boundaries ``end_1``, ``end_2``, ``surface`` (module doc) and,
    for each of ``bands`` (name -> (z0, z1)), the lateral facets whose centroid lies in it."""
    from skfem import MeshTet2

    z = np.asarray(levels, float)
    if z.size < 2 or np.any(np.diff(z) <= 0):
        raise MeshError("extrusion levels must increase")
    L, nv, m = z.size - 1, disc.nv, disc.edges.shape[0]
    find = _edge_index(disc.edges, nv)
    # numbering: vertices (level-major), then edge nodes in levels, vertical mids, diagonal mids
    n_vert = (L + 1) * nv
    o_h, o_v = n_vert, n_vert + (L + 1) * m
    o_d = o_v + L * nv

    def vert(lev, v):
        return lev * nv + v

    xy_v, xy_m = disc.xy[:nv], disc.xy[disc.mid]
    pts = np.vstack(
        [
            np.column_stack([np.tile(xy_v, (L + 1, 1)), np.repeat(z, nv)]),
            np.column_stack([np.tile(xy_m, (L + 1, 1)), np.repeat(z, m)]),
            np.column_stack([np.tile(xy_v, (L, 1)), np.repeat(0.5 * (z[:-1] + z[1:]), nv)]),
            np.column_stack([np.tile(xy_m, (L, 1)), np.repeat(0.5 * (z[:-1] + z[1:]), m)]),
        ]
    )
    tri = np.sort(disc.tri, axis=1)
    a, b, c = tri.T
    tets = []
    for lev in range(L):
        lo, hi = lev, lev + 1
        # corners (bottom a b c, top a' b' c'): (a b c a'), (b c a' b'), (c a' b' c')
        for corners in (
            ((lo, a), (lo, b), (lo, c), (hi, a)),
            ((lo, b), (lo, c), (hi, a), (hi, b)),
            ((lo, c), (hi, a), (hi, b), (hi, c)),
        ):
            tets.append(np.stack([vert(lv, v) for lv, v in corners], axis=1))
    T = np.vstack(tets)  # (ne, 4) global vertex numbers
    lev_of = T // nv
    v_of = T % nv
    pairs = ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))
    mids = np.empty((T.shape[0], 6), np.int64)
    for k, (i, j) in enumerate(pairs):
        li, lj, vi, vj = lev_of[:, i], lev_of[:, j], v_of[:, i], v_of[:, j]
        same = li == lj
        vertical = vi == vj
        lo = np.minimum(li, lj)
        out = np.empty(T.shape[0], np.int64)
        s = same & ~vertical
        out[s] = o_h + li[s] * m + find(vi[s], vj[s])
        out[vertical] = o_v + lo[vertical] * nv + vi[vertical]
        d = ~same & ~vertical
        out[d] = o_d + lo[d] * m + find(vi[d], vj[d])
        mids[:, k] = out
    t10 = np.hstack([T, mids])
    P = pts
    jac = np.einsum("ij,ij->i", np.cross(P[T[:, 1]] - P[T[:, 0]], P[T[:, 2]] - P[T[:, 0]]), P[T[:, 3]] - P[T[:, 0]])
    if np.any(jac == 0):
        raise MeshError("a degenerate prism in the extrusion (coincident levels or vertices)")
    t10[jac < 0] = t10[jac < 0][:, FLIP_TET10]
    mesh = MeshTet2(P.T.copy(), t10.T.astype(np.int32).copy())
    return mesh.with_boundaries(_boundaries(mesh, z, bands or {}))


def _boundaries(mesh, z: np.ndarray, bands) -> dict[str, np.ndarray]:
    bf = mesh.boundary_facets()
    fz = mesh.p[2][mesh.facets[:, bf]]
    first = np.all(fz == z[0], axis=0)
    last = np.all(fz == z[-1], axis=0)
    out = {"end_1": bf[first], "end_2": bf[last], "surface": bf[~first & ~last]}
    zc = fz.mean(axis=0)
    for name, (z0, z1) in bands.items():
        sel = ~first & ~last & (zc > z0) & (zc < z1)
        if not np.any(sel):
            raise MeshError(f"the band {name!r} ({z0:g} .. {z1:g} m) holds no lateral facet")
        out[name] = bf[sel]
    return out
