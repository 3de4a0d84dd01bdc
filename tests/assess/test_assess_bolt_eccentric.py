"""VDI 2230 Part 1 (2015) with eccentric clamping and loading, against the standard's own
formulas worked by hand, and the joints' loads from the geometry and the pin force.

The joint is the M12 10.9 example of ``test_assess_cw_joint`` (its docstring has the centric
numbers: delta_S = 2.72868e-6, delta_P = 4.05424e-7 mm/N, Phi_K = 0.129359, F_M,zul =
64902.3 N, F_M,min = 40563.9 N, F_Z = 3190.70 N, F_A 11607.8 .. 12081.6 N over the cycle,
17054.7 N at the overspeed, F_Q = 120 N), n not stated (bolt n = 1, clamp n = 0).  In N, mm:

Centric (s_sym = a = 0, no moment) on an interface c_T x b_T = 24 x 30: Phi_en* = Phi_K,
F_Kab = 0, no bending: today's numbers, S_F = 1.1327, S_D = 5.2705, S_sep = 2.1914,
S_G = 16.932.

Eccentric: s_sym = 3, a = 8 on the same interface, M_B from -20 to 30 N m over the cycle and
|M_B| = 40 N m at the overspeed.
  I_Bers = I_BT = 30 x 24^3/12 - pi 13^4/64 = 34560 - 1401.985 = 33158.015 mm^4,
  A_D = 720 - pi 13^2/4 = 587.2677 mm^2, l_K/(E_P I_Bers) = 30/(210000 x 33158.015) = 4.30836e-9
  delta_P* = 4.05424e-7 + 3^2 x 4.30836e-9 = 4.44199e-7
  delta_P** = 4.05424e-7 + 8 x 3 x 4.30836e-9 = 5.08825e-7
  Phi_en* = 5.08825e-7 / (2.72868e-6 + 4.44199e-7) = 0.160367 (R3)
  Phi_m* = 3 x 4.30836e-9 / 3.17288e-6 = 4.07363e-3 /mm
  l_ers = 30 (d_S/d_3)^4 = 30 (10.35816/9.85298)^4 = 36.6422 mm
  R9: sigma_SAb = [1 + (1/Phi_en* - s_sym/a)(l_K/l_ers)(E_S/E_P) pi a d_S^3/(8 I_Bers)] Phi_en* F_A/A_S
      = 2.841718e-3 N/mm^2 per N of F_A (M_B = 0); per N mm of M_B, with the joint's rotation
      (F_A a + M_B - F_SA s_sym) l_K/(E_P I_Bers): (Phi_m* + c (1 - Phi_m* s_sym) A_S)/A_S,
      c = (l_K/l_ers)(E_S/E_P) d_S/(2 I_Bers) = 1.248356e-4: 4.834216e-5 + 1.233100e-4.
      The loads' ranges, a start and stop included: dF_A = 12081.6, dM_B = 50000:
      sigma_a = (2.841718e-3 x 12081.6 + 1.716521e-4 x 50000)/2 = 21.4576 MPa, of it bending
      (9.386260e-4 x 12081.6 + 1.233100e-4 x 50000)/2 = 8.75280; S_D = 48.875/21.4576 = 2.27775
  R2/R5: u = 12, I_BT/A_D = 56.4617; at the overspeed with +40 N m
      F_Kab = (17054.7 (8 - 3) 12 + 40000 x 12)/(56.4617 + 3 x 12) = 16258.46 N,
      S_sep = (40563.94 - 3190.70)/(17054.7 + 16258.46) = 1.121876
  R8: sigma_z = 64902.3/84.2665 + 2.841718e-3 x 17054.7 + 1.716521e-4 x 40000 = 825.533,
      tau = 269.434, S_F = 940/sqrt(825.533^2 + 3 (0.5 x 269.434)^2) = 1.095729
  R12: F_KR,min = 40563.94 - 3190.70 - 17054.7 = 20318.53, S_G = 16.9321 (unchanged: n = 0)

Slip with distinct coefficients mu_G = 0.12, mu_K = 0.14, mu_T = 0.07 (centric): R7
  1.5 (d_2/d_S)(P/(pi d_2) + 1.155 x 0.12) = 0.298707, F_M,zul = 84.2665 x 0.9 x 940 /
  sqrt(1 + 3 x 0.298707^2) = 63317.10, F_M,min = 39573.19, F_KR = 39573.19 - 3190.70 - 17054.7
  = 19327.79, S_G = 19327.79 x 0.07/120 = 11.2745 (R12: the interface's mu_T, not mu_G);
  R13: M_A = 63317.10 (0.16 x 1.75 + 0.58 x 10.86334 x 0.12 + 15/2 x 0.14) = 132.085 N m.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from helpers.joints import JOINT
from helpers.joints import joint_loads as _loads

from fe_crank.assess.counterweight import BoltedCounterweight, CounterweightData, JointGeometry
from fe_crank.assess.cw_joint import check_joint
from fe_crank.assess.joint_criteria import (
    DEFAULT_LIMITS,
    DEFAULT_WORDS,
    JOINT_QUANTITIES,
    joint_qualifiers,
    with_default_limits,
)
from fe_crank.assess.joint_loads import joint_loads, web_moments
from fe_crank.assess.throw_geometry import ThrowGeometry
from fe_crank.io.criteria import build_criteria
from fe_crank.rules import vdi2230


def _ecc(s=0.0, a=0.0):
    return vdi2230.Eccentric(width=0.024, length=0.030, s_sym=s, a=a)


def test_a_centric_joint_on_an_interface_gives_the_centric_numbers():
    loads = dataclasses.replace(_loads(), eccentric=_ecc())
    c = check_joint("cw", JOINT, loads, 210e9)
    assert c.eccentric_load_factor == pytest.approx(0.129359, rel=2e-5)
    assert c.opening_limit == 0.0 and c.bending_amplitude == 0.0 and c.moment_load_factor == 0.0
    assert c.working_safety == pytest.approx(1.1327, rel=2e-4)
    assert c.fatigue_safety == pytest.approx(5.2705, rel=2e-4)
    assert c.separation_safety == pytest.approx(2.1914, rel=2e-4)
    assert c.slip_safety == pytest.approx(16.932, rel=2e-4)


def test_eccentric_joint_by_vdi_2230_by_hand():
    loads = dataclasses.replace(
        _loads(), eccentric=_ecc(0.003, 0.008), moment_min=-20.0, moment_max=30.0, moment_overspeed=40.0
    )
    i_bt, a_d = vdi2230.interface_section(loads.eccentric, 0.013)
    assert i_bt == pytest.approx(33158.015e-12, rel=1e-7) and a_d == pytest.approx(587.2677e-6, rel=1e-7)
    c = check_joint("cw", JOINT, loads, 210e9)
    assert c.eccentric_load_factor == pytest.approx(0.160367, rel=2e-5)
    assert c.moment_load_factor == pytest.approx(4.07363, rel=2e-5)  # 1/m
    assert vdi2230.bending_length(0.012, 0.00175, 0.030) == pytest.approx(36.6422e-3, rel=1e-5)
    assert c.fatigue_amplitude == pytest.approx(21.4576e6, rel=2e-5)
    assert c.bending_amplitude == pytest.approx(8.75280e6, rel=2e-5)
    assert c.fatigue_safety == pytest.approx(2.27775, rel=2e-5)
    assert c.opening_limit == pytest.approx(16258.46, rel=2e-5)
    assert c.separation_safety == pytest.approx(1.121876, rel=2e-5)
    assert c.working_safety == pytest.approx(1.095729, rel=2e-5)
    assert c.residual_clamp == pytest.approx(20318.53, rel=2e-5)
    assert c.slip_safety == pytest.approx(16.9321, rel=2e-5)


def test_bolt_bending_stress_is_vdi_2230s_printed_formula():
    """For M_B = 0 the general form (the clamped parts' rotation) is VDI 2230's R9 formula."""
    ecc = _ecc(0.003, 0.008)
    t = vdi2230.thread(0.012, 0.00175)
    ds, dp = 2.728680e-9, 4.054239e-10  # m/N
    i_b = vdi2230.interface_section(ecc, 0.013)[0]
    phi_en, phi_m = vdi2230.eccentric_load_factors(ds, dp, ecc, 0.030, 210e9, i_b, 1.0)
    l_ers = vdi2230.bending_length(0.012, 0.00175, 0.030)
    k_f, _, b_f, _ = vdi2230.bending_stress_coefficients(
        ecc, phi_en, phi_m, 0.012, 0.00175, 0.030, l_ers, 205e9, 210e9, i_b
    )
    a, s, d_s = 0.008, 0.003, t["ds"]
    printed = (1 + (1 / phi_en - s / a) * (0.030 / l_ers) * (205 / 210) * math.pi * a * d_s**3 / (8 * i_b)) * phi_en
    assert (k_f + b_f) * t["As"] == pytest.approx(printed, rel=1e-12)


def test_the_opening_limit_takes_the_edge_that_opens():
    """F_Kab of both edges: a moment of either sign opens the one edge or the other."""
    ecc = _ecc()
    i_bt, a_d = vdi2230.interface_section(ecc, 0.013)
    up = vdi2230.opening_limit_both_edges(0.0, 30.0, ecc, i_bt, a_d)
    down = vdi2230.opening_limit_both_edges(0.0, -30.0, ecc, i_bt, a_d)
    assert up == pytest.approx(down) == pytest.approx(30.0 * 0.012 * a_d / i_bt, rel=1e-12)


def test_slip_with_distinct_thread_head_and_interface_friction_by_hand():
    joint = dataclasses.replace(JOINT, thread_friction=0.12, head_friction=0.14, interface_friction=0.07)
    c = check_joint("cw", joint, _loads(), 210e9)
    assert c.preload_max == pytest.approx(63317.10, rel=2e-6)
    assert c.residual_clamp == pytest.approx(19327.79, rel=2e-6)
    assert c.slip_safety == pytest.approx(11.2745, rel=2e-5)
    assert c.tightening_torque == pytest.approx(132.085, rel=2e-5)
    assert c.friction == (0.12, 0.14, 0.07)
    # each coefficient where it belongs: the interface's alone moves the slip safety
    assert check_joint("cw", dataclasses.replace(joint, interface_friction=0.14), _loads(), 210e9).slip_safety == (
        pytest.approx(2 * c.slip_safety, rel=1e-12)
    )


GEO = JointGeometry(
    seat_radius=0.042,
    web_thickness=0.017,
    thickness=0.017,
    inner_radius=0.035,
    outer_radius=0.080,
    angle=math.radians(140.0),
    bearing_lever=0.011 + 0.0085,
    bearing_span=0.024 + 2 * (0.017 + 0.011),
    web=1,
)


def test_web_moment_is_the_bearing_reaction_times_the_lever():
    """A pin force of (F_x, F_y) at mid-pin: each bearing takes half, M_w = F/2 (L_j + t/2);
    a rod 6 mm to the rear loads the front bearing by (L/2 - 6)/L, L = 80 mm."""
    f = np.array([[1000.0, -4000.0], [-500.0, 6000.0]])
    w = web_moments(GEO, f)
    assert w.about_x == pytest.approx([-4000.0 * 0.5 * 0.0195, 6000.0 * 0.5 * 0.0195], rel=1e-12)
    assert w.largest == pytest.approx(math.hypot(500.0, 6000.0) * 0.5 * 0.0195, rel=1e-12)
    w_rod = web_moments(GEO, f, ((f, 0.006),), [(2 * f, None)])
    assert w_rod.about_x == pytest.approx([-4000.0 * 0.034 / 0.080 * 0.0195, 6000.0 * 0.034 / 0.080 * 0.0195])
    assert w_rod.overspeed == pytest.approx(2 * w.largest, rel=1e-12)
    rear = web_moments(dataclasses.replace(GEO, web=2), f, ((f, 0.006),))
    assert rear.about_x[1] == pytest.approx(6000.0 * 0.046 / 0.080 * 0.0195)


def test_radial_joint_loads_from_the_geometry_by_hand():
    """Two radial M10 bolts at r_b = 58 mm over a 140 deg counterweight: x = +-58 sin 35 deg =
    +-33.267 mm; m = 0.5 kg at r_c = 55 mm, 6000 rpm, delta 0.01, |alpha| 2000 rad/s^2:
    F_c,hi = 0.0275 (628.3185 x 1.005)^2 = 10963.9, F_c,lo = 10747.8 N; F_t = 55 N with the
    lever 55 - 42 = 13 mm pries +-55 x 13 x 33.267/(2 x 33.267^2) = +-10.746 N per bolt; the web
    moment +-M/2 per bolt; the interface 17 mm (web and counterweight as thick), a = s_sym = 0."""
    joint = dataclasses.replace(JOINT, count=2, diameter=0.010, pitch_radius=0.058, clamped_diameter=0.022)
    b = BoltedCounterweight("counterweight_1", joint, 0.5, 0.055, GEO)
    w = web_moments(GEO, np.array([[0.0, -4000.0], [0.0, 6000.0]]))
    w = dataclasses.replace(w, overspeed=80.0)
    om = 6000 * math.pi / 30
    ld = joint_loads(
        b, omega=om, overspeed=7200 * math.pi / 30, speed_fluctuation=0.01, angular_acceleration=2000.0, web=w
    )
    x = 0.058 * math.sin(math.radians(35.0))
    pry = 55.0 * 0.013 * x / (2 * x * x)
    assert pry == pytest.approx(10.746, rel=1e-4)
    assert ld.axial_max == pytest.approx(0.0275 * (om * 1.005) ** 2 / 2 + pry, rel=1e-12)
    assert ld.axial_min == pytest.approx(0.0275 * (om * 0.995) ** 2 / 2 - pry, rel=1e-12)
    assert ld.transverse_max == pytest.approx(55.0 / 2, rel=1e-12)
    assert (ld.moment_min, ld.moment_max, ld.moment_overspeed) == pytest.approx((-39.0 / 2, 58.5 / 2, 40.0))
    assert ld.eccentric == vdi2230.Eccentric(0.017, 0.022, 0.0, 0.0)
    thick = joint_loads(
        dataclasses.replace(b, geometry=dataclasses.replace(GEO, thickness=0.021)), omega=om, overspeed=None
    )
    assert thick.eccentric.a == pytest.approx(0.002) and thick.eccentric.width == pytest.approx(0.017)


def test_axial_joint_pries_open_at_its_inner_edge():
    """Axial bolts: F_A = 0, the centrifugal force at mid-thickness b/2 pries: M_B = F_c b/(2 n);
    s_sym = (80 + 35)/2 - 58 = -0.5 mm (towards the axis positive)."""
    joint = dataclasses.replace(JOINT, count=2, pitch_radius=0.058, direction="axial")
    b = BoltedCounterweight("counterweight_1", joint, 0.5, 0.055, GEO)
    om = 3000 * math.pi / 30
    ld = joint_loads(b, omega=om, overspeed=None)
    fc = 0.0275 * om**2
    assert ld.axial_max == 0.0 and ld.moment_max == pytest.approx(fc * 0.0085 / 2, rel=1e-12)
    assert ld.eccentric.s_sym == pytest.approx(-0.0005) and ld.eccentric.width == pytest.approx(0.045)
    c = check_joint("cw", joint, ld, 210e9)
    assert c.opening_limit > 0 and c.bending_amplitude > 0


def test_default_limits_and_the_verdict_lines_words():
    cws = (
        CounterweightData(
            "counterweight_1", 0.5, 0.055, joints=(BoltedCounterweight("counterweight_1", JOINT, 0.5, 0.055),)
        ),
    )
    tg = {"1": ThrowGeometry(0.024, (-0.0205, 0.0205), None, None, cws)}
    crit = build_criteria({"min_static_safety": 2.0}, "c.toml")
    got, added = with_default_limits(crit)
    assert set(added) == set(JOINT_QUANTITIES)
    assert {lim.quantity: lim.value for lim in got.limits if lim.quantity in added} == DEFAULT_LIMITS
    assert {lim.key for lim in got.limits} >= {
        "criteria.min_bolt_slip_safety",
        "criteria.max_bolt_assembly_utilisation",
    }
    stated = build_criteria({"min_bolt_slip_safety": 1.2}, "c.toml")
    assert with_default_limits(stated) == (stated, ())
    words = joint_qualifiers(tg, added)
    assert words["bolt_slip_safety"] == f"friction mu_G 0.10, mu_K 0.10, mu_T 0.10; {DEFAULT_WORDS}"
    assert joint_qualifiers(tg)["bolt_fatigue_safety"] == "friction mu_G 0.10, mu_K 0.10, mu_T 0.10"


def test_the_fe_section_fit_recovers_a_linear_stress_field():
    """sigma_yy = 5 MPa + 2 MPa/mm zeta + 0.1 MPa/mm x on a grid of counterweight nodes about
    the joint plane y = -42 mm (the front web's interface z from -29 to -12 mm, zeta positive
    towards the throw's middle, +z): each bolt's prism (22 x 17 mm) carries M_B = 2e9 Pa/m x
    22 x 17^3/12 mm^4 = 18.0143 N m and F = (5 MPa + 0.1 MPa/mm x_i) 22 x 17 mm^2, x_i =
    +-58 sin 35 deg; the unit case coefficient scales both, the centrifugal case is left out."""
    from fe_crank.assess.joint_loads import fe_section_loads
    from fe_crank.assess.superpose import UnitStresses

    joint = dataclasses.replace(JOINT, count=2, diameter=0.010, pitch_radius=0.058, clamped_diameter=0.022)
    zz, xx, yy = np.meshgrid(np.linspace(-0.029, -0.012, 7), np.linspace(-0.05, 0.05, 9), [-0.043, -0.042, -0.041])
    pts = np.vstack([xx.ravel(), yy.ravel(), zz.ravel()])
    zeta = pts[2] - (-0.029 + 0.0085)
    syy = 5e6 + 2e9 * zeta + 1e8 * pts[0]
    stress = np.zeros((2, 6, pts.shape[1]))
    stress[0, 1] = syy  # pin case
    stress[1, 1] = 7e7  # centrifugal: the counterweight's own inertia, not the web's deformation
    unit = UnitStresses(stress, pts, {"counterweight_1": np.arange(pts.shape[1])}, cases=("pin_0", "centrifugal"))
    coeffs = np.array([[1.0, 1.0], [-0.5, 1.0]])
    got = fe_section_loads(unit, "counterweight_1", GEO, joint, coeffs, np.array([[2.0, 1.0]]))
    m = 2e9 * 0.022 * 0.017**3 / 12
    assert m == pytest.approx(18.0143, rel=1e-5)
    assert got.moment == pytest.approx([m, -0.5 * m], rel=1e-9)
    x = 0.058 * math.sin(math.radians(35.0))
    f = np.array([5e6 - 1e8 * x, 5e6 + 1e8 * x]) * 0.022 * 0.017
    assert got.force == pytest.approx(np.array([f, -0.5 * f]), rel=1e-9)
    assert got.moment_overspeed == pytest.approx(2 * m, rel=1e-9) and got.force_overspeed == pytest.approx(2 * f.max())
    rear = fe_section_loads(
        dataclasses.replace(unit, points=pts * np.array([[1.0], [1.0], [-1.0]])),
        "counterweight_1",
        dataclasses.replace(GEO, web=2),
        joint,
        coeffs,
    )
    assert rear.moment == pytest.approx(got.moment, rel=1e-9)  # the mirror image: zeta towards the middle


def test_bolted_bodies_without_joint_data_are_named():
    """A CAD geometry's bolted bodies carry no joint data: named for the case's warning."""
    from fe_crank.assess.joint_criteria import has_joints, unchecked_joints

    cad = (CounterweightData("counterweight_1", 0.5, 0.055, bolted=True),)
    tg = {"1": ThrowGeometry(0.024, (-0.0205, 0.0205), None, None, cad)}
    assert unchecked_joints(tg) == ["throw 1: counterweight_1"] and not has_joints(tg)
