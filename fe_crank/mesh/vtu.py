"""The mesh as a VTK file (quadratic tetrahedra with a ``subdomain`` cell array)."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def write_vtu(path: Path, mesh) -> None:
    """Write a ``MeshTet2`` as VTK quadratic tetrahedra with a ``subdomain`` cell array."""
    import meshio

    cells = mesh.dofs.element_dofs.T  # vertex dofs then edge dofs: VTK_QUADRATIC_TETRA order
    sub = np.full(mesh.nelements, -1, dtype=np.int32)
    names = sorted(mesh.subdomains or {})
    for i, name in enumerate(names):
        sub[mesh.subdomains[name]] = i
    m = meshio.Mesh(mesh.doflocs.T, [("tetra10", cells)], cell_data={"subdomain": [sub]})
    m.field_data = {name: np.array([i, 3]) for i, name in enumerate(names)}
    meshio.write(str(path), m, file_format="vtu")
