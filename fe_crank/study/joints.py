"""The bolted counterweights' joints in the counterweight study (docs/study.md): VDI 2230
by the check's own code on each candidate's counterweights.

A bolted counterweight's joint (``assess.cw_joint``) takes its loads from the
counterweight's own inertia (its mass m and centre-of-mass radius r_c: the centrifugal
force m r_c omega^2 and the tangential inertia m r_c alpha, with the speed fluctuation and
angular acceleration of each cycle, ``joint_loads.cycle_speed_data``) and the web's
deformation under the pin force and the journal torque (the per-throw model's normal
stress across the joint plane, ``joint_loads.fe_section_loads``: the pin and torque unit
cases alone, none of the centrifugal ones; the lever model where the section cannot be
fitted).  Per candidate the counterweight data are those the check builds for the
geometry the candidate writes (``assess.adapters.counterweights_of`` on the written
throw's exact mass properties, ``geometry.mass``: the written sector's mass, centre of
mass and joint geometry; the bolts as drawn); a candidate that cannot be built keeps the
drawn counterweight scaled in mass by k_w.  The web's deformation comes from the
per-throw model of the drawn geometry (``study.bodies``), its coefficients per load state
as the check's (``assess.throw.fe_coefficients``), and each throw's joints in each
load state of the check (every speed of the full-load curve, firing and each misfire
case) are checked by ``assess.throw.throw_joints``, the check's own call.  With
``[torsion]`` the load states are the candidate's own torsional stage's (``study.torsion``):
the throw's torsional angular acceleration added to the rigid one
(``assess.state_throws.speed_data``) and the vibratory pin force and angular-acceleration
case in the coefficients, as the check.  The study keeps,
per VDI 2230 quantity of the check's criteria (``assess.joint_criteria.JOINT_QUANTITIES``),
the worst over the joints and states, and where.

Exact for the geometry the study writes when its counterweights are the drawn shapes (the
same mesh): the figures equal the check's (test).  A written sector of another shape
changes the web's stiffness at the joint, which the section's stresses (from the drawn
mesh) do not follow; its mass, centre of mass and joint geometry are the written ones."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from fe_crank.assess.adapters import counterweights_of
from fe_crank.assess.counterweight import CounterweightData
from fe_crank.assess.joint_criteria import DEFAULT_LIMITS, JOINT_QUANTITIES, with_default_limits
from fe_crank.assess.loads import AssessedLoads
from fe_crank.assess.state_throws import cycle_dynamics, speed_data
from fe_crank.assess.throw import fe_coefficients, throw_joints
from fe_crank.errors import InputError
from fe_crank.fe.throw.pin_patches import rod_loads
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.io.criteria import Criteria
from fe_crank.io.loadcase import LoadCase
from fe_crank.io.material import Material
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.study.bodies import BodyModel
from fe_crank.study.candidates import Candidate, ThrowSolidCache, written_throw
from fe_crank.torsion.loads import assessed_loads

#: the study's limit key of each VDI 2230 quantity: the check's criterion key
#: (``max_bolt_assembly_utilisation``, ``min_bolt_working_safety``, ...)
LIMITS = {f"{sense}_{q}": q for q, (_, sense) in JOINT_QUANTITIES.items()}


def has_bolted(layout: ShaftLayout) -> bool:
    """Whether any drawn counterweight of the shaft is bolted."""
    return any(cw.bolted is not None for th in layout.throws for cw in th.spec.counterweights)


def joint_limits(stated: dict[str, float], criteria: Criteria | None) -> tuple[dict[str, float], str]:
    """The joint limits the study judges by: the ones it states (``LIMITS`` keys of
    ``stated``) or, where it states none, those the check judges the written load case by
    (its ``[criteria]``' joint criteria, else VDI 2230's usual ones,
    ``joint_criteria.DEFAULT_LIMITS``); and the words saying whose they are."""
    own = {k: v for k, v in stated.items() if k in LIMITS}
    if own:
        return own, "the study's"
    default = "VDI 2230's usual limits (neither the study nor the load case names a joint limit), as the check takes"
    if criteria is None:
        return {f"{JOINT_QUANTITIES[q][1]}_{q}": v for q, v in DEFAULT_LIMITS.items()}, default
    judged, added = with_default_limits(criteria)  # the check's own choice of limits
    limits = {f"{lim.sense}_{lim.quantity}": lim.value for lim in judged.limits if lim.quantity in JOINT_QUANTITIES}
    return limits, default if added else "the load case's [criteria] (the study names no joint limit)"


@dataclass(frozen=True)
class _ThrowState:
    """One throw in one load state: what ``throw_joints`` takes besides the counterweights."""

    throw: str
    label: str
    pin_force: np.ndarray
    torque: np.ndarray
    omega: float
    sense: int
    coeffs: np.ndarray
    joint_speed: tuple[float, float]
    rods: tuple | None
    overspeed_loads: list | None


@dataclass(frozen=True)
class JointModel:
    """The load states of the bolted throws, formed once per study (module doc)."""

    body: BodyModel
    states: tuple[_ThrowState, ...]
    layout: ShaftLayout
    overspeed: float | None
    material: Material
    geometry_file: str
    axial: dict[str, float]  # engine throw -> axial position, m
    shafts: dict[str, str]  # engine throw -> its shaft


@dataclass(frozen=True)
class JointScreen:
    """One candidate's bolted joints over the check's load states: per ``LIMITS`` key the
    worst value over the joints and states (a plain number) and where it is."""

    values: dict[str, float]
    where: dict[str, str]
    joints: int  # the bolted counterweights checked (on the written shaft)
    refused: str | None = None  # why the check could not check a written joint (its own message)


def joint_model(
    lc: LoadCase, layout: ShaftLayout, body: BodyModel, cycles: EngineCycles, loads: AssessedLoads | None = None
) -> JointModel:
    """Every load state of the check (``loads``: ``torsion.loads.assessed_loads``, by default
    the rigid shaft's; with [torsion] a candidate's loads with its vibration,
    ``torsion.stage.torsional_loads``) of every throw that carries a bolted counterweight as
    drawn (module doc)."""
    if loads is None:
        loads = assessed_loads(lc.engine, cycles, reaction=lc.fe.torque_reaction)
    dyn = cycle_dynamics(cycles)
    bolted = {th.name for th in layout.throws if any(cw.bolted is not None for cw in th.spec.counterweights)}
    j_fly = cycles.operating.flywheel_inertia
    out = []
    for states in loads.speeds:
        for state in states:
            for name in sorted(bolted):
                tc = state.throws[name]
                places = body.places[name]
                rods = rod_loads(tc, places)
                # with [torsion]: the throw's vibration, as the check's assess_throw
                coeffs = fe_coefficients(
                    body.units[name],
                    tc.pin_force,
                    tc.torque_in,
                    state.speed,
                    sense=body.senses[name],
                    rod_loads=rods,
                    angular_acceleration=tc.angular_acceleration,
                    fe_pin_force=tc.fe_pin_force,
                    fe_rod_loads=tc.fe_rod_loads(places) if tc.fe_rods else None,
                )
                # the check's ``assess.state_throws.joint_speed``: with [torsion] the throw's
                # largest torsional angular acceleration added to the rigid one
                joint_speed = speed_data(dyn[state.speed, state.case], j_fly, tc.angular_acceleration)
                os_loads = [
                    (s.throws[name].pin_force, s.throws[name].torque_in, rod_loads(s.throws[name], places))
                    for s in loads.overspeed
                ]
                rpm = state.speed * 30 / math.pi
                out.append(
                    _ThrowState(
                        name,
                        f"{state.case} at {rpm:.0f} rpm",
                        tc.pin_force,
                        tc.torque_in,
                        state.speed,
                        body.senses[name],
                        coeffs,
                        joint_speed,
                        rods,
                        os_loads or None,
                    )
                )
    assert lc.material is not None
    return JointModel(
        body,
        tuple(out),
        layout,
        lc.operating.overspeed,
        lc.material,
        str(layout.geometry.file or lc.source_file),
        {t.name: t.axial_position for t in lc.engine.throws},
        {t.name: t.shaft for t in lc.engine.throws},
    )


def candidate_counterweights(
    model: JointModel, cand: Candidate, solids: ThrowSolidCache, mass: dict
) -> dict[str, tuple[CounterweightData, ...]]:
    """Per engine throw the counterweight data the check builds for the geometry the
    candidate writes (``adapters.counterweights_of``, no balance design: the joints do not
    use it); a candidate that cannot be built: the drawn ones scaled in mass by k_w
    (``mass``: the drawn throws' properties)."""
    g = model.layout.geometry
    out = {}
    for th in model.layout.throws:
        if not any(cw.bolted is not None for cw in th.spec.counterweights):
            continue
        if cand.buildable:
            spec = written_throw(th.spec, cand)
            cws = counterweights_of(spec, solids.of(spec), model.axial[th.name], model.shafts[th.name], None, g)
        else:
            drawn = counterweights_of(th.spec, mass[th.name], model.axial[th.name], model.shafts[th.name], None, g)
            cws = tuple(
                dataclasses.replace(
                    c,
                    joints=tuple(
                        dataclasses.replace(j, mass=j.mass * cand.factors.get((th.name, _web(j.name)), 0.0))
                        for j in c.joints
                        if cand.factors.get((th.name, _web(j.name)), 0.0) > 0.0
                    ),
                )
                for c in drawn
            )
        out[th.name] = cws
    return out


def _web(part: str) -> int:
    """The web of a counterweight part's name ``counterweight_<web>``."""
    return int(part.rpartition("_")[2])


def candidate_joints(
    model: JointModel, cand: Candidate, solids: ThrowSolidCache, mass: dict, keys: tuple[str, ...] = tuple(LIMITS)
) -> JointScreen | None:
    """The candidate's joints in every load state (module doc); None when it has no bolted
    counterweight."""
    cws = candidate_counterweights(model, cand, solids, mass)
    if not any(c.joints for v in cws.values() for c in v):
        return None
    values: dict[str, float] = {}
    where: dict[str, str] = {}
    names: set[tuple[str, str]] = set()
    for ts in model.states:
        own = cws.get(ts.throw, ())
        if not any(c.joints for c in own):
            continue
        try:
            checks = throw_joints(
                model.body.units[ts.throw],
                own,
                ts.pin_force,
                ts.torque,
                omega=ts.omega,
                sense=ts.sense,
                overspeed=model.overspeed,
                material=model.material,
                joint_speed=ts.joint_speed,
                coeffs=ts.coeffs,
                rod_loads=ts.rods,
                overspeed_loads=ts.overspeed_loads,
                geometry_file=model.geometry_file,
            )
        except InputError as exc:  # e.g. a written counterweight too thin for its bolts' interface
            return JointScreen({}, {}, len(names), f"throw {ts.throw}: {exc.reason}")
        for j in checks:
            names.add((ts.throw, j.name))
            for key in keys:
                attr, sense = JOINT_QUANTITIES[LIMITS[key]]
                v = float(getattr(j, attr))
                worse = key not in values or (v > values[key] if sense == "max" else v < values[key])
                if worse:
                    values[key] = v
                    where[key] = f"throw {ts.throw} {j.name}, {ts.label}"
    return JointScreen(values, where, len(names))


__all__ = [
    "LIMITS",
    "JointModel",
    "JointScreen",
    "candidate_counterweights",
    "candidate_joints",
    "has_bolted",
    "joint_limits",
    "joint_model",
]
