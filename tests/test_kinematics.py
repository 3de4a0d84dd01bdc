"""Kinematics: exact motion against numerical differentiation and closed forms,
harmonic series against the exact motion."""

import numpy as np
import pytest

from fe_crank.errors import GeometryError
from fe_crank.kinematics import harmonic_coefficients, piston_motion, piston_motion_harmonic

R, L, OMEGA = 0.064, 0.307, 293.07  # seed 001


def _central(f, x, h):
    return (f(x + h) - f(x - h)) / (2 * h)


@pytest.mark.parametrize("offset", [0.0, 0.008, -0.005])
def test_exact_motion_matches_numerical_differentiation(offset):
    phi = np.linspace(0.0, 2 * np.pi, 73)
    h = 1e-4
    cg = 0.3 * L
    m = piston_motion(phi, R, L, OMEGA, offset=offset, rod_cg=cg)

    def s(p):
        return piston_motion(p, R, L, OMEGA, offset=offset).s

    def beta(p):
        return piston_motion(p, R, L, OMEGA, offset=offset).beta

    def v(p):
        return piston_motion(p, R, L, OMEGA, offset=offset).v

    def bd(p):
        return piston_motion(p, R, L, OMEGA, offset=offset).beta_dot

    np.testing.assert_allclose(m.v, OMEGA * _central(s, phi, h), atol=1e-6 * R * OMEGA)
    np.testing.assert_allclose(m.a, OMEGA * _central(v, phi, h), atol=1e-6 * R * OMEGA**2)
    np.testing.assert_allclose(m.beta_dot, OMEGA * _central(beta, phi, h), atol=1e-7 * OMEGA)
    np.testing.assert_allclose(m.beta_ddot, OMEGA * _central(bd, phi, h), atol=1e-6 * OMEGA**2)

    # rod centre of mass: differentiate its position built independently from geometry
    def g(p):
        p = np.asarray(p, float)
        bx, by = R * np.cos(p), R * np.sin(p)
        beta_ = np.arcsin((R * np.sin(p) - offset) / L)
        px, py = R * np.cos(p) + L * np.cos(beta_), np.full_like(p, offset)
        return np.stack([bx + cg / L * (px - bx), by + cg / L * (py - by)], -1)

    vg = OMEGA * (g(phi + h) - g(phi - h)) / (2 * h)
    ag = OMEGA**2 * (g(phi + h) - 2 * g(phi) + g(phi - h)) / h**2
    np.testing.assert_allclose(m.rod_cg_velocity, vg, atol=1e-6 * R * OMEGA)
    np.testing.assert_allclose(m.rod_cg_acceleration, ag, atol=1e-4 * R * OMEGA**2)


def test_dead_centres_closed_form():
    # no offset: s(0) = 0, s(pi) = 2r, a(0) = r w^2 (1 + lam), a(pi) = -r w^2 (1 - lam)
    m = piston_motion(np.array([0.0, np.pi]), R, L, OMEGA)
    lam = R / L
    np.testing.assert_allclose(m.s, [0.0, 2 * R], atol=1e-15)
    np.testing.assert_allclose(m.a, [R * OMEGA**2 * (1 + lam), -R * OMEGA**2 * (1 - lam)], rtol=1e-13)
    # with offset the stroke is sqrt((l+r)^2-e^2) - sqrt((l-r)^2-e^2) (> 2r)
    e = 0.01
    phi = np.linspace(0, 2 * np.pi, 200001)
    s = piston_motion(phi, R, L, OMEGA, offset=e).s
    stroke = np.sqrt((L + R) ** 2 - e**2) - np.sqrt((L - R) ** 2 - e**2)
    assert s.min() == pytest.approx(0.0, abs=1e-9)
    assert s.max() == pytest.approx(stroke, rel=1e-9)


def test_series_coefficients_match_exact_fourier_to_next_power_of_lambda():
    for lam in (0.1, 0.2, 0.3):
        ex = harmonic_coefficients(lam, (1, 2, 3, 4, 6))
        se = harmonic_coefficients(lam, (1, 2, 4, 6), method="series")
        assert ex[1] == pytest.approx(1.0, abs=1e-13)
        assert abs(ex[3]) < 1e-13  # odd orders vanish without offset
        for k in (2, 4, 6):
            # truncation after lam^5: error of order lam^7
            assert abs(ex[k] - se[k]) < lam**7
        # sum of all coefficients at phi = 0 is a(0)/(r w^2) = 1 + lam exactly
        allk = harmonic_coefficients(lam, range(1, 40))
        assert sum(allk.values()) == pytest.approx(1 + lam, abs=1e-12)


def test_truncated_series_converges_with_error_of_next_order():
    phi = np.linspace(0, 2 * np.pi, 721)
    lam = R / L
    ex = piston_motion(phi, R, L, OMEGA)
    A = harmonic_coefficients(lam, (2, 4, 6, 8))
    prev = np.inf
    for orders, nxt in [((1, 2), 4), ((1, 2, 4), 6), ((1, 2, 4, 6), 8)]:
        h = piston_motion_harmonic(phi, R, L, OMEGA, orders)
        err = np.max(np.abs(h.a - ex.a)) / (R * OMEGA**2)
        # error dominated by the first omitted order
        assert err == pytest.approx(abs(A[nxt]), rel=0.1)
        assert err < prev
        prev = err
        err_s = np.max(np.abs(h.s - ex.s)) / R
        assert err_s < 2.5 * abs(A[nxt]) / nxt**2
    # first-order only misses the lam cos 2phi term
    h1 = piston_motion_harmonic(phi, R, L, OMEGA, (1,))
    assert np.max(np.abs(h1.a - ex.a)) / (R * OMEGA**2) == pytest.approx(A[2] + abs(A[4]), rel=0.05)


def test_rod_shorter_than_crank_is_rejected():
    with pytest.raises(GeometryError, match="rod length"):
        piston_motion(0.0, 0.1, 0.09, 1.0)
    with pytest.raises(GeometryError):
        piston_motion(0.0, -0.1, 0.3, 1.0)
