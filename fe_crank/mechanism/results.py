"""The dynamics stage's results: the forces of each cylinder, each rod's load on its
crankpin, each throw's loads and the engine totals over one working cycle
(``fe_crank.mechanism.dynamics.analyse`` computes them; its docstring gives the
formulas and their sources)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from fe_crank.mechanism.kinematics import PistonMotion


@dataclass(frozen=True)
class CylinderForces:
    """Forces of one cylinder over the cycle grid (see module docstring)."""

    name: str
    throw: str
    phi: np.ndarray  # rad: crank angle from the cylinder axis, in the shaft's sense
    gas_angle: np.ndarray  # rad: angle from TDC firing, 0 .. cycle
    pressure: np.ndarray  # Pa absolute
    motion: PistonMotion
    gas: np.ndarray
    inertia: np.ndarray
    rod_force: np.ndarray
    side_thrust: np.ndarray
    tangential: np.ndarray
    radial: np.ndarray
    torque: np.ndarray
    volume_swept: np.ndarray  # m^3: A s, the displaced volume from TDC


@dataclass(frozen=True)
class RodLoad:
    """One rod's force on the crankpin (n, 2), throw frame, and its stated place on the pin
    (``Cylinder.pin_position``, m; None: the default layout, ``fe.throw.pin_patches.rod_positions``)."""

    cylinder: str
    pin_force: np.ndarray
    pin_position: float | None = None


@dataclass(frozen=True)
class ThrowLoads:
    name: str
    shaft: str
    angle_global: np.ndarray  # rad: crankpin direction in the engine frame, from +y
    pin_force: np.ndarray  # (n, 2) throw frame: rods on the crankpin
    torque: np.ndarray  # N m: torque of the cylinders on this throw
    torque_front: np.ndarray
    torque_rear: np.ndarray
    bearing_front: np.ndarray  # (n, 2) engine frame (x, y): force of the shaft on the bearing
    bearing_rear: np.ndarray
    rods: tuple[RodLoad, ...] = ()  # each rod's share of ``pin_force``, in the engine's order

    @property
    def pin_force_magnitude(self) -> np.ndarray:
        return np.hypot(self.pin_force[:, 0], self.pin_force[:, 1])


@dataclass(frozen=True)
class DynamicsResult:
    engine: str
    speed: float  # rad/s of the reference shaft
    theta: np.ndarray  # rad: cycle angle grid, uniform, 0 <= theta < cycle
    cycle: float
    cylinders: dict[str, CylinderForces]
    throws: dict[str, ThrowLoads]
    shaft_torque: dict[str, np.ndarray]  # N m: per shaft, in that shaft's sense
    torque: np.ndarray  # N m: reduced to the reference shaft
    mean_torque: float
    power: float  # W
    torque_nonuniformity: float
    indicated_work: float  # J per cycle: sum of the closed integrals p dV
    speed_fluctuation: float
    excess_energy: float  # J: max - min of the cumulative excess work
    flywheel_inertia: float  # kg m^2 for speed_fluctuation
    warnings: tuple[str, ...] = field(default_factory=tuple)
