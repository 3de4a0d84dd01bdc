"""The load case's criteria evaluated on the throws' results: one evaluator per quantity.

``EVALUATORS`` maps each quantity of ``fe_crank.io.criteria.QUANTITIES`` to the function
that finds its worst value over every throw and where it occurs; ``evaluate_criteria``
judges each limit of the load case with it (``verdict.judge``).  A criterion that cannot
be evaluated (no data for it) is an ``InputError`` naming its key: it never passes
silently.

With the whole-shaft model (``assess.shaft.ShaftAssessment``) a stress quantity is found
on both models' throws (the per-throw model, UR M53's determinate one, and the whole
shaft on its bearings) and the criterion takes the worse of the two, its location naming
the model (``model_values``: both, for the report); the main-bearing quantities are the
whole shaft's alone.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from fe_crank.assess import m53_oil_bore
from fe_crank.assess.group import STATIC_ONLY_PREFIXES, Extreme, GroupResult
from fe_crank.assess.shaft import PER_THROW, WHOLE_SHAFT, ShaftAssessment
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.assess.verdict import judge
from fe_crank.errors import InputError
from fe_crank.io.criteria import QUANTITIES, Criteria
from fe_crank.results import CriterionResult

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


def _bearing_load(bearings) -> Found:
    vals = [
        (b.with_counterweights.peak_n, f"main bearing {b.name}, {b.with_counterweights.peak_angle_deg:.0f} deg")
        for b in bearings
    ]
    return max(vals) if vals else None


def _bearing_specific_load(bearings) -> Found:
    vals = [
        (
            b.with_counterweights.specific_load_pa,
            f"main bearing {b.name} (peak / (d w), w = {b.with_counterweights.width * 1e3:.4g} mm), "
            f"{b.with_counterweights.peak_angle_deg:.0f} deg",
        )
        for b in bearings
    ]
    return max(vals) if vals else None


@dataclass(frozen=True)
class Evaluator:
    """How a quantity is found: ``find`` on the throws' results of a model (worst value,
    location) or None; ``bearings`` on the whole shaft's main bearings (quantities of the
    whole-shaft model alone, ``find`` None); ``unit`` of the value ("" for a pure number);
    ``needs_overspeed``: only defined with an overspeed."""

    find: Callable[[tuple[ThrowAssessment, ...]], Found] | None
    unit: str = ""
    needs_overspeed: bool = False
    bearings: Callable[[tuple], Found] | None = None


@dataclass(frozen=True)
class ModelValue:
    """A criterion's worst value in one model and where it occurs (``model_values``)."""

    criterion: str  # the criterion's key
    model: str  # PER_THROW or WHOLE_SHAFT
    value: float
    location: str
    governs: bool  # the criterion took this model's value


EVALUATORS: dict[str, Evaluator] = {
    "static_safety": Evaluator(_static),
    "overspeed_safety": Evaluator(_overspeed, needs_overspeed=True),
    "fatigue_safety": Evaluator(_goodman),
    "gough_pollard_safety": Evaluator(_gough_pollard),
    "counterweight_stress": Evaluator(_counterweight_stress, unit="Pa"),
    "counterweight_overspeed_stress": Evaluator(_counterweight_overspeed_stress, unit="Pa", needs_overspeed=True),
    "m53_acceptability": Evaluator(_m53),
    "unbalance_error": Evaluator(_unbalance),
    "bolt_utilisation": Evaluator(_bolts),
    "main_bearing_load": Evaluator(None, unit="N", bearings=_bearing_load),
    "main_bearing_specific_load": Evaluator(None, unit="Pa", bearings=_bearing_specific_load),
}


def _found(ev: Evaluator, throws, shaft: ShaftAssessment | None) -> list[tuple[str, float, str]]:
    """(model, worst value, location) of a quantity in each model that gives it."""
    out = []
    got = ev.find(throws) if ev.find is not None else None
    if got is not None:
        out.append((PER_THROW, *got))
    if shaft is not None:
        got = ev.find(shaft.throws) if ev.find is not None else ev.bearings(shaft.bearings) if ev.bearings else None
        if got is not None:
            out.append((WHOLE_SHAFT, *got))
    return out


def _worse(found: list[tuple[str, float, str]], sense: str) -> tuple[str, float, str]:
    """The entry with the worse value (the lower for a "min" criterion); the first of equals."""
    best = found[0]
    for f in found[1:]:
        if (f[1] < best[1]) if sense == "min" else (f[1] > best[1]):
            best = f
    return best


def model_values(
    criteria: Criteria, throws: tuple[ThrowAssessment, ...], shaft: ShaftAssessment | None
) -> tuple[ModelValue, ...]:
    """Each criterion's worst value in each model that gives it, and which one governs
    (the report's table of the two models)."""
    out = []
    for lim in criteria.limits:
        found = _found(EVALUATORS[lim.quantity], throws, shaft)
        if not found:
            continue
        worst = _worse(found, lim.sense)
        out.extend(ModelValue(lim.key, m, v, w, (m, v, w) == worst) for m, v, w in found)
    return tuple(out)


def evaluate_criteria(
    criteria: Criteria,
    throws: tuple[ThrowAssessment, ...],
    *,
    file: str = "",
    overspeed: float | None = None,
    shaft: ShaftAssessment | None = None,
) -> tuple[CriterionResult, ...]:
    """Each limit of ``criteria`` -> a verdict (module docstring); ``shaft``: the whole-shaft
    model's results, when it ran (a criterion then takes the worse of the two models)."""
    out = []
    for lim in criteria.limits:
        ev = EVALUATORS[lim.quantity]
        if ev.needs_overspeed and overspeed is None:
            raise InputError("needs operating.overspeed", file=file, key=lim.key)
        found = _found(ev, throws, shaft)
        if not found:
            missing = (
                "the whole-shaft model, which runs for an engine of several throws on one shaft or a geometry "
                "with a [shaft] section"
                if ev.find is None
                else "missing geometry, mesh group, balance requirement or bolt data"
            )
            raise InputError(
                f"cannot be evaluated: the model gives no {lim.quantity.replace('_', ' ')} ({missing})",
                file=file,
                key=lim.key,
            )
        model, value, where = _worse(found, lim.sense)
        if shaft is not None:
            where = f"{model}: {where}"
        out.append(
            judge(
                lim.key,
                lim.quantity,
                lim.sense,
                value,
                lim.value,
                unit=ev.unit,
                location=where,
                description=QUANTITIES[lim.quantity].meaning,
            )
        )
    return tuple(out)
