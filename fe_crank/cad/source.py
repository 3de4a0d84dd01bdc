"""The check's meshing, one entry point for every model it needs: ``mesh_models``.

Either geometry source of a check is meshed alike: a parametric ``CrankGeometry``
(``fe_crank.mesh.mesh_throw``, the whole shaft ``fe_crank.mesh.shaft.mesh_shaft``) or a CAD
file (``fe_crank.cad.mesh.mesh_cad_throw``, the drawn shaft ``fe_crank.cad.whole.
cad_shaft_mesh``), each throw into the same ``ThrowMesh`` (named groups, fillet rules,
cache) and the whole shaft into the same ``ShaftMesh``.

* ``mesh_models(source, plan, features)``: what the mesh plan (``fe_crank.mesh.plan``)
  asks for, with the plan's options, element limit and cache: each throw model of the
  plan and, when the plan holds the whole shaft, the shaft (``Meshes``).  The pipeline's
  mesh stage calls it once per load case; no later stage meshes a model of the plan.
* ``mesh_source_throw(source, throw, size=...)``: one throw at the options given, for the
  re-meshes whose options a rule or a study decides from a mesh of the plan (UR M53's SCF
  mode at r/4 and its App. III refinements, ``rules.m53.scf_refine``; the hot-spot
  convergence study's levels, ``fe.refinement.convergence``).
* ``mesh_source_shaft(source, layout, size=...)``: the whole shaft of either source.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

from fe_crank.cad.config import CadInput
from fe_crank.cad.features import CadFeatures
from fe_crank.cad.mesh import mesh_cad_throw
from fe_crank.cad.whole import cad_shaft_mesh
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.mesh import mesh_throw
from fe_crank.mesh.options import MeshOptions
from fe_crank.mesh.plan import MeshPlan
from fe_crank.mesh.shaft import ShaftMesh, mesh_shaft
from fe_crank.mesh.types import ThrowMesh

#: the geometry a load case gives (``fe_crank.io.loadcase.LoadCase.geometry``)
GeometrySource = CrankGeometry | CadInput


@dataclass(frozen=True)
class Meshes:
    """The meshes of a plan's models: ``throws`` (plan key -> its throw model's mesh; keys
    whose models are one mesh share it), ``shaft`` (the whole shaft's; None when the plan
    holds no shaft) and the seconds the shaft's mesh took (s; its throws come from the
    cache the throw models filled)."""

    throws: dict[str, ThrowMesh]
    shaft: ShaftMesh | None = None
    shaft_seconds: float = 0.0


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


def mesh_source_shaft(
    geometry: GeometrySource,
    layout: ShaftLayout,
    *,
    size: str | MeshOptions,
    cache_dir: str | Path | None,
    max_elements: int | None = None,
    features: CadFeatures | None = None,
) -> ShaftMesh:
    """The whole shaft ``layout`` of either source: a parametric layout's throws
    (``mesh_shaft``) or, for a CAD file, its drawn throws (``features``: the file's
    recognised features, which gave the layout; ``cad_shaft_mesh``)."""
    if isinstance(geometry, CadInput):
        if features is None:
            raise ValueError("a drawn shaft is meshed from the CAD file's recognised features: give features")
        return cad_shaft_mesh(geometry, features, layout, size=size, cache_dir=cache_dir, max_elements=max_elements)
    return mesh_shaft(layout, size=size, cache_dir=cache_dir, max_elements=max_elements)


def mesh_models(geometry: GeometrySource, plan: MeshPlan, features: CadFeatures | None = None) -> Meshes:
    """Every model of ``plan`` meshed with its options (module doc): the throw models in
    the plan's order, then the whole shaft when the plan holds it (``features``: a CAD
    file's recognised features, for its drawn shaft)."""
    throws = {
        key: mesh_source_throw(
            geometry, name, size=plan.options, cache_dir=plan.cache_dir, max_elements=plan.max_elements
        )
        for key, name in plan.throws.items()
    }
    if plan.shaft is None:
        return Meshes(throws)
    t0 = time.perf_counter()
    shaft = mesh_source_shaft(
        geometry,
        plan.shaft,
        size=plan.options,
        cache_dir=plan.cache_dir,
        max_elements=plan.max_elements,
        features=features,
    )
    return Meshes(throws, shaft, time.perf_counter() - t0)


__all__ = ["GeometrySource", "Meshes", "mesh_models", "mesh_source_shaft", "mesh_source_throw"]
