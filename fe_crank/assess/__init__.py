"""Cycle assessment: unit-load superposition, static and fatigue safety, UR M53,
counterweights, criteria -> verdicts (issue 6).  See docs/assessment.md.

Public API: ``assess_case(loadcase, dynamics, balance, throw_meshes, unit_solutions)
-> Assessment`` and ``to_json(assessment) -> dict``.
"""

from __future__ import annotations

import numpy as np

from fe_crank.assess.adapters import counterweights_of, m53_geometry_of
from fe_crank.assess.case import Assessment, ThrowAssessment, assess_throw, evaluate_criteria
from fe_crank.assess.counterweight import CounterweightData
from fe_crank.assess.m53 import M53Geometry
from fe_crank.assess.recovery import recovery_notes, recovery_ratios
from fe_crank.assess.results import to_json
from fe_crank.assess.superpose import UnitStresses, load_coefficients, unit_nodal_stress
from fe_crank.fe.pin_directions import pin_direction
from fe_crank.errors import InputError

#: boundary groups assessed at their nodes; subdomains assessed with all their nodes
ASSESSED_BOUNDARIES = ("crankpin_fillet_1", "crankpin_fillet_2", "journal_fillet_1", "journal_fillet_2", "oil_bore")
COUNTERWEIGHTS = ("counterweight_1", "counterweight_2")


def _element_nodes(units, elements) -> np.ndarray:
    return np.unique(np.asarray(units.system.basis.element_dofs)[:, elements])


def assessed_groups(units) -> dict[str, np.ndarray]:
    """Mesh node numbers of every assessed group present in the mesh: the fillet and
    oil-bore boundaries (all P2 nodes of their facets), each counterweight subdomain and
    its junction with the web (nodes shared by the counterweight's and the web's
    elements)."""
    mesh, basis = units.mesh, units.system.basis
    groups = {}
    for name in ASSESSED_BOUNDARIES:
        if name in (mesh.boundaries or {}):
            groups[name] = np.unique(basis.get_dofs(facets=mesh.boundaries[name]).all())
    subs = mesh.subdomains or {}
    for i, cw in enumerate(COUNTERWEIGHTS, start=1):
        if cw in subs:
            cw_nodes = _element_nodes(units, subs[cw])
            groups[cw] = cw_nodes
            web = f"web_{i}"
            if web in subs:
                junction = np.intersect1d(cw_nodes, _element_nodes(units, subs[web]))
                if junction.size:
                    groups[f"junction_{i}"] = junction
    return groups


def unit_stresses(units, groups: dict[str, np.ndarray] | None = None) -> UnitStresses:
    """Nodal stresses of every solved unit case at the assessed nodes (FE stage's
    ``UnitSolutions``).  Stress recovery is linear in u, so these are exact unit fields."""
    groups = assessed_groups(units) if groups is None else groups
    if not groups:
        raise InputError("the mesh has none of the assessed groups "
                         f"({', '.join(ASSESSED_BOUNDARIES + COUNTERWEIGHTS)})", key="geometry")
    ids = np.unique(np.concatenate(list(groups.values())))
    local = {k: np.searchsorted(ids, v) for k, v in groups.items()}
    cases = tuple(c for c in units.cases if c in ("centrifugal", "torque") or pin_direction(c) is not None)
    stress = unit_nodal_stress(units, cases, ids)   # = stress_at_nodes(u_c)[:, ids], assessed elements only
    mz = float(units.cases["torque"].applied[5]) if "torque" in units.cases else -1.0
    return UnitStresses(stress=stress, points=np.asarray(units.points)[:, ids], groups=local, node_ids=ids,
                        cases=cases, torque_mz=mz)


def _hook(obj, name, *args):
    f = getattr(obj, name, None)
    return f(*args) if callable(f) else None


def assess_case(loadcase, dynamics, balance, throw_meshes, unit_solutions) -> Assessment:
    """Assess one load case.

    ``throw_meshes`` and ``unit_solutions`` are dicts keyed alike (the pipeline's
    ``{"throw": ...}``); each key names a throw of the engine, or, when the key is not a
    throw name, the mesh stands for every throw and the most loaded throw's history is
    used for each (all throws are assessed on that mesh).  UR M53 dimensions and the
    counterweights' m r and bolts come from the ``CrankGeometry`` (``adapters.py``) and
    the balance stage's ``BalanceResult.design``; a geometry object may instead offer
    ``m53_geometry(throw) -> M53Geometry`` and ``counterweights(throw) ->
    tuple[CounterweightData]``.
    """
    lc = loadcase
    material = lc.material
    if material is None:
        raise InputError("the assessment needs a [material] section", file=lc.source_file, key="material")
    criteria = lc.criteria
    if criteria is None or not criteria.limits:
        raise InputError("the assessment needs a [criteria] section with at least one limit",
                         file=lc.source_file, key="criteria")
    omega, overspeed = lc.operating.speed, lc.operating.overspeed
    notes = [
        "stresses: linear elastic FE, nodal averages; histories by unit-load superposition (exact)",
        "overspeed: centrifugal unit case alone, scaled by omega_os^2",
        "UR M53 nominal torsion from the journal torque (side with the larger alternating part); torsional vibration not included",
    ]
    throws = []
    for key, units in unit_solutions.items():
        unit = unit_stresses(units)
        boundary_groups = {g: units_nodes for g, units_nodes in assessed_groups(units).items()
                           if g in ASSESSED_BOUNDARIES}
        notes.extend(f"mesh {key}: {n}" for n in recovery_notes(recovery_ratios(units, boundary_groups)))
        names = [key] if key in dynamics.throws else list(dynamics.throws)
        for tname in names:
            tl = dynamics.throws[tname]
            throw = lc.engine.throw(tname)
            sense = lc.engine.shaft(throw.shaft).sense
            m53g = _hook(lc.geometry, "m53_geometry", tname)
            if m53g is None:
                m53g = m53_geometry_of(lc.geometry)
            cws = _hook(lc.geometry, "counterweights", tname)
            if cws is None:
                gthrow = getattr(throw_meshes.get(key), "throw", None)
                cws = counterweights_of(lc.geometry, gthrow, throw.axial_position, throw.shaft, balance)
            throws.append(assess_throw(
                tname, unit, dynamics.theta, tl.pin_force, tl.torque_front, omega=omega, sense=sense,
                overspeed=overspeed, material=material, crank_radius=throw.crank_radius, m53_geometry=m53g,
                m53_additional=criteria.m53_additional_bending, counterweights=tuple(cws),
                torque_rear=tl.torque_rear,
            ))
            if m53g is None:
                notes.append(f"throw {tname}: no UR M53 dimensions from the geometry; M53 route not run")
    verdicts = evaluate_criteria(criteria, tuple(throws), file=lc.source_file, overspeed=overspeed)
    return Assessment(lc.name, lc.source_file, omega, overspeed, material, tuple(throws), verdicts, tuple(notes))


__all__ = ["assess_case", "to_json", "Assessment", "ThrowAssessment", "assess_throw", "evaluate_criteria",
           "UnitStresses", "load_coefficients", "unit_stresses", "assessed_groups", "M53Geometry",
           "CounterweightData"]
