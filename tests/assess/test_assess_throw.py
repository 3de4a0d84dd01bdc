"""``assess_throw`` and ``evaluate_criteria`` (``assess.case``) on hand-built unit
stresses: the overspeed load scaling, the groups taken, the UR M53 inputs (rear torque,
K_e, sigma_add), the counterweight checks and every criterion's value and location, each
against a hand value.

One node per group; unit stresses: 0.01 Pa per (rad/s)^2 of sigma_xx for the centrifugal
case, 1 Pa per N of sigma_xx for pin_y, 2 Pa per N m of tau_xy for the torque.  The
stresses are uniaxial or pure shear, so von Mises is |sigma| or sqrt(3) |tau| by hand.
Values are exact to a few roundings: 1e-12 relative.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from fe_crank.assess.counterweight import CounterweightData
from fe_crank.assess.criteria.judge import evaluate_criteria
from fe_crank.assess.superpose import UnitStresses
from fe_crank.assess.throw import ThrowContext, assess_throw
from fe_crank.errors import InputError
from fe_crank.io.criteria import build_criteria
from fe_crank.io.material import load_material
from fe_crank.report.locations import criterion_location
from fe_crank.rules.m53 import calculation as m53

CASES = ("centrifugal", "pin_x", "pin_y", "torque")
THETA = np.deg2rad([0.0, 90.0, 180.0, 270.0])
PIN = np.column_stack([np.zeros(4), [1000.0, 0.0, -500.0, 0.0]])
MAT = load_material("42CrMo4")  # R_e = 650 MPa (library)
INSIDE = m53.M53Geometry(
    pin_diameter=0.1,
    journal_diameter=0.12,
    crank_radius=0.09,
    web_thickness=0.03,
    web_width=0.15,
    pin_fillet_radius=0.005,
    journal_fillet_radius=0.006,
    bearing_to_web=0.06,
)


def _unit(groups, n=1, points=None):
    s = np.zeros((4, 6, n))
    s[0, 0], s[2, 0], s[3, 3] = 0.01, 1.0, 2.0
    pts = np.zeros((3, n)) if points is None else points
    return UnitStresses(
        stress=s,
        points=pts,
        groups={k: np.asarray(v, int) for k, v in groups.items()},
        node_ids=np.arange(100, 100 + n),
        cases=CASES,
    )


def _vm(throw, group):
    return next(g for g in throw.groups if g.group == group)


def test_overspeed_scales_the_operating_loads_by_the_speed_ratio_squared():
    """No overspeed cycle given: the pin force and torque x (omega_os / omega)^2.
    omega = 100, omega_os = 120 -> x 1.44.  Angle 0: centrifugal 0.01 x 120^2 = 144 Pa plus
    pin 1.44 x 1000 = 1440 Pa -> 1584 Pa (operating: 100 + 1000 = 1100 Pa).
    omega = 0 (a standstill cycle): the loads are kept (x 1), the body force is at
    omega_os: 144 + 1000 = 1144 Pa."""
    unit = _unit({"counterweight_1": [0]})
    t = assess_throw(
        ThrowContext("1", unit, THETA, PIN, np.zeros(4), omega=100.0, overspeed=120.0, material=MAT, crank_radius=0.05)
    )
    g = _vm(t, "counterweight_1")
    assert g.max_von_mises.value == pytest.approx(1100.0, rel=1e-12)
    assert g.max_von_mises_overspeed.value == pytest.approx(1584.0, rel=1e-12)
    assert g.max_von_mises_overspeed.angle == 0.0
    assert g.overspeed_safety == pytest.approx(650e6 / 1584.0, rel=1e-12)
    t0 = assess_throw(
        ThrowContext("1", unit, THETA, PIN, np.zeros(4), omega=0.0, overspeed=120.0, material=MAT, crank_radius=0.05)
    )
    assert _vm(t0, "counterweight_1").max_von_mises_overspeed.value == pytest.approx(1144.0, rel=1e-12)
    # the torque is scaled too: T = 10 N m at 90 deg -> tau = 1.44 x 20 = 28.8 Pa, vM = sqrt(3) 28.8
    # (the largest at 90 deg, where the pin force is zero: 144 Pa and tau 28.8 -> sqrt(144^2 + 3 28.8^2))
    t1 = assess_throw(
        ThrowContext(
            "1",
            unit,
            THETA,
            np.zeros((4, 2)),
            np.array([0.0, 10.0, 0.0, 0.0]),
            omega=100.0,
            overspeed=120.0,
            material=MAT,
            crank_radius=0.05,
        )
    )
    g1 = _vm(t1, "counterweight_1").max_von_mises_overspeed
    assert g1.value == pytest.approx(math.sqrt(144.0**2 + 3 * 28.8**2), rel=1e-12)
    assert g1.angle == pytest.approx(math.pi / 2, rel=1e-15)


def test_groups_sorted_empty_ones_skipped_and_the_angle_count():
    unit = _unit({"junction_2": [0], "counterweight_1": [0], "junction_0": []})
    t = assess_throw(
        ThrowContext("7", unit, THETA, PIN, np.zeros(4), omega=100.0, overspeed=None, material=MAT, crank_radius=0.05)
    )
    assert t.name == "7" and [g.group for g in t.groups] == ["counterweight_1", "junction_2"]
    assert t.n_angles == 4 and t.m53 == () and t.m53_nominal is None and t.counterweights == ()
    assert t.groups[0].max_von_mises_overspeed is None


def test_m53_takes_the_journal_torque_with_the_larger_range_and_its_options():
    """UR M53 nominal stresses from the radial pin force and the journal torque with the
    larger half range: front 100 N m alternating (half range 100), rear 300 (half range
    300) -> the rear one; swapped -> the front one.  K_e and sigma_add are passed on: the
    results equal ``m53``'s own with the same inputs (m53 is checked against hand values in
    test_assess_m53*.py)."""
    unit = _unit({"counterweight_1": [0]})
    front = 100.0 * np.cos(THETA)
    rear = 300.0 * np.cos(THETA) + 50.0
    pin = np.column_stack([np.zeros(4), [20e3, -5e3, 8e3, -5e3]])
    kw = dict(omega=100.0, overspeed=None, material=MAT, crank_radius=0.09, m53_geometry=INSIDE)
    t = assess_throw(
        ThrowContext("1", unit, THETA, pin, front, torque_rear=rear, m53_ke=0.8, m53_additional=20e6, **kw)
    )
    nominal = m53.nominal_stresses(INSIDE, pin[:, 1], rear, ke=0.8)
    assert t.m53_nominal == nominal
    for f, name in zip(t.m53, ("pin", "journal")):
        ref = m53.assess_fillet(INSIDE, nominal, name, tensile=MAT.tensile_strength, k=MAT.m53_k, additional=20e6)
        assert f == ref
    t2 = assess_throw(ThrowContext("1", unit, THETA, pin, rear, torque_rear=front, **kw))
    assert t2.m53_nominal == m53.nominal_stresses(INSIDE, pin[:, 1], rear, ke=1.0)
    t3 = assess_throw(ThrowContext("1", unit, THETA, pin, front, **kw))
    assert t3.m53_nominal == m53.nominal_stresses(INSIDE, pin[:, 1], front, ke=1.0)
    assert t3.m53[0] == m53.assess_fillet(
        INSIDE, t3.m53_nominal, "pin", tensile=MAT.tensile_strength, k=MAT.m53_k, additional=10e6
    )
    # a material without UR M53's K (or without a tensile strength): no M53 results
    for field in ("m53_k", "tensile_strength"):
        t4 = assess_throw(
            ThrowContext("1", unit, THETA, pin, front, **dict(kw, material=dataclasses.replace(MAT, **{field: None})))
        )
        assert t4.m53 == () and t4.m53_nominal is None


def test_m53_outside_the_range_without_fe_scfs_names_the_throw_and_key():
    thin = dataclasses.replace(INSIDE, web_thickness=0.015)
    unit = _unit({"counterweight_1": [0]})
    pin = np.column_stack([np.zeros(4), [20e3, -5e3, 8e3, -5e3]])
    nominal = m53.nominal_stresses(thin, pin[:, 1], np.zeros(4))
    with pytest.raises(ValueError) as ref:
        m53.assess_fillet(thin, nominal, "pin", tensile=MAT.tensile_strength, k=MAT.m53_k)
    with pytest.raises(InputError) as e:
        assess_throw(
            ThrowContext(
                "3",
                unit,
                THETA,
                pin,
                np.zeros(4),
                omega=100.0,
                overspeed=None,
                material=MAT,
                crank_radius=0.09,
                m53_geometry=thin,
            )
        )
    assert e.value.key == "geometry" and str(e.value) == f"geometry: throw 3: {ref.value}"


def test_counterweight_checks_at_the_speed_and_overspeed():
    """m r = 0.5 x 0.05 = 0.025 kg m against 0.026 required: error 1/26; bolt load
    m r omega_os^2 = 0.025 x 120^2 = 360 N on 20 kN: 0.018."""
    unit = _unit({"counterweight_1": [0]})
    cw = CounterweightData(
        "counterweight_1", mass=0.5, centroid_radius=0.05, required_unbalance=0.026, bolted=True, bolt_capacity=20e3
    )
    t = assess_throw(
        ThrowContext(
            "1",
            unit,
            THETA,
            PIN,
            np.zeros(4),
            omega=100.0,
            overspeed=120.0,
            material=MAT,
            crank_radius=0.05,
            counterweights=(cw,),
        )
    )
    (c,) = t.counterweights
    assert c.unbalance_error == pytest.approx(1 / 26, rel=1e-12)
    assert c.bolt_utilisation == pytest.approx(0.025 * 120.0**2 / 20e3, rel=1e-12)


def _two_throws():
    """Throw 1: crankpin fillet node (1100 Pa, at (10, 20, 30) mm) and counterweight node
    (1100 Pa); throw 2: the same loads x 2 on the counterweight only (2 x 1000 + 100 = 2100 Pa),
    the fillet at half the pin force (500 + 100 = 600 Pa)."""
    pts = np.array([[0.010, 0.0], [0.020, 0.0], [0.030, 0.0]])
    unit = _unit({"crankpin_fillet_1": [0], "counterweight_1": [1]}, n=2, points=pts)
    kw = dict(omega=100.0, overspeed=120.0, material=MAT, crank_radius=0.05)
    t1 = assess_throw(ThrowContext("1", unit, THETA, PIN, np.zeros(4), **kw))
    s = unit.stress.copy()
    s[2, 0, 0] = 0.5
    s[2, 0, 1] = 2.0
    t2 = assess_throw(ThrowContext("2", dataclasses.replace(unit, stress=s), THETA, PIN, np.zeros(4), **kw))
    return t1, t2


def test_each_criterion_takes_the_worst_group_and_names_where():
    t1, t2 = _two_throws()
    crit = build_criteria(
        {
            "min_static_safety": 1.5,
            "min_overspeed_safety": 1.5,
            "max_counterweight_stress": "1 kPa",
            "max_counterweight_overspeed_stress": "3 kPa",
            "min_fatigue_safety": 1.2,
        },
        "c.toml",
    )
    out = {c.quantity: c for c in evaluate_criteria(crit, (t1, t2), file="c.toml", overspeed=120.0)}
    # static: the largest vM over both throws, 2100 Pa in throw 2's counterweight (node 101)
    assert out["static_safety"].value == pytest.approx(650e6 / 2100.0, rel=1e-12)
    assert criterion_location(out["static_safety"]) == "throw 2, counterweight_1, node 101 at (0.0, 0.0, 0.0) mm, 0 deg"
    # overspeed: x 1.44 pin and 144 Pa body force: 2 x 1440 + 144 = 3024 Pa
    assert out["overspeed_safety"].value == pytest.approx(650e6 / 3024.0, rel=1e-12)
    # counterweight stress: the largest in a counterweight group only, in Pa, failing 1 kPa
    cs = out["counterweight_stress"]
    assert cs.value == pytest.approx(2100.0, rel=1e-12) and cs.unit == "Pa" and not cs.passed
    assert cs.name == "criteria.max_counterweight_stress"
    assert out["counterweight_overspeed_stress"].value == pytest.approx(3024.0, rel=1e-12)
    assert out["counterweight_overspeed_stress"].passed is False
    # fatigue: the crankpin fillets only (counterweights are static-only); throw 1's fillet
    # has the larger stress range, so the lower safety
    fat = out["fatigue_safety"]
    assert criterion_location(fat).startswith("throw 1, crankpin_fillet_1, node 100 at (10.0, 20.0, 30.0) mm")
    f1 = next(g for g in t1.groups if g.group == "crankpin_fillet_1").fatigue_safety.value
    f2 = next(g for g in t2.groups if g.group == "crankpin_fillet_1").fatigue_safety.value
    assert f1 < f2 and fat.value == f1
    # the static criterion's worst is a minimum of the safeties: with throw 2 alone the same
    alone = evaluate_criteria(build_criteria({"min_static_safety": 1.5}, "c.toml"), (t2, t1), file="c.toml")
    assert alone[0].value == out["static_safety"].value and criterion_location(alone[0]) == criterion_location(
        out["static_safety"]
    )
    # names: the key in the file and the quantity's meaning
    assert out["static_safety"].name == "criteria.min_static_safety"
    assert out["static_safety"].description == "yield strength / max von Mises over the cycle"


def test_overspeed_criteria_without_an_overspeed_and_unevaluable_ones_are_input_errors():
    t1, t2 = _two_throws()
    for key in ("min_overspeed_safety", "max_counterweight_overspeed_stress"):
        value = 1.5 if key.startswith("min") else "1 MPa"
        with pytest.raises(InputError) as e:
            evaluate_criteria(build_criteria({key: value}, "c.toml"), (t1,), file="c.toml", overspeed=None)
        assert e.value.key == f"criteria.{key}" and e.value.file == "c.toml"
        assert str(e.value).endswith("needs operating.overspeed")
    for key, q in (
        ("min_m53_acceptability", "m53 acceptability"),
        ("max_unbalance_error", "unbalance error"),
        ("max_bolt_utilisation", "bolt utilisation"),
        ("min_gough_pollard_safety", "gough pollard safety"),
    ):
        no_fillet = dataclasses.replace(t1, groups=tuple(g for g in t1.groups if g.group == "counterweight_1"))
        with pytest.raises(InputError) as e:
            evaluate_criteria(build_criteria({key: 1.0}, "c.toml"), (no_fillet,), file="c.toml", overspeed=120.0)
        assert e.value.key == f"criteria.{key}"
        assert (
            f"cannot be evaluated: the model gives no {q} (missing geometry, mesh group, balance requirement "
            "or bolt data)"
        ) in str(e.value)


def test_m53_and_counterweight_criteria_take_the_worst_over_throws():
    """m53_acceptability: the smallest Q over every fillet of every throw, located by throw
    and fillet; unbalance error and bolt utilisation: the largest over the counterweights."""
    unit = _unit({"counterweight_1": [0]})
    pin = np.column_stack([np.zeros(4), [20e3, -5e3, 8e3, -5e3]])
    kw = dict(omega=100.0, overspeed=120.0, material=MAT, crank_radius=0.09, m53_geometry=INSIDE)
    cw_a = CounterweightData(
        "counterweight_1", mass=0.5, centroid_radius=0.05, required_unbalance=0.026, bolted=True, bolt_capacity=20e3
    )
    cw_b = CounterweightData(
        "counterweight_2", mass=0.5, centroid_radius=0.05, required_unbalance=0.02, bolted=True, bolt_capacity=40e3
    )
    t1 = assess_throw(ThrowContext("1", unit, THETA, pin, 100.0 * np.cos(THETA), counterweights=(cw_a,), **kw))
    t2 = assess_throw(ThrowContext("2", unit, THETA, 3 * pin, 100.0 * np.cos(THETA), counterweights=(cw_b,), **kw))
    crit = build_criteria(
        {"min_m53_acceptability": 1.15, "max_unbalance_error": 0.05, "max_bolt_utilisation": 0.8}, "c.toml"
    )
    out = {c.quantity: c for c in evaluate_criteria(crit, (t1, t2), file="c.toml", overspeed=120.0)}
    worst = min((f.acceptability, t.name, f.fillet, f.scf_source) for t in (t1, t2) for f in t.m53)
    assert worst[1] == "2"  # three times the radial force
    assert out["m53_acceptability"].value == worst[0]
    assert criterion_location(out["m53_acceptability"]) == f"throw 2, {worst[2]} fillet ({worst[3]})"
    # |0.025 - 0.026| / 0.026 = 1/26 (throw 1) and |0.025 - 0.02| / 0.02 = 1/4 (throw 2)
    assert out["unbalance_error"].value == pytest.approx(0.25, rel=1e-12)
    assert criterion_location(out["unbalance_error"]) == "throw 2, counterweight_2"
    # 360 N on 20 kN (throw 1) and on 40 kN (throw 2): 0.018 in throw 1
    assert out["bolt_utilisation"].value == pytest.approx(0.018, rel=1e-12)
    assert criterion_location(out["bolt_utilisation"]) == "throw 1, counterweight_1"


def test_torque_sense_and_unit_moment_reach_both_cycles():
    """A torque unit case that also gives sigma_xx (2 Pa per N m) adds to the pin case's
    1 Pa per N: at angle 0, F = 1000 N, T = 100 N m.  Unit moment M_z = -2 N m:
    coefficient -sense T / M_z = T / 2 = 50 (sense +1) -> 1000 + 100 = 1100 Pa;
    sense -1 -> -50 -> 900 Pa.  The same in the overspeed cycle given as loads (x 1)."""
    s = np.zeros((4, 6, 1))
    s[2, 0], s[3, 0] = 1.0, 2.0
    unit = UnitStresses(
        stress=s, points=np.zeros((3, 1)), groups={"counterweight_1": np.array([0])}, cases=CASES, torque_mz=-2.0
    )
    torque = np.array([100.0, 0.0, 0.0, 0.0])
    for sense, expected in ((1, 1100.0), (-1, 900.0)):
        t = assess_throw(
            ThrowContext(
                "1",
                unit,
                THETA,
                PIN,
                torque,
                omega=1.0,
                sense=sense,
                overspeed=1.0,
                material=MAT,
                crank_radius=0.05,
                overspeed_loads=(PIN, torque),
            )
        )
        g = _vm(t, "counterweight_1")
        assert g.max_von_mises.value == pytest.approx(expected, rel=1e-12)
        assert g.max_von_mises_overspeed.value == pytest.approx(expected, rel=1e-12)


def test_overspeed_scaling_below_one_radian_per_second():
    """omega = 0.5 rad/s, omega_os = 1 rad/s: the loads x (1 / 0.5)^2 = 4: 4000 Pa plus the
    body force 0.01 x 1 = 0.01 Pa at angle 0 (the factor 1 is only for omega = 0)."""
    unit = _unit({"counterweight_1": [0]})
    t = assess_throw(
        ThrowContext("1", unit, THETA, PIN, np.zeros(4), omega=0.5, overspeed=1.0, material=MAT, crank_radius=0.05)
    )
    assert _vm(t, "counterweight_1").max_von_mises_overspeed.value == pytest.approx(4000.01, rel=1e-12)


def test_each_fillet_gets_the_size_factor_of_its_own_section():
    """With the UR M53 geometry given, the crankpin fillets take the pin diameter (0.1 m)
    and the journal fillets the journal diameter (0.12 m) for the size factor."""
    from fe_crank.assess.factors import factors

    unit = _unit({"crankpin_fillet_1": [0], "journal_fillet_1": [0]}, points=np.array([[0.01], [0.05], [0.0]]))
    pin = np.column_stack([np.zeros(4), [20e3, -5e3, 8e3, -5e3]])
    t = assess_throw(
        ThrowContext(
            "1",
            unit,
            THETA,
            pin,
            np.zeros(4),
            omega=100.0,
            overspeed=None,
            material=MAT,
            crank_radius=0.09,
            m53_geometry=INSIDE,
        )
    )
    assert factors(MAT, 0.1) != factors(MAT, 0.12)
    assert _vm(t, "crankpin_fillet_1").fatigue_factors == factors(MAT, 0.1)
    assert _vm(t, "journal_fillet_1").fatigue_factors == factors(MAT, 0.12)


def _scf_result():
    from fe_crank.rules.m53.scf_mode import ScfResult

    # hand-chosen FE SCFs and mesh checks (principal criterion 1 %, averaging 2 %)
    return ScfResult(
        fe={"alpha_B": 2.5, "alpha_T": 1.9, "beta_B": 3.1, "beta_Q": 1.2, "beta_T": 1.7, "beta_BQ": 3.0},
        empirical={},
        out_of_range={},
        quality={"journal": {"principal_ratio": 0.01, "averaging": 0.02, "mesh_ok": True}},
        element_size={},
        stresses=None,
    )


def test_fe_scfs_out_of_range_from_the_given_factors_or_the_scf_mode():
    """Journal fillet radius 2 mm (r/D = 0.017, below UR M53's 0.03): the journal fillet
    takes the FE SCFs, the pin fillet (in range) its empirical ones.  Given as ``fe_scf``
    they are used as given; from ``scf`` (the SCF mode) the journal's record names the
    mode's verdict and why: "<summary>; outside the UR M53 validity range: r = 0.02 not in
    [0.03, 0.13]"."""
    geo = dataclasses.replace(INSIDE, journal_fillet_radius=0.002)
    unit = _unit({"counterweight_1": [0]})
    pin = np.column_stack([np.zeros(4), [20e3, -5e3, 8e3, -5e3]])
    result = _scf_result()
    fe_scf = result.for_assessment()
    nominal = m53.nominal_stresses(geo, pin[:, 1], np.zeros(4))
    ref = [
        m53.assess_fillet(geo, nominal, f, tensile=MAT.tensile_strength, k=MAT.m53_k, fe_scf=fe_scf[f])
        for f in ("pin", "journal")
    ]
    assert ref[0].out_of_range == () and ref[1].out_of_range == ("r = 0.02 not in [0.03, 0.13]",)
    kw = dict(omega=100.0, overspeed=None, material=MAT, crank_radius=0.09, m53_geometry=geo)
    given = assess_throw(ThrowContext("1", unit, THETA, pin, np.zeros(4), fe_scf=fe_scf, **kw))
    assert list(given.m53) == ref
    mode = assess_throw(ThrowContext("1", unit, THETA, pin, np.zeros(4), scf=_scf_result(), **kw))
    summary = (
        "FE, UR M53 App. III SCF mode (mesh accepted: principal criterion max 1.0 % (< 3 %); "
        "averaging max 2.0 % (< 5 %))"
    )
    assert result.summary() == summary
    assert mode.m53[0] == ref[0]
    assert mode.m53[1] == dataclasses.replace(
        ref[1], scf_source=summary + "; outside the UR M53 validity range: r = 0.02 not in [0.03, 0.13]"
    )
    # two reasons are joined by "; "
    geo2 = dataclasses.replace(geo, web_thickness=0.015)
    two = assess_throw(
        ThrowContext("1", unit, THETA, pin, np.zeros(4), scf=_scf_result(), **dict(kw, m53_geometry=geo2))
    )
    assert two.m53[1].scf_source == (
        summary + "; outside the UR M53 validity range: w = 0.15 not in [0.2, 0.8]; r = 0.02 not in [0.03, 0.13]"
    )


def test_counterweight_bolt_load_at_the_speed_without_an_overspeed():
    """No overspeed: the bolt load at omega = 100 rad/s: 0.025 x 100^2 = 250 N on 20 kN."""
    unit = _unit({"counterweight_1": [0]})
    cw = CounterweightData(
        "counterweight_1", mass=0.5, centroid_radius=0.05, required_unbalance=0.026, bolted=True, bolt_capacity=20e3
    )
    t = assess_throw(
        ThrowContext(
            "1",
            unit,
            THETA,
            PIN,
            np.zeros(4),
            omega=100.0,
            overspeed=None,
            material=MAT,
            crank_radius=0.05,
            counterweights=(cw,),
        )
    )
    assert t.counterweights[0].bolt_utilisation == pytest.approx(250.0 / 20e3, rel=1e-12)


def test_ties_go_to_the_first_throw_and_locations_are_in_millimetres():
    """Two identical throws: every worst value ties, and the first throw is named.  The
    node at (0.25, -0.125, 1.5) m is printed as (250.0, -125.0, 1500.0) mm.  Criteria
    without a unit (safeties) carry none; an error without a file names none."""
    pts = np.array([[0.25], [-0.125], [1.5]])
    unit = _unit({"counterweight_1": [0]}, points=pts)
    kw = dict(omega=100.0, overspeed=120.0, material=MAT, crank_radius=0.05)
    a = assess_throw(ThrowContext("A", unit, THETA, PIN, np.zeros(4), **kw))
    b = assess_throw(ThrowContext("B", unit, THETA, PIN, np.zeros(4), **kw))
    crit = build_criteria({"min_static_safety": 1.5, "max_counterweight_stress": "1 MPa"}, "c.toml")
    out = evaluate_criteria(crit, (a, b), file="c.toml", overspeed=120.0)
    assert criterion_location(out[0]) == "throw A, counterweight_1, node 100 at (250.0, -125.0, 1500.0) mm, 0 deg"
    assert criterion_location(out[1]) == criterion_location(out[0])
    assert out[0].unit == "" and out[1].unit == "Pa"
    with pytest.raises(InputError) as e:
        evaluate_criteria(build_criteria({"min_m53_acceptability": 1.15}, "c.toml"), (a,))
    assert e.value.file == "" and str(e.value).startswith("criteria.min_m53_acceptability: cannot be evaluated")
    with pytest.raises(InputError) as e:
        evaluate_criteria(build_criteria({"min_m53_acceptability": 1.15}, "c.toml"), (a,), file="c.toml")
    assert e.value.file == "c.toml"


def test_the_scf_mode_runs_when_only_the_pin_fillet_is_out_of_range():
    """Pin fillet radius 2 mm (r/D = 0.02, below 0.03), journal in range: the SCF mode
    is run (else the pin fillet could not be assessed) and the pin's record names it."""
    geo = dataclasses.replace(INSIDE, pin_fillet_radius=0.002)
    assert m53.out_of_range(geo.related("pin")) and not m53.out_of_range(geo.related("journal"))
    unit = _unit({"counterweight_1": [0]})
    pin = np.column_stack([np.zeros(4), [20e3, -5e3, 8e3, -5e3]])
    t = assess_throw(
        ThrowContext(
            "1",
            unit,
            THETA,
            pin,
            np.zeros(4),
            omega=100.0,
            overspeed=None,
            material=MAT,
            crank_radius=0.09,
            m53_geometry=geo,
            scf=_scf_result(),
        )
    )
    assert t.m53[0].scf_source.startswith("FE, UR M53 App. III SCF mode (mesh accepted")
    assert t.m53[0].scf_source.endswith("; outside the UR M53 validity range: r = 0.02 not in [0.03, 0.13]")
    assert t.m53[1].out_of_range == ()
