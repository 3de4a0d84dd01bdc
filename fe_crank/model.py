"""Frozen data the numerical core works on: SI floats only, no units, no files.

Conventions (docs/architecture.md, "Conventions"):

* Global frame: ``z`` along the crank axis (positive from the front/free end to the
  flywheel end), ``y`` up, ``x`` completing a right-handed frame.  Looking along
  ``-z`` (from the front), positive angles turn from ``+y`` towards ``+x``, i.e.
  clockwise seen from the front: the usual engine-builder's view.  A shaft with
  ``sense = +1`` rotates in this positive direction.
* A cylinder's axis points from the crank axis to its cylinder head; its direction
  is given by ``bank_angle`` measured like the crank angles above, from ``+y``.
* A throw's ``angle`` is the angular position of its crankpin relative to the
  shaft's reference throw, measured in the shaft's sense of rotation.
* The crank angle of a cylinder, ``phi``, is measured from that cylinder's TDC in
  the direction of rotation; piston displacement ``s`` from TDC towards the axis.
* The engine cycle angle ``theta`` is the angle of the reference shaft: at
  ``theta = 0`` the shaft's reference throw (angle 0) points along ``+y``.
* ``firing_offset`` is the cycle angle at which the cylinder is at TDC firing.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np


@dataclass(frozen=True)
class Shaft:
    """One crankshaft.  Several shafts (opposed-piston, Deltic) may be geared together."""

    name: str
    sense: int = 1  # +1 or -1: direction of rotation in the global frame
    phase: float = 0.0  # rad: angle of the reference throw at theta = 0, from +y
    centre: tuple[float, float] = (0.0, 0.0)  # m: (x, y) of the shaft axis
    speed_ratio: float = 1.0  # shaft speed / reference speed


@dataclass(frozen=True)
class Throw:
    """A crankpin: its shaft, angular position, axial position and rotating mass."""

    name: str
    shaft: str
    angle: float  # rad, in the shaft's sense of rotation from its reference throw
    crank_radius: float  # m
    axial_position: float = 0.0  # m, along z
    rotating_mass: float = 0.0  # kg: unbalanced crank mass (pin + webs) reduced to crank_radius


@dataclass(frozen=True)
class Rod:
    """Connecting rod: mass, centre of mass measured from the big-end centre, inertia."""

    length: float  # m, big-end to small-end centres
    mass: float  # kg
    cg_from_big_end: float  # m
    inertia_cg: float | None = None  # kg m^2 about the centre of mass; None -> two-mass model

    @property
    def reciprocating_fraction(self) -> float:
        """Share of the rod mass put at the small end by the static two-mass split."""
        return self.cg_from_big_end / self.length


@dataclass(frozen=True)
class Articulation:
    """An articulated (link) rod pinned to a master rod (radial engines)."""

    master: str  # name of the master cylinder
    link_radius: float  # m: distance of the link pin from the master big-end centre
    link_angle: float  # rad: angle of the link pin on the master rod from its axis


@dataclass(frozen=True)
class GasPressure:
    """Cylinder pressure over the cycle as a table (absolute pressure, SI).

    ``angle`` is the cylinder's own crank angle from TDC firing, over one cycle
    (0 .. 4 pi for a four-stroke, 0 .. 2 pi for a two-stroke), increasing.
    The pressure acting on the piston's underside is ``crankcase_pressure``.
    ``motored``: the same cylinder without combustion (``fe_crank.mechanism.gas.motored_cycle``),
    when the gas data give a compression ratio and the intake pressure; else None.
    """

    angle: np.ndarray
    pressure: np.ndarray
    crankcase_pressure: float = 101325.0
    source: str = ""
    motored: GasPressure | None = None


@dataclass(frozen=True)
class Cylinder:
    name: str
    throw: str
    bore: float  # m
    rod: Rod
    piston_mass: float  # kg: piston group (piston, rings, pin, clips)
    bank_angle: float = 0.0  # rad from +y, see module docstring
    pin_offset: float = 0.0  # m, desaxe: positive towards the side the crankpin moves to on the power stroke
    firing_offset: float = 0.0  # rad of cycle angle
    articulation: Articulation | None = None
    #: m, axial position of the rod's big end on the crankpin from the pin's middle (+z to
    #: the rear); None: the default layout (``fe_crank.fe.throw.pin_patches.rod_positions``)
    pin_position: float | None = None

    @property
    def piston_area(self) -> float:
        return float(np.pi * self.bore**2 / 4.0)


@dataclass(frozen=True)
class Yoke:
    """Synchronising yoke of a Nordberg radial engine (seed 000, sec. 21, eqs. 162-166).

    Its centre of mass circles at ``orbit_radius`` with the crank and oscillates along its
    axis (direction ``axis_angle``) with half-stroke ``arm * sin(beta_max)``.
    """

    mass: float  # kg
    orbit_radius: float  # m: mean radius R_cp of the circular motion
    arm: float  # m: rocker arm l_ya
    beta_max: float  # rad: largest rod deflection
    axis_angle: float = 0.0  # rad: direction of the yoke's oscillation (engine convention)
    axial_position: float = 0.0  # m


@dataclass(frozen=True)
class Engine:
    name: str
    strokes: Literal[2, 4]
    shafts: tuple[Shaft, ...]
    throws: tuple[Throw, ...]
    cylinders: tuple[Cylinder, ...]
    gas: GasPressure | None = None  # same pressure curve for every cylinder, shifted by firing offset
    source: str = ""
    yoke: Yoke | None = None  # Nordberg synchronising yoke (balance stage), optional
    #: "trunk_piston" (default) or "crosshead": sets UR M53's additional bending stress (section 4)
    construction: Literal["trunk_piston", "crosshead"] = "trunk_piston"
    #: False for a machine that burns nothing in its cylinders (air motor, compressor): the
    #: UR M53 route, written for I.C. engines, is then an analogy (``rules.m53.basis``)
    internal_combustion: bool = True

    @property
    def cycle_angle(self) -> float:
        return 4.0 * np.pi if self.strokes == 4 else 2.0 * np.pi

    def shaft(self, name: str) -> Shaft:
        return next(s for s in self.shafts if s.name == name)

    def throw(self, name: str) -> Throw:
        return next(t for t in self.throws if t.name == name)

    def cylinder(self, name: str) -> Cylinder:
        return next(c for c in self.cylinders if c.name == name)


def crank_angle_global(engine: Engine, throw_name: str, theta) -> np.ndarray:
    """``psi`` of a throw's crankpin at cycle angle(s) ``theta`` (rad): the crank-angle
    convention of the package, ``psi = phase + sense (speed_ratio theta + throw angle)``."""
    t = engine.throw(throw_name)
    sh = engine.shaft(t.shaft)
    return sh.phase + sh.sense * (sh.speed_ratio * np.asarray(theta, dtype=float) + t.angle)


@dataclass(frozen=True)
class FullLoadCurve:
    """The speeds of the full-load curve and the gas pressure at each.

    ``speeds`` (rad/s, increasing): every speed the check evaluates (the operating speed
    among them).  ``gas_speeds`` and ``diagrams``: the indicator diagrams the load case
    gives per speed (increasing speeds); between two the pressure is interpolated
    linearly in speed at every crank angle, outside them there is none (never
    extrapolated).  Without per-speed diagrams (``gas_speeds == ()``) ``default`` (the
    engine's one diagram, the conservative reading of a source that gives one) serves
    every speed."""

    speeds: tuple[float, ...]
    gas_speeds: tuple[float, ...] = ()
    diagrams: tuple[GasPressure, ...] = ()
    default: GasPressure | None = None
    cycle: float = 4.0 * np.pi  # rad: the engine's cycle (the tables' period)

    def gas_at(self, speed: float) -> GasPressure | None:
        """The full-load diagram at ``speed`` (rad/s); ValueError outside the diagrams."""
        if not self.gas_speeds:
            return self.default
        w = self.gas_speeds
        if not w[0] * (1 - 1e-12) <= speed <= w[-1] * (1 + 1e-12):
            raise ValueError(
                f"no gas pressure at {speed * 30 / np.pi:.6g} rpm: the diagrams cover "
                f"{w[0] * 30 / np.pi:.6g}-{w[-1] * 30 / np.pi:.6g} rpm (never extrapolated)"
            )
        i = int(np.clip(np.searchsorted(w, speed), 1, len(w) - 1))
        t = float(np.clip((speed - w[i - 1]) / (w[i] - w[i - 1]), 0.0, 1.0))
        if t in (0.0, 1.0):
            return self.diagrams[i - 1 if t == 0.0 else i]
        return interpolate_gas(self.diagrams[i - 1], self.diagrams[i], t, self.cycle)


def interpolate_gas(a: GasPressure, b: GasPressure, t: float, cycle: float) -> GasPressure:
    """``(1 - t) a + t b`` at every crank angle of both tables (periodic with ``cycle``,
    as ``fe_crank.mechanism.gas.pressure_at`` reads them); the motored curves likewise when both
    have one, else none."""
    ang = np.unique(np.concatenate([a.angle, b.angle]))
    pa = np.interp(ang, a.angle, a.pressure, period=cycle)
    pb = np.interp(ang, b.angle, b.pressure, period=cycle)
    motored = None
    if a.motored is not None and b.motored is not None:
        motored = interpolate_gas(a.motored, b.motored, t, cycle)
    return GasPressure(
        ang,
        (1 - t) * pa + t * pb,
        (1 - t) * a.crankcase_pressure + t * b.crankcase_pressure,
        f"{1 - t:.4g} x ({a.source}) + {t:.4g} x ({b.source})",
        motored,
    )


@dataclass(frozen=True)
class OperatingPoint:
    """``overspeed_gas``: the gas load of the overspeed condition (the assessment
    recomputes the whole cycle at the overspeed): ``"motored"`` no combustion (the
    motored compression curve ``GasPressure.motored`` where the gas data allow it, and
    zero gauge pressure; ``fe_crank.assess.overspeed``); ``"as_operating"`` the operating
    gas pressure table.  ``full_load``: the full-load curve (speeds and their gas);
    ``misfire``: the cylinders whose cutout (misfire) is checked, each in turn."""

    speed: float  # rad/s, of the reference shaft
    overspeed: float | None = None  # rad/s: the whole cycle (inertia, centrifugal) at this speed
    overspeed_gas: str = "motored"  # "motored" or "as_operating"
    full_load: FullLoadCurve | None = None  # the speeds of the sweep and their gas; None: ``speed`` alone
    misfire: tuple[str, ...] = ()  # cylinders cut out in turn (each alone motored), ``fe_crank.mechanism.misfire``
