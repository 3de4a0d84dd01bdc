"""Joint reactions of kinetostatics by hand: a massless slider-crank at 90 deg
under a gas force (a two-force rod), the crank's own inertia and weight, the record's
names and shapes for scalar and 2-D angle arrays, and the refusals in full."""

import math

import numpy as np
import pytest
from helpers.kinetostatics import analyse_position, mechanical_efficiency, virtual_power_moment, zhukovsky_moment

from fe_crank.errors import InputError

R, L = 0.05, 0.2
X = math.sqrt(L**2 - R**2)  # u of the piston pin at phi = 90 deg: sqrt(0.04 - 0.0025) = 0.193649 m
MASSLESS = dict(r=R, l=L, omega=100.0, piston_mass=0.0, rod_mass=0.0, rod_cg=0.05, rod_inertia=0.0)


def test_massless_mechanism_at_90_degrees_by_hand():
    """phi = 90 deg, gas force F = 10 kN, no masses: A = (0, r), B = (x, 0), x = 0.193649 m.
    The rod is a two-force member along B -> A, compression C = F l / x, so on the piston
    R23 = (F, -F r/x) = (10000, -2581.99) N (r/x = 0.258199) and the guide's reaction
    R03 = -(R23 + F_gas) = (0, 2581.99) N; crank on rod R12 = R23 (rod in equilibrium).
    The crank: rod on crank R21 = -R12, M_b = -(A x R21) = -(0 * 2581.99 - 0.05 * -10000)...
    = -r F = -500 N m; P_b = M_b / r = -10000 N along e_t = (-1, 0); frame on crank
    R01 = -(R21 + P_b e_t) = (0, -2581.99) N, and with the balancing couple instead
    R01_couple = -R21 = (10000, -2581.99) N."""
    res = analyse_position(math.pi / 2, gas_force=10000.0, **MASSLESS)
    rx = 10000.0 * R / X
    assert rx == pytest.approx(2581.99, rel=1e-6)
    tol = dict(rtol=0, atol=1e-9)
    np.testing.assert_allclose(res.points["A"], [0.0, R], **tol)
    np.testing.assert_allclose(res.points["B"], [X, 0.0], **tol)
    np.testing.assert_allclose(res.R23, [10000.0, -rx], **tol)
    np.testing.assert_allclose(res.R03, [0.0, rx], **tol)
    np.testing.assert_allclose(res.R12, [10000.0, -rx], **tol)
    assert float(res.balancing_moment) == pytest.approx(-500.0, rel=1e-12)
    assert float(res.balancing_force) == pytest.approx(-10000.0, rel=1e-12)
    np.testing.assert_allclose(res.R01, [0.0, -rx], **tol)
    np.testing.assert_allclose(res.R01_couple, [10000.0, -rx], **tol)
    assert float(res.phi) == math.pi / 2


def test_crank_inertia_and_weight_by_hand():
    """Crank 3 kg with its centre at c = 0.02 m, omega = 100 rad/s, nothing else loaded:
    its inertia force m c omega^2 = 3 * 0.02 * 100^2 = 600 N acts outward along e_r, its
    weight 3 * (-9.81, 0) = (-29.43, 0) N.  At phi = 90 deg: e_r = (0, 1), S1 = (0, 0.02):
    R01_couple = -(F_I1 + G1) = (29.43, -600) N; M_b = -(S1 x G1) = -(0 * 0 - 0.02 * -29.43)
    = -0.5886 N m (the radial inertia force has no moment); P_b = M_b / r = -11.772 N and
    R01 = R01_couple - P_b e_t = (29.43 - 11.772, -600) = (17.658, -600) N."""
    res = analyse_position(math.pi / 2, gas_force=0.0, crank_mass=3.0, crank_cg=0.02, **MASSLESS)
    np.testing.assert_allclose(res.R01_couple, [29.43, -600.0], rtol=1e-12)
    assert float(res.balancing_moment) == pytest.approx(-0.5886, rel=1e-12)
    np.testing.assert_allclose(res.R01, [17.658, -600.0], rtol=1e-12)
    np.testing.assert_allclose(res.points["S1"], [0.0, 0.02], atol=1e-15)
    np.testing.assert_allclose(res.loads["inertia_1"][1], [0.0, 600.0], atol=1e-9)
    # without crank arguments the crank carries nothing: the frame reaction is zero
    bare = analyse_position(math.pi / 2, gas_force=0.0, **MASSLESS)
    np.testing.assert_array_equal(bare.R01_couple, [0.0, 0.0])
    np.testing.assert_array_equal(bare.points["S1"], [0.0, 0.0])


def test_record_names_and_shapes_for_scalar_and_2d_angles():
    """Every applied load and couple by name at its point; the points and velocities of O,
    A, B, S1, S2 (O the fixed origin: zero); shapes (..., 2) for a scalar angle and for a
    (2, 3) array of angles; the three balancing moments agree on the 2-D array too."""
    mech = dict(
        r=R,
        l=L,
        omega=100.0,
        piston_mass=1.0,
        rod_mass=1.5,
        rod_cg=0.05,
        rod_inertia=0.01,
        crank_mass=2.0,
        crank_cg=0.01,
    )
    res = analyse_position(0.3, gas_force=5000.0, **mech)
    assert set(res.loads) == {"gas", "inertia_3", "weight_3", "inertia_2", "weight_2", "inertia_1", "weight_1"}
    assert [
        res.loads[k][0] for k in ("gas", "inertia_3", "weight_3", "inertia_2", "weight_2", "inertia_1", "weight_1")
    ] == ["B", "B", "B", "S2", "S2", "S1", "S1"]
    assert set(res.couples) == {"inertia_2"}
    assert set(res.points) == set(res.velocities) == {"O", "A", "B", "S1", "S2"}
    for key in ("O", "A", "B", "S1", "S2"):
        assert res.points[key].shape == (2,) and res.velocities[key].shape == (2,)
    np.testing.assert_array_equal(res.points["O"], [0.0, 0.0])
    np.testing.assert_array_equal(res.velocities["O"], [0.0, 0.0])
    # S2 at c/l = 0.25 of the way from A to B
    np.testing.assert_allclose(
        res.points["S2"], res.points["A"] + 0.25 * (res.points["B"] - res.points["A"]), rtol=1e-14
    )
    for name in ("R12", "R03", "R23", "R01", "R01_couple"):
        assert getattr(res, name).shape == (2,)
    phi = np.array([[0.3, 1.0, 2.0], [3.0, 4.0, 5.5]])
    grid = analyse_position(phi, gas_force=5000.0, gravity=(-9.81, 1.0), **mech)
    for name in ("R12", "R03", "R23", "R01", "R01_couple"):
        assert getattr(grid, name).shape == (2, 3, 2)
    assert grid.points["O"].shape == (2, 3, 2)
    mb = grid.balancing_moment
    assert mb.shape == (2, 3)
    scale = np.abs(mb).max()
    np.testing.assert_allclose(virtual_power_moment(grid), mb, atol=1e-12 * scale)
    np.testing.assert_allclose(zhukovsky_moment(grid), mb, atol=1e-12 * scale)
    # the scalar position is the first entry of an array under the same loads
    same = analyse_position(phi, gas_force=5000.0, **mech)
    np.testing.assert_allclose(same.R01[0, 0], res.R01, rtol=1e-12)
    eff = mechanical_efficiency(grid, friction_coefficient=0.05, d_O1=0.08, d_A=0.06, d_B=0.03)
    assert math.isfinite(eff.efficiency)


@pytest.mark.parametrize("bad", ["piston_mass", "rod_mass", "rod_inertia", "crank_mass"])
def test_each_negative_mass_is_refused_in_full(bad):
    kw = dict(MASSLESS, crank_mass=0.0)
    kw[bad] = -0.1
    with pytest.raises(InputError) as err:
        analyse_position(0.3, gas_force=0.0, **kw)
    assert err.value.reason == "masses and inertia cannot be negative"


def test_efficiency_limits_and_refusals_in_full():
    """Zero journal diameters are valid (no friction moment there); each negative one and a
    negative friction coefficient are refused.  A gas force of 1 N over the expansion
    stroke (phi in [0, pi], omega = 1 rad/s) drives with mean power F 2 r omega / pi =
    0.1 / pi = 0.0318 W: small but positive, accepted; with no gas force it is refused.
    The mean is over 180 mid-step samples: the lambda term of the piston speed cancels
    by symmetry about 90 deg and the mid-point mean of sin is within 1e-5 of 2/pi."""
    phi = (np.arange(180) + 0.5) * math.pi / 180
    res = analyse_position(phi, gas_force=1.0, **dict(MASSLESS, omega=1.0))
    eff = mechanical_efficiency(res, friction_coefficient=0.0, d_O1=0.0, d_A=0.0, d_B=0.0)
    assert eff.driving_power == pytest.approx(0.1 / math.pi, rel=1e-4)
    assert eff.efficiency == 1.0
    for kw in (
        dict(friction_coefficient=-0.01, d_O1=0.1, d_A=0.1, d_B=0.1),
        dict(friction_coefficient=0.01, d_O1=-0.1, d_A=0.1, d_B=0.1),
        dict(friction_coefficient=0.01, d_O1=0.1, d_A=-0.1, d_B=0.1),
        dict(friction_coefficient=0.01, d_O1=0.1, d_A=0.1, d_B=-0.1),
    ):
        with pytest.raises(InputError) as err:
            mechanical_efficiency(res, **kw)
        assert err.value.reason == "friction coefficient and journal diameters cannot be negative"
    idle = analyse_position(phi, gas_force=0.0, **dict(MASSLESS, omega=1.0))
    with pytest.raises(InputError) as err:
        mechanical_efficiency(idle, friction_coefficient=0.01, d_O1=0.1, d_A=0.1, d_B=0.1)
    assert err.value.reason == "no driving power: the gas force does no positive work over these positions"


def test_rod_weight_shared_between_crankpin_and_guide_by_hand():
    """Standing mechanism (omega = 0) at phi = 90 deg, gravity along -w (cylinder
    horizontal), only the rod heavy: m2 = 2 kg, W = 19.62 N at c/l = 0.25 from the big end.
    Moments on the rod about B: -x R12_w + (1 - c/l) x W = 0 -> R12 = (0, 0.75 W) =
    (0, 14.715) N; the group's forces: R03 = (0, W - R12_w) = (0, 0.25 W) = (0, 4.905) N."""
    kw = dict(MASSLESS, omega=0.0, rod_mass=2.0)
    res = analyse_position(math.pi / 2, gas_force=0.0, gravity=(0.0, -9.81), **kw)
    np.testing.assert_allclose(res.R12, [0.0, 14.715], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(res.R03, [0.0, 4.905], rtol=1e-12, atol=1e-12)


def test_efficiency_of_a_2d_array_of_angles_equals_that_of_the_same_angles_in_a_row():
    """The means run over every sampled position whatever the array's shape."""
    mech = dict(r=R, l=L, omega=100.0, piston_mass=1.0, rod_mass=1.5, rod_cg=0.05, rod_inertia=0.01)
    phi = np.array([[0.3, 0.6, 0.9], [1.2, 1.5, 1.8]])
    kw = dict(friction_coefficient=0.05, d_O1=0.08, d_A=0.06, d_B=0.03)
    grid = mechanical_efficiency(analyse_position(phi, gas_force=8000.0, **mech), **kw)
    row = mechanical_efficiency(analyse_position(phi.ravel(), gas_force=8000.0, **mech), **kw)
    for name in ("power_O1", "power_A", "power_B", "power_O3", "driving_power", "efficiency"):
        assert getattr(grid, name) == pytest.approx(getattr(row, name), rel=1e-12)
