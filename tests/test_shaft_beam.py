"""The whole-shaft model on a uniform round shaft against beam theory.

A round bar of extruded pieces (``tests/shaft_helpers.py``), radius 10 mm, spans of
320 mm (slenderness 16: shear deformation changes the support reactions by well under
1 %), each bearing a distributing coupling on one layer of the journal either side of its
centre, each load one on two layers round mid-span.
"""

from __future__ import annotations

import numpy as np
import pytest
from shaft_helpers import point_loads, reactions, round_shaft, three_moment

from fe_crank.geometry.spec import BearingLaw

SPAN, RADIUS = 0.32, 0.01


@pytest.fixture(scope="module")
def three():
    return round_shaft(2, SPAN, RADIUS, layers=24)


@pytest.fixture(scope="module")
def five():
    return round_shaft(4, SPAN, RADIUS, layers=24)


def test_three_bearings_match_the_three_moment_equation(three):
    loads = {0: 1000.0}
    f, _ = reactions(point_loads(three, loads))
    R = three_moment(2, SPAN, loads)
    assert np.allclose(f[:, 1], R, atol=0.01 * 1000.0)
    assert np.abs(f[:, 0]).max() < 1e-4 * 1000.0  # sideways: the mesh's asymmetry only


def test_five_bearings_match_the_three_moment_equation(five):
    loads = {0: 1000.0, 2: 600.0, 3: -300.0}
    f, _ = reactions(point_loads(five, loads))
    R = three_moment(4, SPAN, loads)
    assert np.allclose(f[:, 1], R, atol=0.01 * 1000.0)
    assert f[:, 1].sum() == pytest.approx(1300.0, rel=1e-9)


def test_soft_equal_springs_give_the_rigid_body_reactions(five):
    """Springs 1e-5 of the shaft's stiffness: the shaft moves as a rigid body w = a + b z,
    the forces k w_j balance the load and its moment: R_j = P (1/n + (z_j - z_m)(z_p - z_m)
    / sum (z_i - z_m)^2), z_m the mean bearing position."""
    k = 1e-5 * 48 * 210e9 * np.pi * RADIUS**4 / 4 / (2 * SPAN) ** 3
    laws = [BearingLaw("spring", k)] * 5
    P, zp = 1000.0, 0.5 * SPAN
    f, _ = reactions(point_loads(five, {0: P}), laws)
    z = np.arange(5) * SPAN
    zm = z.mean()
    R = P * (1 / 5 + (z - zm) * (zp - zm) / np.sum((z - zm) ** 2))
    assert np.allclose(f[:, 1], R, atol=1e-3 * P)


def test_springs_converge_to_rigid_bearings(three):
    stiff = [BearingLaw("spring", 1e14)] * 3
    rigid, _ = reactions(point_loads(three, {0: 1000.0}))
    f, _ = reactions(point_loads(three, {0: 1000.0}), stiff)
    assert np.allclose(f, rigid, atol=1e-3 * 1000.0)


def test_a_load_below_gap_closure_is_carried_by_the_other_bearings(three):
    """Middle bearing with a clearance wider than the journal's free deflection there:
    it carries nothing, and the outer bearings carry the load of a simply supported
    beam of two spans (3/4 and 1/4 of P for a load at a quarter of it)."""
    P = 1000.0
    cases = point_loads(three, {0: P})
    rigid = [BearingLaw()] * 3
    k = 1e12
    free = cases.d_rel[1, 1, cases.index("P0")]  # deflection at the middle bearing with it absent
    assert free < 0
    wide = [rigid[0], BearingLaw("clearance", k, 2 * abs(free)), rigid[2]]
    f, d = reactions(cases, wide)
    assert np.allclose(f[:, 1], [0.75 * P, 0.0, 0.25 * P], atol=1e-9 * P)
    assert abs(d[1, 1] - free) < 1e-9 * abs(free)
    # a clearance of half the free deflection: the journal closes it, the bearing carries
    narrow = [rigid[0], BearingLaw("clearance", k, 0.5 * abs(free)), rigid[2]]
    f, d = reactions(cases, narrow)
    assert f[1, 1] > 0.05 * P
    assert np.hypot(*d[1]) == pytest.approx(0.5 * abs(free) + np.hypot(*f[1]) / k, rel=1e-6)
    assert f[:, 1].sum() == pytest.approx(P, rel=1e-9)


def test_journal_slopes_at_the_bearings(three):
    """Two equal spans L, P at the middle of the first: M_B = -3 P L / 32 (three-moment
    equation), so the slopes at the bearings are 3 P L^2 / (64 EI) (A), P L^2 / (32 EI) (B)
    and P L^2 / (64 EI) (C), A and C turning the same way, B the other (beam theory; the
    coupling's mean over its layer of journal, shear deformation neglected)."""
    from fe_crank.fe.shaft_cycle import journal_slopes, solve_cycle

    cases = point_loads(three, {0: 1000.0})
    W = np.zeros((1, len(cases.names)))
    W[0, cases.index("P0")] = 1.0
    _, d, W = solve_cycle(cases, W, [b.law for b in cases.model.mesh.layout.bearings])
    s = journal_slopes(cases, W, d)[0]
    EI = 210e9 * np.pi * RADIUS**4 / 4
    unit = 1000.0 * SPAN**2 / EI
    assert np.allclose(s[:, 1], [-3 / 64 * unit, 1 / 32 * unit, -1 / 64 * unit], rtol=0.03)
    assert np.abs(s[:, 0]).max() < 1e-3 * unit
