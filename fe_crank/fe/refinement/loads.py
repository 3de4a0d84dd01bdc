"""The load sets of the hot-spot convergence study (``fe_crank.fe.refinement.convergence``): unit-case
weights {load set: {unit case: weight}} applied on every level."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar

import numpy as np

K = TypeVar("K")

#: default loads: the radial crankpin force (firing direction, towards the axis) and the torque, 1 N / 1 N m
DEFAULT_LOADS = {"pin_-y": {"pin_-y": 1.0}, "torque": {"torque": 1.0}}


def peak_states(throw_loads: Mapping[K, Any]) -> tuple[tuple[K, int] | None, tuple[K, int] | None]:
    """The study's two states of the cycle: (throw, angle index) of the largest crankpin
    force over the throws and the cycle, and of the largest journal torque through any of
    them (None when no torque passes; the first of equal ones).  ``throw_loads``: {throw:
    an object with ``pin_force`` (n, 2), N, and ``torque_front``/``torque_rear`` (n,), N m},
    e.g. ``DynamicsResult.throws``."""
    best_f: tuple[float, K, int] | None = None
    best_t: tuple[float, K, int] | None = None
    for name, tl in throw_loads.items():
        F = np.asarray(tl.pin_force, float)
        f = np.hypot(F[:, 0], F[:, 1])
        i = int(np.argmax(f))
        if best_f is None or f[i] > best_f[0]:
            best_f = (float(f[i]), name, i)
        tq = np.maximum(np.abs(np.asarray(tl.torque_front, float)), np.abs(np.asarray(tl.torque_rear, float)))
        j = int(np.argmax(tq))
        if tq[j] > 0.0 and (best_t is None or tq[j] > best_t[0]):
            best_t = (float(tq[j]), name, j)
    return (
        None if best_f is None else (best_f[1], best_f[2]),
        None if best_t is None else (best_t[1], best_t[2]),
    )


def check_loads(throw_loads, omega: float) -> dict[str, dict[str, float]]:
    """Load sets of the check's study from the dynamics of one or more throws.

    ``throw_loads``: objects with ``pin_force`` (n, 2) in the throw frame (N) and
    ``torque_front``/``torque_rear`` (n,) (N m), e.g. ``DynamicsResult.throws`` values.
    "peak pin force": the largest crankpin force of the cycle (pin unit cases by the two
    bracketing directions, ``peak_states``) with the centrifugal load at ``omega`` (rad/s);
    "peak torque": the largest journal torque through the throw (skipped when zero).
    """
    from fe_crank.fe.throw.pin_directions import pin_case_weights, pin_cases

    tls = list(throw_loads)
    force, torque = peak_states(dict(enumerate(tls)))
    assert force is not None, "no throw loads"
    k, i = force
    best = np.asarray(tls[k].pin_force, float)[i]
    names = pin_cases()
    w = pin_case_weights(best[None, :], names)[0]
    pin = {n: float(x) for n, x in zip(names, w) if x != 0.0}
    loads = {"peak pin force": {**pin, "centrifugal": float(omega) ** 2}}
    if torque is not None:
        k, j = torque
        tl = tls[k]
        loads["peak torque"] = {"torque": max(abs(float(tl.torque_front[j])), abs(float(tl.torque_rear[j])))}
    return loads


__all__ = ["DEFAULT_LOADS", "check_loads", "peak_states"]
