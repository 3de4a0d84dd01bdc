"""The counterweights' own stress in the counterweight study (docs/study.md): the
per-throw model of the drawn geometry (each throw on its own supports, the check's mesh
plan and meshes, ``mesh.plan``), solved once per study with the centrifugal case split
into the throw's own and each counterweight body's (``fe.core.loads.BODY_CASES``); a
candidate's counterweight on web w, the drawn shape scaled in mass by k_w, is then k_w
times that web's case: per load state the check's coefficients (``assess.superpose
.cycle_coefficients``: the pin cases, the torque, omega^2 on every centrifugal part) with
the web's column times k_w, and each counterweight group's (bodies, transition fillets,
junctions) peak von Mises over the cycle by the check's own search
(``assess.group.peak.group_peak``): the per-throw model's ``counterweight_stress``."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from fe_crank.assess.group.assessment import of_counterweight
from fe_crank.assess.group.nodes import assessed_groups, unit_stresses
from fe_crank.assess.group.peak import group_peak
from fe_crank.assess.loads import AssessedLoads
from fe_crank.assess.superpose import UnitStresses, cycle_coefficients
from fe_crank.cad.source import mesh_source_throw
from fe_crank.fe import solve_unit_cases
from fe_crank.fe.core.loads import CENTRIFUGAL_PARTS
from fe_crank.fe.throw.pin_patches import pin_patch_options, rod_loads, rod_positions
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.io.loadcase import LoadCase
from fe_crank.mesh.plan import plan_meshes
from fe_crank.throw_scope import throws_of


@dataclass(frozen=True)
class BodyModel:
    units: dict[str, UnitStresses]  # engine throw -> its model's stresses at the counterweight groups
    places: dict[str, dict[str, float]]  # engine throw -> each rod's place on the pin, m
    senses: dict[str, int]


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
    options = dataclasses.replace(lc.fe, cases=cases)
    meshes = {
        key: mesh_source_throw(g, name, size=plan.options, cache_dir=plan.cache_dir, max_elements=plan.max_elements)
        for key, name in plan.throws.items()
    }
    solved: dict[str, UnitStresses] = {}
    units: dict[str, UnitStresses] = {}
    for key, m in meshes.items():
        if m.key not in solved:
            throws = [t for k, other in meshes.items() if other.key == m.key for t in throws_of(k, list(names))]
            opts = pin_patch_options(options, lc.engine, layout.geometry.crankpin_length, throws)
            us = solve_unit_cases(m, mat, opts)
            groups = {n: nodes for n, nodes in assessed_groups(us).items() if of_counterweight(n)}
            solved[m.key] = unit_stresses(us, groups)
            us.system.factorisation.free()
        for t in throws_of(key, list(names)):
            units[t] = solved[m.key]
    places = {t: rod_positions(lc.engine, t, layout.geometry.crankpin_length) for t in names}
    senses = {t.name: lc.engine.shaft(t.shaft).sense for t in lc.engine.throws}
    return BodyModel(units, places, senses)


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
                C = cycle_coefficients(
                    unit,
                    tc.pin_force,
                    tc.torque_in,
                    state.speed,
                    sense=model.senses[name],
                    rod_loads=rod_loads(tc, model.places[name]),
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
