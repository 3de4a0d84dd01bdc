"""The load case's ``[torsion]`` section -> frozen ``TorsionSettings`` (SI floats).

::

    [torsion]
    speed_range = ["1000 rpm", "6600 rpm"]   # swept for resonances; contains the operating speed
    speed_steps = 561                        # optional (default 561)
    throw_stiffness = "carter"               # or "fe": from the FE throw model (check stage)
    shaft_loss_factor = 0.04                 # relative damping of the crank segments (eta)
    cylinder_damping = "0.3 N*m*s/rad"       # absolute damping of each throw to ground
    assess_speed = "governing"               # or "operating"

    [torsion.pulley]                         # optional front hub
    inertia = "0.008 kg*m^2"
    stiffness = "4e5 N*m/rad"                # hub to the front journal of throw 1

    [torsion.damper]                         # optional damper ring on the hub
    inertia = "0.01 kg*m^2"
    stiffness = "3e4 N*m/rad"                # omitted: an untuned viscous (Houdaille) damper
    damping = "4 N*m*s/rad"                  # viscous, ring to hub
    loss_factor = 0.2                        # optional, rubber hysteresis

    [torsion.flywheel]                       # required
    inertia = "0.12 kg*m^2"
    stiffness = "6e5 N*m/rad"                # last throw to the flywheel

    [[torsion.driven]]                       # optional chain behind the flywheel
    name = "generator"
    inertia = "0.3 kg*m^2"
    stiffness = "2e4 N*m/rad"                # coupling from the previous mass
    damping = "10 N*m*s/rad"                 # optional, viscous across the coupling
    loss_factor = 0.1                        # optional, coupling hysteresis
    absolute_damping = "0 N*m*s/rad"         # optional, to ground

Torsional stiffness must be written per angle (``N*m/rad``, ``kN*m/deg``) and damping
per angular speed (``N*m*s/rad``): a bare ``N*m`` could be a torque, so it is refused.
Damping is never defaulted for the crank: ``shaft_loss_factor`` and ``cylinder_damping``
are required (docs/torsion.md gives typical values and their sources).

``model = "lumped"``: the chain as an engine maker's stations instead
(``fe_crank.io.torsion_lumped``); the keys above other than ``speed_range``,
``speed_steps`` and ``assess_speed`` do not apply to it and are refused.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from pydantic import Field, model_validator

from fe_crank.errors import InputError
from fe_crank.io.base import Strict, validate
from fe_crank.io.torsion_lumped import Station, parse_stations
from fe_crank.io.torsion_units import Damping, Stiffness
from fe_crank.io.units import Inertia, Speed

#: accepted range of a loss factor (dimensionless); above it a linear model is not credible
MAX_SHAFT_LOSS_FACTOR = 0.2
MAX_COUPLING_LOSS_FACTOR = 1.0


def _positive(obj, *keys):
    for k in keys:
        v = getattr(obj, k)
        if v is not None and not v > 0:
            raise ValueError(f"{k} must be positive")


def _non_negative(obj, *keys):
    for k in keys:
        v = getattr(obj, k)
        if v is not None and v < 0:
            raise ValueError(f"{k} must not be negative")


class MassInput(Strict):
    inertia: Inertia
    stiffness: Stiffness

    @model_validator(mode="after")
    def _check(self):
        _positive(self, "inertia", "stiffness")
        return self


class DamperInput(Strict):
    """The damper ring on the hub: a rubber (tuned) damper with its ``stiffness``, or an
    untuned viscous (Houdaille) damper without one (ring coupled by the silicone film's
    ``damping`` alone, which must then be positive)."""

    inertia: Inertia
    stiffness: Stiffness | None = None
    damping: Damping
    loss_factor: float = 0.0

    @model_validator(mode="after")
    def _damping(self):
        _positive(self, "inertia", "stiffness")
        _non_negative(self, "damping")
        if not 0.0 <= self.loss_factor <= MAX_COUPLING_LOSS_FACTOR:
            raise ValueError(f"loss_factor must lie in [0, {MAX_COUPLING_LOSS_FACTOR}]")
        if self.stiffness is None and not self.damping > 0:
            raise ValueError("a damper without stiffness (viscous, Houdaille) needs a positive damping")
        if self.stiffness is None and self.loss_factor:
            raise ValueError("a loss_factor needs the stiffness it damps (a viscous damper has none)")
        return self


class DrivenInput(Strict):
    name: str = Field(min_length=1)
    inertia: Inertia
    stiffness: Stiffness | None = None
    damping: Damping = 0.0
    loss_factor: float = 0.0
    absolute_damping: Damping = 0.0

    @model_validator(mode="after")
    def _check(self):
        if self.stiffness is None:
            raise ValueError(
                "a driven machine needs the stiffness of its connection (shaft or coupling) to the previous mass"
            )
        _positive(self, "inertia", "stiffness")
        _non_negative(self, "damping", "absolute_damping")
        if not 0.0 <= self.loss_factor <= MAX_COUPLING_LOSS_FACTOR:
            raise ValueError(f"loss_factor must lie in [0, {MAX_COUPLING_LOSS_FACTOR}]")
        return self


class TorsionInput(Strict):
    speed_range: tuple[Speed, Speed]
    speed_steps: int = Field(561, ge=11, le=20001)
    throw_stiffness: Literal["carter", "fe"] = "carter"
    shaft_loss_factor: float
    cylinder_damping: Damping
    assess_speed: Literal["governing", "operating"] = "governing"
    pulley: MassInput | None = None
    damper: DamperInput | None = None
    flywheel: MassInput
    driven: list[DrivenInput] = Field(default_factory=list)

    @model_validator(mode="after")
    def _check(self):
        lo, hi = self.speed_range
        if not 0 < lo < hi:
            raise ValueError("speed_range must be two increasing positive speeds")
        if not 0.0 <= self.shaft_loss_factor <= MAX_SHAFT_LOSS_FACTOR:
            raise ValueError(
                f"shaft_loss_factor must lie in [0, {MAX_SHAFT_LOSS_FACTOR}] "
                "(a crank without damper: about 0.015-0.04, docs/torsion.md)"
            )
        _non_negative(self, "cylinder_damping")
        if self.shaft_loss_factor == 0.0 and self.cylinder_damping == 0.0:
            raise ValueError(
                "shaft_loss_factor and cylinder_damping are both zero: an undamped crank has "
                "unbounded resonances; state the damping"
            )
        if self.damper is not None and self.pulley is None:
            raise ValueError("a damper needs the pulley (hub) it is mounted on: give [torsion.pulley]")
        return self


@dataclass(frozen=True)
class Element:
    """A mass of the chain and the segment that joins it to its neighbour."""

    name: str
    inertia: float
    stiffness: float
    damping: float = 0.0  # viscous across the segment
    loss_factor: float | None = None  # None: the shaft's
    absolute_damping: float = 0.0


class LumpedInput(Strict):
    """``model = "lumped"``: the chain as stations (``fe_crank.io.torsion_lumped``)."""

    model: Literal["lumped"]
    speed_range: tuple[Speed, Speed]
    speed_steps: int = Field(561, ge=11, le=20001)
    assess_speed: Literal["governing", "operating"] = "governing"
    stations: list = Field(min_length=2)
    flywheel_station: str | None = None

    @model_validator(mode="after")
    def _check(self):
        lo, hi = self.speed_range
        if not 0 < lo < hi:
            raise ValueError("speed_range must be two increasing positive speeds")
        return self


@dataclass(frozen=True)
class TorsionSettings:
    """``model = "cad"`` (default): the chain built from the throw CAD, Carter or the FE
    throw stiffness, and the elements below; ``"lumped"``: the ``stations`` as given
    (the CAD keys are then None/empty)."""

    speed_range: tuple[float, float]
    speed_steps: int
    throw_stiffness: str
    shaft_loss_factor: float | None
    cylinder_damping: float | None
    assess_speed: str
    damper: Element | None  # ring; its segment joins it to the pulley
    pulley: Element | None  # hub; its segment joins it to throw 1
    flywheel: Element | None  # its segment joins the last throw to it (cad)
    driven: tuple[Element, ...]  # each segment joins the previous mass to it
    model: str = "cad"
    stations: tuple[Station, ...] = ()  # lumped
    flywheel_station: str | None = None  # lumped: the station whose speed fluctuation is reported


def parse_torsion(value: object, file: str | Path, key: str = "torsion") -> TorsionSettings:
    """Parser of the load case's ``[torsion]`` section (``fe_crank.io.sections``).  Raises InputError naming file and key."""
    if not isinstance(value, dict):
        raise InputError("must be a table", file=str(file), key=key)
    if value.get("model", "cad") == "lumped":
        return _parse_lumped(value, file, key)
    if value.get("model", "cad") != "cad":
        raise InputError("model must be 'cad' (default) or 'lumped'", file=str(file), key=f"{key}.model")
    raw = validate(TorsionInput, {k: v for k, v in value.items() if k != "model"}, file, key)
    d = raw.damper
    damper = None if d is None else Element("damper", d.inertia, d.stiffness or 0.0, d.damping, d.loss_factor)
    pulley = None if raw.pulley is None else Element("pulley", raw.pulley.inertia, raw.pulley.stiffness)
    fly = Element("flywheel", raw.flywheel.inertia, raw.flywheel.stiffness)
    driven = tuple(_driven(x) for x in raw.driven)
    return TorsionSettings(
        raw.speed_range,
        raw.speed_steps,
        raw.throw_stiffness,
        raw.shaft_loss_factor,
        raw.cylinder_damping,
        raw.assess_speed,
        damper,
        pulley,
        fly,
        driven,
    )


def _driven(x: DrivenInput) -> Element:
    """The chain element of a driven machine (its stiffness is required: ``DrivenInput._check``)."""
    assert x.stiffness is not None  # refused by DrivenInput._check with its own message
    return Element(x.name, x.inertia, x.stiffness, x.damping, x.loss_factor, x.absolute_damping)


def _parse_lumped(value: dict[str, object], file: str | Path, key: str) -> TorsionSettings:
    raw = validate(LumpedInput, value, file, key)
    stations = parse_stations(raw.stations, str(file), f"{key}.stations")
    fly = raw.flywheel_station
    if fly is not None and fly not in {s.name for s in stations}:
        raise InputError(f"names station {fly!r}, which is not defined", file=str(file), key=f"{key}.flywheel_station")
    if fly is None:
        fly = next((s.name for s in stations if s.name == "flywheel"), max(stations, key=lambda s: s.inertia).name)
    return TorsionSettings(
        raw.speed_range,
        raw.speed_steps,
        "lumped",
        None,
        None,
        raw.assess_speed,
        None,
        None,
        None,
        (),
        model="lumped",
        stations=stations,
        flywheel_station=fly,
    )
