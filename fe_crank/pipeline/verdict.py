"""The verdict of one load case, built in one place (``decide``) from every criterion.

The criteria are the assessment's (``fe_crank.assess.criteria.judge``: both models, every speed,
the FE stress criteria at the hot-spot convergence study's factors and its
``mesh_convergence`` criterion when it ran, ``assess.refinement``); the verdict only
aggregates them and writes each one's location in words (``report.locations``, the verdict
line's).  A case passes when every criterion passes, fails when one does not, and is an
error when a stage stopped, when a criterion came out NaN, or when nothing was checked.
"""

from __future__ import annotations

from dataclasses import dataclass

from fe_crank.outputs import CaseOutputs
from fe_crank.report.locations import with_words
from fe_crank.results import STATUS_ERROR, STATUS_FAIL, STATUS_PASS, CriterionResult, Status


@dataclass(frozen=True)
class Verdict:
    """``status`` pass | fail | error, the criteria it was decided on, and the message of
    an error ("" otherwise)."""

    status: Status
    criteria: tuple[CriterionResult, ...]
    message: str = ""


def _nan_criterion(criteria: tuple[CriterionResult, ...]) -> str:
    """The message for a criterion whose value, limit or margin is NaN ("" for none): an
    error of the case, never a verdict or a JSON value (an infinite safety factor of an
    unloaded part is legitimate and is kept)."""
    for c in criteria:
        if any(x != x for x in (c.value, c.limit, c.margin)):
            return f"criterion {c.name}: the computation gave NaN (not a number); the case is not assessed"
    return ""


def decide(out: CaseOutputs, error: str = "") -> Verdict:
    """The verdict of a case from its stages' outputs; ``error``: the message of the stage
    that stopped ("" when every stage ran)."""
    if error:
        return Verdict(STATUS_ERROR, (), error)
    a = out.assessment
    criteria = tuple(with_words(c) for c in a.criteria) if a is not None else ()
    nan = _nan_criterion(criteria)
    if nan:
        return Verdict(STATUS_ERROR, (), nan)
    if not criteria:
        return Verdict(STATUS_ERROR, (), "the assessment returned no criteria: nothing was checked")
    return Verdict(STATUS_PASS if all(c.passed for c in criteria) else STATUS_FAIL, criteria)
