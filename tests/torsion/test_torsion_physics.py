"""Closed forms that see the torsional model's physics where a slip would pass the
resonance tests: the throw's mean reciprocating inertia, and a resonance with viscous
and hysteretic damping together (the sign of the loss factor)."""

from __future__ import annotations

import numpy as np
import pytest

from fe_crank import model
from fe_crank.torsion.build import reciprocating_inertia
from fe_crank.torsion.excitation import CylinderHarmonics
from fe_crank.torsion.forced import forced_response
from fe_crank.torsion.model import TorsionModel


def mean_v2_closed(lam: float) -> float:
    """mean over a revolution of (ds/dphi)^2 / r^2 of the central slider crank.

    ds/dphi = r (sin phi + (lam/2) sin 2phi / sqrt(1 - lam^2 sin^2 phi)); squaring, the
    cross term (odd in cos phi) has zero mean and
    mean = 1/2 + (lam^2/4) mean(sin^2 2phi / (1 - lam^2 sin^2 phi))
         = 1/2 + (1 - lam^2/2 - sqrt(1 - lam^2)) / lam^2
    (with mean(1/(1 - lam^2 sin^2 phi)) = 1/sqrt(1 - lam^2)); its series is
    1/2 + lam^2/8 + lam^4/16 + 5 lam^6/128 + ... (Den Hartog sec. 5.2 and Ker Wilson
    vol. 1 give the first two terms)."""
    return 0.5 + (1.0 - lam**2 / 2 - np.sqrt(1.0 - lam**2)) / lam**2


@pytest.mark.parametrize("lam", [0.2, 0.3, 0.45])
def test_mean_of_ds_dphi_squared_closed_form_series_and_quadrature(lam):
    """The closed form against Gauss-Legendre quadrature of the exact slider crank's
    ds/dphi (written here) and against its series to lam^6 (remainder O(lam^8))."""
    x, w = np.polynomial.legendre.leggauss(400)
    phi = np.pi * (x + 1.0)  # [0, 2 pi]
    v = np.sin(phi) + 0.5 * lam * np.sin(2 * phi) / np.sqrt(1 - (lam * np.sin(phi)) ** 2)
    quad = np.pi * np.sum(w * v**2) / (2 * np.pi)
    assert mean_v2_closed(lam) == pytest.approx(quad, rel=1e-12)
    series = 0.5 + lam**2 / 8 + lam**4 / 16 + 5 * lam**6 / 128
    assert abs(mean_v2_closed(lam) - series) < lam**8  # next term 7 lam^8 / 256
    assert abs(mean_v2_closed(lam) - (0.5 + lam**2 / 8)) > lam**4 / 17  # the second-order form is not exact


def test_throw_inertia_of_a_cylinder_is_the_cycle_mean():
    """reciprocating_inertia = rotating rod share m_rod (l - c)/l R^2 + m_j mean((ds/dphi)^2)
    with m_j = m_piston + m_rod c / l: about half of m_j R^2, not m_j R^2."""
    r, l, c, m_rod, m_p = 0.043, 0.1435, 0.037, 0.55, 0.40
    cyl = model.Cylinder("1", "1", 0.086, model.Rod(l, m_rod, c), m_p)
    lam = r / l
    m_j = m_p + m_rod * c / l
    expected = m_rod * (l - c) / l * r**2 + m_j * r**2 * mean_v2_closed(lam)
    assert reciprocating_inertia(cyl, r) == pytest.approx(expected, rel=1e-10)
    assert reciprocating_inertia(cyl, r) < m_rod * (l - c) / l * r**2 + 0.6 * m_j * r**2


def one_mass(k: float, eta: float, c: float, j_ground: float = 1e9) -> TorsionModel:
    """Disc ``j`` on a shaft (k, loss factor eta, viscous c across it) to a disc so heavy
    that it stands still: a one-mass oscillator."""
    return TorsionModel(
        ("disc", "ground"),
        np.array([0.05, j_ground]),
        np.array([k]),
        np.array([eta]),
        np.array([c]),
        np.zeros(2),
        ("disc-ground",),
        {"disc": 0},
    )


def harmonic(torque: float) -> CylinderHarmonics:
    return CylinderHarmonics(
        np.array([0.0, 1.0]), {"c": np.array([0.0, torque])}, {"c": np.zeros(2)}, 100.0, 2 * np.pi, {"c": "disc"}
    )


@pytest.mark.parametrize("eta, zeta_c", [(0.04, 0.01), (0.02, 0.03)])
def test_resonance_with_viscous_and_hysteretic_damping(eta, zeta_c):
    """J theta'' + c theta' + k (1 + i eta) theta = T0 e^(i Omega t) at Omega^2 = k / J:
    theta = T0 / (i (k eta + Omega c)), so the shaft's elastic torque k (1 + i eta) theta
    has |T| = T0 sqrt(1 + eta^2) / (eta + Omega c / k) and the whole segment torque
    (with the viscous part) T0 sqrt(1 + (eta + Omega c/k)^2) / (eta + Omega c / k).
    A loss factor of the wrong sign (k (1 - i eta)) gives T0 / |Omega c / k - eta| instead."""
    k, j, t0 = 4e5, 0.05, 100.0
    w = np.sqrt(k / j)
    c = 2 * zeta_c * np.sqrt(k * j)
    m = one_mass(k, eta, c)
    r = forced_response(m, harmonic(t0), [w], [1.0])
    theta = r.angle[0, 0, 0] - r.angle[0, 0, 1]
    d = eta + w * c / k
    assert abs(k * (1 + 1j * eta) * theta) == pytest.approx(t0 * np.sqrt(1 + eta**2) / d, rel=1e-6)
    assert abs(r.segment[0, 0, 0]) == pytest.approx(t0 * np.sqrt(1 + d**2) / d, rel=1e-6)


def test_damping_work_per_cycle_is_positive_at_every_speed():
    """The work of the exciting torque per cycle, pi Im(T conj(theta)) (the loss of the
    hysteretic and viscous damping, pi |theta|^2 (k eta + Omega c)), is positive at
    every frequency, below, at and above the resonance."""
    k, eta, c, t0 = 4e5, 0.04, 2.0, 100.0
    m = one_mass(k, eta, c)
    w0 = np.sqrt(k / 0.05)
    speeds = w0 * np.array([0.3, 0.7, 0.95, 1.0, 1.05, 1.5, 3.0])
    r = forced_response(m, harmonic(t0), speeds, [1.0])
    for s, w in enumerate(speeds):
        theta = r.angle[s, 0, 0] - r.angle[s, 0, 1]
        work = np.pi * np.imag(t0 * np.conj(r.angle[s, 0, 0]))
        assert work > 0
        assert work == pytest.approx(np.pi * abs(theta) ** 2 * (k * eta + w * c), rel=1e-6)
