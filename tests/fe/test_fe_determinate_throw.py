"""The determinate support on the shipped single-cylinder throw (real gmsh mesh, `test`
preset) against hand calculations and the IACS UR M53 empirical SCFs; the hot-spot
convergence study on the same throw, and its reuse of the check's own solution.

The study's first level is the check's mesh (same mesh options, hence the same cached
mesh); given the check's solution it must neither mesh nor solve again and must give the
peak that solution gives, and the same peaks as a study that solves it afresh (to the
PARDISO solve's round-off: the solution of a column depends in its last bits on the other
right-hand sides solved with it).  One solution of the `test` mesh (the check's, more
unit cases than the study needs) and one study reusing it serve every test here.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from helpers.paths import ROOT
from helpers.verification_meshes import Steel

from fe_crank.assess.adapters import m53_geometry_of
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
from fe_crank.rules.m53 import calculation as m53


@pytest.fixture(scope="module")
def cache(mesh_cache):
    """The run's mesh cache: the `test` mesh of the shipped throw and its r/2 level are
    the ones the zone-study tests mesh too."""
    return mesh_cache


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


@pytest.fixture(scope="module")
def study(geometry, cache, check_solution):
    """The hot-spot study from the `test` preset (fillet edge r and r/2) given the check's
    solution, as the check runs it: its first level is that solution."""
    return fillet_convergence(
        geometry, Steel(), base=PRESETS["test"], factors=(1.0, 2.0), cache_dir=cache, first=check_solution
    )


def test_reactions_at_the_bearing_centres_of_the_shipped_throw(geometry, check_solution):
    """geometry/single_cylinder.toml: pin 36 mm long, webs 22 mm, journals 25 mm
    with 4 mm fillets.  Journal_1 spans z = -(18 + 22 + 25) = -65 mm to -40 mm: half a main
    bearing (docs/geometry.md), so the main-bearing centre is the end face, -65 mm.  A unit
    pin force at z_p = 0 gives R_1 = R_2 = F (65 - 0) / 130 = 0.5 F, acting at -65 and
    +65 mm."""
    _, u = check_solution
    c = u.cases["pin_-y"]
    zc = -(0.018 + 0.022 + 0.025)
    for j, z in (("journal_1", zc), ("journal_2", -zc)):
        r = c.reactions[j]
        assert r[1] == pytest.approx(0.5, abs=1e-4)  # mesh asymmetry of the oil bore only
        assert -r[3] / r[1] == pytest.approx(z, abs=1e-5)  # line of action: M_x = -z R_y
        assert u.bearing_centres[j] == pytest.approx(z, abs=1e-5)
    assert np.abs(c.reactions["point_constraints"]).max() < 1e-9  # N and N m, for a 1 N load
    assert c.equilibrium_error < 1e-6 and u.cases["torque"].equilibrium_error < 1e-6


def test_fillet_stress_of_three_point_bending_against_ur_m53(geometry, check_solution):
    """Unit radial pin force (three-point bending of the determinate throw) vs UR M53.

    Nominal stresses of UR M53 2.1.2 at the web centre (z_w = -(18 + 11) = -29 mm):
    M_BN = R_1 (z_w - z_1) = 0.5 N x 36 mm, sigma_BN = M_BN / (B W^2 / 6),
    sigma_QN = R_1 / (B W), B = 80 mm (stadium web), W = 22 mm.  Fillet stresses of
    UR M53 3.2/3.3/5: crankpin sigma = alpha_B sigma_BN, journal sigma = beta_B sigma_BN +
    beta_Q sigma_QN, with the empirical alpha_B, beta_B, beta_Q of ``rules.m53.calculation`` (the
    geometry is inside their validity range: s = -0.18, w = 0.44, b = 1.6, r = 0.08).
    FE: the largest principal stress magnitude on each fillet.  Measured on this `test`
    mesh: crankpin 1.05, journal 0.92-0.94 of the M53 values; the M53 fit itself scatters
    about 10 % about the measurements it came from, hence 15 %."""
    tm, u = check_solution
    geo = m53_geometry_of(geometry)
    rel_p, rel_j = geo.related("pin"), geo.related("journal")
    assert not m53.out_of_range(rel_p) and not m53.out_of_range(rel_j)
    c = u.cases["pin_-y"]
    r1 = c.reactions["journal_1"][1]
    z_w = -(0.018 + 0.011)
    m_bn = r1 * (z_w - u.bearing_centres["journal_1"])
    assert m_bn == pytest.approx(0.5 * 0.036, rel=1e-3)
    s_bn = m_bn / (geo.web_width * geo.web_thickness**2 / 6)
    s_qn = r1 / (geo.web_width * geo.web_thickness)
    s = u.stress_at_nodes(c.displacement)
    p = u.principal(s)
    mag = np.maximum(np.abs(p[0]), np.abs(p[2]))
    expected = {"crankpin": m53.alpha_b(rel_p) * s_bn, "journal": m53.beta_b(rel_j) * s_bn + m53.beta_q(rel_j) * s_qn}
    for f in FILLETS:
        nodes = u.system.basis.get_dofs(boundary_facets(tm.mesh, f, "test")).all()
        ref = expected[f.split("_")[0]]
        assert mag[nodes].max() / ref == pytest.approx(1.0, abs=0.15), f


@pytest.mark.heavy  # the study: the r/2 level meshed and solved
def test_convergence_study_refines_the_fillets(check_solution, study):
    """Two levels from the `test` preset (fillet edge r and r/2).  The first level is the
    mesh above, given with its solution as the check gives its own (that a fresh solve of
    it gives the same peaks: ``test_first_level_reuses_the_check_solution``): its peak
    equals the one computed directly; the change is |p2 - p1| / p2 by hand; the fillet
    edges of the second level are about half those of the first."""
    tm, u = check_solution
    assert [lv.reused for lv in study.levels] == [True, False]
    assert [lv.fillet_divisions for lv in study.levels] == [1.0, 2.0]
    direct, _ = peak_fillet_stress(u, u.displacement("pin_-y"))
    assert study.levels[0].peaks["pin_-y"] == pytest.approx(direct, rel=1e-9)
    for name in ("pin_-y", "torque"):
        p1, p2 = (lv.peaks[name] for lv in study.levels)
        assert study.changes[name] == [pytest.approx(abs(p2 - p1) / p2, rel=1e-12)]
    assert study.change == max(c[-1] for c in study.changes.values())
    assert study.converged == (study.change <= 0.05)
    e1, e2 = (max(lv.fillet_max_edge.values()) for lv in study.levels)
    assert e2 < 0.75 * e1
    assert study.levels[1].n_dof > study.levels[0].n_dof
    d = study.to_dict()
    assert d["fillet_size"] == ["r/1", "r/2"] and d["converged"] == study.converged
    # the counterweights' transition fillets and the oil-bore outlet are followed as load sets of their own
    assert set(d["peaks"]) == {
        *("pin_-y", "torque", "counterweight fillets, pin_-y", "counterweight fillets, torque"),
        *("oil bore, pin_-y", "oil bore, torque"),
    }
    assert d["bore_divisions"] == [6.0, 12.0] and study.assessed_change == study.change  # two levels
    assert len(d["peaks"]["torque"]) == 2


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


@pytest.mark.heavy  # the study solved afresh: two more factorisations
def test_first_level_reuses_the_check_solution(geometry, cache, check_solution, study):
    tm, units = check_solution
    reused = study
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
