"""Free-force terms of fe_crank.balance.forces against hand arithmetic and ``M = r x F``:
the record's labels and scales, the moment arm of each source (throw plane, shaft centre,
pin offset, reference plane), and a cylinder without reciprocating mass among others."""

import math

import numpy as np
import pytest
from helpers.balance import engine

from fe_crank import model
from fe_crank.balance import free_forces
from fe_crank.balance.forces import reciprocating_terms, rotating_terms

W = 400.0


def _rod():
    return model.Rod(0.2, 1.0, 0.05)  # l = 0.2 m, 1 kg, cg 0.05 m from the big end: c/l = 0.25


def _single(bank=0.0, offset=0.0, z=0.0):
    return model.Engine(
        "single",
        4,
        (model.Shaft("main"),),
        (model.Throw("1", "main", 0.0, 0.05, z, 2.0),),
        (model.Cylinder("1", "1", 0.09, _rod(), 1.5, bank_angle=bank, pin_offset=offset),),
    )


def test_labels_and_scales_of_a_single_cylinder_by_hand():
    """m_rot = 2.0 + 1.0 (1 - 0.25) = 2.75 kg, m_j = 1.5 + 1.0 * 0.25 = 1.75 kg, R = 0.05 m,
    omega = 400 rad/s: force scale (2.75 + 1.75) 0.05 400^2 = 36000 N; every lever is 0 m
    (throw plane and shaft centre at the origin).  Also accepted: a speed below 1 rad/s."""
    ff = free_forces(_single(), W)
    assert (ff.engine, ff.speed, ff.reference_z) == ("single", W, 0.0)
    assert ff.force_scale == pytest.approx(36000.0, rel=1e-14)
    assert ff.length_scale == 0.0
    rot, tot = ff.term("rotating", 1), ff.total(1)
    assert (rot.source, rot.order, tot.source, tot.order) == ("rotating", 1.0, "total", 1.0)
    # first order, cylinder along +y: rotating 2.75 * 0.05 * 400^2 = 22000 N (a circle),
    # reciprocating 1.75 * 0.05 * 400^2 = 14000 N (A_1 = 1 exactly) along y
    assert rot.force_hodograph().major == pytest.approx(22000.0, rel=1e-12)
    np.testing.assert_allclose(np.hypot(*ff.term("reciprocating", 1).force.T), [0.0, 14000.0], atol=1e-6)
    np.testing.assert_allclose(tot.force, rot.force + ff.term("reciprocating", 1).force, rtol=1e-15, atol=1e-9)
    slow = free_forces(_single(), 0.5)
    assert slow.force_scale == pytest.approx(4.5 * 0.05 * 0.25, rel=1e-14)


def test_moments_about_a_shifted_reference_plane_for_every_source():
    """M = r x F with r = (x, y, z - z_ref): moving the reference plane by z_ref = 0.3 m
    adds z_ref Fy to Mx and -z_ref Fx to My, for each source (Nordberg radial engine:
    rotating, reciprocating and the yoke)."""
    e = engine("nordberg_radial.toml")
    a, b = free_forces(e, W), free_forces(e, W, reference_z=0.3)
    assert b.reference_z == 0.3
    for src in ("rotating", "reciprocating", "yoke"):
        ta, tb = a.term(src, 1), b.term(src, 1)
        assert np.max(np.abs(ta.force)) > 1.0
        scale = np.max(np.abs(ta.force))
        np.testing.assert_allclose(tb.moment[0], ta.moment[0] + 0.3 * ta.force[1], rtol=0, atol=1e-9 * scale)
        np.testing.assert_allclose(tb.moment[1], ta.moment[1] - 0.3 * ta.force[0], rtol=0, atol=1e-9 * scale)


def test_term_helpers_take_moments_about_the_origin_by_default():
    """rotating_terms / reciprocating_terms without reference_z: about z = 0, so a throw
    in the plane z = 0.1 m gives Mx = -0.1 Fy and My = 0.1 Fx."""
    e = _single(z=0.1)
    for t in rotating_terms(e, W) + reciprocating_terms(e, W):
        np.testing.assert_allclose(t.moment[0], -0.1 * t.force[1], rtol=1e-14, atol=1e-12)
        np.testing.assert_allclose(t.moment[1], 0.1 * t.force[0], rtol=1e-14, atol=1e-12)


def test_roll_moment_of_an_off_centre_shaft():
    """Rotating force of a shaft at (x, y) = (0.1, -0.3) m: Mz = x Fy - y Fx = 0.1 Fy + 0.3 Fx
    (the main shaft's throw carries no rotating mass and a massless rod)."""
    shafts = (model.Shaft("main"), model.Shaft("aux", centre=(0.1, -0.3)))
    throws = (model.Throw("m", "main", 0.0, 0.05), model.Throw("a", "aux", 0.0, 0.05, 0.0, 2.0))
    cyls = (model.Cylinder("m", "m", 0.09, model.Rod(0.2, 0.0, 0.05), 1.5), model.Cylinder("a", "a", 0.09, _rod(), 1.5))
    rot = free_forces(model.Engine("two", 4, shafts, throws, cyls), W).term("rotating", 1)
    assert rot.force_hodograph().major == pytest.approx(22000.0, rel=1e-12)
    np.testing.assert_allclose(rot.moment[2], 0.1 * rot.force[1] + 0.3 * rot.force[0], rtol=1e-13, atol=1e-9)


@pytest.mark.parametrize("bank_deg", [0.0, 90.0])
def test_pin_offset_moves_the_line_of_action(bank_deg):
    """A pin offset e = 10 mm puts the piston's line of action on the side the crankpin
    moves to after TDC: for a cylinder along +y (sense +1) at x = +e, so Mz = e Fy; for a
    cylinder along +x at y = -e, so Mz = -y Fx = e Fx.  Every order."""
    ff = free_forces(_single(bank=math.radians(bank_deg), offset=0.01), W)
    for k in (1.0, 2.0, 4.0):
        t = ff.term("reciprocating", k)
        f_along = t.force[1] if bank_deg == 0.0 else t.force[0]
        assert np.max(np.abs(f_along)) > 1.0
        np.testing.assert_allclose(t.moment[2], 0.01 * f_along, rtol=1e-9, atol=1e-9)


def test_cylinder_without_reciprocating_mass_does_not_hide_the_next():
    """Two cylinders on two throws 180 deg apart; the first has no piston and a massless rod:
    the second alone gives the first order 1.75 * 0.05 * 400^2 = 14000 N along y.  The force
    scale sums both throws: 1.0 * 0.05 * 400^2 = 8000 N (throw 1's own mass) plus
    (0.75 + 1.75) * 0.05 * 400^2 = 20000 N (throw 2), 28000 N."""
    shafts = (model.Shaft("main"),)
    throws = (model.Throw("1", "main", 0.0, 0.05, 0.0, 1.0), model.Throw("2", "main", math.pi, 0.05))
    cyls = (model.Cylinder("1", "1", 0.09, model.Rod(0.2, 0.0, 0.05), 0.0), model.Cylinder("2", "2", 0.09, _rod(), 1.5))
    ff = free_forces(model.Engine("pair", 4, shafts, throws, cyls), W)
    np.testing.assert_allclose(np.hypot(*ff.term("reciprocating", 1).force.T), [0.0, 14000.0], rtol=1e-12, atol=1e-6)
    assert ff.force_scale == pytest.approx(28000.0, rel=1e-14)
