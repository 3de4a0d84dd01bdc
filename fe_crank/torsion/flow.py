"""Torque flow through the throws of the determinate per-throw model: the torque entering
and leaving every throw, for either power take-off end, with the torsional vibration.

Quasi-static (rigid shaft, statically determinate as IACS UR M53 2.1): the torque
through a journal is the sum of the cylinder torques between it and the free end.  With
the power taken off at the rear (``torque_reaction = "end_2"``) the free end is the
front: throw ``i`` receives ``sum_{j<i} T_j`` at its front journal and passes
``sum_{j<=i} T_j`` on at its rear one; with a front power take-off (``"end_1"``) the
free end is the rear, the torque ``sum_{j>i} T_j`` enters at the rear journal and
``sum_{j>=i} T_j`` leaves at the front one.  The difference is the throw's own torque
``T_i = R F_t`` (gas and inertia of its cylinders, the pin's tangential force).

With torsional vibration (the torsional stage's chain, power taken off behind the last
throw) at crank speed ``omega``: the throw's mass obeys
``J theta'' = T_i + T_front - T_rear - c theta'`` (``c`` its damping to ground), so
``T_rear - T_front = T_i - J alpha - c theta'`` with ``alpha`` and ``theta'`` the
vibratory angular acceleration and velocity of the throw.  The FE model of the throw
carries it as (``fe_loads``): the entering torque ``T_front`` on the torque face, the
pin force with an added tangential force ``-((J - J_FE) alpha + c theta') / R`` (the
cylinders' inertia ``J_cyl`` and the CAD-vs-mesh difference act through the pin, as the
rod does), and the body force of ``alpha`` on the meshed throw (unit case
``angular_acceleration``, moment ``-J_FE alpha``).  The torque reacted at the rear face
is then the torsional stage's rear journal torque: the FE model stays in equilibrium and
each journal carries its own torque.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.errors import InputError

REACTION_ENDS = ("end_2", "end_1")


@dataclass(frozen=True)
class ThrowTorqueFlow:
    """Torques of one throw over the cycle at one speed, positive in the sense of
    rotation (driving), N m; ``torque_in`` enters at the FE torque face (``end_1`` when
    the power is taken off at ``end_2``, else ``end_2``), ``torque_out`` leaves at the
    reaction face; ``own`` the throw's cylinder torque (quasi-static, exact);
    ``angular_acceleration`` (rad/s^2) and ``inertia`` (kg m^2, its mass in the chain)
    and ``damping_torque`` (``c theta'``, N m) of the torsional vibration, zero without."""

    throw: str
    speed: float
    reaction: str
    torque_in: np.ndarray
    torque_out: np.ndarray
    own: np.ndarray
    angular_acceleration: np.ndarray
    inertia: float
    damping_torque: np.ndarray


@dataclass(frozen=True)
class FeThrowLoads:
    """What the FE superposition takes for one throw (``assess.superpose.load_coefficients``):
    the pin force (n, 2) in the throw frame, the torque entering at the torque face (n,)
    and the angular acceleration (n,), rad/s^2, in the sense of rotation."""

    pin_force: np.ndarray
    torque: np.ndarray
    angular_acceleration: np.ndarray


def _shaft_throws(dynamics, engine):
    by_shaft: dict[str, list] = {}
    for t in sorted(engine.throws, key=lambda t: t.axial_position):
        by_shaft.setdefault(t.shaft, []).append(t.name)
    return by_shaft


def torque_flow(dynamics, engine, *, reaction: str = "end_2", torsion=None) -> dict[str, ThrowTorqueFlow]:
    """Throw name -> its torque flow (module docstring) at the speed of ``dynamics``.

    ``torsion`` (a ``TorsionResult`` whose speed grid contains ``dynamics.speed``, on the
    same cycle grid) adds the vibration; it needs the power taken off behind the last
    throw (``reaction = "end_2"``), as its chain has it."""
    if reaction not in REACTION_ENDS:
        raise InputError(f"torque_reaction must be one of {REACTION_ENDS}", key="fe.torque_reaction")
    zero = np.zeros_like(dynamics.theta)
    out = {}
    for names in _shaft_throws(dynamics, engine).values():
        own = [dynamics.throws[n].torque for n in names]
        before = np.cumsum([zero] + own, axis=0)  # before[i] = sum_{j<i}
        total = before[-1]
        for i, n in enumerate(names):
            if reaction == "end_2":
                t_in, t_out = before[i], before[i + 1]
            else:
                t_in, t_out = total - before[i + 1], total - before[i]
            out[n] = ThrowTorqueFlow(n, dynamics.speed, reaction, t_in, t_out, own[i], zero, 0.0, zero)
    if torsion is None:
        return out
    if reaction != "end_2":
        raise InputError(
            "the torsional chain takes the power off behind the last throw (flywheel, driven machines); "
            "a front power take-off (torque_reaction = 'end_1') contradicts it",
            key="fe.torque_reaction",
        )
    return {n: _with_vibration(f, torsion, dynamics) for n, f in out.items()}


def _with_vibration(flow: ThrowTorqueFlow, torsion, dynamics) -> ThrowTorqueFlow:
    s = torsion.index(dynamics.speed)
    w = float(torsion.response.speeds[s])
    if not np.isclose(w, dynamics.speed, rtol=1e-9) or not np.allclose(torsion.theta, dynamics.theta):
        raise ValueError("the torsional response has no result at the dynamics stage's speed and cycle grid")
    vib = torsion.vibratory(s)
    front, rear = torsion.journal_segments(flow.throw)
    m = torsion.model.throw_mass[flow.throw]
    n_seg = vib.shape[0]
    vf = vib[front] if front >= 0 else 0.0
    vr = vib[rear] if rear < n_seg else 0.0
    r = torsion.response
    phase = np.exp(1j * np.outer(r.orders, torsion.theta))
    iw = 1j * r.orders[:, None] * w
    velocity = np.real(np.sum(iw * r.angle[s][:, m : m + 1] * phase, axis=0))
    accel = np.real(np.sum(iw**2 * r.angle[s][:, m : m + 1] * phase, axis=0))
    c = float(torsion.model.absolute_damping[m])
    return ThrowTorqueFlow(
        flow.throw,
        w,
        flow.reaction,
        flow.torque_in + vf,
        flow.torque_out + vr,
        flow.own,
        accel,
        float(torsion.model.inertia[m]),
        c * velocity,
    )


def fe_loads(flow: ThrowTorqueFlow, pin_force: np.ndarray, *, fe_inertia: float, crank_radius: float, sense: int):
    """``FeThrowLoads`` of one throw (module docstring).  ``fe_inertia`` J_FE: the moment
    about the axis of the FE ``angular_acceleration`` unit case (its applied M_z, kg m^2);
    ``pin_force`` the dynamics stage's (throw frame, x = sense x tangential)."""
    extra = -((flow.inertia - fe_inertia) * flow.angular_acceleration + flow.damping_torque) / crank_radius
    pin = np.array(pin_force, float, copy=True)
    pin[:, 0] += sense * extra
    return FeThrowLoads(pin, np.asarray(flow.torque_in, float), np.asarray(flow.angular_acceleration, float))


__all__ = ["ThrowTorqueFlow", "FeThrowLoads", "torque_flow", "fe_loads", "REACTION_ENDS"]
