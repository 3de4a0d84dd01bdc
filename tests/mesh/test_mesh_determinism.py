"""The same input gives the same mesh bit for bit, whichever process builds it.

Each mesh is built twice, each time in a fresh Python process (its own memory layout,
hash seed and gmsh state; each of the two processes builds both meshes), without the cache, and the node coordinates, the element
arrays and the named groups are compared exactly.  The shipped inline-4's throw is
meshed as the whole shaft meshes it (end faces split into sectors so the turned throws
meet node to node: the part whose surface mesh used to depend on the order of objects
in memory), the single-cylinder throw as its load case meshes it.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]

BUILD = """
import sys
import numpy as np
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mesh import mesh_throw
from fe_crank.mesh.options import resolve_options

for case, out, mode in zip(sys.argv[1::3], sys.argv[2::3], sys.argv[3::3]):
    lc = load_loadcase(case)
    g, spec, opt = lc.geometry, lc.geometry.throws[0], resolve_options("test")
    if mode == "shaft":
        from fe_crank.geometry.shaft import engine_shaft_layout
        from fe_crank.mesh.shaft import shaft_options

        layout = engine_shaft_layout(g, lc.engine, geometry_file="g", engine_file="e")
        g, spec, opt = layout.geometry, layout.throws[0].spec, shaft_options(layout, "test")
    tm = mesh_throw(g, spec, size=opt, cache_dir=None)
    m = tm.mesh
    arrays = {"doflocs": m.doflocs, "t": m.t, "straightened": np.array(tm.stats.straightened)}
    arrays.update({"b::" + k: v for k, v in m.boundaries.items()})
    arrays.update({"s::" + k: v for k, v in m.subdomains.items()})
    np.savez(out, **arrays)
"""

#: the meshes compared: the inline-4's throw as the whole shaft meshes it, the single
#: cylinder's as its load case does (both built in each of the two processes)
MESHES = {"inline4": ("inline4_rated.toml", "shaft"), "single": ("single_cylinder.toml", "throw")}


def _build(folder: Path) -> dict[str, dict[str, np.ndarray]]:
    """Every mesh of ``MESHES`` built in one fresh Python process, by name."""
    env = dict(os.environ, PYTHONPATH=str(ROOT), OPENBLAS_NUM_THREADS="1")
    env.pop("PYTHONHASHSEED", None)  # each process its own hash seed
    folder.mkdir()
    args = [
        a
        for name, (case, mode) in MESHES.items()
        for a in (str(ROOT / "loadcases" / case), str(folder / f"{name}.npz"), mode)
    ]
    subprocess.run([sys.executable, "-c", BUILD, *args], check=True, env=env, cwd=ROOT, timeout=600)
    out = {}
    for name in MESHES:
        with np.load(folder / f"{name}.npz") as z:
            out[name] = {k: z[k] for k in z.files}
    return out


@pytest.mark.heavy
def test_a_mesh_is_the_same_in_two_fresh_processes(tmp_path):
    first, second = _build(tmp_path / "a"), _build(tmp_path / "b")
    for mesh in MESHES:
        a, b = first[mesh], second[mesh]
        assert sorted(a) == sorted(b), mesh
        for name in a:
            assert a[name].dtype == b[name].dtype, (mesh, name)
            assert a[name].shape == b[name].shape, (mesh, name)
            assert np.array_equal(a[name], b[name]), (mesh, name)  # bit for bit: no tolerance


def test_the_cache_key_holds_what_the_mesher_depends_on():
    import gmsh

    from fe_crank.gmsh_io import SESSION_OPTIONS
    from fe_crank.mesh.cache import mesher_key
    from fe_crank.mesh.options import CACHE_FORMAT, GENERATE_OPTIONS
    from fe_crank.version import __version__

    key = mesher_key()
    assert key["gmsh"] == gmsh.__version__ and key["fe_crank"] == __version__ and key["format"] == CACHE_FORMAT
    for name, value in {**SESSION_OPTIONS, **GENERATE_OPTIONS}.items():
        assert key["gmsh_options"][name] == value
    assert SESSION_OPTIONS["General.NumThreads"] == 1 and GENERATE_OPTIONS["Mesh.RandomSeed"] == 1


def test_a_cad_mesh_key_moves_with_the_mesher_options(monkeypatch):
    """The CAD route's cache key holds the same mesher key as the parametric route's: a
    changed gmsh generation option gives another key (no mesh of other options reused)."""
    from fe_crank.cad.config import CadInput
    from fe_crank.cad.mesh import cad_cache_key
    from fe_crank.mesh import options

    cad = CadInput(file=Path("crank.step"), density=7850.0)
    opt = options.resolve_options("test")
    before = cad_cache_key(cad, "0" * 64, "1", opt)
    assert cad_cache_key(cad, "0" * 64, "1", opt) == before
    monkeypatch.setitem(options.GENERATE_OPTIONS, "Mesh.RandomSeed", 2)
    assert cad_cache_key(cad, "0" * 64, "1", opt) != before
