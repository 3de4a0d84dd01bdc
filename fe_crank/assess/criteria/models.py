"""The criteria with the whole-shaft model beside the per-throw one (``assess.criteria.judge``).

With the whole-shaft model (``assess.shaft.ShaftAssessment``) a stress quantity is found
on both models' throws, each at every speed and load state of the full-load sweep (the
whole shaft's ``states``, assessed as the per-throw model's, with its pruning; its
overspeed cycles for an overspeed quantity).  At each speed the criterion's value is the
worse of the models there, its location naming the model; the verdict is the worst speed,
as without the whole shaft (``speeds.over_sweep``).  The main-bearing quantities are the
whole shaft's alone: the peak bearing load with counterweights, and that peak over the
projected area d w, at every speed and load state of the sweep
(``ShaftAssessment.sweep``).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass

from fe_crank.assess.oil_film import FILM_FINDERS, film_criterion
from fe_crank.assess.shaft import PER_THROW, WHOLE_SHAFT, ShaftAssessment
from fe_crank.assess.speeds import Found, Located, over_states
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.fe.shaft.cycle import BearingLoads
from fe_crank.fe.shaft.whole_shaft import BearingResult
from fe_crank.results import Location, Sense, SpeedValue


def no_throw_value(throws: tuple[ThrowAssessment, ...]) -> Found:
    """The per-throw model gives no main-bearing load (the whole shaft's alone)."""
    return None


def _law(loads: BearingLoads) -> str:
    """ "bearing law <law>" when the loads name theirs (the governing law of the envelope)."""
    return f"bearing law {loads.law}" if loads.law else ""


def _order(found: tuple[float, Location]) -> tuple[float, str, float]:
    """By value, equals by the bearing's name and angle (the last of equals: ``max``)."""
    v, loc = found
    return v, loc.group, loc.angle_deg if loc.angle_deg is not None else 0.0


def _bearing_load(bearings: tuple[BearingResult, ...]) -> Found:
    vals = [
        (
            b.with_counterweights.peak_n,
            Location(
                "bearing",
                group=b.name,
                angle_deg=b.with_counterweights.peak_angle_deg,
                detail=_law(b.with_counterweights),
            ),
        )
        for b in bearings
    ]
    return max(vals, key=_order) if vals else None


def _bearing_specific_load(bearings: tuple[BearingResult, ...]) -> Found:
    vals = [
        (
            b.with_counterweights.specific_load_pa,
            Location(
                "bearing_specific",
                group=b.name,
                angle_deg=b.with_counterweights.peak_angle_deg,
                width=b.with_counterweights.width,
                detail=_law(b.with_counterweights),
            ),
        )
        for b in bearings
    ]
    return max(vals, key=_order) if vals else None


#: the main bearings' quantities: quantity -> its finder over the bearings of one state
BEARING_FINDERS: dict[str, Callable[[tuple[BearingResult, ...]], Found]] = {
    "main_bearing_load": _bearing_load,
    "main_bearing_specific_load": _bearing_specific_load,
}


def _worse(a: float, b: float, sense: Sense) -> bool:
    return a < b if sense == "min" else a > b


def _labelled(model: str, where: Location | None) -> Location:
    return dataclasses.replace(where if where is not None else Location(), model=model)


def _label(found: Located, model: str) -> Located:
    v, w, s, per = found
    return v, _labelled(model, w), s, tuple(dataclasses.replace(x, where=_labelled(model, x.where)) for x in per)


def whole_shaft(
    quantity: str,
    sense: Sense,
    find: Callable[[tuple[ThrowAssessment, ...]], Found],
    shaft: ShaftAssessment,
    *,
    speed_rpm: float | None,
) -> Located | None:
    """The whole shaft's worst value of ``quantity``: a main-bearing quantity over the sweep
    of the bearings' states (the operating speed's when no sweep), else ``find`` on its
    throws at the one speed ``speed_rpm`` (None: a quantity of no speed)."""
    if quantity in FILM_FINDERS:  # the hydrodynamic bearings' oil film (assess.oil_film)
        return film_criterion(quantity, sense, shaft.film) if shaft.film else None
    if quantity in BEARING_FINDERS:
        f = BEARING_FINDERS[quantity]
        if shaft.sweep:
            return over_states(f, sense, [(s.speed, s.case, s.bearings) for s in shaft.sweep])
        got = f(shaft.bearings)
    else:
        got = find(shaft.throws)
    if got is None:
        return None
    per = (SpeedValue(speed_rpm, got[0], where=got[1]),) if speed_rpm is not None else ()
    return got[0], got[1], speed_rpm, per


def combined(per_throw: Located | None, whole: Located | None, sense: Sense) -> Located | None:
    """The criterion from both models (module doc): at each speed the worse of the two (the
    per-throw model's on equals), the verdict the worst speed (the lowest of equals)."""
    if whole is None:
        return None if per_throw is None else _label(per_throw, PER_THROW)
    if per_throw is None:
        return _label(whole, WHOLE_SHAFT)
    a, b = _label(per_throw, PER_THROW), _label(whole, WHOLE_SHAFT)
    if not a[3] or not b[3]:  # a value of no speed: the worse of the two
        return b if _worse(b[0], a[0], sense) else a
    entries = {x.speed_rpm: x for x in a[3]}
    for x in b[3]:
        key = next((k for k in entries if math.isclose(k, x.speed_rpm, rel_tol=1e-9)), x.speed_rpm)
        if key not in entries or _worse(x.value, entries[key].value, sense):
            entries[key] = SpeedValue(key, x.value, where=x.where)
    per = tuple(entries[k] for k in sorted(entries))
    best = per[0]
    for x in per[1:]:
        if _worse(x.value, best.value, sense):
            best = x
    assert best.where is not None
    loc = dataclasses.replace(best.where, speed_rpm=best.speed_rpm) if len(per) > 1 else best.where
    return best.value, loc, best.speed_rpm, per


@dataclass(frozen=True)
class ModelValue:
    """A criterion's worst value in one model and where it occurs (``model_values``)."""

    criterion: str  # the criterion's key
    model: str  # PER_THROW or WHOLE_SHAFT
    value: float
    where: Location
    governs: bool  # the criterion took this model's value


def model_pair(key: str, per_throw: Located | None, whole: Located | None, sense: Sense) -> tuple[ModelValue, ...]:
    """The worst value of criterion ``key`` in each model that gives it, and which governs."""
    both = combined(per_throw, whole, sense)
    if both is None:
        return ()
    out = []
    for model, found in ((PER_THROW, per_throw), (WHOLE_SHAFT, whole)):
        if found is not None:
            out.append(ModelValue(key, model, found[0], found[1], both[1].model == model))
    return tuple(out)


__all__ = ["BEARING_FINDERS", "ModelValue", "combined", "model_pair", "no_throw_value", "whole_shaft"]
