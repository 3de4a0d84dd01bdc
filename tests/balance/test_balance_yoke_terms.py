"""Nordberg yoke terms (fe_crank.balance.nordberg, seed 000 eqs. 162-164) on a shaft with a
phase, an off-centre axis, a throw angle and a cylinder 1 off the +y axis, by hand."""

import math

import numpy as np
import pytest

from fe_crank import model
from fe_crank.balance.nordberg import rocker_counterweight_force, yoke_terms
from fe_crank.errors import InputError


def test_yoke_terms_of_a_phased_off_centre_shaft_by_hand():
    """Shaft sense +1, phase pi/6, axis (0.3, 0.1) m; throw angle pi/3; cylinder 1 at bank
    pi/2 (along +x).  The crankpin is at gamma = pi/6 + theta + pi/3 = pi/2 + theta: at
    theta = 0 it points along +x, up cylinder 1's axis (its TDC, alpha = 0).
    Yoke 100 kg, R_cp = 0.2 m, l_ya = 0.176 m, sin(beta_max) = 0.25 (S/2 = 0.044 m), axis
    along +y, at z = 0.4 m; omega = 10 rad/s:  P_omega = 100 * 0.2 * 100 = 2000 N along
    u(gamma) = (sin, cos);  P' = 100 * 0.044 * 100 = 440 N * sin(alpha) along +y.
    * theta = 0:    F = 2000 (1, 0) + 0 = (2000, 0) N
    * theta = pi/2: F = 2000 (0, -1) + 440 (0, 1) = (0, -1560) N
    Moments about the origin (default reference plane), r = (0.3, 0.1, 0.4) m,
    M = (-rz Fy, rz Fx, rx Fy - ry Fx):
    * theta = 0:    (0, 0.4 * 2000, -0.1 * 2000) = (0, 800, -200) N m
    * theta = pi/2: (-0.4 * -1560, 0, 0.3 * -1560) = (624, 0, -468) N m"""
    rod = model.Rod(0.4, 0.0, 0.1)
    e = model.Engine(
        "phased",
        4,
        (model.Shaft("main", phase=math.pi / 6, centre=(0.3, 0.1)),),
        (model.Throw("1", "main", math.pi / 3, 0.05, 0.0, 0.0),),
        (model.Cylinder("1", "1", 0.1, rod, 1.0, bank_angle=math.pi / 2),),
    )
    yoke = model.Yoke(100.0, 0.2, 0.176, math.asin(0.25), 0.0, 0.4)
    (term,) = yoke_terms(e, yoke, 10.0)
    assert (term.source, term.order) == ("yoke", 1.0)
    f, m = term.evaluate([0.0, math.pi / 2])
    np.testing.assert_allclose(f, [[2000.0, 0.0], [0.0, -1560.0]], rtol=0, atol=1e-9)
    np.testing.assert_allclose(m, [[0.0, 800.0, -200.0], [624.0, 0.0, -468.0]], rtol=0, atol=1e-9)


def test_rocker_arm_refusal_message_in_full():
    with pytest.raises(InputError) as err:
        rocker_counterweight_force(1000.0, 0.0, 0.2)
    assert err.value.key == "yoke"
    assert "rocker arms must be positive" == str(err.value).split(": ", 1)[-1]
