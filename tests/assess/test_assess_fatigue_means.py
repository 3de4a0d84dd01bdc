"""Mean stresses in the two fatigue criteria, tensile and compressive, normal and shear,
at one surface node of a straight bar, against hand calculations; the half range; the
minimum circumscribed ball of a path whose mid-range centre is not the ball's centre.

Node at (0, a, 0) on the bar axis z (the journal axis through (0, 0)): there the
cylindrical frame has e_r = +y, e_theta = -x, so the torsional shear tau_theta_z is -s_xz
and the bending stress is s_zz.  History over the cycle angle t:

    s_zz = sigma_m + sigma_a sin t,    tau_theta_z = tau_m + tau_a cos t

material 42CrMo4 with every factor 1: sigma_e = 450, tau_e = 260, R_m = 900 MPa.
"""

from __future__ import annotations

import numpy as np
import pytest

from fe_crank.assess import ThrowContext, assess_throw
from fe_crank.assess.fatigue import amplitude_mean, goodman_safety, gough_pollard_safety, half_range, signed_mean
from fe_crank.assess.stress import von_mises
from fe_crank.assess.superpose import UnitStresses
from fe_crank.io.material import load_material

A = 0.02  # m, radius of the node
SA, TA = 120e6, 50e6  # Pa: bending and torsion amplitudes
THETA = np.deg2rad(np.arange(0.0, 360.0, 2.0))


def _node_throw(sigma_m: float, tau_m: float):
    """assess_throw on a one-node group: the centrifugal case (omega = 1 rad/s, coefficient
    1) carries the means, pin_x (coefficient F_x) the bending, torque (coefficient T with
    sense -1, M_z = 1) the torsion; unit stresses of 1 Pa per unit load."""
    s = np.zeros((4, 6, 1))
    s[0, 2], s[0, 5] = sigma_m, -tau_m  # centrifugal: the mean tensor
    s[1, 2] = 1.0  # pin_x: s_zz per N
    s[3, 5] = -1.0  # torque: s_xz = -tau_theta_z per N m
    unit = UnitStresses(
        stress=s,
        points=np.array([[0.0], [A], [0.0]]),
        groups={"journal_fillet_1": np.arange(1)},
        node_ids=np.arange(1),
        cases=("centrifugal", "pin_x", "pin_y", "torque"),
        torque_mz=1.0,
    )
    mat = load_material("42CrMo4", surface_factor=1.0, size_factor=1.0, reliability=0.5)
    pin = np.column_stack([SA * np.sin(THETA), np.zeros_like(THETA)])
    t = assess_throw(
        ThrowContext(
            "1",
            unit,
            THETA,
            pin,
            TA * np.cos(THETA),
            omega=1.0,
            sense=-1,
            overspeed=None,
            material=mat,
            crank_radius=0.0,
            m53_additional=0.0,  # the FE model's own stresses (UR M53 sigma_add: test_assess_m53_basis.py)
        )
    )
    return t.groups[0]


# (sigma_m, tau_m) MPa -> (Goodman n, Gough-Pollard n), by hand:
#  vM + Goodman: amplitude = MCB of the ellipse (120 sin t, sqrt3 50 cos t) about its centre
#    = max(120, 86.6) = 120 MPa; signed mean: s_1 = s_m/2 + sqrt(s_m^2/4 + t_m^2),
#    vM = sqrt(s_m^2 + 3 t_m^2); sigma_m' = max(vM, s_1) if s_1 > 0 else -vM;
#    1/n = 120/450 + max(sigma_m', 0)/900.
#  Gough-Pollard: sigma_e' = 450 (1 - max(s_m, 0)/900), tau_e' = 260 (1 - |t_m|/519.62),
#    n = 1/sqrt((120/sigma_e')^2 + (50/tau_e')^2).
# (+100, +150): s_1 = 208.11, vM = 278.39: 1/n = 0.26667 + 0.30932 -> 1.7361;
#               sigma_e' = 400, tau_e' = 184.94: 1/sqrt(0.09 + 0.073094) -> 2.4762
# (-100, -150): s_1 = 108.11 > 0, the shear mean counts: sigma_m' = 278.39 -> 1.7361;
#               no credit for the compressive normal mean: 1/sqrt(0.071111 + 0.073094) -> 2.6334
# (-100, 0):    s_1 = 0, sigma_m' = -100: no credit -> 450/120 = 3.75;
#               1/sqrt(0.071111 + 0.036982) -> 3.0416
# (+100, 0):    1/n = 0.26667 + 0.11111 -> 2.6471;  1/sqrt(0.09 + 0.036982) -> 2.8063
# The sign errors these catch move n by 4 % or more (e.g. a compressive mean taken as
# tensile: 3.75 -> 2.6471; |tau_m| taken signed: 2.6334 -> 3.5); abs 1e-4 on 4-digit values.
CASES = {
    (100e6, 150e6): (1.7361, 2.4762),
    (-100e6, -150e6): (1.7361, 2.6334),
    (-100e6, 0.0): (3.75, 3.0416),
    (100e6, 0.0): (2.6471, 2.8063),
    (100e6, -150e6): (1.7361, 2.4762),
    (-100e6, 150e6): (1.7361, 2.6334),
}


@pytest.mark.parametrize("means", list(CASES))
def test_tensile_and_compressive_normal_and_shear_means(means):
    sigma_m, tau_m = means
    g = _node_throw(sigma_m, tau_m)
    good, gp = CASES[means]
    assert g.fatigue_safety.value == pytest.approx(good, abs=1e-4)
    assert g.gough_pollard_safety.value == pytest.approx(gp, abs=1e-4)
    # the same from the formulas in full precision (1e-9: the 2-deg sampling hits every
    # extreme of sin t and cos t exactly, so only round-off remains)
    s1 = sigma_m / 2 + np.sqrt(sigma_m**2 / 4 + tau_m**2)
    vm = np.hypot(sigma_m, np.sqrt(3) * tau_m)
    signed = max(vm, s1) if s1 > 0 else -vm
    assert g.amplitude_at_critical == pytest.approx(SA, rel=1e-9)
    assert g.mean_at_critical == pytest.approx(signed, rel=1e-9)
    assert g.fatigue_safety.value == pytest.approx(1 / (SA / 450e6 + max(signed, 0) / 900e6), rel=1e-9)
    se = 450e6 * (1 - max(sigma_m, 0) / 900e6)
    te = 260e6 * (1 - abs(tau_m) / (900e6 / np.sqrt(3)))
    assert g.gough_pollard_safety.value == pytest.approx(1 / np.hypot(SA / se, TA / te), rel=1e-9)


def test_gough_pollard_and_goodman_at_the_edges():
    """Scalar limits, exact to round-off (rel 1e-12 catches a 1-Pa shift of a clamp):
    a compressive mean alone leaves an infinite Goodman safety; a shear mean at half the
    ultimate shear tau_u = R_m/sqrt(3) halves tau_e, whatever its sign; a normal mean at
    R_m gives n = 0 even without an amplitude; a tensile normal mean does not touch tau_e."""
    rm = 800e6
    assert goodman_safety(0.0, -50e6, 200e6, rm) == np.inf
    assert goodman_safety(100e6, -1.0, 200e6, rm) == pytest.approx(2.0, rel=1e-12)
    assert goodman_safety(100e6, 80e6, 200e6, rm) == pytest.approx(1 / (0.5 + 0.1), rel=1e-12)
    half_tu = rm / np.sqrt(3) / 2
    for sign in (1, -1):
        assert gough_pollard_safety(0.0, 0.0, 50e6, sign * half_tu, 200e6, 100e6, rm) == pytest.approx(1.0, rel=1e-12)
    assert gough_pollard_safety(0.0, rm, 0.0, 0.0, 200e6, 100e6, rm) == 0.0
    assert gough_pollard_safety(0.0, 0.0, 0.0, rm / np.sqrt(3), 200e6, 100e6, rm) == 0.0
    assert gough_pollard_safety(0.0, 0.0, 0.0, 0.0, 200e6, 100e6, rm) == np.inf
    # sigma_m = R_m/4 -> sigma_e' = 150 MPa; tau_e stays 100 MPa: (60/150)^2 + (30/100)^2 = 0.25
    assert gough_pollard_safety(60e6, rm / 4, 30e6, 0.0, 200e6, 100e6, rm) == pytest.approx(2.0, rel=1e-12)
    assert gough_pollard_safety(60e6, -rm / 4, 30e6, 0.0, 200e6, 100e6, rm) == pytest.approx(
        1 / np.hypot(0.3, 0.3), rel=1e-12
    )


def test_half_range():
    """Half range and mid range of 3 + 2 sin t sampled at its extremes: (2, 3), per column."""
    h = np.stack([3 + 2 * np.sin(THETA), -5 + 0 * THETA], axis=1)
    a, m = half_range(h)
    np.testing.assert_allclose(a, [2.0, 0.0], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(m, [3.0, -5.0], rtol=1e-12)


def test_minimum_ball_when_the_mid_range_is_not_its_centre():
    """Three shear states at the corners of an equilateral triangle in the
    (tau_xy, tau_yz) plane, unit circumradius tau = 100 MPa, visited in turn:
    A = (0, 1), B = (-sqrt3/2, -1/2), C = (sqrt3/2, -1/2) times tau.  vM of a pure shear
    difference is sqrt(3) times its Euclidean length, so the minimum ball is the
    circumcircle: radius sqrt(3) tau = 173.2 MPa, centre 0.  The mid-range centre is
    (0, tau/4), whose farthest corner is sqrt(3/4 + 9/16) tau = 1.1456 tau away: 14.6 %
    above the minimum -- the error the refinement must remove; 1 % is asked (the
    Badoiu-Clarkson steps reach it on this path).  The lower bound is half the longest
    chord found: the side sqrt(3) tau, so sqrt(3) * sqrt(3)/2 tau = 1.5 tau, exactly."""
    tau = 100e6
    corners = np.array([[0.0, 1.0], [-np.sqrt(3) / 2, -0.5], [np.sqrt(3) / 2, -0.5]]) * tau
    path = np.concatenate([np.linspace(corners[i], corners[(i + 1) % 3], 40, endpoint=False) for i in range(3)])
    h = np.zeros((path.shape[0], 6, 1))
    h[:, 3, 0], h[:, 4, 0] = path[:, 0], path[:, 1]
    mid = 0.5 * (h.min(axis=0) + h.max(axis=0))
    assert von_mises(h - mid[None]).max() == pytest.approx(np.sqrt(3) * np.sqrt(0.75 + 0.5625) * tau, rel=1e-12)
    a, m, low = amplitude_mean(h)
    assert a[0] == pytest.approx(np.sqrt(3) * tau, rel=1e-2)
    assert a[0] >= np.sqrt(3) * tau * (1 - 1e-12)  # an upper bound, never below the minimum
    assert von_mises(m).max() < 0.05 * tau  # the centre near 0 (0.027 tau), far from the mid-range's 0.433 tau
    assert low[0] == pytest.approx(1.5 * tau, rel=1e-12)
    # the signed mean of a pure shear centre is tensile (s_1 > 0): +vM
    assert signed_mean(np.array([[0, 0, 0, 30e6, 0, 0.0]]).T)[0] == pytest.approx(np.sqrt(3) * 30e6, rel=1e-12)


def test_bending_direction_from_the_largest_meridional_deviation():
    """``bending_torsion`` on a four-instant path at the node (0, a) of an axis through
    the origin (e_r = +y, e_theta = -x: s_rr = s_yy, s_rz = s_yz, s_rtheta = -s_xy,
    s_thetaz = -s_xz).  Meridional deviations (rr, zz, rz) from the mean m = (0, 200, 0)
    MPa, summing to zero, with their Frobenius sizes sqrt(rr^2 + zz^2 + 2 rz^2):

        d0 = (10, -50, -10)     52.9
        d1 = -100 t t = (-36, -64, -48), t = (0.6, 0.8)   100   <- the largest
        d2 = (26, 44, 58)       96.6
        d3 = (0, 70, 0)         70

    The eigenvalue of d1 of largest magnitude is -100 (compressive), its direction
    t = (0.6, 0.8), so sigma = t.S.t = 0.36 rr + 0.96 rz + 0.64 zz at each instant:
    S0 = (10, 150, -10): 3.6 - 9.6 + 96 = 90;  S1 = (-36, 136, -48): -12.96 - 46.08 + 87.04
    = 28;  S2 = (26, 244, 58): 9.36 + 55.68 + 156.16 = 221.2;  S3 = (0, 270, 0): 172.8 MPa;
    tau = +-(0.6 s_rtheta + 0.8 s_thetaz) (the sign of t is free).  The path is chosen so
    that another instant (d2, or d0 when the search is skipped), the eigenvalue of the
    other sign, another weighting of the size or deviations not taken from the mean give
    another direction: sigma off by more than 1 MPa."""
    from fe_crank.assess.fatigue import bending_torsion

    mer = np.array([[10.0, 150.0, -10.0], [-36.0, 136.0, -48.0], [26.0, 244.0, 58.0], [0.0, 270.0, 0.0]]) * 1e6
    rt = np.array([10.0, 20.0, -30.0, 0.0]) * 1e6
    tz = np.array([5.0, -5.0, 0.0, 0.0]) * 1e6
    h = np.zeros((4, 6, 1))
    h[:, 1, 0], h[:, 2, 0], h[:, 4, 0] = mer[:, 0], mer[:, 1], mer[:, 2]  # yy, zz, yz
    h[:, 3, 0], h[:, 5, 0] = -rt, -tz  # xy, xz
    h[:, 0, 0] = 30e6  # s_xx = s_thetatheta: outside the meridional plane, no effect
    sigma, tau = bending_torsion(h, np.array([[0.0], [0.02], [0.001]]), (0.0, 0.0))
    np.testing.assert_allclose(sigma[:, 0], [90e6, 28e6, 221.2e6, 172.8e6], rtol=1e-12)
    expected_tau = 0.6 * rt + 0.8 * tz
    np.testing.assert_allclose(np.sign(tau[0, 0]) * tau[:, 0], expected_tau, rtol=1e-12, atol=1e-6)


def test_bending_torsion_and_signed_mean_are_homogeneous_at_any_scale():
    """sigma, tau and the signed mean are linear in the stress (degree 1): the path above
    scaled by 1e-8 (deviations below 1 Pa) gives the values scaled by 1e-8 -- no
    threshold in pascals may enter the directions or the signs.  A path with no
    variation has no bending direction: the axis direction (0, 1) is taken, sigma =
    s_zz, tau = s_thetaz."""
    from fe_crank.assess.fatigue import bending_torsion

    mer = np.array([[10.0, 150.0, -10.0], [-36.0, 136.0, -48.0], [26.0, 244.0, 58.0], [0.0, 270.0, 0.0]])
    h = np.zeros((4, 6, 1))
    h[:, 1, 0], h[:, 2, 0], h[:, 4, 0] = mer[:, 0], mer[:, 1], mer[:, 2]
    pts = np.array([[0.0], [0.02], [0.001]])
    for scale in (1e6, 1e-8):
        sigma, _ = bending_torsion(scale * h, pts, (0.0, 0.0))
        np.testing.assert_allclose(sigma[:, 0], scale * np.array([90.0, 28.0, 221.2, 172.8]), rtol=1e-12)
    still = np.zeros((3, 6, 1))
    still[:, 1, 0], still[:, 2, 0], still[:, 5, 0] = 50e6, 100e6, -7e6  # s_rr, s_zz, s_thetaz = +7 MPa
    sigma, tau = bending_torsion(still, pts, (0.0, 0.0))
    np.testing.assert_allclose(sigma[:, 0], 100e6, rtol=1e-12)
    np.testing.assert_allclose(tau[:, 0], 7e6, rtol=1e-12)
    # a tensile mean of 0.5 Pa is tensile, a compressive one compressive
    np.testing.assert_allclose(
        signed_mean(np.array([[0.5, -0.5], [0, 0], [0, 0], [0, 0], [0, 0], [0, 0.0]])), [0.5, -0.5], rtol=1e-12
    )


def test_the_mid_range_centre_is_kept_when_it_is_the_minimum():
    """Four shear states on a circle of radius tau about 0, visited P2, P1, P3, P4 with
    P1 = (1, 0), P2 = (-1/2, sqrt3/2), P3 = (-1/2, -sqrt3/2), P4 = (-1, 0) times tau in the
    (tau_xy, tau_yz) plane.  The mid-range is 0, and P1, P4 are a diameter: the minimum
    ball is centred on the mid-range, radius sqrt(3) tau exactly.  The chord search
    starts from P2 (the first of the equally far points), whose longest chord is
    sqrt(3) tau < the diameter, so the refinement runs -- and must not replace the exact
    centre by a worse one: the amplitude stays sqrt(3) tau to round-off."""
    tau = 100e6
    pts = np.array([[-0.5, np.sqrt(3) / 2], [1.0, 0.0], [-0.5, -np.sqrt(3) / 2], [-1.0, 0.0]]) * tau
    h = np.zeros((4, 6, 1))
    h[:, 3, 0], h[:, 4, 0] = pts[:, 0], pts[:, 1]
    a, m, low = amplitude_mean(h)
    assert low[0] == pytest.approx(1.5 * tau, rel=1e-12)  # sqrt3 * (sqrt3 tau / 2): refinement runs
    assert a[0] == pytest.approx(np.sqrt(3) * tau, rel=1e-12)
    assert np.abs(m).max() < 1e-9 * tau
