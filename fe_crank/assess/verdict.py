"""Criteria -> verdicts.  Margin: value/limit - 1 for a minimum, 1 - value/limit for a
maximum; positive passes, and the case passes when every criterion does."""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class CriterionResult:
    """One criterion's verdict (the fields the pipeline and the report read)."""

    name: str  # the criterion's key, e.g. "criteria.min_fatigue_safety"
    quantity: str
    sense: str  # "min" | "max"
    value: float
    limit: float
    margin: float
    passed: bool
    unit: str = ""
    location: str = ""
    description: str = ""


def judge(name: str, quantity: str, sense: str, value: float, limit: float, *, unit: str = "",
          location: str = "", description: str = "") -> CriterionResult:
    if sense == "min":
        passed = value >= limit
        margin = value / limit - 1.0 if limit > 0 else math.inf
    else:
        passed = value <= limit
        margin = 1.0 - value / limit if limit > 0 else (math.inf if value <= 0 else -math.inf)
    return CriterionResult(name, quantity, sense, float(value), float(limit), float(margin), bool(passed), unit,
                           location, description)
