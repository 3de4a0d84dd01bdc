"""Criteria -> verdicts: ``judge`` (margins by hand) and ``evaluate_criteria`` (which
value of which group, throw, fillet or counterweight each criterion takes, and the
errors when one cannot be evaluated), on hand-built results of two throws."""

from __future__ import annotations

import math

import pytest
from helpers.verdicts import group_result as _group
from helpers.verdicts import two_throws as _throws

from fe_crank.assess.criteria.judge import evaluate_criteria
from fe_crank.assess.criteria.verdict import judge
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.errors import InputError
from fe_crank.io.criteria import build_criteria
from fe_crank.report.locations import criterion_location


def test_judge_margins_by_hand():
    # min: margin value/limit - 1: 1.5/1.2 - 1 = 0.25; max: 1 - value/limit: 1 - 80/100 = 0.2
    c = judge("criteria.min_static_safety", "static_safety", "min", 1.5, 1.2, unit="", location="here", description="d")
    assert (c.passed, c.margin, c.value, c.limit) == (True, pytest.approx(0.25, rel=1e-12), 1.5, 1.2)
    assert (c.name, c.quantity, c.sense, c.location, c.description) == (
        "criteria.min_static_safety",
        "static_safety",
        "min",
        "here",
        "d",
    )
    c = judge("k", "q", "min", 0.9, 1.2)
    assert not c.passed and c.margin == pytest.approx(0.9 / 1.2 - 1, rel=1e-12)
    c = judge("k", "counterweight_stress", "max", 80e6, 100e6, unit="Pa")
    assert c.passed and c.margin == pytest.approx(0.2, rel=1e-12) and c.unit == "Pa"
    c = judge("k", "q", "max", 120e6, 100e6)
    assert not c.passed and c.margin == pytest.approx(-0.2, rel=1e-12)
    # equal to the limit passes either way, with a zero margin
    assert judge("k", "q", "min", 1.2, 1.2).passed and judge("k", "q", "min", 1.2, 1.2).margin == 0.0
    assert judge("k", "q", "max", 5.0, 5.0).passed and judge("k", "q", "max", 5.0, 5.0).margin == 0.0
    # a zero limit: a maximum of 0 passes only at (or below) 0, a minimum of 0 always
    assert judge("k", "q", "max", 0.0, 0.0).margin == math.inf and judge("k", "q", "max", 0.0, 0.0).passed
    c = judge("k", "q", "max", 1e-3, 0.0)
    assert c.margin == -math.inf and not c.passed
    assert judge("k", "q", "min", 0.0, 0.0).margin == math.inf and judge("k", "q", "min", 0.0, 0.0).passed
    assert judge("k", "q", "min", -1.0, 0.0).passed is False
    # limits below 1 (unbalance error, bolt utilisation): 1 - 0.03/0.05 = 0.4; 0.6/0.5 - 1 = 0.2
    assert judge("k", "unbalance_error", "max", 0.03, 0.05).margin == pytest.approx(0.4, rel=1e-12)
    assert judge("k", "q", "min", 0.6, 0.5).margin == pytest.approx(0.2, rel=1e-12)
    # unit, location and description are empty unless given (a safety factor has no unit)
    c = judge("k", "q", "min", 2.0, 1.0)
    assert (c.unit, c.location, c.description) == ("", "", "")


def test_each_criterion_takes_the_worst_value_and_names_where():
    crit = build_criteria(
        {
            "min_static_safety": 1.5,
            "min_overspeed_safety": 1.5,
            "min_fatigue_safety": 1.7,
            "min_gough_pollard_safety": 1.2,
            "max_counterweight_stress": "50 MPa",
            "max_counterweight_overspeed_stress": "100 MPa",
            "min_m53_acceptability": 1.15,
            "max_unbalance_error": 0.04,
            "max_bolt_utilisation": 0.8,
        },
        "t.toml",
    )
    by = {v.quantity: v for v in evaluate_criteria(crit, _throws(), file="t.toml", overspeed=400.0)}
    # static: min of R_e / vM over every group: 650/130 = 5.0 at throw 2's fillet, 30 deg
    assert by["static_safety"].value == pytest.approx(5.0, rel=1e-12)
    assert (
        criterion_location(by["static_safety"]) == "throw 2, journal_fillet_2, node 30 at (30.0, 0.0, 2.0) mm, 30 deg"
    )
    assert by["overspeed_safety"].value == pytest.approx(650 / 140, rel=1e-12)
    assert criterion_location(by["overspeed_safety"]).endswith("node 30 at (30.0, 0.0, 2.0) mm, 60 deg")
    # fatigue: min over the groups that have one: 1.6 < 1.7 fails, margin 1.6/1.7 - 1
    assert by["fatigue_safety"].value == 1.6 and not by["fatigue_safety"].passed
    assert by["fatigue_safety"].margin == pytest.approx(1.6 / 1.7 - 1, rel=1e-12)
    assert criterion_location(by["fatigue_safety"]) == "throw 2, journal_fillet_2, node 31 at (31.0, 0.0, 2.0) mm"
    assert by["gough_pollard_safety"].value == 2.5 and "throw 1, crankpin_fillet_1, node 12" in criterion_location(
        by["gough_pollard_safety"]
    )
    # counterweight stresses: max over counterweight and junction groups only (the fillets'
    # 100-140 MPa are not counterweight stresses): 55 MPa at junction_2 fails 50 MPa
    cw = by["counterweight_stress"]
    assert (cw.value, cw.unit, cw.passed) == (55e6, "Pa", False)
    assert criterion_location(cw).startswith("throw 2, junction_2, node 40")
    assert by["counterweight_overspeed_stress"].value == 70e6 and by["counterweight_overspeed_stress"].passed
    # UR M53: min over all fillets and outlets of all throws: 1.3 at throw 1's journal fillet
    m53 = by["m53_acceptability"]
    assert m53.value == 1.3 and criterion_location(m53) == "throw 1, journal fillet (empirical (UR M53 3.2/3.3))"
    # unbalance and bolts: max over the counterweights that have a value
    assert by["unbalance_error"].value == 0.05 and criterion_location(by["unbalance_error"]) == "throw 2, cw_c"
    assert not by["unbalance_error"].passed
    assert by["bolt_utilisation"].value == 0.4 and criterion_location(by["bolt_utilisation"]) == "throw 2, cw_b"
    assert [v.passed for v in by.values()] == [True, True, False, True, False, True, True, False, True]


@pytest.mark.parametrize("key", ["min_overspeed_safety", "max_counterweight_overspeed_stress"])
def test_overspeed_criteria_need_an_overspeed(key):
    crit = build_criteria({key: 1.5 if key.startswith("min") else "100 MPa"}, "t.toml")
    with pytest.raises(InputError, match="needs operating.overspeed") as e:
        evaluate_criteria(crit, _throws(), file="t.toml", overspeed=None)
    assert e.value.key == f"criteria.{key}" and e.value.file == "t.toml"


@pytest.mark.parametrize(
    "key", ["min_fatigue_safety", "min_m53_acceptability", "max_bolt_utilisation", "max_counterweight_stress"]
)
def test_a_criterion_without_data_is_an_error(key):
    bare = (ThrowAssessment("1", (_group("crankpin_fillet_1", 10, 100e6, 120e6, None, None),)),)
    crit = build_criteria({key: 1.5 if key.startswith("min") else "1 MPa" if key.endswith("stress") else 0.5}, "t.toml")
    with pytest.raises(InputError, match="cannot be evaluated: the model gives no") as e:
        evaluate_criteria(crit, bare, file="t.toml", overspeed=400.0)
    assert e.value.key == f"criteria.{key}"
