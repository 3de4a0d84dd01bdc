"""The one VTU writer of the project: quadratic tetrahedra (VTK ``tetra10``), readable
by ParaView, meshio and pyvista.

Cells are VTK quadratic tetrahedra: scikit-fem's P2 local order (corners, then the
edges (0,1) (1,2) (0,2) (0,3) (1,3) (2,3)) is VTK's ``VTK_QUADRATIC_TETRA`` order, so
the P2 element dofs are the cell connectivity as they are and every P2 node (corners
and mid-edge nodes) is a point of a cell.  Point fields live on the P2 nodes.

Units are part of the field names (``von_mises_Pa``, ``displacement_m``); fields
without a unit suffix are pure numbers or ids.  Region ids: cell data ``subdomain``
and point data ``boundary`` index into the sorted names given by ``region_names``
(also written as field data ``subdomain:<name>`` / ``boundary:<name>`` = id).
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np
from skfem import Mesh


def quadratic_tet_mesh(
    points: np.ndarray,
    cells: np.ndarray,
    *,
    point_data: dict | None = None,
    cell_data: dict | None = None,
    field_data: dict | None = None,
):
    """A ``meshio.Mesh`` of ``tetra10`` cells.

    ``points`` (n, 3) or (3, n) node coordinates [m]; ``cells`` (m, 10) or (10, m)
    P2 element dofs in scikit-fem/VTK order; ``cell_data`` name -> (m,) array.
    """
    import meshio

    pts = np.asarray(points, float)
    if pts.shape[1] != 3:
        pts = pts.T
    c = np.asarray(cells)
    if c.shape[1] != 10:
        c = c.T
    if c.shape[1] != 10:
        raise ValueError("quadratic tetrahedra need 10 nodes per cell")
    c = positively_oriented(pts, c)
    pdata = {k: np.asarray(v) for k, v in (point_data or {}).items()}
    for k, v in pdata.items():
        if v.shape[0] != pts.shape[0]:
            raise ValueError(f"point field {k!r} has {v.shape[0]} values for {pts.shape[0]} points")
    cdata = {k: [np.asarray(v)] for k, v in (cell_data or {}).items()}
    return meshio.Mesh(
        np.ascontiguousarray(pts),
        [("tetra10", np.ascontiguousarray(c, dtype=np.int64))],
        point_data=pdata,
        cell_data=cdata,
        field_data=dict(field_data or {}),
    )


#: tetra10 node order with corners 1 and 2 swapped (edges follow: (0,1) <-> (0,2), (1,3) <-> (2,3))
_MIRROR = np.array([0, 2, 1, 3, 6, 5, 4, 7, 9, 8])


def positively_oriented(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Cells (m, 10) reordered so that every tetrahedron has a positive volume
    ((p1 - p0) x (p2 - p0) . (p3 - p0) > 0, VTK's convention); others unchanged."""
    a, b, c, d = (points[cells[:, k]] for k in range(4))
    neg = np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a) < 0
    if not neg.any():
        return cells
    out = cells.copy()
    out[neg] = cells[neg][:, _MIRROR]
    return out


def write_vtu(path: str | Path, mesh) -> Path:
    """Write a ``meshio.Mesh`` (see ``quadratic_tet_mesh``) as binary VTU with VTK's own
    writer (through pyvista; meshio's writer drops field data), atomically: a
    temporary file in the same folder renamed into place, so a reader never sees
    half a file."""
    import pyvista as pv

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    grid = pv.from_meshio(mesh)
    for k, v in (mesh.field_data or {}).items():
        grid.field_data[k] = np.asarray(v)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=".vtu", dir=path.parent)
    os.close(fd)
    try:
        grid.save(tmp, binary=True)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path


def region_ids(skmesh: Mesh) -> tuple[dict, dict]:
    """Cell data ``subdomain`` of a scikit-fem mesh with named ``subdomains`` (the index
    of the sorted name, -1 where none) and the matching field data."""
    subs = sorted(skmesh.subdomains or {})
    sub = np.full(skmesh.t.shape[1], -1, np.int32)
    for i, name in enumerate(subs):
        sub[skmesh.subdomains[name]] = i
    return {"subdomain": sub}, {f"subdomain:{name}": np.array([i, 3]) for i, name in enumerate(subs)}
