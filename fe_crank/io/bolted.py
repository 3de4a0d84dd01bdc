"""The ``bolted`` table of a counterweight in the geometry file: the joint's bolts,
their preload or property class and the clamped parts (VDI 2230-1:2015; the keys and
their defaults in docs/assessment.md, "The bolted counterweight")."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, StrictBool, model_validator

from fe_crank.io.base import Strict
from fe_crank.io.units import Force, Length, Pressure


class BoltedInput(Strict):
    """A bolted counterweight's joint (docs/assessment.md, "The bolted counterweight")."""

    count: int = Field(gt=0, le=64)
    diameter: Length = Field(gt=0.0)
    pitch_radius: Length = Field(gt=0.0)
    preload: Force | None = Field(default=None, gt=0.0)
    yield_strength: Pressure | None = Field(default=None, gt=0.0)
    pitch: Length | None = Field(default=None, gt=0.0)
    property_class: Literal["8.8", "10.9", "12.9"] | None = None
    clamp_length: Length | None = Field(default=None, gt=0.0)
    bearing_diameter: Length | None = Field(default=None, gt=0.0)
    hole_diameter: Length | None = Field(default=None, gt=0.0)
    clamped_diameter: Length | None = Field(default=None, gt=0.0)
    tightening_factor: float | None = Field(default=None, ge=1.0, le=4.0)
    direction: Literal["radial", "axial"] = "radial"
    tapped: StrictBool = True
    thread_friction: float = Field(default=0.10, ge=0.04, le=0.5)
    head_friction: float = Field(default=0.10, ge=0.04, le=0.5)
    interface_friction: float = Field(default=0.10, ge=0.04, le=0.8)
    roughness: Literal["below_10", "10_to_40", "40_to_160"] = "10_to_40"
    rolled_after_heat_treatment: StrictBool = False
    load_introduction: float | None = Field(default=None, gt=0.0, le=1.0)
    shank_length: Length = Field(default=0.0, ge=0.0)
    shank_diameter: Length | None = Field(default=None, gt=0.0)

    @model_validator(mode="after")
    def _joint(self):
        d = self.diameter
        if self.yield_strength is not None and self.property_class is not None:
            raise ValueError("give yield_strength or property_class, not both")
        if self.pitch is not None and not self.pitch < 0.25 * d:
            raise ValueError(f"pitch {self.pitch * 1e3:g} mm is not a thread pitch of d = {d * 1e3:g} mm")
        if self.hole_diameter is not None and not self.hole_diameter > d:
            raise ValueError("hole_diameter must exceed the bolt diameter")
        if self.bearing_diameter is not None and not self.bearing_diameter > max(d, self.hole_diameter or 0.0):
            raise ValueError("bearing_diameter must exceed the bolt and hole diameters")
        if self.clamped_diameter is not None and not self.clamped_diameter > (self.hole_diameter or d):
            raise ValueError("clamped_diameter must exceed the hole diameter")
        if self.clamp_length is not None and not self.shank_length < self.clamp_length:
            raise ValueError("shank_length must be shorter than clamp_length")
        if self.shank_diameter is not None and not self.shank_diameter <= d:
            raise ValueError("shank_diameter cannot exceed the thread diameter")
        return self


def require_joint_data(geometry, file) -> None:
    """Refuse, before any meshing, a bolted counterweight without the data its VDI 2230 check
    needs: every bolted joint of a geometry (``geometry.spec.CrankGeometry``) is checked
    (with VDI 2230's usual limits where the load case names none, ``assess.cw_joint``), so
    its clamp length, bearing, hole and clamped diameters, tightening factor and yield data
    are required.  ``file``: the load case (the geometry's own file is named when known)."""
    from fe_crank.errors import InputError

    for i, t in enumerate(geometry.throws):
        for cw in t.counterweights:
            if cw.bolted is None:
                continue
            missing = cw.bolted.vdi_missing()
            if missing:
                key = f"throws[{i}].counterweight.bolted" if len(geometry.throws) > 1 else "counterweight.bolted"
                raise InputError(
                    f"a bolted counterweight is checked by VDI 2230 (docs/assessment.md, with default limits where "
                    f"the load case names none): give {', '.join(missing)}",
                    file=str(geometry.file or file),
                    key=key,
                )
