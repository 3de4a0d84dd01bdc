"""The whole-shaft stage: every throw of the shaft in one model on all its main bearings.

It runs for an engine of several throws on one shaft, and for a single throw whose
geometry states its shaft (a ``[shaft]`` section), after the FE and torsional stages and
before the assessment (docs/shaft.md):

* the shaft placed by the engine (``geometry.shaft.shaft_layout``; a geometry of one
  throw stands for every throw, ``for_engine_throws``), meshed, condensed and solved on
  its bearings over the operating cycle, with and without counterweights, and over the
  overspeed cycles (``fe.whole_shaft.analyse_whole_shaft``); each journal carries its own
  torque (``torque_flow``: the journal torques the assessment takes, with the torsional
  stage's vibratory torque when it ran);
* its main bearings' loads at every speed and load state of the full-load sweep
  (``bearing_sweep``, the main-bearing criteria's worst speed);
* the hydrodynamic main bearings' oil film in each of those states, with and without
  counterweights (``assess.oil_film.film_sweep``: the journals' periodic orbits under
  those loads; the film does not change the shaft's solution);
* its throws' fillets, oil bores and counterweight junctions assessed by the per-throw
  model's code (``assess.shaft``) at the operating speed and the overspeed, for the
  criteria beside the per-throw model;
* the whole mesh's state at the angle of its largest von Mises stress, for the report's
  picture and ``.vtu`` (``fe.shaft_fields``), when those are wanted.
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np

from fe_crank.assess.loads import FIRING, misfire_label
from fe_crank.assess.m53_basis import m53_basis
from fe_crank.assess.oil_film import film_sweep
from fe_crank.assess.shaft import BearingState, ShaftAssessment, assess_shaft_throws
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.fe.shaft_cases import ShaftCases
from fe_crank.fe.shaft_fields import shaft_fields
from fe_crank.fe.shaft_model import ShaftFeOptions
from fe_crank.fe.whole_shaft import WholeShaftResult, analyse_whole_shaft, bearings_of, throw_masses
from fe_crank.geometry.shaft import ShaftLayout, engine_shaft_layout, whole_shaft_wanted
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.io.loadcase import LoadCase
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.mesh.options import MeshOptions
from fe_crank.mesh.shaft import place, shaft_options
from fe_crank.outputs import CaseOutputs, GeometryModel, ShaftHotSpot, WholeShaftOutput


def wanted(lc: LoadCase) -> bool:
    """Whether the whole-shaft stage runs (``geometry.shaft.whole_shaft_wanted``: several
    throws on one shaft, or a ``[shaft]`` section) for a load case with a material and a
    parametric geometry (a CAD geometry's throws are meshed from the file one by one, on
    the journals' middles it recognises: the per-throw model alone, docs/shaft.md)."""
    g = lc.geometry
    return lc.material is not None and isinstance(g, CrankGeometry) and whole_shaft_wanted(g, lc.engine)


def layout_of(lc: LoadCase) -> ShaftLayout:
    """The shaft of the load case placed by its engine (a geometry of one throw stands for
    every throw, ``geometry.shaft.engine_shaft_layout``)."""
    g = lc.geometry
    assert isinstance(g, CrankGeometry)
    return engine_shaft_layout(
        g, lc.engine, geometry_file=g.file or lc.source_file, engine_file=lc.engine_file or lc.source_file
    )


def throw_mesh_options(lc: LoadCase, options: MeshOptions) -> MeshOptions:
    """The per-throw model's mesh options when the whole shaft runs: the whole shaft's
    (``mesh.shaft.shaft_options``: end faces split into rotated-copy sectors), so that both
    models mesh each throw once (one cached mesh)."""
    return shaft_options(layout_of(lc), options)


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


def whole_shaft_stage(lc: LoadCase, geo: GeometryModel, out: CaseOutputs, fields: bool) -> WholeShaftOutput:
    """The stage (module doc); ``fields``: also the whole mesh's state at the governing
    angle (the report's picture and ``.vtu``)."""
    g, mat = lc.geometry, lc.material
    assert isinstance(g, CrankGeometry) and mat is not None and out.cycles is not None
    dyn = out.assessed_dynamics
    assert dyn is not None
    layout = layout_of(lc)
    overspeed = tuple(c.dynamics for c in out.cycles.overspeed) if lc.operating.overspeed is not None else ()
    options = ShaftFeOptions(
        solver=lc.fe.solver, pin_half_angle=lc.fe.pin_half_angle, symmetry=lc.fe.symmetry, keep_factors=fields
    )
    result, cases = analyse_whole_shaft(
        layout,
        mat,
        dyn,
        size=geo.plan.options,
        cache_dir=geo.plan.cache_dir,
        options=options,
        torque_flow=lc.torsion is not None,
        overspeed=overspeed,
        max_elements=geo.plan.max_elements,
    )
    try:
        t0 = time.perf_counter()
        sweep = bearing_sweep(out.cycles, cases, layout, result)
        t1 = time.perf_counter()
        own = (BearingState(float(dyn.speed), FIRING, result.bearings),)
        film = film_sweep(layout, sweep or own, result.crank_angle_deg)
        t = {"sweep": t1 - t0, **({"oil_film": time.perf_counter() - t1} if film else {})}
        result = dataclasses.replace(result, timings={**result.timings, **t})
        return _assessed(lc, geo, layout, dyn, result, cases, fields, sweep, film)
    finally:
        cases.model.free_factors()


def bearing_sweep(
    cycles: EngineCycles, cases: ShaftCases, layout: ShaftLayout, result: WholeShaftResult
) -> tuple[BearingState, ...]:
    """The main bearings' loads at every speed and load state of the full-load sweep (every
    cylinder firing, each misfire case; ``mechanism.cycles.EngineCycles.sweep``): the
    operating speed's firing state is the stage's own cycle (``result``, with the torsional
    stage's journal torques when it ran), the others the dynamics stage's cycles on the
    condensed shaft (``fe.whole_shaft.bearings_of``; each journal's torque quasi-static)."""
    mass = throw_masses(layout)
    out = []
    for sc in cycles.sweep:
        own = sc.firing is cycles.operating
        out.append(
            BearingState(sc.speed, FIRING, result.bearings if own else bearings_of(cases, layout, mass, sc.firing))
        )
        out.extend(
            BearingState(sc.speed, misfire_label(m.cylinder), bearings_of(cases, layout, mass, m.dynamics))
            for m in sc.misfire
        )
    return tuple(out)


def _assessed(
    lc: LoadCase,
    geo: GeometryModel,
    layout: ShaftLayout,
    dyn,
    result: WholeShaftResult,
    cases: ShaftCases,
    fields: bool,
    sweep: tuple[BearingState, ...],
    film: tuple = (),
) -> WholeShaftOutput:
    """The whole shaft's throws assessed and its governing state (``whole_shaft_stage``)."""
    mat, g = lc.material, lc.geometry
    assert mat is not None and isinstance(g, CrankGeometry)
    t0 = time.perf_counter()
    stated = lc.criteria.m53_additional_bending if lc.criteria is not None else None
    basis = m53_basis(lc.engine, mat, stated, file=lc.source_file)
    diameters: dict[str, tuple[float | None, float | None]] = {
        name: (tg.m53.pin_diameter, tg.m53.journal_diameter) if tg.m53 is not None else (None, None)
        for name, tg in geo.throws.items()
    }
    throws = assess_shaft_throws(
        cases,
        result,
        dyn.theta,
        mat,
        crank_radius=g.crank_radius,
        overspeed=lc.operating.overspeed,
        diameters=diameters,
        additional_bending=basis.additional,
    )
    worst = governing(throws, layout)
    t = {"assessment": time.perf_counter() - t0}
    state = None
    if fields and worst is not None:
        t0 = time.perf_counter()
        cases.model.release_recovery()  # the assessed nodes' fields are taken: their memory goes first
        k = int(np.argmin(np.abs(np.degrees(np.asarray(dyn.theta)) - worst.angle_deg)))
        state = shaft_fields(cases, result.cycles[0].weights[k], mat, lc.fe.solver, mark=np.asarray(worst.point))
        t["fields"] = time.perf_counter() - t0
    result = dataclasses.replace(result, timings={**result.timings, **t})
    assessed = ShaftAssessment(throws, result.bearings, float(dyn.speed), sweep, film)
    return WholeShaftOutput(layout, result, assessed, worst, state)
