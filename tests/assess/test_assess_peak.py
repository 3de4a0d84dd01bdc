"""``assess.group.peak``: the tie rule of ``max_over_cycle``, the bound B of ``peak_bound`` by
hand, and which nodes ``group_peak`` evaluates.

On hand-built unit stresses with one unit case and uniaxial unit stresses the bound is exact (B = max_t |a(t)|
sigma_v(U) = the peak), so the nodes ``group_peak`` must evaluate follow by hand from
the stopping rule of the module docstring: a block is skipped once its largest bound
is below peak - 1e-9 peak.  Tie-band tests place values 5e-10 (inside) and 2e-9 or
1e-6 (outside) relative from the extreme: the band's edge is resolved to better than a
factor 2.

On a real throw (gmsh mesh with fillets, scikit-fem solve): the bound holds at every
node, and the pruned evaluation finds what evaluating every node finds, bit for bit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from fe_crank.assess.group.assessment import first_extreme
from fe_crank.assess.group.peak import BOUND_RTOL, TIE_RTOL, group_peak, max_over_cycle, peak_bound
from fe_crank.assess.stress import von_mises
from fe_crank.assess.superpose import UnitStresses, stress_history


def test_max_over_cycle_first_index_of_the_tie_band():
    """Column 0: max 2 at t = 2 and 3, 2 (1 - 5e-10) at t = 1 is inside the band -> 1.
    Column 1: 2 (1 - 2e-9) at t = 1 is outside -> the exact maximum's first index, 3.
    Column 2 (negative values): max -1 at t = 2; band -1 - 1e-9 holds -1 - 5e-10 at t = 1."""
    assert TIE_RTOL == 1e-9
    vm = np.array([[1.0, 1.0, -2.0], [2 * (1 - 5e-10), 2 * (1 - 2e-9), -1 - 5e-10], [2.0, 1.5, -1.0], [2.0, 2.0, -3.0]])
    e, first = max_over_cycle(vm)
    np.testing.assert_array_equal(e, [2.0, 2.0, -1.0])
    np.testing.assert_array_equal(first, [1, 3, 1])


def _unit(values, shear=None):
    """One node per value: case 0 uniaxial sigma_xx = value, case 1 (if given) pure shear
    tau_xy = shear (von Mises sqrt(3) tau)."""
    n = len(values)
    s = np.zeros((1 if shear is None else 2, 6, n))
    s[0, 0] = values
    if shear is not None:
        s[1, 3] = shear
    return UnitStresses(stress=s, points=np.zeros((3, n)), cases=("a",) if shear is None else ("a", "b"))


def test_peak_bound_by_hand_in_chunks():
    """Coefficients (1, 1) and (1, -2) -> |a| = (1, 1), (1, 2):
    node 0: sigma 100, tau 50 (vM 86.603): B = max(100 + 86.603, 100 + 173.205) = 273.205
    node 1: sigma -30, no shear: B = 30 x max(1, 1) = 30
    node 2: no sigma, tau 40 / sqrt(3) (vM 40): B = max(40, 80) = 80."""
    unit = _unit([100.0, -30.0, 0.0], shear=[50.0, 0.0, 40.0 / math.sqrt(3.0)])
    co = np.array([[1.0, 1.0], [1.0, -2.0]])
    expected = [100 + 2 * math.sqrt(3.0) * 50, 30.0, 80.0]
    for chunk in (1, 2, 2048):
        np.testing.assert_allclose(peak_bound(unit, co, np.array([0, 1, 2]), chunk=chunk), expected, rtol=1e-14)
    np.testing.assert_allclose(peak_bound(unit, co, np.array([2, 0])), [80.0, expected[0]], rtol=1e-14)
    # a single angle given as a 1-D row (1, -2): node 0 -> 100 + 173.205
    assert peak_bound(unit, co[1], np.array([0]))[0] == pytest.approx(expected[0], rel=1e-14)


def test_group_peak_evaluates_only_the_nodes_that_can_reach_the_tie_band():
    """Nodes sigma_xx = 10, 20, ..., 60 Pa, coefficients (1, -2, 0.5): peak 2 x sigma at
    angle 1, bound = peak.  ``block`` = 1: node 5 (120 Pa) first; the next bound, 100 Pa, is
    below 120 (1 - 1e-9) -> stop.  ``block`` = 2: nodes 5 and 4."""
    unit = _unit([10.0, 20.0, 30.0, 40.0, 50.0, 60.0])
    co = np.array([[1.0], [-2.0], [0.5]])
    nodes = np.arange(6)
    pos, peak, arg = group_peak(unit, co, nodes, block=1)
    np.testing.assert_array_equal(pos, [5])
    np.testing.assert_array_equal(peak, [120.0])
    np.testing.assert_array_equal(arg, [1])
    pos, peak, arg = group_peak(unit, co, nodes, block=2)
    np.testing.assert_array_equal(pos, [4, 5])
    np.testing.assert_array_equal(peak, [100.0, 120.0])
    np.testing.assert_array_equal(arg, [1, 1])
    # positions refer to ``nodes``: the same group given as nodes 5, 0, 3 -> its node 5 is position 0
    pos, peak, _ = group_peak(unit, co, np.array([5, 0, 3]), block=1)
    np.testing.assert_array_equal(pos, [0])
    assert peak[0] == 120.0


def test_group_peak_keeps_every_node_of_the_tie_band():
    """Nodes 1 and 4 at 30 Pa (peak 60), node 2 at 30 (1 - 5e-10) (inside the band of
    1e-9), node 3 at 30 (1 - 1e-6) and node 0 at 10 (outside): one node per block, the
    evaluation stops after node 2 -> positions 1, 2, 4 (ascending)."""
    unit = _unit([10.0, 30.0, 30 * (1 - 5e-10), 30 * (1 - 1e-6), 30.0])
    co = np.array([[1.0], [-2.0], [0.5]])
    pos, peak, arg = group_peak(unit, co, np.arange(5), block=1)
    np.testing.assert_array_equal(pos, [1, 2, 4])
    np.testing.assert_allclose(peak, [60.0, 60 * (1 - 5e-10), 60.0], rtol=1e-15)
    np.testing.assert_array_equal(arg, [1, 1, 1])


def test_group_peak_first_angle_of_the_tie_band_and_uneven_blocks():
    """Coefficients (1, 2 (1 - 5e-10), -2): the peak 2 sigma at angle 2, and angle 1 is
    inside the band -> angle 1.  Five equal nodes in blocks of 2 (2 + 2 + 1): all evaluated
    (each bound ties with the peak), the last block smaller than the others."""
    unit = _unit([7.0] * 5)
    co = np.array([[1.0], [2 * (1 - 5e-10)], [-2.0]])
    pos, peak, arg = group_peak(unit, co, np.arange(5), block=2)
    np.testing.assert_array_equal(pos, np.arange(5))
    np.testing.assert_array_equal(peak, [14.0] * 5)
    np.testing.assert_array_equal(arg, [1] * 5)


def test_group_peak_default_block_of_128_nodes():
    """200 nodes sigma = 1 ... 200 Pa, one angle: the first block holds the 128 largest
    bounds (73 ... 200 Pa); the 129th (72 Pa) is below the band of 200 Pa -> 128 nodes."""
    unit = _unit(np.arange(1.0, 201.0))
    pos, peak, _ = group_peak(unit, np.array([[1.0]]), np.arange(200))
    np.testing.assert_array_equal(pos, np.arange(72, 200))
    np.testing.assert_array_equal(peak, np.arange(73.0, 201.0))


def test_a_node_whose_bound_equals_the_peak_found_is_evaluated():
    """A node whose bound is the same number as the best peak found is evaluated, not
    skipped (its true peak may equal it: a tie).  Two cases that cancel at angle 1
    (sigma (1 - 1) = 0) and add at angle 0: the bound of node 1, |1| x 10 + |1| x 10 = 20,
    is its true peak and equals node 0's 20 Pa peak.  The bound's widening for rounding,
    1e-12, is below the tie band's 1e-9."""
    assert BOUND_RTOL == 1e-12 < TIE_RTOL
    s = np.zeros((2, 6, 2))
    s[0, 0, 0] = 20.0  # node 0: 20 Pa from case a alone
    s[0, 0, 1], s[1, 0, 1] = 10.0, 10.0  # node 1: 10 + 10 at angle 0
    unit = UnitStresses(stress=s, points=np.zeros((3, 2)), cases=("a", "b"))
    co = np.array([[1.0, 1.0], [1.0, -1.0]])
    pos, peak, arg = group_peak(unit, co, np.arange(2), block=1)
    np.testing.assert_array_equal(pos, [0, 1])
    np.testing.assert_array_equal(peak, [20.0, 20.0])
    np.testing.assert_array_equal(arg, [0, 0])


def test_max_over_cycle_of_a_zero_maximum_after_negative_values():
    """A column whose maximum is exactly 0, first reached at t = 1 (band of width 0):
    the first index is 1, not 0."""
    e, first = max_over_cycle(np.array([[-1.0], [0.0], [0.0]]))
    assert e[0] == 0.0 and first[0] == 1


def test_a_node_whose_peak_lies_on_the_edge_of_the_tie_band_is_evaluated():
    """Node 1 peaks at 60 Pa; node 0 exactly at the band's edge, 60 - 1e-9 x 60 (a tie:
    the band is closed).  Its bound, widened by 1e-12 for rounding, reaches the band, so it
    is evaluated and, being the first node of the band, is the group's extreme.  (The
    peak of a uniaxial state is exact: sqrt(fl(x^2)) = |x| in IEEE arithmetic.)"""
    edge = 60.0 - TIE_RTOL * 60.0
    unit = _unit([edge, 60.0])
    pos, peak, _ = group_peak(unit, np.array([[1.0]]), np.arange(2), block=1)
    np.testing.assert_array_equal(pos, [0, 1])
    assert peak[0] == edge and peak[0] >= peak.max() - TIE_RTOL * peak.max()


def test_a_node_with_a_non_finite_stress_is_never_pruned():
    """A NaN unit stress (a failed recovery) at node 0: the bound is not finite, so the
    nodes are taken in their own order and node 0 is evaluated (its NaN peak reaches the
    group's extreme and fails the check) -- the pruning must not drop it behind the
    finite bounds.  Node 1 (20 Pa) is evaluated next, node 2 (10 Pa) is below the band."""
    unit = _unit([np.nan, 10.0, 5.0])
    pos, peak, _ = group_peak(unit, np.array([[1.0], [-2.0]]), np.arange(3), block=1)
    np.testing.assert_array_equal(pos, [0, 1])
    assert np.isnan(peak[0]) and peak[1] == 20.0


def test_blocks_larger_than_the_history_default():
    """Blocks of 200 nodes (more than ``iter_planes``' default of 128): 200 equal nodes
    are one block and every one gets its peak."""
    unit = _unit([3.0] * 200)
    pos, peak, arg = group_peak(unit, np.array([[1.0], [-2.0]]), np.arange(200), block=200)
    np.testing.assert_array_equal(pos, np.arange(200))
    np.testing.assert_array_equal(peak, np.full(200, 6.0))
    np.testing.assert_array_equal(arg, np.ones(200, int))


def test_nodes_of_equal_bound_are_taken_in_node_order():
    """41 nodes: 100 Pa at node 0, 80 Pa at nodes 5, 17 and 30, 50 Pa elsewhere; blocks of
    three.  The first block holds node 0 and the first two of the tied 80-Pa nodes in node
    order (5, 17), so the nodes evaluated -- and the work done -- do not depend on the
    sorting algorithm (numpy's default quicksort takes 5, 30 for this input)."""
    values = np.full(41, 50.0)
    values[0], values[[5, 17, 30]] = 100.0, 80.0
    pos, peak, _ = group_peak(_unit(values), np.array([[1.0]]), np.arange(41), block=3)
    np.testing.assert_array_equal(pos, [0, 5, 17])
    np.testing.assert_array_equal(peak, [100.0, 80.0, 80.0])


@pytest.mark.heavy
def test_group_peak_bound_holds_and_the_extreme_is_the_full_evaluations(filleted_throw_cycle):
    """B >= every node's peak (the seminorm's triangle inequality), and the pruned
    evaluation finds the same largest peak, first node of its tie band and first angle as
    evaluating every node, bit for bit (the evaluated nodes' values are the same
    operations)."""
    us, co = filleted_throw_cycle
    co = 1.44 * co
    for g in ("journal_fillet_1", "crankpin_fillet_2", "counterweight_1"):
        nodes = us.groups.get(g)
        if nodes is None:
            continue
        full, full_arg = max_over_cycle(von_mises(stress_history(us, co, nodes)))
        bound = peak_bound(us, co, nodes)
        assert np.all(full <= bound * (1 + 1e-12)), g
        pos, peak, arg = group_peak(us, co, nodes)
        assert pos.size < nodes.size, g  # it did prune
        k_full = int(first_extreme(full, "max"))
        k = int(first_extreme(peak, "max"))
        assert pos[k] == k_full and peak[k] == full[k_full] and arg[k] == full_arg[k_full], g


def test_peak_bound_hand_value():
    """Two unit states, uniaxial 100 MPa and pure shear 50 MPa (vM 100 and 86.60 MPa),
    with coefficients (1, 1) and (1, -2): B = max(100 + 86.60, 100 + 173.21) = 273.21 MPa;
    the true peaks are vM(100, shear 50) = sqrt(100^2 + 3 50^2) = 132.29 MPa and
    vM(100, shear -100) = sqrt(100^2 + 3 100^2) = 200 MPa."""
    s = np.zeros((2, 6, 1))
    s[0, 0, 0], s[1, 3, 0] = 100e6, 50e6
    unit = UnitStresses(stress=s, points=np.zeros((3, 1)), cases=("a", "b"))
    co = np.array([[1.0, 1.0], [1.0, -2.0]])
    assert peak_bound(unit, co, np.array([0]))[0] == pytest.approx(100e6 + 2 * np.sqrt(3) * 50e6, rel=1e-15)
    pos, peak, arg = group_peak(unit, co, np.array([0]))
    assert peak[0] == pytest.approx(200e6, rel=1e-15) and arg[0] == 1


def test_window_peak_bound_by_hand():
    """One uniaxial case of 100 MPa (vM 100 MPa), a(t) = 1 + (t/10)^2 for t = 0..10 (one
    run), stride 4: samples 0, 4, 8, 10 (a = 1, 1.16, 1.64, 2).  The coefficient's
    largest departure below its chord: 0.04 at t = 2 and at t = 6, 0.01 at t = 9; the
    windows give 1.16 + 0.04, 1.64 + 0.04, 2 + 0.01: bound 2.01 x 100 MPa, the peak
    200 MPa."""
    from fe_crank.assess.group.bounds import window_peak_bound

    unit = _unit([100e6])
    co = (1.0 + (np.arange(11.0) / 10.0) ** 2)[:, None]
    b = window_peak_bound(unit, co, np.array([0]), stride=4)[0]
    assert b == pytest.approx(201e6, rel=1e-11)
    pos, peak, _ = group_peak(unit, co, np.array([0]), bound=np.array([b]))
    assert peak[0] == pytest.approx(200e6, rel=1e-15)


@pytest.mark.heavy
def test_window_peak_bound_holds_and_the_extreme_is_the_full_evaluations(filleted_throw_cycle):
    """The windowed bound >= every node's evaluated peak (the seminorm's convexity between
    samples), and the search ordered by it finds the same largest peak, first node of its
    tie band and first angle as evaluating every node, bit for bit."""
    from fe_crank.assess.group.bounds import window_peak_bound

    us, co = filleted_throw_cycle
    for g in ("journal_fillet_1", "crankpin_fillet_2"):
        nodes = us.groups[g]
        full, full_arg = max_over_cycle(von_mises(stress_history(us, co, nodes)))
        for stride in (1, 4, 8):
            bound = window_peak_bound(us, co, nodes, stride=stride)
            assert np.all(full <= bound), g
            pos, peak, arg = group_peak(us, co, nodes, 16, bound)
            k_full = int(first_extreme(full, "max"))
            k = int(first_extreme(peak, "max"))
            assert pos[k] == k_full and peak[k] == full[k_full] and arg[k] == full_arg[k_full], g
