"""The torsional stage as the check runs it: two calls for the pipeline.

``torsion_stage(lc, units)`` -> ``TorsionResult`` or ``None`` (no ``[torsion]`` section:
the check stays quasi-static and the report says so).  The FE throw stiffness is always
measured from the FE stage's torque unit case when it is there, so the report shows it
beside Carter's; it is used when ``throw_stiffness = "fe"``.

``dynamics_for_assessment(dynamics, torsion)`` -> the dynamics result whose journal
torques carry the vibratory torque (unchanged without torsion).
"""

from __future__ import annotations

from fe_crank.errors import InputError
from fe_crank.torsion.analysis import analyse_torsion, with_vibratory_torque
from fe_crank.torsion.stiffness import fe_throw_stiffness


def torsion_stage(lc, units: dict | None = None):
    settings = lc.extras.get("torsion")
    if settings is None:
        return None
    k_fe = None
    first = next(iter((units or {}).values()), None)
    if first is not None and "torque" in first.cases:
        k_fe = fe_throw_stiffness(first)
    if settings.throw_stiffness == "fe" and k_fe is None:
        raise InputError(
            "throw_stiffness = 'fe' needs the FE torque unit case", file=lc.source_file, key="torsion.throw_stiffness"
        )
    return analyse_torsion(lc, fe_stiffness=k_fe)


def dynamics_for_assessment(dynamics, torsion):
    return dynamics if torsion is None else with_vibratory_torque(dynamics, torsion)
