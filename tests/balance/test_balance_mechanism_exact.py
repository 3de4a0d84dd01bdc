"""Exact piston and big-end positions of ``fe_crank.balance.mechanism`` by hand: the side of
a pin offset (one cylinder, both shaft senses, two bank angles), the master rod's pin
offset in an articulated big end, and the refusals (rod that cannot reach, the rod
exactly square to the axis, chained and cross-throw articulation) in full.

The offset side needs a single cylinder: in a flat-crank inline-4 only the odd orders
of each piston's motion change with the offset's sign (the part of ``x(phi)`` odd in
``phi`` is odd in ``e`` and holds only odd orders), and those cancel between the throws,
so the engine's free force is blind to it."""

import math

import numpy as np
import pytest

from fe_crank import model
from fe_crank.balance.mechanism import big_end, piston_positions
from fe_crank.errors import InputError


def _single(r, l, offset=0.0, bank=0.0, sense=1):
    return model.Engine(
        "single",
        4,
        (model.Shaft("main", sense=sense),),
        (model.Throw("1", "main", 0.0, r),),
        (model.Cylinder("1", "1", 0.09, model.Rod(l, 1.0, l / 4), 1.5, bank_angle=bank, pin_offset=offset),),
    )


@pytest.mark.parametrize("sense", [1, -1])
def test_pin_offset_side_by_hand(sense):
    """r = 0.05 m, l = 0.2 m, e = 0.01 m, cylinder along +y.  A quarter turn after TDC the
    crankpin stands on the side the offset lies on (``+x`` for sense +1, ``-x`` for -1),
    |across| = r - e: x = sqrt(0.2^2 - 0.04^2) = sqrt(0.0384) = 0.195959179 m; three
    quarters after TDC |across| = r + e: x = sqrt(0.04 - 0.0036) = sqrt(0.0364) =
    0.190787840 m; at TDC and BDC x = +-r + sqrt(l^2 - e^2) = +-0.05 + sqrt(0.0399).
    The offset on the wrong side swaps the two quarter values (2.7 % apart), checked to
    1e-12."""
    e = _single(0.05, 0.2, offset=0.01, sense=sense)
    x = piston_positions(e, "1", np.array([0.0, 0.5, 1.0, 1.5]) * math.pi)
    root = math.sqrt(0.0399)
    np.testing.assert_allclose(x, [0.05 + root, math.sqrt(0.0384), -0.05 + root, math.sqrt(0.0364)], rtol=1e-12)


def test_pin_offset_of_a_horizontal_cylinder_by_hand():
    """Bank 90 deg (axis +x): the crankpin passes TDC at theta = 90 deg and stands at
    (0, -r) a quarter turn later, on the offset's side (normal ``u(180 deg) = -y``):
    x = sqrt(l^2 - (r - e)^2) = sqrt(0.0384) m; at theta = 0, (0, +r):
    x = sqrt(0.0364) m (r = 0.05, l = 0.2, e = 0.01 m)."""
    e = _single(0.05, 0.2, offset=0.01, bank=math.pi / 2)
    x = piston_positions(e, "1", np.array([0.0, 0.5, 1.0]) * math.pi)
    np.testing.assert_allclose(x, [math.sqrt(0.0364), 0.05 + math.sqrt(0.0399), math.sqrt(0.0384)], rtol=1e-12)


def _radial(master_offset, sense=1, master_of_b="M", throw_of_b="1"):
    """Master M along +y (l = 0.4 m, pin offset e), articulated A at 90 deg on M's rod
    (link radius 0.05 m, link angle 90 deg, rod 0.35 m); an optional third cylinder B."""
    throws = (model.Throw("1", "main", 0.0, 0.1), model.Throw("2", "main", math.pi, 0.1, 0.2))
    cyls = [
        model.Cylinder("M", "1", 0.1, model.Rod(0.4, 2.0, 0.1), 1.0, pin_offset=master_offset),
        model.Cylinder(
            "A",
            "1",
            0.1,
            model.Rod(0.35, 1.0, 0.1),
            1.0,
            bank_angle=math.pi / 2,
            articulation=model.Articulation("M", 0.05, math.pi / 2),
        ),
    ]
    if master_of_b is not None:
        cyls.append(
            model.Cylinder(
                "B",
                throw_of_b,
                0.1,
                model.Rod(0.35, 1.0, 0.1),
                1.0,
                bank_angle=math.pi,
                articulation=model.Articulation(master_of_b, 0.05, math.pi),
            )
        )
    return model.Engine("radial", 4, (model.Shaft("main", sense=sense),), throws, tuple(cyls))


@pytest.mark.parametrize("sense", [1, -1])
def test_articulated_big_end_with_a_master_pin_offset_by_hand(sense):
    """theta = 0: crankpin (0, 0.1).  Master pin offset e = 0.2 m on the side ``s u(90 deg)``:
    across = -e, x_m = 0.1 + sqrt(0.4^2 - 0.2^2), piston pin (s e, x_m); master rod
    (s 0.2, sqrt(0.12)) from the big end: gamma = s 30 deg.  Link pin at
    gamma + 90 deg: (0, 0.1) + 0.05 u(120 deg) = (0.05 sqrt(3)/2, 0.1 - 0.025) =
    (0.0433013, 0.075) for s = +1 and 0.05 u(60 deg) = (0.0433013, 0.125) for s = -1.
    The offset on the other side, or along the axis, moves gamma by 30 deg or more."""
    be = big_end(_radial(0.2, sense=sense, master_of_b=None), "A", 0.0)
    gamma = sense * math.radians(30.0)
    expected = [0.05 * math.sin(gamma + math.pi / 2), 0.1 + 0.05 * math.cos(gamma + math.pi / 2)]
    np.testing.assert_allclose(be, expected, rtol=1e-12)
    np.testing.assert_allclose(expected, [0.05 * math.sqrt(3) / 2, 0.1 - sense * 0.025], rtol=1e-15)


def test_articulated_big_end_without_offset_at_a_quarter_turn_by_hand():
    """theta = 90 deg: crankpin (0.1, 0); master rod from (0.1, 0) to (0, sqrt(0.4^2 - 0.1^2)),
    gamma = atan2(-0.1, sqrt(0.15)); link pin (0.1, 0) + 0.05 u(gamma + 90 deg)."""
    be = big_end(_radial(0.0, master_of_b=None), "A", math.pi / 2)
    gamma = math.atan2(-0.1, math.sqrt(0.15))
    np.testing.assert_allclose(
        be, [0.1 + 0.05 * math.sin(gamma + math.pi / 2), 0.05 * math.cos(gamma + math.pi / 2)], rtol=1e-12, atol=1e-15
    )


def test_rod_that_cannot_reach_the_axis_is_refused_in_full():
    """r = 0.3 m, l = 0.25 m: at a quarter turn |across| = 0.3 > l."""
    with pytest.raises(InputError) as err:
        piston_positions(_single(0.3, 0.25), "1", np.linspace(0.0, 2 * math.pi, 9))
    assert err.value.key == "cylinders.1"
    assert err.value.reason == (
        "cylinder '1': the connecting rod (250 mm) cannot reach the cylinder axis at every "
        "crank angle; check rod length, offset and articulation"
    )


def test_rod_exactly_square_to_the_axis_is_refused():
    """r = l = 0.25 m (exact binary fractions): at theta = 90 deg across = 0.25 exactly, so
    l^2 - across^2 = 0: the rod lies square to the cylinder axis and the piston's
    acceleration is unbounded there, a locked mechanism -- refused like one that cannot
    reach.  Just short of it (r = 0.25 - 2^-20) the positions are finite."""
    with pytest.raises(InputError) as err:
        piston_positions(_single(0.25, 0.25), "1", [math.pi / 2])
    assert err.value.key == "cylinders.1"
    x = piston_positions(_single(0.25 - 2.0**-20, 0.25), "1", [math.pi / 2])
    assert x[0] == pytest.approx(math.sqrt(0.25**2 - (0.25 - 2.0**-20) ** 2), rel=1e-6)


def test_articulation_on_an_articulated_master_is_refused_in_full():
    with pytest.raises(InputError) as err:
        big_end(_radial(0.0, master_of_b="A"), "B", 0.0)
    assert err.value.key == "cylinders.B.articulation.master"
    assert err.value.reason == "cylinder 'B': its master 'A' is itself articulated"


def test_articulation_on_a_master_of_another_throw_is_refused_in_full():
    with pytest.raises(InputError) as err:
        big_end(_radial(0.0, master_of_b="M", throw_of_b="2"), "B", 0.0)
    assert err.value.key == "cylinders.B.articulation.master"
    assert err.value.reason == "cylinder 'B': master 'M' runs on another throw"
