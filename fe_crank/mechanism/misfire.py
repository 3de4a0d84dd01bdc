"""A misfiring cylinder (cylinder cutout): one cylinder without combustion, the others
firing.  What the tool does (``READING``): each named cylinder motored in turn, every
such state judged against the same continuous-operation limits as normal firing.  The
reading is the tool's, the conservative one: UR M53 itself does not name misfire; class
rules on torsional vibration ask that system designs take account of engine misfire
conditions and restrict speed or power where the limits for continuous operation are
exceeded (e.g. Lloyd's Register, Rules for Inland Waterways Ships, Pt 5 Ch 6 1.1.2-1.1.3),
docs/mechanism.md.  The cutout changes the crankpin and journal loads of the stress
history and the torsional excitation.

The misfiring cylinder is motored: it still compresses and re-expands its charge.
Where the gas data give the compression ratio and the intake/boost pressure, its
pressure is the motored curve ``GasPressure.motored`` (``fe_crank.mechanism.gas.motored_cycle``:
``p = p_0 (V_BDC / V)^n``, n = 1.35 unless stated); where they do not, zero gauge
pressure (the cylinder pressure equal to the crankcase pressure), and the result says
which (``MisfireCycle.gas``).  The load case names the cylinders (``[operating]
misfire``, each in turn with ``"each"``); each cutout is its own cycle, and the worst
of them governs (with the cylinder and speed that give it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank import model
from fe_crank.mechanism import dynamics
from fe_crank.mechanism.full_load import dynamics_at, gas_at

#: what the misfire states are, in words (the report and the notes say it so)
READING = "each cylinder motored in turn, judged against the continuous-operation limits"

ZERO_GAUGE = "zero gauge pressure (the gas data give no compression ratio and intake pressure for a motored curve)"


def motored_gas(gas: model.GasPressure | None) -> tuple[model.GasPressure | None, str]:
    """(the misfiring cylinder's gas table or None for zero gauge pressure, in words)."""
    motored = gas.motored if gas is not None else None
    if motored is None:
        return None, ZERO_GAUGE
    return motored, motored.source


@dataclass(frozen=True)
class MisfireCycle:
    """The engine's cycle at ``speed`` (rad/s) with ``cylinder`` misfiring."""

    cylinder: str
    speed: float
    gas: str  # the misfiring cylinder's pressure, in words
    dynamics: dynamics.DynamicsResult


def misfire_cycles(
    engine: model.Engine,
    operating: model.OperatingPoint,
    speed: float | None = None,
    *,
    step: float = np.radians(1.0),
) -> tuple[MisfireCycle, ...]:
    """One cycle per misfiring cylinder of ``operating.misfire`` at ``speed`` (default the
    operating speed) with that speed's full-load diagram for the firing cylinders; ()
    without a misfire case."""
    w = operating.speed if speed is None else speed
    gas, words = motored_gas(gas_at(engine, operating, w))
    return tuple(
        MisfireCycle(c, w, words, dynamics_at(engine, operating, w, step=step, cylinder_gas={c: gas}))
        for c in operating.misfire
    )


__all__ = ["MisfireCycle", "misfire_cycles", "motored_gas", "ZERO_GAUGE", "READING"]
