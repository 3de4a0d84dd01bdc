"""The engine over its full-load curve: one dynamics result per speed of the sweep.

The load case's ``[operating]`` gives the speeds and the gas pressure at each
(``fe_crank.model.FullLoadCurve``; one diagram for all speeds when the case gives one,
the conservative reading of a source that gives one).  Each speed's cycle is the exact
slider-crank dynamics at that constant speed with that speed's diagram
(``fe_crank.mechanism.dynamics.analyse``), on one cycle grid for all speeds, so that the unit
stresses of one FE solve serve every speed (docs/mechanism.md).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from fe_crank import model
from fe_crank.mechanism import dynamics


def sweep_speeds(operating: model.OperatingPoint) -> tuple[float, ...]:
    """The speeds (rad/s, increasing) of the sweep: the full-load curve's, else the
    operating speed alone."""
    return operating.full_load.speeds if operating.full_load is not None else (operating.speed,)


def gas_at(engine: model.Engine, operating: model.OperatingPoint, speed: float) -> model.GasPressure | None:
    """The full-load diagram at ``speed``: interpolated between the case's per-speed
    diagrams, or the engine's one diagram."""
    curve = operating.full_load
    if curve is None or not curve.gas_speeds:
        return engine.gas
    return curve.gas_at(speed)


def dynamics_at(
    engine: model.Engine,
    operating: model.OperatingPoint,
    speed: float,
    *,
    step: float = np.radians(1.0),
    cylinder_gas: dict | None = None,
) -> dynamics.DynamicsResult:
    """The engine's cycle at ``speed`` with that speed's full-load diagram
    (``cylinder_gas``: cylinders with a gas of their own, e.g. a misfire)."""
    return dynamics.analyse(
        replace(engine, gas=gas_at(engine, operating, speed)),
        model.OperatingPoint(speed),
        step=step,
        cylinder_gas=cylinder_gas,
    )


def dynamics_sweep(
    engine: model.Engine, operating: model.OperatingPoint, *, step: float = np.radians(1.0)
) -> tuple[dynamics.DynamicsResult, ...]:
    """One ``DynamicsResult`` per speed of the sweep, in speed order, on one cycle grid."""
    return tuple(dynamics_at(engine, operating, w, step=step) for w in sweep_speeds(operating))


__all__ = ["sweep_speeds", "gas_at", "dynamics_at", "dynamics_sweep"]
