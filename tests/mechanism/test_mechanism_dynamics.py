"""Dynamics: virtual power at every grid angle, cycle work = p-V work, closed forms
of the two-mass model, multi-cylinder sums, flywheel by time integration."""

from dataclasses import replace

import numpy as np
import pytest
from helpers.kinetostatics import analyse_position

from fe_crank import model
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.dynamics import analyse, solve_cylinder
from fe_crank.mechanism.gas import cylinder_volume, pressure_at, wiebe_cycle
from fe_crank.mechanism.kinematics import piston_motion

SEED_CASE = "loadcases/single_cylinder.toml"


@pytest.fixture(scope="module")
def seed(request):
    return load_loadcase(request.config.rootpath / SEED_CASE)


def _single(offset=0.0, inertia=0.02, sense=1, gas=None, bank=0.0, phase=0.0):
    r, l = 0.064, 0.307
    if gas is None:
        gas = wiebe_cycle(
            bore=0.092,
            r=r,
            l=l,
            compression_ratio=8.5,
            intake_pressure=0.09e6,
            exhaust_pressure=0.11e6,
            heat_released=1800.0,
            combustion_start=np.radians(-15),
            combustion_duration=np.radians(50),
        )
    return model.Engine(
        name="single",
        strokes=4,
        shafts=(model.Shaft("main", sense=sense, phase=phase),),
        throws=(model.Throw("1", "main", 0.0, r, 0.0, 0.17),),
        cylinders=(
            model.Cylinder("1", "1", 0.092, model.Rod(l, 1.9, 0.138, inertia), 1.1, bank_angle=bank, pin_offset=offset),
        ),
        gas=gas,
    )


@pytest.mark.parametrize("offset,inertia", [(0.0, 0.02), (0.006, 0.02), (-0.004, None)])
def test_virtual_power_at_every_grid_angle(offset, inertia):
    """T omega = F_gas v + sum of inertia powers (piston, rod translation, rod rotation)."""
    eng = _single(offset, inertia)
    op = model.OperatingPoint(293.07)
    res = analyse(eng, op, step=np.radians(2.0))
    cf = res.cylinders["1"]
    cyl = eng.cylinders[0]
    m = piston_motion(cf.phi, 0.064, 0.307, op.speed, offset=offset, rod_cg=0.138)
    J = 1.9 * 0.138 * (0.307 - 0.138) if inertia is None else inertia
    power = (
        cf.gas * m.v
        - cyl.piston_mass * m.a * m.v
        - 1.9 * np.sum(m.rod_cg_acceleration * m.rod_cg_velocity, axis=1)
        - J * m.beta_ddot * m.beta_dot
    )
    scale = np.max(np.abs(power))
    np.testing.assert_allclose(res.torque * op.speed, power, atol=1e-11 * scale)


def test_cycle_integral_of_torque_equals_indicated_work_of_pv_loop(seed):
    res = analyse(seed.engine, seed.operating, step=np.radians(0.5))
    work_torque = np.sum(res.torque) * res.cycle / res.theta.size
    # p-V loop integrated independently on a fine grid of the gas table
    cyl = seed.engine.cylinders[0]
    phi = np.linspace(0.0, 4 * np.pi, 200001)
    V = cylinder_volume(phi, cyl.bore, 0.064, cyl.rod.length, 8.5)
    p = pressure_at(seed.engine.gas, phi, 4 * np.pi)
    work_pv = np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(V))
    assert work_pv > 500.0  # a working engine
    assert work_torque == pytest.approx(work_pv, rel=2e-4)
    assert res.indicated_work == pytest.approx(work_pv, rel=2e-4)
    assert res.mean_torque == pytest.approx(work_pv / (4 * np.pi), rel=2e-4)
    assert res.power == pytest.approx(res.mean_torque * seed.operating.speed)


def test_two_mass_model_closed_forms():
    """With J = m c (l - c) the rigid rod equals the two-mass split, whose torque and pin
    load have the textbook closed forms (Kolchin & Demidov ch. 4):
    T = F r sin(phi + beta)/cos(beta), radial = -F cos(phi + beta)/cos(beta) + m_r r w^2,
    F = F_g - m_j a, m_j = m_p + m c/l, m_r = m (l - c)/l."""
    r, l, w, c, m_rod, m_p = 0.064, 0.307, 300.0, 0.1, 2.0, 1.0
    phi = np.linspace(0, 2 * np.pi, 181)
    fg = 8000.0 * np.exp(-((phi - 0.3) ** 2) / 0.1)
    sol = solve_cylinder(phi, r=r, l=l, omega=w, gas_force=fg, piston_mass=m_p, rod_mass=m_rod, rod_cg=c)
    mo = piston_motion(phi, r, l, w)
    F = fg - (m_p + m_rod * c / l) * mo.a
    T = F * r * np.sin(phi + mo.beta) / np.cos(mo.beta)
    Z = -F * np.cos(phi + mo.beta) / np.cos(mo.beta) + m_rod * (l - c) / l * r * w**2
    np.testing.assert_allclose(sol["torque"], T, atol=1e-9 * np.abs(T).max())
    np.testing.assert_allclose(sol["radial"], Z, atol=1e-9 * np.abs(Z).max())
    # the link force of the two-mass model is S = F / cos(beta) along the rod; the force on the
    # piston pin is S minus the small-end mass's inertia, whose component along the rod is
    # (F_g - m_p a) cos(beta) + F tan(beta) sin(beta)
    b = mo.beta
    rod = (fg - m_p * mo.a) * np.cos(b) + F * np.tan(b) * np.sin(b)
    np.testing.assert_allclose(sol["rod_force"], rod, atol=1e-9 * np.abs(F).max())
    np.testing.assert_allclose(sol["side_thrust"], -F * np.tan(mo.beta), atol=1e-9 * np.abs(F).max())


def test_torque_equals_minus_balancing_moment_of_force_analysis(seed):
    res = analyse(seed.engine, seed.operating, step=np.radians(5.0))
    cyl = seed.engine.cylinders[0]
    cf = res.cylinders["1"]
    ks = analyse_position(
        cf.phi,
        r=0.064,
        l=cyl.rod.length,
        omega=seed.operating.speed,
        gas_force=cf.gas,
        piston_mass=cyl.piston_mass,
        rod_mass=cyl.rod.mass,
        rod_cg=cyl.rod.cg_from_big_end,
        rod_inertia=cyl.rod.inertia_cg,
        gravity=(0.0, 0.0),
    )
    np.testing.assert_allclose(res.torque, -ks.balancing_moment, atol=1e-10 * np.abs(res.torque).max())
    # force of the rod on the crankpin = -R12 (crank on rod), in the throw frame (x, y) = (tangential, radial)
    pin = res.throws["1"].pin_force
    er = np.stack([np.cos(cf.phi), np.sin(cf.phi)], 1)
    et = np.stack([-np.sin(cf.phi), np.cos(cf.phi)], 1)
    np.testing.assert_allclose(pin[:, 0], np.sum(-ks.R12 * et, 1), atol=1e-8 * np.abs(pin).max())
    np.testing.assert_allclose(pin[:, 1], np.sum(-ks.R12 * er, 1), atol=1e-8 * np.abs(pin).max())


def test_inline_four_sums_and_journal_torques(seed):
    single = seed.engine
    cyl = single.cylinders[0]
    angles = {"1": 0.0, "2": np.pi, "3": np.pi, "4": 0.0}
    order = ["1", "3", "4", "2"]
    throws = tuple(model.Throw(n, "main", a, 0.064, 0.1 * i, 0.17) for i, (n, a) in enumerate(angles.items()))
    cyls = tuple(replace(cyl, name=n, throw=n, firing_offset=order.index(n) * np.pi) for n in angles)
    eng = replace(single, name="I4", throws=throws, cylinders=cyls)
    r1 = analyse(single, seed.operating, step=np.radians(2.0))
    r4 = analyse(eng, seed.operating, step=np.radians(2.0))
    assert r4.warnings == ()
    assert r4.mean_torque == pytest.approx(4 * r1.mean_torque, rel=1e-9)
    # each cylinder repeats cylinder 1 shifted by its firing offset
    for n in angles:
        shift = int(round(order.index(n) * 180 / 2))
        np.testing.assert_allclose(r4.cylinders[n].torque, np.roll(r1.torque, shift), atol=1e-8)
    # journals: cumulative from the front; the rear journal of the last throw carries all
    tq = sum(r4.cylinders[n].torque for n in angles)
    np.testing.assert_allclose(r4.throws["4"].torque_rear, tq, atol=1e-9)
    np.testing.assert_allclose(r4.throws["1"].torque_front, 0.0)
    np.testing.assert_allclose(r4.throws["3"].torque_front, r4.throws["2"].torque_rear)
    # even firing every 180 deg: the total torque has only orders 2, 4, ... (index k of the
    # 720-deg spectrum is order k/2), so orders 1/2, 1 and 3/2 vanish
    spec = np.abs(np.fft.rfft(r4.torque))
    assert np.all(spec[1:4] < 1e-9 * spec[4])


def test_v_twin_two_rods_on_one_pin_and_sense(seed):
    """Two cylinders at +-45 deg on one pin: the pin load is the sum of both rods'
    loads; a shaft turning the other way mirrors the engine-frame loads in x."""
    cyl = seed.engine.cylinders[0]
    c1 = replace(cyl, name="L", bank_angle=-np.pi / 4, firing_offset=0.0)
    c2 = replace(cyl, name="R", bank_angle=np.pi / 4, firing_offset=np.pi / 2 + 2 * np.pi)
    eng = replace(seed.engine, cylinders=(c1, c2), shafts=(model.Shaft("main", 1, phase=-np.pi / 4),))
    res = analyse(eng, seed.operating, step=np.radians(2.0))
    assert res.warnings == ()
    th = res.throws["1"]
    np.testing.assert_allclose(th.pin_force[:, 0], res.cylinders["L"].tangential + res.cylinders["R"].tangential)
    np.testing.assert_allclose(th.pin_force[:, 1], res.cylinders["L"].radial + res.cylinders["R"].radial)
    # mirrored engine: sense -1, banks and phase mirrored -> same torques, bearing x flipped
    m1 = replace(c1, bank_angle=np.pi / 4)
    m2 = replace(c2, bank_angle=-np.pi / 4)
    mir = replace(eng, cylinders=(m1, m2), shafts=(model.Shaft("main", -1, phase=np.pi / 4),))
    rm = analyse(mir, seed.operating, step=np.radians(2.0))
    np.testing.assert_allclose(rm.torque, res.torque, atol=1e-8)
    np.testing.assert_allclose(rm.throws["1"].bearing_front[:, 0], -th.bearing_front[:, 0], atol=1e-8)
    np.testing.assert_allclose(rm.throws["1"].bearing_front[:, 1], th.bearing_front[:, 1], atol=1e-8)
    np.testing.assert_allclose(rm.throws["1"].pin_force[:, 0], -th.pin_force[:, 0], atol=1e-8)


def test_two_geared_shafts_are_computed_per_shaft(seed):
    single = seed.engine
    cyl = single.cylinders[0]
    shafts = (model.Shaft("a", 1), model.Shaft("b", -1, centre=(0.3, 0.0)))
    throws = (replace(single.throws[0], name="a1", shaft="a"), replace(single.throws[0], name="b1", shaft="b"))
    cyls = (replace(cyl, name="a", throw="a1"), replace(cyl, name="b", throw="b1"))
    eng = replace(single, shafts=shafts, throws=throws, cylinders=cyls)
    res = analyse(eng, seed.operating, step=np.radians(2.0))
    r1 = analyse(single, seed.operating, step=np.radians(2.0))
    np.testing.assert_allclose(res.shaft_torque["a"], r1.torque, atol=1e-9)
    np.testing.assert_allclose(res.shaft_torque["b"], r1.torque, atol=1e-9)
    assert res.power == pytest.approx(2 * r1.power)


def test_flywheel_inertia_gives_the_target_speed_fluctuation_by_time_integration(seed):
    """Integrate J d(w^2/2)/dtheta = T - T_mean with the computed J: the speed varies by delta."""
    res = analyse(seed.engine, seed.operating, step=np.radians(0.5), speed_fluctuation=0.02)
    dth = res.cycle / res.theta.size
    excess = np.concatenate([[0.0], np.cumsum(res.torque - res.mean_torque) * dth])
    w_mean = seed.operating.speed
    w = np.sqrt(w_mean**2 + 2 * (excess - excess.mean()) / res.flywheel_inertia)
    delta = (w.max() - w.min()) / w.mean()
    assert delta == pytest.approx(0.02, rel=0.02)
    assert res.torque_nonuniformity == pytest.approx((res.torque.max() - res.torque.min()) / res.mean_torque)


def test_bearing_split_and_centrifugal_force(seed):
    """Simply supported throw, pin at mid-span: each bearing takes half the pin load plus half
    the centrifugal force of the throw's rotating mass (engine frame)."""
    res = analyse(seed.engine, seed.operating, step=np.radians(5.0))
    th = res.throws["1"]
    np.testing.assert_allclose(
        th.bearing_front + th.bearing_rear,
        _to_engine(th.pin_force, th.angle_global)
        + 0.1714 * 0.064 * seed.operating.speed**2 * np.stack([np.sin(th.angle_global), np.cos(th.angle_global)], 1),
        rtol=1e-12,
        atol=1e-9,
    )
    np.testing.assert_allclose(np.hypot(*(th.bearing_front).T), np.hypot(*(th.bearing_rear).T))


def _to_engine(f, gamma):
    ex = np.stack([np.cos(gamma), -np.sin(gamma)], 1)
    ey = np.stack([np.sin(gamma), np.cos(gamma)], 1)
    return f[:, :1] * ex + f[:, 1:] * ey


def test_inconsistent_firing_offset_is_reported(seed):
    cyl = replace(seed.engine.cylinders[0], firing_offset=np.radians(90))
    res = analyse(replace(seed.engine, cylinders=(cyl,)), seed.operating, step=np.radians(5))
    assert any("not at its TDC" in w for w in res.warnings)


def test_wiebe_cycle_without_heat_is_the_polytrope():
    g = wiebe_cycle(
        bore=0.092,
        r=0.064,
        l=0.307,
        compression_ratio=8.5,
        intake_pressure=1e5,
        exhaust_pressure=1e5,
        heat_released=0.0,
        combustion_start=0.0,
        combustion_duration=1.0,
        k=1.35,
    )
    closed = (g.angle <= np.pi) | (g.angle >= 3 * np.pi)
    V = cylinder_volume(g.angle, 0.092, 0.064, 0.307, 8.5)
    pv = g.pressure[closed] * V[closed] ** 1.35
    vbdc = cylinder_volume(np.pi, 0.092, 0.064, 0.307, 8.5)
    np.testing.assert_allclose(pv, 1e5 * vbdc**1.35, rtol=1e-6)
    assert g.pressure.max() == pytest.approx(1e5 * 8.5**1.35, rel=1e-6)


def test_wiebe_cycle_with_fast_combustion_at_tdc_gives_otto_efficiency():
    """Heat released in 1 deg at TDC, no pumping loop: work = Q (1 - eps^(1-k)) (Otto cycle)."""
    Q, eps, k = 1000.0, 8.5, 1.35
    g = wiebe_cycle(
        bore=0.092,
        r=0.064,
        l=0.307,
        compression_ratio=eps,
        intake_pressure=1e5,
        exhaust_pressure=1e5,
        heat_released=Q,
        combustion_start=np.radians(-0.5),
        combustion_duration=np.radians(1.0),
        k=k,
        n=3601,
    )
    phi = np.linspace(0, 4 * np.pi, 400001)
    V = cylinder_volume(phi, 0.092, 0.064, 0.307, eps)
    p = pressure_at(g, phi, 4 * np.pi)
    work = np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(V))
    assert work == pytest.approx(Q * (1 - eps ** (1 - k)), rel=5e-3)
