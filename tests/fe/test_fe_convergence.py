"""Load sets of the check-stage convergence study (``fe_crank.fe.refinement.convergence.check_loads``)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest

from fe_crank.fe.refinement.convergence import check_loads


@dataclass(frozen=True)
class Loads:
    pin_force: np.ndarray
    torque_front: np.ndarray
    torque_rear: np.ndarray


def test_peak_pin_force_with_its_bracketing_unit_cases_and_the_torque():
    # |F| = 5, 13, 10 N: the peak is (5, -12) N at 292.6 deg, between pin_270 (= pin_-y) and pin_300;
    # sine rule: a_270 = |F| sin(300 - psi) / sin 30, a_300 = |F| sin(psi - 270) / sin 30
    F = np.array([[3.0, 4.0], [5.0, -12.0], [-6.0, 8.0]])
    tl = Loads(F, np.array([0.0, 1.0, -2.0]), np.array([1.0, -7.0, 3.0]))
    loads = check_loads([tl], omega=100.0)
    psi = np.arctan2(-12.0, 5.0) + 2 * np.pi
    a270 = 13.0 * np.sin(np.deg2rad(300) - psi) / 0.5
    a300 = 13.0 * np.sin(psi - np.deg2rad(270)) / 0.5
    pin = loads["peak pin force"]
    assert set(pin) == {"pin_-y", "pin_300", "centrifugal"}
    assert pin["pin_-y"] == pytest.approx(a270) and pin["pin_300"] == pytest.approx(a300)
    assert pin["centrifugal"] == pytest.approx(1e4)
    assert loads["peak torque"] == {"torque": 7.0}
    # no torque anywhere: no torque load set
    assert "peak torque" not in check_loads([Loads(F, np.zeros(3), np.zeros(3))], omega=1.0)
