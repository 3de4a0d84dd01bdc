"""Counterweight checks: stress (from the group results), built m r against the
balance requirement, and the bolt load of a bolted counterweight.

Bolt load: the counterweight's centrifugal force F = m r_c omega^2 (m its mass, r_c
the radius of its centre of mass), carried by the bolts; utilisation F / capacity.
Unbalance error: |m r_built - m r_required| / m r_required.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

from fe_crank.balance.counterweights import Counterweight
from fe_crank.geometry.spec import BoltedJoint


@dataclass(frozen=True)
class JointGeometry:
    """Where a bolted counterweight bears on its web, for VDI 2230's eccentric model
    (``assess.cw_joint``; throw frame, SI)."""

    seat_radius: float  # r_J: the web's end radius opposite the pin (joint plane of radial bolts)
    web_thickness: float  # t
    thickness: float  # b, the counterweight's axial thickness (flush with the web's outer face)
    inner_radius: float  # r_2
    outer_radius: float  # r_1
    angle: float  # rad, the counterweight's included angle
    bearing_lever: float  # L_j + t/2: main-bearing centre to the web's mid-plane
    bearing_span: float  # between the throw's two main-bearing centres
    web: int  # 1 front, 2 rear
    offset: float = 0.0  # rad, the counterweight turned from -y towards +x (its frame turns with it)


@dataclass(frozen=True)
class BoltedCounterweight:
    """One bolted counterweight for the VDI 2230 check (``assess.cw_joint``): its joint
    (``geometry.spec.BoltedJoint``), its own mass and centre-of-mass radius (SI) and where it
    bears on the web (None: checked as a centric joint without moment)."""

    name: str
    joint: BoltedJoint
    mass: float
    radius: float
    geometry: JointGeometry | None = None


@dataclass(frozen=True)
class CounterweightData:
    """What the geometry and balance stages say about one counterweight (SI)."""

    name: str
    mass: float  # kg
    centroid_radius: float  # m
    required_unbalance: float | None = None  # kg m, from the balance stage
    bolted: bool = False
    bolt_capacity: float | None = None  # N, total over the counterweight's bolts
    joints: tuple[BoltedCounterweight, ...] = ()  # the bolted ones, for VDI 2230
    #: rad, 0..pi: the angle between the built m r vector and the required one
    #: (``direction_error``); None: the magnitudes alone are compared
    direction_error: float | None = None

    @property
    def built_unbalance(self) -> float:
        return self.mass * self.centroid_radius


def direction_error(
    unbalance_xy: tuple[float, float], required: Counterweight, throw_angle: float, sense: int
) -> float:
    """The angle (rad, 0..pi) between a throw's built m r vector ``unbalance_xy`` (throw
    frame: x, y) and its balance plane's requirement ``required``.  The throw frame is the
    engine frame turned so that its +y is the crankpin (docs/contracts.md), so a direction
    ``a`` of the throw frame (from +y towards +x) lies on the shaft at
    ``throw_angle + sense a``, measured from the shaft's reference throw in its sense as
    ``Counterweight.angle_on_shaft`` is (``throw_angle``: the engine throw's angle)."""
    a = math.atan2(unbalance_xy[0], unbalance_xy[1])
    return abs(math.remainder(throw_angle + sense * a - required.angle_on_shaft, 2.0 * math.pi))


@dataclass(frozen=True)
class CounterweightCheck:
    name: str
    built_unbalance: float  # kg m
    required_unbalance: float | None
    unbalance_error: float | None  # relative
    bolt_load: float | None  # N at overspeed (or speed when none is given)
    bolt_utilisation: float | None


def balance_rate(checks: Iterable[CounterweightCheck]) -> float | None:
    """The balance rate of ``checks`` (counterweight checks of one throw, or of every throw
    for the shaft): the built m r over the required m r, each summed over the checks that
    have a requirement (1.0: as required; None when none has one)."""
    own = [c for c in checks if c.required_unbalance is not None and c.required_unbalance > 0]
    if not own:
        return None
    rate: float = sum(c.built_unbalance for c in own) / sum(c.required_unbalance or 0.0 for c in own)
    return rate


def centrifugal_force(mass: float, radius: float, omega: float) -> float:
    """F = m r omega^2."""
    return mass * radius * omega**2


def check_counterweight(cw: CounterweightData, omega: float, overspeed: float | None) -> CounterweightCheck:
    err = None
    if cw.required_unbalance is not None and cw.required_unbalance > 0:
        built, required = cw.built_unbalance, cw.required_unbalance
        if cw.direction_error is None:
            err = abs(built - required) / required
        else:  # |U_built - U_required| of the two vectors, by the law of cosines
            gap = (built - required) ** 2 + 2.0 * built * required * (1.0 - math.cos(cw.direction_error))
            err = math.sqrt(gap) / required
    load = util = None
    if cw.bolted:
        load = centrifugal_force(cw.mass, cw.centroid_radius, overspeed if overspeed is not None else omega)
        if cw.bolt_capacity:
            util = load / cw.bolt_capacity
    return CounterweightCheck(cw.name, cw.built_unbalance, cw.required_unbalance, err, load, util)
