"""A geared shaft (speed ratio 2) in the balance and dynamics stages, against closed forms.

A shaft turning at n = 2 times the crank speed omega carries inertia forces of
(n omega)^2: centrifugal m_rot R (n omega)^2 at engine order n, and reciprocating
m_j r (n omega)^2 A_k at engine order k n (A_1 = 1, A_2 = lam + lam^3/4 + 15 lam^5/128,
A_4 = -(lam^3/4 + 3 lam^5/16); Taylor vol. 2 ch. 8).  Writing n omega^2 instead halves
every force of this shaft; the 1e-9..3e-4 tolerances below are far tighter than that.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from fe_crank import model
from fe_crank.balance import free_forces
from fe_crank.io.engine import load_engine
from fe_crank.mechanism.dynamics import analyse

OMEGA = 100.0  # rad/s of the crankshaft
M_CRANK, R_CRANK, L_CRANK = 1.0, 0.04, 0.16  # piston kg, crank radius m, rod m (lam = 0.25)
M_AUX, R_AUX, L_AUX = 0.5, 0.02, 0.08  # geared cylinder (lam = 0.25)
M_ROT = 3.0  # kg at R_AUX on the geared shaft's second throw (no cylinder on it)

ENGINE = f"""
name = "crank plus a shaft geared 2:1 (test)"
strokes = 2

[[shafts]]
name = "crank"

[[shafts]]
name = "aux"
centre_x = "0 mm"
centre_y = "-300 mm"
speed_ratio = 2

[[throws]]
name = "1"
shaft = "crank"
crank_radius = "{R_CRANK * 1e3} mm"

[[throws]]
name = "2"
shaft = "aux"
angle = "90 deg"
crank_radius = "{R_AUX * 1e3} mm"
axial_position = "100 mm"

[[throws]]
name = "3"
shaft = "aux"
crank_radius = "{R_AUX * 1e3} mm"
axial_position = "200 mm"
rotating_mass = "{M_ROT} kg"

[[cylinders]]
name = "c"
throw = "1"
bore = "80 mm"
rod_length = "{L_CRANK * 1e3} mm"
rod_mass = "0 kg"
rod_cg_from_big_end = "0 mm"
piston_mass = "{M_CRANK} kg"

[[cylinders]]
name = "g"
throw = "2"
bank_angle = "90 deg"
bore = "40 mm"
rod_length = "{L_AUX * 1e3} mm"
rod_mass = "0 kg"
rod_cg_from_big_end = "0 mm"
piston_mass = "{M_AUX} kg"
"""

LAM = 0.25
A2 = LAM + LAM**3 / 4 + 15 * LAM**5 / 128  # 0.25402..., series error < lam^7 = 6.1e-5 (2.4e-4 rel)
A4 = LAM**3 / 4 + 3 * LAM**5 / 16  # 0.0040894; its omitted lam^7 part is ~9e-6 (0.2 %): rtol 3e-3 at order 4


@pytest.fixture(scope="module")
def geared(tmp_path_factory):
    p = Path(tmp_path_factory.mktemp("geared")) / "geared.toml"
    p.write_text(ENGINE)
    e = load_engine(p)
    assert e.shaft("aux").speed_ratio == 2
    return e


def _row_amplitudes(term):
    """Amplitudes of the x and y rows of an order term (a cos + b sin -> hypot(a, b))."""
    return np.hypot(term.force[:, 0], term.force[:, 1])


def test_geared_shaft_free_forces(geared):
    ff = free_forces(geared, OMEGA)
    # centrifugal of throw 3 at engine order 2: 3 kg * 0.02 m * (2 * 100 rad/s)^2 = 2400 N
    rot = ff.term("rotating", 2)
    assert rot.force_hodograph().kind == "circle"
    assert rot.force_hodograph().major == pytest.approx(M_ROT * R_AUX * (2 * OMEGA) ** 2, rel=1e-9)
    assert ff.term("rotating", 1).force_hodograph().kind == "zero"
    # reciprocating: crank cylinder along y (bank 0), geared cylinder along x (bank 90 deg)
    # order 1: y = 1 kg * 0.04 m * 100^2 = 400 N; x = 0
    np.testing.assert_allclose(_row_amplitudes(ff.term("reciprocating", 1)), [0.0, 400.0], rtol=1e-9, atol=1e-9)
    # order 2: x = geared first harmonic 0.5 * 0.02 * 200^2 = 400 N; y = crank 400 A_2 = 101.6 N
    np.testing.assert_allclose(
        _row_amplitudes(ff.term("reciprocating", 2)),
        [M_AUX * R_AUX * (2 * OMEGA) ** 2, M_CRANK * R_CRANK * OMEGA**2 * A2],
        rtol=3e-4,
    )
    # order 4: x = geared second harmonic 400 A_2; y = crank 400 |A_4| = 1.636 N
    np.testing.assert_allclose(
        _row_amplitudes(ff.term("reciprocating", 4)),
        [M_AUX * R_AUX * (2 * OMEGA) ** 2 * A2, M_CRANK * R_CRANK * OMEGA**2 * A4],
        rtol=3e-3,
    )


def test_geared_shaft_dynamics(geared):
    res = analyse(geared, model.OperatingPoint(speed=OMEGA), step=math.radians(1.0))
    theta = res.theta
    i0 = int(np.argmin(np.abs(theta)))
    assert theta[i0] == pytest.approx(0.0, abs=1e-12)
    # geared cylinder: phi = sense (phase - bank) + 2 theta + throw angle = 2 theta, TDC at theta = 0:
    # inertia -m_j r (2 omega)^2 (1 + lam) = -0.5 * 0.02 * 40000 * 1.25 = -500 N
    g = res.cylinders["g"]
    np.testing.assert_allclose(g.phi, 2 * theta, atol=1e-12)
    assert g.inertia[i0] == pytest.approx(-M_AUX * R_AUX * (2 * OMEGA) ** 2 * (1 + LAM), rel=1e-12)
    # crank cylinder at its TDC: -1 * 0.04 * 100^2 * 1.25 = -500 N as well
    assert res.cylinders["c"].inertia[i0] == pytest.approx(-M_CRANK * R_CRANK * OMEGA**2 * (1 + LAM), rel=1e-12)
    # throw 3 (no cylinder): each bearing carries half its centrifugal force, 1200 N, at every angle
    b = res.throws["3"].bearing_front
    np.testing.assert_allclose(np.hypot(b[:, 0], b[:, 1]), 0.5 * M_ROT * R_AUX * (2 * OMEGA) ** 2, rtol=1e-12)


def test_geared_shaft_torque_is_reduced_to_the_crank_by_its_speed_ratio(geared):
    """Power equivalence: the aux shaft turns at 2 omega, so its torque T_aux counts as
    2 T_aux on the crankshaft (T omega = T_crank omega + T_aux 2 omega)."""
    res = analyse(geared, model.OperatingPoint(speed=OMEGA), step=math.radians(2.0))
    np.testing.assert_allclose(
        res.torque,
        res.shaft_torque["crank"] + 2.0 * res.shaft_torque["aux"],
        rtol=1e-13,
        atol=1e-12 * np.max(np.abs(res.torque)),
    )
    assert np.max(np.abs(res.shaft_torque["aux"])) > 1.0  # N m: the geared shaft does carry torque
