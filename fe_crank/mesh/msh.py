"""A scikit-fem ``MeshTet2`` as a gmsh ``.msh`` file: second-order tetrahedra (gmsh type
11) in one discrete volume per named subdomain and six-node triangles (type 9) in one
discrete surface per named boundary, each a physical group of that name.  Used for the
mirrored meshes of symmetric throws, which gmsh itself never held whole.

Node orders (gmsh reference manual, "Node ordering"): tet10 as in
``fe_crank.gmsh_io.GMSH_TO_SKFEM_TET10`` (its own inverse); triangle6 corners 0, 1, 2 then
the nodes of edges (0,1), (1,2), (2,0).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from fe_crank.errors import MeshError, environment_fault


def _edge_dofs(mesh, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """P2 node numbers of the edges (a, b) (scikit-fem: vertices first, then one node per edge)."""
    nv = np.int64(mesh.nvertices)
    e = np.sort(mesh.edges, axis=0).astype(np.int64)
    ekey = e[0] * nv + e[1]
    order = np.argsort(ekey)
    lo, hi = np.minimum(a, b).astype(np.int64), np.maximum(a, b).astype(np.int64)
    pos = order[np.searchsorted(ekey[order], lo * nv + hi)]
    return mesh.nvertices + pos


def write_msh(path: Path, mesh) -> None:
    """Write ``mesh`` (``MeshTet2`` with named subdomains/boundaries) to ``path`` with gmsh."""
    from fe_crank.gmsh_io import GMSH_TO_SKFEM_TET10, gmsh_session

    edofs = np.asarray(mesh.dofs.element_dofs, dtype=np.int64)  # (10, ne)
    with gmsh_session() as gmsh:
        n = mesh.doflocs.shape[1]
        tags = np.arange(1, n + 1)
        gmsh.model.addDiscreteEntity(0, 1)  # nodes are attached to a point entity, elements to their own
        gmsh.model.mesh.addNodes(0, 1, tags.tolist(), mesh.doflocs.T.ravel().tolist())
        next_el = 1
        parts = mesh.subdomains or {"volume": np.arange(mesh.nelements)}
        for k, (name, idx) in enumerate(sorted(parts.items()), start=1):
            gmsh.model.addDiscreteEntity(3, k)
            conn = edofs[:, idx][GMSH_TO_SKFEM_TET10].T + 1
            els = np.arange(next_el, next_el + conn.shape[0])
            next_el += conn.shape[0]
            gmsh.model.mesh.addElementsByType(k, 11, els.tolist(), conn.ravel().tolist())
            gmsh.model.addPhysicalGroup(3, [k], name=name)
        for k, (name, idx) in enumerate(sorted((mesh.boundaries or {}).items()), start=1):
            f = mesh.facets[:, idx].astype(np.int64)  # (3, k) vertices
            mids = [_edge_dofs(mesh, f[i], f[j]) for i, j in ((0, 1), (1, 2), (2, 0))]
            conn = np.vstack([f, *mids]).T + 1
            gmsh.model.addDiscreteEntity(2, k)
            els = np.arange(next_el, next_el + conn.shape[0])
            next_el += conn.shape[0]
            gmsh.model.mesh.addElementsByType(k, 9, els.tolist(), conn.ravel().tolist())
            gmsh.model.addPhysicalGroup(2, [k], name=name)
        write_model(gmsh, path)


def write_model(gmsh, path: str | Path) -> None:
    """``gmsh.write(path)``; a file the machine does not let gmsh write (a full disk, no
    permission) is an ``EnvironmentFault`` naming it, any other failure a ``MeshError``."""
    try:
        gmsh.write(str(path))
    except Exception as exc:  # gmsh raises bare Exception
        try:  # the operating system's reason, which gmsh does not give
            with open(path, "ab"):
                pass
        except OSError as os_exc:
            raise environment_fault(os_exc, "writing the mesh", path) from None
        raise MeshError(f"gmsh could not write {path}: {exc}") from None
