"""Kinetostatics (seed 004): force analysis, Zhukovsky's lever and virtual power agree
to round-off; every body is in equilibrium; friction efficiency against closed forms."""

import numpy as np
import pytest
from helpers.kinetostatics import analyse_position, mechanical_efficiency, virtual_power_moment, zhukovsky_moment

from fe_crank.errors import InputError

# seed 001/004 mechanism; crank mass 0.4284 kg with its centre at 0.4 r (seed 004 eq. 104,
# seed 001 eq. 15); rod J_S2 = 0.02 kg m^2 (seed 004); the other values chosen
MECH = dict(
    r=0.064,
    l=0.307,
    omega=293.07,
    piston_mass=1.1,
    rod_mass=1.9,
    rod_cg=0.138,
    rod_inertia=0.02,
    crank_mass=0.4284,
    crank_cg=0.4 * 0.064,
)


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


@pytest.fixture(scope="module")
def res():
    phi = np.linspace(0, 4 * np.pi, 145)
    gas = 16000.0 * np.exp(-((phi - 0.35) ** 2) / 0.15) - 500.0
    return analyse_position(phi, gas_force=gas, offset=0.004, **MECH)


def test_balancing_moment_three_ways_agree_to_round_off(res):
    """Seed 004 finds 311.5 N m by force analysis and 298.9 N m by Zhukovsky's lever (4 %):
    a drawing error.  Exactly computed, the methods agree to round-off at every position."""
    mb = res.balancing_moment
    scale = np.abs(mb).max()
    assert scale > 100.0
    np.testing.assert_allclose(zhukovsky_moment(res), mb, atol=1e-12 * scale)
    np.testing.assert_allclose(virtual_power_moment(res), mb, atol=1e-12 * scale)


def test_every_body_in_equilibrium(res):
    P = res.points
    L = res.loads
    f = {k: v[1] for k, v in L.items()}
    M_I2 = res.couples["inertia_2"][1]
    # piston 3: R23 + R03 + gas + inertia + weight = 0
    np.testing.assert_allclose(res.R23 + res.R03 + f["gas"] + f["inertia_3"] + f["weight_3"], 0, atol=1e-8)
    assert np.all(res.R03[:, 0] == 0)  # normal to the guide
    # rod 2: forces and moments about its centre of mass
    R32 = -res.R23
    np.testing.assert_allclose(res.R12 + R32 + f["inertia_2"] + f["weight_2"], 0, atol=1e-8)
    mom = _cross(P["A"] - P["S2"], res.R12) + _cross(P["B"] - P["S2"], R32) + M_I2
    np.testing.assert_allclose(mom, 0, atol=1e-9)
    # crank 1 with the balancing force at A normal to the crank
    et = np.stack([-np.sin(res.phi), np.cos(res.phi)], 1)
    Pb = res.balancing_force[:, None] * et
    np.testing.assert_allclose(-res.R12 + res.R01 + Pb + f["inertia_1"] + f["weight_1"], 0, atol=1e-8)
    mom1 = _cross(P["A"], -res.R12 + Pb) + _cross(P["S1"], f["inertia_1"] + f["weight_1"])
    np.testing.assert_allclose(mom1, 0, atol=1e-9)
    np.testing.assert_allclose(res.balancing_force * 0.064, res.balancing_moment)


def test_static_mechanism_closed_form():
    """Massless links, no gravity, gas force F: R03 = F tan(beta), |R12| = F / cos(beta),
    M_b = -F r sin(phi + beta) / cos(beta) (the classical torque, reversed)."""
    phi = np.linspace(0.1, 3.0, 30)
    F = 10000.0
    r = analyse_position(
        phi,
        r=0.064,
        l=0.307,
        omega=1.0,
        gas_force=F,
        piston_mass=0,
        rod_mass=0,
        rod_cg=0.1,
        rod_inertia=0,
        gravity=(0, 0),
    )
    b = r.motion.beta
    np.testing.assert_allclose(np.abs(r.R03[:, 1]), F * np.tan(b), rtol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(r.R12, axis=1), F / np.cos(b), rtol=1e-12)
    np.testing.assert_allclose(r.balancing_moment, -F * 0.064 * np.sin(phi + b) / np.cos(b), rtol=1e-12)


def test_friction_efficiency_closed_form():
    """Massless mechanism, gas force F only while the piston moves towards the axis:
    joint loads have closed forms, so each friction power does (seed 004 eqs. 111-115)."""
    n = 720
    phi = 2 * np.pi * np.arange(n) / n
    F0, w, r, l = 5000.0, 300.0, 0.064, 0.307
    probe = analyse_position(
        phi, r=r, l=l, omega=w, gas_force=0.0, piston_mass=0, rod_mass=0, rod_cg=0.1, rod_inertia=0, gravity=(0, 0)
    )
    F = np.where(probe.motion.v > 0, F0, 0.0)
    res = analyse_position(
        phi, r=r, l=l, omega=w, gas_force=F, piston_mass=0, rod_mass=0, rod_cg=0.1, rod_inertia=0, gravity=(0, 0)
    )
    fr, d1, dA, dB = 0.15, 0.040, 0.040, 0.020  # seed 004 values
    out = mechanical_efficiency(res, friction_coefficient=fr, d_O1=d1, d_A=dA, d_B=dB)
    b, bd, v = probe.motion.beta, probe.motion.beta_dot, probe.motion.v
    S = F / np.cos(b)
    assert out.power_O1 == pytest.approx(np.mean(fr * S * d1 / 2 * w), rel=1e-12)
    assert out.power_A == pytest.approx(np.mean(fr * S * dA / 2 * np.abs(w + bd)), rel=1e-12)
    assert out.power_B == pytest.approx(np.mean(fr * S * dB / 2 * np.abs(bd)), rel=1e-12)
    assert out.power_O3 == pytest.approx(np.mean(fr * F * np.abs(np.tan(b)) * np.abs(v)), rel=1e-12)
    assert out.driving_power == pytest.approx(np.mean(F * v), rel=1e-12)
    assert 0.5 < out.efficiency < 1.0
    assert out.efficiency == pytest.approx(1 - out.friction_power / out.driving_power)
    # no friction: efficiency 1
    assert mechanical_efficiency(res, friction_coefficient=0.0, d_O1=d1, d_A=dA, d_B=dB).efficiency == 1.0
    with pytest.raises(InputError):
        mechanical_efficiency(probe, friction_coefficient=fr, d_O1=d1, d_A=dA, d_B=dB)
