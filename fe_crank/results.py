"""Result types shared by every layer (plain, frozen, picklable data).

``CriterionResult`` is the verdict on one criterion (``fe_crank.assess.criteria.verdict.judge``
makes the assessment's; ``fe_crank.pipeline.verdict`` collects every stage's);
``StageTime`` one stage's wall time; ``Location`` where a criterion's value occurs (its
words are made in ``fe_crank.report.locations``).  The record of a whole case, ``CaseResult``, is in
``fe_crank.records``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Final, Literal

#: a load case's outcome: every criterion passed, one failed, or it could not be assessed
Status = Literal["pass", "fail", "error"]
STATUS_PASS: Final = "pass"
STATUS_FAIL: Final = "fail"
STATUS_ERROR: Final = "error"
#: a criterion's sense: its value must not fall below ("min", a safety factor) or rise
#: above ("max", a stress) its limit
Sense = Literal["min", "max"]
SENSES: dict[str, Sense] = {"min": "min", "max": "max"}


#: what a ``Location`` points at: an FE node group's node, a UR M53 fillet (or the oil-bore
#: outlet), a counterweight, a bolted joint (per bolt), a main bearing (its peak load, or
#: that peak over d w), a hot spot of the convergence study
LOCATION_KINDS = ("group", "m53", "counterweight", "joint", "bearing", "bearing_specific", "hot_spot")


@dataclass(frozen=True)
class Location:
    """Where a criterion's value occurs, as data (the words: ``report.locations``).

    ``model``: the model that gave it ("" when the case has one model; else
    ``assess.shaft.PER_THROW`` or ``WHOLE_SHAFT``); ``throw``: the engine throw (or the FE
    model key); ``group``: the FE node group, UR M53 fillet ("pin", "journal", "oil_bore"),
    counterweight, joint, main bearing, or hot-spot surface the value is on; ``node`` and
    ``point`` (m, the throw frame): the node of an FE group; ``angle_deg``: the cycle angle
    of the state (None: no angle); ``case``: the load state ("" every cylinder firing, else
    the misfire case); ``speed_rpm``: the speed, set when the criterion spans several
    speeds; ``detail``: what the value rests on (UR M53's SCF source, a hot spot's load
    set); ``width``: a main bearing's width (m, the specific load's); ``levels``: a hot
    spot's assessed and finest fillet divisions (r/n)."""

    kind: str = "group"
    throw: str = ""
    group: str = ""
    node: int | None = None
    point: tuple[float, float, float] | None = None
    angle_deg: float | None = None
    case: str = ""
    speed_rpm: float | None = None
    model: str = ""
    detail: str = ""
    width: float | None = None
    levels: tuple[float, float] | None = None


@dataclass(frozen=True)
class SpeedValue:
    """A criterion's worst value at one speed of the full-load curve (or at the
    overspeed), rpm, and where it occurs (``where``; ``location``: its words, set by the
    verdict)."""

    speed_rpm: float
    value: float
    location: str = ""
    where: Location | None = None


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
    speed); ``speed_rpm`` the speed of ``value`` (None: no speed).  ``where``: where the
    value occurs (``Location``); ``remarks``: the words the verdict line carries after it
    (the convergence study's factor, the qualifiers of ``assess.criteria.qualifiers``);
    ``location``: the verdict line's words of both, made by the verdict
    (``fe_crank.pipeline.verdict.decide`` with ``fe_crank.report.locations``).
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
    sense: Sense | Literal[""] = ""  # "" only where no criterion was judged
    per_speed: tuple[SpeedValue, ...] = ()
    speed_rpm: float | None = None
    where: Location | None = None
    remarks: tuple[str, ...] = ()


@dataclass(frozen=True)
class StageTime:
    stage: str
    seconds: float
