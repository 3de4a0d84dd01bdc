"""The whole shaft's stresses, assessed as the per-throw model's are.

Every throw of the whole-shaft model (``fe.shaft.whole_shaft``) is assessed at the nodes of the
per-throw model's groups (``fe.throw.node_groups``: fillets, oil bore, counterweight fillets and
junctions; the counterweight bodies, loaded by their own centrifugal force alike in both
models, stay with the per-throw model) by the same code (``assess.group.assessment.assess_group``:
static, overspeed, Goodman and Gough-Pollard fatigue, UR M53's sigma_add on the shaft
fillets, the size and surface factors), from the whole shaft's unit cases:

    sigma(theta) = sum_c W_c(theta) S_c,

``S_c`` the nodal stress of shaft case c (``ShaftCases.names``: each throw's pin cases,
the centrifugal cases, the torque-flow cases, the redundant bearings' unit forces) at
the throw's assessed nodes, recovered exactly from the condensed fields
(``ShaftCases.recover``: sum a_p L_p + X v in the throw's own frame), and ``W_c`` the
cycle's weights with the bearings' forces found per angle (``ShaftCycle.weights``; the
overspeed cycles likewise).  The throw frame is the per-throw model's, so the axes of
the Gough-Pollard split and the groups' names are the same.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from fe_crank.assess.group.assessment import assess_groups, section_diameter, sigma_add_applies
from fe_crank.assess.group.extremes import Running, Wanted, group_extremes
from fe_crank.assess.loads import FIRING, misfire_label
from fe_crank.assess.speeds import StateResults
from fe_crank.assess.superpose import UnitStresses
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.assess.workers import Scratch, run_blocks, thread_count
from fe_crank.fe.core.stress import stress_at_selected_nodes
from fe_crank.fe.shaft.cases import ShaftCases
from fe_crank.fe.shaft.whole_shaft import BearingResult, WholeShaftResult, bearing_state_of
from fe_crank.fe.throw.node_groups import node_groups
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.io.material import Material
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.mechanism.dynamics import DynamicsResult
from fe_crank.mesh.shaft import place

#: the label of each model in the criteria's locations and the report
PER_THROW = "per-throw model"
WHOLE_SHAFT = "whole-shaft model"


@dataclass(frozen=True)
class BearingState:
    """The main bearings' loads (with and without counterweights) in one load state at one
    speed of the full-load sweep (rad/s; ``case``: ``assess.loads.FIRING`` or a misfire),
    and the weights of the shaft's unit cases over that cycle with the counterweights
    (``ShaftCycle.weights``: the stresses of the state by superposition)."""

    speed: float
    case: str
    bearings: tuple[BearingResult, ...]
    weights: np.ndarray | None = None


@dataclass(frozen=True)
class WholeShaftOutput:
    """The whole-shaft stage (``pipeline.shaft_stage``): the shaft placed by the engine, its
    bearing loads and web moments over the cycle with and without counterweights
    (``result``), the main bearings' loads at every speed and load state of the full-load
    sweep (``sweep``, ``bearing_sweep``), and its unit cases (``cases``: condensed, with each
    throw's recovery fields at its assessed nodes, and the factorisations when whole fields
    are wanted) which the assessment reads (``assess_shaft_throws``; None once the stages
    that read them ran)."""

    layout: ShaftLayout
    result: WholeShaftResult
    dynamics: DynamicsResult  # the operating cycle it was solved over (the assessed one)
    sweep: tuple[BearingState, ...] = ()
    cases: ShaftCases | None = None
    #: the hydrodynamic bearings' oil film in every state of ``sweep`` (``assess.oil_film``;
    #: () : no hydrodynamic bearing)
    film: tuple[Any, ...] = ()  # assess.oil_film.FilmState (that module reads this one)


@dataclass(frozen=True)
class ShaftHotSpot:
    """Where and when the whole shaft's von Mises stress is largest over the cycle."""

    throw: str
    group: str
    angle_deg: float  # cycle angle
    von_mises: float  # Pa
    point: tuple[float, float, float]  # m, shaft frame (the engine frame at crank angle zero)


@dataclass(frozen=True)
class ShaftAssessment:
    """What the criteria read from the whole-shaft model: its throws' group results at the
    operating speed ``speed`` (rad/s; None: not stated) and its overspeed cycles (the
    per-throw model's groups, ``ThrowAssessment.groups``; no UR M53, no counterweight
    checks), its main bearings' loads with and without counterweights at the operating
    speed, and at every speed and load state of the sweep (``sweep``; () : the operating
    speed alone); ``governing``: its largest von Mises stress over the cycle (``governing``);
    ``states``: its throws in every load state at every speed of the sweep, as the
    per-throw model's (``speeds.StateResults``; the operating speed's firing state is
    ``throws``, the others their extremes only; () : the operating speed alone)."""

    throws: tuple[ThrowAssessment, ...]
    bearings: tuple[BearingResult, ...]
    speed: float | None = None
    sweep: tuple[BearingState, ...] = ()
    governing: ShaftHotSpot | None = None
    seconds: float = 0.0  # the time its throws' assessment took
    states: tuple[StateResults, ...] = ()
    #: the hydrodynamic bearings' oil film in every state of ``sweep``
    #: (``assess.oil_film.FilmState``; () : no hydrodynamic bearing)
    film: tuple[Any, ...] = ()


def bearing_sweep(
    cycles: EngineCycles, cases: ShaftCases, layout: ShaftLayout, result: WholeShaftResult
) -> tuple[BearingState, ...]:
    """The main bearings' loads at every speed and load state of the full-load sweep (every
    cylinder firing, each misfire case; ``mechanism.cycles.EngineCycles.sweep``): the
    operating speed's firing state is the stage's own cycle (``result``, with the torsional
    stage's journal torques when it ran), the others the dynamics stage's cycles on the
    condensed shaft with and without counterweights, the envelope over the bearing laws, each
    journal's torque quasi-static; each with the case weights of the stated law with the
    counterweights for the stresses (``fe.shaft.whole_shaft.bearing_state_of``: the stated
    law solved once for both)."""

    def state(speed: float, case: str, dynamics: DynamicsResult) -> BearingState:
        bearings, weights = bearing_state_of(cases, layout, dynamics)
        return BearingState(speed, case, bearings, weights)

    out = []
    for sc in cycles.sweep:
        own = sc.firing is cycles.operating
        out.append(
            BearingState(sc.speed, FIRING, result.bearings, result.cycles[0].weights)
            if own
            else state(sc.speed, FIRING, sc.firing)
        )
        out.extend(state(sc.speed, misfire_label(m.cylinder), m.dynamics) for m in sc.misfire)
    return tuple(out)


def governing(throws: tuple[ThrowAssessment, ...], layout: ShaftLayout) -> ShaftHotSpot | None:
    """The largest von Mises stress over the cycle on the whole shaft's throws and where
    it is (the first of equals), its point placed in the shaft frame."""
    best = None
    for t in throws:
        for g in t.groups:
            e = g.max_von_mises
            if e.angle is not None and (best is None or e.value > best[1].value):
                best = (t.name, e)
    if best is None:
        return None
    name, e = best
    assert e.angle is not None
    th = next(t for t in layout.throws if t.name == name)
    p = place(np.asarray(e.point, float)[:, None], layout.sense * th.angle, th.z)[:, 0]
    return ShaftHotSpot(
        name, e.group, float(np.degrees(e.angle)), float(e.value), (float(p[0]), float(p[1]), float(p[2]))
    )


def piece_unit_stresses(cases: ShaftCases, piece: int, material: Material) -> UnitStresses:
    """Nodal stresses of every shaft case at the assessed nodes of throw piece ``piece``
    (its own frame; module doc)."""
    pp = cases.model.pieces[piece]
    c = pp.cond
    groups = node_groups(c.mesh, c.basis, bodies=False)
    ids = np.unique(np.concatenate(list(groups.values())))
    rec = np.asarray(c.rec_nodes)
    if np.setdiff1d(ids, rec).size:
        raise ValueError("the condensed throw keeps no field at some of its assessed nodes")
    n = len(cases.names)
    rows = (3 * rec[:, None] + np.arange(3)).ravel()
    stress = np.empty((n, 6, ids.size))
    sets = [x for x in np.array_split(np.arange(n), max(1, min(thread_count(), n))) if x.size]

    def block(sel: np.ndarray, _scratch: Scratch) -> None:  # each case's stress alone: any thread count, same bits
        w = np.zeros((n, sel.size))
        w[sel, np.arange(sel.size)] = 1.0
        u = np.zeros((sel.size, 3 * c.basis.N))  # full-length fields, zero away from the recovery nodes
        u[:, rows] = cases.recover(piece, w).T
        stress[sel] = stress_at_selected_nodes(
            c.mesh, u, material.youngs_modulus, material.poisson_ratio, ids, dofs=c.basis.dofs
        )

    run_blocks(block, sets, len(sets))
    return UnitStresses(
        stress=stress,
        points=np.asarray(c.basis.doflocs)[:, ids],
        groups={k: np.searchsorted(ids, v) for k, v in groups.items()},
        node_ids=ids,
        cases=tuple(cases.names),
    )


def assess_shaft_throws(
    cases: ShaftCases,
    result: WholeShaftResult,
    theta: np.ndarray,
    material: Material,
    *,
    crank_radius: float,
    overspeed: float | None,
    diameters: dict[str, tuple[float | None, float | None]] | None = None,
    additional_bending: float = 0.0,
    sweep: tuple[BearingState, ...] = (),
    wanted: Wanted | None = None,
    units: Mapping[int, UnitStresses] | None = None,
) -> tuple[tuple[ThrowAssessment, ...], tuple[StateResults, ...]]:
    """Every throw of the whole shaft assessed with the per-throw model's group code
    (module doc), with the counterweights as built; ``theta`` the cycle's angles (rad);
    ``overspeed`` (rad/s) with ``result.overspeed``'s cycles; ``diameters``: throw name ->
    (pin, journal) diameter for the size factor (UR M53's dimensions; None: the factor's
    fallback); ``additional_bending``: UR M53 4's sigma_add on the shaft fillets (as the
    per-throw model).  Returns the throws at the operating cycle (in full, with the
    overspeed) and, with ``sweep`` (``bearing_sweep``'s states, their weights), the throws
    in every load state at every speed: the operating speed's firing state (the state whose
    weights are the operating cycle's) in full, the others their extremes only
    (``extremes.group_extremes`` with ``wanted``, each state searched with its own
    ``Running``: the per-throw model's pruning).  ``units``: throw piece index -> its
    ``piece_unit_stresses`` of these ``cases`` and ``material`` where already taken (read,
    not taken again)."""
    coeffs = result.cycles[0].weights
    theta = np.asarray(theta, float)
    coeffs_os = None
    if overspeed is not None and result.overspeed:
        coeffs_os = np.vstack([c.weights for c in result.overspeed])
    elif overspeed is not None:
        overspeed = None  # no overspeed cycle of the whole shaft: the per-throw model's alone
    own = [i for i, st in enumerate(sweep) if st.weights is coeffs]
    others = [i for i in range(len(sweep)) if i not in own]
    running = {i: Running() for i in others}  # each state's least fatigue values so far, over the throws
    out = []
    per_state: dict[int, list[ThrowAssessment]] = {i: [] for i in range(len(sweep))}
    for k, pp in enumerate(cases.model.pieces):
        if pp.kind != "throw":
            continue
        unit = units[k] if units is not None and k in units else piece_unit_stresses(cases, k, material)
        pin_diameter, journal_diameter = (diameters or {}).get(str(pp.throw), (None, None))
        groups = assess_groups(
            unit,
            coeffs,
            theta,
            material,
            crank_radius=crank_radius,
            overspeed=overspeed,
            overspeed_coefficients=coeffs_os,
            pin_diameter=pin_diameter,
            journal_diameter=journal_diameter,
            additional_bending=additional_bending,
        )
        t = ThrowAssessment(str(pp.throw), groups, n_angles=int(theta.size))
        out.append(t)
        for i in own:
            per_state[i].append(t)

        def one(
            i: int,
            _scratch: Scratch,
            unit: UnitStresses = unit,
            name: str = str(pp.throw),
            dp: float | None = pin_diameter,
            dj: float | None = journal_diameter,
        ) -> None:
            w = sweep[i].weights
            assert w is not None
            extremes = tuple(
                group_extremes(
                    unit,
                    g,
                    w,
                    theta,
                    material,
                    crank_radius=crank_radius,
                    diameter=section_diameter(g, dp, dj),
                    wanted=wanted or Wanted(),
                    running=running[i],
                    additional_bending=additional_bending if sigma_add_applies(g) else 0.0,
                )
                for g in sorted(unit.groups)
                if len(unit.groups[g])
            )
            per_state[i].append(ThrowAssessment(name, extremes, n_angles=int(theta.size)))

        run_blocks(one, others)
        del unit
    states = tuple(StateResults(st.speed, st.case, tuple(per_state[i])) for i, st in enumerate(sweep))
    return tuple(out), states
