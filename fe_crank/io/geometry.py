"""Crankshaft geometry files (``geometry/*.toml``) -> frozen ``CrankGeometry`` (SI).

::

    name = "V4 90 deg pneumatic engine crank"
    density = "7400 kg/m^3"
    crank_radius = "33 mm"          # or: stroke = "66 mm"
    require_overlap = false         # true: refuse a pin that does not overlap the journal

    [journal]                       # main journal, each side of a throw
    diameter = "50 mm"
    length = "20 mm"                # half a main bearing: the throw model ends mid-bearing
    fillet_radius = "3 mm"
    undercut = "0 mm"               # optional: recess of the fillet into the web (< fillet radius)

    [crankpin]
    diameter = "45 mm"
    length = "44 mm"
    fillet_radius = "3 mm"
    oil_bore = { diameter = "5 mm", angle = "90 deg" }   # optional, through the pin

    [web]
    thickness = "19 mm"
    outline = "stadium"             # width = "64 mm"  (rectangle with rounded ends)
    width = "64 mm"
    # outline = "pear"; journal_end_radius = "38 mm"; pin_end_radius = "30 mm"

    [counterweight]                 # optional: the same annular sector on each listed web
    outer_radius = "71 mm"
    inner_radius = "32 mm"
    angle = "180 deg"
    thickness = "19 mm"
    fillet_radius = "5 mm"          # transition radius where the sector meets the web
    offset = "0 deg"                # optional: turned from opposite the pin, from -y towards +x
    webs = [1, 2]
    bolted = { count = 2, diameter = "10 mm", pitch_radius = "50 mm", property_class = "10.9",
               clamp_length = "30 mm", bearing_diameter = "16 mm", hole_diameter = "11 mm",
               clamped_diameter = "24 mm", tightening_factor = 1.6 }   # VDI 2230: docs/assessment.md

    [[throws]]                      # optional: one throw at 0 deg when absent
    name = "1"
    angle = "0 deg"
    # counterweight = { ... }       # per-throw override; counterweight = false for none

    [shaft]                         # optional: the whole shaft (fe_crank.io.shaft has the keys)

The load case refers to the file with ``geometry = "../geometry/x.toml"`` (relative
to the load case).  Impossible geometries are refused here, before gmsh runs
(``fe_crank.geometry.checks``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Literal

from pydantic import Field, model_validator

from fe_crank.errors import InputError
from fe_crank.geometry.checks import check_geometry
from fe_crank.geometry.spec import (
    BoltedJoint,
    CounterweightSpec,
    CrankGeometry,
    OilBore,
    ThrowSpec,
    WebOutline,
)
from fe_crank.io.base import Strict, read_toml, validate
from fe_crank.io.bolted import BoltedInput
from fe_crank.io.bounds import check_crank_radius
from fe_crank.io.includes import read_included, with_include_context
from fe_crank.io.shaft import ShaftInput, shaft_spec
from fe_crank.io.units import Angle, Density, Length


class OilBoreInput(Strict):
    diameter: Length
    angle: Angle = 1.5707963267948966


class JournalInput(Strict):
    diameter: Length
    length: Length
    fillet_radius: Length = 0.0
    undercut: Length = 0.0


class CrankpinInput(JournalInput):
    oil_bore: OilBoreInput | None = None


class WebInput(Strict):
    thickness: Length
    outline: Literal["stadium", "pear"] = "stadium"
    width: Length | None = None
    journal_end_radius: Length | None = None
    pin_end_radius: Length | None = None

    @model_validator(mode="after")
    def _outline_keys(self):
        if self.outline == "stadium":
            if self.width is None:
                raise ValueError('outline "stadium" needs width')
            if self.journal_end_radius is not None or self.pin_end_radius is not None:
                raise ValueError('outline "stadium" takes width only; use outline = "pear" for two end radii')
        else:
            if self.journal_end_radius is None or self.pin_end_radius is None:
                raise ValueError('outline "pear" needs journal_end_radius and pin_end_radius')
            if self.width is not None:
                raise ValueError('outline "pear" takes journal_end_radius and pin_end_radius, not width')
        return self

    def end_radii(self) -> tuple[float, float]:
        """(journal end, pin end) radius of the outline (the validator gave one form)."""
        if self.width is not None:
            return self.width / 2, self.width / 2
        assert self.journal_end_radius is not None and self.pin_end_radius is not None
        return self.journal_end_radius, self.pin_end_radius


class CounterweightInput(Strict):
    outer_radius: Length
    inner_radius: Length
    angle: Angle
    thickness: Length | None = None  # default: the web thickness
    fillet_radius: Length | None = None  # None: a sharp edge (its stress cannot be assessed)
    offset: Angle = 0.0  # its mid-line from -y (opposite the pin) towards +x, |offset| < 180 deg
    webs: list[int] = Field(default_factory=lambda: [1, 2], min_length=1)
    bolted: BoltedInput | None = None


class ThrowInput(Strict):
    name: str | None = None
    angle: Angle = 0.0
    counterweight: CounterweightInput | Literal[False] | None = None


class GeometryInput(Strict):
    name: str = Field(min_length=1)
    description: str = ""
    source: str = ""
    density: Density = 7850.0
    crank_radius: Length | None = None
    stroke: Length | None = None
    require_overlap: bool = False
    journal: JournalInput
    crankpin: CrankpinInput
    web: WebInput
    counterweight: CounterweightInput | None = None
    throws: list[ThrowInput] | None = None
    shaft: ShaftInput | None = None  # whole-shaft model: ends, bearings (fe_crank.io.shaft)

    @model_validator(mode="after")
    def _radius(self):
        if (self.crank_radius is None) == (self.stroke is None):
            raise ValueError("give exactly one of crank_radius and stroke")
        return self


def _counterweights(cw: CounterweightInput | None, web_thickness: float) -> tuple[CounterweightSpec, ...]:
    if cw is None:
        return ()
    bolted = None
    if cw.bolted is not None:
        b = cw.bolted
        bolted = BoltedJoint(**b.model_dump())
    thickness = web_thickness if cw.thickness is None else cw.thickness
    return tuple(
        CounterweightSpec(
            web=w,
            outer_radius=cw.outer_radius,
            inner_radius=cw.inner_radius,
            angle=cw.angle,
            thickness=thickness,
            bolted=bolted,
            fillet_radius=cw.fillet_radius,
            offset=cw.offset,
        )
        for w in cw.webs
    )


def geometry_from_dict(data: dict, file: str | Path = "<geometry>", prefix: str = "") -> CrankGeometry:
    """Validate a geometry table (already read from TOML) and check it."""
    raw = validate(GeometryInput, data, file, prefix)
    web = WebOutline(raw.web.outline, *raw.web.end_radii())
    default_cw = _counterweights(raw.counterweight, raw.web.thickness)
    throws_in = raw.throws if raw.throws else [ThrowInput()]
    throws = []
    for i, t in enumerate(throws_in):
        if t.counterweight is None:
            cws = default_cw
        elif t.counterweight is False:
            cws = ()
        else:
            cws = _counterweights(t.counterweight, raw.web.thickness)
        throws.append(ThrowSpec(name=t.name or str(i + 1), angle=t.angle, counterweights=cws))
    bore = raw.crankpin.oil_bore
    g = CrankGeometry(
        name=raw.name,
        description=raw.description,
        source=raw.source,
        density=raw.density,
        crank_radius=raw.crank_radius if raw.crank_radius is not None else (raw.stroke or 0.0) / 2,
        journal_diameter=raw.journal.diameter,
        journal_length=raw.journal.length,
        crankpin_diameter=raw.crankpin.diameter,
        crankpin_length=raw.crankpin.length,
        web_thickness=raw.web.thickness,
        web=web,
        crankpin_fillet=raw.crankpin.fillet_radius,
        journal_fillet=raw.journal.fillet_radius,
        throws=tuple(throws),
        oil_bore=OilBore(bore.diameter, bore.angle) if bore is not None else None,
        crankpin_undercut=raw.crankpin.undercut,
        journal_undercut=raw.journal.undercut,
        require_overlap=raw.require_overlap,
        shaft=shaft_spec(raw.shaft),
        file=str(file),
    )
    check_crank_radius(
        g.crank_radius, str(file), _key(prefix, "crank_radius" if raw.crank_radius is not None else "stroke")
    )
    check_geometry(g)
    _check_bolts(g, raw, str(file), prefix)
    return g


def _key(prefix: str, key: str) -> str:
    return f"{prefix}.{key}" if prefix else key


def bolt_misfit(g: CrankGeometry, cw: CounterweightSpec) -> str | None:
    """Why the bolts of the bolted counterweight ``cw`` do not pass through it (None: they
    do, or it is not bolted): each bolt (at ``pitch_radius`` from the crank axis, +- half
    its ``diameter`` for an axial bolt) must lie outside the journal and within the
    counterweight's radial extent (``inner_radius`` ... ``outer_radius``)."""
    b = cw.bolted
    if b is None:
        return None
    half = b.diameter / 2 if b.direction == "axial" else 0.0  # a radial bolt runs along the radius
    lo, hi = b.pitch_radius - half, b.pitch_radius + half
    rj = g.journal_diameter / 2
    if lo < rj:
        return (
            f"the bolts ({b.diameter * 1e3:.6g} mm at a pitch radius of {b.pitch_radius * 1e3:.6g} mm) reach "
            f"into the journal (radius {rj * 1e3:.6g} mm): a bolt must pass through the counterweight into the web"
        )
    if lo < cw.inner_radius or hi > cw.outer_radius:
        return (
            f"the bolts ({b.diameter * 1e3:.6g} mm at a pitch radius of {b.pitch_radius * 1e3:.6g} mm, "
            f"{lo * 1e3:.6g}-{hi * 1e3:.6g} mm from the axis) do not lie within the counterweight "
            f"({cw.inner_radius * 1e3:.6g}-{cw.outer_radius * 1e3:.6g} mm from the axis): a bolt must pass "
            "through the counterweight into the web"
        )
    return None


def _check_bolts(g: CrankGeometry, raw: GeometryInput, file: str, prefix: str) -> None:
    """Refuse a bolted counterweight whose bolts do not pass through it (``bolt_misfit``)."""
    for i, t in enumerate(g.throws):
        own = (
            raw.throws is not None
            and i < len(raw.throws)
            and isinstance(raw.throws[i].counterweight, CounterweightInput)
        )
        where = f"throws[{i}].counterweight" if own else "counterweight"
        for cw in t.counterweights:
            reason = bolt_misfit(g, cw)
            if reason is not None:
                raise InputError(reason, file=file, key=_key(prefix, f"{where}.bolted.pitch_radius"))


#: criteria (``io.criteria`` quantities) that judge the counterweights' FE stress
COUNTERWEIGHT_STRESS_QUANTITIES = ("counterweight_stress", "counterweight_overspeed_stress")


def require_counterweight_fillets(g: CrankGeometry | None, quantities, file: str | Path) -> None:
    """Refuse a counterweight stress criterion on a counterweight without ``fillet_radius``.

    A sharp re-entrant edge between counterweight and web is a stress singularity
    (``fe_crank.geometry.cw_fillet``): its FE stress grows with every mesh refinement, so
    any figure from it would be optimistic.  ``quantities``: the criteria's quantities."""
    wanted = sorted(set(quantities) & set(COUNTERWEIGHT_STRESS_QUANTITIES))
    if g is None or not wanted:
        return
    for i, t in enumerate(g.throws):
        for cw in t.counterweights:
            if cw.fillet_radius is None:
                key = f"throws[{i}].counterweight.fillet_radius" if len(g.throws) > 1 else "counterweight.fillet_radius"
                raise InputError(
                    f"required by the criterion max_{wanted[0]} of {Path(file).name}: the transition radius "
                    'between counterweight and web (e.g. fillet_radius = "5 mm"); a sharp edge there is a '
                    "stress singularity whose FE stress grows without bound as the mesh is refined",
                    file=g.file or str(file),
                    key=key,
                )


def load_geometry(path: str | Path) -> CrankGeometry:
    """Read, validate and check one geometry file.  Raises ``InputError``/``GeometryError``."""
    path = Path(path)
    return geometry_from_dict(read_toml(path), path)


def parse_geometry(value: object, file: str | Path, key: str = "geometry") -> CrankGeometry:
    """Section parser of the load case's ``[geometry]`` section (``fe_crank.io.sections``): a path relative to the load case."""
    if isinstance(value, str):
        p, data = read_included(value, file, key, "geometry file")
        try:
            return geometry_from_dict(data, p)
        except InputError as exc:
            raise with_include_context(exc, file, key) from None
    if isinstance(value, dict):
        return geometry_from_dict(value, file, key)
    raise InputError('must be a file name, e.g. geometry = "../geometry/x.toml", or a table', file=str(file), key=key)
