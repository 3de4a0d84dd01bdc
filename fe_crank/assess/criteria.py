"""The load case's criteria evaluated on the throws' results: one evaluator per quantity.

``EVALUATORS`` maps each quantity of ``fe_crank.io.criteria.QUANTITIES`` to the function
that finds its worst value over every throw and where it occurs; ``evaluate_criteria``
judges each limit of the load case with it (``verdict.judge``).  A criterion that cannot
be evaluated (no data for it) is an ``InputError`` naming its key: it never passes
silently; one the model's results must not judge (UR M53 on FE SCFs of a mesh UR M53
App. III rejects) is refused with the reason.

Over a full-load curve (``speeds.StateResults`` of every speed and load state) a
criterion that depends on speed (``Evaluator.speed == "sweep"``: the FE stress criteria,
UR M53, the counterweights and their bolted joints) is evaluated at every speed: its
value at a speed is the worst of the load states there (all cylinders firing, each
misfire case), its verdict the worst speed, reported with that speed (``per_speed``
lists them all, ``speeds.over_sweep``).  The overspeed criteria are evaluated at the
overspeed (one speed); the unbalance error does not depend on speed.  ``locate`` is that
search for one quantity; the convergence study's factor on the groups' stresses
(``check.converged``) goes through it too.  The verdict line's qualifiers
(``assess.qualifiers``) follow the location of the worst speed.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass

from fe_crank.assess import m53_oil_bore
from fe_crank.assess.cw_joint import JOINT_QUANTITIES
from fe_crank.assess.group import STATIC_ONLY_PREFIXES, Extreme, GroupResult
from fe_crank.assess.qualifiers import qualified
from fe_crank.assess.speeds import RPM, Found, StateResults, over_sweep
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.assess.verdict import judge
from fe_crank.errors import InputError
from fe_crank.io.criteria import QUANTITIES, Criteria
from fe_crank.results import CriterionResult, SpeedValue

NOT_CONFORM = "not UR M53-conform"
QUASI_STATIC_M53 = (
    "the quasi-static journal torque accepted by m53_quasi_static_torque = true: UR M53 2.2.2 asks for "
    "the torsional vibration over the speed range, which was not computed"
)


def _where(throw: str, ext: Extreme | None) -> str:
    if ext is None:
        return ""
    p = ", ".join(f"{c * 1e3:.1f}" for c in ext.point)
    s = f"throw {throw}, {ext.group}, node {ext.node} at ({p}) mm"
    if ext.angle is not None:
        s += f", {math.degrees(ext.angle):.0f} deg"
    return s


def _over_groups(
    throws: tuple[ThrowAssessment, ...],
    getter: Callable[[GroupResult], tuple[float, Extreme] | None],
    worst: str,
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
                best = (value, _where(t.name, ext))
    return best


def _cw_stress(g: GroupResult) -> tuple[float, Extreme] | None:
    ext = g.max_von_mises
    return (ext.value, ext) if g.group.startswith(STATIC_ONLY_PREFIXES) else None


def _cw_overspeed_stress(g: GroupResult) -> tuple[float, Extreme] | None:
    ext = g.max_von_mises_overspeed
    return (ext.value, ext) if ext is not None and g.group.startswith(STATIC_ONLY_PREFIXES) else None


#: the quantities read from the FE groups' results: quantity -> (getter, worst)
GROUP_QUANTITIES: dict[str, tuple[Callable[[GroupResult], tuple[float, Extreme] | None], str]] = {
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
    convergence study's, ``fe_crank.check.converged``; None: the assessed values)."""
    getter, worst = GROUP_QUANTITIES[quantity]
    return _over_groups(throws, getter, worst, factor)


def _group_evaluator(quantity: str) -> Callable[[tuple[ThrowAssessment, ...]], Found]:
    return lambda throws: over_groups(quantity, throws)


class Refused(Exception):
    """A criterion the model's results must not judge (the reason is the message)."""


def _m53(throws: tuple[ThrowAssessment, ...]) -> Found:
    for t in throws:
        for f in t.m53:
            if not f.scf_accepted:  # UR M53 App. III rejected the SCF mode's mesh: no verdict on it
                raise Refused(
                    f"throw {t.name}, {m53_oil_bore.where(f.fillet)}: the FE SCFs come from a mesh UR M53 "
                    f"App. III does not accept ({f.scf_source}); no UR M53 verdict is given on them "
                    "(refine the mesh or bring the throw into the empirical range)"
                )
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


def _joint(quantity: str) -> Callable[[tuple[ThrowAssessment, ...]], Found]:
    """The evaluator of a VDI 2230 quantity (``cw_joint.JOINT_QUANTITIES``: the
    ``JointCheck`` field and its sense): the worst bolted joint over the throws, from the
    joint checks the assessment made once (``ThrowAssessment.joints``)."""
    attr, sense = JOINT_QUANTITIES[quantity]

    def find(throws: tuple[ThrowAssessment, ...]) -> Found:
        vals = [(float(getattr(j, attr)), f"throw {t.name}, {j.name} (per bolt)") for t in throws for j in t.joints]
        if not vals:
            return None
        return min(vals, key=lambda v: v[0]) if sense == "min" else max(vals, key=lambda v: v[0])

    return find


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
    "static_safety": Evaluator(_group_evaluator("static_safety")),
    "overspeed_safety": Evaluator(_group_evaluator("overspeed_safety"), needs_overspeed=True, speed=OVERSPEED),
    "fatigue_safety": Evaluator(_group_evaluator("fatigue_safety")),
    "gough_pollard_safety": Evaluator(_group_evaluator("gough_pollard_safety")),
    "counterweight_stress": Evaluator(_group_evaluator("counterweight_stress"), unit="Pa"),
    "counterweight_overspeed_stress": Evaluator(
        _group_evaluator("counterweight_overspeed_stress"), unit="Pa", needs_overspeed=True, speed=OVERSPEED
    ),
    "m53_acceptability": Evaluator(_m53),
    "unbalance_error": Evaluator(_unbalance, speed=NO_SPEED),
    "bolt_utilisation": Evaluator(_bolts),
    **{q: Evaluator(_joint(q)) for q in JOINT_QUANTITIES},
}


def locate(
    quantity: str,
    sense: str,
    throws: tuple[ThrowAssessment, ...],
    *,
    sweep: tuple[StateResults, ...] = (),
    overspeed: float | None = None,
    factor: Callable[[str, str], float] | None = None,
) -> tuple[float, str, float | None, tuple[SpeedValue, ...]] | None:
    """(worst value, where, its speed in rpm or None, per-speed values) of ``quantity``:
    over the sweep for a speed-dependent quantity (``throws`` then unused), on ``throws``
    (the operating speed's, with the overspeed) otherwise; None when the model gives none.
    ``factor(throw, group)``: k on the groups' stresses of a group quantity (``over_groups``).
    A criterion the results must not judge raises ``Refused``."""
    ev = EVALUATORS[quantity]
    find = ev.find
    if factor is not None and quantity in GROUP_QUANTITIES:

        def find(th: tuple[ThrowAssessment, ...]) -> Found:
            return over_groups(quantity, th, factor)

    if ev.speed == SWEEP and sweep:
        return over_sweep(find, sense, sweep)
    got = find(throws)
    if got is None:
        return None
    if ev.speed == OVERSPEED and overspeed is not None:
        return got[0], got[1], overspeed * RPM, (SpeedValue(overspeed * RPM, got[0], got[1]),)
    return got[0], got[1], None, ()


def evaluate_criteria(
    criteria: Criteria,
    throws: tuple[ThrowAssessment, ...],
    *,
    file: str = "",
    overspeed: float | None = None,
    sweep: tuple[StateResults, ...] = (),
    qualifiers: dict[str, str] | None = None,
) -> tuple[CriterionResult, ...]:
    """Each limit of ``criteria`` -> a verdict (module docstring).  ``throws``: the
    operating speed's results (with the overspeed); ``sweep``: every speed and state of
    the full-load curve (the operating speed's firing state among them), () for the
    operating speed alone.  ``qualifiers``: quantity -> words its verdict line carries
    after the location (``assess.qualifiers``)."""
    qualifiers = qualifiers or {}
    out = []
    for lim in criteria.limits:
        ev = EVALUATORS[lim.quantity]
        if ev.needs_overspeed and overspeed is None:
            raise InputError("needs operating.overspeed", file=file, key=lim.key)
        try:
            found = locate(lim.quantity, lim.sense, throws, sweep=sweep, overspeed=overspeed)
        except Refused as exc:
            raise InputError(f"cannot be evaluated: {exc}", file=file, key=lim.key) from None
        if found is None:
            raise InputError(
                f"cannot be evaluated: the model gives no {lim.quantity.replace('_', ' ')} "
                "(missing geometry, mesh group, balance requirement or bolt data)",
                file=file,
                key=lim.key,
            )
        value, where, speed_rpm, per_speed = found
        meaning = QUANTITIES[lim.quantity].meaning
        if lim.quantity == "m53_acceptability" and criteria.m53_quasi_static_torque:
            meaning = f"{meaning}; {NOT_CONFORM} ({QUASI_STATIC_M53})"
        verdict = judge(
            lim.key,
            lim.quantity,
            lim.sense,
            value,
            lim.value,
            unit=ev.unit,
            location=qualified(where, qualifiers.get(lim.quantity, "")),
            description=meaning,
        )
        out.append(dataclasses.replace(verdict, per_speed=per_speed, speed_rpm=speed_rpm))
    return tuple(out)
