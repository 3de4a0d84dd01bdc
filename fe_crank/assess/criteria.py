"""The load case's criteria evaluated on the throws' results: one evaluator per quantity.

``EVALUATORS`` maps each quantity of ``fe_crank.io.criteria.QUANTITIES`` to the function
that finds its worst value over every throw and where it occurs; ``evaluate_criteria``
judges each limit of the load case with it (``verdict.judge``).  A criterion that cannot
be evaluated (no data for it) is an ``InputError`` naming its key: it never passes
silently.

Over a full-load curve (``StateResults`` of every speed and load state) a criterion
that depends on speed (``Evaluator.speed == "sweep"``) is evaluated at every speed: its
value at a speed is the worst of the load states there (all cylinders firing, each
misfire case), its verdict the worst speed, reported with that speed (``per_speed``
lists them all).  The overspeed criteria are evaluated at the overspeed (one speed);
the unbalance error does not depend on speed.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass

from fe_crank.assess import m53_oil_bore
from fe_crank.assess.extremes import Wanted
from fe_crank.assess.group import STATIC_ONLY_PREFIXES, Extreme, GroupResult
from fe_crank.assess.loads import FIRING
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.assess.verdict import judge
from fe_crank.errors import InputError
from fe_crank.io.criteria import QUANTITIES, Criteria
from fe_crank.results import CriterionResult, SpeedValue

RPM = 30.0 / math.pi
NOT_CONFORM = "not UR M53-conform"
QUASI_STATIC_M53 = (
    "the quasi-static journal torque accepted by m53_quasi_static_torque = true: UR M53 2.2.2 asks for "
    "the torsional vibration over the speed range, which was not computed"
)

#: (value, where) of a criterion's worst case, or None when the model gives none
Found = tuple[float, str] | None


def _where(throw: str, ext: Extreme | None) -> str:
    if ext is None:
        return ""
    p = ", ".join(f"{c * 1e3:.1f}" for c in ext.point)
    s = f"throw {throw}, {ext.group}, node {ext.node} at ({p}) mm"
    if ext.angle is not None:
        s += f", {math.degrees(ext.angle):.0f} deg"
    return s


def _over_groups(
    throws: tuple[ThrowAssessment, ...], getter: Callable[[GroupResult], tuple[float, Extreme] | None], worst: str
) -> Found:
    """(value, location) of the worst non-None value of getter(group) over all groups
    (the first of equals, in the throws' and groups' order)."""
    best: Found = None
    for t in throws:
        for g in t.groups:
            got = getter(g)
            if got is None:
                continue
            value, ext = got
            if best is None or (value < best[0] if worst == "min" else value > best[0]):
                best = (value, _where(t.name, ext))
    return best


def _static(throws: tuple[ThrowAssessment, ...]) -> Found:
    return _over_groups(throws, lambda g: (g.static_safety, g.max_von_mises), "min")


def _overspeed(throws: tuple[ThrowAssessment, ...]) -> Found:
    return _over_groups(
        throws,
        lambda g: (
            None
            if g.overspeed_safety is None or g.max_von_mises_overspeed is None
            else (g.overspeed_safety, g.max_von_mises_overspeed)
        ),
        "min",
    )


def _goodman(throws: tuple[ThrowAssessment, ...]) -> Found:
    return _over_groups(
        throws, lambda g: None if g.fatigue_safety is None else (g.fatigue_safety.value, g.fatigue_safety), "min"
    )


def _gough_pollard(throws: tuple[ThrowAssessment, ...]) -> Found:
    return _over_groups(
        throws,
        lambda g: None if g.gough_pollard_safety is None else (g.gough_pollard_safety.value, g.gough_pollard_safety),
        "min",
    )


def _counterweight_stress(throws: tuple[ThrowAssessment, ...]) -> Found:
    def get(g: GroupResult) -> tuple[float, Extreme] | None:
        ext = g.max_von_mises
        return (ext.value, ext) if g.group.startswith(STATIC_ONLY_PREFIXES) else None

    return _over_groups(throws, get, "max")


def _counterweight_overspeed_stress(throws: tuple[ThrowAssessment, ...]) -> Found:
    def get(g: GroupResult) -> tuple[float, Extreme] | None:
        ext = g.max_von_mises_overspeed
        return (ext.value, ext) if ext is not None and g.group.startswith(STATIC_ONLY_PREFIXES) else None

    return _over_groups(throws, get, "max")


def _m53(throws: tuple[ThrowAssessment, ...]) -> Found:
    vals = [
        (f.acceptability, f"throw {t.name}, {m53_oil_bore.where(f.fillet)} ({f.scf_source})")
        for t in throws
        for f in t.m53
    ]
    return min(vals) if vals else None


def _unbalance(throws: tuple[ThrowAssessment, ...]) -> Found:
    vals = [
        (c.unbalance_error, f"throw {t.name}, {c.name}")
        for t in throws
        for c in t.counterweights
        if c.unbalance_error is not None
    ]
    return max(vals) if vals else None


def _bolts(throws: tuple[ThrowAssessment, ...]) -> Found:
    vals = [
        (c.bolt_utilisation, f"throw {t.name}, {c.name}")
        for t in throws
        for c in t.counterweights
        if c.bolt_utilisation is not None
    ]
    return max(vals) if vals else None


#: where a quantity is evaluated: at every speed of the sweep, at the overspeed, at none
SWEEP, OVERSPEED, NO_SPEED = "sweep", "overspeed", "none"


@dataclass(frozen=True)
class Evaluator:
    """How a quantity is found on the throws' results: ``find`` gives (worst value,
    location) or None; ``unit`` of the value ("" for a pure number); ``needs_overspeed``:
    only defined with an overspeed; ``speed``: SWEEP (every speed of the full-load curve),
    OVERSPEED or NO_SPEED (independent of speed)."""

    find: Callable[[tuple[ThrowAssessment, ...]], Found]
    unit: str = ""
    needs_overspeed: bool = False
    speed: str = SWEEP


EVALUATORS: dict[str, Evaluator] = {
    "static_safety": Evaluator(_static),
    "overspeed_safety": Evaluator(_overspeed, needs_overspeed=True, speed=OVERSPEED),
    "fatigue_safety": Evaluator(_goodman),
    "gough_pollard_safety": Evaluator(_gough_pollard),
    "counterweight_stress": Evaluator(_counterweight_stress, unit="Pa"),
    "counterweight_overspeed_stress": Evaluator(
        _counterweight_overspeed_stress, unit="Pa", needs_overspeed=True, speed=OVERSPEED
    ),
    "m53_acceptability": Evaluator(_m53),
    "unbalance_error": Evaluator(_unbalance, speed=NO_SPEED),
    "bolt_utilisation": Evaluator(_bolts),
}


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


def _worse(a: tuple[float, str], b: tuple[float, str] | None, sense: str) -> bool:
    """``a`` is worse than ``b`` (None: nothing yet); equals keep the first."""
    return b is None or (a[0] < b[0] if sense == "min" else a[0] > b[0])


def _over_sweep(ev: Evaluator, sense: str, sweep: tuple[StateResults, ...]):
    """(worst value, its location with its speed and case, its speed in rpm, per-speed
    values) over the sweep, or None when no state gives a value."""
    per: dict[float, tuple[float, str]] = {}
    for st in sweep:
        got = ev.find(st.throws)
        if got is None:
            continue
        value, where = got
        if st.case != FIRING:
            where = f"{where}; {st.case}" if where else st.case
        if _worse((value, where), per.get(st.speed), sense):
            per[st.speed] = (value, where)
    if not per:
        return None
    speeds = sorted(per)
    best = None
    for w in speeds:
        if _worse(per[w], best[1] if best else None, sense):
            best = (w, per[w])
    w, (value, where) = best
    many = len(speeds) > 1
    loc = f"{where}; {w * RPM:.0f} rpm" if many and where else where
    return value, loc, w * RPM, tuple(SpeedValue(x * RPM, per[x][0], per[x][1]) for x in speeds)


def evaluate_criteria(
    criteria: Criteria,
    throws: tuple[ThrowAssessment, ...],
    *,
    file: str = "",
    overspeed: float | None = None,
    sweep: tuple[StateResults, ...] = (),
) -> tuple[CriterionResult, ...]:
    """Each limit of ``criteria`` -> a verdict (module docstring).  ``throws``: the
    operating speed's results (with the overspeed); ``sweep``: every speed and state of
    the full-load curve (the operating speed's firing state among them), () for the
    operating speed alone."""
    out = []
    for lim in criteria.limits:
        ev = EVALUATORS[lim.quantity]
        if ev.needs_overspeed and overspeed is None:
            raise InputError("needs operating.overspeed", file=file, key=lim.key)
        speed_rpm, per_speed = None, ()
        if ev.speed == SWEEP and sweep:
            found = _over_sweep(ev, lim.sense, sweep)
            got = None if found is None else found[:2]
            if found is not None:
                speed_rpm, per_speed = found[2], found[3]
        else:
            got = ev.find(throws)
            if got is not None and ev.speed == OVERSPEED and overspeed is not None:
                speed_rpm = overspeed * RPM
                per_speed = (SpeedValue(speed_rpm, got[0], got[1]),)
        if got is None:
            raise InputError(
                f"cannot be evaluated: the model gives no {lim.quantity.replace('_', ' ')} "
                "(missing geometry, mesh group, balance requirement or bolt data)",
                file=file,
                key=lim.key,
            )
        value, where = got
        meaning = QUANTITIES[lim.quantity].meaning
        if lim.quantity == "m53_acceptability" and criteria.m53_quasi_static_torque:
            where = f"{NOT_CONFORM}: {where}"
            meaning = f"{meaning}; {NOT_CONFORM} ({QUASI_STATIC_M53})"
        verdict = judge(
            lim.key,
            lim.quantity,
            lim.sense,
            value,
            lim.value,
            unit=ev.unit,
            location=where,
            description=meaning,
        )
        out.append(dataclasses.replace(verdict, per_speed=per_speed, speed_rpm=speed_rpm))
    return tuple(out)
