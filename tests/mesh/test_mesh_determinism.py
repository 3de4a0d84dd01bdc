"""The same input gives the same mesh bit for bit, whichever process builds it.

Each mesh is built in a fresh Python process (its own memory layout, hash seed and gmsh
state), without the cache, and compared exactly (node coordinates, element arrays, named
groups) with the run's own build of it: the one in the run's shared mesh cache, which the
test process or another process of the run built (a process that has meshed other
throws before: another memory layout and gmsh history), or, when no file has taken it
yet, the test process's build into that cache.  The cache keeps the arrays as built
(``mesh.npz``), so what is compared is two processes' builds.  The shipped inline-4's
throw is meshed as the whole shaft meshes it (end faces split into sectors so the turned
throws meet node to node: the part whose surface mesh used to depend on the order of
objects in memory), the single-cylinder throw as its load case meshes it.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from helpers.mesh_arrays import mesh_arrays
from helpers.shared import locked

ROOT = Path(__file__).resolve().parents[2]

BUILD = """
import sys
import numpy as np
sys.path.insert(0, sys.argv[1])
from helpers.mesh_arrays import mesh_arrays

for case, out, mode in zip(sys.argv[2::3], sys.argv[3::3], sys.argv[4::3]):
    np.savez(out, **mesh_arrays(case, mode, None))
"""

#: the meshes compared: the inline-4's throw as the whole shaft meshes it, the single
#: cylinder's as its load case does; with the run's lock of each mesh in the shared cache
#: (``None``: none taken, the cache takes concurrent writers)
MESHES = {
    "inline4": ("inline4_rated.toml", "shaft", None),
    "single": ("single_cylinder.toml", "throw", "single_cylinder_test_meshes"),
}


def _build(folder: Path) -> dict[str, dict[str, np.ndarray]]:
    """Every mesh of ``MESHES`` built without the cache in one fresh Python process, by name."""
    env = dict(os.environ, PYTHONPATH=str(ROOT), OPENBLAS_NUM_THREADS="1")
    env.pop("PYTHONHASHSEED", None)  # the process its own hash seed
    folder.mkdir()
    args = [
        a
        for name, (case, mode, _) in MESHES.items()
        for a in (str(ROOT / "loadcases" / case), str(folder / f"{name}.npz"), mode)
    ]
    subprocess.run(
        [sys.executable, "-c", BUILD, str(ROOT / "tests"), *args], check=True, env=env, cwd=ROOT, timeout=600
    )
    out = {}
    for name in MESHES:
        with np.load(folder / f"{name}.npz") as z:
            out[name] = {k: z[k] for k in z.files}
    return out


def _run_build(tmp_path_factory, mesh_cache: Path) -> dict[str, dict[str, np.ndarray]]:
    """Every mesh of ``MESHES`` as the run's shared mesh cache holds it (built here into
    it when no process of the run has yet), by name."""
    out = {}
    for name, (case, mode, lock) in MESHES.items():
        path = ROOT / "loadcases" / case
        if lock is None:
            out[name] = mesh_arrays(path, mode, mesh_cache)
        else:
            with locked(tmp_path_factory, lock):
                out[name] = mesh_arrays(path, mode, mesh_cache)
    return out


@pytest.mark.heavy
def test_a_mesh_is_the_same_in_two_processes(tmp_path, tmp_path_factory, mesh_cache):
    first, second = _build(tmp_path / "fresh"), _run_build(tmp_path_factory, mesh_cache)
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
