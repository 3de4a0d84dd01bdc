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
from helpers.cad_files import layout_step, parametric_step
from helpers.paths import ROOT
from helpers.shared import copy_of, shared_file, shared_value

from fe_crank.cad import CadFeatures, CadInput, recognise
from fe_crank.geometry.shaft import ShaftLayout, engine_shaft_layout
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.io.engine import load_engine
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


@pytest.fixture(scope="session")
def inline4_throw_step(tmp_path_factory) -> tuple[CrankGeometry, Path]:
    """``geometry/inline4.toml`` and one throw of it exported to STEP, once in the run."""
    g = load_geometry(ROOT / "geometry" / "inline4.toml")
    return g, shared_file(tmp_path_factory, "inline4_throw.step", lambda p: parametric_step(g, p))


@pytest.fixture(scope="session")
def inline4_drawing(tmp_path_factory) -> tuple[ShaftLayout, Path, CadFeatures]:
    """The shipped inline-4's whole shaft (``geometry/inline4.toml`` on the throws of
    ``engines/inline4.toml``, ``engine_shaft_layout``: the solid
    ``loadcases/inline4_rated.toml`` places too) written to ``inline4.step`` with a nose
    (40 mm across, 30 mm long) and a flange (100 mm, 12 mm), and what ``recognise`` finds in
    it at the geometry's density: both once in the run.  Recognition reads the file and the
    ``[cad]`` keys that describe it (density, unit, axis, throws, bodies, recesses), not the
    bearings a drawn shaft is given (``[cad.shaft]``, ``bearing_width``: the whole-shaft
    stage's), so these features are also those of the file with its bearings stated.
    Returns the layout, the file (copy it where a test needs it, ``helpers.shared.copy_of``,
    keeping its name) and the features."""
    g = load_geometry(ROOT / "geometry" / "inline4.toml")
    engine = load_engine(ROOT / "engines" / "inline4.toml")
    layout = engine_shaft_layout(g, engine, geometry_file="g", engine_file="e")
    step = shared_file(
        tmp_path_factory,
        "inline4.step",
        lambda p: layout_step(layout, p, nose=(0.04, 0.03), flange=(0.1, 0.012)),
    )
    features = shared_value(
        tmp_path_factory, "inline4.features.pickle", lambda: recognise(CadInput(step, density=g.density))
    )
    return layout, step, features
