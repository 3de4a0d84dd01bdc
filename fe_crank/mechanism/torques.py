"""Each cylinder's torque over the cycle at any speed: what the torsional stage excites
the crank train with, for every cylinder firing and for each misfire case.

At constant crank speed the inertia forces of the exact slider crank scale exactly with
``omega^2`` (the piston's acceleration, the rod's angular acceleration and its centre's
acceleration are ``omega^2`` times functions of the crank angle), and the gas force is
linear in the cylinder pressure, which the full-load curve interpolates linearly in
speed between its diagrams (``fe_crank.model.FullLoadCurve``).  So one cycle without gas
at a reference speed ``omega_0`` and one cycle with each diagram at ``omega_0`` give a
cylinder's torque at every speed ``omega`` of the range exactly::

    T(theta; omega) = sum_k w_k(omega) (T_k(theta; omega_0) - T_0(theta; omega_0))
                      + (omega / omega_0)^2 T_0(theta; omega_0)

``T_0`` the cycle without gas, ``T_k`` the cycle with diagram ``k`` (the engine's one
diagram, or each per-speed diagram of the full-load curve), ``w_k`` the linear
interpolation weights of the diagrams at ``omega`` (one diagram: weight 1, the same
diagram at every speed).  A misfire case has the misfiring cylinder motored in every
diagram (``fe_crank.mechanism.misfire.motored_gas``), the other cylinders as firing.

The dynamics stage computes these cycles once (``EngineCycles.torques``); the torsional
stage reads them (``fe_crank.torsion.excitation.cylinder_harmonics``).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from fe_crank import model
from fe_crank.mechanism.dynamics import analyse
from fe_crank.mechanism.misfire import motored_gas


def gas_weights(gas_speeds: tuple[float, ...], speed: float) -> np.ndarray:
    """The linear interpolation weights of the diagrams at ``gas_speeds`` (rad/s) at
    ``speed`` (``[1.0]`` for the one diagram, ``gas_speeds == ()``); a speed outside the
    diagrams is a ValueError (they are never extrapolated)."""
    if not gas_speeds:
        return np.ones(1)
    w = np.asarray(gas_speeds)
    if not w[0] * (1 - 1e-9) <= speed <= w[-1] * (1 + 1e-9):
        raise ValueError(f"no gas pressure at {speed * 30 / np.pi:.6g} rpm (the diagrams are never extrapolated)")
    return np.array([np.interp(speed, w, e) for e in np.eye(w.size)]) if w.size > 1 else np.ones(1)


@dataclass(frozen=True)
class CylinderTorques:
    """Every cylinder's torque (N m, positive driving) over the cycle grid ``theta`` at
    ``reference_speed`` (rad/s): ``inertia[c]`` without gas, ``loaded[k][c]`` with the
    diagram of ``gas_speeds[k]`` (the engine's one diagram when ``gas_speeds == ()``);
    ``misfire``: the motored cylinder ("" with every cylinder firing) and ``gas`` its
    pressure in words; ``throw_of``: cylinder -> throw.  ``at(speed)`` gives the torques
    at any speed (module docstring)."""

    theta: np.ndarray
    cycle: float
    reference_speed: float
    inertia: dict[str, np.ndarray]
    loaded: tuple[dict[str, np.ndarray], ...]
    throw_of: dict[str, str]
    gas_speeds: tuple[float, ...] = ()
    misfire: str = ""
    gas: str = ""

    def weights(self, speed: float) -> np.ndarray:
        """The weights of ``loaded`` at ``speed`` (``gas_weights``)."""
        return gas_weights(self.gas_speeds, speed)

    def at(self, speed: float) -> dict[str, np.ndarray]:
        """Cylinder -> its torque over ``theta`` at ``speed`` (module docstring)."""
        w = self.weights(speed)
        ratio = (speed / self.reference_speed) ** 2
        return {
            c: sum(wk * (part[c] - t0) for wk, part in zip(w, self.loaded, strict=True)) + ratio * t0
            for c, t0 in self.inertia.items()
        }


def cylinder_torques(
    engine: model.Engine,
    operating: model.OperatingPoint,
    *,
    misfire: str = "",
    step: float = np.radians(1.0),
) -> CylinderTorques:
    """The cycles of ``CylinderTorques`` at the operating speed: without gas, and with the
    engine's diagram or each diagram of the full-load curve; ``misfire``: the cylinder
    motored in each diagram ("" for every cylinder firing)."""
    op = model.OperatingPoint(operating.speed)
    no_gas = analyse(replace(engine, gas=None), op, step=step)
    inertia = {n: cf.torque for n, cf in no_gas.cylinders.items()}
    curve = operating.full_load
    per_speed = curve is not None and bool(curve.gas_speeds)
    diagrams = curve.diagrams if per_speed and curve is not None else (engine.gas,)

    def loaded(diagram: model.GasPressure | None) -> dict[str, np.ndarray]:
        own = {misfire: motored_gas(diagram)[0]} if misfire else {}
        run = analyse(replace(engine, gas=diagram), op, step=step, cylinder_gas=own)
        return {n: cf.torque for n, cf in run.cylinders.items()}

    return CylinderTorques(
        no_gas.theta,
        no_gas.cycle,
        operating.speed,
        inertia,
        tuple(loaded(d) for d in diagrams),
        {c.name: c.throw for c in engine.cylinders},
        curve.gas_speeds if per_speed and curve is not None else (),
        misfire,
        motored_gas(engine.gas)[1] if misfire else "",
    )


def engine_torques(engine: model.Engine, operating: model.OperatingPoint) -> tuple[CylinderTorques, ...]:
    """Every cylinder firing, then each misfire case of ``operating.misfire`` in its order."""
    return tuple(cylinder_torques(engine, operating, misfire=c) for c in ("", *operating.misfire))


__all__ = ["CylinderTorques", "cylinder_torques", "engine_torques", "gas_weights"]
