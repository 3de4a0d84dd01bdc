"""The ``[shaft]`` section of a geometry file -> ``fe_crank.geometry.spec.ShaftSpec`` (SI).

::

    [shaft]
    pitch = "92 mm"                  # optional: checked against the engine's axial positions
    end_journal_length = "34 mm"     # optional: outer web face to the end of an end journal
                                     # (default: twice the half-gap, a bearing centred as the inner ones)
    nose = { diameter = "40 mm", length = "45 mm" }      # optional, front
    flange = { diameter = "100 mm", length = "16 mm" }   # optional, rear
    bearing_width = "26 mm"          # optional: default width of every main bearing
    bearing = { model = "rigid" }    # default law; or { model = "spring", stiffness = "1e9 N/m" }
                                     # or { model = "clearance", clearance = "40 um", stiffness = "2e9 N/m" }
                                     # or { model = "hydrodynamic", clearance = "30 um", viscosity = "8 mPa*s" }
                                     #   (the oil film, fe_crank.fe.oil_film; ``HydrodynamicInput`` below)
    stiffness_range = ["3e8 N/m", "3e9 N/m"]   # optional: the bearings' realistic radial stiffness;
                                     # the main-bearing loads are the envelope of the law above and
                                     # springs across this range (default 3e8 to 3e9 N/m)
    thrust_bearing = "3"             # optional: default the bearing nearest the power take-off
    power_takeoff = "rear"           # "rear" (flywheel end, default) or "front"
    flywheel = { mass = "12 kg", offset = "40 mm", eccentricity = "0.1 mm", unbalance_angle = "0 deg" }
                                     # optional, at the power take-off's end: its centre plane offset
                                     # beyond the end journal's face; unbalance m e from the eccentricity
    pulley = { mass = "1.5 kg", offset = "35 mm", belt_pull = "1.2 kN", belt_angle = "90 deg" }
                                     # optional, at the other end; a belt pull fixed in the engine frame
                                     # (direction from +y towards +x); their weights are not modelled

    [[shaft.bearings]]               # optional: default one bearing at every journal, named 1, 2, ...
    name = "1"
    journal = 0                      # 0 front end journal, i between throws i and i + 1, n rear end
    width = "24 mm"                  # optional
    bearing = { model = "spring", stiffness = "8e8 N/m" }   # optional: this bearing's law

A negative stiffness or clearance, a spring or clearance bearing without its
stiffness, two bearings on one journal or with one name are refused here, and a
specific-load criterion without a stated bearing width (``require_bearing_widths``: the
journal's flat between its fillets is wider than a bearing shell); a bearing on
a journal the shaft does not have and a thrust bearing that names no bearing are refused
where the engine gives the journals (``fe_crank.geometry.shaft``).
"""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from fe_crank.errors import InputError
from fe_crank.geometry.oil import FilmSpec, walther_viscosity
from fe_crank.geometry.spec import BearingInput, BearingLaw, EndLoad, PlainCylinder, ShaftSpec
from fe_crank.io.base import Strict
from fe_crank.io.units import (
    Angle,
    Density,
    Force,
    KinematicViscosity,
    Length,
    Mass,
    Stiffness,
    Temperature,
    Viscosity,
)


class CylinderInput(Strict):
    diameter: Length = Field(gt=0)
    length: Length = Field(gt=0)


class OilInput(Strict):
    """An oil by its data sheet: kinematic viscosity at 40 and 100 degC, density, and the
    film's temperature (Walther's equation, ``geometry.oil.walther_viscosity``)."""

    nu40: KinematicViscosity = Field(gt=0)
    nu100: KinematicViscosity = Field(gt=0)
    density: Density = Field(gt=0)
    temperature: Temperature = Field(gt=0)

    @model_validator(mode="after")
    def _order(self):
        if self.nu100 >= self.nu40:
            raise ValueError("an oil's viscosity at 100 degC (nu100) must be below its viscosity at 40 degC (nu40)")
        return self


#: the keys of a hydrodynamic bearing's film (``BearingLawInput``)
FILM_KEYS = ("viscosity", "oil", "groove", "groove_width", "diameter")


class BearingLawInput(Strict):
    model: Literal["rigid", "spring", "clearance", "hydrodynamic"] = "rigid"
    stiffness: Stiffness | None = Field(default=None, gt=0)
    clearance: Length | None = Field(default=None, ge=0)
    # model = "hydrodynamic": the oil film (fe_crank.fe.oil_film); the shaft's static
    # solution takes the bearing as rigid (or as a spring of ``stiffness``)
    viscosity: Viscosity | None = Field(default=None, gt=0)
    oil: OilInput | None = None
    groove: Literal["none", "full"] | None = None
    groove_width: Length | None = Field(default=None, gt=0)
    diameter: Length | None = Field(default=None, gt=0)

    @model_validator(mode="after")
    def _keys(self):
        if self.model != "hydrodynamic":
            given = [k for k in FILM_KEYS if getattr(self, k) is not None]
            if given:
                raise ValueError(f'{", ".join(given)}: only a "hydrodynamic" bearing takes an oil film\'s keys')
        else:
            return self._film_keys()
        if self.model == "rigid" and (self.stiffness is not None or self.clearance is not None):
            raise ValueError('a "rigid" bearing takes no stiffness or clearance')
        if self.model in ("spring", "clearance") and self.stiffness is None:
            raise ValueError(f'a "{self.model}" bearing needs its radial stiffness, e.g. stiffness = "1e9 N/m"')
        if self.model == "spring" and self.clearance is not None:
            raise ValueError('a "spring" bearing takes no clearance (model = "clearance" does)')
        if self.model == "clearance" and self.clearance is None:
            raise ValueError('a "clearance" bearing needs its radial clearance, e.g. clearance = "40 um"')
        return self

    def _film_keys(self):
        if self.clearance is None or self.clearance <= 0:
            raise ValueError('a "hydrodynamic" bearing needs its radial clearance above zero, e.g. clearance = "30 um"')
        if self.viscosity is None and self.oil is None:
            raise ValueError(
                'a "hydrodynamic" bearing needs its oil: viscosity = "8 mPa*s" (at the film temperature) or '
                'oil = { nu40 = "68 mm^2/s", nu100 = "8.7 mm^2/s", density = "860 kg/m^3", temperature = "110 degC" }'
            )
        if self.viscosity is not None and self.oil is not None:
            raise ValueError('a "hydrodynamic" bearing takes its viscosity or its oil, not both')
        if self.groove == "full" and self.groove_width is None:
            raise ValueError('a full circumferential groove needs its width, e.g. groove_width = "4 mm"')
        if self.groove != "full" and self.groove_width is not None:
            raise ValueError('groove_width: only a bearing with groove = "full" has a groove')
        if self.diameter is not None and self.clearance >= self.diameter / 2:
            raise ValueError(
                f"the radial clearance {self.clearance * 1e6:.4g} um is not smaller than the journal's radius "
                f"{self.diameter * 500:.4g} mm"
            )
        return self

    def film(self) -> FilmSpec | None:
        if self.model != "hydrodynamic":
            return None
        assert self.clearance is not None
        if self.oil is not None:
            o = self.oil
            eta = walther_viscosity(o.nu40, o.nu100, o.density, o.temperature)
            how = (
                f"nu40 {o.nu40 * 1e6:.4g} mm^2/s, nu100 {o.nu100 * 1e6:.4g} mm^2/s, density {o.density:.4g} kg/m^3 "
                f"at {o.temperature - 273.15:.4g} degC (Walther, ASTM D341): {eta * 1e3:.4g} mPa s"
            )
        else:
            assert self.viscosity is not None
            eta, how = self.viscosity, f"{self.viscosity * 1e3:.4g} mPa s (stated)"
        return FilmSpec(
            clearance=self.clearance,
            viscosity=eta,
            groove=self.groove or "none",
            groove_width=self.groove_width or 0.0,
            diameter=self.diameter,
            oil=how,
        )

    def law(self) -> BearingLaw:
        if self.model == "hydrodynamic":  # the static solution: rigid, or a spring of the stated stiffness
            structural = "rigid" if self.stiffness is None else "spring"
            return BearingLaw(structural, self.stiffness, 0.0, self.film())
        return BearingLaw(self.model, self.stiffness, self.clearance or 0.0)


class EndLoadInput(Strict):
    mass: Mass = Field(gt=0)
    offset: Length = Field(ge=0)
    eccentricity: Length = Field(default=0.0, ge=0)
    unbalance_angle: Angle = 0.0
    belt_pull: Force = Field(default=0.0, ge=0)
    belt_angle: Angle = 0.0

    def load(self, name: str, end: str) -> EndLoad:
        return EndLoad(
            name,
            end,
            self.mass,
            self.offset,
            self.eccentricity,
            self.unbalance_angle,
            self.belt_pull,
            self.belt_angle,
        )


class BearingEntry(Strict):
    name: str = Field(min_length=1, max_length=64)
    journal: int = Field(ge=0, le=1000)
    width: Length | None = Field(default=None, gt=0)
    bearing: BearingLawInput | None = None


class ShaftInput(Strict):
    pitch: Length | None = Field(default=None, gt=0)
    end_journal_length: Length | None = Field(default=None, gt=0)
    nose: CylinderInput | None = None
    flange: CylinderInput | None = None
    bearing_width: Length | None = Field(default=None, gt=0)
    bearing: BearingLawInput = BearingLawInput()
    bearings: list[BearingEntry] | None = Field(default=None, min_length=2, max_length=1000)
    thrust_bearing: str | None = Field(default=None, min_length=1, max_length=64)
    power_takeoff: Literal["rear", "front"] = "rear"
    stiffness_range: list[Stiffness] | None = Field(default=None, min_length=2, max_length=2)
    flywheel: EndLoadInput | None = None
    pulley: EndLoadInput | None = None

    @model_validator(mode="after")
    def _range(self):
        if self.stiffness_range is not None:
            lo, hi = self.stiffness_range
            if not 0 < lo < hi:
                raise ValueError(
                    'stiffness_range: two positive stiffnesses, the lower first, e.g. ["3e8 N/m", "3e9 N/m"]'
                )
        return self

    @model_validator(mode="after")
    def _unique(self):
        if self.bearings:
            names = [b.name for b in self.bearings]
            journals = [b.journal for b in self.bearings]
            if len(set(names)) < len(names):
                raise ValueError("two bearings with one name")
            if len(set(journals)) < len(journals):
                raise ValueError("two bearings on one journal")
        return self


def shaft_spec(raw: ShaftInput | None) -> ShaftSpec | None:
    """The validated section as the frozen ``ShaftSpec`` (None when the file has none)."""
    if raw is None:
        return None

    def cyl(c: CylinderInput | None) -> PlainCylinder | None:
        return None if c is None else PlainCylinder(c.diameter, c.length)

    bearings = None
    if raw.bearings:
        bearings = tuple(
            BearingInput(b.name, b.journal, b.width, None if b.bearing is None else b.bearing.law())
            for b in sorted(raw.bearings, key=lambda b: b.journal)
        )
    return ShaftSpec(
        pitch=raw.pitch,
        end_journal_length=raw.end_journal_length,
        nose=cyl(raw.nose),
        flange=cyl(raw.flange),
        bearing_width=raw.bearing_width,
        bearing_law=raw.bearing.law(),
        bearings=bearings,
        thrust_bearing=raw.thrust_bearing,
        power_takeoff=raw.power_takeoff,
        stiffness_range=None if raw.stiffness_range is None else (raw.stiffness_range[0], raw.stiffness_range[1]),
        end_loads=_end_loads(raw),
    )


def _end_loads(raw: ShaftInput) -> tuple[EndLoad, ...]:
    """The flywheel at the power take-off's end, the pulley at the other."""
    other = "front" if raw.power_takeoff == "rear" else "rear"
    out = []
    if raw.pulley is not None:
        out.append(raw.pulley.load("pulley", other))
    if raw.flywheel is not None:
        out.append(raw.flywheel.load("flywheel", raw.power_takeoff))
    return tuple(out)


#: criteria that read a main bearing's width
WIDTH_CRITERIA = ("main_bearing_specific_load",)


def require_bearing_widths(bearings, quantities, geometry_file: str, criteria_file: str) -> None:
    """Refuse a specific-load criterion (peak / (d w)) while a main bearing has no stated
    width: the default, the journal's cylinder between its fillets, is wider than the
    bearing shell on it and would under-state the specific load.  ``bearings``: the
    layout's ``MainBearing``s; ``quantities``: the criteria's quantity names."""
    asked = [q for q in quantities if q in WIDTH_CRITERIA]
    missing = [b for b in bearings if not b.width_stated]
    if not asked or not missing:
        return
    names = ", ".join(b.name for b in missing)
    raise InputError(
        f"the criterion max_{asked[0]} of {criteria_file} divides each main bearing's peak load by its "
        f"projected area (journal diameter x bearing width), and main bearing(s) {names} have no stated "
        f"width (the journal's flat between its fillets, {missing[0].width * 1e3:.3g} mm, is not a bearing "
        'width): state it as [shaft] bearing_width = "24 mm" or per bearing ([[shaft.bearings]] width)',
        file=geometry_file,
        key="shaft.bearing_width",
    )
