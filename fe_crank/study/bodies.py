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
from fe_crank.assess.group.peak import BOUND_RTOL, group_peak
from fe_crank.assess.loads import AssessedLoads
from fe_crank.assess.stress import von_mises
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
    #: per load state and throw, what every candidate of the same loads shares
    #: (``candidate_bodies``)
    cache: dict = field(default_factory=dict, compare=False, repr=False)


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


@dataclass(frozen=True)
class BodyBase:
    """One load state of one throw, for every candidate (``candidate_bodies``): the
    coefficients with each counterweight's column as drawn (k_w = 1), the columns of the
    counterweights, and per group the part of ``peak.peak_bound``'s sum that no
    counterweight scales, max_t sum_c |a_c(t)| sigma_v(U_c) over the other cases, with
    sigma_v of each counterweight's case."""

    coefficients: np.ndarray
    columns: dict[int, int]  # web -> its centrifugal column
    free: dict[str, np.ndarray]  # group -> (n,) Pa
    vm_cw: dict[str, dict[int, np.ndarray]]  # group -> web -> (n,) Pa per unit coefficient


def body_base(unit: UnitStresses, coefficients: np.ndarray) -> BodyBase:
    """``BodyBase`` of the coefficients ``coefficients`` (every counterweight as drawn)."""
    C = np.asarray(coefficients, float)
    columns = {w: unit.cases.index(f"centrifugal_cw_{w}") for w in (1, 2)}
    other = np.ones(C.shape[1], bool)
    other[list(columns.values())] = False
    free, vm_cw = {}, {}
    for grp in sorted(unit.groups):
        nodes = np.asarray(unit.groups[grp])
        if not nodes.size:
            continue
        v = von_mises(unit.stress[:, :, nodes])  # (n_cases, n)
        free[grp] = (np.abs(C[:, other]) @ v[other]).max(axis=0)
        vm_cw[grp] = {w: v[k] for w, k in columns.items()}
    return BodyBase(C, columns, free, vm_cw)


def body_bound(base: BodyBase, group: str, coefficients: np.ndarray) -> np.ndarray | None:
    """An upper bound of each node's computed peak over the cycle of ``coefficients`` (the
    base's with the counterweights' columns scaled): ``peak.peak_bound``'s B, the
    counterweight-free part kept plus sum_w |a_w| sigma_v(U_w) (the columns constant, a_w
    their value: the same sum), widened by ``peak.BOUND_RTOL`` for the rounding of both
    sums; None where a counterweight's column varies over the cycle."""
    b = base.free[group].copy()
    for w, k in base.columns.items():
        col = coefficients[:, k]
        if not np.all(col == col[0]):
            return None
        if col[0] != 0.0:
            b += abs(float(col[0])) * base.vm_cw[group][w]
    out: np.ndarray = b * (1.0 + BOUND_RTOL)
    return out


def candidate_bodies(model: BodyModel, loads: AssessedLoads, factors: dict[tuple[str, int], float]) -> BodyScreen:
    """The candidate's counterweight groups' peak (module doc); ``factors``: (throw, web)
    -> the mass factor k_w of that web's drawn counterweight (0: none).

    Each state's coefficients and the counterweight-free part of each node's bound are
    taken once for every candidate of the same ``loads`` (``body_base``), the bound of
    the candidate's coefficients formed from them (``body_bound``), what ``group_peak``
    searches by.  A group whose largest bound does not exceed the largest peak found
    before (in the order of the states, throws and groups) cannot hold a larger one,
    which alone would change the value or its place: it is not searched.  The value and
    place are those of every group's search."""
    if model.cache.get("loads") is not loads:  # the bases of one loads object at a time
        model.cache.clear()
        model.cache["loads"] = loads
    best, where = 0.0, ""
    for i, states in enumerate(loads.speeds):
        for j, state in enumerate(states):
            for name, tc in state.throws.items():
                unit = model.units[name]
                if not unit.groups:
                    continue
                key = (i, j, name)
                if key not in model.cache:
                    places = model.places[name]
                    C0 = fe_coefficients(  # with [torsion]: the throw's vibration, as the check's assess_throw
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
                    model.cache[key] = body_base(unit, C0)
                base: BodyBase = model.cache[key]
                C = base.coefficients.copy()
                for w, k in base.columns.items():
                    C[:, k] *= factors.get((name, w), 0.0)
                for grp in sorted(unit.groups):
                    nodes = np.asarray(unit.groups[grp])
                    if not nodes.size:
                        continue
                    bound = body_bound(base, grp, C)
                    if bound is not None and float(bound.max()) <= best:
                        continue  # cannot exceed the largest peak found (docstring)
                    v = float(group_peak(unit, C, nodes, bound=bound)[1].max())
                    if v > best:
                        rpm = state.speed * 30 / math.pi
                        best, where = v, f"throw {name} {grp}, {state.case} at {rpm:.0f} rpm"
    return BodyScreen(best, where)


__all__ = ["BodyModel", "BodyScreen", "BodyBase", "body_model", "body_base", "body_bound", "candidate_bodies"]
