"""The CAD files the CAD tests share, written once per run (``helpers.shared``).

A STEP file's header holds the time it was written, so two exports of one solid differ
in their bytes and hence in their mesh cache keys (``fe_crank.cad.mesh.cad_cache_key``
hashes the file).  One file, meshed into the run's shared ``mesh_cache``, lets the
tests that mesh it at the same options build that mesh once and read it back
after, whichever process runs them; the tests of the cache itself use folders of their
own."""

from __future__ import annotations

from pathlib import Path

import pytest
from helpers.cad_files import parametric_step
from helpers.paths import ROOT
from helpers.shared import copy_of, shared_file

from fe_crank.geometry.spec import CrankGeometry
from fe_crank.io.geometry import load_geometry


@pytest.fixture(scope="session")
def small_throw_step(tmp_path_factory) -> tuple[CrankGeometry, Path]:
    """``tests/data/geometry_small.toml`` and its throw exported to ``throw.step`` (a folder
    of its own: a test may write a TOML file beside it)."""
    g = load_geometry(ROOT / "tests" / "data" / "geometry_small.toml")
    step = shared_file(tmp_path_factory, "small_throw.step", lambda p: parametric_step(g, p))
    return g, copy_of(step, tmp_path_factory.mktemp("small_throw_step") / "throw.step")


@pytest.fixture(scope="session")
def single_cylinder_step(tmp_path_factory) -> tuple[CrankGeometry, Path]:
    """``geometry/single_cylinder.toml`` and its throw exported to STEP, once in the run
    (copy it where a test needs it: ``helpers.shared.copy_of``)."""
    g = load_geometry(ROOT / "geometry" / "single_cylinder.toml")
    return g, shared_file(tmp_path_factory, "single_cylinder.step", lambda p: parametric_step(g, p))
