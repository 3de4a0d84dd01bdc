"""Cycle assessment: unit-load superposition, static and fatigue safety, UR M53,
counterweights, criteria -> verdicts.  See docs/assessment.md.

Public API: ``assess_case(AssessInputs) -> Assessment`` (``case.py``) and
``to_json(assessment) -> dict`` (``results.py``); one throw: ``assess_throw``
(``throw.py``); one node group: ``assess_group`` (``group/assessment.py``); the assessed node
groups are in ``group/nodes.py``, the criteria table in ``criteria/judge.py``, the drawn states in
``states.py``.
"""

from __future__ import annotations

from fe_crank.assess.case import Assessment, assess_case
from fe_crank.assess.counterweight import CounterweightData
from fe_crank.assess.criteria.judge import EVALUATORS, evaluate_criteria, judge_criteria
from fe_crank.assess.group.nodes import ASSESSED_BOUNDARIES, COUNTERWEIGHTS, assessed_groups, unit_stresses
from fe_crank.assess.inputs import AssessInputs
from fe_crank.assess.results import to_json
from fe_crank.assess.superpose import UnitStresses, load_coefficients
from fe_crank.assess.throw import ThrowAssessment, ThrowContext, assess_throw
from fe_crank.rules.m53.calculation import M53Geometry

__all__ = [
    "ASSESSED_BOUNDARIES",
    "COUNTERWEIGHTS",
    "EVALUATORS",
    "AssessInputs",
    "Assessment",
    "CounterweightData",
    "M53Geometry",
    "ThrowAssessment",
    "ThrowContext",
    "UnitStresses",
    "assess_case",
    "assess_throw",
    "assessed_groups",
    "evaluate_criteria",
    "judge_criteria",
    "load_coefficients",
    "to_json",
    "unit_stresses",
]
