"""The engine cycles a load case is checked on: the operating cycle and the cycles at the
overspeed.

Every inertia force of the mechanism grows with omega^2: the reciprocating mass's
m_j r omega^2 (cos phi + lambda cos 2 phi + ...), the rod's, and the crank's own body
force (the FE centrifugal unit case, applied at omega_os^2 by the superposition).  The
gas force does not.  So the overspeed check recomputes the whole cycle with the
dynamics at omega_os (``fe_crank.mechanism.dynamics.analyse``, exact slider-crank), with
the gas load the load case states for the overspeed condition:

* ``[operating] overspeed_gas = "motored"`` (default): no combustion.  A motored
  cylinder still compresses its charge: where the gas data give the compression ratio
  and the intake/boost pressure (``GasPressure.motored``, ``fe_crank.mechanism.gas.motored_cycle``:
  p = p_0 (V_BDC/V)^n, p_TDC = p_0 eps^n, n = 1.35) the cycle is computed with that
  curve **and** with zero gauge gas pressure, and the check takes the worse of the two
  (the largest von Mises over both cycles).  The two bound the gas load from both
  sides: the compression pressure at the firing TDC pushes the piston towards the
  crank, against the inertia pull, so it can raise the compressive rod force there
  (high compression ratio, boost) while it lowers the tensile one; zero gas keeps the
  largest tensile rod force at every TDC (for a two-stroke, whose every TDC compresses,
  that is the conservative bound; for a four-stroke the gas-exchange TDC of the motored
  cycle gives it too).  Where the data do not give the curve: zero gauge gas pressure
  alone, and the notes say so;
* ``"as_operating"``: the operating gas pressure table at the higher speed (a governor
  failure at full load).

The assessment then takes the worst angle of those cycles.

The full-load curve (``[operating] speeds`` or ``speed_range``, ``fe_crank.mechanism.full_load``):
the cycle at every speed of the sweep with that speed's diagram (``SpeedCycles``), and at
each the misfire cases the load case names (``fe_crank.mechanism.misfire``); the operating
speed is one of them.  All on one cycle-angle grid, so that one FE solve serves them all.

The torsional stage's excitation (``fe_crank.mechanism.torques``): every cylinder's torque
at every speed of the torsional speed range, with every cylinder firing and with each
misfire case, from the cycles without gas and with each diagram at the operating speed
(``EngineCycles.torques``).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from fe_crank import model
from fe_crank.errors import FeCrankError
from fe_crank.mechanism.dynamics import DynamicsResult, analyse
from fe_crank.mechanism.full_load import dynamics_at, sweep_speeds
from fe_crank.mechanism.misfire import MisfireCycle, misfire_cycles
from fe_crank.mechanism.torques import CylinderTorques, engine_torques

GAS_MODES = ("motored", "as_operating")


@dataclass(frozen=True)
class OverspeedCycle:
    """One overspeed cycle: its gas load in words and its dynamics."""

    gas: str
    dynamics: DynamicsResult


@dataclass(frozen=True)
class SpeedCycles:
    """The engine's cycles at one speed of the sweep (rad/s): every cylinder firing with
    that speed's full-load diagram, and each misfire case of the load case (() without)."""

    speed: float
    firing: DynamicsResult
    misfire: tuple[MisfireCycle, ...] = ()


@dataclass(frozen=True)
class EngineCycles:
    """The operating cycle and the overspeed cycles (() without an overspeed), all on one
    cycle-angle grid; ``overspeed_note``: which gas the overspeed cycles used, in words
    ("" without an overspeed); ``sweep``: the cycles at every speed of the full-load curve,
    in speed order (the operating speed alone without one; its firing cycle is
    ``operating``); ``torques``: every cylinder's torque at any speed, for every cylinder
    firing and then each misfire case (``fe_crank.mechanism.torques``), the torsional
    stage's excitation."""

    operating: DynamicsResult
    overspeed: tuple[OverspeedCycle, ...] = ()
    overspeed_note: str = ""
    sweep: tuple[SpeedCycles, ...] = ()
    torques: tuple[CylinderTorques, ...] = ()

    @property
    def firing_torques(self) -> CylinderTorques:
        """The cylinders' torques with every cylinder firing."""
        return next(t for t in self.torques if not t.misfire)

    @property
    def misfire_torques(self) -> tuple[CylinderTorques, ...]:
        """The cylinders' torques of each misfire case, in the load case's order."""
        return tuple(t for t in self.torques if t.misfire)

    @property
    def speeds(self) -> tuple[float, ...]:
        """The speeds of the sweep, rad/s, increasing."""
        return tuple(s.speed for s in self.sweep)

    @property
    def operating_index(self) -> int:
        """The index of the operating speed in ``sweep``."""
        return next(i for i, s in enumerate(self.sweep) if s.firing is self.operating)


def _mode(operating: model.OperatingPoint) -> str:
    mode = operating.overspeed_gas
    if mode not in GAS_MODES:
        raise ValueError(f"overspeed_gas must be one of {GAS_MODES}, not {mode!r}")
    return mode


def _gas_states(engine: model.Engine, operating: model.OperatingPoint) -> list[tuple[str, model.GasPressure | None]]:
    """(description, gas table or None for zero gauge pressure) of each overspeed cycle."""
    gas = engine.gas
    if _mode(operating) == "as_operating":
        return [("the operating gas pressure table", gas)]
    zero = ("no combustion, zero gauge gas pressure", None)
    motored = gas.motored if gas is not None else None
    if motored is None:
        return [zero]
    return [(f"no combustion, {motored.source}", motored), zero]


def overspeed_cycles(
    engine: model.Engine, operating: model.OperatingPoint, dynamics: DynamicsResult
) -> tuple[OverspeedCycle, ...]:
    """The cycles at ``operating.overspeed`` (module docstring) on the angle grid of
    ``dynamics``; () without an overspeed.  The check takes the worst over all."""
    if operating.overspeed is None:
        return ()
    step = dynamics.cycle / dynamics.theta.size
    out = []
    for words, gas in _gas_states(engine, operating):
        dyn = analyse(replace(engine, gas=gas), model.OperatingPoint(operating.overspeed), step=step)
        if dyn.theta.size != dynamics.theta.size:
            raise ValueError("overspeed cycle grid differs from the operating one")
        out.append(OverspeedCycle(words, dyn))
    return tuple(out)


def describe(engine: model.Engine, operating: model.OperatingPoint) -> str:
    """One line for the assessment notes: which gas the overspeed cycle(s) used."""
    if operating.overspeed is None:
        return ""
    states = [w for w, _ in _gas_states(engine, operating)]
    gas = states[0] if len(states) == 1 else " and ".join(f"({w})" for w in states) + ", the worse of the two"
    if _mode(operating) == "motored" and len(states) == 1:
        gas += " (the gas data give no compression ratio and intake pressure for a motored curve)"
    return (
        f"overspeed: whole cycle recomputed at {operating.overspeed * 30 / 3.141592653589793:.0f} rpm "
        f"(rod and piston inertia and crank body force at omega_os^2; gas: {gas}); worst angle"
    )


def refuse_non_finite(res: DynamicsResult, file: str) -> None:
    """Forces and torques over the cycle must be finite: a NaN or inf (an input at the
    edge of what the mechanism allows) is an error of the case, never a result."""
    arrays = {"torque": res.torque}
    arrays.update({f"throw {n} pin force": t.pin_force for n, t in res.throws.items()})
    for what, a in arrays.items():
        if not np.all(np.isfinite(a)):
            raise FeCrankError(f"{file}: the dynamics gave a non-finite {what} (NaN or inf); check the engine data")


def speed_cycles(
    engine: model.Engine, operating: model.OperatingPoint, res: DynamicsResult, *, file: str = ""
) -> tuple[SpeedCycles, ...]:
    """The cycles at every speed of the sweep (``full_load.sweep_speeds``): at the
    operating speed its cycle ``res`` (the same diagram), at the others ``dynamics_at``
    with that speed's diagram; each with the load case's misfire cases
    (``misfire.misfire_cycles``).  A non-finite force is an error naming ``file``."""
    step = res.cycle / res.theta.size
    out = []
    for w in sweep_speeds(operating):
        firing = res if np.isclose(w, operating.speed, rtol=1e-12) else dynamics_at(engine, operating, w, step=step)
        misfire = misfire_cycles(engine, operating, w, step=step)
        for d in (firing, *(m.dynamics for m in misfire)):
            refuse_non_finite(d, file)
        out.append(SpeedCycles(w, firing, misfire))
    return tuple(out)


def engine_cycles(engine: model.Engine, operating: model.OperatingPoint, *, file: str = "") -> EngineCycles:
    """The operating cycle (``analyse``), the overspeed cycles, the cycles at every
    speed of the sweep and the cylinders' torques of the torsional stage
    (``torques.engine_torques``) of one operating point; a non-finite force or torque is an error
    of the case naming ``file``."""
    res = analyse(engine, operating)
    refuse_non_finite(res, file)
    return EngineCycles(
        res,
        overspeed_cycles(engine, operating, res),
        describe(engine, operating),
        speed_cycles(engine, operating, res, file=file),
        engine_torques(engine, operating),
    )
