"""Mirror a quadratic tetrahedral mesh across a coordinate plane through the origin.

``mirror_mesh(mesh, axis)`` takes a scikit-fem ``MeshTet2`` lying on one side of the
plane ``x_axis = 0`` (the fundamental part of a symmetric throw) and returns the whole:
the part and its reflection ``x_axis -> -x_axis``, joined on the plane.

* Nodes within ``tol`` of the plane are snapped to exactly 0 in the normal coordinate and
  shared by both halves; every other node gets an image whose normal coordinate is the
  exact negation (so ``x -> -x`` maps the node set onto itself bit for bit).  A node
  between ``tol`` and ``1000 tol`` off the plane is ambiguous and refused.
* A reflection reverses orientation: an image element lists its corners as
  ``(0, 2, 1, 3)`` and its mid-edge nodes consistently with scikit-fem's P2 order
  (edges (0,1) (1,2) (0,2) (0,3) (1,3) (2,3)), i.e. the permutation
  ``[0, 2, 1, 3, 6, 5, 4, 7, 9, 8]``, so its Jacobian is positive again.
* Elements ``0..ne-1`` are the part's, ``ne..2 ne-1`` their images, in the same order.
  Named subdomains (element indices) and boundaries (facet indices) are carried over; an
  image group is named ``rename(name)`` (``swap_side`` exchanges the ``_1``/``_2`` suffixes
  for a mirror across ``z = 0``, which exchanges the front and rear of a throw).
* Facets on the plane become interior; a boundary facet left on the plane (the part and
  its image do not close) is an error.

Pure numpy; no gmsh.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from fe_crank.errors import MeshError

#: local P2 node order of the mirrored element (corners 1 and 2 exchanged)
FLIP_TET10 = np.array([0, 2, 1, 3, 6, 5, 4, 7, 9, 8])


def swap_side(name: str) -> str:
    """``journal_1 <-> journal_2``, ``web_1 <-> web_2``, ...; other names unchanged."""
    if name.endswith("_1"):
        return name[:-2] + "_2"
    if name.endswith("_2"):
        return name[:-2] + "_1"
    return name


def _facet_index(mesh, tri: np.ndarray) -> np.ndarray:
    """Indices in ``mesh.facets`` of the vertex triples ``tri`` (k, 3); MeshError if one is missing."""
    nv = np.int64(mesh.nvertices)
    f = np.sort(mesh.facets, axis=0).astype(np.int64)
    fkey = (f[0] * nv + f[1]) * nv + f[2]
    order = np.argsort(fkey)
    s = np.sort(tri, axis=1).astype(np.int64)
    key = (s[:, 0] * nv + s[:, 1]) * nv + s[:, 2]
    pos = np.minimum(np.searchsorted(fkey[order], key), fkey.size - 1)
    if np.any(fkey[order][pos] != key):
        raise MeshError("mirroring: a named boundary triangle is not a facet of the mirrored mesh")
    return order[pos]


def mirror_mesh(mesh, axis: int, *, rename: Callable[[str], str] = lambda n: n, tol: float | None = None):
    """The mesh and its mirror image across ``x_axis = 0``, joined (see the module docstring).

    ``tol`` (m) defaults to ``1e-9`` times the largest extent of the mesh.
    """
    from skfem import MeshTet2

    P = np.array(mesh.doflocs, dtype=float).T  # (N, 3), vertices first
    T = np.asarray(mesh.dofs.element_dofs, dtype=np.int64).T  # (ne, 10), scikit-fem P2 order
    nv, N, ne = int(mesh.nvertices), P.shape[0], T.shape[0]
    if tol is None:
        tol = 1e-9 * float(np.max(np.ptp(P, axis=0)))
    c = P[:, axis]
    if np.any(c < -tol) and np.any(c > tol):
        raise MeshError(f"mirroring across axis {axis}: the mesh lies on both sides of the plane")
    on = np.abs(c) <= tol
    if not np.any(on):
        raise MeshError(f"mirroring across axis {axis}: no node lies on the plane")
    if np.any(~on & (np.abs(c) < 1e3 * tol)):
        raise MeshError(f"mirroring across axis {axis}: nodes lie within round-off of the plane but not on it")
    P[on, axis] = 0.0

    off = np.flatnonzero(~on)
    off_v, off_m = off[off < nv], off[off >= nv]
    nov, nom = off_v.size, off_m.size
    # new numbering: part's vertices, image vertices, part's mid-edge nodes, image mid-edge nodes
    own = np.arange(N)
    own[nv:] += nov
    img = own.copy()
    img[off_v] = nv + np.arange(nov)
    img[off_m] = N + nov + np.arange(nom)
    Q = np.empty((N + nov + nom, 3))
    Q[own] = P
    Q[img[off]] = P[off]
    Q[img[off], axis] = -P[off, axis]
    t = np.vstack([own[T], img[T][:, FLIP_TET10]])
    full = MeshTet2(Q.T.copy(), t.T.astype(np.int32).copy())
    if full.nvertices != nv + nov:
        raise MeshError("mirroring: vertex numbering not preserved")  # every vertex belongs to an element

    sub: dict[str, list[np.ndarray]] = {}
    for name, idx in (mesh.subdomains or {}).items():
        idx = np.asarray(idx, dtype=np.int64)
        sub.setdefault(name, []).append(idx)
        sub.setdefault(rename(name), []).append(idx + ne)
    bnd: dict[str, list[np.ndarray]] = {}
    for name, idx in (mesh.boundaries or {}).items():
        tri = mesh.facets[:, np.asarray(idx, dtype=np.int64)].T.astype(np.int64)  # vertex indices < nv: own == identity
        bnd.setdefault(name, []).append(_facet_index(full, tri))
        bnd.setdefault(rename(name), []).append(_facet_index(full, img[tri]))

    bf = full.boundary_facets()
    on_plane = np.all(np.abs(full.p[axis][full.facets[:, bf]]) == 0.0, axis=0)
    if np.any(on_plane):
        raise MeshError(f"mirroring across axis {axis}: {int(on_plane.sum())} boundary facets remain on the plane")
    out = full
    if bnd:
        out = out.with_boundaries({k: np.unique(np.concatenate(v)).astype(np.int32) for k, v in bnd.items()})
    if sub:
        out = out.with_subdomains({k: np.unique(np.concatenate(v)).astype(np.int32) for k, v in sub.items()})
    return out


def mirror_all(mesh, axes: tuple[int, ...]):
    """Mirror across each plane of ``axes`` in turn (x = 0 keeps names, z = 0 swaps ``_1``/``_2``)."""
    for axis in axes:
        mesh = mirror_mesh(mesh, axis, rename=swap_side if axis == 2 else (lambda n: n))
    return mesh
