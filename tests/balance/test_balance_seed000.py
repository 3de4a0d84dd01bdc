"""Seed 000 (Liventsev): Napier Deltic section, its four-shaft derivative, Nordberg radial."""

import math

import numpy as np
import pytest
from helpers.balance import engine

from fe_crank.balance import (
    BalanceStrategy,
    free_forces,
    hodograph,
    radial_counterweight_mass,
    rocker_counterweight_force,
    size_counterweights,
    yoke_inertia,
)
from fe_crank.balance.mechanism import reciprocating_mass, rotating_mass
from fe_crank.mechanism.kinematics import harmonic_coefficients

W = 150.0


def normalised(e, ff, source, k):
    c = e.cylinders[0]
    r = e.throw(c.throw).crank_radius
    if source == "rotating":
        unit = rotating_mass(e, c.throw) * r * W**2
    else:
        unit = reciprocating_mass(c) * r * W**2 * harmonic_coefficients(r / c.rod.length)[k]
    return ff.term(source, k).force / unit


@pytest.fixture(scope="module")
def deltic():
    e = engine("napier_deltic_section.toml")
    return e, free_forces(e, W)


@pytest.mark.parametrize(
    "source, k, seed",
    [
        ("reciprocating", 1, (-0.185, 0.283, 0.178, -0.103)),  # eqs. 152-153
        ("reciprocating", 2, (0.454, 0.946, 0.381, -0.660)),  # eqs. 156-157
        # eqs. 154-155; the OCR shows a stray minus before P_omega in eq. 155 that its own bracket
        # [sin(100+a) + sin(80+a) - cos(30+a)] = 1.104 cos a + 0.5 sin a does not carry
        ("rotating", 1, (0.152, 0.866, 1.104, 0.5)),
    ],
)
def test_deltic_section_coefficients_eqs_152_to_157(deltic, source, k, seed):
    e, ff = deltic
    got = normalised(e, ff, source, k)
    assert np.allclose(got.ravel(), seed, atol=1e-3)


@pytest.mark.parametrize("source, k", [("reciprocating", 1), ("reciprocating", 2), ("rotating", 1)])
def test_deltic_section_ellipse_tilts_30_deg_and_turning_against_shaft_c(deltic, source, k):
    e, ff = deltic
    h = ff.term(source, k).force_hodograph()
    assert h.kind == "ellipse"
    # the seed gives the angle between the ellipse's axes and the coordinate axes: 30 deg
    tilt = abs(math.degrees(h.tilt)) % 90.0
    assert min(tilt, 90.0 - tilt) == pytest.approx(30.0, abs=0.01)
    # seed: the resultant turns at the speed of shaft c but opposite to it (c has sense -1 here)
    assert e.shaft("c").sense == -1 and h.co_magnitude > h.counter_magnitude


def test_deltic_centrifugal_exceeds_first_and_second_order_several_times(deltic):
    """Seed: the centrifugal resultant is 8-10 times the first two (with its masses); here
    with plausible masses it is still the largest by far."""
    _, ff = deltic
    rot = ff.term("rotating", 1).force_hodograph().major
    assert rot > 5 * ff.term("reciprocating", 1).force_hodograph().major


@pytest.fixture(scope="module")
def four_shaft():
    e = engine("deltic_four_shaft.toml")
    return e, free_forces(e, W)


@pytest.mark.parametrize(
    "k, seed, tilt_deg, printed_tol",
    # eqs. (a)-(d); delta_1 = 3 deg 15 min, delta_II = 42 deg 30 min (the seed rounds to half degrees)
    [(1, (-0.061, 0.351, -0.003, 0.020), 3.25, 1 / 60), (2, (-0.452, 1.24, -0.413, 1.135), 42.5, 0.05)],
)
def test_four_shaft_coefficients_lines_and_tilts(four_shaft, k, seed, tilt_deg, printed_tol):
    e, ff = four_shaft
    got = normalised(e, ff, "reciprocating", k)
    assert np.allclose(got.ravel(), seed, atol=1e-3)
    h = ff.term("reciprocating", k).force_hodograph()
    assert h.kind == "line"  # 'in this particular case straight lines' (seed)
    # the seed's printed coefficients give its tilt (seed: tan 2 delta = 2B/(C - A)) ...
    assert math.degrees(hodograph(*seed).tilt) == pytest.approx(tilt_deg, abs=printed_tol)
    # ... and the unrounded coefficients agree within the rounding of the printed ones
    assert math.degrees(h.tilt) == pytest.approx(tilt_deg, abs=0.15)


def test_four_shaft_first_order_tilt_worked_example():
    """Seed: B = 0.0072, C = 0.1269, A = 0.0004, tan 2 delta_1 = 0.114, delta_1 = 3 deg 15 min.

    The hodograph of the seed's printed coefficients (a, b, c, d) = (-0.061, 0.351, -0.003, 0.020)
    must have its major axis at the seed's delta_1 (the package finds the axis from the co- and
    counter-rotating parts, not from tan 2 delta).  Hand check of the seed's route:
    B = ac + bd = 0.000183 + 0.00702 = 0.0072, C = a^2 + b^2 = 0.003721 + 0.123201 = 0.1269,
    A = c^2 + d^2 = 0.000009 + 0.0004 = 0.0004, 2B/(C - A) = 0.014406/0.126513 = 0.1139,
    delta = atan(0.1139)/2 = 3.249 deg.  Tolerance: the seed prints delta to the minute."""
    h = hodograph(-0.061, 0.351, -0.003, 0.020)
    assert h.kind == "ellipse"
    assert math.degrees(h.tilt) == pytest.approx(3.25, abs=1 / 60)
    # the semi-axes squared are the eigenvalues of [[C, B], [B, A]] (seed eqs. 112-114)
    lam = np.linalg.eigvalsh([[0.126922, 0.007203], [0.007203, 0.000409]])
    assert (h.minor**2, h.major**2) == pytest.approx(tuple(lam), rel=1e-3)


def test_nordberg_yoke_example_16():
    """l_ya = 0.176 m, beta_max = 14 deg 44 min, m = 100 kg, omega^2 = 1740 -> 45 mm, 7.83 kN, 35.4 kN.

    Hand calculation (eqs. 162-164): S/2 = l_ya sin beta_max = 0.176 * 0.254321 = 0.0447604 m
    (the seed rounds it to 45 mm); P'_ya = m S/2 omega^2 = 100 * 0.0447604 * 1740 = 7788.3 N
    (the seed's 7.83 kN is 100 * 0.045 * 1740 with the rounded 45 mm)."""
    e = engine("nordberg_radial.toml")
    y = yoke_inertia(e.yoke, math.sqrt(1740.0))
    # rel 1e-5: the hand values carry 6 digits; a wrong trig function (tan: +3.4 %) or a
    # missing factor is far outside
    assert y.half_stroke == pytest.approx(0.0447604, rel=1e-5)
    assert y.half_stroke == pytest.approx(0.045, abs=5e-4)  # the seed's rounded figure
    assert y.oscillating_amplitude == pytest.approx(7788.3, rel=1e-5)
    assert y.oscillating_amplitude == pytest.approx(7830.0, rel=0.01)  # seed, from the rounded 45 mm
    assert y.centrifugal == pytest.approx(35.4e3, rel=2e-3)


def test_nordberg_free_forces_include_the_yoke():
    e = engine("nordberg_radial.toml")
    w = math.sqrt(1740.0)
    ff = free_forces(e, w)
    y = yoke_inertia(e.yoke, w)
    h = ff.term("yoke", 1).force_hodograph()
    assert h.major == pytest.approx(y.centrifugal + y.oscillating_amplitude, rel=1e-12)
    # a circle plus an in-phase line: co-rotating R + A/2, counter-rotating A/2 -> semi-axes R + A and R
    assert h.minor == pytest.approx(y.centrifugal, rel=1e-12)
    # P'_ya is zero at alpha = 0 and 180 deg (seed, scheme a of fig. 50): then only the centrifugal part acts
    f, _ = ff.evaluate([0.0, math.pi], sources=("yoke",))
    assert np.allclose(np.hypot(f[:, 0], f[:, 1]), y.centrifugal)
    for k in (2, 4, 6):
        assert ff.total(k).force_hodograph().kind == "zero"


def test_nordberg_counterweight_mass_eq_161():
    """m_pr = P / (r_pr omega^2), P = P_omega + (i/2) P_I (eqs. 158-161), equal to per-throw f = 1/2."""
    e = engine("nordberg_radial.toml")
    w, r_pr = math.sqrt(1740.0), 0.25
    c = e.cylinders[0]
    r = e.throws[0].crank_radius
    p = rotating_mass(e, "pin") * r * w**2 + len(e.cylinders) / 2 * reciprocating_mass(c) * r * w**2
    m_pr = radial_counterweight_mass(e, "pin", w, r_pr)
    assert m_pr == pytest.approx(p / (r_pr * w**2), rel=1e-12)
    design = size_counterweights(e, BalanceStrategy(1.0, 0.5), w)
    assert design.counterweights[0].mass_at(r_pr) == pytest.approx(m_pr, rel=1e-12)
    residual = design.residual.total(1, ("rotating", "reciprocating", "counterweights"))
    assert residual.force_hodograph().kind == "zero"


def test_rocker_counterweight_lever_rule_eq_166():
    p = rocker_counterweight_force(35.4e3, 0.176, 0.25)
    assert p * 0.25 == pytest.approx(35.4e3 * 0.176)
