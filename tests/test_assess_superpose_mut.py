"""``assess.superpose`` on hand-built inputs: the load coefficients of the unit cases and
the combination of unit stresses, each against a hand calculation.

The FE solve of ``test_assess_superpose.py`` checks the superposition against a direct
solve; these tests pin down the parts a mutation of the arithmetic could change without
that solve noticing: the centrifugal omega^2, the torque's sign and scale, the column of
each pin case, the refusals, the node selection and the chunking of the histories.
Values are exact small numbers, so the tolerances (1e-12 relative) only absorb the
rounding of a handful of products; any wrong term moves a value by O(1).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from fe_crank.assess.superpose import (
    UNIT_CASES,
    UnitStresses,
    combine,
    iter_histories,
    iter_planes,
    load_coefficients,
    stress_history,
)
from fe_crank.fe.pin_directions import pin_direction


def _pin_column(deg):
    """Column of the pin case at ``deg`` in the default cases (the FE stage's names)."""
    return [i for i, c in enumerate(UNIT_CASES) if pin_direction(c) == deg][0]


def test_default_cases_centrifugal_pin_and_torque_by_hand():
    """Default cases: centrifugal, 12 pin directions 30 deg apart, torque.

    omega = 3 rad/s -> centrifugal coefficient omega^2 = 9 (omega * 2 = 6 and omega^3 = 27
    would differ by 3 and 18).  A 1000 N force at 45 deg lies between the 30 and 60 deg
    cases: w30 e30 + w60 e60 = F, Cramer's rule with det = sin(60 - 30) = 0.5:
    w30 = 1000 sin(60 - 45) / sin 30 = 1000 x 0.2588190 / 0.5 = 517.6381 N = w60.
    A force along 90 deg (0, -250 N is 270 deg) is carried by that case alone.
    Torque: the FE case is M_z = -1 N m (torque_mz), sense +1 -> coefficient = -1 x T / -1 = T.
    """
    pin = np.array([[1000 * math.cos(math.pi / 4), 1000 * math.sin(math.pi / 4)], [0.0, -250.0]])
    c = load_coefficients(pin, np.array([40.0, -7.0]), 3.0)
    assert c.shape == (2, len(UNIT_CASES)) and UNIT_CASES[0] == "centrifugal" and UNIT_CASES[-1] == "torque"
    np.testing.assert_allclose(c[:, 0], [9.0, 9.0], rtol=1e-15)
    w = 1000 * math.sin(math.radians(15.0)) / math.sin(math.radians(30.0))
    assert w == pytest.approx(517.6381, abs=1e-4)
    expected_pins = np.zeros((2, 12))
    expected_pins[0, [_pin_column(30) - 1, _pin_column(60) - 1]] = w
    expected_pins[1, _pin_column(270) - 1] = 250.0
    np.testing.assert_allclose(c[:, 1:-1], expected_pins, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(c[:, -1], [40.0, -7.0], rtol=1e-15)


def test_torque_coefficient_sign_and_scale():
    """coefficient = -sense T / torque_mz: T = 12 N m, torque_mz = -4 -> 3 (sense +1) and
    -3 (sense -1); torque_mz = +0.5 -> -24 (sense +1).  A product in place of the quotient
    would give 48 / -6: off by a factor 16."""
    pin = np.zeros((1, 2))
    cases = ("pin_x", "pin_y", "torque")
    assert load_coefficients(pin, np.array([12.0]), 1.0, cases=cases, torque_mz=-4.0)[0, 2] == 3.0
    assert load_coefficients(pin, np.array([12.0]), 1.0, cases=cases, sense=-1, torque_mz=-4.0)[0, 2] == -3.0
    assert load_coefficients(pin, np.array([12.0]), 1.0, cases=cases, torque_mz=0.5)[0, 2] == -24.0
    # the defaults: sense +1 and the FE stage's M_z = -1 N m
    assert load_coefficients(pin, np.array([12.0]), 1.0, cases=cases)[0, 2] == 12.0


def test_integer_inputs_give_the_float_coefficients():
    """Integer arrays (a TOML table of whole newtons) give the same coefficients as floats:
    F = (3, -4) N on pin_x/pin_y is (3, -4); T = 5 N m -> 5; omega 2 -> 4."""
    c = load_coefficients(np.array([[3, -4]]), np.array([5]), 2, cases=("centrifugal", "pin_x", "pin_y", "torque"))
    assert c.dtype == float
    np.testing.assert_allclose(c, [[4.0, 3.0, -4.0, 5.0]], rtol=1e-12)  # the 2x2 solve rounds


def test_bad_shapes_and_unknown_cases_are_refused():
    good_pin, good_t = np.zeros((2, 2)), np.zeros(2)
    msg = "pin_force must be (n, 2) and torque (n,); got"
    with pytest.raises(ValueError) as e:
        load_coefficients(np.zeros((2, 3)), good_t, 1.0)
    assert str(e.value) == f"{msg} (2, 3), (2,)"
    with pytest.raises(ValueError) as e:
        load_coefficients(good_pin, np.zeros(3), 1.0)
    assert str(e.value) == f"{msg} (2, 2), (3,)"
    with pytest.raises(ValueError) as e:
        load_coefficients(good_pin, good_t, 1.0, cases=("centrifugal", "pin_x", "pin_y", "bending"))
    assert str(e.value) == "unknown unit case 'bending'"


def _unit(n=3):
    """Three unit cases at ``n`` nodes: case c, component j, node k holds
    100 c + 10 j + k (small exact integers)."""
    c, j, k = np.meshgrid(np.arange(3), np.arange(6), np.arange(n), indexing="ij")
    return UnitStresses(stress=(100.0 * c + 10.0 * j + k), points=np.zeros((3, n)), cases=("a", "b", "c"))


def test_combine_is_the_hand_sum_of_coefficients_times_unit_stresses():
    """Node 1, component xx (j = 0) at t = 0 with coefficients (2, -1, 0.5):
    2 x 1 - 1 x 101 + 0.5 x 201 = 2 - 101 + 100.5 = 1.5; at t = 1, (0, 0, 3): 3 x 201 = 603.
    Component yz (j = 4) of node 2 at t = 0: 2 x 42 - 142 + 0.5 x 242 = 84 - 142 + 121 = 63."""
    unit = _unit()
    co = np.array([[2.0, -1.0, 0.5], [0.0, 0.0, 3.0]])
    s = combine(unit.stress, co)
    assert s.shape == (2, 6, 3)
    assert s[0, 0, 1] == 1.5 and s[1, 0, 1] == 603.0 and s[0, 4, 2] == 63.0
    # one angle given as a 1-D row: a leading axis of 1
    one = combine(unit.stress, co[0])
    assert one.shape == (1, 6, 3) and one[0, 4, 2] == 63.0
    # displacement vectors (n_cases, n_dof): 2 (1, 2) - (3, 4) + 0.5 (6, 8) = (2, 4)
    d = combine(np.array([[1.0, 2.0], [3.0, 4.0], [6.0, 8.0]]), co[:1])
    np.testing.assert_array_equal(d, [[2.0, 4.0]])
    with pytest.raises(ValueError) as e:
        combine(unit.stress, co[:, :2])
    assert str(e.value) == "2 coefficients for 3 unit cases"


def test_stress_history_at_selected_nodes_and_in_chunks():
    """History at nodes [2, 0]: the values of nodes 2 and 0 in that order (t = 0, xx:
    node 2: 2 x 2 - 102 + 0.5 x 202 = 3; node 0: 2 x 0 - 100 + 100 = 0).  The chunked
    iterators yield every node once, in order, with those values, ``chunk`` / ``block``
    nodes at a time (the defaults bound the memory: 2048 and 128 nodes)."""
    unit = _unit(5)
    co = np.array([[2.0, -1.0, 0.5], [0.0, 0.0, 3.0]])
    h = stress_history(unit, co, np.array([2, 0]))
    assert h.shape == (2, 6, 2) and h[0, 0, 0] == 3.0 and h[0, 0, 1] == 0.0
    full = stress_history(unit, co)
    assert full.shape == (2, 6, 5) and unit.n_nodes == 5
    np.testing.assert_array_equal(full[:, :, [2, 0]], h)
    nodes = np.array([4, 1, 3, 0, 2])
    got = list(iter_histories(unit, co, nodes, chunk=2))
    assert [list(i) for i, _ in got] == [[4, 1], [3, 0], [2]]
    for idx, hist in got:
        np.testing.assert_array_equal(hist, full[:, :, idx])
    planes = list(iter_planes(unit, co, nodes, block=2))
    assert [list(i) for i, _ in planes] == [[4, 1], [3, 0], [2]]
    for idx, p in planes:
        assert p.shape == (6, 2, idx.size)
        np.testing.assert_array_equal(p, full[:, :, idx].transpose(1, 0, 2))
    with pytest.raises(ValueError) as e:
        next(iter_planes(unit, co[:, :2], nodes))
    assert str(e.value) == "2 coefficients for 3 unit cases"
    # the default chunk sizes
    big = UnitStresses(stress=np.ones((3, 6, 2049)), points=np.zeros((3, 2049)), cases=("a", "b", "c"))
    assert [i.size for i, _ in iter_histories(big, co, np.arange(2049))] == [2048, 1]
    assert [i.size for i, _ in iter_planes(big, co, np.arange(129))] == [128, 1]
    # one angle as a 1-D row of coefficients
    ((idx, p),) = iter_planes(unit, co[1], np.array([1]))
    assert p.shape == (6, 1, 1) and p[0, 0, 0] == 3 * 201.0


def test_integer_tables_combine_to_float_stresses():
    """Whole-number unit stresses and coefficients (as a hand-written table gives them)
    combine to float arrays with the hand values: node 0, xx: 2 x 0 + 3 x 100 + 1 x 200 = 500;
    the per-component planes are float too (written into a float array)."""
    stress = (100 * np.arange(3)[:, None, None] + np.zeros((3, 6, 2), dtype=int)).astype(int)
    unit = UnitStresses(stress=stress, points=np.zeros((3, 2)), cases=("a", "b", "c"))
    co = np.array([[2, 3, 1]])
    s = combine(unit.stress, co)
    assert s.dtype == float and s[0, 0, 0] == 500.0
    ((idx, planes),) = iter_planes(unit, co, np.arange(2))
    assert planes.dtype == float and planes[0, 0, 0] == 500.0
