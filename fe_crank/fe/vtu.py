"""VTU output of FE fields (meshio), readable by ParaView.

Cells are VTK quadratic tetrahedra (``tetra10``): scikit-fem's P2 local order (corners,
then edges (0,1) (1,2) (0,2) (0,3) (1,3) (2,3)) is VTK's order, so the element dofs are
the cell connectivity as they are.  Point fields live on the P2 nodes.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from fe_crank.fe.stress import VOIGT, max_shear, principal, von_mises


def write_fields(path: str | Path, basis, u: np.ndarray | None = None, stress: np.ndarray | None = None,
                 extra: dict[str, np.ndarray] | None = None) -> Path:
    """Write displacement (3 per node), stress (6, Voigt) and derived scalars to ``path`` (.vtu).

    ``basis``: the scalar P2 basis of the solution (``UnitSolutions.system.basis``).
    Derived fields: von_mises, principal_1..3, max_shear.  The file is written to a
    temporary name and renamed, so a reader never sees half a file.
    """
    import meshio

    path = Path(path)
    points = np.ascontiguousarray(basis.doflocs.T)
    cells = [("tetra10", np.ascontiguousarray(basis.element_dofs.T))]
    data: dict[str, np.ndarray] = {}
    if u is not None:
        data["displacement"] = np.asarray(u).reshape(-1, 3)
    if stress is not None:
        data["stress"] = np.ascontiguousarray(np.asarray(stress).T)        # (n, 6): xx yy zz xy yz zx
        data["von_mises"] = von_mises(stress)
        p = principal(stress)
        for k in range(3):
            data[f"principal_{k + 1}"] = p[k]
        data["max_shear"] = max_shear(stress)
    for name, arr in (extra or {}).items():
        data[name] = np.asarray(arr)
    tmp = path.with_name(path.name + ".part")
    meshio.write(tmp, meshio.Mesh(points, cells, point_data=data), file_format="vtu")
    tmp.replace(path)
    return path


STRESS_COMPONENTS = VOIGT
