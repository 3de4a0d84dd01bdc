"""The CAD file the CAD tests share, written once per test process.

A STEP file's header holds the time it was written, so two exports of one solid differ
in their bytes and hence in their mesh cache keys (``fe_crank.cad.mesh.cad_cache_key``
hashes the file).  One file, meshed into the suite's ``mesh_cache``, lets the
tests that mesh it at the same options build that mesh once and read it back
after; the tests of the cache itself use folders of their own."""

from __future__ import annotations

from pathlib import Path

import pytest
from helpers.cad_files import parametric_step
from helpers.paths import ROOT

from fe_crank.geometry.spec import CrankGeometry
from fe_crank.io.geometry import load_geometry


@pytest.fixture(scope="session")
def small_throw_step(tmp_path_factory) -> tuple[CrankGeometry, Path]:
    """``tests/data/geometry_small.toml`` and its throw exported to ``throw.step`` (a folder
    of its own: a test may write a TOML file beside it)."""
    g = load_geometry(ROOT / "tests" / "data" / "geometry_small.toml")
    return g, parametric_step(g, tmp_path_factory.mktemp("small_throw_step") / "throw.step")
