"""The criteria with the whole-shaft model beside the per-throw one: each stress criterion
takes the worse of the two models and names it; the main-bearing criteria are the whole
shaft's; hand-built results, values by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers.verdicts import group_result as _group
from helpers.verdicts import two_throws as _throws

from fe_crank.assess.criteria.judge import evaluate_criteria, model_values
from fe_crank.assess.shaft import PER_THROW, WHOLE_SHAFT, ShaftAssessment
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.errors import InputError
from fe_crank.fe.shaft.cycle import BearingLoads
from fe_crank.fe.shaft.whole_shaft import BearingResult
from fe_crank.io.criteria import build_criteria
from fe_crank.report.locations import criterion_location, location_text


def _bearing(name, peak, width=0.02, diameter=0.05, law=""):
    def loads(p):
        f = np.array([[0.0, p], [0.5 * p, 0.0]])
        return BearingLoads(name, 0.0, width, diameter, f, p, 0.75 * p, 30.0, p / (diameter * width), 0.0, law)

    return BearingResult(loads(peak), loads(3 * peak))


def _shaft():
    # whole shaft: throw "1" fillet 150 MPa, static 650/150 = 4.33 (the per-throw model's worst
    # is 5.0, throw "2": the whole shaft governs), fatigue 1.8 (the per-throw 1.6 governs)
    t1 = ThrowAssessment("1", (_group("crankpin_fillet_1", 11, 150e6, 160e6, 1.8, 2.8),))
    bearings = (_bearing("1", 20e3, law="rigid"), _bearing("2", 35e3, width=0.025, law="spring 3e+08 N/m"))
    return ShaftAssessment((t1,), bearings + (_bearing("3", 30e3),))


def test_a_criterion_takes_the_worse_model_and_says_which():
    crit = build_criteria({"min_static_safety": 1.5, "min_fatigue_safety": 1.7, "min_overspeed_safety": 1.5}, "t.toml")
    by = {c.quantity: c for c in evaluate_criteria(crit, _throws(), overspeed=400.0, shaft=_shaft())}
    assert by["static_safety"].value == pytest.approx(650 / 150, rel=1e-12)
    assert criterion_location(by["static_safety"]).startswith(f"{WHOLE_SHAFT}: throw 1, crankpin_fillet_1")
    assert by["fatigue_safety"].value == pytest.approx(1.6)  # the per-throw model's throw "2"
    assert criterion_location(by["fatigue_safety"]).startswith(f"{PER_THROW}: throw 2, journal_fillet_2")
    assert by["overspeed_safety"].value == pytest.approx(650 / 160, rel=1e-12)
    values = model_values(crit, _throws(), _shaft())
    static = [v for v in values if v.criterion == "criteria.min_static_safety"]
    assert [(v.model, v.governs) for v in static] == [(PER_THROW, False), (WHOLE_SHAFT, True)]
    assert static[0].value == pytest.approx(5.0, rel=1e-12) and static[1].value == pytest.approx(650 / 150)
    # without the whole shaft: the per-throw model alone, locations as before
    alone = {c.quantity: c for c in evaluate_criteria(crit, _throws(), overspeed=400.0)}
    assert alone["static_safety"].value == pytest.approx(5.0) and criterion_location(alone["static_safety"]).startswith(
        "throw 2"
    )


def test_main_bearing_criteria_by_hand():
    """Peaks 20, 35, 30 kN; specific load peak / (d w): 35e3 / (0.05 x 0.025) = 28 MPa,
    the others 20 and 30 MPa: bearing 3 governs the specific load (30 MPa), bearing 2 the load."""
    crit = build_criteria({"max_main_bearing_load": "40 kN", "max_main_bearing_specific_load": "25 MPa"}, "t.toml")
    by = {c.quantity: c for c in evaluate_criteria(crit, _throws(), shaft=_shaft())}
    load, spec = by["main_bearing_load"], by["main_bearing_specific_load"]
    assert load.value == pytest.approx(35e3) and load.passed and load.unit == "N"
    assert load.margin == pytest.approx(1 - 35 / 40) and "main bearing 2, 30 deg" in criterion_location(load)
    assert spec.value == pytest.approx(30e6) and not spec.passed and spec.unit == "Pa"
    assert "main bearing 3" in criterion_location(spec) and criterion_location(spec).startswith(WHOLE_SHAFT)
    assert "main bearing 2, 30 deg, bearing law spring 3e+08 N/m" in criterion_location(
        load
    )  # the envelope's governing law
    assert "bearing law" not in criterion_location(spec)  # loads that name no law
    assert math.isclose(spec.margin, 1 - 30 / 25)


def test_main_bearing_criteria_need_the_whole_shaft():
    crit = build_criteria({"max_main_bearing_load": "40 kN"}, file="case.toml")
    with pytest.raises(InputError, match="whole-shaft model") as err:
        evaluate_criteria(crit, _throws(), file="case.toml")
    assert err.value.key == "criteria.max_main_bearing_load" and err.value.file == "case.toml"


def _state(speed_rpm, case, peaks):
    from fe_crank.assess.shaft import BearingState

    return BearingState(speed_rpm * math.pi / 30, case, tuple(_bearing(str(k + 1), p) for k, p in enumerate(peaks)))


def test_main_bearing_criteria_at_every_speed_and_load_state():
    """The main-bearing load at every speed of the sweep: 2000 rpm firing (peaks 20 and 30
    kN), 3000 rpm firing (25, 28 kN) and with cylinder 1 misfiring (bearing 2 at 40 kN): the
    speed's value is the worst of its states (30 kN; 40 kN naming the misfire), the
    criterion the worst speed (40 kN at 3000 rpm)."""
    from fe_crank.assess.loads import FIRING

    sweep = (
        _state(2000, FIRING, (20e3, 30e3)),
        _state(3000, FIRING, (25e3, 28e3)),
        _state(3000, "cylinder 1 misfiring", (22e3, 40e3)),
    )
    shaft = ShaftAssessment((), sweep[1].bearings, 3000 * math.pi / 30, sweep)
    crit = build_criteria({"max_main_bearing_load": "45 kN"}, "t.toml")
    (c,) = evaluate_criteria(crit, _throws(), shaft=shaft)
    assert c.value == pytest.approx(40e3) and c.speed_rpm == pytest.approx(3000)
    assert [(p.speed_rpm, p.value) for p in c.per_speed] == [(pytest.approx(2000), 30e3), (pytest.approx(3000), 40e3)]
    assert location_text(c.per_speed[0].where).startswith(f"{WHOLE_SHAFT}: main bearing 2")
    assert "cylinder 1 misfiring" in location_text(c.per_speed[1].where) and criterion_location(c).endswith(
        "; 3000 rpm"
    )


def test_the_whole_shaft_enters_at_the_operating_speed():
    """Per-throw model at 2000 and 3000 rpm (the same results at both: static 5.0, fatigue
    1.6); the whole shaft at the operating 3000 rpm (static 650/150, fatigue 1.8): at 3000
    rpm the static safety is the whole shaft's, at 2000 the per-throw model's; the fatigue
    safety stays the per-throw model's at the lowest speed of equals."""
    from fe_crank.assess.loads import FIRING
    from fe_crank.assess.speeds import StateResults

    w2, w3 = 2000 * math.pi / 30, 3000 * math.pi / 30
    sweep = (StateResults(w2, FIRING, _throws()), StateResults(w3, FIRING, _throws()))
    shaft = ShaftAssessment(_shaft().throws, _shaft().bearings, w3)
    crit = build_criteria({"min_static_safety": 1.5, "min_fatigue_safety": 1.5}, "t.toml")
    by = {c.quantity: c for c in evaluate_criteria(crit, _throws(), sweep=sweep, shaft=shaft)}
    st, fat = by["static_safety"], by["fatigue_safety"]
    assert st.value == pytest.approx(650 / 150) and st.speed_rpm == pytest.approx(3000)
    assert [p.value for p in st.per_speed] == [pytest.approx(5.0), pytest.approx(650 / 150)]
    assert location_text(st.per_speed[0].where).startswith(PER_THROW) and location_text(
        st.per_speed[1].where
    ).startswith(WHOLE_SHAFT)
    assert criterion_location(st).startswith(f"{WHOLE_SHAFT}: throw 1") and criterion_location(st).endswith(
        "; 3000 rpm"
    )
    assert fat.value == pytest.approx(1.6) and fat.speed_rpm == pytest.approx(2000)
    assert [p.value for p in fat.per_speed] == [pytest.approx(1.6), pytest.approx(1.6)]
    values = {(v.criterion, v.model): v for v in model_values(crit, _throws(), shaft, sweep=sweep)}
    assert values["criteria.min_static_safety", WHOLE_SHAFT].governs
    assert values["criteria.min_fatigue_safety", PER_THROW].governs


def test_the_whole_shaft_at_every_speed_and_load_state():
    """Per-throw model at 2000 and 3000 rpm (static 5.0, fatigue 1.6 at both); the whole
    shaft in every state (``ShaftAssessment.states``): 3000 rpm firing static 650/150 =
    4.33, fatigue 1.8; 2000 rpm firing static 650/120 = 5.42, and with cylinder 1 misfiring
    static 650/200 = 3.25, fatigue 1.2.  At 2000 rpm both criteria are the whole shaft's
    misfire state (3.25 < 5.0, 1.2 < 1.6), which governs; at 3000 rpm the static safety is
    the whole shaft's 4.33, the fatigue safety the per-throw model's 1.6."""
    from fe_crank.assess.loads import FIRING
    from fe_crank.assess.speeds import StateResults

    w2, w3 = 2000 * math.pi / 30, 3000 * math.pi / 30
    sweep = (StateResults(w2, FIRING, _throws()), StateResults(w3, FIRING, _throws()))

    def whole(vm, fat):
        return (ThrowAssessment("1", (_group("crankpin_fillet_1", 11, vm, 160e6, fat, 2.8),)),)

    misfire = "cylinder 1 misfiring"
    states = (
        StateResults(w2, FIRING, whole(120e6, 2.0)),
        StateResults(w2, misfire, whole(200e6, 1.2)),
        StateResults(w3, FIRING, _shaft().throws),
    )
    shaft = ShaftAssessment(_shaft().throws, _shaft().bearings, w3, states=states)
    crit = build_criteria({"min_static_safety": 1.5, "min_fatigue_safety": 1.5}, "t.toml")
    by = {c.quantity: c for c in evaluate_criteria(crit, _throws(), sweep=sweep, shaft=shaft)}
    st, fat = by["static_safety"], by["fatigue_safety"]
    assert [p.value for p in st.per_speed] == [pytest.approx(650 / 200), pytest.approx(650 / 150)]
    assert st.value == pytest.approx(650 / 200) and st.speed_rpm == pytest.approx(2000)
    assert criterion_location(st) == (
        f"{WHOLE_SHAFT}: throw 1, crankpin_fillet_1, node 11 at (11.0, 0.0, 2.0) mm, 30 deg; {misfire}; 2000 rpm"
    )
    assert [p.value for p in fat.per_speed] == [pytest.approx(1.2), pytest.approx(1.6)]
    assert [p.where.model for p in fat.per_speed] == [WHOLE_SHAFT, PER_THROW]
    assert fat.value == pytest.approx(1.2) and fat.speed_rpm == pytest.approx(2000)
    values = {(v.criterion, v.model): v for v in model_values(crit, _throws(), shaft, sweep=sweep)}
    assert values["criteria.min_fatigue_safety", WHOLE_SHAFT].value == pytest.approx(1.2)
    assert values["criteria.min_fatigue_safety", WHOLE_SHAFT].governs
