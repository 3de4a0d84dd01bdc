"""Where a criterion's value occurs is data (``results.Location``), put into words in one
place (``report.locations``): each kind's words written out by hand here, and the
verdict (``pipeline.verdict.decide``) giving every criterion and speed its words."""

from __future__ import annotations

import math

from fe_crank.assess.case import Assessment
from fe_crank.assess.criteria.judge import judge_criteria
from fe_crank.assess.group.assessment import Extreme, GroupResult
from fe_crank.assess.loads import FIRING
from fe_crank.assess.speeds import StateResults
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.io.criteria import build_criteria
from fe_crank.io.material import load_material
from fe_crank.outputs import CaseOutputs
from fe_crank.pipeline.verdict import decide
from fe_crank.report.locations import criterion_location, location_text
from fe_crank.results import CriterionResult, Location


def test_the_words_of_each_kind():
    node = Location("group", "2", "journal_fillet_2", 31, (0.031, 0.0, 0.002), 30.4)
    assert location_text(node) == "throw 2, journal_fillet_2, node 31 at (31.0, 0.0, 2.0) mm, 30 deg"
    assert location_text(Location("group", "A", "junction_1", 4, (0.25, -0.125, 1.5))) == (
        "throw A, junction_1, node 4 at (250.0, -125.0, 1500.0) mm"
    )
    assert location_text(Location("m53", "1", "journal", detail="empirical")) == "throw 1, journal fillet (empirical)"
    assert location_text(Location("m53", "1", "oil_bore", detail="FE")) == "throw 1, oil-bore outlet (FE)"
    assert location_text(Location("counterweight", "4", "counterweight_2")) == "throw 4, counterweight_2"
    assert location_text(Location("joint", "1", "counterweight_1")) == "throw 1, counterweight_1 (per bolt)"
    assert location_text(Location("bearing", group="2", angle_deg=29.6)) == "main bearing 2, 30 deg"
    spec = Location("bearing_specific", group="3", angle_deg=180.0, width=0.029)
    assert location_text(spec) == "main bearing 3 (peak / (d w), w = 29 mm), 180 deg"
    spot = Location("hot_spot", "1", "crankpin_fillet_1", detail="peak torque", levels=(4.0, 8.0))
    assert location_text(spot) == "throw 1, crankpin_fillet_1, peak torque, r/4 (assessed) -> r/8 (finest)"
    # the load state, the speed (when named) and the model, in that order
    full = Location(
        "counterweight", "4", "cw", case="cylinder 1 misfiring", speed_rpm=2999.6, model="whole-shaft model"
    )
    assert location_text(full) == "whole-shaft model: throw 4, cw; cylinder 1 misfiring; 3000 rpm"
    assert location_text(None) == ""
    # a criterion's words: its location, then its remarks
    c = CriterionResult("k", True, 1.0, 1.0, 0.0, where=Location("joint", "1", "cw"), remarks=("x1.050 by", "q"))
    assert criterion_location(c) == "throw 1, cw (per bolt); x1.050 by; q"


def _group(vm: float) -> GroupResult:
    e = Extreme(vm, "crankpin_fillet_1", 12, (0.01, 0.02, 0.0), math.radians(90))
    return GroupResult("crankpin_fillet_1", 3, e, None, 600e6 / vm, None, None, None)


def test_the_verdict_writes_every_criterion_and_speed_in_words():
    """Two speeds with a misfire at the second: the worst speed is named after the location
    and each speed's entry carries its own words (the misfire case, no speed)."""
    low, high = 1000 * math.pi / 30, 2000 * math.pi / 30
    sweep = (
        StateResults(low, FIRING, (ThrowAssessment("1", (_group(100e6),)),)),
        StateResults(high, FIRING, (ThrowAssessment("1", (_group(150e6),)),)),
        StateResults(high, "cylinder 1 misfiring", (ThrowAssessment("1", (_group(200e6),)),)),
    )
    crit = judge_criteria(build_criteria({"min_static_safety": 2.0}, "c.toml"), sweep[0].throws, sweep=sweep)
    (c,) = crit.criteria
    assert c.location == "" and c.where is not None and c.where.case == "cylinder 1 misfiring"
    a = Assessment("c", "c.toml", low, None, load_material("C45"), sweep[0].throws, crit.criteria, sweep=sweep)
    (v,) = decide(CaseOutputs(assessment=a)).criteria
    head = "throw 1, crankpin_fillet_1, node 12 at (10.0, 20.0, 0.0) mm, 90 deg"
    assert v.value == 3.0 and v.location == f"{head}; cylinder 1 misfiring; 2000 rpm"
    assert [p.location for p in v.per_speed] == [head, f"{head}; cylinder 1 misfiring"]
