"""Balance shafts (``fe_crank.balance.shafts``) designed for targets written by hand, so that
every field of the design follows from closed forms: the unbalance ``U = |P| / (k omega)^2``
per rotating part, its direction ``arg(-P)`` at theta = 0, the shafts' names and signed
speed ratios, their default places across the major axis, the planes of a couple pair,
the roll moment, the residual, and the refusals in full.

Notation (``fe_crank.balance.hodograph.rotating_parts``): ``w = F_y + i F_x``;
``w(theta) = P exp(i k theta) + Q exp(-i k theta)``; a direction ``psi`` from ``+y``
towards ``+x`` is ``exp(i psi)``."""

import cmath
import math

import numpy as np
import pytest

from fe_crank import model
from fe_crank.balance import balance_shafts, free_forces
from fe_crank.balance.forces import FreeForces
from fe_crank.balance.terms import OrderTerm, point_term
from fe_crank.errors import InputError

W = 100.0  # rad/s


def record(*terms, speed=W, ref_z=0.0, scale=1000.0):
    return FreeForces("hand", speed, ref_z, tuple(terms), scale, 1.0)


def force_term(order, p, q, source="reciprocating"):
    """Force whose rotating parts are ``p``, ``q`` (N), acting at the origin.  With
    F_x = a cos + b sin, F_y = c cos + d sin and ``w = F_y + i F_x``:
    c + b = 2 Re P, a - d = 2 Im P, c - b = 2 Re Q, a + d = 2 Im Q, so
    c = Re(P + Q), b = Re(P - Q), a = Im(P + Q), d = Im(Q - P)."""
    c, b = (p + q).real, (p - q).real
    a, d = (p + q).imag, (q - p).imag
    return point_term(source, order, np.array([[a, b], [c, d]]), (0.0, 0.0, 0.0))


def couple_term(order, p, q, source="reciprocating"):
    """A pure couple (M_x, M_y) with rotating parts ``p``, ``q`` (N m), no force."""
    c, b = (p + q).real, (p - q).real
    a, d = (p + q).imag, (q - p).imag
    return OrderTerm(source, float(order), np.zeros((2, 2)), np.array([[a, b], [c, d], [0.0, 0.0]]))


def u(angle):
    return (math.sin(angle), math.cos(angle))


def test_single_cylinder_secondary_force_by_a_pair_at_twice_the_speed():
    """Closed form: one cylinder along +y, r = 0.05 m, l = 0.2 m (lambda = 1/4),
    m_j = 1.5 + 1.0 * 0.25 = 1.75 kg, omega = 400 rad/s.  Its secondary force is
    m_j r omega^2 A_2 cos 2 theta along y, A_2 = lambda + lambda^3/4 + 15 lambda^5/128 =
    0.25 + 0.00390625 + 0.00011444 = 0.25402069 (the lambda^7 term is below 2e-5 of A_2):
    F_2 = 1.75 * 0.05 * 400^2 * 0.25402069 = 3556.290 N.  Two shafts at speed ratios +2 and
    -2 each take half: U (2 omega)^2 = F_2 / 2, U = 1778.145 / 800^2 = 2.778352e-3 kg m,
    pointing -y at theta = 0 (against the force at its peak); checked to 1e-4, so that an
    error of 1 % in U (or omega instead of 2 omega: a factor 4) fails."""
    e = model.Engine(
        "single",
        4,
        (model.Shaft("main"),),
        (model.Throw("1", "main", 0.0, 0.05),),
        (model.Cylinder("1", "1", 0.09, model.Rod(0.2, 1.0, 0.05), 1.5),),
    )
    ff = free_forces(e, 400.0)
    d = balance_shafts(ff, "force", 2)
    assert [(s.name, s.speed_ratio) for s in d.shafts] == [("force2_plus", 2), ("force2_minus", -2)]
    a2 = 0.25 + 0.25**3 / 4 + 15 * 0.25**5 / 128
    assert a2 == pytest.approx(0.25402069, abs=1e-8)
    for s in d.shafts:
        assert s.unbalance == pytest.approx(1.75 * 0.05 * 400.0**2 * a2 / 2 / 800.0**2, rel=1e-4)
        assert s.unbalance == pytest.approx(2.778352e-3, rel=1e-4)
        assert u(s.angle) == pytest.approx((0.0, -1.0), abs=1e-12)
    assert d.residual.total(2).force_hodograph().kind == "zero"


def test_line_force_pair_every_field_by_hand():
    """Order 2, F = 1000 cos 2 theta along y (P = Q = 500 N) at omega = 100 rad/s, reference
    plane z = 0.3 m.  U = 500 / 200^2 = 0.0125 kg m on each shaft, direction -y; the shafts
    sit at +-offset across the force line (default offset 0.1 m: x = +-0.1), the one
    turning with the crank at +x; both unbalances in the reference plane; no roll moment.
    The shafts' terms carry the source ``balance_shafts``, their forces cancel the target
    and, acting in the reference plane, add no pitch or yaw couple."""
    ff = record(force_term(2, 500 + 0j, 500 + 0j), ref_z=0.3)
    d = balance_shafts(ff, "force", 2)
    assert (d.component, d.order) == ("force", 2)
    assert d.roll_moment < 1e-12  # the two x parts act at the same height
    plus, minus = d.shafts
    assert (plus.name, plus.speed_ratio, minus.name, minus.speed_ratio) == ("force2_plus", 2, "force2_minus", -2)
    for s, x in ((plus, 0.1), (minus, -0.1)):
        assert s.unbalance == pytest.approx(0.0125, rel=1e-14)
        assert u(s.angle) == pytest.approx((0.0, -1.0), abs=1e-15)
        assert s.position == pytest.approx((x, 0.0), abs=1e-15)
        assert s.z == (0.3,) and s.on_crankshaft is False
        assert s.constraint == (
            "axes parallel to the crank axis and symmetric about it, in the plane across the "
            "force line; unbalance in the plane of the force resultant"
        )
    own = d.residual.term("balance_shafts", 2)
    np.testing.assert_allclose(own.force, [[0.0, 0.0], [-1000.0, 0.0]], atol=1e-12)
    np.testing.assert_allclose(own.moment, 0.0, atol=1e-12)
    assert d.residual.sources == ("reciprocating", "balance_shafts")
    assert np.abs(d.residual.total(2).force).max() < 1e-12


def test_ellipse_pair_is_placed_across_its_major_axis():
    """P = 600 e^{i 80 deg}, Q = 200 e^{i 20 deg} (order 1, omega = 100): the major axis lies
    at (80 + 20)/2 = 50 deg, so the shafts sit at +-offset u(140 deg) (offset 0.05 m):
    (0.05 sin 140, 0.05 cos 140) = (0.0321394, -0.0383022) m for the shaft turning with the
    crank, the opposite point for the other.  U = 600 / 100^2 = 0.06 and 200 / 100^2 = 0.02
    kg m, directions arg(-P) = 80 - 180 = -100 deg and arg(-Q) = -160 deg.  An axis at
    80 deg (the phase of P alone) or 30 deg (half their difference) moves the shafts by
    2 * 0.05 sin(15 deg) = 26 mm or 17 mm."""
    p, q = cmath.rect(600.0, math.radians(80)), cmath.rect(200.0, math.radians(20))
    d = balance_shafts(record(force_term(1, p, q)), "force", 1, offset=0.05)
    plus, minus = d.shafts
    assert (plus.name, plus.speed_ratio, minus.name, minus.speed_ratio) == ("force1_plus", 1, "force1_minus", -1)
    assert plus.position == pytest.approx(
        (0.05 * math.sin(math.radians(140)), 0.05 * math.cos(math.radians(140))), abs=1e-15
    )
    assert plus.position == pytest.approx((0.0321394, -0.0383022), abs=1e-7)
    assert minus.position == pytest.approx((-0.0321394, 0.0383022), abs=1e-7)
    assert (plus.unbalance, minus.unbalance) == pytest.approx((0.06, 0.02), rel=1e-14)
    assert math.degrees(plus.angle) == pytest.approx(-100.0, abs=1e-12)
    assert math.degrees(minus.angle) == pytest.approx(-160.0, abs=1e-12)
    assert np.abs(d.residual.total(1).force).max() < 1e-9


def test_co_rotating_circle_needs_one_shaft_and_adds_a_roll_moment():
    """P = 500 e^{i 60 deg}, Q = 0 (order 1, omega = 100): one shaft turning with the crank,
    U = 500 / 100^2 = 0.05 kg m at arg(-P) = -120 deg, on the major axis' normal
    u(60 + 90 deg) at the default offset 0.1 m: (0.05, -0.0866025) m.  Its force
    500 u(-120 deg + theta) acts off the crank axis: M_z = x F_y - y F_x has amplitude
    500 N * 0.1 m = 50 N m (the lever is perpendicular to a force turning around it)."""
    d = balance_shafts(record(force_term(1, cmath.rect(500.0, math.radians(60)), 0j)), "force", 1)
    (s,) = d.shafts
    assert (s.name, s.speed_ratio) == ("force1_plus", 1)
    assert s.unbalance == pytest.approx(0.05, rel=1e-14)
    assert math.degrees(s.angle) == pytest.approx(-120.0, abs=1e-12)
    assert s.position == pytest.approx((0.05, -0.1 * math.sqrt(3) / 2), abs=1e-15)
    assert d.roll_moment == pytest.approx(50.0, rel=1e-12)
    assert np.abs(d.residual.total(1).force).max() < 1e-9


def test_counter_rotating_circle_needs_one_shaft_turning_against_the_crank():
    """P = 0, Q = 300 e^{i 90 deg} (a force along +x at theta = 0 turning against the
    crank), order 1: one shaft at speed ratio -1, U = 0.03 kg m at arg(-Q) = -90 deg,
    placed at -offset u(90 + 90 deg) = (0, +0.1) m (the side of a counter-rotating part)."""
    d = balance_shafts(record(force_term(1, 0j, 300j)), "force", 1)
    (s,) = d.shafts
    assert (s.name, s.speed_ratio) == ("force1_minus", -1)
    assert s.unbalance == pytest.approx(0.03, rel=1e-14)
    assert math.degrees(s.angle) == pytest.approx(-90.0, abs=1e-12)
    assert s.position == pytest.approx((0.0, 0.1), abs=1e-15)
    assert np.abs(d.residual.total(1).force).max() < 1e-9


def test_reference_shaft_turning_backwards_swaps_the_speed_signs():
    """reference_sense = -1: the part turning in the engine's positive sense turns against
    the reference crankshaft, speed ratio -2 and the name ``minus``; the other +2, ``plus``."""
    d = balance_shafts(record(force_term(2, 500 + 0j, 500 + 0j)), "force", 2, reference_sense=-1)
    assert [(s.name, s.speed_ratio) for s in d.shafts] == [("force2_minus", -2), ("force2_plus", 2)]


def test_second_order_couple_pair_by_hand():
    """M_x = 400 cos 2 theta N m (P = Q = 200i), omega = 100, span 0.25 m, reference plane
    z = -0.1 m.  Each shaft carries +U at z_r + span/2 = 0.025 m and -U at z_r - span/2 =
    -0.225 m, U = |P| / (span (2 omega)^2) = 200 / (0.25 * 40000) = 0.02 kg m, pointing +y
    (U e^{i psi} = -i P / (L (k omega)^2) = 200 / 10000 > 0); places across the major axis
    (90 deg): +-0.1 u(180 deg) = (0, -+0.1) m.  Pair check: F = U (2 omega)^2 = 800 N at
    +-L/2 gives M_x = -L F cos 2 theta = -200 cos 2 theta per shaft, -400 for both: zero
    residual couple, and no force."""
    ff = record(couple_term(2, 200j, 200j), ref_z=-0.1)
    d = balance_shafts(ff, "couple", 2, span=0.25)
    plus, minus = d.shafts
    assert (plus.name, plus.speed_ratio, minus.name, minus.speed_ratio) == ("couple2_plus", 2, "couple2_minus", -2)
    for s, y in ((plus, -0.1), (minus, 0.1)):
        assert s.unbalance == pytest.approx(0.02, rel=1e-14)
        assert u(s.angle) == pytest.approx((0.0, 1.0), abs=1e-15)
        assert s.z == pytest.approx((0.025, -0.225), abs=1e-15)
        assert s.position == pytest.approx((0.0, y), abs=1e-15)
        assert s.on_crankshaft is False
        assert s.constraint == "axis parallel to the crank axis, anywhere in the crankcase; two opposed unbalances"
    own = d.residual.term("balance_shafts", 2)
    np.testing.assert_allclose(own.moment[:2], [[-400.0, 0.0], [0.0, 0.0]], atol=1e-9)
    np.testing.assert_allclose(own.force, 0.0, atol=1e-9)
    assert (d.component, d.order) == ("couple", 2)


@pytest.mark.parametrize("sense", [1, -1])
def test_first_order_couple_takes_a_crank_pair_and_one_shaft(sense):
    """Order-1 couple M_x = 400 cos theta (P = Q = 200i), omega = 100, span 0.2 m: the part
    turning with the reference crankshaft is a counterweight pair on it (on the crank
    axis, speed ratio +1, ``couple1_crank``), the other a shaft at -1 placed at the default
    offset; U = 200 / (0.2 * 100^2) = 0.1 kg m each.  With reference_sense = -1 the roles of
    P and Q swap."""
    d = balance_shafts(record(couple_term(1, 200j, 200j)), "couple", 1, reference_sense=sense)
    crank = next(s for s in d.shafts if s.on_crankshaft)
    other = next(s for s in d.shafts if not s.on_crankshaft)
    assert [s.name for s in d.shafts] == (
        ["couple1_crank", "couple1_minus"] if sense == 1 else ["couple1_minus", "couple1_crank"]
    )
    assert (crank.speed_ratio, crank.position) == (1, (0.0, 0.0))
    assert crank.constraint == "counterweight pair on the crankshaft (one balance shaft plus a crank pair)"
    assert other.speed_ratio == -1 and math.hypot(*other.position) == pytest.approx(0.1, rel=1e-14)
    assert (crank.unbalance, other.unbalance) == pytest.approx((0.1, 0.1), rel=1e-14)
    assert np.abs(d.residual.total(1).moment).max() < 1e-9


def test_zero_target_returns_the_record_unchanged():
    """No order-2 term: nothing to cancel, no shafts, the residual is the given record."""
    ff = record(force_term(1, 500 + 0j, 0j))
    d = balance_shafts(ff, "couple", 2)
    assert (d.component, d.order, d.shafts, d.roll_moment) == ("couple", 2, (), 0.0)
    assert d.residual is ff


def test_a_one_newton_target_is_balanced():
    """F = 1 cos 2 theta N (P = Q = 0.5 N, |P| + |Q| = 1 N exactly) at omega = 1 rad/s:
    two shafts of U = 0.5 / 2^2 = 0.125 kg m (only an exactly zero target is skipped)."""
    d = balance_shafts(record(force_term(2, 0.5 + 0j, 0.5 + 0j), speed=1.0, scale=1.0), "force", 2)
    assert [s.unbalance for s in d.shafts] == pytest.approx([0.125, 0.125], rel=1e-14)


def test_the_part_threshold_is_relative_to_the_target():
    """A rotating part below 1e-12 of |P| + |Q| is round-off and gets no shaft; one of 1e-11
    is kept, at any scale: a 1-mN target with a 1e-14 N counter-rotating part keeps two
    shafts; a 1-kN target whose co-rotating part is 1e-13 of it (1e-10 N) keeps one, the
    shaft of the larger part."""
    d = balance_shafts(record(force_term(1, 1e-3 + 0j, 1e-14 + 0j), scale=1e-3), "force", 1)
    assert [s.name for s in d.shafts] == ["force1_plus", "force1_minus"]
    assert d.shafts[1].unbalance == pytest.approx(1e-14 / W**2, rel=1e-9)
    d = balance_shafts(record(force_term(1, 1e-10 + 0j, 1000.0 + 0j)), "force", 1)
    assert [s.name for s in d.shafts] == ["force1_minus"]


def test_a_part_of_exactly_the_threshold_is_round_off():
    """P = 1 N, Q = 1.000000000001e-12 i N: in floating point 1e-12 * (|P| + |Q|) equals |Q|
    exactly (checked below), and a part at the threshold counts as round-off: one shaft.
    The coefficients are exact: F_x = |Q| cos + sin, F_y = cos + |Q| sin (record force
    scale 1e-6 N, so that the record's own round-off clearing leaves them)."""
    q = 1.000000000001e-12
    assert 1e-12 * (1.0 + q) == q
    d = balance_shafts(record(force_term(1, 1.0 + 0j, q * 1j), scale=1e-6), "force", 1)
    assert [s.name for s in d.shafts] == ["force1_plus"]


def test_shaft_terms_cancel_only_the_selected_sources():
    """Target the reciprocating source only: the rotating 700 N of the same order stays in
    the residual; only the 300 N line is cancelled."""
    ff = record(force_term(1, 150 + 0j, 150 + 0j), force_term(1, 700 + 0j, 0j, source="rotating"))
    d = balance_shafts(ff, "force", 1, sources=("reciprocating",))
    assert [s.unbalance for s in d.shafts] == pytest.approx([0.015, 0.015], rel=1e-14)
    t = d.residual.total(1).force_hodograph()
    assert (t.kind, t.major) == ("circle", pytest.approx(700.0, rel=1e-12))


@pytest.mark.parametrize(
    "kwargs, key, reason",
    [
        ({"component": "torque"}, "balance.shafts.component", "'torque' is not one of ('force', 'couple')"),
        ({"order": 3}, "balance.shafts.order", "balance shafts are for orders 1 and 2 (got 3)"),
        ({"offset": -0.01}, "balance.shafts", "offset must be >= 0 and span > 0"),
        ({"span": 0.0}, "balance.shafts", "offset must be >= 0 and span > 0"),
        ({"offset": math.nan}, "balance.shafts", "offset must be >= 0 and span > 0"),
    ],
)
def test_refusals_in_full(kwargs, key, reason):
    args = {"component": "force", "order": 2, **kwargs}
    with pytest.raises(InputError) as err:
        balance_shafts(record(force_term(2, 500 + 0j, 500 + 0j)), args.pop("component"), args.pop("order"), **args)
    assert (err.value.key, err.value.reason) == (key, reason)


def test_offset_zero_is_accepted():
    """offset = 0 puts both force shafts on the crank axis: allowed (the forces cancel;
    only a placement given by the user is checked against the axis)."""
    d = balance_shafts(record(force_term(2, 500 + 0j, 500 + 0j)), "force", 2, offset=0.0)
    assert [s.position for s in d.shafts] == [(0.0, 0.0), (0.0, 0.0)]


def test_free_placement_fields_and_refusals_in_full():
    ff = record(force_term(2, 500 + 0j, 500 + 0j))
    d = balance_shafts(ff, "force", 2, positions=[(0.0, 0.05), (1e-9, 0.0)])
    assert [s.position for s in d.shafts] == [(0.0, 0.05), (1e-9, 0.0)]  # 1e-9 m is off the axis
    assert d.shafts[0].constraint.endswith("resultant; placed as given")
    key = "balance.shafts.positions"
    cases = [
        ([(0.1, 0.0)], "the order-2 force needs 2 shaft(s) (force2_plus, force2_minus); give one position each"),
        ([(math.nan, 0.1), (-0.1, 0.0)], "positions must be finite"),
        ([(0.1, 0.0), (0.1, math.inf)], "positions must be finite"),
        ([(0.1, 0.0), (5e-10, 0.0)], "balance shaft force2_minus cannot sit on the crank axis"),
    ]
    for positions, reason in cases:
        with pytest.raises(InputError) as err:
            balance_shafts(ff, "force", 2, positions=positions)
        assert (err.value.key, err.value.reason) == (key, reason)
    couple = record(couple_term(1, 200j, 200j))
    with pytest.raises(InputError) as err:
        balance_shafts(couple, "couple", 1, positions=[(0.0, 1e-6), (0.0, 0.1)])
    assert (err.value.key, err.value.reason) == (
        key,
        "couple1_crank is a counterweight pair on the crankshaft: its position is the crank axis (0, 0)",
    )
    d = balance_shafts(couple, "couple", 1, positions=[(0.0, 0.0), (0.0, 0.1)])
    assert d.shafts[0].constraint == (
        "counterweight pair on the crankshaft (one balance shaft plus a crank pair); placed as given"
    )
