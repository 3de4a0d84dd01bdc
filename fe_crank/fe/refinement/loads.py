"""The load sets of the hot-spot convergence study (``fe_crank.fe.refinement.convergence``): unit-case
weights {load set: {unit case: weight}} applied on every level."""

from __future__ import annotations

import numpy as np

#: default loads: the radial crankpin force (firing direction, towards the axis) and the torque, 1 N / 1 N m
DEFAULT_LOADS = {"pin_-y": {"pin_-y": 1.0}, "torque": {"torque": 1.0}}


def check_loads(throw_loads, omega: float) -> dict[str, dict[str, float]]:
    """Load sets of the check's study from the dynamics of one or more throws.

    ``throw_loads``: objects with ``pin_force`` (n, 2) in the throw frame (N) and
    ``torque_front``/``torque_rear`` (n,) (N m), e.g. ``DynamicsResult.throws`` values.
    "peak pin force": the largest crankpin force of the cycle (pin unit cases by the two
    bracketing directions) with the centrifugal load at ``omega`` (rad/s); "peak torque":
    the largest journal torque through the throw (skipped when zero).
    """
    from fe_crank.fe.throw.pin_directions import pin_case_weights, pin_cases

    best, tmax = None, 0.0
    for tl in throw_loads:
        F = np.asarray(tl.pin_force, float)
        i = int(np.argmax(np.hypot(F[:, 0], F[:, 1])))
        if best is None or np.hypot(*F[i]) > np.hypot(*best):
            best = F[i]
        tmax = max(tmax, float(np.abs(tl.torque_front).max()), float(np.abs(tl.torque_rear).max()))
    names = pin_cases()
    w = pin_case_weights(np.asarray(best, float)[None, :], names)[0]
    pin = {n: float(x) for n, x in zip(names, w) if x != 0.0}
    loads = {"peak pin force": {**pin, "centrifugal": float(omega) ** 2}}
    if tmax > 0:
        loads["peak torque"] = {"torque": tmax}
    return loads


__all__ = ["DEFAULT_LOADS", "check_loads"]
