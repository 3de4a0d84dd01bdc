"""The explicit lumped torsional model of ``[torsion]`` (``model = "lumped"``): the
stations, inertias, stiffnesses and damping as an engine maker's torsional data give
them (often measured), instead of the throw CAD and Carter's formula::

    [torsion]
    model = "lumped"
    speed_range = ["800 rpm", "3600 rpm"]
    flywheel_station = "flywheel"            # optional: where the speed fluctuation is read

    [[torsion.stations]]                     # from the free end
    name = "damper ring"
    inertia = "0.006 kg*m^2"

    [[torsion.stations]]
    name = "hub"
    inertia = "0.004 kg*m^2"
    damping = "3 N*m*s/rad"                  # to the previous station: viscous only (Houdaille)

    [[torsion.stations]]
    name = "crank 1"
    inertia = "0.012 kg*m^2"
    stiffness = "3e5 N*m/rad"                # to the previous station
    loss_factor = 0.025                      # optional, hysteresis of that connection
    absolute_damping = "0.2 N*m*s/rad"       # optional, to ground
    cylinders = ["1"]                        # the engine's cylinders acting on this station

Every station states its inertia (> 0); every station after the first its connection to
the previous one: a ``stiffness`` (> 0), a viscous ``damping`` (>= 0), or both; a
connection with damping and no stiffness is an untuned viscous damper's film.  Every
cylinder of the engine acts on exactly one station, and the cylinders of one throw on
the same station (a throw is one rigid mass).  The cross-check against the engine is
``check_stations``.
"""

from __future__ import annotations

from dataclasses import dataclass

from pydantic import Field, model_validator

from fe_crank.errors import InputError
from fe_crank.io.base import Strict, validate
from fe_crank.io.torsion_units import parse_per_angle
from fe_crank.io.units import Inertia

#: the largest accepted loss factor of a connection (a rubber coupling reaches ~0.3)
MAX_LOSS_FACTOR = 1.0
#: the most stations a chain may have (bounds the eigen and frequency-response work)
MAX_STATIONS = 200


class StationInput(Strict):
    name: str = Field(min_length=1, max_length=60)
    inertia: Inertia
    stiffness: float | None = None  # set by parse (per-angle unit)
    damping: float | None = None
    loss_factor: float = 0.0
    absolute_damping: float = 0.0
    cylinders: list[str] = Field(default_factory=list, max_length=64)

    @model_validator(mode="after")
    def _check(self):
        if not self.inertia > 0:
            raise ValueError("inertia must be positive")
        for key in ("stiffness", "damping", "absolute_damping"):
            v = getattr(self, key)
            if v is not None and v < 0:
                raise ValueError(f"{key} must not be negative")
        if not 0.0 <= self.loss_factor <= MAX_LOSS_FACTOR:
            raise ValueError(f"loss_factor must lie in [0, {MAX_LOSS_FACTOR}]")
        return self


@dataclass(frozen=True)
class Station:
    """One mass of the lumped chain and its connection to the previous station (SI)."""

    name: str
    inertia: float
    stiffness: float  # N m/rad to the previous station (0: viscous only; unused on the first)
    damping: float  # N m s/rad, viscous across that connection
    loss_factor: float  # hysteresis of that connection
    absolute_damping: float  # N m s/rad to ground
    cylinders: tuple[str, ...]


def parse_stations(items: list, file: str, key: str) -> tuple[Station, ...]:
    """Validate ``[[torsion.stations]]`` (module docstring).  Raises InputError."""
    if not isinstance(items, list) or len(items) < 2:
        raise InputError("a lumped model needs at least two stations", file=file, key=key)
    if len(items) > MAX_STATIONS:
        raise InputError(f"at most {MAX_STATIONS} stations", file=file, key=key)
    out, names = [], set()
    for i, item in enumerate(items):
        k = f"{key}[{i}]"
        if not isinstance(item, dict):
            raise InputError("each station must be a table", file=file, key=k)
        data = dict(item)
        if "inertia" not in data:
            raise InputError("a station needs its inertia (kg*m^2)", file=file, key=f"{k}.inertia")
        for unit_key, kind in (("stiffness", "stiffness"), ("damping", "damping"), ("absolute_damping", "damping")):
            if unit_key in data:
                data[unit_key] = parse_per_angle(data[unit_key], kind, file, f"{k}.{unit_key}")
        raw = validate(StationInput, data, file, k)
        if raw.name in names:
            raise InputError(f"duplicate station name {raw.name!r}", file=file, key=f"{k}.name")
        names.add(raw.name)
        if i == 0 and (raw.stiffness is not None or raw.damping is not None or raw.loss_factor):
            raise InputError(
                "the first station has no previous station: its connection keys (stiffness, damping, "
                "loss_factor) belong to the second",
                file=file,
                key=k,
            )
        if i > 0 and not ((raw.stiffness or 0.0) > 0 or (raw.damping or 0.0) > 0):
            raise InputError(
                "needs its connection to the previous station: a stiffness (> 0), a viscous damping "
                "(> 0, an untuned viscous damper), or both",
                file=file,
                key=k,
            )
        if i > 0 and raw.loss_factor > 0 and not (raw.stiffness or 0.0) > 0:
            raise InputError("a loss_factor needs the stiffness it damps", file=file, key=f"{k}.loss_factor")
        out.append(
            Station(
                raw.name,
                raw.inertia,
                raw.stiffness or 0.0,
                raw.damping or 0.0,
                raw.loss_factor,
                raw.absolute_damping,
                tuple(raw.cylinders),
            )
        )
    if not any(s.damping > 0 or s.loss_factor > 0 or s.absolute_damping > 0 for s in out):
        raise InputError(
            "no station or connection has damping: an undamped chain has unbounded resonances; state the damping",
            file=file,
            key=key,
        )
    return tuple(out)


def check_stations(stations: tuple[Station, ...], engine, file: str, key: str = "torsion.stations") -> None:
    """Every cylinder of ``engine`` on exactly one station, the cylinders of one throw on
    one station, no unknown cylinder.  Raises InputError naming the file and the key."""
    where: dict[str, str] = {}
    throw_at: dict[str, str] = {}
    names = [c.name for c in engine.cylinders]
    for i, s in enumerate(stations):
        for j, c in enumerate(s.cylinders):
            k = f"{key}[{i}].cylinders[{j}]"
            if c not in names:
                raise InputError(f"names cylinder {c!r}, which the engine does not have ({names})", file=file, key=k)
            if c in where:
                raise InputError(f"cylinder {c!r} is already on station {where[c]!r}", file=file, key=k)
            where[c] = s.name
            throw = engine.cylinder(c).throw
            if throw_at.setdefault(throw, s.name) != s.name:
                raise InputError(
                    f"cylinder {c!r} is on throw {throw!r}, whose other cylinders act on station "
                    f"{throw_at[throw]!r}: a throw is one mass",
                    file=file,
                    key=k,
                )
    missing = [c for c in names if c not in where]
    if missing:
        raise InputError(f"cylinders {missing} act on no station: attach each to one", file=file, key=key)


__all__ = ["Station", "StationInput", "parse_stations", "check_stations", "MAX_STATIONS"]
