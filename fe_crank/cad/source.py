"""Either geometry source of a check, meshed alike: a parametric ``CrankGeometry``
(``fe_crank.mesh.mesh_throw``) or a CAD file (``fe_crank.cad.mesh.mesh_cad_throw``),
one throw by name into the same ``ThrowMesh`` (named groups, fillet rules, cache)."""

from __future__ import annotations

from pathlib import Path

from fe_crank.cad.config import CadInput
from fe_crank.cad.mesh import mesh_cad_throw
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.mesh import mesh_throw
from fe_crank.mesh.options import MeshOptions
from fe_crank.mesh.types import ThrowMesh

#: the geometry a load case gives (``fe_crank.io.loadcase.LoadCase.geometry``)
GeometrySource = CrankGeometry | CadInput


def mesh_source_throw(
    geometry: GeometrySource,
    throw: str | None,
    *,
    size: str | MeshOptions,
    cache_dir: str | Path | None,
    max_elements: int | None = None,
) -> ThrowMesh:
    """The quadratic tetrahedral mesh of ``throw`` (its name; None: the first) of either
    source (cached)."""
    if isinstance(geometry, CadInput):
        return mesh_cad_throw(geometry, throw, size=size, cache_dir=cache_dir, max_elements=max_elements)
    return mesh_throw(geometry, throw=throw, size=size, cache_dir=cache_dir, max_elements=max_elements)
