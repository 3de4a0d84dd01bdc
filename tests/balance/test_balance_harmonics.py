"""Harmonic split of the piston acceleration: spectral coefficients vs the closed-form series."""

import numpy as np
import pytest

from fe_crank.balance import harmonics


@pytest.mark.parametrize("lam", [0.2, 0.25, 0.3])
def test_spectral_coefficients_match_the_series_to_its_truncation(lam):
    """A2 = lam + lam^3/4 + 15 lam^5/128, A4 = -(lam^3/4 + 3 lam^5/16), A6 = 9 lam^5/128 (Taylor;
    Heywood): the series is truncated after lam^5, so it agrees to O(lam^7)."""
    r, l = 0.05, 0.05 / lam
    phi = harmonics.sample_angles()
    x = r * np.cos(phi) + np.sqrt(l**2 - (r * np.sin(phi)) ** 2)  # piston pin from the crank axis
    acc = harmonics.acceleration_coefficients(x, 12)
    a_k = -acc[:, 0] / r  # s = const - x, a = -x'' omega^2; cos coefficients
    series = harmonics.series_coefficients(lam)
    for k, ak in series.items():
        assert a_k[k] == pytest.approx(ak, abs=2 * lam**7)
    assert np.abs(acc[:, 1]).max() < 1e-12 * r  # no sine terms without a pin offset
    assert np.abs(a_k[3::2]).max() < 1e-12  # nor odd orders above the first


def test_fourier_coefficients_of_a_trigonometric_polynomial_are_exact():
    t = harmonics.sample_angles(64)
    y = 0.5 + 2 * np.cos(t) - 3 * np.sin(3 * t) + 0.25 * np.cos(7 * t)
    c = harmonics.fourier_coefficients(y, 8)
    assert c[0, 0] == pytest.approx(0.5)
    assert c[1] == pytest.approx([2, 0], abs=1e-12)
    assert c[3] == pytest.approx([0, -3], abs=1e-12)
    assert c[7] == pytest.approx([0.25, 0], abs=1e-12)
    with pytest.raises(ValueError):
        harmonics.fourier_coefficients(y, 32)
