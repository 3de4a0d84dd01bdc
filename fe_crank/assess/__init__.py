"""Cycle assessment: unit-load superposition, static and fatigue safety, UR M53,
counterweights, criteria -> verdicts.  See docs/assessment.md.

Public API: ``assess_case(loadcase, dynamics, balance, throw_meshes, unit_solutions)
-> Assessment`` (``loadcase.py``) and ``to_json(assessment) -> dict`` (``results.py``);
the assessed node groups are in ``groups.py``.
"""

from __future__ import annotations

from fe_crank.assess.case import assess_case
from fe_crank.assess.counterweight import CounterweightData
from fe_crank.assess.groups import ASSESSED_BOUNDARIES, COUNTERWEIGHTS, assessed_groups, unit_stresses
from fe_crank.assess.m53 import M53Geometry
from fe_crank.assess.results import to_json
from fe_crank.assess.superpose import UnitStresses, load_coefficients
from fe_crank.assess.throw import Assessment, ThrowAssessment, assess_throw, evaluate_criteria

__all__ = [
    "assess_case",
    "to_json",
    "Assessment",
    "ThrowAssessment",
    "assess_throw",
    "evaluate_criteria",
    "UnitStresses",
    "load_coefficients",
    "unit_stresses",
    "assessed_groups",
    "M53Geometry",
    "CounterweightData",
    "ASSESSED_BOUNDARIES",
    "COUNTERWEIGHTS",
]
