"""Engine input model (TOML) -> ``fe_crank.model.Engine``.

An engine file looks like::

    name = "Single-cylinder four-stroke engine"
    strokes = 4

    [[throws]]
    name = "1"
    angle = "0 deg"
    crank_radius = "64 mm"          # or: stroke = "128 mm"

    [cylinder_defaults]              # merged into every [[cylinders]] entry
    bore = "92 mm"
    rod_length = "307 mm"

    [[cylinders]]
    name = "1"
    throw = "1"
    ...

``[[shafts]]`` may be omitted (one shaft called "main").  ``firing_order`` (names;
alone: evenly spaced over the cycle) and per-cylinder ``firing_offset``: either or both,
and when both they must agree (``fe_crank.io.firing``).
``construction`` ("trunk_piston" default, "crosshead") and ``internal_combustion`` (true
default; false: an air motor) are UR M53's (``rules.m53.basis``); a cylinder's
``pin_position``: its rod on the pin (``fe.throw.pin_patches``).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Literal

from pydantic import Field, StrictBool, model_validator

from fe_crank import model
from fe_crank.errors import InputError
from fe_crank.io.base import Strict, read_toml, validate
from fe_crank.io.bounds import check_crank_radius
from fe_crank.io.firing import firing_offsets
from fe_crank.io.gas import build_gas
from fe_crank.io.includes import read_included, with_include_context
from fe_crank.io.units import Angle, Inertia, Length, Mass


class ShaftInput(Strict):
    name: str = Field(min_length=1)
    sense: Literal[1, -1] = 1
    phase: Angle = 0.0
    centre_x: Length = 0.0
    centre_y: Length = 0.0
    speed_ratio: float = Field(default=1.0, gt=0)


class ThrowInput(Strict):
    name: str = Field(min_length=1)
    shaft: str = "main"
    angle: Angle = 0.0
    crank_radius: Length | None = None
    stroke: Length | None = None
    axial_position: Length = 0.0
    rotating_mass: Mass = 0.0

    @model_validator(mode="after")
    def _radius(self):
        if (self.crank_radius is None) == (self.stroke is None):
            raise ValueError("give exactly one of crank_radius and stroke")
        r = self.radius
        if not r > 0:
            raise ValueError(f"crank radius must be positive (got {r} m)")
        if self.rotating_mass < 0:
            raise ValueError("rotating_mass cannot be negative")
        return self

    @property
    def radius(self) -> float:
        if self.crank_radius is not None:
            return self.crank_radius
        assert self.stroke is not None  # the validator asks for one of the two
        return self.stroke / 2.0


class ArticulationInput(Strict):
    master: str
    link_radius: Length
    link_angle: Angle


class CylinderInput(Strict):
    name: str = Field(min_length=1)
    throw: str
    bore: Length
    rod_length: Length
    rod_mass: Mass
    rod_cg_from_big_end: Length
    rod_inertia: Inertia | None = None
    piston_mass: Mass
    bank_angle: Angle = 0.0
    pin_offset: Length = 0.0
    firing_offset: Angle | None = None
    articulation: ArticulationInput | None = None
    pin_position: Length | None = None  # big end's axial place on the pin from its middle

    @model_validator(mode="after")
    def _sizes(self):
        for key in ("bore", "rod_length"):
            if not getattr(self, key) > 0:
                raise ValueError(f"{key} must be positive (got {getattr(self, key)} m)")
        for key in ("rod_mass", "piston_mass"):
            if getattr(self, key) < 0:
                raise ValueError(f"{key} cannot be negative")
        if not 0.0 <= self.rod_cg_from_big_end <= self.rod_length:
            raise ValueError("rod_cg_from_big_end must lie between the big and small ends")
        if self.rod_inertia is not None and self.rod_inertia < 0:
            raise ValueError("rod_inertia cannot be negative")
        return self


class YokeInput(Strict):
    """Nordberg synchronising yoke (Liventsev, example 16); see ``fe_crank.model.Yoke``."""

    mass: Mass
    orbit_radius: Length
    arm: Length
    beta_max: Angle
    axis_angle: Angle = 0.0
    axial_position: Length = 0.0

    @model_validator(mode="after")
    def _positive(self):
        if not (self.mass > 0 and self.orbit_radius >= 0 and self.arm > 0):
            raise ValueError("yoke mass and arm must be positive, orbit_radius >= 0")
        return self


class EngineInput(Strict):
    name: str = Field(min_length=1)
    strokes: Literal[2, 4]
    source: str = ""
    shafts: list[ShaftInput] = Field(default_factory=lambda: [ShaftInput(name="main")])
    throws: list[ThrowInput] = Field(min_length=1)
    cylinder_defaults: dict = Field(default_factory=dict)
    cylinders: list[dict] = Field(min_length=1)
    firing_order: list[str] | None = None
    gas: dict | None = None  # validated by fe_crank.io.gas.build_gas (model = table | csv | wiebe)
    yoke: YokeInput | None = None  # Nordberg synchronising yoke (balance stage)
    construction: Literal["trunk_piston", "crosshead"] = "trunk_piston"  # UR M53 4: sigma_add
    internal_combustion: StrictBool = True  # false: air motor, compressor (UR M53 by analogy)


def _check_names(kind: str, names: list[str], file) -> None:
    for i, n in enumerate(names):
        if n in names[:i]:
            raise InputError(f"duplicate name {n!r}", file=str(file), key=f"{kind}[{i}].name")


def _check_cylinder_spacing(cylinders: list[CylinderInput], throws: dict, file: str, pre: str) -> None:
    """Refuse two cylinders of one bank (the same shaft and bank angle, neither an
    articulated rod's) whose bores overlap along the crank axis: their axes, at the
    throws' axial positions (plus the rods' ``pin_position``), must lie at least half of
    each bore apart.  An engine whose throws all keep the default axial position 0 states
    no layout along the axis and is not compared."""
    if all(t.axial_position == 0.0 for t in throws.values()):
        return  # the engine states no axial layout (the default): nothing to compare
    placed = []
    for i, c in enumerate(cylinders):
        if c.articulation is not None or c.throw not in throws:
            continue
        t = throws[c.throw]
        z = t.axial_position + (c.pin_position or 0.0)
        bank = round(math.remainder(c.bank_angle, 2 * math.pi), 9)
        placed.append((i, c, t.shaft, bank, z))
    for a, (i, ci, si, bi, zi) in enumerate(placed):
        for _, cj, sj, bj, zj in placed[:a]:
            gap = abs(zi - zj)
            if si == sj and bi == bj and gap < 0.5 * (ci.bore + cj.bore) * (1 - 1e-9):
                raise InputError(
                    f"cylinders {cj.name!r} and {ci.name!r} of one bank are {gap * 1e3:.6g} mm apart along the "
                    f"crank axis, less than their bores ({cj.bore * 1e3:.6g} and {ci.bore * 1e3:.6g} mm): the "
                    "cylinders overlap; check the bores and the throws' axial_position",
                    file=file,
                    key=f"{pre}cylinders[{i}].bore",
                )


def build_engine(data: dict, file: str | Path, prefix: str = "") -> model.Engine:
    """Validate an engine table and return the frozen engine (SI)."""
    pre = f"{prefix}." if prefix else ""
    raw = validate(EngineInput, data, file, prefix)
    cylinders: list[CylinderInput] = []
    for i, entry in enumerate(raw.cylinders):
        if not isinstance(entry, dict):
            raise InputError("each [[cylinders]] entry must be a table", file=str(file), key=f"{pre}cylinders[{i}]")
        merged = {**raw.cylinder_defaults, **entry}
        cylinders.append(validate(CylinderInput, merged, file, f"{pre}cylinders[{i}]"))
    _check_names(f"{pre}shafts", [s.name for s in raw.shafts], file)
    _check_names(f"{pre}throws", [t.name for t in raw.throws], file)
    _check_names(f"{pre}cylinders", [c.name for c in cylinders], file)
    shaft_names = {s.name for s in raw.shafts}
    throws = {t.name: t for t in raw.throws}
    for i, t in enumerate(raw.throws):
        if t.shaft not in shaft_names:
            raise InputError(
                f"names shaft {t.shaft!r}, which is not defined (shafts: {sorted(shaft_names)})",
                file=str(file),
                key=f"{pre}throws[{i}].shaft",
            )
    for i, t in enumerate(raw.throws):
        check_crank_radius(
            t.radius, str(file), f"{pre}throws[{i}].{'crank_radius' if t.crank_radius is not None else 'stroke'}"
        )
    names = [c.name for c in cylinders]
    _check_cylinder_spacing(cylinders, throws, str(file), pre)
    for i, c in enumerate(cylinders):
        if c.throw not in throws:
            raise InputError(
                f"names throw {c.throw!r}, which is not defined (throws: {sorted(throws)})",
                file=str(file),
                key=f"{pre}cylinders[{i}].throw",
            )
        r = throws[c.throw].radius
        if c.rod_length <= r + abs(c.pin_offset):
            raise InputError(
                f"rod length {c.rod_length * 1e3:.4g} mm must exceed crank radius {r * 1e3:.4g} mm "
                f"plus pin offset {abs(c.pin_offset) * 1e3:.4g} mm: the mechanism cannot turn",
                file=str(file),
                key=f"{pre}cylinders[{i}].rod_length",
            )
        if c.articulation is not None and c.articulation.master not in names:
            raise InputError(
                f"articulated rod names master {c.articulation.master!r}, which is not a cylinder",
                file=str(file),
                key=f"{pre}cylinders[{i}].articulation.master",
            )
    cycle = 4.0 * math.pi if raw.strokes == 4 else 2.0 * math.pi
    offsets = firing_offsets(
        names,
        raw.firing_order,
        {c.name: c.firing_offset for c in cylinders},
        cycle,
        file=str(file),
        key=f"{pre}firing_order",
    )
    gas = None
    if raw.gas is not None:
        c0 = cylinders[0]
        gas = build_gas(
            raw.gas,
            file,
            f"{pre}gas",
            strokes=raw.strokes,
            bore=c0.bore,
            crank_radius=throws[c0.throw].radius,
            rod_length=c0.rod_length,
        )
    return model.Engine(
        name=raw.name,
        strokes=raw.strokes,
        source=raw.source,
        shafts=tuple(
            model.Shaft(s.name, s.sense, s.phase, (s.centre_x, s.centre_y), s.speed_ratio) for s in raw.shafts
        ),
        throws=tuple(
            model.Throw(t.name, t.shaft, t.angle, t.radius, t.axial_position, t.rotating_mass) for t in raw.throws
        ),
        cylinders=tuple(
            model.Cylinder(
                name=c.name,
                throw=c.throw,
                bore=c.bore,
                rod=model.Rod(c.rod_length, c.rod_mass, c.rod_cg_from_big_end, c.rod_inertia),
                piston_mass=c.piston_mass,
                bank_angle=c.bank_angle,
                pin_offset=c.pin_offset,
                firing_offset=offsets[c.name],
                pin_position=c.pin_position,
                articulation=(
                    model.Articulation(c.articulation.master, c.articulation.link_radius, c.articulation.link_angle)
                    if c.articulation
                    else None
                ),
            )
            for c in cylinders
        ),
        gas=gas,
        construction=raw.construction,
        internal_combustion=raw.internal_combustion,
        yoke=(
            model.Yoke(
                raw.yoke.mass,
                raw.yoke.orbit_radius,
                raw.yoke.arm,
                raw.yoke.beta_max,
                raw.yoke.axis_angle,
                raw.yoke.axial_position,
            )
            if raw.yoke is not None
            else None
        ),
    )


def load_engine(path: str | Path) -> model.Engine:
    return build_engine(read_toml(path), path)


def engine_from_reference(value: object, file: str | Path, key: str = "engine") -> model.Engine:
    """``engine = "../engines/x.toml"`` (a path relative to ``file``) or an inline table."""
    if isinstance(value, str):
        p, data = read_included(value, file, key, "engine file")
        try:
            return build_engine(data, p)
        except InputError as exc:
            raise with_include_context(exc, file, key) from None
    if isinstance(value, dict):
        return build_engine(value, file, key)
    raise InputError("must be a path to an engine file or an inline [engine] table", file=str(file), key=key)


__all__ = ["build_engine", "load_engine", "engine_from_reference", "EngineInput", "CylinderInput"]
