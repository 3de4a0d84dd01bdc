"""The hot-spot convergence study reuses the check's own solution as its first level.

Real gmsh meshes of the shipped single-cylinder throw (`test` preset and its fillets at
r/2) and real PARDISO solves.  The first level of the study is the check's mesh (same
mesh options, hence the same cached mesh); given the check's solution it must neither
mesh nor solve again and must give the peak that solution gives, and the same peaks as
a study that solves it afresh (to the PARDISO solve's round-off: the solution of a
column depends in its last bits on the other right-hand sides solved with it).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from helpers.paths import ROOT
from helpers.verification_meshes import Steel

from fe_crank.fe import FeOptions, solve_unit_cases
from fe_crank.fe.core.supports import boundary_facets
from fe_crank.fe.refinement.convergence import (  # FILLETS: the four shaft fillets of a throw
    FILLETS,
    _reusable,
    fillet_convergence,
    peak_fillet_stress,
)
from fe_crank.io.geometry import load_geometry
from fe_crank.mesh import PRESETS, mesh_throw

pytestmark = pytest.mark.heavy  # two meshes of the shipped throw, three factorisations


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    return tmp_path_factory.mktemp("meshes")


@pytest.fixture(scope="module")
def geometry():
    return load_geometry(ROOT / "geometry" / "single_cylinder.toml")


@pytest.fixture(scope="module")
def check_solution(geometry, cache):
    """What the check's FE stage hands on: its mesh and its unit solutions (more cases than
    the study needs), with the factor already released as the check does."""
    tm = mesh_throw(geometry, size="test", cache_dir=cache)
    units = solve_unit_cases(tm, Steel(), FeOptions(cases=("centrifugal", "pin_-y", "pin_x", "torque")))
    units.system.factorisation.free()
    return tm, units


def test_peak_at_the_fillet_nodes_equals_the_whole_mesh_average(check_solution):
    _, units = check_solution
    u = units.displacement("pin_-y")
    peak, where = peak_fillet_stress(units, u)
    vm = units.von_mises(units.stress_at_nodes(u))  # every node of the mesh, then the fillets
    mesh, basis = units.mesh, units.system.basis
    full = {f: vm[basis.get_dofs(boundary_facets(mesh, f, "test")).all()].max() for f in FILLETS}
    best = max(full, key=full.get)
    # the throw is a mirror image across its mid-plane: a fillet and its mirror image carry
    # equal peaks, and the summation order decides which of the two is found first
    assert _mirror_pair(where) == _mirror_pair(best)
    assert full[where] == pytest.approx(full[best], rel=1e-12)
    assert peak == pytest.approx(full[best], rel=1e-12)  # summation order of the nodal average only


def test_first_level_reuses_the_check_solution(geometry, cache, check_solution):
    tm, units = check_solution
    reused = fillet_convergence(
        geometry, Steel(), base=PRESETS["test"], factors=(1.0, 2.0), cache_dir=cache, first=check_solution
    )
    fresh = fillet_convergence(geometry, Steel(), base=PRESETS["test"], factors=(1.0, 2.0), cache_dir=cache)
    # one mesh and one solve fewer: the first level is the check's (its factor is released,
    # so a solve there would have raised), the second is solved as before
    assert [lv.reused for lv in reused.levels] == [True, False]
    assert [lv.reused for lv in fresh.levels] == [False, False]
    assert reused.levels[0].n_dof == units.n_dof == fresh.levels[0].n_dof
    for name in ("pin_-y", "torque"):
        direct, _ = peak_fillet_stress(units, units.displacement(name))
        assert reused.levels[0].peaks[name] == direct
        # the fresh level solves 2 right-hand sides, the check 4: the PARDISO solutions differ
        # by round-off (relative residual < 1e-8 is checked; observed ~1e-13)
        assert reused.levels[0].peaks[name] == pytest.approx(fresh.levels[0].peaks[name], rel=1e-9)
        # two solves of the same system: equal up to PARDISO's threaded round-off (2e-12 seen
        # on the single-cylinder mesh with its counterweight fillets)
        assert reused.levels[1].peaks[name] == pytest.approx(fresh.levels[1].peaks[name], rel=1e-9)
    # where each peak is: the same fillet up to its mirror image (the throw is symmetric
    # across its mid-plane, so a fillet and its mirror image carry equal peaks and the
    # solve's round-off decides which of the two is reported), every peak to round-off
    for level in (0, 1):
        r, f = reused.levels[level], fresh.levels[level]
        assert set(r.where) == set(f.where) == set(r.peaks)
        for key in r.where:
            assert _mirror_pair(r.where[key]) == _mirror_pair(f.where[key]), (level, key)
            assert r.peaks[key] == pytest.approx(f.peaks[key], rel=1e-9), (level, key)
    assert reused.converged == fresh.converged


def _mirror_pair(fillet: str) -> str:
    """A fillet's name without its side: ``crankpin_fillet_1`` and ``crankpin_fillet_2``
    are mirror images of each other across the throw's mid-plane (the oil bore, at
    mid-length, is its own image)."""
    if fillet == "oil_bore":
        return fillet
    assert fillet.endswith(("_1", "_2")), fillet
    return fillet[:-2]


def test_reuse_only_for_the_same_mesh_support_and_cases(check_solution):
    tm, units = check_solution
    opts = FeOptions(cases=("pin_-y", "torque"))
    assert _reusable(check_solution, tm.options, opts)
    finer = dataclasses.replace(tm.options, fillet_divisions=tm.options.fillet_divisions * 1.5)
    assert not _reusable(check_solution, finer, opts)  # another mesh
    assert not _reusable(check_solution, tm.options, FeOptions(cases=("pin_y",)))  # a case not solved
    assert not _reusable(
        check_solution, tm.options, dataclasses.replace(opts, torque_reaction="end_1")
    )  # another support
    assert not _reusable(None, tm.options, opts)
    assert np.all(np.isfinite(units.displacement("torque")))
