"""The bolted counterweight by VDI 2230 Part 1 (2015), one bolt, against a hand calculation.

Example: one radial M12 bolt, property class 10.9 (R_p0.2 = 940 MPa, ISO 898-1), coarse
pitch P = 1.75 mm, screwed into the steel web (tapped thread joint, ESV), clamp length
l_K = 30 mm, head bearing d_W = 17 mm, hole d_h = 13 mm, clamped parts D_A = 30 mm,
E_S = 205 GPa, E_P = 210 GPa, mu_G = mu_K = mu_T = 0.10, alpha_A = 1.6, Rz 10-40 um,
tightened to F_M,zul.  Counterweight m = 2 kg at r_c = 60 mm, 3000 rpm with delta = 0.02,
|alpha| <= 1000 rad/s^2, overspeed 3600 rpm.  By hand (N, mm):

thread (5.1.1): d_2 = 12 - 0.64952 x 1.75 = 10.86334, d_3 = 12 - 1.22687 x 1.75 = 9.85298,
  d_s = 10.35816, A_s = 84.2665, A_d3 = 76.2474, A_N = 113.0973 mm^2
delta_S = 6/(205000 A_N) + 30/(205000 A_d3) + 6/(205000 A_d3) + 0.33 x 12/(210000 A_N)
        = 2.5879e-7 + 1.9193e-6 + 3.8386e-7 + 1.6673e-7 = 2.7287e-6 mm/N
cone (5.1.2, ESV): beta_L = y = 30/17 = 1.76471, tan(phi) = 0.348 + 0.013 ln 1.76471
  + 0.193 ln 1.76471 = 0.46500, D_A,Gr = 17 + 2 x 30 x 0.465 = 44.90 > D_A = 30: cones and
  sleeve, 2/(2 x 13 x 0.465) ln(30 x 17 / (4 x 43)) = 0.179802,
  4/(30^2 - 13^2) (30 - 13/(2 x 0.465)) = 0.087670, delta_P = 0.267472/(210000 pi) = 4.0542e-7
Phi_K = 4.0542e-7 / 3.13412e-6 = 0.12936
embedding (table 5.4/1, shear, 10-40 um): 3 + 4.5 + 2.5 = 10 um, F_Z = 0.010/3.13412e-6 = 3190.7
F_M,zul (R7): 1.5 (10.86334/10.35816)(1.75/(pi 10.86334) + 0.1155) = 0.26237,
  F_M,zul = 84.2665 x 0.9 x 940 / sqrt(1 + 3 x 0.26237^2) = 64902.3, F_M,min = /1.6 = 40563.9
M_A = 64902.3 (0.16 x 1.75 + 0.58 x 10.86334 x 0.1 + 15/2 x 0.1) = 107.74 N m
loads per bolt: F_A,max = 0.12 (314.159 x 1.01)^2 = 12081.6, F_A,min = 0.12 (314.159 x 0.99)^2
  = 11607.8, at overspeed 0.12 x 376.991^2 = 17054.7; F_Q = 0.12 x 1000 = 120
n not stated (the bounds n = 1 for the bolt, 0 for the clamp):
  R8: sigma_z = (64902.3 + 0.12936 x 17054.7)/84.2665 = 796.38 MPa, tau = 64902.3 x 0.90588
      /(pi 10.35816^3/16) = 269.43 MPa, sigma_red,B = sqrt(796.38^2 + 3 (0.5 x 269.43)^2) = 829.86,
      S_F = 940/829.86 = 1.1327
  R9: dF_A = max(474, 12081.6) (start-stop), sigma_a = 0.12936 x 12081.6/(2 x 84.2665) = 9.2733 MPa,
      sigma_ASV = 0.85 (150/12 + 45) = 48.875 MPa, S_D = 5.2705
  F_KR,min = 40563.9 - 3190.7 - 17054.7 = 20318.6, S_sep = 37373.3/17054.7 = 2.1914,
  R12: S_G = 20318.6 x 0.10 / 120 = 16.932
n = 0.5 stated: S_F = 1.15012, S_D = 10.541, F_KR = 21421.6, S_sep = 2.3429, S_G = 17.851.
"""

from __future__ import annotations

import dataclasses
import math

import pytest
from helpers.joints import JOINT, W_OS, W
from helpers.joints import joint_loads as _loads

from fe_crank.assess.cw_joint import check_joint
from fe_crank.assess.joint_loads import counterweight_loads
from fe_crank.errors import InputError
from fe_crank.io.geometry import geometry_from_dict
from fe_crank.rules import vdi2230


def test_thread_and_resiliences_by_hand():
    t = vdi2230.thread(0.012, 0.00175)
    assert t["d2"] == pytest.approx(10.86334e-3, rel=1e-6) and t["d3"] == pytest.approx(9.85298e-3, rel=1e-6)
    assert t["As"] == pytest.approx(84.2665e-6, rel=1e-5) and t["Ad3"] == pytest.approx(76.2474e-6, rel=1e-5)
    ds = vdi2230.bolt_resilience(0.012, 0.00175, 0.030, 205e9, 210e9, tapped=True)
    assert ds == pytest.approx(2.7287e-6 / 1e3, rel=2e-4)  # mm/N -> m/N
    assert vdi2230.cone_tangent(0.030, 0.017, 0.030, tapped=True) == pytest.approx(0.46500, abs=2e-5)
    dp = vdi2230.plate_resilience(0.030, 0.017, 0.013, 0.030, 210e9, tapped=True)
    assert dp == pytest.approx(4.0542e-7 / 1e3, rel=2e-4)
    assert vdi2230.permissible_preload(0.012, 0.00175, 940e6, 0.10) == pytest.approx(64902.3, rel=2e-5)
    # the permissible preload puts the equivalent assembly stress at 0.9 R_p0.2 (R7)
    assert vdi2230.assembly_stress(0.012, 0.00175, 64902.3, 0.10)[2] == pytest.approx(0.9 * 940e6, rel=2e-6)
    assert vdi2230.endurance_limit(0.012, rolled_after_heat_treatment=False) == pytest.approx(48.875e6, rel=1e-12)


def test_counterweight_loads_by_hand():
    ld = _loads()
    assert ld.axial_max == pytest.approx(12081.6, rel=1e-5) and ld.axial_min == pytest.approx(11607.8, rel=1e-5)
    assert ld.axial_overspeed == pytest.approx(17054.7, rel=1e-5) and ld.transverse_max == pytest.approx(120.0)
    axial = counterweight_loads(2.0, 0.06, 2, "axial", omega=W, overspeed=W_OS, angular_acceleration=1000.0)
    assert axial.axial_max == 0.0 and axial.transverse_max == pytest.approx(math.hypot(17054.7, 120.0) / 2, rel=1e-5)


def test_single_bolt_joint_by_hand_with_the_load_introduction_bounds():
    c = check_joint("counterweight_1", JOINT, _loads(), 210e9)
    assert c.load_factor == pytest.approx(0.12936, rel=2e-4)
    assert c.embedding_loss == pytest.approx(3190.7, rel=2e-4)
    assert (c.preload_max, c.preload_min) == (pytest.approx(64902.3, rel=2e-5), pytest.approx(40563.9, rel=2e-5))
    assert c.assembly_utilisation == pytest.approx(0.9, rel=1e-6)
    assert c.tightening_torque == pytest.approx(107.74, rel=1e-4)
    assert c.working_safety == pytest.approx(1.1327, rel=2e-4)
    assert c.fatigue_amplitude == pytest.approx(9.2733e6, rel=2e-4)
    assert c.endurance_limit == pytest.approx(48.875e6, rel=1e-9)
    assert c.fatigue_safety == pytest.approx(5.2705, rel=2e-4)
    assert c.residual_clamp == pytest.approx(20318.6, rel=2e-4)
    assert c.separation_safety == pytest.approx(2.1914, rel=2e-4)
    assert c.slip_safety == pytest.approx(16.932, rel=2e-4)


def test_stated_load_introduction_factor():
    import dataclasses

    c = check_joint("counterweight_1", dataclasses.replace(JOINT, load_introduction=0.5), _loads(), 210e9)
    assert c.working_safety == pytest.approx(1.15012, rel=2e-4)
    assert c.fatigue_safety == pytest.approx(10.541, rel=2e-4)
    assert c.residual_clamp == pytest.approx(21421.6, rel=2e-4)
    assert c.separation_safety == pytest.approx(2.3429, rel=2e-4)
    assert c.slip_safety == pytest.approx(17.851, rel=2e-4)


def test_a_lower_stated_preload_opens_the_joint():
    """A preload of 20 kN (F_M,min = 12.5 kN) minus F_Z cannot hold 17.05 kN at the overspeed:
    S_sep < 1, no residual clamp, no friction grip."""
    import dataclasses

    c = check_joint("cw", dataclasses.replace(JOINT, preload=20e3), _loads(), 210e9)
    assert c.separation_safety == pytest.approx((12500.0 - 3190.7) / 17054.7, rel=2e-4)
    assert c.separation_safety < 1 and c.residual_clamp < 0 and c.slip_safety == 0.0


#: the VDI 2230 data of the joint of ``_geometry`` (M12, 10.9, counterbored head)
VDI_DATA = {
    "property_class": "10.9",
    "clamp_length": "30 mm",
    "bearing_diameter": "17 mm",
    "hole_diameter": "13 mm",
    "clamped_diameter": "30 mm",
    "tightening_factor": 1.6,
}


def _geometry(**bolted):
    bolt = {"count": 2, "diameter": "12 mm", "pitch_radius": "55 mm", **bolted}
    return {
        "name": "bolted",
        "crank_radius": "40 mm",
        "journal": {"diameter": "50 mm", "length": "20 mm", "fillet_radius": "3 mm"},
        "crankpin": {"diameter": "45 mm", "length": "30 mm", "fillet_radius": "3 mm"},
        "web": {"thickness": "18 mm", "outline": "stadium", "width": "70 mm"},
        "counterweight": {
            "outer_radius": "80 mm",
            "inner_radius": "30 mm",
            "angle": "140 deg",
            "fillet_radius": "4 mm",
            "bolted": bolt,
        },
    }


def test_joint_input_keys_with_units_and_validation():
    full = {**VDI_DATA, "thread_friction": 0.12}
    b = geometry_from_dict(_geometry(**full), "g.toml").throw().counterweights[0].bolted
    got = (b.clamp_length, b.hole_diameter, b.thread_friction, b.thread_pitch)
    assert got == pytest.approx((0.030, 0.013, 0.12, 0.00175), rel=1e-12)
    assert b.vdi_missing() == []
    partial = geometry_from_dict(_geometry(), "g.toml").throw().counterweights[0].bolted
    assert partial.vdi_missing() == [
        *("clamp_length", "bearing_diameter", "hole_diameter"),
        "clamped_diameter",
        "tightening_factor",
        "property_class",
    ]
    for bad, words in [
        ({**full, "hole_diameter": "11 mm"}, "hole_diameter must exceed"),
        ({**full, "bearing_diameter": "12.5 mm"}, "bearing_diameter must exceed"),
        ({**full, "clamp_length": "-3 mm"}, "greater than 0"),
        ({**full, "clamp_length": "30"}, ""),
        ({**full, "tightening_factor": 0.8}, "greater than or equal to 1"),
        ({**full, "yield_strength": "900 MPa"}, "not both"),
        ({**full, "property_class": "5.6"}, "8.8"),
        ({**full, "direction": "tangential"}, "radial"),
        ({**full, "thread_friction": float("nan")}, ""),
    ]:
        with pytest.raises(InputError) as e:
            geometry_from_dict(_geometry(**bad), "g.toml")
        assert "counterweight.bolted" in e.value.key and words in str(e.value), (bad, str(e.value))


def test_coarse_pitch_from_iso_261_or_the_pitch_required():
    """ISO 261 coarse pitches (M6 1 mm, M48 5 mm, M12 1.75 mm); a diameter off the coarse
    series without a stated pitch is a missing VDI 2230 datum, refused before any meshing
    (``io.bolted.require_joint_data``), not a failure of the check after meshing."""
    from fe_crank.io.bolted import require_joint_data

    full = dict(VDI_DATA)
    for d, pitch in [("6 mm", 1.0e-3), ("12 mm", 1.75e-3), ("48 mm", 5.0e-3)]:
        g = _geometry(**full)
        g["counterweight"]["bolted"]["diameter"] = d
        g["counterweight"]["bolted"]["hole_diameter"] = "60 mm" if d == "48 mm" else "13 mm"
        g["counterweight"]["bolted"]["bearing_diameter"] = "70 mm" if d == "48 mm" else "17 mm"
        g["counterweight"]["bolted"]["clamped_diameter"] = "90 mm" if d == "48 mm" else "30 mm"
        b = geometry_from_dict(g, "g.toml").throw().counterweights[0].bolted
        assert b.thread_pitch == pytest.approx(pitch, rel=1e-12) and b.vdi_missing() == []
    g = _geometry(**full)
    g["counterweight"]["bolted"]["diameter"] = "11 mm"
    geometry = geometry_from_dict(g, "g.toml")
    assert geometry.throw().counterweights[0].bolted.vdi_missing() == ["pitch"]
    with pytest.raises(InputError) as e:
        require_joint_data(geometry, "lc.toml")
    assert "counterweight.bolted" in e.value.key and "pitch" in str(e.value)
    g["counterweight"]["bolted"]["pitch"] = "1.5 mm"
    require_joint_data(geometry_from_dict(g, "g.toml"), "lc.toml")


def test_joints_from_the_geometry_and_the_cycle(tmp_path):
    """The adapter gives each bolted counterweight its joint, mass and radius (exact B-rep mass
    properties); the cycle's delta and |alpha|max = max |T - T_mean| / J come from the
    dynamics stage; a joint without the VDI data is refused, naming the keys."""
    import numpy as np

    from fe_crank.assess.adapters import counterweights_of
    from fe_crank.assess.cw_joint import check_joints
    from fe_crank.assess.joint_loads import cycle_speed_data
    from fe_crank.geometry import mass_properties
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mechanism import dynamics

    full = dict(VDI_DATA)
    g = geometry_from_dict(_geometry(**full), "g.toml")
    whole = mass_properties(g, g.throw())
    cws = counterweights_of(g.throw(), whole, 0.0, "main", None)  # no balance design: one entry per web
    props = whole.parts
    assert [j.name for c in cws for j in c.joints] == ["counterweight_1", "counterweight_2"]
    cw = cws[0]
    for j in (j for c in cws for j in c.joints):
        p = props[j.name]
        assert j.mass == pytest.approx(p.mass, rel=1e-12)
        assert j.radius == pytest.approx(math.hypot(*p.unbalance_vector) / p.mass, rel=1e-12)
    lc = load_loadcase("loadcases/single_cylinder.toml")
    dyn = dynamics.analyse(lc.engine, lc.operating)
    delta, alpha = cycle_speed_data(dyn)
    assert delta == dyn.speed_fluctuation
    assert alpha * dyn.flywheel_inertia == pytest.approx(np.abs(dyn.torque - dyn.mean_torque).max(), rel=1e-12)
    checks = check_joints(
        cw,
        omega=lc.operating.speed,
        overspeed=lc.operating.overspeed,
        e_clamped=210e9,
        speed_fluctuation=delta,
        angular_acceleration=alpha,
    )
    assert len(checks) == 1 and checks[0].loads.transverse_max > 0
    bare = geometry_from_dict(_geometry(), "g.toml")
    cw0 = counterweights_of(bare.throw(), mass_properties(bare, bare.throw()), 0.0, "main", None)[0]
    with pytest.raises(InputError) as e:
        check_joints(cw0, omega=300.0, overspeed=None, e_clamped=210e9, file="g.toml")
    assert e.value.key == "counterweight.bolted" and "clamp_length" in str(e.value)


def test_a_joint_without_the_data_the_check_needs_is_refused_by_name():
    """A joint built by hand without a datum VDI 2230 needs (``BoltedJoint.vdi_missing``), or
    with neither a yield strength nor a property class, is an error naming what is missing."""
    loads = _loads()
    for key in ("clamp_length", "bearing_diameter", "hole_diameter", "clamped_diameter", "tightening_factor"):
        with pytest.raises(ValueError, match=f"cw1: the VDI 2230 bolt check needs {key}"):
            check_joint("cw1", dataclasses.replace(JOINT, **{key: None}), loads, 210e9)
    with pytest.raises(ValueError, match="needs the bolt's yield_strength or property_class"):
        check_joint("cw1", dataclasses.replace(JOINT, property_class=None), loads, 210e9)
