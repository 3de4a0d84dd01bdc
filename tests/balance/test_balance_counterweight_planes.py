"""Counterweight sizing of fe_crank.balance.counterweights by hand: two shafts (one
counter-rotating with a phase and an off-centre axis), a massless throw, a zero design,
moments about a shifted reference plane, the plane-determinant threshold of the
whole-shaft balance, and ``m = P / (r omega^2)`` below 1 rad/s."""

import math

import numpy as np
import pytest

from fe_crank import model
from fe_crank.balance import BalanceStrategy, counterweight_mass, free_forces, size_counterweights
from fe_crank.errors import InputError

W = 400.0
PHASE = math.pi / 6.0


def _rod():
    return model.Rod(0.2, 1.0, 0.05)  # 1 kg, c/l = 0.25: big-end share 0.75 kg


def _two_shafts():
    """Shaft ``a``: sense +1, phase 0, on the axis; throws ``A0`` (no mass, no cylinder) and
    ``A1`` (2 kg at R = 0.05 m, z = 0).  Shaft ``b``: sense -1, phase pi/6, axis at
    (0.3, 0.1) m; throw ``B1`` (2 kg, R = 0.05 m, z = 0.1 m) -- listed after ``A0`` and
    ``A1``, so sizing shaft ``b`` passes over throws of shaft ``a`` first.  Each loaded
    throw: m_rot = 2 + 0.75 = 2.75 kg, m_rot R = 0.1375 kg m."""
    shafts = (model.Shaft("a"), model.Shaft("b", sense=-1, phase=PHASE, centre=(0.3, 0.1)))
    throws = (
        model.Throw("A0", "a", 0.5, 0.05, -0.1, 0.0),
        model.Throw("A1", "a", 0.0, 0.05, 0.0, 2.0),
        model.Throw("B1", "b", 0.0, 0.05, 0.1, 2.0),
    )
    cyls = (model.Cylinder("1", "A1", 0.09, _rod(), 1.5), model.Cylinder("2", "B1", 0.09, _rod(), 1.5))
    return model.Engine("two-shaft", 4, shafts, throws, cyls)


def test_per_throw_counterweights_of_two_shafts_by_hand():
    """Rotating balance per throw, reference plane z_ref = 0.2 m.

    * A0 has no mass: a zero counterweight, reported at angle 0 (on the shaft too).
    * A1: U = 0.1375 kg m opposite the pin (psi_pin = 0): angle pi, on the shaft pi.
    * B1: pin at psi = phase + s angle = pi/6, counterweight at pi/6 + pi = 7pi/6, reported
      in (-pi, pi] as -5pi/6; on the shaft s (psi - phase) = -(-5pi/6 - pi/6) = pi.
    * At theta = 0, U omega^2 = 0.1375 * 400^2 = 22000 N along u(psi) = (sin, cos):
      A1 (0, -22000) N, B1 22000 (-1/2, -sqrt3/2) = (-11000, -19052.56) N.  About
      (0, 0, 0.2): A1 acts at (0, 0, -0.2), B1 at (0.3, 0.1, -0.1):
      Mx = -rz Fy = -(-0.2)(-22000) - (-0.1)(-19052.56) = -4400 - 1905.256 = -6305.256 N m,
      Mz = rx Fy - ry Fx = 0.3 (-19052.56) - 0.1 (-11000) = -5715.77 + 1100 = -4615.77 N m.
    * Every counterweight sits where its throw's centrifugal force acts, so the residual
      rotating + counterweights first order is zero, force and moment."""
    e = _two_shafts()
    st = BalanceStrategy(rotating_fraction=1.0)
    d = size_counterweights(e, st, W, reference_z=0.2)
    assert d.strategy is st
    assert d.before.reference_z == 0.2 and d.residual.reference_z == 0.2
    cw = {(c.shaft, round(c.z, 9)): c for c in d.counterweights}
    assert len(cw) == 3
    z0 = cw[("a", -0.1)]
    assert (z0.unbalance, z0.angle, z0.angle_on_shaft) == (0.0, 0.0, 0.0)
    a1, b1 = cw[("a", 0.0)], cw[("b", 0.1)]
    assert a1.unbalance == pytest.approx(0.1375, rel=1e-14) and b1.unbalance == pytest.approx(0.1375, rel=1e-14)
    assert a1.angle == pytest.approx(math.pi, abs=1e-12) and a1.angle_on_shaft == pytest.approx(math.pi, abs=1e-12)
    assert b1.angle == pytest.approx(-5 * math.pi / 6, abs=1e-12)
    assert b1.angle_on_shaft == pytest.approx(math.pi, abs=1e-12)
    f, m = d.residual.evaluate([0.0], sources=("counterweights",))
    s3 = 22000.0 * math.sqrt(3) / 2  # 19052.56 N
    np.testing.assert_allclose(f[0], [-11000.0, -22000.0 - s3], rtol=1e-12)
    np.testing.assert_allclose(m[0, 0], -0.2 * 22000.0 - 0.1 * s3, rtol=1e-12)
    np.testing.assert_allclose(m[0, 2], 0.3 * -s3 + 0.1 * 11000.0, rtol=1e-12)
    th = np.linspace(0.0, 4 * math.pi, 73)
    f, m = d.residual.evaluate(th, sources=("rotating", "counterweights"), orders=(1.0,))
    assert np.max(np.abs(f)) < 1e-9 * 22000.0 and np.max(np.abs(m)) < 1e-9 * 22000.0


def test_default_reference_plane_and_given_forces():
    """Without ``reference_z`` the moments are about z = 0 (the A1 counterweight at z = 0
    has no pitch/yaw moment, B1's Mx = -(0.1)(-19052.56) = 1905.256 N m at theta = 0); with
    ``forces`` given, the design is built on exactly that record."""
    e = _two_shafts()
    st = BalanceStrategy(rotating_fraction=1.0)
    d = size_counterweights(e, st, W)
    assert d.before.reference_z == 0.0
    _, m = d.residual.evaluate([0.0], sources=("counterweights",))
    assert m[0, 0] == pytest.approx(0.1 * 22000.0 * math.sqrt(3) / 2, rel=1e-12)
    ff = free_forces(e, W, reference_z=0.2)
    d2 = size_counterweights(e, st, W, forces=ff)
    assert d2.before is ff


def test_a_zero_design_adds_no_terms_and_reports_angle_zero():
    """Nothing balanced (both fractions 0): every counterweight is 0 kg m, reported at
    angle 0 in the engine frame and s (0 - phase) on its shaft (shaft b: -(0 - pi/6) = pi/6);
    the residual is the free forces unchanged."""
    e = _two_shafts()
    d = size_counterweights(e, BalanceStrategy(rotating_fraction=0.0), W)
    assert [c.unbalance for c in d.counterweights] == [0.0, 0.0, 0.0]
    assert [c.angle for c in d.counterweights] == [0.0, 0.0, 0.0]
    on = {c.shaft: c.angle_on_shaft for c in d.counterweights}
    assert on["a"] == 0.0 and on["b"] == pytest.approx(PHASE, abs=1e-15)
    assert d.residual.terms == d.before.terms


def _one_throw():
    return model.Engine(
        "single",
        4,
        (model.Shaft("main"),),
        (model.Throw("1", "main", 0.0, 0.05, 0.0, 2.0),),
        (model.Cylinder("1", "1", 0.09, _rod(), 1.5),),
    )


def _planes(planes):
    return size_counterweights(_one_throw(), BalanceStrategy(couple="whole_shaft", planes=planes), W)


def test_whole_shaft_plane_determinant_threshold_by_hand():
    """Two planes z1 < z2: sgn = (-1, +1), the system matrix [[2, 0], [z1 + z2, z2 - z1]]
    has det = 2 (z2 - z1); planes count as distinct when det >= 1e-12 max(1, z_max^2) m^2.

    * (0, 4e-13): det = 8e-13 < 1e-12 (max(1, z_max^2) = 1): refused; (0, 7.5e-13):
      det = 1.5e-12: accepted (a floor of 2 instead of 1 would refuse it).
    * (100, 100 + 1e-9): det = 2e-9 < 1e-12 * 100^2 = 1e-8: refused (a threshold scaled by
      z_max rather than z_max^2, 2e-10, or not scaled, would accept it).
    * (100, 100 + 1e-7): det = 2e-7 > 1e-8: accepted (one scaled by z_max^3, 1e-6, would
      refuse it).
    An accepted pair balances the throw's U = 0.1375 kg m at z = 0: U1 + U2 = U (opposite
    the pin) and z1 U1 + z2 U2 = 0, i.e. U1 = U z2 / (z2 - z1)."""
    for ok in ((0.0, 7.5e-13), (100.0, 100.0 + 1e-7)):
        d = _planes(ok)
        u1 = d.counterweights[0].unbalance
        z1, z2 = ok
        assert u1 == pytest.approx(0.1375 * z2 / (z2 - z1), rel=1e-6)
    for bad in ((0.0, 4e-13), (100.0, 100.0 + 1e-9)):
        with pytest.raises(InputError, match="distinct axial positions"):
            _planes(bad)


def test_counterweight_mass_below_one_rad_per_s_and_one_metre():
    """m = P / (r omega^2) (seed 000, eq. 161): P = 1 N, r = 0.5 m, omega = 0.5 rad/s:
    1 / (0.5 * 0.25) = 8 kg.  Speeds and radii below 1 are valid; zero is refused."""
    assert counterweight_mass(1.0, 0.5, 0.5) == pytest.approx(8.0, rel=1e-15)
    for r, w in ((0.0, 0.5), (0.5, 0.0)):
        with pytest.raises(InputError, match="must be positive"):
            counterweight_mass(1.0, r, w)


def test_per_throw_webs_either_side_of_the_throw():
    """web_offset 0.05 m: each throw's U = 0.1375 kg m is split into U/2 = 0.06875 kg m on
    its two webs at z_t - 0.05 and z_t + 0.05 (throw A1 at 0: -0.05 and +0.05 m)."""
    e = _one_throw()
    d = size_counterweights(e, BalanceStrategy(rotating_fraction=1.0, web_offset=0.05), W)
    assert sorted(c.z for c in d.counterweights) == pytest.approx([-0.05, 0.05], abs=1e-15)
    assert [c.unbalance for c in d.counterweights] == pytest.approx([0.06875, 0.06875], rel=1e-14)


def test_strategy_and_sizing_refusals_in_full():
    cases = [
        (
            lambda: BalanceStrategy(couple="whole_shaft", planes=(0.1,)),
            "balance.planes",
            "whole_shaft couple balance needs at least two counterweight planes",
        ),
        (lambda: BalanceStrategy(web_offset=-0.01), "balance.web_offset", "web_offset cannot be negative"),
        (lambda: counterweight_mass(1.0, 0.0, 10.0), "balance", "counterweight radius and speed must be positive"),
        (
            lambda: _planes((0.1, 0.1)),
            "balance.planes",
            "counterweight planes must lie at two or more distinct axial positions",
        ),
    ]
    for make, key, reason in cases:
        with pytest.raises(InputError) as err:
            make()
        assert (err.value.key, err.value.reason) == (key, reason)
