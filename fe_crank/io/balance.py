"""The load case's ``[balance]`` section -> frozen ``BalanceSettings`` (SI floats).

::

    [balance]
    reference_z = "0 mm"              # moments about this point on the crank axis
    rotating_fraction = 1.0           # share of the rotating masses balanced
    reciprocating_fraction = 0.5      # share of each cylinder's first-order mass m_j R
    couple = "whole_shaft"            # or "per_throw"
    planes = ["-108.5 mm", "-64 mm", "64 mm", "108.5 mm"]   # whole_shaft only
    web_offset = "20 mm"              # per_throw: webs at throw z +- web_offset

    [balance.counterweight]           # optional: synthesise annular sectors
    density = "7400 kg/m^3"
    free = "thickness"                # r_outer | r_inner | thickness | angle
    r_outer = "71 mm"
    r_inner = "32 mm"
    angle = "180 deg"
    envelope = "75 mm"                # largest outer radius allowed
    journal_radius = "25 mm"          # smallest inner radius allowed

    [[balance.shafts]]                # optional: balance shafts, one entry per component
    component = "force"               # or "couple"
    order = 2
    offset = "100 mm"
    span = "200 mm"
    positions = [["60 mm", "40 mm"], ["-60 mm", "-20 mm"]]   # optional: (x, y) of each shaft
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from pydantic import Field, model_validator

from fe_crank.balance.counterweights import BalanceStrategy
from fe_crank.errors import InputError
from fe_crank.io.base import Strict, validate
from fe_crank.io.units import Angle, Density, Length


class CounterweightInput(Strict):
    density: Density
    free: Literal["r_outer", "r_inner", "thickness", "angle"]
    r_outer: Length | None = None
    r_inner: Length | None = None
    thickness: Length | None = None
    angle: Angle | None = None
    envelope: Length | None = None
    journal_radius: Length | None = None

    @model_validator(mode="after")
    def _given(self):
        for k in ("r_outer", "r_inner", "thickness", "angle"):
            if k != self.free and getattr(self, k) is None:
                raise ValueError(f"give {k} (only {self.free!r} is solved for)")
        if self.density <= 0:
            raise ValueError("density must be positive")
        return self


class ShaftRequestInput(Strict):
    component: Literal["force", "couple"]
    order: Literal[1, 2]
    offset: Length = 0.1
    span: Length = 0.2
    positions: list[tuple[Length, Length]] | None = None


class BalanceInput(Strict):
    reference_z: Length = 0.0
    rotating_fraction: float = 1.0
    reciprocating_fraction: float = 0.0
    couple: Literal["per_throw", "whole_shaft"] = "per_throw"
    planes: list[Length] = Field(default_factory=list)
    web_offset: Length = 0.0
    counterweight: CounterweightInput | None = None
    shafts: list[ShaftRequestInput] = Field(default_factory=list)

    @model_validator(mode="after")
    def _fractions(self):
        for k in ("rotating_fraction", "reciprocating_fraction"):
            if getattr(self, k) < 0:
                raise ValueError(f"{k} must be >= 0 (got {getattr(self, k)})")
        if self.reciprocating_fraction > 1:
            raise ValueError(f"reciprocating_fraction cannot exceed 1 (got {self.reciprocating_fraction})")
        if self.couple == "whole_shaft" and len(self.planes) < 2:
            raise ValueError("couple = 'whole_shaft' needs at least two planes")
        return self


@dataclass(frozen=True)
class CounterweightSpec:
    density: float
    free: str
    r_outer: float | None
    r_inner: float | None
    thickness: float | None
    angle: float | None
    envelope: float | None
    journal_radius: float | None


@dataclass(frozen=True)
class ShaftRequest:
    component: str
    order: int
    offset: float
    span: float
    positions: tuple[tuple[float, float], ...] | None = None


@dataclass(frozen=True)
class BalanceSettings:
    strategy: BalanceStrategy
    reference_z: float = 0.0
    counterweight: CounterweightSpec | None = None
    shafts: tuple[ShaftRequest, ...] = ()


def parse_balance(value: object, file: str | Path, key: str = "balance") -> BalanceSettings:
    """Parser of the load case's ``[balance]`` section (``fe_crank.io.sections``).  Raises InputError naming file and key."""
    if not isinstance(value, dict):
        raise InputError("must be a table", file=str(file), key=key)
    raw = validate(BalanceInput, value, file, key)
    try:
        strategy = BalanceStrategy(
            raw.rotating_fraction, raw.reciprocating_fraction, raw.couple, tuple(raw.planes), raw.web_offset
        )
    except InputError as exc:
        raise InputError(exc.reason, file=str(file), key=exc.key) from None
    cw = None
    if raw.counterweight is not None:
        c = raw.counterweight
        cw = CounterweightSpec(
            c.density, c.free, c.r_outer, c.r_inner, c.thickness, c.angle, c.envelope, c.journal_radius
        )
    shafts = tuple(
        ShaftRequest(
            s.component,
            s.order,
            s.offset,
            s.span,
            None if s.positions is None else tuple(s.positions),
        )
        for s in raw.shafts
    )
    return BalanceSettings(strategy, raw.reference_z, cw, shafts)
