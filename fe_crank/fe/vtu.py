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

from fe_crank.fe.stress import VOIGT, max_shear, principal, von_mises


def quadratic_tet_mesh(points: np.ndarray, cells: np.ndarray, *, point_data: dict | None = None,
                       cell_data: dict | None = None, field_data: dict | None = None):
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
    return meshio.Mesh(np.ascontiguousarray(pts), [("tetra10", np.ascontiguousarray(c, dtype=np.int64))],
                       point_data=pdata, cell_data=cdata, field_data=dict(field_data or {}))


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


def region_ids(skmesh) -> tuple[dict, dict]:
    """Cell data ``subdomain`` of a scikit-fem mesh with named ``subdomains`` (the index
    of the sorted name, -1 where none) and the matching field data."""
    subs = sorted(getattr(skmesh, "subdomains", None) or {})
    sub = np.full(skmesh.t.shape[1], -1, np.int32)
    for i, name in enumerate(subs):
        sub[skmesh.subdomains[name]] = i
    return {"subdomain": sub}, {f"subdomain:{name}": np.array([i, 3]) for i, name in enumerate(subs)}


def boundary_point_ids(skmesh, basis) -> tuple[np.ndarray, dict]:
    """Point data ``boundary``: for every P2 node, the id of the first (sorted) named
    boundary it lies on, -1 for none; and the matching field data."""
    names = sorted(getattr(skmesh, "boundaries", None) or {})
    ids = np.full(basis.doflocs.shape[1], -1, np.int32)
    for i, name in reversed(list(enumerate(names))):  # the first name wins
        nodes = np.unique(basis.get_dofs(facets=skmesh.boundaries[name]).all())
        ids[nodes] = i
    return ids, {f"boundary:{name}": np.array([i, 2]) for i, name in enumerate(names)}


def stress_fields(stress: np.ndarray, suffix: str = "") -> dict[str, np.ndarray]:
    """Point fields of a (6, n) Voigt stress (xx yy zz xy yz zx, Pa): ``stress_Pa``
    (n, 6), ``von_mises_Pa``, ``principal_1_Pa`` >= ``principal_2_Pa`` >= ``principal_3_Pa``,
    ``max_shear_Pa`` (Tresca, (s1 - s3) / 2); ``suffix`` is appended to every name."""
    s = np.asarray(stress)
    p = principal(s)
    out = {"stress_Pa": np.ascontiguousarray(s.T), "von_mises_Pa": von_mises(s)}
    for k in range(3):
        out[f"principal_{k + 1}_Pa"] = p[k]
    out["max_shear_Pa"] = max_shear(s)
    return {k.replace("_Pa", f"{suffix}_Pa") if suffix else k: v for k, v in out.items()}


def write_fields(path: str | Path, basis, u: np.ndarray | None = None, stress: np.ndarray | None = None,
                 extra: dict[str, np.ndarray] | None = None) -> Path:
    """Write displacement ``displacement_m`` (3 per node), stress ``stress_Pa`` (n, 6,
    Voigt) and the derived scalars of ``stress_fields`` to ``path`` (.vtu), with the
    region ids of ``basis.mesh`` when it has named groups.

    ``basis``: the scalar P2 basis of the solution (``UnitSolutions.system.basis``).
    """
    data: dict[str, np.ndarray] = {}
    if u is not None:
        data["displacement_m"] = np.asarray(u).reshape(-1, 3)
    if stress is not None:
        data.update(stress_fields(stress))
    for name, arr in (extra or {}).items():
        data[name] = np.asarray(arr)
    cdata, fdata = region_ids(basis.mesh)
    if getattr(basis.mesh, "boundaries", None):
        data["boundary"], bf = boundary_point_ids(basis.mesh, basis)
        fdata.update(bf)
    mesh = quadratic_tet_mesh(basis.doflocs, basis.element_dofs, point_data=data, cell_data=cdata,
                              field_data=fdata)
    return write_vtu(path, mesh)


STRESS_COMPONENTS = VOIGT
