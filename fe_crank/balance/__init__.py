"""Balance: free forces and moments by order, counterweights, balance shafts.

Public API (see docs/contracts.md and docs/balance.md):

* ``free_forces(engine, speed, *, reference_z=0.0) -> FreeForces``
* ``size_counterweights(engine, strategy, speed, ...) -> CounterweightDesign``
* ``annular_sector(r_outer, r_inner, thickness, angle, density) -> SectorProperties``
  and its inverse ``solve_sector(unbalance, free=..., ...)``
* ``balance_shafts(forces, component, order, ...) -> BalanceShaftDesign``
* ``hodograph(a, b, c, d) -> Hodograph``
* ``analyse_balance(engine, speed, settings) -> BalanceResult`` (all of the above)
"""

from fe_crank.balance.counterweights import (
    BalanceStrategy,
    Counterweight,
    CounterweightDesign,
    counterweight_mass,
    radial_counterweight_mass,
    size_counterweights,
)
from fe_crank.balance.forces import REPORTED_ORDERS, FreeForces, OrderTerm, free_forces
from fe_crank.balance.harmonics import series_coefficients
from fe_crank.balance.hodograph import Hodograph, hodograph
from fe_crank.balance.nordberg import YokeInertia, rocker_counterweight_force, yoke_inertia
from fe_crank.balance.sector import SectorProperties, annular_sector, solve_sector
from fe_crank.balance.shafts import BalanceShaft, BalanceShaftDesign, balance_shafts

__all__ = [
    "BalanceShaft",
    "BalanceShaftDesign",
    "BalanceStrategy",
    "Counterweight",
    "CounterweightDesign",
    "FreeForces",
    "Hodograph",
    "OrderTerm",
    "REPORTED_ORDERS",
    "SectorProperties",
    "YokeInertia",
    "annular_sector",
    "balance_shafts",
    "counterweight_mass",
    "free_forces",
    "hodograph",
    "radial_counterweight_mass",
    "rocker_counterweight_force",
    "series_coefficients",
    "size_counterweights",
    "solve_sector",
    "yoke_inertia",
]
