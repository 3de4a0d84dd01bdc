"""The determinate support on the shipped single-cylinder throw (real gmsh mesh, `test`
preset) against hand calculations and the IACS UR M53 empirical SCFs; the hot-spot
convergence study on the same throw."""

from __future__ import annotations

import numpy as np
import pytest
from helpers.paths import ROOT
from helpers.verification_meshes import Steel

from fe_crank.assess.adapters import m53_geometry_of
from fe_crank.fe import FeOptions, solve_unit_cases
from fe_crank.fe.core.supports import boundary_facets
from fe_crank.fe.refinement.convergence import (
    FILLETS,  # the four shaft fillets of a throw
    fillet_convergence,
    peak_fillet_stress,
)
from fe_crank.io.geometry import load_geometry
from fe_crank.mesh import PRESETS, mesh_throw
from fe_crank.rules.m53 import calculation as m53


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    return tmp_path_factory.mktemp("meshes")


@pytest.fixture(scope="module")
def geometry():
    return load_geometry(ROOT / "geometry" / "single_cylinder.toml")


@pytest.fixture(scope="module")
def solved(geometry, cache):
    tm = mesh_throw(geometry, size="test", cache_dir=cache)
    return tm, solve_unit_cases(tm, Steel(), FeOptions(cases=("pin_-y", "torque")))


def test_reactions_at_the_bearing_centres_of_the_shipped_throw(geometry, solved):
    """geometry/single_cylinder.toml: pin 36 mm long, webs 22 mm, journals 25 mm
    with 4 mm fillets.  Journal_1 spans z = -(18 + 22 + 25) = -65 mm to -40 mm: half a main
    bearing (docs/geometry.md), so the main-bearing centre is the end face, -65 mm.  A unit
    pin force at z_p = 0 gives R_1 = R_2 = F (65 - 0) / 130 = 0.5 F, acting at -65 and
    +65 mm."""
    _, u = solved
    c = u.cases["pin_-y"]
    zc = -(0.018 + 0.022 + 0.025)
    for j, z in (("journal_1", zc), ("journal_2", -zc)):
        r = c.reactions[j]
        assert r[1] == pytest.approx(0.5, abs=1e-4)  # mesh asymmetry of the oil bore only
        assert -r[3] / r[1] == pytest.approx(z, abs=1e-5)  # line of action: M_x = -z R_y
        assert u.bearing_centres[j] == pytest.approx(z, abs=1e-5)
    assert np.abs(c.reactions["point_constraints"]).max() < 1e-9  # N and N m, for a 1 N load
    assert c.equilibrium_error < 1e-6 and u.cases["torque"].equilibrium_error < 1e-6


def test_fillet_stress_of_three_point_bending_against_ur_m53(geometry, solved):
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
    tm, u = solved
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


def test_convergence_study_refines_the_fillets(geometry, solved, cache):
    """Two levels from the `test` preset (fillet edge r and r/2).  The first level is the
    mesh above, given with its solution as the check gives its own (that a fresh solve of
    it gives the same peaks is tests/pipeline/test_pipeline_convergence_reuse.py's): its
    peak equals the one computed directly; the change is |p2 - p1| / p2 by hand; the
    fillet edges of the second level are about half those of the first."""
    tm, u = solved
    study = fillet_convergence(
        geometry, Steel(), base=PRESETS["test"], factors=(1.0, 2.0), cache_dir=cache, first=(tm, u)
    )
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
