"""Torsional free vibration against closed forms (Den Hartog, Mechanical Vibrations,
4th ed., ch. 5) and Holzer's table against the generalised eigenproblem."""

from __future__ import annotations

import numpy as np
import pytest

from fe_crank.torsion.free import holzer_frequencies, holzer_table, natural_modes
from fe_crank.torsion.model import TorsionModel


def chain(J, k, eta=None):
    J, k = np.asarray(J, float), np.asarray(k, float)
    eta = np.zeros(k.size) if eta is None else np.asarray(eta, float)
    return TorsionModel(
        tuple(f"m{i}" for i in range(J.size)),
        J,
        k,
        eta,
        np.zeros(k.size),
        np.zeros(J.size),
        tuple(f"s{i}" for i in range(k.size)),
        {},
    )


def test_two_discs():
    """omega^2 = k (J1 + J2) / (J1 J2) = 1e4 * 2.5 / (0.5 * 2) = 25000 -> 158.114 rad/s;
    node where theta_2 / theta_1 = -J1 / J2 = -0.25 (Den Hartog sec. 5.2)."""
    m = natural_modes(chain([0.5, 2.0], [1e4]))
    assert m.omega[0] == pytest.approx(0.0, abs=1e-5)
    assert m.omega[1] == pytest.approx(np.sqrt(25000.0), rel=1e-12)
    assert m.shapes[1, 1] / m.shapes[0, 1] == pytest.approx(-0.25, rel=1e-12)


def test_three_equal_discs():
    """Free-free J-k-J-k-J: omega^2 = k/J and 3 k/J (100 and 300 rad^2/s^2 for
    J = 1, k = 100); shapes (1, 0, -1) and (1, -2, 1)."""
    m = natural_modes(chain([1.0, 1.0, 1.0], [100.0, 100.0]))
    np.testing.assert_allclose(m.omega[1:] ** 2, [100.0, 300.0], rtol=1e-12)
    np.testing.assert_allclose(m.shapes[:, 1], [1.0, 0.0, -1.0], atol=1e-12)
    np.testing.assert_allclose(m.shapes[:, 2], [0.5, -1.0, 0.5], atol=1e-12)


def test_three_unequal_discs_closed_form():
    """Free-free three discs: the elastic omega^2 are the roots of
    J1 J2 J3 w^4 - [k1 J3 (J1 + J2) + k2 J1 (J2 + J3)] w^2 + k1 k2 (J1 + J2 + J3) = 0."""
    J1, J2, J3, k1, k2 = 0.2, 1.5, 0.7, 3e4, 8e3
    a, b, c = J1 * J2 * J3, -(k1 * J3 * (J1 + J2) + k2 * J1 * (J2 + J3)), k1 * k2 * (J1 + J2 + J3)
    roots = np.sort(np.roots([a, b, c]).real)
    m = natural_modes(chain([J1, J2, J3], [k1, k2]))
    np.testing.assert_allclose(m.omega[1:] ** 2, roots, rtol=1e-12)


def test_uniform_shaft_lumped_converges_to_continuous():
    """A free-free steel shaft (D 50 mm, L 1 m) cut into N - 1 = 100 equal elements
    (end masses halved): omega_r -> r pi c / L, c = sqrt(G / rho) (Den Hartog sec. 8.2).
    The lumped chain is low by about (r pi / (N - 1))^2 / 24: 4.1e-5 for r = 1,
    1.6e-4 for r = 2, so 1e-4 and 4e-4 would catch an error in J or k of 2e-4."""
    G, rho, D, L, N = 80e9, 7850.0, 0.05, 1.0, 101
    Ip = np.pi * D**4 / 32
    h = L / (N - 1)
    J = np.full(N, rho * Ip * h)
    J[[0, -1]] /= 2
    m = natural_modes(chain(J, np.full(N - 1, G * Ip / h)))
    c = np.sqrt(G / rho)
    assert m.omega[1] / (np.pi * c / L) == pytest.approx(1.0, abs=1e-4)
    assert m.omega[2] / (2 * np.pi * c / L) == pytest.approx(1.0, abs=4e-4)
    # the discrete chain's own closed form (interior masses J, ends J/2): sin law
    # omega_r = 2 sqrt(k/J) sin(r pi / (2 (N - 1)))
    exact = 2 * np.sqrt((G * Ip / h) / (rho * Ip * h)) * np.sin(np.arange(1, 4) * np.pi / (2 * (N - 1)))
    np.testing.assert_allclose(m.omega[1:4], exact, rtol=1e-9)


def test_holzer_equals_eigenproblem():
    """Holzer's residual torque vanishes exactly at the eigenvalues of K x = w^2 J x (an
    independent method: no matrices), here for an irregular 7-mass engine-like chain."""
    J = [0.006, 0.004, 0.021, 0.019, 0.019, 0.021, 0.15]
    k = [2e4, 3e5, 4.1e5, 4.0e5, 4.1e5, 4e5]
    model = chain(J, k)
    m = natural_modes(model)
    h = holzer_frequencies(model, 1.2 * m.omega[-1])
    np.testing.assert_allclose(h, m.omega[1:], rtol=1e-9)
    # the Holzer angles at a natural frequency are the mode shape
    tab = holzer_table(model, m.omega[2])
    np.testing.assert_allclose(tab["theta"] / tab["theta"][0], m.shapes[:, 2] / m.shapes[0, 2], rtol=1e-7, atol=1e-9)
    assert abs(tab["cumulative"][-1]) < 1e-8 * np.max(np.abs(tab["inertia_torque"]))
