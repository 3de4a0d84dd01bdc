"""The cycle assessment's fast paths give the same numbers as the plain formulas.

``assess.stress.von_mises_path`` evaluates the von Mises formula into reused buffers and
``fatigue.amplitude_mean`` takes the nodes in blocks: both must reproduce the plain
evaluation bit for bit (they change where temporaries live, not the arithmetic), and the
formula itself is checked against hand values.
"""

from __future__ import annotations

import numpy as np

from fe_crank.assess import fatigue
from fe_crank.assess.stress import von_mises, von_mises_path


def _paths(n=300, n_t=720, seed=3):
    """Non-proportional paths of 14 unit cases with cycle coefficients (as the check builds)."""
    rng = np.random.default_rng(seed)
    th = np.linspace(0.0, 4 * np.pi, n_t, endpoint=False)
    coeff = np.column_stack(
        [np.full(n_t, 1e4)]
        + [np.maximum(0.0, np.cos(th * k / 2 + k)) * 1e4 for k in range(12)]
        + [1e3 * np.sin(3 * th)]
    )
    unit = rng.normal(size=(14, 6, n)) * 1e3
    hist = np.tensordot(coeff, unit, axes=(1, 0))
    # a third of the nodes proportional: S(t) = S_0 + sin(t) A
    k = n // 3
    hist[:, :, :k] = hist[:1, :, :k] + np.sin(th)[:, None, None] * unit[0, :, :k] * 1e4
    return hist


def test_von_mises_path_hand_values():
    # uniaxial 100 MPa: vM = 100 MPa; pure shear 50 MPa: vM = sqrt(3) 50 = 86.60 MPa;
    # about a centre of uniaxial 40 MPa the uniaxial 100 MPa state is 60 MPa away
    h = np.zeros((2, 6, 2))
    h[0, 0, 0] = 100e6
    h[1, 3, 1] = 50e6
    vm = von_mises_path(h)
    assert vm[0, 0] == 100e6
    assert abs(vm[1, 1] - np.sqrt(3.0) * 50e6) <= 1e-15 * 86.6e6 * 4
    centre = np.zeros((6, 2))
    centre[0, 0] = 40e6
    assert von_mises_path(h, centre)[0, 0] == 60e6


def test_von_mises_path_equals_plain_formula_bitwise():
    h = _paths()
    c = 0.5 * (h.min(axis=0) + h.max(axis=0))
    assert np.array_equal(von_mises_path(h), von_mises(h))
    assert np.array_equal(von_mises_path(h, c), von_mises(h - c[None]))


def test_amplitude_mean_independent_of_the_node_block():
    h = _paths()
    whole = fatigue.amplitude_mean(h, block=10_000)
    for block in (1, 7, 256):
        parts = fatigue.amplitude_mean(h, block=block)
        assert all(np.array_equal(a, b) for a, b in zip(whole, parts))


def test_amplitude_mean_proportional_paths_exact():
    # proportional S_0 + sin(t) A: the amplitude is vM(A) (max sin - min sin)/2 = vM(A)
    # (sin reaches +-1 on the 720-sample grid to 1 - cos(0.5 deg) ~ 4e-5), and the
    # lower bound equals it (the path is a segment through its mid-range)
    h = _paths()
    k = h.shape[-1] // 3
    th = np.linspace(0.0, 4 * np.pi, h.shape[0], endpoint=False)
    A = (h[:, :, :k] - h[:1, :, :k])[np.argmax(np.sin(th))] / np.sin(th).max()
    amp, _, lower = fatigue.amplitude_mean(h[:, :, :k])
    half = 0.5 * (np.sin(th).max() - np.sin(th).min())
    np.testing.assert_allclose(amp, von_mises(A) * half, rtol=1e-12)
    np.testing.assert_allclose(lower, amp, rtol=1e-12)
