"""The load case's criteria evaluated on the throws' results: one evaluator per quantity.

``EVALUATORS`` maps each quantity of ``fe_crank.io.criteria.QUANTITIES`` to the function
that finds its worst value over every throw and where it occurs (a ``results.Location``);
``judge_criteria`` judges each limit of the load case with it (``verdict.judge``).  A criterion that cannot
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
(``assess.refinement``) goes through it, once, when the study ran (``judge_criteria``'s
``factors``; the study's own ``mesh_convergence`` criterion joins the criteria then).  The
verdict line's remarks -- the factor, the qualifiers (``assess.criteria.qualifiers``) -- follow the
location (``results.Location``) of the worst speed.  With the whole-shaft
model a criterion takes the worse of the two models at each speed -- the whole shaft
assessed at every speed and load state of the sweep as the per-throw model is
(``ShaftAssessment.states``) -- and the main-bearing quantities are the whole shaft's
(``assess.criteria.models``).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from fe_crank.assess import refinement
from fe_crank.assess.criteria.finders import (
    GROUP_QUANTITIES,
    Refused,
    bolts,
    group_finder,
    joint_finder,
    m53_acceptability,
    over_groups,
    unbalance,
)
from fe_crank.assess.criteria.models import (
    BEARING_FINDERS,
    ModelValue,
    combined,
    model_pair,
    no_throw_value,
    whole_shaft,
)
from fe_crank.assess.criteria.verdict import judge
from fe_crank.assess.joint_criteria import JOINT_QUANTITIES
from fe_crank.assess.oil_film import FILM_FINDERS
from fe_crank.assess.refinement import SCALED, Refinement, StudyFactors
from fe_crank.assess.shaft import ShaftAssessment
from fe_crank.assess.speeds import RPM, Found, Located, StateResults, over_sweep
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.errors import InputError
from fe_crank.io.criteria import QUANTITIES, Criteria
from fe_crank.results import CriterionResult, Sense, SpeedValue

NOT_CONFORM = "not UR M53-conform"
QUASI_STATIC_M53 = (
    "the quasi-static journal torque accepted by m53_quasi_static_torque = true: UR M53 2.2.2 asks for "
    "the torsional vibration over the speed range, which was not computed"
)


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
    "static_safety": Evaluator(group_finder("static_safety")),
    "overspeed_safety": Evaluator(group_finder("overspeed_safety"), needs_overspeed=True, speed=OVERSPEED),
    "fatigue_safety": Evaluator(group_finder("fatigue_safety")),
    "gough_pollard_safety": Evaluator(group_finder("gough_pollard_safety")),
    "counterweight_stress": Evaluator(group_finder("counterweight_stress"), unit="Pa"),
    "counterweight_overspeed_stress": Evaluator(
        group_finder("counterweight_overspeed_stress"), unit="Pa", needs_overspeed=True, speed=OVERSPEED
    ),
    "m53_acceptability": Evaluator(m53_acceptability),
    "unbalance_error": Evaluator(unbalance, speed=NO_SPEED),
    "bolt_utilisation": Evaluator(bolts),
    **{q: Evaluator(joint_finder(q)) for q in JOINT_QUANTITIES},
    "main_bearing_load": Evaluator(no_throw_value, unit="N"),  # the whole shaft's (shaft_criteria)
    "main_bearing_specific_load": Evaluator(no_throw_value, unit="Pa"),
    "oil_film_thickness": Evaluator(no_throw_value, unit="m"),  # the whole shaft's film (assess.oil_film)
    "oil_film_pressure": Evaluator(no_throw_value, unit="Pa"),
}


def _parts(
    quantity: str,
    sense: Sense,
    throws: tuple[ThrowAssessment, ...],
    sweep: tuple[StateResults, ...],
    overspeed: float | None,
    factor: Callable[[str, str], float] | None,
    shaft: ShaftAssessment | None,
) -> tuple[Located | None, Located | None]:
    """``locate`` in the per-throw model and in the whole shaft (None without it)."""
    ev = EVALUATORS[quantity]
    find = ev.find
    if factor is not None and quantity in GROUP_QUANTITIES:

        def find(th: tuple[ThrowAssessment, ...]) -> Found:
            return over_groups(quantity, th, factor)

    per: Located | None
    if ev.speed == SWEEP and sweep:
        per = over_sweep(find, sense, sweep)
    else:
        got = find(throws)
        if got is None:
            per = None
        elif ev.speed == OVERSPEED and overspeed is not None:
            per = got[0], got[1], overspeed * RPM, (SpeedValue(overspeed * RPM, got[0], where=got[1]),)
        else:
            per = got[0], got[1], None, ()
    if shaft is None:
        return per, None
    # the main bearings' loads and films are the whole shaft's own, over its bearing sweep
    if (
        ev.speed == SWEEP
        and sweep
        and shaft.states
        and quantity not in BEARING_FINDERS
        and quantity not in FILM_FINDERS
    ):
        return per, over_sweep(find, sense, shaft.states)  # the whole shaft at every speed, as the per-throw model
    at = shaft.speed * RPM if ev.speed == SWEEP and shaft.speed is not None and sweep else None
    if ev.speed == OVERSPEED and overspeed is not None:
        at = overspeed * RPM
    return per, whole_shaft(quantity, sense, find, shaft, speed_rpm=at)


def locate(
    quantity: str,
    sense: Sense,
    throws: tuple[ThrowAssessment, ...],
    *,
    sweep: tuple[StateResults, ...] = (),
    overspeed: float | None = None,
    factor: Callable[[str, str], float] | None = None,
    shaft: ShaftAssessment | None = None,
) -> Located | None:
    """(worst value, where, its speed in rpm or None, per-speed values) of ``quantity``:
    over the sweep for a speed-dependent quantity (``throws`` then unused), on ``throws``
    (the operating speed's, with the overspeed) otherwise; None when the model gives none.
    ``factor(throw, group)``: k on the groups' stresses of a group quantity (``over_groups``;
    the whole shaft's throws are meshed as the per-throw model's, the same k, the largest over
    both models' load sets, ``fe.shaft.refinement``).  ``shaft``:
    the worse of both models, located by model (``shaft_criteria.combined``).  A criterion
    the results must not judge raises ``Refused``."""
    per, whole = _parts(quantity, sense, throws, sweep, overspeed, factor, shaft)
    return per if shaft is None else combined(per, whole, sense)


def _factor_of(quantity: str, factors: StudyFactors | None) -> Callable[[str, str], float] | None:
    return factors.factor if factors is not None and quantity in SCALED else None


def model_values(
    criteria: Criteria,
    throws: tuple[ThrowAssessment, ...],
    shaft: ShaftAssessment,
    *,
    sweep: tuple[StateResults, ...] = (),
    overspeed: float | None = None,
    factors: StudyFactors | None = None,
) -> tuple[ModelValue, ...]:
    """Each criterion's worst value in each model that gives it, and which one governs
    (the report's table of the two models), at the convergence study's ``factors`` as the
    criteria are."""
    out: list[ModelValue] = []
    for lim in criteria.limits:
        try:
            per, whole = _parts(
                lim.quantity, lim.sense, throws, sweep, overspeed, _factor_of(lim.quantity, factors), shaft
            )
        except Refused:
            continue
        out.extend(model_pair(lim.key, per, whole, lim.sense))
    return tuple(out)


@dataclass(frozen=True)
class Judged:
    """The load case's criteria judged (``judge_criteria``), and the convergence study's
    factor each FE stress criterion was taken at (none without the study)."""

    criteria: tuple[CriterionResult, ...]
    refinements: tuple[Refinement, ...] = ()


def judge_criteria(
    criteria: Criteria,
    throws: tuple[ThrowAssessment, ...],
    *,
    file: str = "",
    overspeed: float | None = None,
    sweep: tuple[StateResults, ...] = (),
    qualifiers: dict[str, str] | None = None,
    shaft: ShaftAssessment | None = None,
    factors: StudyFactors | None = None,
) -> Judged:
    """Each limit of ``criteria`` -> a verdict (module docstring); ``shaft``: the whole-shaft
    model's results, when it ran (each criterion the worse of the two models).  ``throws``: the
    operating speed's results (with the overspeed); ``sweep``: every speed and state of
    the full-load curve (the operating speed's firing state among them), () for the
    operating speed alone.  ``qualifiers``: quantity -> words its verdict line carries
    after the location (``assess.criteria.qualifiers``).  ``factors``: the hot-spot convergence
    study's, on the FE stress criteria (``assess.refinement``; None: the assessed mesh's
    values)."""
    qualifiers = qualifiers or {}
    out, made = [], []
    for lim in criteria.limits:
        ev = EVALUATORS[lim.quantity]
        if ev.needs_overspeed and overspeed is None:
            raise InputError("needs operating.overspeed", file=file, key=lim.key)
        try:
            found = locate(
                lim.quantity,
                lim.sense,
                throws,
                sweep=sweep,
                overspeed=overspeed,
                factor=_factor_of(lim.quantity, factors),
                shaft=shaft,
            )
        except Refused as exc:
            raise InputError(f"cannot be evaluated: {exc}", file=file, key=lim.key) from None
        if found is None:
            missing = (
                "the whole-shaft model, which runs for a parametric geometry of an engine with several throws on one "
                "shaft or with a [shaft] section"
                if ev.find is no_throw_value
                else "missing geometry, mesh group, balance requirement or bolt data"
            )
            raise InputError(
                f"cannot be evaluated: the model gives no {lim.quantity.replace('_', ' ')} ({missing})",
                file=file,
                key=lim.key,
            )
        value, where, speed_rpm, per_speed = found
        meaning = QUANTITIES[lim.quantity].meaning
        if lim.quantity == "m53_acceptability" and criteria.m53_quasi_static_torque:
            meaning = f"{meaning}; {NOT_CONFORM} ({QUASI_STATIC_M53})"
        remarks = []
        r = factors.refinement(lim.key, where) if factors is not None and lim.quantity in SCALED else None
        if r is not None:
            made.append(r)
            remarks.append(r.words)
        if qualifiers.get(lim.quantity):
            remarks.append(qualifiers[lim.quantity])
        verdict = judge(lim.key, lim.quantity, lim.sense, value, lim.value, unit=ev.unit, description=meaning)
        out.append(
            dataclasses.replace(verdict, per_speed=per_speed, speed_rpm=speed_rpm, where=where, remarks=tuple(remarks))
        )
    if factors is not None and factors.studies:
        out.append(refinement.criterion(factors.studies))
    return Judged(tuple(out), tuple(made))


def evaluate_criteria(
    criteria: Criteria, throws: tuple[ThrowAssessment, ...], **kwargs: Any
) -> tuple[CriterionResult, ...]:
    """The criteria of ``judge_criteria`` (its keywords) without the factors' record."""
    return judge_criteria(criteria, throws, **kwargs).criteria
