"""The whole-shaft stage: every throw of the shaft in one model on all its main bearings.

It runs when the geometry stage placed the shaft (``GeometryModel.shaft``: an engine of
several throws on one shaft, or a single throw whose geometry states its shaft, a
``[shaft]`` section), after the FE and torsional stages and before the assessment
(docs/shaft.md).  It computes the shaft and nothing of its assessment:

* the shaft (meshed by the mesh stage, ``cad.source.mesh_models``) condensed and solved
  on its bearings over the operating cycle, with and without counterweights, and over the
  overspeed cycles (``fe.shaft.whole_shaft.analyse_whole_shaft``, with the masses of the
  throws' solids, parametric or drawn); each journal carries its own torque
  (``torque_flow``: the journal torques the assessment takes, with the torsional stage's
  vibratory torque when it ran);
* its main bearings' loads at every speed and load state of the full-load sweep
  (``assess.shaft.bearing_sweep``);
* the hydrodynamic main bearings' oil film in each of those states, with and without
  counterweights (``assess.oil_film.film_sweep``: the journals' periodic orbits under
  those loads; the film does not change the shaft's solution).

Its unit cases go to the assess stage, which assesses the shaft's throws beside the
per-throw model (``assess.case``); the whole mesh's state at the governing angle, for the
report's picture and ``.vtu``, is ``shaft_fields_stage``, after the assessment.
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np

from fe_crank.assess.loads import FIRING
from fe_crank.assess.oil_film import film_sweep
from fe_crank.assess.shaft import BearingState, ShaftHotSpot, WholeShaftOutput, bearing_sweep
from fe_crank.cad.config import CadInput
from fe_crank.cad.source import Meshes
from fe_crank.cad.whole import cad_throw_masses
from fe_crank.fe.shaft.fields import ShaftFields, shaft_fields
from fe_crank.fe.shaft.model import ShaftFeOptions
from fe_crank.fe.shaft.whole_shaft import analyse_whole_shaft, throw_masses
from fe_crank.io.loadcase import LoadCase
from fe_crank.outputs import CaseOutputs, GeometryModel


def whole_shaft_stage(
    lc: LoadCase, geo: GeometryModel, meshes: Meshes, out: CaseOutputs, keep_factors: bool
) -> WholeShaftOutput:
    """The stage (module doc) on the mesh stage's ``meshes``; ``keep_factors``: keep the pieces'
    factorisations for their whole fields (the state the report draws, ``shaft_fields_stage``;
    the convergence study's load sets, ``fe.shaft.refinement``)."""
    mat, layout, sm = lc.material, geo.shaft, meshes.shaft
    assert layout is not None and sm is not None and mat is not None and out.cycles is not None
    dyn = out.assessed_dynamics
    assert dyn is not None
    overspeed = tuple(c.dynamics for c in out.cycles.overspeed) if lc.operating.overspeed is not None else ()
    options = ShaftFeOptions(
        solver=lc.fe.solver, pin_half_angle=lc.fe.pin_half_angle, symmetry=lc.fe.symmetry, keep_factors=keep_factors
    )
    features = geo.cad
    if features is not None and isinstance(lc.geometry, CadInput):  # the shaft as drawn: its throws' masses
        mass = cad_throw_masses(features, layout)
    else:
        mass = throw_masses(layout)
    result, cases = analyse_whole_shaft(
        sm, mat, dyn, mass=mass, options=options, torque_flow=lc.torsion is not None, overspeed=overspeed
    )
    # the shaft's mesh time is the mesh stage's, reported with the shaft's own (results.json)
    result = dataclasses.replace(result, timings={"mesh": meshes.shaft_seconds, **result.timings})
    try:
        t0 = time.perf_counter()
        sweep = bearing_sweep(out.cycles, cases, layout, result)
        t1 = time.perf_counter()
        own = (BearingState(float(dyn.speed), FIRING, result.bearings),)
        film = film_sweep(layout, sweep or own, result.crank_angle_deg)
        t = {"sweep": t1 - t0, **({"oil_film": time.perf_counter() - t1} if film else {})}
        result = dataclasses.replace(result, timings={**result.timings, **t})
    except BaseException:
        cases.model.free_factors()
        raise
    return WholeShaftOutput(layout, result, dyn, sweep, cases, film)


def shaft_fields_stage(lc: LoadCase, ws: WholeShaftOutput, hot_spot: ShaftHotSpot | None) -> ShaftFields | None:
    """The whole mesh's state at the angle of the whole shaft's largest von Mises stress
    (``hot_spot``, the assessment's), for the report's picture and ``.vtu``; None without a
    hot spot.  The throws' recovery fields go first (the assessment has read them), the
    factorisations after."""
    assert lc.material is not None and ws.cases is not None
    cases = ws.cases
    try:
        if hot_spot is None:
            return None
        cases.model.release_recovery()
        k = int(np.argmin(np.abs(np.degrees(np.asarray(ws.dynamics.theta)) - hot_spot.angle_deg)))
        return shaft_fields(
            cases, ws.result.cycles[0].weights[k], lc.material, lc.fe.solver, mark=np.asarray(hot_spot.point)
        )
    finally:
        cases.model.free_factors()
