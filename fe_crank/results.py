"""Result types shared by every layer (plain, frozen, picklable data).

``CriterionResult`` is the verdict on one criterion (``fe_crank.assess.verdict.judge``
makes the assessment's; ``fe_crank.check.verdict`` collects every stage's);
``StageTime`` one stage's wall time.  The record of a whole case, ``CaseResult``, is in
``fe_crank.records``.
"""

from __future__ import annotations

from dataclasses import dataclass

STATUS_PASS, STATUS_FAIL, STATUS_ERROR = "pass", "fail", "error"


@dataclass(frozen=True)
class SpeedValue:
    """A criterion's worst value at one speed of the full-load curve (or at the
    overspeed), rpm, and where it occurs."""

    speed_rpm: float
    value: float
    location: str = ""


@dataclass(frozen=True)
class CriterionResult:
    """One acceptance criterion of a load case: the assessment's verdict, as the
    check, the report and ``case.json`` read it.

    ``margin`` is ``value / limit - 1`` for a "not below" criterion (``sense`` "min",
    a safety factor) and ``1 - value / limit`` for a "not above" one ("max": a
    stress, a residual unbalance): a criterion passes when its margin is not
    negative.  ``name`` is the criterion's key, e.g. "criteria.min_fatigue_safety".
    ``per_speed``: its worst value at each speed it was evaluated at (every speed of the
    full-load curve, or the overspeed; () for a criterion that does not depend on
    speed); ``speed_rpm`` the speed of ``value`` (None: no speed).
    """

    name: str
    passed: bool
    value: float
    limit: float
    margin: float
    description: str = ""
    location: str = ""
    unit: str = ""
    quantity: str = ""
    sense: str = ""  # "min" | "max"
    per_speed: tuple[SpeedValue, ...] = ()
    speed_rpm: float | None = None


@dataclass(frozen=True)
class StageTime:
    stage: str
    seconds: float
