"""The engine cycle at the overspeed.

Every inertia force of the mechanism grows with omega^2: the reciprocating mass's
m_j r omega^2 (cos phi + lambda cos 2 phi + ...), the rod's, and the crank's own body
force (the FE centrifugal unit case, applied at omega_os^2 by the superposition).  The
gas force does not.  So the overspeed check recomputes the whole cycle with the
dynamics stage at omega_os (``fe_crank.dynamics.analyse``, exact slider-crank), with the
gas load the load case states for the overspeed condition:

* ``[operating] overspeed_gas = "motored"`` (default): no combustion.  The engine's gas
  model is a p(phi) table without a motored compression curve, so the gas pressure is
  taken as zero gauge (p = crankcase pressure).  At TDC the compression pressure would
  push the piston towards the crank against the inertia pull, so leaving it out keeps
  the largest tensile rod force;
* ``"as_operating"``: the operating gas pressure table at the higher speed (a governor
  failure at full load).

The check then takes the worst angle of that cycle (``assess_group``).
"""

from __future__ import annotations

from dataclasses import replace

from fe_crank import model

GAS_MODES = ("motored", "as_operating")


def overspeed_dynamics(loadcase, dynamics):
    """``DynamicsResult`` of the cycle at ``loadcase.operating.overspeed`` on the same
    angle grid as ``dynamics``, or None without an overspeed."""
    op = loadcase.operating
    if op.overspeed is None:
        return None
    mode = getattr(op, "overspeed_gas", "motored")
    if mode not in GAS_MODES:
        raise ValueError(f"overspeed_gas must be one of {GAS_MODES}, not {mode!r}")
    from fe_crank.dynamics import analyse

    engine = loadcase.engine if mode == "as_operating" else replace(loadcase.engine, gas=None)
    step = dynamics.cycle / dynamics.theta.size
    out = analyse(engine, model.OperatingPoint(op.overspeed), step=step)
    if out.theta.size != dynamics.theta.size:
        raise ValueError("overspeed cycle grid differs from the operating one")
    return out


def describe(loadcase) -> str:
    """One line for the assessment notes."""
    op = loadcase.operating
    mode = getattr(op, "overspeed_gas", "motored")
    gas = ("no combustion, zero gauge gas pressure (motored)" if mode == "motored"
           else "the operating gas pressure table")
    return (f"overspeed: whole cycle recomputed at {op.overspeed * 30 / 3.141592653589793:.0f} rpm "
            f"(rod and piston inertia and crank body force at omega_os^2; gas: {gas}); worst angle")
