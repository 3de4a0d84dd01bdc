"""The loads the assessment superposes, per speed of the full-load curve and per load
state: what the torque flow hands over (``fe_crank.torsion.loads.assessed_loads``).

At every speed of the sweep the engine runs with all cylinders firing and, when the
load case names misfire cases, with each named cylinder misfiring (motored): each is a
``LoadState``, a steady cycle of its own (its stresses and its fatigue amplitude are
those of that cycle; the worst state at a speed is the speed's value: each cylinder
motored in turn, judged against the continuous-operation limits, the tool's reading of
the misfire, ``fe_crank.mechanism.misfire.READING``).  Each throw of a state carries
(``ThrowCycle``) the pin force the FE pin cases carry, the torque entering at the FE
model's torque face and the one leaving at its reaction face (the torque flow through
the throw for the load case's power take-off end), and with torsional vibration the
throw's angular acceleration (FE unit case ``angular_acceleration``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from fe_crank.mechanism.dynamics import RodLoad
from fe_crank.rules.m53.calculation import RodLoads

#: the load state with every cylinder firing (misfire states: "cylinder <name> misfiring")
FIRING = "all cylinders firing"


def misfire_label(cylinder: str) -> str:
    return f"cylinder {cylinder} misfiring"


@dataclass(frozen=True)
class ThrowCycle:
    """The loads of one throw over one cycle: ``pin_force`` (n, 2) the rods' force on the
    crankpin in the throw frame, N (the dynamics stage's; UR M53's bending takes it);
    ``torque_in`` (n,) entering at the FE torque face and ``torque_out`` (n,) leaving at
    the reaction face, N m in the sense of rotation; with torsional vibration
    ``angular_acceleration`` (n,) rad/s^2 in the sense of rotation and ``fe_pin_force``
    (n, 2), the pin force with the inertia and damping torque of the throw's cylinders
    and of the CAD-vs-mesh inertia difference added as a tangential force
    (``torsion.flow.fe_loads``), which the FE pin cases carry (None: the rods' force,
    no vibration); ``rods``: each rod's own force, at its place on the pin for UR M53's
    moments (``fe.throw.pin_patches.rod_loads``); ``fe_rods``: with vibration, each rod's force
    with its share of the vibratory tangential force (``fe_pin_force - pin_force``), which
    the FE model's patch cases carry where rods bear at more than one place (the shares sum
    to one, so the rods' FE forces sum to ``fe_pin_force``); () without vibration."""

    pin_force: np.ndarray
    torque_in: np.ndarray
    torque_out: np.ndarray
    angular_acceleration: np.ndarray | None = None
    fe_pin_force: np.ndarray | None = None
    rods: tuple[RodLoad, ...] = ()  # each rod's own force (the dynamics' ``ThrowLoads.rods``)
    fe_rods: tuple[RodLoad, ...] = ()  # with vibration: each rod's force with its vibratory share

    @property
    def fe_pin(self) -> np.ndarray:
        """The pin force the FE superposition takes."""
        return self.pin_force if self.fe_pin_force is None else self.fe_pin_force

    def fe_rod_loads(self, places: dict[str, float]) -> RodLoads | None:
        """(force (n, 2), place m) of each rod as the FE patch cases take it (``fe_rods``
        with vibration, else ``rods``) at ``places`` (``fe.throw.pin_patches.rod_positions``);
        None without places (the summed force at mid-pin)."""
        if not places:
            return None
        return tuple((r.pin_force, places[r.cylinder]) for r in (self.fe_rods or self.rods))


@dataclass(frozen=True)
class LoadState:
    """One steady cycle of the engine at ``speed`` (rad/s): ``case`` FIRING or a misfire
    (``misfire_label``), or an overspeed cycle's gas in words; ``throws``: throw name ->
    its loads, all on the cycle grid ``theta``."""

    speed: float
    case: str
    theta: np.ndarray
    throws: dict[str, ThrowCycle]


@dataclass(frozen=True)
class AssessedLoads:
    """Everything the assessment superposes: ``speeds[i]`` the states at the i-th speed of
    the sweep (firing first, then each misfire case), ``operating`` the index of the
    operating speed, ``overspeed`` the overspeed cycles (rigid shaft); ``m53_torques``:
    throw name -> the torsional stage's journal torque histories of its journals (one
    synthesis at the speed of the largest half range over the torsional speed range,
    ``torsion.handover``), which UR M53 2.2.2's nominal torsional stress takes at every
    speed ("the highest value over the speed range"); empty without a torsional stage."""

    speeds: tuple[tuple[LoadState, ...], ...]
    operating: int
    overspeed: tuple[LoadState, ...] = ()
    m53_torques: dict[str, tuple[np.ndarray, ...]] = field(default_factory=dict)
    torsion: bool = False  # the journal torques carry the torsional vibration

    @property
    def speed_values(self) -> tuple[float, ...]:
        return tuple(states[0].speed for states in self.speeds)

    @property
    def operating_state(self) -> LoadState:
        """The operating speed with every cylinder firing."""
        return self.speeds[self.operating][0]


__all__ = ["FIRING", "misfire_label", "ThrowCycle", "LoadState", "AssessedLoads"]
