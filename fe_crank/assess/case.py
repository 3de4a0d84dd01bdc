"""``assess_case``: the assessment of one load case, every throw, its criteria.

It takes what the earlier stages made (typed, ``AssessInputs``): the engine cycles
(operating and overspeed, ``fe_crank.mechanism.cycles``; the journal torques with the
vibratory torque when the torsional stage ran), the balance design, the counterweights'
CAD mass properties (geometry stage), the FE unit solutions and, where UR M53's empirical
SCFs are out of range, the SCF mode's result (FE stage), the whole-shaft stage's model (its throws assessed here by
the per-throw model's code, ``assess.shaft``), the hot-spot convergence study (its factors
on the FE stress criteria, ``assess.refinement``).  It is the one owner of the assessment:
both models, every speed and load state, every criterion judged once; it computes nothing
any other stage owns.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

from fe_crank.assess.criteria.judge import NOT_CONFORM, QUASI_STATIC_M53, judge_criteria, model_values
from fe_crank.assess.criteria.models import ModelValue
from fe_crank.assess.criteria.qualifiers import criterion_qualifiers
from fe_crank.assess.group.nodes import ASSESSED_BOUNDARIES, assessed_groups, unit_stresses
from fe_crank.assess.inputs import AssessInputs
from fe_crank.assess.joint_criteria import (
    JOINT_QUANTITIES,
    has_joints,
    joint_qualifiers,
    unchecked_joints,
    with_default_limits,
)
from fe_crank.assess.loads import AssessedLoads
from fe_crank.assess.recovery import recovery_notes, recovery_ratios
from fe_crank.assess.refinement import Refinement, StudyFactors
from fe_crank.assess.shaft import ShaftAssessment, assess_shaft_throws, governing
from fe_crank.assess.speeds import StateResults, wanted_extremes
from fe_crank.assess.state_throws import assess_state, places_of, state_dynamics
from fe_crank.assess.states import ModelStates, model_states
from fe_crank.assess.superpose import UnitStresses
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.assess.workers import Scratch, run_blocks
from fe_crank.fe.throw.unit_cases import UnitSolutions
from fe_crank.io.material import Material
from fe_crank.mechanism.misfire import READING
from fe_crank.notes import ASSUMPTION, WARNING, Note, grouped
from fe_crank.results import CriterionResult
from fe_crank.rules.m53 import oil_bore as m53_oil_bore
from fe_crank.rules.m53.basis import M53Basis, m53_basis
from fe_crank.throw_scope import throws_of

#: 1.1: optional provenance and warnings (written by the report); 1.2: warnings name their throws;
#: 1.3: provenance.cad, criteria per speed; 1.4: bolted joints (VDI 2230), sigma_add per group;
#: 1.5: the whole-shaft model (``whole_shaft``: main-bearing loads at every speed, web moments) and
#: each criterion's value in each model (``criteria_by_model``)
SCHEMA_VERSION = "1.6"


@dataclass(frozen=True)
class Assessment:
    """Everything the assessment found for one load case."""

    case: str
    source_file: str
    speed: float  # rad/s
    overspeed: float | None
    material: Material
    throws: tuple[ThrowAssessment, ...]
    criteria: tuple[CriterionResult, ...]
    notes: tuple[Note, ...] = field(default_factory=tuple)  # the assessment's assumptions
    states: tuple[ModelStates, ...] = ()  # per FE model: the hot spot, overspeed state, averaging check
    sweep: tuple[StateResults, ...] = ()  # every speed and load state of the full-load curve (the verdict's)
    qualifiers: dict[str, str] = field(default_factory=dict)  # quantity -> its verdict line's words
    by_model: tuple[ModelValue, ...] = ()  # with the whole shaft: each criterion's value in each model
    shaft: ShaftAssessment | None = None  # the whole-shaft model's results the criteria read
    refinements: tuple[Refinement, ...] = ()  # the convergence study's factor of each FE stress criterion

    @property
    def passed(self) -> bool:
        return all(c.passed for c in self.criteria)


def _notes(a: AssessInputs, basis: M53Basis) -> list[Note]:
    texts = [
        "stresses: linear elastic FE, nodal averages; histories by unit-load superposition (exact)",
        "UR M53 nominal torsion from the journal torque (side with the larger alternating part); torsional vibration "
        + (
            "included: quasi-static + vibratory journal torque ([torsion], docs/torsion.md)"
            if a.loads.torsion
            else "not included (no [torsion] section)"
        ),
    ]
    texts.extend(basis.notes)
    if a.cycles.overspeed:
        texts.insert(1, a.cycles.overspeed_note)
    out = [_assumption(t) for t in texts]
    m53_keys = tuple(lim.key for lim in a.criteria.limits if lim.quantity == "m53_acceptability")
    if a.criteria.m53_quasi_static_torque and m53_keys:
        out.append(Note(f"{NOT_CONFORM}: {QUASI_STATIC_M53}", WARNING, m53_keys, "assessment"))
    return out


def _assumption(text: str, throws: tuple[str, ...] = ()) -> Note:
    return Note(text, ASSUMPTION, (), "assessment", throws)


def assess_case(a: AssessInputs, *, fields: bool = False) -> Assessment:
    """Assess one load case.

    ``a.models`` and ``a.unit_solutions`` are keyed alike (``fe_crank.throw_scope``): a key
    is the name of one throw of the engine, or ``ALL_THROWS``, the model then standing for
    every throw, each assessed on it with its own loads.  UR M53 dimensions and the
    counterweights' built m r against the balance stage's required m r come from the
    geometry stage (``a.throw_geometry``).  ``fields``: also recover the whole-mesh
    stress of the states the report draws (``states.model_states``).
    """
    lim = a.criteria  # a material and at least one limit: checked where the inputs are made
    omega, overspeed = a.operating.speed, a.operating.overspeed
    basis = m53_basis(a.engine, a.material, lim.m53_additional_bending, file=a.source_file)
    shaft = _shaft(a, basis) if a.shaft is not None else None
    notes = _notes(a, basis)
    senses = {t.name: a.engine.shaft(t.shaft).sense for t in a.engine.throws}
    units: dict[int, UnitStresses] = {}  # keys sharing one FE solution (equal meshes) share its unit stresses
    for key, unit_solutions in a.unit_solutions.items():
        if id(unit_solutions) not in units:
            groups = assessed_groups(unit_solutions)
            unit = units[id(unit_solutions)] = unit_stresses(unit_solutions, groups)
            boundary_groups = {g: nodes for g, nodes in groups.items() if g in ASSESSED_BOUNDARIES}
            notes.extend(
                _assumption(f"mesh {key}: {n}")
                for n in recovery_notes(recovery_ratios(unit_solutions, boundary_groups, unit=unit))
            )
        for tname in throws_of(key, a.dynamics.throws):
            tg = a.throw_geometry.get(tname)
            m53_geometry = tg.m53 if tg is not None else None
            if m53_geometry is None:
                why = tg.m53_note if tg is not None and tg.m53_note else "no UR M53 dimensions from the geometry"
                notes.append(_assumption(f"{why}; M53 route not run", (tname,)))
            elif m53_geometry.oil_bore_diameter > 0:
                outside = m53_oil_bore.in_range(m53_geometry)
                if outside is not None:
                    notes.append(
                        _assumption(
                            f"UR M53 oil-bore outlet not assessed empirically ({outside}); FE route only "
                            "(group oil_bore)",
                            (tname,),
                        )
                    )
    # the bolted joints by VDI 2230 when a criterion asks or the geometry has any (their data then
    # required; without a joint criterion VDI 2230's usual limits, said on each verdict line), at every speed
    defaulted: tuple[str, ...] = ()
    if has_joints(a.throw_geometry):
        lim, defaulted = with_default_limits(lim, a.source_file)
        if defaulted:
            notes.append(
                _assumption(
                    "bolted counterweights: the load case names no VDI 2230 joint criterion; checked with the "
                    "default limits " + ", ".join(f"{x.key} = {x.value:g}" for x in lim.limits[-len(defaulted) :])
                )
            )
    joints = any(q.quantity in JOINT_QUANTITIES for q in lim.limits)
    unchecked = unchecked_joints(a.throw_geometry)
    if unchecked:
        notes.append(
            Note(
                "bolted counterweights without joint data (a CAD geometry's bolted bodies carry none): their bolted "
                f"joints are not checked by VDI 2230 ({', '.join(unchecked)}); check them by hand or with a "
                "parametric geometry's bolted table",
                WARNING,
                (),
                "assessment",
            )
        )
    cycles = state_dynamics(a) if joints else None
    done = assess_state(a, units, a.loads.operating_state, senses, basis, None, cycles)
    others = [
        (i, j)
        for i, states in enumerate(a.loads.speeds)
        for j in range(len(states))
        if (i, j) != (a.loads.operating, 0)
    ]
    found: dict[tuple[int, int], tuple[ThrowAssessment, ...]] = {(a.loads.operating, 0): done}
    wanted = wanted_extremes(a.criteria)

    def one(ij: tuple[int, int], _scratch: Scratch) -> None:  # each state on its own: independent, one thread each
        found[ij] = assess_state(a, units, a.loads.speeds[ij[0]][ij[1]], senses, basis, wanted, cycles)

    run_blocks(one, others)
    sweep = [
        StateResults(state.speed, state.case, found[(i, j)])
        for i, states in enumerate(a.loads.speeds)
        for j, state in enumerate(states)
    ]
    if len(a.loads.speeds) > 1 or len(sweep) > 1:
        notes.append(_assumption(_sweep_note(a.loads, shaft is not None)))
    qualifiers = criterion_qualifiers(basis, a.criteria, torsion=a.loads.torsion)
    qualifiers.update(joint_qualifiers(a.throw_geometry, defaulted) if joints else {})
    factors = StudyFactors(a.convergence) if a.convergence else None
    judged = judge_criteria(
        lim,
        done,
        file=a.source_file,
        overspeed=overspeed,
        sweep=tuple(sweep),
        qualifiers=qualifiers,
        shaft=shaft,
        factors=factors,
    )
    by_model = (
        model_values(lim, done, shaft, sweep=tuple(sweep), overspeed=overspeed, factors=factors)
        if shaft is not None
        else ()
    )
    # each rod at its place on the pin in the drawn states too (the assessment's coefficients)
    places = {t: places_of(a, t) for t in a.loads.operating_state.throws}
    states = []
    for keys, unit_solutions in shared_models(a.unit_solutions):
        st = model_states(
            keys, unit_solutions, done, a.loads.operating_state, a.loads.overspeed, senses, fields=fields, places=places
        )
        if st is not None:
            states.append(st)
    return Assessment(
        a.case,
        a.source_file,
        omega,
        overspeed,
        a.material,
        done,
        judged.criteria,
        tuple(grouped(notes)),
        tuple(states),
        tuple(sweep),
        qualifiers,
        by_model,
        shaft,
        judged.refinements,
    )


def _shaft(a: AssessInputs, basis: M53Basis) -> ShaftAssessment:
    """The whole shaft's throws assessed by the per-throw model's code (``assess.shaft``) at
    the operating speed and the overspeed, and in every load state at every speed of the
    sweep with the per-throw model's pruning (``wanted_extremes``), with each throw's UR
    M53 diameters (the size factor) and UR M53's sigma_add as the per-throw model; its
    governing hot spot; its bearings."""
    ws = a.shaft
    assert ws is not None
    if ws.cases is None:
        raise ValueError("the whole shaft's unit cases were released after its assessment: run its stage again")
    t0 = time.perf_counter()
    diameters: dict[str, tuple[float | None, float | None]] = {
        name: (tg.m53.pin_diameter, tg.m53.journal_diameter) if tg.m53 is not None else (None, None)
        for name, tg in a.throw_geometry.items()
    }
    throws, states = assess_shaft_throws(
        ws.cases,
        ws.result,
        ws.dynamics.theta,
        a.material,
        crank_radius=ws.layout.geometry.crank_radius,
        overspeed=a.operating.overspeed,
        diameters=diameters,
        additional_bending=basis.additional,
        sweep=ws.sweep,
        wanted=wanted_extremes(a.criteria),
    )
    worst = governing(throws, ws.layout)
    seconds = time.perf_counter() - t0
    return ShaftAssessment(
        throws,
        ws.result.bearings,
        float(ws.dynamics.speed),
        ws.sweep,
        worst,
        seconds,
        states if len(states) > 1 else (),
        ws.film,
    )


def _sweep_note(loads: AssessedLoads, both: bool) -> str:
    rpm = [w * 30.0 / math.pi for w in loads.speed_values]
    states = len(loads.speeds[0])
    text = (
        f"full-load curve: every criterion but the overspeed ones at {len(rpm)} speeds, "
        f"{rpm[0]:.0f}-{rpm[-1]:.0f} rpm, on the same unit stresses{' in both models' if both else ''}; "
        "a criterion's value is its worst speed"
    )
    if states > 1:
        text += (
            f"; at each speed all cylinders firing and {states - 1} misfire case(s) ({READING}), the worst governing"
        )
    return text


def shared_models(unit_solutions: dict[str, UnitSolutions]) -> list[tuple[tuple[str, ...], UnitSolutions]]:
    """[(keys, unit solutions)] grouping the keys that share one FE solution, in order."""
    groups: dict[int, tuple[list[str], UnitSolutions]] = {}
    for k, u in unit_solutions.items():
        groups.setdefault(id(u), ([], u))[0].append(k)
    return [(tuple(keys), u) for keys, u in groups.values()]
