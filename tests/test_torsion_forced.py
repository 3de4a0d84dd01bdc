"""Forced damped response against single-degree-of-freedom closed forms."""

from __future__ import annotations

import numpy as np
import pytest

from fe_crank.torsion.forced import receptance
from fe_crank.torsion.model import TorsionModel


def two_discs(J1, J2, k, *, c=0.0, eta=0.0):
    return TorsionModel(("a", "b"), np.array([J1, J2]), np.array([k]), np.array([eta]), np.array([c]),
                        np.zeros(2), ("a-b",), {})


@pytest.mark.parametrize("zeta", [0.01, 0.05, 0.2])
def test_viscous_amplification_at_resonance_is_one_over_two_zeta(zeta):
    """Torque T on disc 1 of a free two-disc system: the relative twist q obeys
    mu q'' + c q' + k q = T mu / J1 (mu = J1 J2 / (J1 + J2)), a single-DOF oscillator.
    At Omega^2 = k / mu the spring torque k|q| is 1/(2 zeta) times its static value
    T mu / J1 (= T J2 / (J1 + J2)), zeta = c / (2 sqrt(k mu))."""
    J1, J2, k, T = 0.02, 0.15, 4e5, 100.0
    mu = J1 * J2 / (J1 + J2)
    c = 2 * zeta * np.sqrt(k * mu)
    m = two_discs(J1, J2, k, c=c)
    w = np.sqrt(k / mu)
    x = np.linalg.solve(receptance(m, w), np.array([T, 0.0]))
    spring = k * abs(x[0] - x[1])
    assert spring / (T * J2 / (J1 + J2)) == pytest.approx(1 / (2 * zeta), rel=1e-10)
    # total segment torque (spring + damper) = spring * sqrt(1 + (2 zeta)^2)
    seg = abs(m.segment_torque(x, w)[0])
    assert seg / spring == pytest.approx(np.sqrt(1 + (2 * zeta) ** 2), rel=1e-10)


def test_hysteretic_amplification_at_resonance_is_one_over_eta():
    """With a loss factor eta (complex stiffness k (1 + i eta)) the resonant spring
    twist is 1/eta times the static one (Den Hartog sec. 2.8 with 2 zeta -> eta)."""
    J1, J2, k, T, eta = 0.02, 0.15, 4e5, 100.0, 0.04
    mu = J1 * J2 / (J1 + J2)
    m = two_discs(J1, J2, k, eta=eta)
    x = np.linalg.solve(receptance(m, np.sqrt(k / mu)), np.array([T, 0.0]))
    assert k * abs(x[0] - x[1]) / (T * J2 / (J1 + J2)) == pytest.approx(1 / eta, rel=1e-10)


def test_off_resonance_dynamic_magnifier():
    """Undamped: spring torque / static = 1 / |1 - r^2|, r = Omega / omega_n (here r = 0.5 -> 4/3)."""
    J1, J2, k, T = 0.02, 0.15, 4e5, 100.0
    mu = J1 * J2 / (J1 + J2)
    m = two_discs(J1, J2, k)
    x = np.linalg.solve(receptance(m, 0.5 * np.sqrt(k / mu)), np.array([T, 0.0]))
    assert k * abs(x[0] - x[1]) / (T * J2 / (J1 + J2)) == pytest.approx(4 / 3, rel=1e-10)
