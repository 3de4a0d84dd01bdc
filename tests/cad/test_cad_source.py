"""The check's one meshing entry point (``cad.source.mesh_models``): every model of the
mesh plan, the throw models and the whole shaft, with the plan's options.

Reference: the node-to-node join of the whole shaft needs its throws' end faces split
into sectors that map onto themselves under the angles between the throws (two throws
at 0 and 180 deg: two sectors, ``mesh.interface.sectors_for``); the plan decides that
count for both models, so the per-throw model's mesh is the shaft's throw mesh (one
cache entry, one key)."""

from __future__ import annotations

import dataclasses

import numpy as np
from helpers.shaft import small_engine, small_geometry

from fe_crank.cad.source import mesh_models
from fe_crank.geometry.shaft import shaft_layout
from fe_crank.mesh.options import MeshSection
from fe_crank.mesh.plan import plan_meshes


def test_one_call_meshes_the_throw_models_and_the_whole_shaft_with_the_plans_options(mesh_cache):
    angles = [0.0, np.pi]
    engine = small_engine(angles)
    layout = shaft_layout(small_geometry(angles), engine, geometry_file="g.toml", engine_file="e.toml")
    g = layout.geometry
    names = tuple(t.name for t in engine.throws)
    section = MeshSection(size="test")
    alone = plan_meshes(g, names, section, cache_dir=str(mesh_cache))
    plan = plan_meshes(g, names, section, cache_dir=str(mesh_cache), shaft=layout)
    # the plan decides the shaft's options: the preset's with two end-face sectors
    assert alone.shaft is None and alone.options.interface_sectors == 1
    assert plan.shaft is layout and plan.options.interface_sectors == 2
    meshes = mesh_models(g, plan)
    assert meshes.shaft is not None and meshes.shaft.options == plan.options
    assert meshes.shaft_seconds > 0.0
    assert set(meshes.throws) == set(plan.throws)
    assert {tm.options for tm in meshes.throws.values()} == {plan.options}
    # both models mesh each throw once: the shaft's throw meshes are the throw models' entries
    assert set(meshes.shaft.throw_meshes) <= {tm.key for tm in meshes.throws.values()}
    assert mesh_models(g, dataclasses.replace(plan, shaft=None)).shaft is None  # the throws from the cache
