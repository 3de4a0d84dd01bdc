"""The engine cycle at the overspeed.

Every inertia force of the mechanism grows with omega^2: the reciprocating mass's
m_j r omega^2 (cos phi + lambda cos 2 phi + ...), the rod's, and the crank's own body
force (the FE centrifugal unit case, applied at omega_os^2 by the superposition).  The
gas force does not.  So the overspeed check recomputes the whole cycle with the
dynamics stage at omega_os (``fe_crank.mechanism.dynamics.analyse``, exact slider-crank), with the
gas load the load case states for the overspeed condition:

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

The check then takes the worst angle of those cycles (``assess_group``).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from fe_crank import model

GAS_MODES = ("motored", "as_operating")


@dataclass(frozen=True)
class OverspeedCycle:
    """One overspeed cycle: its gas load in words and the ``DynamicsResult``."""

    gas: str
    dynamics: object


def _mode(loadcase) -> str:
    mode = getattr(loadcase.operating, "overspeed_gas", "motored")
    if mode not in GAS_MODES:
        raise ValueError(f"overspeed_gas must be one of {GAS_MODES}, not {mode!r}")
    return mode


def _gas_states(loadcase) -> list[tuple[str, model.GasPressure | None]]:
    """(description, gas table or None for zero gauge pressure) of each overspeed cycle."""
    gas = loadcase.engine.gas
    if _mode(loadcase) == "as_operating":
        return [("the operating gas pressure table", gas)]
    zero = ("no combustion, zero gauge gas pressure", None)
    motored = getattr(gas, "motored", None) if gas is not None else None
    if motored is None:
        return [zero]
    return [(f"no combustion, {motored.source}", motored), zero]


def overspeed_cycles(loadcase, dynamics) -> tuple[OverspeedCycle, ...]:
    """The cycles at ``loadcase.operating.overspeed`` (module docstring) on the angle grid
    of ``dynamics``; () without an overspeed.  The check takes the worst over all."""
    op = loadcase.operating
    if op.overspeed is None:
        return ()
    from fe_crank.mechanism.dynamics import analyse

    step = dynamics.cycle / dynamics.theta.size
    out = []
    for words, gas in _gas_states(loadcase):
        dyn = analyse(replace(loadcase.engine, gas=gas), model.OperatingPoint(op.overspeed), step=step)
        if dyn.theta.size != dynamics.theta.size:
            raise ValueError("overspeed cycle grid differs from the operating one")
        out.append(OverspeedCycle(words, dyn))
    return tuple(out)


def overspeed_dynamics(loadcase, dynamics):
    """``DynamicsResult`` of the first overspeed cycle (the motored compression curve where
    the data give it, else zero gas; or the operating table), None without an overspeed."""
    cycles = overspeed_cycles(loadcase, dynamics)
    return cycles[0].dynamics if cycles else None


def describe(loadcase) -> str:
    """One line for the assessment notes: which gas the overspeed cycle(s) used."""
    op = loadcase.operating
    states = [w for w, _ in _gas_states(loadcase)]
    gas = states[0] if len(states) == 1 else " and ".join(f"({w})" for w in states) + ", the worse of the two"
    if _mode(loadcase) == "motored" and len(states) == 1:
        gas += " (the gas data give no compression ratio and intake pressure for a motored curve)"
    return (
        f"overspeed: whole cycle recomputed at {op.overspeed * 30 / 3.141592653589793:.0f} rpm "
        f"(rod and piston inertia and crank body force at omega_os^2; gas: {gas}); worst angle"
    )
