"""Equivalent amplitude and mean of a multiaxial stress history (fatigue.amplitude_mean,
signed_mean) against closed forms.  Measure: radius of the minimum circumscribed ball
(MCB) of the path in the von Mises norm (Dang Van 1989; Papadopoulos et al., Int. J.
Fatigue 19(3) 1997), centre = mean tensor.

Closed forms (von Mises of a tensor difference, s_ij components):
* uniaxial reversed s_xx = s cos wt: amplitude s, mean 0;
* reversed shear s_xx = +t cos wt, s_yy = -t cos wt: vM(t, -t, 0) = sqrt(((2t)^2 + t^2 + t^2)/2)
  = sqrt(3) t.  (Half-ranges component by component, then vM, give the same here, but
  |s_xx|, |s_yy| half-ranges with the sign dropped -- vM(t, t, 0) = t -- is 42 % low.)
* rotating s_xx = s cos wt, s_yy = s sin wt: a circle of radius s about 0 in the (s_xx, s_yy)
  plane; vM(s cos a, s sin a, 0)^2 = s^2 (1 - sin a cos a), largest 1.5 s^2 at a = 135 deg,
  so the MCB (centre 0 by symmetry) has radius sqrt(3/2) s = 1.2247 s.

On the paths of a whole cycle (``cycle_paths``: 14 unit cases combined as the check
combines them, a third of the nodes proportional): the amplitude of a proportional path
S_0 + sin(t) A is vM(A) times the half range of sin, and taking the nodes in blocks of any
size gives the same bits.
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers.cycles import cycle_paths

from fe_crank.assess.fatigue import amplitude_mean, goodman_safety, signed_mean
from fe_crank.assess.stress import von_mises

W = np.linspace(0, 2 * np.pi, 720, endpoint=False)


def _hist(**comp):
    """(n_t, 6, 1) history from component arrays xx, yy, zz, xy, yz, xz."""
    h = np.zeros((W.size, 6, 1))
    for i, k in enumerate(("xx", "yy", "zz", "xy", "yz", "xz")):
        if k in comp:
            h[:, i, 0] = comp[k]
    return h


def test_uniaxial_reversed_gives_sigma():
    a, m, low = amplitude_mean(_hist(xx=200e6 * np.cos(W)))
    assert a[0] == pytest.approx(200e6, rel=1e-12)
    assert np.abs(m).max() < 1e-6
    assert low[0] == pytest.approx(200e6, rel=1e-12)


def test_reversed_shear_gives_sqrt3_tau():
    t = 100e6
    a, m, _ = amplitude_mean(_hist(xx=t * np.cos(W), yy=-t * np.cos(W)))
    assert a[0] == pytest.approx(np.sqrt(3) * t, rel=1e-12)  # 173.2 MPa; sign-dropping gives 100 MPa
    a2, _, _ = amplitude_mean(_hist(xy=t * np.cos(W)))  # the same state in the rotated frame
    assert a2[0] == pytest.approx(np.sqrt(3) * t, rel=1e-12)


def test_proportional_with_mean_exact_and_mean_tensor():
    """S(t) = S0 + cos(wt) A: amplitude vM(A), mean S0 (component signs mixed)."""
    s0 = np.array([50e6, -20e6, 10e6, 30e6, 0.0, -5e6])
    amp = np.array([80e6, -60e6, 5e6, -40e6, 10e6, 20e6])
    h = (s0[None, :] + np.cos(W)[:, None] * amp[None, :])[:, :, None]
    a, m, _ = amplitude_mean(h)
    assert a[0] == pytest.approx(von_mises(amp[:, None])[0], rel=1e-12)
    np.testing.assert_allclose(m[:, 0], s0, atol=1e-6 * 80e6)


def test_rotating_stress_state_closed_form():
    s = 100e6
    a, m, low = amplitude_mean(_hist(xx=s * np.cos(W), yy=s * np.sin(W)))
    # 720 samples: the largest sampled vM is within cos^2 of half a step of the circle's
    assert a[0] == pytest.approx(np.sqrt(1.5) * s, rel=1e-5)
    assert np.abs(m).max() < 1e-3 * s
    assert low[0] <= a[0]


def test_non_proportional_bounds_against_brute_force():
    """Random two-harmonic paths: the returned radius lies between half the longest chord
    (brute force over all pairs: a lower bound of the MCB radius) and 1.05 times it (the
    MCB radius of a point set is at most sqrt(n/(2(n+1))) * diameter (Jung), i.e.
    <= 1.10 x half the diameter in 5-D; the iterations must get well inside that)."""
    rng = np.random.default_rng(3)
    w = W[::4]
    n = 40
    c1, c2, c3 = (rng.normal(size=(6, n)) * 1e8 for _ in range(3))
    h = c1[None] + np.cos(w)[:, None, None] * c2[None] + np.sin(2 * w + 0.3)[:, None, None] * c3[None]
    a, _, low = amplitude_mean(h)
    d = von_mises(h[:, None] - h[None, :]).max(axis=(0, 1)) / 2
    assert np.all(a >= d * (1 - 1e-12))
    assert np.all(low <= d * (1 + 1e-12))
    assert np.all(a <= 1.05 * d)


def test_tensile_mean_lowers_goodman_safety_compressive_gives_no_credit():
    """Uniaxial s = m + a cos wt, a = 100 MPa, sigma_e = 200 MPa, R_m = 800 MPa (Shigley 6-46):
    m = +200 MPa: 1/n = 100/200 + 200/800 = 0.75, n = 1.333;  m = -200 MPa: n = 200/100 = 2
    (no credit for the compressive mean);  m = 0: n = 2."""
    out = {}
    for m in (200e6, -200e6, 0.0):
        amp, mean, _ = amplitude_mean(_hist(xx=m + 100e6 * np.cos(W)))
        out[m] = float(goodman_safety(amp, signed_mean(mean), 200e6, 800e6)[0])
    assert out[200e6] == pytest.approx(1 / 0.75, rel=1e-9)
    assert out[-200e6] == pytest.approx(2.0, rel=1e-9)
    assert out[0.0] == pytest.approx(2.0, rel=1e-9)


def test_signed_mean_rules():
    """Signed equivalent mean: uniaxial tension +s; pure shear tau: +sqrt(3) tau (Shigley
    6-67 counts a shear mean); hydrostatic tension p: +p (vM is 0, s_1 = p); uniaxial
    compression -s; a mean with a tensile principal stress and a larger compressive one
    (s_xx = +50, s_yy = -150 MPa, trace < 0) still counts as tensile: +vM = 180.3 MPa."""
    cols = np.array(
        [
            [100e6, 0, 0, 0, 0, 0],
            [0, 0, 0, 50e6, 0, 0],
            [30e6, 30e6, 30e6, 0, 0, 0],
            [-100e6, 0, 0, 0, 0, 0],
            [50e6, -150e6, 0, 0, 0, 0],
        ]
    ).T
    got = signed_mean(cols)
    vm5 = np.sqrt(((200e6) ** 2 + 150e6**2 + 50e6**2) / 2)  # 180.3 MPa
    np.testing.assert_allclose(got, [100e6, np.sqrt(3) * 50e6, 30e6, -100e6, vm5], rtol=1e-12)


def test_amplitude_mean_independent_of_the_node_block():
    h = cycle_paths()
    whole = amplitude_mean(h, block=10_000)
    for block in (1, 7, 256):
        parts = amplitude_mean(h, block=block)
        assert all(np.array_equal(a, b) for a, b in zip(whole, parts))


def test_amplitude_mean_proportional_paths_exact():
    # proportional S_0 + sin(t) A: the amplitude is vM(A) (max sin - min sin)/2 = vM(A)
    # (sin reaches +-1 on the 720-sample grid to 1 - cos(0.5 deg) ~ 4e-5), and the
    # lower bound equals it (the path is a segment through its mid-range)
    h = cycle_paths()
    k = h.shape[-1] // 3
    th = np.linspace(0.0, 4 * np.pi, h.shape[0], endpoint=False)
    A = (h[:, :, :k] - h[:1, :, :k])[np.argmax(np.sin(th))] / np.sin(th).max()
    amp, _, lower = amplitude_mean(h[:, :, :k])
    half = 0.5 * (np.sin(th).max() - np.sin(th).min())
    np.testing.assert_allclose(amp, von_mises(A) * half, rtol=1e-12)
    np.testing.assert_allclose(lower, amp, rtol=1e-12)
