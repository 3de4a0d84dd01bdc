"""Textbook balance results of common layouts."""

import math

import numpy as np
import pytest
from helpers.balance import engine, radial

from fe_crank.balance import BalanceStrategy, free_forces, size_counterweights
from fe_crank.balance.mechanism import crank_angle_global, reciprocating_mass
from fe_crank.mechanism.kinematics import harmonic_coefficients

W = 314.159  # rad/s (3000 rpm)


def basics(e):
    c = e.cylinders[0]
    r = e.throw(c.throw).crank_radius
    lam = r / c.rod.length
    return reciprocating_mass(c), r, harmonic_coefficients(lam)


def assert_zero(term, what=("force", "moment")):
    if "force" in what:
        assert term.force_hodograph().kind == "zero", term.force
    if "moment" in what:
        assert term.moment_hodograph().kind == "zero", term.moment


def test_inline4_flat_crank():
    """First-order force and couple zero; second-order force 4 m_j r omega^2 lambda (vertical)."""
    e = engine("inline4.toml")
    m, r, a = basics(e)
    ff = free_forces(e, W)
    assert_zero(ff.term("reciprocating", 1))
    assert_zero(ff.term("rotating", 1))
    h2 = ff.term("reciprocating", 2).force_hodograph()
    assert h2.kind == "line" and math.degrees(h2.tilt) == pytest.approx(90.0)
    assert h2.major == pytest.approx(4 * m * r * W**2 * a[2], rel=1e-9)
    lam = r / e.cylinders[0].rod.length
    assert h2.major == pytest.approx(4 * m * r * W**2 * lam, rel=lam**2 / 4 + 1e-3)  # textbook, truncated
    assert_zero(ff.term("reciprocating", 2), ("moment",))


def test_inline6_first_and_second_order_forces_and_couples_vanish():
    e = engine("inline6.toml")
    m, r, a = basics(e)
    ff = free_forces(e, W)
    for k in (1, 2, 4):
        assert_zero(ff.term("reciprocating", k))
    assert_zero(ff.term("rotating", 1))
    # the sixth order adds up: 6 m_j r omega^2 A6, vertical
    h6 = ff.term("reciprocating", 6).force_hodograph()
    assert h6.major == pytest.approx(6 * m * r * W**2 * abs(a[6]), rel=1e-6)


def test_inline3_first_order_couple_is_sqrt3_m_r_omega2_a():
    e = engine("inline3.toml")
    m, r, _ = basics(e)
    spacing = e.throws[1].axial_position - e.throws[0].axial_position
    ff = free_forces(e, W)
    for k in (1, 2):
        assert_zero(ff.term("reciprocating", k), ("force",))
    h = ff.term("reciprocating", 1).moment_hodograph()
    assert h.kind == "line"
    assert h.major == pytest.approx(math.sqrt(3) * m * r * W**2 * spacing, rel=1e-9)


def test_inline2_180_first_order_couple_and_second_order_force():
    e = engine("inline2_180.toml")
    m, r, a = basics(e)
    spacing = e.throws[1].axial_position - e.throws[0].axial_position
    ff = free_forces(e, W)
    assert_zero(ff.term("reciprocating", 1), ("force",))
    assert ff.term("reciprocating", 1).moment_hodograph().major == pytest.approx(m * r * W**2 * spacing, rel=1e-9)
    assert ff.term("reciprocating", 2).force_hodograph().major == pytest.approx(2 * m * r * W**2 * a[2], rel=1e-9)


def test_v8_crossplane_second_order_zero_and_first_couple_balanced_by_counterweights():
    e = engine("v8_crossplane.toml")
    ff = free_forces(e, W)
    assert_zero(ff.term("reciprocating", 2))
    assert_zero(ff.term("reciprocating", 1), ("force",))
    h1 = ff.term("reciprocating", 1).moment_hodograph()
    assert h1.kind == "circle"  # purely co-rotating: counterweights can take it all
    for strategy in (BalanceStrategy(1.0, 0.5, "whole_shaft", planes=(-0.2, 0.2)), BalanceStrategy(1.0, 0.5)):
        res = size_counterweights(e, strategy, W).residual
        t = res.total(1)
        scale = h1.major
        assert np.abs(t.force).max() < 1e-9 * scale and np.abs(t.moment).max() < 1e-9 * scale


def test_v8_flatplane_first_order_zero_second_order_horizontal():
    e = engine("v8_flatplane.toml")
    m, r, a = basics(e)
    ff = free_forces(e, W)
    assert_zero(ff.term("reciprocating", 1))
    h2 = ff.term("reciprocating", 2).force_hodograph()
    assert h2.kind == "line" and abs(math.degrees(h2.tilt)) == pytest.approx(0.0, abs=1e-9)
    assert h2.major == pytest.approx(4 * math.sqrt(2) * m * r * W**2 * a[2], rel=1e-9)
    assert_zero(ff.term("reciprocating", 2), ("moment",))


def test_v2_90_first_order_constant_and_turning_with_the_crank():
    e = engine("v2_90.toml")
    m, r, _ = basics(e)
    ff = free_forces(e, W)
    h = ff.term("reciprocating", 1).force_hodograph()
    assert h.kind == "circle"
    th = np.linspace(0, 2 * np.pi, 37)
    f, _ = ff.evaluate(th, sources=("reciprocating",), orders=(1,))
    psi = crank_angle_global(e, "1", th)
    assert np.allclose(np.hypot(f[:, 0], f[:, 1]), 2 * m / 2 * r * W**2)  # m_j r omega^2
    assert np.allclose(f[:, 0] * np.cos(psi) - f[:, 1] * np.sin(psi), 0.0, atol=1e-9 * m * r * W**2)  # along the crank
    assert np.all(f[:, 0] * np.sin(psi) + f[:, 1] * np.cos(psi) > 0)  # pointing outwards


@pytest.mark.parametrize("i", [3, 5, 7, 12])
def test_radial_first_order_is_half_i_m_r_omega2_turning_with_the_crank(i):
    e = radial(i)
    m, r = e.cylinders[0].piston_mass, 0.1
    ff = free_forces(e, W)
    h = ff.term("reciprocating", 1).force_hodograph()
    assert h.kind == "circle"
    assert h.major == pytest.approx(i / 2 * m * r * W**2, rel=1e-12)
    assert h.co_angle == pytest.approx(0.0, abs=1e-12)  # along the crank at theta = 0
    h2 = ff.term("reciprocating", 2).force_hodograph()
    if i == 3:
        # sum_j cos 2(psi - b_j) u(b_j) = (1/2) sum_j [u(2 psi - b_j) + u(3 b_j - 2 psi)]: for i = 3 the
        # second sum survives, a vector (3/2) m r omega^2 A2 turning backwards at twice the speed
        a2 = harmonic_coefficients(r / e.cylinders[0].rod.length)[2]
        assert h2.kind == "circle" and h2.counter_magnitude == pytest.approx(1.5 * m * r * W**2 * a2, rel=1e-9)
    else:
        assert h2.kind == "zero"


def test_boxer4_forces_vanish_at_every_order():
    ff = free_forces(engine("boxer4.toml"), W)
    for k in ff.orders:
        assert_zero(ff.total(k), ("force",))


def test_v6_90_common_pins_first_order_is_a_rotating_couple():
    e = engine("v6_90.toml")
    ff = free_forces(e, W)
    assert_zero(ff.term("reciprocating", 1), ("force",))
    assert ff.term("reciprocating", 1).moment_hodograph().kind == "circle"
    res = size_counterweights(e, BalanceStrategy(1.0, 0.5, "whole_shaft", planes=(-0.15, 0.15)), W).residual
    assert res.total(1).moment_hodograph().kind == "zero"


def test_moments_move_with_the_reference_point():
    """M(z0) = M(0) - z0 x F: a free force makes the couple depend on the reference point."""
    e = engine("inline2_180.toml")
    a, b = free_forces(e, W), free_forces(e, W, reference_z=0.3)
    for k in (1, 2):
        ta, tb = a.total(k), b.total(k)
        fx, fy = ta.force
        assert np.allclose(tb.moment[0], ta.moment[0] + 0.3 * fy)
        assert np.allclose(tb.moment[1], ta.moment[1] - 0.3 * fx)


def test_v6_60_split_pins_forces_balanced_couples_left():
    """Even-firing 60 deg V6 on six split pins: first- and second-order forces cancel, the
    rocking couples of both orders remain (the classical trade of this layout)."""
    ff = free_forces(engine("v6_60.toml"), W)
    for k in (1, 2):
        assert_zero(ff.term("reciprocating", k), ("force",))
        assert ff.term("reciprocating", k).moment_hodograph().kind != "zero"


def test_articulated_nine_cylinder_radial_departs_from_the_plain_star():
    """With link rods the first order stays close to (i/2) m_j r omega^2 (mean m_j) but becomes
    an ellipse, and a second order appears that a plain star of i >= 4 cancels exactly."""
    e = engine("radial9_articulated.toml")
    r = e.throws[0].crank_radius
    mj = np.mean([reciprocating_mass(c) for c in e.cylinders])
    ff = free_forces(e, W)
    h1 = ff.term("reciprocating", 1).force_hodograph()
    assert h1.kind == "ellipse"
    assert 0.5 * (h1.major + h1.minor) == pytest.approx(9 / 2 * mj * r * W**2, rel=0.05)
    h2 = ff.term("reciprocating", 2).force_hodograph()
    assert 0.01 * h1.major < h2.major < 0.2 * h1.major
