"""``assess.group.nodes`` on the small bar 'throw' of test_assess_case.py (real mesh, real
scikit-fem solve): which groups are taken and which nodes they hold, against the mesh
geometry, and the unit stresses' bookkeeping against the whole-mesh nodal average.

The bar's counterweight is the subdomain z < L/6 and its web L/6 < z < L/3: their
junction is the plane z = L/6, so its nodes are exactly the P2 nodes (vertices and edge
midpoints) with z = L/6 -- found here from the coordinates (1e-12 m: the nodes' z are
exact multiples of L/24).
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers.bar_throw import L
from helpers.bar_throw import bar_throw as _bar
from helpers.verification_meshes import as_throw_mesh

import fe_crank.fe.throw.unit_cases as fe
from fe_crank.assess.group.nodes import assessed_groups, unit_stresses
from fe_crank.errors import InputError
from fe_crank.io.material import load_material


@pytest.fixture(scope="module")
def units():
    return fe.solve_unit_cases(as_throw_mesh(_bar()), load_material("42CrMo4"), fe.FeOptions(solver="superlu"))


def test_groups_of_the_bar_and_their_nodes(units):
    groups = assessed_groups(units)
    assert list(groups) == ["crankpin_fillet_1", "journal_fillet_2", "counterweight_1", "junction_1"]
    z = units.points[2]
    # fillet: every P2 node of the boundary's facets (vertices and edge midpoints)
    facets = units.mesh.boundaries["crankpin_fillet_1"]
    expected = np.unique(
        np.concatenate([units.mesh.facets[:, facets].ravel(), units.mesh.nvertices + units.mesh.f2e[:, facets].ravel()])
    )
    np.testing.assert_array_equal(groups["crankpin_fillet_1"], expected)
    assert np.all(np.abs(z[groups["crankpin_fillet_1"]] - L / 3) <= L / 12 + 1e-12)
    # counterweight: every node of its elements, z <= L/6; the junction: the plane z = L/6
    cw = groups["counterweight_1"]
    assert np.all(z[cw] <= L / 6 + 1e-12)
    np.testing.assert_array_equal(cw, np.nonzero(z <= L / 6 + 1e-12)[0])
    np.testing.assert_array_equal(groups["junction_1"], np.nonzero(np.abs(z - L / 6) < 1e-12)[0])
    assert groups["junction_1"].size > 25  # the 5 x 5 vertices and the edge midpoints


def test_unit_stresses_hold_every_group_at_its_own_nodes(units):
    groups = {"journal_fillet_2": np.array([7, 3, 5]), "counterweight_1": np.array([5, 1])}
    unit = unit_stresses(units, groups)
    np.testing.assert_array_equal(unit.node_ids, [1, 3, 5, 7])
    assert {k: list(unit.node_ids[v]) for k, v in unit.groups.items()} == {
        "journal_fillet_2": [7, 3, 5],
        "counterweight_1": [5, 1],
    }
    assert unit.cases == tuple(units.cases)
    # the FE stage's torque case: M_z = -1 N m, as integrated from its face load
    assert unit.torque_mz == pytest.approx(-1.0, rel=1e-12)
    np.testing.assert_array_equal(unit.points, units.points[:, [1, 3, 5, 7]])
    for i, c in enumerate(unit.cases):
        whole = units.stress_at_nodes(units.displacement(c))[:, [1, 3, 5, 7]]
        np.testing.assert_allclose(unit.stress[i], whole, rtol=0, atol=1e-12 * np.abs(whole).max())
    # no group: the mesh's own (all of them)
    assert set(unit_stresses(units).groups) == set(assessed_groups(units))


def test_a_mesh_without_assessed_groups_is_refused(units):
    with pytest.raises(InputError) as e:
        unit_stresses(units, {})
    assert e.value.key == "geometry"
    assert str(e.value) == (
        "geometry: the mesh has none of the assessed groups (crankpin_fillet_1, "
        "crankpin_fillet_2, journal_fillet_1, journal_fillet_2, oil_bore, counterweight_fillet_1, "
        "counterweight_fillet_2, counterweight_1, counterweight_2)"
    )


def test_without_a_torque_case_the_fe_stages_convention_is_taken():
    """A solve of the centrifugal and four pin cases only: those cases, in the solve's
    order, and M_z = -1 N m for the (absent) torque case."""
    cases = ("centrifugal", "pin_x", "pin_y", "pin_-x", "pin_-y")
    units = fe.solve_unit_cases(
        as_throw_mesh(_bar()), load_material("42CrMo4"), fe.FeOptions(solver="superlu", cases=cases)
    )
    unit = unit_stresses(units, {"crankpin_fillet_1": np.array([2, 0])})
    assert unit.cases == cases and unit.torque_mz == -1.0


def test_recovery_ratios_read_from_the_unit_stresses_and_the_notes(units):
    """``recovery_ratios`` reading the assessment's unit stresses gives its own recovery's
    ratios (the same averages: 1e-12); groups without boundary facets (a counterweight
    subdomain) and cases the solve lacks give nothing.  The note: above 1.25 only, sorted
    by group, the ratio to two decimals."""
    from fe_crank.assess.recovery import RATIO_LIMIT, recovery_notes, recovery_ratios

    groups = {k: v for k, v in assessed_groups(units).items() if "fillet" in k}
    own = recovery_ratios(units, groups)
    assert set(own) == {"crankpin_fillet_1", "journal_fillet_2"} and all(r >= 1.0 for r in own.values())
    for unit in (unit_stresses(units, groups), unit_stresses(units)):
        read = recovery_ratios(units, groups, unit=unit)
        assert set(read) == set(own)
        for g in own:
            assert read[g] == pytest.approx(own[g], rel=1e-12)
    # a unit-stress set for other nodes under the same name: recovered, not read
    other = unit_stresses(units, {"crankpin_fillet_1": groups["journal_fillet_2"]})
    assert recovery_ratios(units, {"crankpin_fillet_1": groups["crankpin_fillet_1"]}, unit=other) == {
        "crankpin_fillet_1": own["crankpin_fillet_1"]
    }
    # torque alone: the largest of the cases is the reported one
    torsion = recovery_ratios(units, groups, cases=("torque",))
    bending = recovery_ratios(units, groups, cases=("pin_y",))
    for g in own:
        assert own[g] == max(torsion[g], bending[g])
    assert recovery_ratios(units, {"counterweight_1": assessed_groups(units)["counterweight_1"]}) == {}
    assert recovery_ratios(units, groups, cases=("pin_400",)) == {}
    assert RATIO_LIMIT == 1.25
    notes = recovery_notes({"oil_bore": 1.3, "journal_fillet_2": 7.5, "crankpin_fillet_1": 1.25})
    assert notes == [
        f"stress recovery: peak nodal stress at {g} is {r} x the peak at the quadrature points of its elements "
        "(unit cases); nodal peaks there are extrapolation artefacts of the mesh, treat its safety factors as "
        "unreliable (finer or better-shaped fillet elements)"
        for g, r in (("journal_fillet_2", "7.50"), ("oil_bore", "1.30"))
    ]
    assert recovery_notes({"oil_bore": 1.3}, limit=1.5) == []
