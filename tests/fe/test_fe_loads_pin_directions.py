"""Crankpin unit-case names, unit forces and the weights that build a pin force from them
(``fe_crank.fe.throw.pin_directions``), against their definitions worked by hand.

Pure arithmetic, no mesh: the weights are the sine rule of the triangle F = a e_lo + b e_hi
(a = |F| sin(hi - psi) / sin(hi - lo), b = |F| sin(psi - lo) / sin(hi - lo)), evaluated
below with the sines written out.  Tolerance 1e-12 relative: the values are a few float
operations; a wrong bracket, sign or angle moves them by percent.
"""

from __future__ import annotations

import numpy as np
import pytest

from fe_crank.fe.throw.pin_directions import (
    AXIS_NAMES,
    STEP_DEG,
    pin_case_weights,
    pin_cases,
    pin_direction,
    pin_name,
    unit_force,
)

REL = 1e-12


def test_names_of_the_directions():
    assert AXIS_NAMES == {"pin_x": 0, "pin_y": 90, "pin_-x": 180, "pin_-y": 270}
    assert [pin_direction(n) for n in ("pin_x", "pin_y", "pin_-x", "pin_-y")] == [0, 90, 180, 270]
    assert pin_direction("pin_030") == 30 and pin_direction("pin_000") == 0 and pin_direction("pin_359") == 359
    for not_pin in ("pin_360", "pin_999", "pin_30", "pin_0300", "pin_+x", "torque", "centrifugal", "xpin_030"):
        assert pin_direction(not_pin) is None, not_pin
    # pin_name: whole degrees mod 360, the axis names on the axes, three digits otherwise
    expected = {
        0: "pin_x",
        90: "pin_y",
        180: "pin_-x",
        270: "pin_-y",
        30: "pin_030",
        5: "pin_005",
        359: "pin_359",
        360: "pin_x",
        390: "pin_030",
        -30: "pin_330",
        -90: "pin_-y",
        720: "pin_x",
    }
    for deg, name in expected.items():
        assert pin_name(deg) == name, deg
    assert pin_name(30.7) == "pin_030"  # int() truncates


def test_default_and_other_direction_sets():
    assert STEP_DEG == 30
    assert pin_cases() == (
        "pin_x",
        "pin_030",
        "pin_060",
        "pin_y",
        "pin_120",
        "pin_150",
        "pin_-x",
        "pin_210",
        "pin_240",
        "pin_-y",
        "pin_300",
        "pin_330",
    )
    assert pin_cases(90) == ("pin_x", "pin_y", "pin_-x", "pin_-y")
    assert pin_cases(360) == ("pin_x",)
    assert pin_cases(120) == ("pin_x", "pin_120", "pin_240")
    one = pin_cases(1)
    assert len(one) == 360 and one[1] == "pin_001" and one[-1] == "pin_359"
    for bad in (0, -30, 7, 400, 720):
        with pytest.raises(ValueError) as e:
            pin_cases(bad)
        assert str(e.value) == f"pin direction step must divide 360 deg, got {bad}"


def test_unit_forces_by_definition():
    # exact on the axes (no cos(pi/2) = 6e-17 residue)
    assert unit_force("pin_x") == (1.0, 0.0)
    assert unit_force("pin_y") == (0.0, 1.0)
    assert unit_force("pin_-x") == (-1.0, 0.0)
    assert unit_force("pin_-y") == (0.0, -1.0)
    assert unit_force("pin_000") == (1.0, 0.0)
    # 1 deg: (cos 1, sin 1) = (0.9998476952, 0.0174524064)
    assert unit_force("pin_001") == pytest.approx((0.9998476951563913, 0.01745240643728351), rel=1e-15)
    assert unit_force("pin_091") == pytest.approx((-0.01745240643728351, 0.9998476951563913), rel=1e-14)
    # angle from +x towards +y: (cos 30, sin 30) = (0.8660254037844386, 0.5); 120: (-0.5, 0.866)
    assert unit_force("pin_030") == pytest.approx((0.8660254037844386, 0.5), rel=1e-15)
    assert unit_force("pin_120") == pytest.approx((-0.5, 0.8660254037844386), rel=1e-15)
    assert unit_force("pin_300") == pytest.approx((0.5, -0.8660254037844386), rel=1e-15)
    assert all(isinstance(v, float) for v in unit_force("pin_030"))
    with pytest.raises(ValueError) as e:
        unit_force("torque")
    assert str(e.value) == "'torque' is not a pin unit case"


def test_weights_of_the_default_twelve_directions_by_the_sine_rule():
    names = pin_cases()
    idx = {n: i for i, n in enumerate(names)}
    # F = 1000 N at 40 deg: bracketed by 30 and 60 deg, dl = 30 deg, sin 30 = 0.5:
    #   a(30) = 1000 sin(20) / 0.5 = 2000 x 0.3420201433 = 684.0402867
    #   b(60) = 1000 sin(10) / 0.5 = 2000 x 0.1736481777 = 347.2963553
    # F = 500 N at 90 deg: on pin_y exactly -> 500 there, 0 elsewhere
    # F = 200 N at 350 deg (= -10 deg): bracketed by 330 and 360 = pin_x:
    #   a(330) = 200 sin(10) / 0.5 = 69.45927107,  b(0) = 200 sin(20) / 0.5 = 136.8080573
    # F = 0: no weight
    # F = 100 N at 20 deg: between the first two directions, 0 and 30 deg:
    #   a(0) = 100 sin(10) / 0.5 = 34.72963553,  b(30) = 100 sin(20) / 0.5 = 68.40402867
    F = np.array(
        [
            [1000 * np.cos(np.deg2rad(40)), 1000 * np.sin(np.deg2rad(40))],
            [0.0, 500.0],
            [200 * np.cos(np.deg2rad(-10)), 200 * np.sin(np.deg2rad(-10))],
            [0.0, 0.0],
            [100 * np.cos(np.deg2rad(20)), 100 * np.sin(np.deg2rad(20))],
        ]
    )
    W = pin_case_weights(F, names)
    assert W.shape == (5, 12)
    want = np.zeros((5, 12))
    want[4, idx["pin_x"]], want[4, idx["pin_030"]] = 34.72963553, 68.40402867
    want[0, idx["pin_030"]], want[0, idx["pin_060"]] = 684.0402867, 347.2963553
    want[1, idx["pin_y"]] = 500.0
    want[2, idx["pin_330"]], want[2, idx["pin_x"]] = 69.45927107, 136.8080573
    np.testing.assert_allclose(W, want, rtol=1e-9, atol=1e-9)  # 10 digits written above
    # and exactly the force back (the weights of the unit forces)
    E = np.array([unit_force(n) for n in names])
    np.testing.assert_allclose(W @ E, F, rtol=0, atol=1e-12 * 1000)


def test_weights_of_unsorted_sets_below_the_first_and_past_the_last_direction():
    # directions 270, 0, 120 (given out of order); F = 1 N at 300 deg lies between 270 and 360:
    #   dl = 90 deg: a(270) = sin(60)/sin(90) = 0.8660254038, b(0) = sin(30) = 0.5
    names = ["pin_-y", "pin_x", "pin_120"]
    F = np.array([np.cos(np.deg2rad(300)), np.sin(np.deg2rad(300))])
    np.testing.assert_allclose(pin_case_weights(F, names), [[0.8660254037844386, 0.5, 0.0]], rtol=REL, atol=1e-15)
    # directions 30, 150, 270 (given as 150, 270, 30); F = 2 N at 10 deg, below the first (30):
    #   bracket 270 - 360 = -90 and 30, dl = 120 deg, sin 120 = 0.8660254038:
    #   a(270) = 2 sin(30 - 10) / sin 120 = 2 x 0.3420201433 / 0.8660254038 = 0.78986169
    #   b(30)  = 2 sin(10 + 90) / sin 120 = 2 x 0.9848077530 / 0.8660254038 = 2.2743160
    # check: a (0, -1) + b (0.8660254, 0.5) = (1.9696155, 0.3472964) = 2 (cos 10, sin 10)
    names = ["pin_150", "pin_-y", "pin_030"]
    F = 2 * np.array([np.cos(np.deg2rad(10)), np.sin(np.deg2rad(10))])
    W = pin_case_weights(F, names)
    np.testing.assert_allclose(W, [[0.0, 0.78986169, 2.2743160]], rtol=1e-7, atol=1e-12)
    np.testing.assert_allclose(W[0, 1], 2 * np.sin(np.deg2rad(20)) / np.sin(np.deg2rad(120)), rtol=REL)
    np.testing.assert_allclose(W[0, 2], 2 * np.sin(np.deg2rad(100)) / np.sin(np.deg2rad(120)), rtol=REL)
    # F = 3 N exactly at 150 deg: all on pin_150; at 270 (the last): all on pin_-y
    W = pin_case_weights(np.array([[3 * np.cos(np.deg2rad(150)), 1.5], [0.0, -3.0]]), names)
    np.testing.assert_allclose(W, [[3.0, 0.0, 0.0], [0.0, 3.0, 0.0]], rtol=REL, atol=1e-14)


def test_one_and_two_directions_are_signed_decompositions():
    # one direction: the component along it, signed
    np.testing.assert_array_equal(pin_case_weights((0.0, -250.0), ["pin_y"]), [[-250.0]])
    np.testing.assert_allclose(pin_case_weights([[4.0, 0.0], [-2.5, 0.0]], ["pin_x"]), [[4.0], [-2.5]], rtol=REL)
    # along 30 deg: F = 10 (cos 30, sin 30) -> 10 (the across part Fx sin 30 - Fy cos 30 is 0)
    np.testing.assert_allclose(pin_case_weights(10 * np.array(unit_force("pin_030")), ["pin_030"]), [[10.0]], rtol=REL)
    np.testing.assert_array_equal(pin_case_weights((0.0, 0.0), ["pin_y"]), [[0.0]])
    # the across part may be round-off only, 1e-9 of the along part: 250 N along pin_y with
    # 2e-7 N across passes (threshold 2.5e-7), 3e-7 N is refused
    np.testing.assert_allclose(pin_case_weights((2e-7, 250.0), ["pin_y"]), [[250.0]], rtol=REL)
    for across in (3e-7, -3e-7):
        with pytest.raises(ValueError) as e:
            pin_case_weights((across, 250.0), ["pin_y"])
        assert str(e.value) == "one pin direction (pin_y) carries only forces along it"
    # relative at any scale: 1 mN along with 2e-13 N across passes (threshold 1e-12 N),
    # 3e-12 N across (3e-9 of the force) is refused
    np.testing.assert_allclose(pin_case_weights((2e-13, 1e-3), ["pin_y"]), [[1e-3]], rtol=REL)
    with pytest.raises(ValueError, match="carries only forces along it"):
        pin_case_weights((3e-12, 1e-3), ["pin_y"])
    # two directions: F = a e_1 + b e_2.  pin_x and pin_y: (3, -4) -> 3, -4.
    np.testing.assert_allclose(pin_case_weights((3.0, -4.0), ["pin_x", "pin_y"]), [[3.0, -4.0]], rtol=REL)
    # pin_x and pin_060, F = (0, 1): b sin 60 = 1 -> b = 2/sqrt(3) = 1.1547005384,
    # a + b/2 = 0 -> a = -1/sqrt(3) = -0.5773502692
    np.testing.assert_allclose(
        pin_case_weights((0.0, 1.0), ["pin_x", "pin_060"]), [[-0.5773502691896258, 1.1547005383792517]], rtol=REL
    )
    for parallel in (["pin_x", "pin_-x"], ["pin_y", "pin_-y"]):
        with pytest.raises(ValueError) as e:
            pin_case_weights((1.0, 1.0), parallel)
        assert str(e.value) == f"pin unit cases {parallel} are parallel: they cannot carry an arbitrary force"


def test_refused_sets():
    assert pin_case_weights(np.zeros((2, 2)), []).shape == (2, 0)
    with pytest.raises(ValueError) as e:
        pin_case_weights((0.0, 1.0), [])
    assert str(e.value) == "a pin force but no pin unit case"
    with pytest.raises(ValueError) as e:
        pin_case_weights((0.0, 1.0), ["pin_x", "torque", "pin_y", "pin_400"])
    assert str(e.value) == "not pin unit cases: ['torque', 'pin_400']"
    with pytest.raises(ValueError) as e:
        pin_case_weights((0.0, 1.0), ["pin_x", "pin_000", "pin_y"])
    assert str(e.value) == "pin unit cases with the same direction: ['pin_x', 'pin_000', 'pin_y']"
    # gaps: 0, 30, 60 leaves 300 deg; 0, 90, 180 leaves exactly 180 deg (refused: >= 180)
    with pytest.raises(ValueError) as e:
        pin_case_weights((0.0, 1.0), ["pin_x", "pin_030", "pin_060"])
    assert str(e.value) == (
        "pin unit cases ['pin_x', 'pin_030', 'pin_060'] leave a gap of 300 deg: every gap must be < 180 deg"
    )
    with pytest.raises(ValueError, match="leave a gap of 180 deg"):
        pin_case_weights((0.0, 1.0), ["pin_x", "pin_y", "pin_-x"])
    # 0, 90, 181 leaves 179 deg at most: accepted, F at 270 between 181 and 360
    W = pin_case_weights((0.0, -1.0), ["pin_x", "pin_y", "pin_181"])
    # dl = 179 deg: a(181) = sin(90)/sin(179), b(0) = sin(89)/sin(179)
    np.testing.assert_allclose(
        W, [[np.sin(np.deg2rad(89)) / np.sin(np.deg2rad(179)), 0.0, 1.0 / np.sin(np.deg2rad(179))]], rtol=REL
    )
