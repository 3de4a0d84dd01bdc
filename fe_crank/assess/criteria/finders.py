"""What each quantity of the criteria is found from on the throws' results (worst value
and where, ``speeds.Found``), for ``assess.criteria.judge.EVALUATORS``: the FE groups' safety
factors and stresses (``over_groups``, with the convergence study's factor on a group's
stresses), UR M53's acceptability (refused on FE SCFs of a mesh UR M53 App. III rejects),
the counterweights' unbalance error and bolt utilisation, the bolted joints (VDI 2230).
"""

from __future__ import annotations

import math
from collections.abc import Callable

from fe_crank.assess.group.assessment import Extreme, GroupResult, of_counterweight
from fe_crank.assess.joint_criteria import JOINT_QUANTITIES
from fe_crank.assess.speeds import Found
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.results import Location, Sense
from fe_crank.rules.m53 import oil_bore as m53_oil_bore


def where(throw: str, ext: Extreme) -> Location:
    """The location of an FE group's extreme on ``throw`` (its node, point, cycle angle)."""
    return Location(
        "group",
        throw,
        ext.group,
        node=ext.node,
        point=(float(ext.point[0]), float(ext.point[1]), float(ext.point[2])),
        angle_deg=None if ext.angle is None else math.degrees(ext.angle),
    )


def _over_groups(
    throws: tuple[ThrowAssessment, ...],
    getter: Callable[[GroupResult], tuple[float, Extreme] | None],
    worst: Sense,
    factor: Callable[[str, str], float] | None = None,
) -> Found:
    """(value, location) of the worst non-None value of getter(group) over all groups
    (the first of equals, in the throws' and groups' order).  ``factor(throw, group)``: a
    factor k >= 1 on the group's stresses (``over_groups``), a safety ("min") divided by it,
    a stress ("max") multiplied."""
    best: Found = None
    for t in throws:
        for g in t.groups:
            got = getter(g)
            if got is None:
                continue
            value, ext = got
            if factor is not None:
                k = factor(t.name, g.group)
                value = value / k if worst == "min" else value * k
            if best is None or (value < best[0] if worst == "min" else value > best[0]):
                best = (value, where(t.name, ext))
    return best


def _cw_stress(g: GroupResult) -> tuple[float, Extreme] | None:
    ext = g.max_von_mises
    return (ext.value, ext) if of_counterweight(g.group) else None


def _cw_overspeed_stress(g: GroupResult) -> tuple[float, Extreme] | None:
    ext = g.max_von_mises_overspeed
    return (ext.value, ext) if ext is not None and of_counterweight(g.group) else None


#: the quantities read from the FE groups' results: quantity -> (getter, worst)
GROUP_QUANTITIES: dict[str, tuple[Callable[[GroupResult], tuple[float, Extreme] | None], Sense]] = {
    "static_safety": (lambda g: (g.static_safety, g.max_von_mises), "min"),
    "overspeed_safety": (
        lambda g: (
            None
            if g.overspeed_safety is None or g.max_von_mises_overspeed is None
            else (g.overspeed_safety, g.max_von_mises_overspeed)
        ),
        "min",
    ),
    "fatigue_safety": (
        lambda g: None if g.fatigue_safety is None else (g.fatigue_safety.value, g.fatigue_safety),
        "min",
    ),
    "gough_pollard_safety": (
        lambda g: None if g.gough_pollard_safety is None else (g.gough_pollard_safety.value, g.gough_pollard_safety),
        "min",
    ),
    "counterweight_stress": (_cw_stress, "max"),
    "counterweight_overspeed_stress": (_cw_overspeed_stress, "max"),
}


def over_groups(
    quantity: str, throws: tuple[ThrowAssessment, ...], factor: Callable[[str, str], float] | None = None
) -> Found:
    """The worst value of a group quantity (``GROUP_QUANTITIES``) over every throw's groups
    and where it occurs; ``factor(throw, group)``: k on each group's stresses (the
    convergence study's, ``fe_crank.assess.refinement``; None: the assessed values)."""
    getter, worst = GROUP_QUANTITIES[quantity]
    return _over_groups(throws, getter, worst, factor)


def _value(found: tuple[float, Location]) -> tuple[float, str, str, str]:
    """Order of (value, location): by value, equals by the throw, the part and what the value
    rests on (as their words sort: the last of equals for a maximum, the first for a minimum)."""
    v, loc = found
    part = m53_oil_bore.where(loc.group) if loc.kind == "m53" else loc.group
    return v, loc.throw, part, loc.detail


def group_finder(quantity: str) -> Callable[[tuple[ThrowAssessment, ...]], Found]:
    return lambda throws: over_groups(quantity, throws)


class Refused(Exception):
    """A criterion the model's results must not judge (the reason is the message)."""


def m53_acceptability(throws: tuple[ThrowAssessment, ...]) -> Found:
    for t in throws:
        for f in t.m53:
            if not f.scf_accepted:  # UR M53 App. III rejected the SCF mode's mesh: no verdict on it
                raise Refused(
                    f"throw {t.name}, {m53_oil_bore.where(f.fillet)}: the FE SCFs come from a mesh UR M53 "
                    f"App. III does not accept ({f.scf_source}); no UR M53 verdict is given on them "
                    "(refine the mesh or bring the throw into the empirical range)"
                )
    vals = [(f.acceptability, Location("m53", t.name, f.fillet, detail=f.scf_source)) for t in throws for f in t.m53]
    return min(vals, key=_value) if vals else None


def unbalance(throws: tuple[ThrowAssessment, ...]) -> Found:
    vals = [
        (c.unbalance_error, Location("counterweight", t.name, c.name))
        for t in throws
        for c in t.counterweights
        if c.unbalance_error is not None
    ]
    return max(vals, key=_value) if vals else None


def bolts(throws: tuple[ThrowAssessment, ...]) -> Found:
    vals = [
        (c.bolt_utilisation, Location("counterweight", t.name, c.name))
        for t in throws
        for c in t.counterweights
        if c.bolt_utilisation is not None
    ]
    return max(vals, key=_value) if vals else None


def joint_finder(quantity: str) -> Callable[[tuple[ThrowAssessment, ...]], Found]:
    """The evaluator of a VDI 2230 quantity (``joint_criteria.JOINT_QUANTITIES``: the
    ``JointCheck`` field and its sense): the worst bolted joint over the throws, from the
    joint checks the assessment made once (``ThrowAssessment.joints``)."""
    attr, sense = JOINT_QUANTITIES[quantity]

    def find(throws: tuple[ThrowAssessment, ...]) -> Found:
        vals = [(float(getattr(j, attr)), Location("joint", t.name, j.name)) for t in throws for j in t.joints]
        if not vals:
            return None
        return min(vals, key=lambda v: v[0]) if sense == "min" else max(vals, key=lambda v: v[0])

    return find
