"""A throw mesh of a shipped load case as plain arrays, for comparing two builds bit for
bit (tests/mesh/test_mesh_determinism.py builds it in a fresh Python process and in the
test's own, so both take this one function)."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def mesh_arrays(case: str | Path, mode: str, cache_dir: str | Path | None) -> dict[str, np.ndarray]:
    """The first throw of load case ``case`` meshed at ``test`` (``mode`` "shaft": as the
    whole shaft meshes it, its end faces split into sectors; "throw": as the load case
    does), through the mesh cache ``cache_dir`` (``None``: built afresh, no cache): the
    node coordinates, the elements, the straightened count and the named groups."""
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mesh import mesh_throw
    from fe_crank.mesh.options import resolve_options

    lc = load_loadcase(case)
    g, spec, opt = lc.geometry, lc.geometry.throws[0], resolve_options("test")
    if mode == "shaft":
        from fe_crank.geometry.shaft import engine_shaft_layout
        from fe_crank.mesh.shaft import shaft_options

        layout = engine_shaft_layout(g, lc.engine, geometry_file="g", engine_file="e")
        g, spec, opt = layout.geometry, layout.throws[0].spec, shaft_options(layout, "test")
    tm = mesh_throw(g, spec, size=opt, cache_dir=cache_dir)
    m = tm.mesh
    arrays = {"doflocs": m.doflocs, "t": m.t, "straightened": np.array(tm.stats.straightened)}
    arrays.update({"b::" + k: v for k, v in m.boundaries.items()})
    arrays.update({"s::" + k: v for k, v in m.subdomains.items()})
    return arrays
