"""The counterweights' own stress in the counterweight study (docs/study.md): the
per-throw model of the drawn geometry (each throw on its own supports, the check's mesh
plan and meshes, ``mesh.plan``), solved once per study with the centrifugal case split
into the throw's own and each counterweight body's (``fe.core.loads.BODY_CASES``); a
candidate's counterweight on web w, the drawn shape scaled in mass by k_w, is then k_w
times that web's case: per load state the check's coefficients (``assess.superpose
.cycle_coefficients``: the pin cases, the torque, omega^2 on every centrifugal part) with
the web's column times k_w, and each counterweight group's (bodies, transition fillets,
junctions) peak von Mises over the cycle by the check's own search
(``assess.group.peak.group_peak``): the per-throw model's ``counterweight_stress``.
With ``[torsion]`` the model also solves the ``angular_acceleration`` case (as the check's
FE stage) and the coefficients carry the candidate's vibration
(``assess.throw.fe_coefficients`` on its torsional loads, ``study.torsion``)."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from fe_crank.assess.group.assessment import of_counterweight
from fe_crank.assess.group.nodes import assessed_groups, unit_stresses
from fe_crank.assess.group.peak import group_peak
from fe_crank.assess.loads import AssessedLoads
from fe_crank.assess.superpose import UnitStresses
from fe_crank.assess.throw import fe_coefficients
from fe_crank.cad.source import mesh_source_throw
from fe_crank.fe import solve_unit_cases
from fe_crank.fe.core.loads import CENTRIFUGAL_PARTS
from fe_crank.fe.throw.pin_patches import pin_patch_options, rod_loads, rod_positions
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.io.loadcase import LoadCase
from fe_crank.mesh.plan import plan_meshes
from fe_crank.throw_scope import throws_of
from fe_crank.torsion.loads import fe_inertias


@dataclass(frozen=True)
class BodyModel:
    units: dict[str, UnitStresses]  # engine throw -> its model's stresses at the counterweight groups
    places: dict[str, dict[str, float]]  # engine throw -> each rod's place on the pin, m
    senses: dict[str, int]
    #: engine throw -> the moment about the axis of its model's ``angular_acceleration``
    #: unit case (kg m^2; with [torsion] only, ``torsion.loads.fe_inertias``)
    fe_inertia: dict[str, float] = field(default_factory=dict)


@dataclass(frozen=True)
class BodyScreen:
    peak: float  # Pa, the largest von Mises of the counterweight groups, any state and angle
    where: str


def body_model(lc: LoadCase, layout: ShaftLayout, *, size, cache_dir, max_elements=None) -> BodyModel:
    """The per-throw model of the drawn geometry with the centrifugal parts (module doc)."""
    g, mat = layout.geometry, lc.material
    assert mat is not None
    names = tuple(t.name for t in lc.engine.throws)
    plan = plan_meshes(
        g,
        names,
        lc.mesh,
        size=size,
        max_elements=max_elements,
        cache_dir=cache_dir,
        file=lc.source_file,
        shaft=layout,
    )
    cases = tuple(c for c in lc.fe.cases if c != "centrifugal") + CENTRIFUGAL_PARTS
    if lc.torsion is not None and "angular_acceleration" not in cases:  # as the check's FE stage
        cases += ("angular_acceleration",)
    options = dataclasses.replace(lc.fe, cases=cases)
    meshes = {
        key: mesh_source_throw(g, name, size=plan.options, cache_dir=plan.cache_dir, max_elements=plan.max_elements)
        for key, name in plan.throws.items()
    }
    solved: dict[str, UnitStresses] = {}
    units: dict[str, UnitStresses] = {}
    inertia: dict[str, float] = {}
    fe_inertia: dict[str, float] = {}
    for key, m in meshes.items():
        if m.key not in solved:
            throws = [t for k, other in meshes.items() if other.key == m.key for t in throws_of(k, list(names))]
            opts = pin_patch_options(options, lc.engine, layout.geometry.crankpin_length, throws)
            us = solve_unit_cases(m, mat, opts)
            groups = {n: nodes for n, nodes in assessed_groups(us).items() if of_counterweight(n)}
            solved[m.key] = unit_stresses(us, groups)
            if "angular_acceleration" in us.cases:
                # the check's ``torsion.loads.fe_inertias`` of this model
                inertia[m.key] = fe_inertias({key: us}, list(names))[throws[0]]
            us.system.factorisation.free()
        for t in throws_of(key, list(names)):
            units[t] = solved[m.key]
            if m.key in inertia:
                fe_inertia[t] = inertia[m.key]
    places = {t: rod_positions(lc.engine, t, layout.geometry.crankpin_length) for t in names}
    senses = {t.name: lc.engine.shaft(t.shaft).sense for t in lc.engine.throws}
    return BodyModel(units, places, senses, fe_inertia)


def candidate_bodies(model: BodyModel, loads: AssessedLoads, factors: dict[tuple[str, int], float]) -> BodyScreen:
    """The candidate's counterweight groups' peak (module doc); ``factors``: (throw, web)
    -> the mass factor k_w of that web's drawn counterweight (0: none)."""
    best, where = 0.0, ""
    for states in loads.speeds:
        for state in states:
            for name, tc in state.throws.items():
                unit = model.units[name]
                if not unit.groups:
                    continue
                places = model.places[name]
                C = fe_coefficients(  # with [torsion]: the throw's vibration, as the check's assess_throw
                    unit,
                    tc.pin_force,
                    tc.torque_in,
                    state.speed,
                    sense=model.senses[name],
                    rod_loads=rod_loads(tc, places),
                    angular_acceleration=tc.angular_acceleration,
                    fe_pin_force=tc.fe_pin_force,
                    fe_rod_loads=tc.fe_rod_loads(places) if tc.fe_rods else None,
                )
                for w in (1, 2):
                    C[:, unit.cases.index(f"centrifugal_cw_{w}")] *= factors.get((name, w), 0.0)
                for grp in sorted(unit.groups):
                    nodes = np.asarray(unit.groups[grp])
                    if not nodes.size:
                        continue
                    v = float(group_peak(unit, C, nodes)[1].max())
                    if v > best:
                        rpm = state.speed * 30 / math.pi
                        best, where = v, f"throw {name} {grp}, {state.case} at {rpm:.0f} rpm"
    return BodyScreen(best, where)


__all__ = ["BodyModel", "BodyScreen", "body_model", "candidate_bodies"]
