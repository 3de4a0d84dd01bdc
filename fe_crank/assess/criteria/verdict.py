"""Criteria -> verdicts.  Margin: value/limit - 1 for a minimum, 1 - value/limit for a
maximum; positive passes, and the case passes when every criterion does."""

from __future__ import annotations

import math

from fe_crank.results import CriterionResult, Sense

__all__ = ["CriterionResult", "judge"]


def judge(
    name: str,
    quantity: str,
    sense: Sense,
    value: float,
    limit: float,
    *,
    unit: str = "",
    location: str = "",
    description: str = "",
) -> CriterionResult:
    if sense == "min":
        passed = value >= limit
        margin = value / limit - 1.0 if limit > 0 else math.inf
    else:
        passed = value <= limit
        margin = 1.0 - value / limit if limit > 0 else (math.inf if value <= 0 else -math.inf)
    return CriterionResult(
        name=name,
        quantity=quantity,
        sense=sense,
        value=float(value),
        limit=float(limit),
        margin=float(margin),
        passed=bool(passed),
        unit=unit,
        location=location,
        description=description,
    )
