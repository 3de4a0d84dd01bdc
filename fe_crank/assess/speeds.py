"""A criterion over the speeds of the full-load curve: the worst load state at each
speed, the worst speed for the verdict (``assess.criteria.judge``).

``StateResults`` holds the throws' results of one load state (all cylinders firing or a
misfire case) at one speed of the sweep.  ``over_sweep`` applies a quantity's finder
(worst value and where, over the throws of one state) to every state: a speed's value is
the worst of its states (a misfire case named in its ``Location``), the criterion's the
worst speed (named in its location when the sweep has more than one), and every speed's
value is kept (``results.SpeedValue``, results.json's ``per_speed``).  Equals keep the
first: the first state at a speed, the lowest speed.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TypeVar

from fe_crank.assess.group.extremes import Wanted
from fe_crank.assess.loads import FIRING
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.io.criteria import Criteria
from fe_crank.results import Location, Sense, SpeedValue

RPM = 30.0 / math.pi

T = TypeVar("T")

#: (value, where) of a criterion's worst case, or None when the model gives none
Found = tuple[float, Location] | None
#: a located criterion: (worst value, where, its speed in rpm or None, per-speed values)
Located = tuple[float, Location, float | None, tuple[SpeedValue, ...]]


@dataclass(frozen=True)
class StateResults:
    """The throws' results in one load state at one speed of the sweep (rad/s)."""

    speed: float
    case: str  # assess.loads.FIRING or a misfire case
    throws: tuple[ThrowAssessment, ...]


def wanted_extremes(criteria: Criteria) -> Wanted:
    """The fatigue extremes the criteria need at the speeds of a sweep."""
    q = {lim.quantity for lim in criteria.limits}
    return Wanted(fatigue="fatigue_safety" in q, gough_pollard="gough_pollard_safety" in q)


def _worse(a: tuple[float, Location], b: tuple[float, Location] | None, sense: Sense) -> bool:
    """``a`` is worse than ``b`` (None: nothing yet); equals keep the first."""
    return b is None or (a[0] < b[0] if sense == "min" else a[0] > b[0])


def over_sweep(
    find: Callable[[tuple[ThrowAssessment, ...]], Found], sense: Sense, sweep: tuple[StateResults, ...]
) -> Located | None:
    """(worst value, its location with its speed and case, its speed in rpm, per-speed
    values) over the sweep, or None when no state gives a value."""
    return over_states(find, sense, [(st.speed, st.case, st.throws) for st in sweep])


def over_states(find: Callable[[T], Found], sense: Sense, states: Sequence[tuple[float, str, T]]) -> Located | None:
    """``over_sweep`` of any results per load state: (speed rad/s, case, results) each,
    ``find`` on the results (the whole shaft's main bearings, ``assess.criteria.models``)."""
    per: dict[float, tuple[float, Location]] = {}
    for speed, case, results in states:
        got = find(results)
        if got is None:
            continue
        value, where = got
        if case != FIRING:
            where = dataclasses.replace(where, case=case)
        if _worse((value, where), per.get(speed), sense):
            per[speed] = (value, where)
    if not per:
        return None
    speeds = sorted(per)
    best: tuple[float, tuple[float, Location]] | None = None
    for w in speeds:
        if _worse(per[w], best[1] if best else None, sense):
            best = (w, per[w])
    assert best is not None
    w, (value, where) = best
    loc = dataclasses.replace(where, speed_rpm=w * RPM) if len(speeds) > 1 else where
    return value, loc, w * RPM, tuple(SpeedValue(x * RPM, per[x][0], where=per[x][1]) for x in speeds)


__all__ = ["RPM", "Found", "Located", "StateResults", "wanted_extremes", "over_sweep", "over_states"]
