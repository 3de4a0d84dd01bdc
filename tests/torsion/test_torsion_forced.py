"""Forced damped response against single-degree-of-freedom closed forms."""

from __future__ import annotations

import numpy as np
import pytest

from fe_crank.torsion.forced import receptance
from fe_crank.torsion.model import TorsionModel


def two_discs(J1, J2, k, *, c=0.0, eta=0.0):
    return TorsionModel(
        ("a", "b"), np.array([J1, J2]), np.array([k]), np.array([eta]), np.array([c]), np.zeros(2), ("a-b",), {}
    )


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


def test_forced_response_at_resonance_and_its_synthesis():
    """The batched response of ``forced_response`` on the two-disc oscillator: a torque
    T cos(theta) on disc 1 (order 1) at the speed where omega = sqrt(k / mu) gives the
    spring twist 1/eta times the static one, and the synthesised segment torque is
    T_seg cos(theta + phase) with the same amplitude (hysteretic model: segment torque
    = spring torque * |1 + i eta|)."""
    from fe_crank.torsion.excitation import CylinderHarmonics
    from fe_crank.torsion.forced import forced_response

    J1, J2, k, T, eta = 0.02, 0.15, 4e5, 100.0, 0.04
    mu = J1 * J2 / (J1 + J2)
    m = TorsionModel(
        ("a", "b"), np.array([J1, J2]), np.array([k]), np.array([eta]), np.zeros(1), np.zeros(2), ("a-b",), {"a": 0}
    )
    h = CylinderHarmonics(
        np.array([0.0, 1.0]), {"c": np.array([0.0, T])}, {"c": np.zeros(2)}, 100.0, 2 * np.pi, {"c": "a"}
    )
    w = np.sqrt(k / mu)
    r = forced_response(m, h, [0.5 * w, w], [1.0])
    static = T * J2 / (J1 + J2)
    assert abs(r.segment[1, 0, 0]) / static == pytest.approx(np.hypot(1, eta) / eta, rel=1e-10)
    assert abs(r.segment[0, 0, 0]) / static == pytest.approx(
        np.hypot(1, eta) / abs(1 - 0.25 + 0j + 1j * eta), rel=1e-10
    )
    theta = np.linspace(0, 2 * np.pi, 361)[:-1]
    syn = r.synthesis(1, theta)[0]
    assert 0.5 * np.ptp(syn) == pytest.approx(abs(r.segment[1, 0, 0]), rel=1e-4)
    np.testing.assert_allclose(r.synthesis_all(theta)[1, 0], syn, rtol=0, atol=1e-9 * static)
