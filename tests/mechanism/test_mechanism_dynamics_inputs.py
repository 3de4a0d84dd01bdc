"""Dynamics stage: the cycle grid, the refusal of bad step and speed-fluctuation
arguments (by message and key), and an engine without a gas table (inertia only)."""

from dataclasses import replace

import numpy as np
import pytest

from fe_crank.errors import InputError
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.dynamics import analyse

SEED_CASE = "loadcases/single_cylinder.toml"


@pytest.fixture(scope="module")
def seed(request):
    return load_loadcase(request.config.rootpath / SEED_CASE)


@pytest.mark.parametrize("step", [0.0, -0.01, float("nan")])
def test_angle_step_must_be_positive(seed, step):
    with pytest.raises(InputError, match="angle step must be positive") as err:
        analyse(seed.engine, seed.operating, step=step)
    assert err.value.key == "step"


def test_cycle_grid_has_round_cycle_over_step_equal_steps_and_at_least_eight(seed):
    """Four-stroke cycle, 720 deg: step 720/8.4 deg gives round(8.4) = 8 steps of exactly
    90 deg (0, 90, ..., 630); step 720/7.4 deg gives round(7.4) = 7 < 8 steps: refused."""
    assert seed.engine.cycle_angle == pytest.approx(4 * np.pi, rel=1e-15)
    res = analyse(seed.engine, seed.operating, step=np.radians(720 / 8.4))
    np.testing.assert_allclose(np.degrees(res.theta), 90.0 * np.arange(8), rtol=0, atol=1e-12)
    assert res.cycle == pytest.approx(4 * np.pi, rel=1e-15)
    with pytest.raises(InputError, match="too coarse for the cycle") as err:
        analyse(seed.engine, seed.operating, step=np.radians(720 / 7.4))
    assert err.value.key == "step"


@pytest.mark.parametrize("delta", [0.0, -0.01])
def test_speed_fluctuation_must_be_positive(seed, delta):
    with pytest.raises(InputError, match="speed_fluctuation must be positive") as err:
        analyse(seed.engine, seed.operating, step=np.radians(10), speed_fluctuation=delta)
    assert err.value.key == "speed_fluctuation"


def test_engine_without_gas_table_has_zero_gas_force_and_says_so(seed):
    """No gas table: cylinder and crankcase both at 101325 Pa, so F_g = 0 and the rod force
    is the inertia alone; one warning names the model."""
    res = analyse(replace(seed.engine, gas=None), seed.operating, step=np.radians(10))
    assert res.warnings == ("engine has no gas pressure: inertia forces only",)
    cyl = res.cylinders[seed.engine.cylinders[0].name]
    assert cyl.pressure.shape == cyl.gas.shape == res.theta.shape
    np.testing.assert_array_equal(cyl.pressure, 101325.0)
    np.testing.assert_array_equal(cyl.gas, 0.0)
    assert res.indicated_work == pytest.approx(0.0, abs=1e-9)  # closed integral of a constant p dV (J)


def test_slider_crank_at_tdc_by_hand_for_a_scalar_angle():
    """At TDC (phi = 0, no offset) the rod lies on the axis: beta = 0, beta'' = 0 and the
    rod's centre of mass has no lateral acceleration, so the side thrust and the tangential
    force vanish and, with the two-mass rod (J = m c (l - c)), the radial force on the pin is
    ``-F_g + (m_p + m c/l) r w^2 (1 + lam) + m (1 - c/l) r w^2``.  r = 0.05 m, l = 0.2 m
    (lam = 0.25), w = 100 rad/s: r w^2 = 500, a = 500 * 1.25 = 625 m/s^2; m_p = 1.5 kg,
    m = 1 kg, c = 0.05 m (c/l = 0.25), F_g = 10 kN:
    radial = -10000 + 1.75 * 625 + 0.75 * 500 = -10000 + 1093.75 + 375 = -8531.25 N;
    rod force = F_g - m_p a = 10000 - 937.5 = 9062.5 N.  A scalar angle gives scalars."""
    from fe_crank.mechanism.slider_crank import solve_cylinder

    sol = solve_cylinder(0.0, r=0.05, l=0.2, omega=100.0, gas_force=10000.0, piston_mass=1.5, rod_mass=1.0, rod_cg=0.05)
    for name in ("rod_force", "side_thrust", "tangential", "radial", "torque"):
        assert np.shape(sol[name]) == ()
    assert float(sol["radial"]) == pytest.approx(-8531.25, rel=1e-13)
    assert float(sol["rod_force"]) == pytest.approx(9062.5, rel=1e-13)
    for name in ("side_thrust", "tangential", "torque"):
        assert float(sol[name]) == pytest.approx(0.0, abs=1e-9)


def test_default_speed_fluctuation_is_one_percent(seed):
    """The flywheel of docs/mechanism.md is for delta = 0.01, the default; J = dE / (delta w^2)."""
    res = analyse(seed.engine, seed.operating, step=np.radians(10))
    assert res.speed_fluctuation == 0.01
    w = seed.operating.speed
    assert res.flywheel_inertia == pytest.approx(res.excess_energy / (0.01 * w**2), rel=1e-14)


@pytest.mark.parametrize("offset_deg, off_tdc", [(0.01, 0.01), (10.0, 10.0), (370.0, 10.0), (-20.0, -20.0)])
def test_firing_offset_off_its_tdc_is_reported_even_when_small(seed, offset_deg, off_tdc):
    """Single cylinder, axis at bank 0: firing TDC is crank angle 0 mod 360 deg; a firing
    offset of 0.01, 10, 370 (= 360 + 10) or -20 deg is 0.01, 10, 10 or -20 deg from the
    nearest TDC, and the warning says so; 360 deg (the other revolution of the four-stroke
    cycle) is a TDC and is not reported."""
    assert seed.engine.cylinders[0].firing_offset == 0.0
    assert not analyse(seed.engine, seed.operating, step=np.radians(10)).warnings
    cyl = replace(seed.engine.cylinders[0], firing_offset=np.radians(offset_deg))
    res = analyse(replace(seed.engine, cylinders=(cyl,)), seed.operating, step=np.radians(10))
    (w,) = res.warnings
    assert w == (
        f"cylinder {cyl.name}: firing_offset {offset_deg:.6g} deg is not at its TDC (crank "
        f"{off_tdc:.6g} deg from the axis); the gas table is applied from the nearest TDC"
    )
    cyl = replace(seed.engine.cylinders[0], firing_offset=np.radians(360.0))
    assert not analyse(replace(seed.engine, cylinders=(cyl,)), seed.operating, step=np.radians(10)).warnings


def test_inline_four_cylinder_records_against_independent_relations(request, seed):
    """Each cylinder record of the inline four (engines/inline4.toml, firing offsets 0, 540,
    180, 360 deg; it has no pressure table, so the seed 001 table is lent to it) against
    relations the record must obey:

    * ``gas_angle = mod(theta - firing_offset, 720 deg)``: the gas table's angle is the
      cycle angle counted from that cylinder's firing TDC;
    * ``s`` of the central slider crank, ``r + l - r cos phi - sqrt(l^2 - r^2 sin^2 phi)``;
    * ``volume_swept = (pi/4) bore^2 s``;
    * Newton on the piston along its axis: the rod's axial push on the pin,
      ``(rod_force + side_thrust sin beta) / cos beta`` (the rod-direction component and
      the lateral component of that force resolved back onto the axis), equals
      ``F_g - m_p a``;
    * the cycle integral of the engine torque equals the sum of the four p-V loop works
      (inertia forces do no net work over a cycle), and is four times one cylinder's.
    """
    lc = load_loadcase(request.config.rootpath / "loadcases/inline4_rated.toml")
    lc = replace(lc, engine=replace(lc.engine, gas=seed.engine.gas))
    res = analyse(lc.engine, lc.operating, step=np.radians(0.5))
    works = []
    for cyl in lc.engine.cylinders:
        cf = res.cylinders[cyl.name]
        assert (cf.name, cf.throw) == (cyl.name, cyl.throw)
        np.testing.assert_allclose(cf.gas_angle, np.mod(res.theta - cyl.firing_offset, 4 * np.pi), rtol=0, atol=1e-9)
        r, l = lc.engine.throw(cyl.throw).crank_radius, cyl.rod.length
        phi = cf.motion.phi
        np.testing.assert_allclose(phi, cf.phi, rtol=0, atol=0)
        s = r + l - r * np.cos(phi) - np.sqrt(l**2 - (r * np.sin(phi)) ** 2)
        np.testing.assert_allclose(cf.motion.s, s, rtol=0, atol=1e-12 * r)
        np.testing.assert_allclose(cf.volume_swept, np.pi / 4 * cyl.bore**2 * s, rtol=1e-12, atol=1e-18)
        beta = cf.motion.beta
        axial = (cf.rod_force + cf.side_thrust * np.sin(beta)) / np.cos(beta)
        np.testing.assert_allclose(
            axial, cf.gas - cyl.piston_mass * cf.motion.a, rtol=1e-12, atol=1e-9 * np.max(np.abs(cf.gas))
        )
        works.append(
            np.sum(0.5 * (cf.pressure + np.roll(cf.pressure, -1)) * (np.roll(cf.volume_swept, -1) - cf.volume_swept))
        )
    assert works[0] > 100.0  # J: a working engine
    np.testing.assert_allclose(works, works[0], rtol=1e-3)  # four equal cylinders
    work_torque = np.sum(res.torque) * res.cycle / res.theta.size
    assert res.indicated_work == pytest.approx(sum(works), rel=1e-12)
    assert work_torque == pytest.approx(sum(works), rel=2e-4)


def test_throw_records_have_the_documented_shapes_and_bearing_split(seed):
    """docs/contracts.md: ``pin_force`` (n, 2) in the throw frame (x tangential, y radial);
    each bearing takes half of the pin load plus half of the throw's centrifugal force
    ``m_rot R w^2`` along the crank, resolved into the engine frame with the crank at
    ``gamma`` from +y: x-axis of the throw (cos g, -sin g), y-axis (sin g, cos g)."""
    res = analyse(seed.engine, seed.operating, step=np.radians(5.0))
    n = res.theta.size
    throw = seed.engine.throws[0]
    th = res.throws[throw.name]
    assert th.pin_force.shape == (n, 2) and th.bearing_front.shape == (n, 2)
    g = th.angle_global
    fx, fy = th.pin_force[:, 0], th.pin_force[:, 1] + throw.rotating_mass * throw.crank_radius * seed.operating.speed**2
    half = 0.5 * np.stack([fx * np.cos(g) + fy * np.sin(g), -fx * np.sin(g) + fy * np.cos(g)], axis=1)
    np.testing.assert_allclose(th.bearing_front, half, rtol=1e-13, atol=1e-9)
    np.testing.assert_allclose(th.bearing_rear, half, rtol=1e-13, atol=1e-9)
    np.testing.assert_allclose(th.pin_force_magnitude, np.hypot(th.pin_force[:, 0], th.pin_force[:, 1]), rtol=1e-15)


def test_throw_names_and_torque_and_small_engine_nonuniformity(seed):
    """The throw record carries its name, shaft and the torque of its cylinder
    (``tangential * r``); a small engine (bore 9.2 mm, mean torque well below 1 N m) still
    gets the non-uniformity ``(T_max - T_min) / T_mean`` (Kolchin & Demidov, ch. 5)."""
    cyl = replace(seed.engine.cylinders[0], bore=0.0092)
    eng = replace(seed.engine, cylinders=(cyl,))
    res = analyse(eng, seed.operating, step=np.radians(2.0))
    throw = eng.throws[0]
    th = res.throws[throw.name]
    assert (th.name, th.shaft) == (throw.name, throw.shaft)
    cf = res.cylinders[cyl.name]
    np.testing.assert_allclose(th.torque, cf.tangential * throw.crank_radius, rtol=1e-15, atol=0)
    assert 0.0 < res.mean_torque < 1.0
    t = res.torque
    assert res.torque_nonuniformity == pytest.approx((t.max() - t.min()) / t.mean(), rel=1e-12)


def test_massless_engine_without_gas_has_no_torque_and_infinite_nonuniformity(seed):
    """No gas table, massless piston and rod: every force is exactly zero, the mean torque
    is 0 and the non-uniformity (T_max - T_min) / T_mean is reported as infinite."""
    cyl = seed.engine.cylinders[0]
    cyl = replace(cyl, piston_mass=0.0, rod=replace(cyl.rod, mass=0.0, inertia_cg=None))
    eng = replace(seed.engine, gas=None, cylinders=(cyl,))
    res = analyse(eng, seed.operating, step=np.radians(10))
    assert (res.engine, res.speed) == (eng.name, seed.operating.speed)
    np.testing.assert_array_equal(res.torque, 0.0)
    assert res.mean_torque == 0.0 and res.torque_nonuniformity == float("inf")
    assert res.excess_energy == 0.0 and res.flywheel_inertia == 0.0


def test_flywheel_of_a_toy_engine_with_under_one_joule_of_excess_work(seed):
    """Bore 2 mm at 1 rad/s: the excess work E(theta) = int (T - T_mean) dtheta swings by
    far less than 1 J, and the flywheel J = dE / (delta w^2) still gives the speed
    fluctuation delta = 0.02 when J d(w^2/2)/dtheta = T - T_mean is integrated (as in
    tests/mechanism/test_mechanism_dynamics.py for the full-size engine)."""
    cyl = replace(seed.engine.cylinders[0], bore=0.002)
    eng = replace(seed.engine, cylinders=(cyl,))
    op = replace(seed.operating, speed=1.0)
    res = analyse(eng, op, step=np.radians(0.5), speed_fluctuation=0.02)
    assert 0.0 < res.excess_energy < 0.5
    dth = res.cycle / res.theta.size
    excess = np.concatenate([[0.0], np.cumsum(res.torque - res.mean_torque) * dth])
    assert excess.max() - excess.min() == pytest.approx(res.excess_energy, rel=0.01)
    w = np.sqrt(1.0 + 2 * (excess - excess.mean()) / res.flywheel_inertia)
    assert (w.max() - w.min()) / w.mean() == pytest.approx(0.02, rel=0.02)
