"""Holzer's table by hand, the root search of ``holzer_frequencies`` on a grid where two
natural frequencies fall in neighbouring cells, and the rigid-body mode of the
eigen-solution (Den Hartog, Mechanical Vibrations, 4th ed., sec. 5.5)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import eigh

from fe_crank.torsion.free import holzer_frequencies, holzer_table, natural_modes
from fe_crank.torsion.model import TorsionModel


def chain(J, k):
    J, k = np.asarray(J, float), np.asarray(k, float)
    return TorsionModel(
        tuple(f"m{i}" for i in range(J.size)),
        J,
        k,
        np.zeros(k.size),
        np.zeros(k.size),
        np.zeros(J.size),
        tuple(f"s{i}" for i in range(k.size)),
        {},
    )


def test_holzer_table_of_two_discs_by_hand():
    """J = (0.5, 2.0) kg m^2, k = 1e4 N m/rad, omega = 100 rad/s (omega^2 = 1e4), theta_0 = 1:
    inertia torque 1e4 * 0.5 * 1 = 5000 N m, cumulative 5000, twist 5000 / 1e4 = 0.5 rad,
    theta_1 = 1 - 0.5 = 0.5; inertia torque 1e4 * 2.0 * 0.5 = 10000, cumulative (the
    residual) 15000 N m."""
    tab = holzer_table(chain([0.5, 2.0], [1e4]), 100.0)
    assert set(tab) == {"theta", "inertia_torque", "cumulative", "twist"}
    np.testing.assert_allclose(tab["theta"], [1.0, 0.5], rtol=1e-15)
    np.testing.assert_allclose(tab["inertia_torque"], [5000.0, 10000.0], rtol=1e-15)
    np.testing.assert_allclose(tab["cumulative"], [5000.0, 15000.0], rtol=1e-15)
    assert tab["twist"].shape == (1,)
    assert tab["twist"][0] == pytest.approx(0.5, rel=1e-15)


def test_two_frequencies_in_neighbouring_cells_of_the_grid():
    """Three equal discs J = 1, k = 100: omega = 10 and sqrt(300) = 17.3205 rad/s.  Searched
    up to 3999 * 6 = 23994 rad/s on the 4000-point grid (cells of 6 rad/s from 0.024), the
    two roots lie in neighbouring cells (6.02-12.02 and 12.02-18.02): each is bracketed by
    its own cell and found to 1e-12; a bracket two cells wide holds both and no sign change,
    a 50-point grid puts both in its first cell."""
    roots = holzer_frequencies(chain([1.0, 1.0, 1.0], [100.0, 100.0]), 3999 * 6.0)
    np.testing.assert_allclose(roots, [10.0, math.sqrt(300.0)], rtol=1e-12)


def test_rigid_mode_reads_zero_when_its_eigenvalue_rounds_below_zero():
    """Free-free J = (0.2, 1.5, 0.7), k = (3e4, 8e3): scipy's eigenvalue of the rigid-body
    mode comes out slightly negative (checked below); the frequency is 0 rad/s, not NaN."""
    m = chain([0.2, 1.5, 0.7], [3e4, 8e3])
    lam = eigh(m.stiffness_matrix(), m.mass_matrix(), eigvals_only=True)
    assert lam[0] < 0.0
    modes = natural_modes(m)
    assert modes.omega[0] == 0.0
    assert np.all(np.isfinite(modes.omega)) and modes.frequencies_hz[0] == 0.0
