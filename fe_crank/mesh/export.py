"""The mesh as a VTK file: quadratic tetrahedra with a ``subdomain`` cell array and the
region ids, written by the project's one VTU writer (``fe_crank.vtu_writer``)."""

from __future__ import annotations

from pathlib import Path

from fe_crank.vtu_writer import quadratic_tet_mesh, region_ids
from fe_crank.vtu_writer import write_vtu as write


def write_vtu(path: Path, mesh) -> None:
    """Write a ``MeshTet2`` as VTK quadratic tetrahedra (``tetra10``) with cell data
    ``subdomain`` (field data ``subdomain:<name>`` = [id, 3])."""
    cdata, fdata = region_ids(mesh)
    write(path, quadratic_tet_mesh(mesh.doflocs, mesh.dofs.element_dofs, cell_data=cdata, field_data=fdata))
