"""``assess_case``: the assessment of one load case, every throw, its criteria."""

from __future__ import annotations

from fe_crank.assess import m53_oil_bore
from fe_crank.assess.adapters import counterweights_of, m53_geometry_of
from fe_crank.assess.case import Assessment, assess_throw, evaluate_criteria
from fe_crank.assess.groups import ASSESSED_BOUNDARIES, assessed_groups, unit_stresses
from fe_crank.assess.m53_basis import m53_basis
from fe_crank.assess.overspeed import describe as describe_overspeed
from fe_crank.assess.overspeed import overspeed_cycles
from fe_crank.assess.recovery import recovery_notes, recovery_ratios
from fe_crank.assess.scf import scf_provider
from fe_crank.errors import InputError
from fe_crank.fe.pin_patches import rod_loads, rod_positions
from fe_crank.throw_scope import throws_of


def _hook(obj, name, *args):
    f = getattr(obj, name, None)
    return f(*args) if callable(f) else None


def _cycle(tl, places):
    """(pin force, front torque, rod loads) of a throw's cycle (``assess_throw``'s overspeed)."""
    return tl.pin_force, tl.torque_front, rod_loads(tl, places)


def assess_case(loadcase, dynamics, balance, throw_meshes, unit_solutions, *, threads: int = 1) -> Assessment:
    """Assess one load case.

    ``throw_meshes`` and ``unit_solutions`` are dicts keyed alike
    (``fe_crank.throw_scope``): a key is the name of one throw of the engine, or
    ``ALL_THROWS``, the mesh then standing for every throw, each assessed on it with its
    own loads.  Any other key is a ValueError.  UR M53 dimensions and the
    counterweights' m r and bolts come from the ``CrankGeometry`` (``adapters.py``) and
    the balance stage's ``BalanceResult.design``; a geometry object may instead offer
    ``m53_geometry(throw) -> M53Geometry`` and ``counterweights(throw) ->
    tuple[CounterweightData]``.  ``threads``: the node blocks of every group (and the
    unit-stress recovery) on that many threads, the same results bit for bit as one
    (``assess.workers``); the caller says how many cores are this case's.
    """
    lc = loadcase
    material = lc.material
    if material is None:
        raise InputError("the assessment needs a [material] section", file=lc.source_file, key="material")
    criteria = lc.criteria
    if criteria is None or not criteria.limits:
        raise InputError(
            "the assessment needs a [criteria] section with at least one limit", file=lc.source_file, key="criteria"
        )
    omega, overspeed = lc.operating.speed, lc.operating.overspeed
    notes = [
        "stresses: linear elastic FE, nodal averages; histories by unit-load superposition (exact)",
        "UR M53 nominal torsion from the journal torque (side with the larger alternating part); torsional vibration "
        + (
            "included: quasi-static + vibratory journal torque ([torsion], docs/torsion.md)"
            if "torsion" in lc.extras
            else "not included (no [torsion] section)"
        ),
    ]
    basis = m53_basis(lc.engine, material, criteria.m53_additional_bending, file=lc.source_file)
    notes.extend(basis.notes)
    cycles_os = overspeed_cycles(lc, dynamics)
    if cycles_os:
        notes.insert(1, describe_overspeed(lc))
    throws = []
    scf_cache: dict = {}  # SCF mode (UR M53 App. III), solved only for a throw outside the empirical range
    solved: dict = {}  # keys sharing one FE solution (equal meshes) share its unit stresses
    solids: list = []  # counterweight mass properties of equal throw solids (adapters.counterweights_of)
    for key, units in unit_solutions.items():
        if id(units) not in solved:
            groups = assessed_groups(units)
            unit = unit_stresses(units, groups, threads=threads)
            boundary_groups = {g: units_nodes for g, units_nodes in groups.items() if g in ASSESSED_BOUNDARIES}
            solved[id(units)] = unit, recovery_notes(recovery_ratios(units, boundary_groups, unit=unit))
        unit, recovery = solved[id(units)]
        notes.extend(f"mesh {key}: {n}" for n in recovery)
        for tname in throws_of(key, dynamics.throws):
            tl = dynamics.throws[tname]
            throw = lc.engine.throw(tname)
            sense = lc.engine.shaft(throw.shaft).sense
            m53g = _hook(lc.geometry, "m53_geometry", tname)
            if m53g is None:
                m53g = m53_geometry_of(lc.geometry)
            pin_length = getattr(lc.geometry, "crankpin_length", None)  # None: the summed force at mid-pin
            places = rod_positions(lc.engine, tname, pin_length) if pin_length else {}
            rods = rod_loads(tl, places)
            cws = _hook(lc.geometry, "counterweights", tname)
            if cws is None:
                gthrow = getattr(throw_meshes.get(key), "throw", None)
                cws = counterweights_of(lc.geometry, gthrow, throw.axial_position, throw.shaft, balance, solids=solids)
            throws.append(
                assess_throw(
                    tname,
                    unit,
                    dynamics.theta,
                    tl.pin_force,
                    tl.torque_front,
                    omega=omega,
                    sense=sense,
                    overspeed=overspeed,
                    material=material,
                    crank_radius=throw.crank_radius,
                    m53_geometry=m53g,
                    m53_additional=basis.additional,
                    m53_ke=basis.ke,
                    counterweights=tuple(cws),
                    torque_rear=tl.torque_rear,
                    threads=threads,
                    overspeed_loads=[_cycle(c.dynamics.throws[tname], places) for c in cycles_os] or None,
                    rod_loads=rods,
                    scf=None
                    if m53g is None
                    else scf_provider(
                        scf_cache,
                        key,
                        throw_meshes.get(key, units.mesh),
                        lc.geometry,
                        material,
                        m53g,
                        solver=getattr(lc.fe, "solver", None) or "auto",
                    ),
                )
            )
            if m53g is None:
                notes.append(f"throw {tname}: no UR M53 dimensions from the geometry; M53 route not run")
            elif m53g.oil_bore_diameter > 0 and m53_oil_bore.in_range(m53g) is not None:
                notes.append(
                    f"throw {tname}: UR M53 oil-bore outlet not assessed empirically "
                    f"({m53_oil_bore.in_range(m53g)}); FE route only (group oil_bore)"
                )
    verdicts = evaluate_criteria(criteria, tuple(throws), file=lc.source_file, overspeed=overspeed)
    return Assessment(lc.name, lc.source_file, omega, overspeed, material, tuple(throws), verdicts, tuple(notes))
