"""``assess_case``: the assessment of one load case, every throw, its criteria.

It takes what the earlier stages made (typed, ``AssessInputs``): the engine cycles
(operating and overspeed, ``fe_crank.mechanism.cycles``; the journal torques with the
vibratory torque when the torsional stage ran), the balance design, the counterweights'
CAD mass properties (geometry stage), the FE unit solutions and, where UR M53's empirical
SCFs are out of range, the SCF mode's result (FE stage).  It computes nothing any other
stage owns.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from fe_crank import model
from fe_crank.assess import m53, m53_oil_bore
from fe_crank.assess.adapters import counterweights_of
from fe_crank.assess.criteria import ModelValue, evaluate_criteria, model_values
from fe_crank.assess.groups import ASSESSED_BOUNDARIES, assessed_groups, unit_stresses
from fe_crank.assess.m53_basis import M53Basis, m53_basis
from fe_crank.assess.recovery import recovery_notes, recovery_ratios
from fe_crank.assess.scf import ScfResult
from fe_crank.assess.shaft import ShaftAssessment
from fe_crank.assess.states import ModelStates, model_states
from fe_crank.assess.superpose import UnitStresses, inertia_acceleration
from fe_crank.assess.throw import ThrowAssessment, assess_throw
from fe_crank.balance.analysis import BalanceResult
from fe_crank.errors import InputError
from fe_crank.fe.pin_patches import rod_loads, rod_positions
from fe_crank.fe.unit_cases import UnitSolutions
from fe_crank.geometry.mass import ThrowSolids
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.io.criteria import Criteria
from fe_crank.io.material import Material
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.mechanism.dynamics import DynamicsResult, ThrowLoads
from fe_crank.notes import ASSUMPTION, Note, grouped
from fe_crank.results import CriterionResult
from fe_crank.throw_scope import throws_of

#: 1.1: optional provenance and warnings (written by the report); 1.2: warnings name their throws;
#: 1.3: the whole-shaft model (``whole_shaft``) and each criterion's value in each model (``criteria_by_model``)
SCHEMA_VERSION = "1.3"


@dataclass(frozen=True)
class AssessInputs:
    """Everything ``assess_case`` reads, from the load case and the earlier stages.

    ``dynamics``: the operating cycle the stresses follow (its journal torques carry the
    vibratory torque when the torsional stage ran); ``cycles``: the operating and
    overspeed cycles of the dynamics stage; ``models``: FE model key -> geometry throw
    name (the mesh plan; with ``geometry`` None, a model that is no throw of a crank
    geometry, no counterweights are checked); ``unit_solutions``: key -> unit solutions (keys sharing one
    mesh share one object); ``scf``: key -> the SCF mode's result, for the models whose
    UR M53 dimensions are outside the empirical range."""

    case: str
    source_file: str
    engine: model.Engine
    operating: model.OperatingPoint
    material: Material
    criteria: Criteria
    geometry: CrankGeometry | None
    cycles: EngineCycles
    dynamics: DynamicsResult
    balance: BalanceResult | None
    models: dict[str, str]
    unit_solutions: dict[str, UnitSolutions]
    solids: ThrowSolids | None = None
    m53_geometry: m53.M53Geometry | None = None
    scf: dict[str, ScfResult] = field(default_factory=dict)
    torsion: bool = False  # the journal torques carry the torsional stage's vibratory torque
    shaft: ShaftAssessment | None = None  # the whole-shaft model's results (its stage), when it ran


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
    by_model: tuple[ModelValue, ...] = ()  # with the whole shaft: each criterion's value in each model

    @property
    def passed(self) -> bool:
        return all(c.passed for c in self.criteria)


def _notes(a: AssessInputs, basis: M53Basis) -> list[Note]:
    texts = [
        "stresses: linear elastic FE, nodal averages; histories by unit-load superposition (exact)",
        "UR M53 nominal torsion from the journal torque (side with the larger alternating part); torsional vibration "
        + (
            "included: quasi-static + vibratory journal torque ([torsion], docs/torsion.md)"
            if a.torsion
            else "not included (no [torsion] section)"
        ),
    ]
    texts.extend(basis.notes)
    if a.cycles.overspeed:
        texts.insert(1, a.cycles.overspeed_note)
    return [_assumption(t) for t in texts]


def _assumption(text: str, throws: tuple[str, ...] = ()) -> Note:
    return Note(text, ASSUMPTION, (), "assessment", throws)


def assess_case(a: AssessInputs, *, fields: bool = False) -> Assessment:
    """Assess one load case.

    ``a.models`` and ``a.unit_solutions`` are keyed alike (``fe_crank.throw_scope``): a key
    is the name of one throw of the engine, or ``ALL_THROWS``, the model then standing for
    every throw, each assessed on it with its own loads.  UR M53 dimensions come from
    ``a.m53_geometry``; the counterweights' built m r from the geometry stage's mass properties
    against the balance stage's required m r.  ``fields``: also recover the whole-mesh
    stress of the states the report draws (``states.model_states``).
    """
    lim = a.criteria
    if not lim.limits:
        raise InputError(
            "the assessment needs a [criteria] section with at least one limit", file=a.source_file, key="criteria"
        )
    omega, overspeed = a.operating.speed, a.operating.overspeed
    basis = m53_basis(a.engine, a.material, lim.m53_additional_bending, file=a.source_file)
    notes = _notes(a, basis)
    senses = {t.name: a.engine.shaft(t.shaft).sense for t in a.engine.throws}
    design = a.balance.design if a.balance is not None else None
    throws = []
    solved: dict[int, UnitStresses] = {}  # keys sharing one FE solution (equal meshes) share its unit stresses
    for key, unit_solutions in a.unit_solutions.items():
        if id(unit_solutions) not in solved:
            groups = assessed_groups(unit_solutions)
            unit = solved[id(unit_solutions)] = unit_stresses(unit_solutions, groups)
            boundary_groups = {g: nodes for g, nodes in groups.items() if g in ASSESSED_BOUNDARIES}
            notes.extend(
                _assumption(f"mesh {key}: {n}")
                for n in recovery_notes(recovery_ratios(unit_solutions, boundary_groups, unit=unit))
            )
        unit = solved[id(unit_solutions)]
        spec = a.geometry.throw(a.models[key]) if a.geometry is not None else None
        for tname in throws_of(key, a.dynamics.throws):
            tl = a.dynamics.throws[tname]
            throw = a.engine.throw(tname)
            # each rod at its place on the pin (UR M53 2.1); without a geometry, the summed
            # force at mid-pin
            places = rod_positions(a.engine, tname, a.geometry.crankpin_length) if a.geometry is not None else {}
            cws = (
                counterweights_of(spec, a.solids.of(spec.name), throw.axial_position, throw.shaft, design)
                if spec is not None and spec.counterweights and a.solids is not None
                else ()
            )
            alpha = (  # the throw's vibratory inertia torque as the body force of its angular acceleration
                inertia_acceleration(tl.torque_front, tl.torque_rear, tl.torque, unit.inertia_mz)
                if "angular_acceleration" in unit.cases
                else None
            )
            throws.append(
                assess_throw(
                    tname,
                    unit,
                    a.dynamics.theta,
                    tl.pin_force,
                    tl.torque_front,
                    omega=omega,
                    sense=senses[tname],
                    overspeed=overspeed,
                    material=a.material,
                    crank_radius=throw.crank_radius,
                    m53_geometry=a.m53_geometry,
                    m53_additional=basis.additional,
                    m53_ke=basis.ke,
                    counterweights=cws,
                    torque_rear=tl.torque_rear,
                    overspeed_loads=[_cycle(c.dynamics.throws[tname], places) for c in a.cycles.overspeed] or None,
                    rod_loads=rod_loads(tl, places),
                    scf=a.scf.get(key),
                    angular_acceleration=alpha,
                )
            )
            if a.m53_geometry is None:
                notes.append(_assumption("no UR M53 dimensions from the geometry; M53 route not run", (tname,)))
            elif a.m53_geometry.oil_bore_diameter > 0 and m53_oil_bore.in_range(a.m53_geometry) is not None:
                notes.append(
                    _assumption(
                        f"UR M53 oil-bore outlet not assessed empirically "
                        f"({m53_oil_bore.in_range(a.m53_geometry)}); FE route only (group oil_bore)",
                        (tname,),
                    )
                )
    done = tuple(throws)
    verdicts = evaluate_criteria(lim, done, file=a.source_file, overspeed=overspeed, shaft=a.shaft)
    by_model = model_values(lim, done, a.shaft) if a.shaft is not None else ()
    states = []
    for keys, unit_solutions in shared_models(a.unit_solutions):
        st = model_states(keys, unit_solutions, done, a.dynamics, a.cycles.overspeed, senses, fields=fields)
        if st is not None:
            states.append(st)
    return Assessment(
        a.case,
        a.source_file,
        omega,
        overspeed,
        a.material,
        done,
        verdicts,
        tuple(grouped(notes)),
        tuple(states),
        by_model,
    )


def _cycle(tl: ThrowLoads, places: dict[str, float]) -> tuple:
    """(pin force, front torque, rod loads) of a throw's cycle (``assess_throw``'s overspeed)."""
    return tl.pin_force, tl.torque_front, rod_loads(tl, places)


def shared_models(unit_solutions: dict[str, UnitSolutions]) -> list[tuple[tuple[str, ...], UnitSolutions]]:
    """[(keys, unit solutions)] grouping the keys that share one FE solution, in order."""
    groups: dict[int, tuple[list[str], UnitSolutions]] = {}
    for k, u in unit_solutions.items():
        groups.setdefault(id(u), ([], u))[0].append(k)
    return [(tuple(keys), u) for keys, u in groups.values()]
