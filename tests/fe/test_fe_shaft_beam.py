"""The whole-shaft model on a uniform round shaft against beam theory.

A round bar of extruded pieces (``tests/helpers/shaft.py``), radius 10 mm, spans of
320 mm (slenderness 16: shear deformation changes the support reactions by well under
1 %), each bearing a distributing coupling on one layer of the journal either side of its
centre, each load one on two layers round mid-span.
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers.shaft import point_loads, reactions, round_shaft, three_moment

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
    from fe_crank.fe.shaft.cycle import journal_slopes, solve_cycle

    cases = point_loads(three, {0: 1000.0})
    W = np.zeros((1, len(cases.names)))
    W[0, cases.index("P0")] = 1.0
    _, d, W = solve_cycle(cases, W, [b.law for b in cases.model.mesh.layout.bearings])
    s = journal_slopes(cases, W, d)[0]
    EI = 210e9 * np.pi * RADIUS**4 / 4
    unit = 1000.0 * SPAN**2 / EI
    assert np.allclose(s[:, 1], [-3 / 64 * unit, 1 / 32 * unit, -1 / 64 * unit], rtol=0.03)
    assert np.abs(s[:, 0]).max() < 1e-3 * unit


def test_end_bearings_in_clearance_carry_the_statically_determinate_reactions(three):
    """Every bearing in clearance, the middle one wider than the journal's free deflection
    there: the shaft sinks until the end journals touch (the solution without clearance
    leaves every journal inside its circle, where no bearing resists a rigid motion) and
    the ends carry the simply supported beam's 3/4 and 1/4 of P; each end journal sits
    at c + R/k."""
    P, k, c = 1000.0, 2e9, 5e-6
    cases = point_loads(three, {0: P})
    free = cases.d_rel[1, 1, cases.index("P0")]
    laws = [BearingLaw("clearance", k, c), BearingLaw("clearance", k, 2 * abs(free)), BearingLaw("clearance", k, c)]
    f, d = reactions(cases, laws)
    assert np.allclose(f[:, 1], [0.75 * P, 0.0, 0.25 * P], atol=1e-9 * P)
    assert np.abs(f[:, 0]).max() < 1e-9 * P
    for j, R in ((0, 0.75 * P), (2, 0.25 * P)):
        assert d[j, 1] == pytest.approx(-(c + R / k), rel=1e-9)


@pytest.mark.parametrize("c", [5e-6, 20e-6, 40e-6])
def test_equal_clearances_closed_on_one_side_give_the_rigid_reactions(three, c):
    """A load on both spans presses every journal down: with equal clearances the shaft
    sinks by c as a rigid body, which changes no force, so the reactions are those of
    rigid bearings (three-moment equation: 5/16, 22/16, 5/16 of P) and every journal
    sits at c + R/k below its bearing's centre."""
    P, k = 1000.0, 1e14
    f, d = reactions(point_loads(three, {0: P, 1: P}), [BearingLaw("clearance", k, c)] * 3)
    R = three_moment(2, SPAN, {0: P, 1: P})
    assert np.allclose(R / P, [5 / 16, 22 / 16, 5 / 16])
    assert np.allclose(f[:, 1], R, atol=0.01 * P)
    assert np.allclose(d[:, 1], -(c + f[:, 1] / k), rtol=1e-6)


@pytest.mark.parametrize("c", [5e-6, 40e-6])
def test_a_journal_lifted_across_its_clearance_settles_the_beam(three, c):
    """A load on the first span alone pulls the third journal up (rigid reaction -3/32 P):
    with equal clearances it crosses its circle and touches at +c while the others touch
    at -c, so the middle bearing sits c below the line through the ends.  A support
    settlement delta of the middle of a two-span beam takes 6 EI delta / L^3 off it and
    puts half of that on each end (beam theory), on top of the rigid bearings' reactions."""
    P, k = 1000.0, 1e14
    cases = point_loads(three, {0: P})
    rigid, _ = reactions(cases)
    f, d = reactions(cases, [BearingLaw("clearance", k, c)] * 3)
    assert d[0, 1] < 0 and d[1, 1] < 0 and d[2, 1] > 0
    assert np.allclose(np.abs(d[:, 1]), c + np.abs(f[:, 1]) / k, rtol=1e-6)
    EI = 210e9 * np.pi * RADIUS**4 / 4
    dR = 6 * EI * c / SPAN**3
    assert np.allclose(f[:, 1] - rigid[:, 1], [dR / 2, -dR, dR / 2], rtol=0.02)
    assert f[:, 1].sum() == pytest.approx(P, rel=1e-9)


@pytest.mark.parametrize("k", [1e5, 3e5, 1e6])
def test_soft_supports_move_load_to_the_end_bearings(three, k):
    """Two spans on three equal springs k, P at the middle of the first: with the middle
    reaction X as the redundant, compatibility at the middle bearing (its spring's
    compression = the mean of the end springs' + the beam's deflection there relative to
    the ends) gives X (3/(2k) + L^3/(6 EI)) = P/(2k) + 11 P L^3/(96 EI) (deflection of a
    simply supported span 2L at its middle under P at L/2: P a (l - x)(2 l x - x^2 - a^2)
    / (6 EI l), and X (2L)^3/(48 EI) under X), the ends 3/4 P - X/2 and P/4 - X/2.  The
    softer the springs, the more the end bearings carry (rigid: X = 11/16 P): the reason
    the main-bearing loads are enveloped over a stiffness range."""
    P = 1000.0
    EI = 210e9 * np.pi * RADIUS**4 / 4
    L3 = SPAN**3
    X = (P / (2 * k) + 11 * P * L3 / (96 * EI)) / (1.5 / k + L3 / (6 * EI))
    f, _ = reactions(point_loads(three, {0: P}), [BearingLaw("spring", k)] * 3)
    expect = [0.75 * P - X / 2, X, 0.25 * P - X / 2]
    assert np.allclose(f[:, 1], expect, atol=0.01 * P)
    assert f[0, 1] > 0.75 * P - 11 / 32 * P + 0.02 * P  # more than on rigid bearings (13/32 P)


def test_no_load_on_clearance_bearings_gives_no_force(three):
    """Nothing to carry: every journal stays inside its circle, no bearing pushes (the
    position inside the clearance is not determined; the forces are, zero)."""
    f, d = reactions(point_loads(three, {0: 0.0}), [BearingLaw("clearance", 2e9, 20e-6)] * 3)
    assert np.abs(f).max() == 0.0
    assert np.hypot(d[:, 0], d[:, 1]).max() <= 20e-6
