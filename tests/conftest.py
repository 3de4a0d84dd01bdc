"""Shared test helpers.  Keep fixtures small: tests mirror the pipeline stages."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

os.environ.setdefault("PYVISTA_OFF_SCREEN", "true")

ROOT = Path(__file__).resolve().parents[1]
SEEDS = ROOT.parent / "shared" / "seeds"


@pytest.fixture
def root() -> Path:
    return ROOT


@pytest.fixture(scope="session")
def mesh_cache(tmp_path_factory) -> Path:
    """The run's mesh cache for the tests that run the check's stages on the same
    geometries, shared by the run's processes (``helpers.shared``): a mesh is built once
    in the run and read back after, whichever process needs it (the cache key holds
    everything that changes a mesh, and entries are renamed into place whole,
    ``fe_crank.mesh.cache``).  Tests of the cache itself use their own folders."""
    from helpers.shared import shared_mesh_cache

    return shared_mesh_cache(tmp_path_factory)


@pytest.fixture(scope="session")
def big_fillet(tmp_path_factory):
    """geometry_small with 3.8 mm fillets, outside UR M53 3.1's range, on a coarse mesh
    (``helpers.scf.big_fillet_throw``): the geometry and its ThrowMesh."""
    from helpers.scf import big_fillet_throw

    return big_fillet_throw(tmp_path_factory.mktemp("big_fillet_cache"))


@pytest.fixture(scope="session")
def big_fillet_scf(big_fillet):
    """The SCF mode on ``big_fillet``'s coarse mesh as it is (``helpers.scf.big_fillet_scf``):
    solved once for the tests of a process that read it."""
    from helpers.scf import big_fillet_scf

    return big_fillet_scf(*big_fillet)


@pytest.fixture(scope="session")
def filleted_throw():
    """The FE stage's unit solutions of ``simple_throw`` with 4 mm fillets (real gmsh mesh,
    12 mm elements, 4 mm at the fillets; SuperLU): centrifugal, four pin directions, torque."""
    from helpers.verification_meshes import Steel, as_throw_mesh, simple_throw

    from fe_crank.fe import FeOptions, solve_unit_cases

    mesh = simple_throw(size=0.012, fillet=0.004, fillet_size=0.004)
    cases = ("centrifugal", "pin_x", "pin_y", "pin_-x", "pin_-y", "torque")
    return solve_unit_cases(as_throw_mesh(mesh), Steel(), FeOptions(solver="superlu", cases=cases))


@pytest.fixture(scope="session")
def filleted_throw_cycle(filleted_throw):
    """The unit stresses at the assessed nodes of ``filleted_throw`` and the load
    coefficients of a 72-angle, 720-degree cycle: pin force (3 sin t, 20 cos t + 5) kN,
    torque 400 sin 2t N m, 300 rad/s."""
    import numpy as np

    from fe_crank.assess import unit_stresses
    from fe_crank.assess.superpose import load_coefficients

    us = unit_stresses(filleted_throw)
    th = np.linspace(0.0, 4 * np.pi, 72, endpoint=False)
    pin = np.column_stack([3e3 * np.sin(th), 2e4 * np.cos(th) + 5e3])
    co = load_coefficients(pin, 400.0 * np.sin(2 * th), 300.0, cases=us.cases, torque_mz=us.torque_mz)
    return us, co


@pytest.fixture(autouse=True)
def _refusals_without_library_internals(monkeypatch):
    """Every ``InputError`` any test provokes (the whole bad-input set of the suite) is
    checked: its message names no pydantic union member and no input class
    (``tests/helpers/messages.py``)."""
    from helpers.messages import internals

    from fe_crank.errors import InputError

    made: list[str] = []
    original = InputError.__init__

    def observed(self, message, **kwargs):
        original(self, message, **kwargs)
        made.append(str(self))

    monkeypatch.setattr(InputError, "__init__", observed)
    yield
    bad = [(m, internals(m)) for m in made if internals(m)]
    assert not bad, f"refusal messages with library internals: {bad}"


def pytest_collection_modifyitems(session, config, items):
    """The test files in the order of their count of ``heavy`` tests, most first (the
    collection order among equals, and within a file, kept): ``make test`` hands whole
    files to its two workers (``--dist loadfile``, so a file's module fixtures are built
    once, on one worker), and the longest files started first leave the shortest for the
    end, where they fill the gap between the workers."""
    heavy: dict[str, int] = {}
    first: dict[str, int] = {}
    for i, item in enumerate(items):
        path = str(item.path)
        first.setdefault(path, i)
        heavy[path] = heavy.get(path, 0) + (item.get_closest_marker("heavy") is not None)
    items.sort(key=lambda item: (-heavy[str(item.path)], first[str(item.path)]))
