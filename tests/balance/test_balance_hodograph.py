"""Hodograph ellipses: seed 000 tilt formula, degenerate cases, co/counter-rotating split."""

import math

import numpy as np
import pytest

from fe_crank.balance.hodograph import hodograph


def trace(h, n=36000):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return h.a * np.cos(t) + h.b * np.sin(t), h.c * np.cos(t) + h.d * np.sin(t)


@pytest.mark.parametrize("abcd", [(0.3, -1.2, 0.7, 0.4), (-0.185, 0.283, 0.178, -0.103), (2.0, 0.1, -0.5, 1.5)])
def test_semi_axes_and_tilt_match_the_traced_curve(abcd):
    h = hodograph(*abcd)
    x, y = trace(h)
    r = np.hypot(x, y)
    assert h.major == pytest.approx(r.max(), rel=1e-5)
    assert h.minor == pytest.approx(r.min(), rel=1e-4, abs=1e-12)
    i = np.argmax(r)
    assert math.tan(h.tilt) == pytest.approx(y[i] / x[i], rel=1e-3)


@pytest.mark.parametrize("abcd", [(0.3, -1.2, 0.7, 0.4), (0.152, 0.866, 1.104, 0.5), (1.0, 0.0, 0.0, 0.2)])
def test_seed000_tilt_formula_names_a_principal_axis(abcd):
    """tan 2 delta = 2B/(C - A) (seed 000 eqs. 112-114) gives the major or the minor axis."""
    a, b, c, d = abcd
    delta = 0.5 * math.atan2(2.0 * (a * c + b * d), (a * a + b * b) - (c * c + d * d))
    h = hodograph(*abcd)
    diff = (h.tilt - delta) % (math.pi / 2)
    assert min(diff, math.pi / 2 - diff) < 1e-9


def test_co_and_counter_rotating_vectors_rebuild_the_resultant():
    h = hodograph(0.3, -1.2, 0.7, 0.4)
    t = np.linspace(0, 2 * np.pi, 50)
    x, y = 0.3 * np.cos(t) - 1.2 * np.sin(t), 0.7 * np.cos(t) + 0.4 * np.sin(t)
    # engine convention: direction psi -> (sin psi, cos psi); co turns with +t, counter with -t
    px = h.co_magnitude * np.sin(h.co_angle + t) + h.counter_magnitude * np.sin(h.counter_angle - t)
    py = h.co_magnitude * np.cos(h.co_angle + t) + h.counter_magnitude * np.cos(h.counter_angle - t)
    assert np.allclose(px, x) and np.allclose(py, y)
    assert h.major == pytest.approx(h.co_magnitude + h.counter_magnitude)
    assert h.minor == pytest.approx(abs(h.co_magnitude - h.counter_magnitude))


def test_degenerate_ellipses_are_reported():
    assert hodograph(0, 0, 0, 0).kind == "zero"
    line = hodograph(1.0, 2.0, 0.5, 1.0)  # y = x/2 at every instant
    assert line.kind == "line" and line.minor == pytest.approx(0, abs=1e-12)
    assert math.degrees(line.tilt) == pytest.approx(math.degrees(math.atan(0.5)))
    circ = hodograph(0.0, 3.0, 3.0, 0.0)  # x = 3 sin t, y = 3 cos t: turns with +t
    assert circ.kind == "circle" and circ.counter_magnitude == pytest.approx(0, abs=1e-12)
    assert circ.co_magnitude == pytest.approx(3.0)
    anti = hodograph(0.0, -3.0, 3.0, 0.0)
    assert anti.kind == "circle" and anti.co_magnitude == pytest.approx(0, abs=1e-12)
    assert hodograph(1.0, 0.2, 0.3, 1.1).kind == "ellipse"


def test_degenerate_kinds_at_force_scale_and_tiny_scale():
    """The kind thresholds are relative (1e-9 of the major semi-axis) at any scale."""
    # a line with a 1e-11 relative minor axis at 5e4 N: Fx = 5e4 cos, Fy = 5e-7 sin -> "line"
    h = hodograph(5e4, 0.0, 0.0, 5e-7)
    assert (
        h.kind == "line" and h.major == pytest.approx(5e4) and h.minor == pytest.approx(5e-7, abs=1e-10)
    )  # round-off of p - q: eps * 5e4 ~ 1e-11
    assert h.tilt == pytest.approx(0.0, abs=1e-12)
    # a circle with a 1e-11 relative eccentricity: Fx = 5e4 sin, Fy = (5e4 + 1e-6) cos -> "circle", tilt 0
    h = hodograph(0.0, 5e4, 5e4 + 1e-6, 0.0)
    assert h.kind == "circle" and h.tilt == 0.0 and h.major == pytest.approx(5e4)
    # a true ellipse at 1e-20 N is still an ellipse (no absolute threshold): semi-axes 1e-20, 0.5e-20
    h = hodograph(1e-20, 0.0, 0.0, 0.5e-20)
    assert h.kind == "ellipse"
    assert (h.major, h.minor) == pytest.approx((1e-20, 0.5e-20), rel=1e-12)
    assert h.tilt == pytest.approx(0.0, abs=1e-12)
    # an exactly zero resultant: kind "zero", tilt 0
    z = hodograph(0.0, 0.0, 0.0, 0.0)
    assert z.kind == "zero" and z.tilt == 0.0 and z.major == 0.0


def test_as_dict_of_an_axis_aligned_ellipse_and_a_45_degree_line():
    """The record written to results.json, by hand:

    * Fx = 3 cos t, Fy = sin t: P = ((0 + 0) + i (3 - 1))/2 = i, Q = ((0 - 0) + i (3 + 1))/2
      = 2i, so |P| = 1, |Q| = 2 (both at 90 deg from +y), semi-axes 1 + 2 = 3 and 2 - 1 = 1,
      major axis along +x (tilt 0);
    * Fx = Fy = cos t: P = Q = (1 + i)/2, |P| = |Q| = sqrt(2)/2 at 45 deg, semi-axes
      sqrt(2) and 0 (a line), tilt 90 - (45 + 45)/2 = 45 deg from +x towards +y.
    """
    d = hodograph(3.0, 0.0, 0.0, 1.0).as_dict()
    assert d["coefficients"] == {"a": 3.0, "b": 0.0, "c": 0.0, "d": 1.0}
    assert d["kind"] == "ellipse"
    assert d["semi_major"] == pytest.approx(3.0, rel=1e-15)
    assert d["semi_minor"] == pytest.approx(1.0, rel=1e-15)
    assert d["tilt_deg"] == pytest.approx(0.0, abs=1e-12)
    assert d["co_rotating"] == pytest.approx({"magnitude": 1.0, "angle_deg": 90.0}, rel=1e-15)
    assert d["counter_rotating"] == pytest.approx({"magnitude": 2.0, "angle_deg": 90.0}, rel=1e-15)
    line = hodograph(1.0, 0.0, 1.0, 0.0).as_dict()
    assert line["kind"] == "line"
    assert line["semi_major"] == pytest.approx(math.sqrt(2.0), rel=1e-15)
    assert line["semi_minor"] == pytest.approx(0.0, abs=1e-15)
    assert line["tilt_deg"] == pytest.approx(45.0, rel=1e-13)
    assert line["co_rotating"] == pytest.approx({"magnitude": math.sqrt(0.5), "angle_deg": 45.0}, rel=1e-14)
    assert line["counter_rotating"] == pytest.approx({"magnitude": math.sqrt(0.5), "angle_deg": 45.0}, rel=1e-14)


@pytest.mark.parametrize("deg", [-89.0, -70.0, -45.0, -10.0, 30.0, 90.0])
def test_tilt_is_reported_in_the_half_open_range_minus_90_to_90(deg):
    """A line oscillation along the direction ``deg`` from +x towards +y,
    ``(Fx, Fy) = (cos deg, sin deg) cos t``, has its major axis at ``deg`` itself; the
    class documents the range (-90, 90] deg, so -70 stays -70 (not 110) and 90 stays 90."""
    u = math.radians(deg)
    h = hodograph(math.cos(u), 0.0, math.sin(u), 0.0)
    assert h.kind == "line"
    assert math.degrees(h.tilt) == pytest.approx(deg, abs=1e-9)
