"""Result types of a check, shared by every layer (plain, frozen, picklable data).

``CriterionResult`` is the assessment's verdict on one criterion
(``fe_crank.assess.verdict.judge`` makes it); ``CaseResult`` is the outcome of one
load case (``fe_crank.check.case.run_case`` makes it, the report reads it).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

STATUS_PASS, STATUS_FAIL, STATUS_ERROR = "pass", "fail", "error"
_EXIT = {STATUS_PASS: 0, STATUS_FAIL: 1, STATUS_ERROR: 2}


@dataclass(frozen=True)
class CriterionResult:
    """One acceptance criterion of a load case: the assessment's verdict, as the
    check, the report and ``case.json`` read it.

    ``margin`` is ``value / limit - 1`` for a "not below" criterion (``sense`` "min",
    a safety factor) and ``1 - value / limit`` for a "not above" one ("max": a
    stress, a residual unbalance): a criterion passes when its margin is not
    negative.  ``name`` is the criterion's key, e.g. "criteria.min_fatigue_safety".
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


@dataclass(frozen=True)
class StageTime:
    stage: str
    seconds: float


@dataclass(frozen=True)
class CaseResult:
    """Outcome of one load case.  Frozen and picklable (plain data only)."""

    name: str
    source: str
    status: str  # "pass" | "fail" | "error"
    message: str = ""
    criteria: tuple[CriterionResult, ...] = ()
    timings: tuple[StageTime, ...] = ()
    folder: str = ""  # the finished case folder, "" when none could be written
    seconds: float = 0.0
    error_stage: str = ""
    started: str = ""  # ISO 8601 UTC
    provenance: dict = field(default_factory=dict, compare=False)  # fe_crank.provenance.collect
    warnings: tuple[str, ...] = ()  # notes shown beside the verdict (fe_crank.report.quality)
    planned_criteria: tuple[str, ...] = ()  # the load case's criteria (listed as errored when the case errors)

    @property
    def exit_code(self) -> int:
        """0 pass, 1 a criterion failed, 2 an input or computation error."""
        return _EXIT[self.status]

    @property
    def worst(self) -> CriterionResult | None:
        """The criterion with the smallest margin (None without criteria)."""
        if not self.criteria:
            return None
        return min(self.criteria, key=lambda c: (c.margin, c.name))

    def to_dict(self) -> dict:
        d = _finite(asdict(self))
        d["exit_code"] = self.exit_code
        w = self.worst
        d["worst"] = w.name if w else None
        return d


def _finite(x):
    """Non-finite floats (an unloaded part's infinite safety) -> None, for strict JSON."""
    if isinstance(x, float):
        return x if x == x and x not in (float("inf"), float("-inf")) else None
    if isinstance(x, dict):
        return {k: _finite(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_finite(v) for v in x]
    return x
