"""The torsional stage of the check (``pipeline.stages.run_stages`` runs it with a
``[torsion]`` section): the forced response with every cylinder firing and each misfire
case, and the loads it hands over to the assessment (docs/torsion.md)."""

from __future__ import annotations

from typing import cast

from fe_crank.errors import InputError
from fe_crank.fe.throw.unit_cases import UnitSolutions
from fe_crank.io.loadcase import LoadCase
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.outputs import GeometryModel, TorsionOutput
from fe_crank.torsion.build import throw_inertias
from fe_crank.torsion.loads import fe_inertias
from fe_crank.torsion.model import TorsionCase
from fe_crank.torsion.stage import operating_dynamics, torsional_loads, torsional_response
from fe_crank.torsion.stiffness import plan_throw_stiffness


def torsion_stage(
    lc: LoadCase, geo: GeometryModel, unit_solutions: dict[str, UnitSolutions], cycles: EngineCycles
) -> TorsionOutput:
    """The torsional forced response (``torsion.analysis``) excited by the dynamics stage's
    cylinder torques (``cycles.torques``), with the throws' inertias from
    the geometry stage's CAD mass properties, with every cylinder firing and with each
    misfire case of ``[operating] misfire`` (``torsion.stage.torsional_response``); the FE
    throw stiffness is measured from the torque unit case of the plan's first throw model
    when it is there (``torsion.stiffness.plan_throw_stiffness``; the report shows it
    beside Carter's; it is used when ``throw_stiffness = "fe"``).  Hands over the
    loads of every speed of the sweep and state with their vibration
    (``torsion.stage.torsional_loads``) and UR M53's journal torques (the largest half
    range over the speed range and every case, ``torsion.handover``)."""
    settings = lc.torsion
    assert settings is not None
    assert lc.geometry is not None and lc.material is not None  # the FE stage ran
    k_fe = plan_throw_stiffness(lc.geometry, geo.plan, lc.material, lc.fe, unit_solutions)
    if settings.throw_stiffness == "fe" and k_fe is None:
        raise InputError(
            "throw_stiffness = 'fe' needs the FE torque unit case", file=lc.source_file, key="torsion.throw_stiffness"
        )
    # a CAD geometry with [torsion] is refused at input (io.loadcase): the case is a TorsionCase
    response = torsional_response(
        cast(TorsionCase, lc), cycles, inertias=throw_inertias(cast(TorsionCase, lc), geo.solids), fe_stiffness=k_fe
    )
    mis = response.misfire
    loads = torsional_loads(
        lc.engine,
        cycles,
        response,
        fe_inertias(unit_solutions, cycles.operating.throws),
        reaction=lc.fe.torque_reaction,
    )
    return TorsionOutput(
        mis.firing,
        operating_dynamics(cycles, response),
        misfire=mis if mis.cases else None,
        loads=loads,
    )
