"""Displacement states of one throw at one crank angle, by superposition of the FE unit
cases with the assessment's own coefficients (``fe_crank.assess.superpose``)::

    u(theta) = omega^2 u_c + sum_k a_k(F(theta)) u_pk - sense T(theta) / M_z u_t

Stress recovery is linear in u, so the stress of this state equals the assessment's
superposed unit stresses at every node: the pictures and the tables agree.
"""

from __future__ import annotations

import numpy as np

from fe_crank.assess.superpose import load_coefficients
from fe_crank.torsion.stage import dynamics_for_assessment


def assessed_dynamics(stage_out: dict):
    """The dynamics the assessment used (``check.stages._assess_stage``): the journal
    torques carry the vibratory torque when the torsional stage ran."""
    dyn = stage_out.get("dynamics")
    return None if dyn is None else dynamics_for_assessment(dyn, stage_out.get("torsion"))


def angle_index(dyn, angle: float | None) -> int:
    """Index of the cycle angle nearest ``angle`` (the first of equals)."""
    if angle is None:
        return 0
    return int(np.argmin(np.abs(np.asarray(dyn.theta) - angle)))


def field_at_angle(units, dyn, lc, throw: str, index: int) -> np.ndarray:
    """Displacement of the throw at cycle-angle index ``index`` of ``dyn`` (the operating
    cycle, or the overspeed cycle: ``dyn.speed`` is the omega of its centrifugal term)."""
    tl = dyn.throws[throw]
    sense = lc.engine.shaft(lc.engine.throw(throw).shaft).sense
    cases = tuple(units.cases)
    mz = float(units.cases["torque"].applied[5]) if "torque" in units.cases else -1.0
    c = load_coefficients(
        tl.pin_force[index : index + 1],
        tl.torque_front[index : index + 1],
        dyn.speed,
        cases=cases,
        sense=sense,
        torque_mz=mz,
    )[0]
    return units.combine(dict(zip(cases, c)))
