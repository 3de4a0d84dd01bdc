"""The torsional stage's computation, one owner for the check (``pipeline.torsion_stage``)
and the counterweight study (``study.torsion``): the forced response with every cylinder
firing and with each misfire case on the chain of the given throw inertias
(``misfire.analyse_misfire``), UR M53's hand-over of the journal torques (the worst
history of every case, ``misfire.MisfireTorsion.journal_torques``), the operating cycle
with those journal torques (``operating_dynamics``: what the whole shaft takes at the
operating speed's firing state) and the loads of every speed and state of the sweep with
their vibration (``loads.assessed_loads``)."""

from __future__ import annotations

from dataclasses import dataclass

from fe_crank.assess.loads import AssessedLoads
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.mechanism.dynamics import DynamicsResult
from fe_crank.model import Engine
from fe_crank.torsion.analysis import with_vibratory_torque
from fe_crank.torsion.handover import JournalTorque
from fe_crank.torsion.loads import assessed_loads
from fe_crank.torsion.misfire import MisfireTorsion, analyse_misfire
from fe_crank.torsion.model import TorsionCase


@dataclass(frozen=True)
class TorsionalResponse:
    """The forced response of every case and the journal torques handed to UR M53."""

    misfire: MisfireTorsion
    handed: dict[str, JournalTorque]  # segment name -> the worst history of every case

    @property
    def first_frequency(self) -> float:
        """The first elastic natural frequency of the chain (Hz)."""
        return float(self.misfire.firing.modes.elastic_hz[0])


def torsional_response(
    lc: TorsionCase, cycles: EngineCycles, *, inertias: dict[str, float], fe_stiffness: float | None = None
) -> TorsionalResponse:
    """The response on the dynamics stage's cylinder torques (``cycles.torques``) of the
    chain with the throws' inertias ``inertias`` (engine throw -> kg m^2 about the crank
    axis, ``build.throw_inertias``); ``fe_stiffness``: the FE throw stiffness (N m/rad,
    used with ``throw_stiffness = "fe"``)."""
    mis = analyse_misfire(lc, cycles.torques, inertias=inertias, fe_stiffness=fe_stiffness)
    return TorsionalResponse(mis, mis.journal_torques())


def operating_dynamics(cycles: EngineCycles, response: TorsionalResponse) -> DynamicsResult:
    """The operating cycle (``cycles.operating``) with the journal torques handed over
    (``response.handed``, ``analysis.with_vibratory_torque``): the operating speed's firing
    state of the whole shaft and the assessment with a torsional stage."""
    return with_vibratory_torque(cycles.operating, response.misfire.firing, handed=response.handed)


def torsional_loads(
    engine: Engine,
    cycles: EngineCycles,
    response: TorsionalResponse,
    fe_inertia: dict[str, float],
    *,
    reaction: str,
) -> AssessedLoads:
    """The loads of every speed and state with their vibration for the power take-off end
    ``reaction`` (``[fe] torque_reaction``; ``loads.assessed_loads``); ``fe_inertia``:
    engine throw -> the moment about the axis of its FE model's ``angular_acceleration``
    unit case (kg m^2)."""
    mis = response.misfire
    return assessed_loads(
        engine,
        cycles,
        reaction=reaction,
        torsion=mis.firing,
        misfire_torsion={c.cylinder: c.result for c in mis.cases},
        fe_inertia=fe_inertia,
        handed=response.handed,
    )


__all__ = ["TorsionalResponse", "operating_dynamics", "torsional_loads", "torsional_response"]
