"""The five VDI 2230 criteria of the bolted counterweight in the criteria table: each judges
the worst joint the assessment checked (``ThrowAssessment.joints``), in its own sense.

Two joints of the hand-calculated M12 10.9 example of ``test_assess_cw_joint`` (its
docstring has the numbers): one tightened to F_M,zul (S_F = 1.1327, S_D = 5.2705, S_sep =
2.1914, S_G = 16.932, nu = 0.9 exactly) and one with a 20 kN preload, which opens at the
overspeed (S_sep = (12500 - 3190.7)/17054.7 = 0.5458, no residual clamp: S_G = 0) and has
the smaller assembly utilisation (20 kN / 64.9 kN of the same stress state, nu < 0.9)."""

from __future__ import annotations

import dataclasses

import pytest
from helpers.joints import JOINT
from helpers.joints import joint_loads as _loads

from fe_crank.assess.criteria.judge import EVALUATORS, evaluate_criteria
from fe_crank.assess.cw_joint import check_joint
from fe_crank.assess.joint_criteria import JOINT_QUANTITIES
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.errors import InputError
from fe_crank.io.criteria import QUANTITIES, build_criteria
from fe_crank.report.locations import criterion_location


def _throws():
    tight = check_joint("counterweight_1", JOINT, _loads(), 210e9)
    loose = check_joint("counterweight_2", dataclasses.replace(JOINT, preload=20e3), _loads(), 210e9)
    return (ThrowAssessment("1", (), joints=(tight,)), ThrowAssessment("4", (), joints=(loose,))), tight, loose


def test_every_quantity_has_an_evaluator():
    assert set(QUANTITIES) == set(EVALUATORS)


def test_the_five_bolt_criteria_judge_the_worst_joint():
    throws, tight, loose = _throws()
    crit = build_criteria(
        {
            "max_bolt_assembly_utilisation": 0.9,
            "min_bolt_working_safety": 1.0,
            "min_bolt_fatigue_safety": 1.2,
            "min_bolt_separation_safety": 1.0,
            "min_bolt_slip_safety": 1.2,
        },
        "c.toml",
    )
    got = {c.quantity: c for c in evaluate_criteria(crit, throws, file="c.toml")}
    assert set(got) == set(JOINT_QUANTITIES)
    # R7: the larger utilisation, the joint at F_M,zul: 0.9 exactly, passes (<= 0.9)
    a = got["bolt_assembly_utilisation"]
    assert a.value == pytest.approx(0.9, rel=1e-6) and criterion_location(a) == "throw 1, counterweight_1 (per bolt)"
    # R8 at the overspeed: the tighter joint, 1.1327 by hand
    assert got["bolt_working_safety"].value == pytest.approx(1.1327, rel=2e-4)
    assert got["bolt_working_safety"].passed
    # the loose joint opens: S_sep 0.5458 and S_G 0 fail, in throw 4
    sep, slip = got["bolt_separation_safety"], got["bolt_slip_safety"]
    assert sep.value == pytest.approx((12500.0 - 3190.7) / 17054.7, rel=2e-4) and not sep.passed
    assert slip.value == 0.0 and not slip.passed and criterion_location(slip).startswith("throw 4, counterweight_2")
    assert got["bolt_fatigue_safety"].value == pytest.approx(min(tight.fatigue_safety, loose.fatigue_safety))


def test_a_bolt_criterion_without_a_checked_joint_is_refused():
    crit = build_criteria({"min_bolt_slip_safety": 1.2}, "c.toml")
    with pytest.raises(InputError) as e:
        evaluate_criteria(crit, (ThrowAssessment("1", ()),), file="c.toml")
    assert "criteria.min_bolt_slip_safety" in str(e.value) and "bolt slip safety" in str(e.value)
