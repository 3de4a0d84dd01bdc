"""Coefficient tables of fe_crank.mechanism.kinematics against hand arithmetic and closed forms:
the Fourier transform helper on trigonometric polynomials whose coefficients are known
exactly, the "leading" and "series" coefficient tables of Kolchin & Demidov ch. 2 /
Taylor vol. 2 ch. 8 at lambda = 1/4 (exact binary fractions, so the comparisons are to
round-off), and the input checks (crank ratio, orders, crank radius, sample count)."""

import numpy as np
import pytest

from fe_crank.errors import GeometryError, InputError
from fe_crank.mechanism.kinematics import fourier_coefficients, harmonic_coefficients, piston_motion, sample_angles

LAM = 0.25


def test_fourier_coefficients_of_a_known_trigonometric_polynomial():
    """f(t) = 3 + 2 cos t - 5 sin t + 0.5 cos 3t + 0.25 sin 3t on 8 samples: alpha_0 = 3
    (the mean), (alpha_1, beta_1) = (2, -5), (alpha_2, beta_2) = (0, 0),
    (alpha_3, beta_3) = (0.5, 0.25) and beta_0 = 0 by definition."""
    t = sample_angles(8)
    np.testing.assert_allclose(t, np.arange(8) * np.pi / 4, rtol=0, atol=1e-15)
    f = 3 + 2 * np.cos(t) - 5 * np.sin(t) + 0.5 * np.cos(3 * t) + 0.25 * np.sin(3 * t)
    c = fourier_coefficients(f, 3)
    expected = [[3.0, 0.0], [2.0, -5.0], [0.0, 0.0], [0.5, 0.25]]
    np.testing.assert_allclose(c, expected, rtol=0, atol=1e-14)
    assert c[0, 1] == 0.0


def test_fourier_coefficients_row_by_row_for_stacked_samples():
    """A (2, n) stack gives (2, kmax + 1, 2): row 0 is 1 + cos t, row 1 is sin 2t."""
    t = sample_angles(16)
    c = fourier_coefficients(np.stack([1 + np.cos(t), np.sin(2 * t)]), 2)
    assert c.shape == (2, 3, 2)
    np.testing.assert_allclose(c[0], [[1, 0], [1, 0], [0, 0]], rtol=0, atol=1e-14)
    np.testing.assert_allclose(c[1], [[0, 0], [0, 0], [0, 1]], rtol=0, atol=1e-14)


def test_highest_order_below_half_the_sample_count():
    """Orders k < n/2 are resolved: n = 7 (odd) gives order 3 exactly, n = 8 order 3;
    order 4 on 8 samples is the Nyquist term (sin 4t vanishes at every sample) and is
    refused with the key ``kmax``."""
    t7 = sample_angles(7)
    c7 = fourier_coefficients(np.cos(3 * t7) + 2 * np.sin(3 * t7), 3)
    np.testing.assert_allclose(c7[3], [1.0, 2.0], rtol=0, atol=1e-14)
    t8 = sample_angles(8)
    c8 = fourier_coefficients(np.sin(3 * t8), 3)
    np.testing.assert_allclose(c8[3], [0.0, 1.0], rtol=0, atol=1e-14)
    with pytest.raises(InputError, match="order 4 needs more than 8 samples") as err:
        fourier_coefficients(np.sin(4 * t8), 4)
    assert err.value.key == "kmax"


def test_leading_coefficients_at_lambda_one_quarter():
    """method="leading": A_1 = 1, A_2 = lam = 0.25, A_4 = -lam^3/4 = -0.015625/4 =
    -0.00390625, A_6 = 9 lam^5/128 = 9 * 0.0009765625/128 = 6.866455078125e-05, and every
    other order (3, 5, 8) zero."""
    a = harmonic_coefficients(LAM, (1, 2, 3, 4, 5, 6, 8), method="leading")
    assert a == {1: 1.0, 2: 0.25, 3: 0.0, 4: -0.00390625, 5: 0.0, 6: 6.866455078125e-05, 8: 0.0}


def test_series_coefficients_at_lambda_one_quarter():
    """method="series" (to lam^5): A_2 = 0.25 + 0.015625/4 + 15 * 0.0009765625/128
    = 0.25 + 0.00390625 + 0.000114440918 = 0.254020690918; A_4 = -(0.00390625 +
    3 * 0.0009765625/16) = -0.004089355469; A_6 = 6.866455078125e-05; orders the series
    does not hold (odd orders, 8) are zero."""
    a = harmonic_coefficients(LAM, (1, 2, 3, 4, 6, 8), method="series")
    assert a[1] == 1.0
    assert a[2] == pytest.approx(0.254020690918, rel=1e-11)
    assert a[4] == pytest.approx(-0.004089355469, rel=1e-9)
    assert a[6] == pytest.approx(6.866455078125e-05, rel=1e-12)
    assert a[3] == 0.0 and a[8] == 0.0


@pytest.mark.parametrize("lam", [0.0, -0.1, 1.0, 1.5])
@pytest.mark.parametrize("method", ["series", "leading", "exact"])
def test_crank_ratio_outside_the_open_unit_interval_is_refused(lam, method):
    with pytest.raises(GeometryError, match=r"crank ratio lambda = r/l must lie in \(0, 1\)"):
        harmonic_coefficients(lam, (1, 2), method=method)


def test_bad_orders_and_method_are_refused_by_name():
    with pytest.raises(ValueError, match="harmonic orders must be >= 1"):
        harmonic_coefficients(LAM, (0, 2))
    with pytest.raises(ValueError, match="method must be 'exact', 'series' or 'leading'"):
        harmonic_coefficients(LAM, (1, 2), method="taylor")


def test_mechanism_checks_by_message():
    """r and l must be positive and finite, and l > r + |e| (the crank turns fully):
    l = r + |e| exactly (0.375 = 0.25 + 0.125, binary fractions) is refused as well."""
    with pytest.raises(GeometryError, match="crank radius must be positive"):
        piston_motion(0.0, 0.0, 0.3, 1.0)
    for bad_l in (0.0, float("inf")):
        with pytest.raises(GeometryError, match="rod length must be positive"):
            piston_motion(0.0, 0.1, bad_l, 1.0)
    turn = "must exceed crank radius .* otherwise the crank cannot turn fully"
    with pytest.raises(GeometryError, match=turn):
        piston_motion(0.0, 0.25, 0.375, 1.0, offset=-0.125)
    with pytest.raises(GeometryError, match=turn):
        piston_motion(0.0, 0.1, 0.12, 1.0, offset=0.05)  # 0.12 < 0.1 + 0.05


def test_integer_angles_are_float_radians():
    m = piston_motion([0, 1, 2], 0.05, 0.2, 10.0)
    assert m.phi.dtype == np.float64
    np.testing.assert_array_equal(m.phi, [0.0, 1.0, 2.0])


def test_crankpin_vectors_closed_form_and_rod_cg_zero_without_a_distance():
    """Crankpin B = r (cos phi, sin phi) in (axial, lateral): v_B = r omega (-sin, cos),
    a_B = -r omega^2 (cos, sin); at phi = 90 deg with r = 0.05 m, omega = 10 rad/s:
    v_B = (-0.5, 0) m/s and a_B = (0, -5) m/s^2.  Without ``rod_cg`` the rod's
    centre-of-mass vectors are zero arrays of the same (n, 2) shape (class docstring)."""
    phi = np.array([0.0, np.pi / 2, 2.0])
    r, omega = 0.05, 10.0
    m = piston_motion(phi, r, 0.2, omega)
    np.testing.assert_allclose(m.crankpin_velocity[1], [-0.5, 0.0], rtol=0, atol=1e-15)
    np.testing.assert_allclose(m.crankpin_acceleration[1], [0.0, -5.0], rtol=0, atol=1e-15)
    np.testing.assert_allclose(
        m.crankpin_velocity, r * omega * np.stack([-np.sin(phi), np.cos(phi)], -1), rtol=1e-15, atol=1e-16
    )
    np.testing.assert_allclose(
        m.crankpin_acceleration, -r * omega**2 * np.stack([np.cos(phi), np.sin(phi)], -1), rtol=1e-15, atol=1e-15
    )
    for vec in (m.rod_cg_velocity, m.rod_cg_acceleration):
        assert vec.shape == (3, 2)
        np.testing.assert_array_equal(vec, 0.0)
