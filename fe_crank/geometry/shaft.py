"""The whole crankshaft: the geometry file's throws placed where the engine puts them.

``shaft_layout(geometry, engine, ...)`` checks that the two files describe one shaft
(throw count, names in axial order, angles, crank radius against stroke / 2, a uniform
pitch, the geometry's stated ``[shaft] pitch``) and returns a frozen ``ShaftLayout``:

* throw i at ``z_i`` (the engine's ``axial_position``, the crankpin's mid-plane) and its
  angle on the shaft;
* journals between the webs: the gap between adjacent webs is
  ``g = pitch - (L_pin + 2 t)``, the inner journal i fills it and its main bearing sits at
  mid-gap; the end journals reach ``end_journal_length`` beyond the outer webs (default
  ``g``: a bearing centred like the inner ones, at ``g / 2`` from the web);
* main bearings (default one on every journal, named "1", "2", ... from the front), each
  with its width for the specific load (default the journal's cylindrical length between
  its two fillets, ``g - 2 r_f``; on an end journal the same, or less where the journal
  ends sooner) and its radial law;
* nose and flange beyond the end journals, the thrust bearing and the power take-off.

``bearing_stub(geometry, engine)`` is the length of a throw's journal stub from the web to
its main-bearing centre, ``g / 2`` on a shaft of two or more throws (the geometry's own
``journal.length`` on a single throw), and ``throw_at_bearings`` the geometry with that
stub: the per-throw model (FE and the UR M53 lever ``a = stub + t / 2``, "supported in the
centre of the adjacent main journals", UR M53 2.1) and the whole-shaft model both take
their bearing centres from it.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from fe_crank.errors import InputError
from fe_crank.geometry.engine_fit import (
    TOL,
    check_against_engine,
    for_engine_throws,
    pitch_of,
)
from fe_crank.geometry.spec import (
    DEFAULT_STIFFNESS_RANGE,
    BearingInput,
    BearingLaw,
    BoltedMass,
    CrankGeometry,
    EndLoad,
    PlainCylinder,
    PowerTakeoff,
    ShaftSpec,
    ThrowSpec,
)


@dataclass(frozen=True)
class PlacedThrow:
    name: str
    index: int  # 0-based from the front
    z: float  # m, the crankpin's mid-plane
    angle: float  # rad, the throw's angle on the shaft (geometry = engine)
    spec: ThrowSpec


@dataclass(frozen=True)
class JournalSpan:
    index: int  # 0 front end journal, i between throws i and i + 1 (1-based), n rear end journal
    z0: float  # m, front end
    z1: float  # m, rear end
    centre: float  # m, main-bearing centre plane (where a bearing on it sits)


@dataclass(frozen=True)
class MainBearing:
    name: str
    journal: int
    z: float  # m, centre plane
    width: float  # m, for the specific load
    law: BearingLaw
    thrust: bool = False
    #: the width is the file's (``[shaft] bearing_width`` or the bearing's ``width``); False:
    #: the journal's flat between its fillets, no bearing width (no specific-load criterion)
    width_stated: bool = True


@dataclass(frozen=True)
class ShaftLayout:
    """The shaft resolved against the engine (module doc).  ``geometry``: the throw
    geometry with its journal stubs reaching the bearing centres (``throw_at_bearings``)."""

    geometry: CrankGeometry
    throws: tuple[PlacedThrow, ...]
    journals: tuple[JournalSpan, ...]
    bearings: tuple[MainBearing, ...]
    stub: float  # m, web face to bearing centre
    pitch: float | None  # m; None for a single throw
    sense: int  # +1 / -1, the shaft's direction of rotation (engine)
    nose: PlainCylinder | None
    flange: PlainCylinder | None
    power_takeoff: PowerTakeoff
    geometry_file: str
    engine_file: str
    #: N/m, the stiffness range the main-bearing loads are enveloped over (``fe.shaft.whole_shaft``)
    stiffness_range: tuple[float, float] = DEFAULT_STIFFNESS_RANGE
    end_loads: tuple[EndLoad, ...] = ()  # flywheel, pulley (``fe.shaft.whole_shaft.end_load_cases``)
    #: counterweights bolted on and not meshed (a drawn shaft's, ``fe_crank.cad.whole``): their
    #: centrifugal forces, with the counterweights only (``fe.shaft.whole_shaft.end_load_cases``)
    bolted: tuple[BoltedMass, ...] = ()

    @property
    def thrust_bearing(self) -> MainBearing:
        return next(b for b in self.bearings if b.thrust)

    @property
    def half_length(self) -> float:
        """Axial distance of the outer web faces from the crankpin mid-plane, m."""
        return self.geometry.crankpin_length / 2 + self.geometry.web_thickness


#: the largest land width / diameter the oil film (``fe.oil_film``: its finite-length
#: factor's fitted range, ``fe.oil_film.MAX_LAND_ASPECT``) is offered for
MAX_FILM_ASPECT = 0.5


def film_fits(law: BearingLaw, width: float, g: CrankGeometry, gf: str, key: str) -> None:
    """A hydrodynamic bearing's film against its journal and width: the clearance below the
    journal's radius, the groove narrower than the bearing, each land's width / diameter at
    most ``MAX_FILM_ASPECT`` (the finite-bearing film's fitted range, docs/shaft.md)."""
    f = law.film
    assert f is not None
    d = f.diameter or g.journal_diameter
    if f.clearance >= d / 2:
        raise InputError(
            f"the radial clearance {f.clearance * 1e6:.4g} um is not smaller than the journal's radius {d * 500:.4g} mm",
            file=gf,
            key=f"{key}.clearance",
        )
    land = width
    if f.groove == "full":
        if f.groove_width >= width:
            raise InputError(
                f"the groove ({f.groove_width * 1e3:.4g} mm) is not narrower than the bearing ({width * 1e3:.4g} mm)",
                file=gf,
                key=f"{key}.groove_width",
            )
        land = (width - f.groove_width) / 2
    if land / d > MAX_FILM_ASPECT:
        raise InputError(
            f"a land {land * 1e3:.4g} mm wide on a {d * 1e3:.4g} mm journal (width / diameter {land / d:.3g}) is beyond "
            f"the oil film model's range (at most {MAX_FILM_ASPECT}: its finite-length factor is fitted up to "
            "there): state a narrower bearing_width or a full groove",
            file=gf,
            key=key,
        )


def require_film(layout: ShaftLayout, keys: list[str], path) -> None:
    """An oil-film criterion (``keys``) needs a hydrodynamic main bearing."""
    if keys and not any(b.law.film is not None for b in layout.bearings):
        raise InputError(
            'cannot be evaluated: no main bearing has an oil film (a [shaft] bearing with model = "hydrodynamic" '
            f"in the geometry file {layout.geometry_file})",
            file=str(path),
            key=f"criteria.{keys[0]}",
        )


def _bearings(spec: ShaftSpec, journals, g: CrankGeometry, gf: str, ef: str) -> tuple[MainBearing, ...]:
    n = len(journals) - 1
    rf = g.journal_fillet
    entries: tuple[BearingInput | None, ...] = spec.bearings if spec.bearings is not None else (None,) * len(journals)
    out = []
    for k, b in enumerate(entries):
        j = k if b is None else b.journal
        if j > n:
            label = b.name if b is not None else str(k)
            raise InputError(
                f"bearing {label!r} sits on journal {j}, but with the {n} throw(s) of the engine {ef} the "
                f"shaft has journals 0 (front) to {n} (rear)",
                file=gf,
                key=f"shaft.bearings[{k}].journal",
            )
        js = journals[j]
        flat = (js.z1 - js.z0) - 2 * rf  # the cylinder between two fillets ...
        if n > 0 and j in (0, n):  # ... or, on an end journal, as wide as an inner bearing at most
            flat = min(js.z1 - js.z0 - rf, 2 * (js.centre - js.z0 if j == n else js.z1 - js.centre) - 2 * rf)
        stated = (b.width if b is not None else None) or spec.bearing_width
        law = (b.law if b is not None else None) or spec.bearing_law
        if law.film is not None:
            own = b is not None and b.law is not None
            film_fits(law, stated or flat, g, gf, f"shaft.bearings[{k}].bearing" if own else "shaft.bearing")
        name = str(j + 1) if b is None else b.name
        out.append(MainBearing(name, j, js.centre, stated or flat, law, width_stated=stated is not None))
    if len(out) < 2:
        raise InputError("a shaft needs at least two main bearings", file=gf, key="shaft.bearings")
    if spec.thrust_bearing is None:
        thrust = out[-1].name if spec.power_takeoff == "rear" else out[0].name
    else:
        thrust = spec.thrust_bearing
        if thrust not in {b.name for b in out}:
            raise InputError(
                f"the thrust bearing {thrust!r} is none of the main bearings ({', '.join(b.name for b in out)})",
                file=gf,
                key="shaft.thrust_bearing",
            )
    return tuple(dataclasses.replace(b, thrust=b.name == thrust) for b in out)


def shaft_layout(
    g: CrankGeometry, engine, *, geometry_file: str, engine_file: str, shaft: str | None = None
) -> ShaftLayout:
    """The whole shaft of ``g`` placed by ``engine`` (module doc); ``InputError`` naming
    both files, the keys and both values where they disagree."""
    gf, ef = geometry_file, engine_file
    et, sense = check_against_engine(g, engine, geometry_file=gf, engine_file=ef, shaft=shaft)
    pitch = pitch_of(g, et, gf, ef)
    spec = g.shaft or ShaftSpec()
    stub = g.journal_length if pitch is None else 0.5 * (pitch - g.crankpin_length - 2 * g.web_thickness)
    tg = g if stub == g.journal_length else dataclasses.replace(g, journal_length=stub)
    zw = g.crankpin_length / 2 + g.web_thickness
    end_len = spec.end_journal_length if spec.end_journal_length is not None else 2 * stub
    if end_len < stub * (1 - TOL):
        raise InputError(
            f"end journals of {end_len * 1e3:.6g} mm end before their bearing centre, {stub * 1e3:.6g} mm from the web",
            file=gf,
            key="shaft.end_journal_length",
        )
    zs = [t.axial_position for t in et]
    throws = tuple(PlacedThrow(t.name, i, z, t.angle, g.throws[i]) for i, (t, z) in enumerate(zip(et, zs)))
    journals = [JournalSpan(0, zs[0] - zw - end_len, zs[0] - zw, zs[0] - zw - stub)]
    for i in range(1, len(zs)):
        a, b = zs[i - 1] + zw, zs[i] - zw
        journals.append(JournalSpan(i, a, b, 0.5 * (a + b)))
    journals.append(JournalSpan(len(zs), zs[-1] + zw, zs[-1] + zw + end_len, zs[-1] + zw + stub))
    bearings = _bearings(spec, journals, g, gf, ef)
    return ShaftLayout(
        geometry=tg,
        throws=throws,
        journals=tuple(journals),
        bearings=bearings,
        stub=stub,
        pitch=pitch,
        sense=int(sense),
        nose=spec.nose,
        flange=spec.flange,
        power_takeoff=spec.power_takeoff,
        geometry_file=gf,
        engine_file=ef,
        stiffness_range=spec.stiffness_range or DEFAULT_STIFFNESS_RANGE,
        end_loads=spec.end_loads,
    )


def main_bearings(spec: ShaftSpec, journals, g: CrankGeometry, gf: str, ef: str) -> tuple[MainBearing, ...]:
    """The main bearings of ``spec`` on ``journals`` (``JournalSpan``s, front to rear):
    names, widths, laws and the thrust bearing, as ``shaft_layout`` places them (a drawn
    shaft's journals too, ``fe_crank.cad.whole``)."""
    return _bearings(spec, journals, g, gf, ef)


def whole_shaft_wanted(g: CrankGeometry | None, engine) -> bool:
    """Whether a check builds the whole shaft: an engine of one shaft whose throws the
    engine spreads along the axis (two or more), or a geometry with a ``[shaft]`` section."""
    if g is None or len(engine.shafts) != 1:
        return False
    z = [t.axial_position for t in engine.throws]
    return g.shaft is not None or (len(z) > 1 and max(z) - min(z) > 0)


def engine_shaft_layout(g: CrankGeometry, engine, *, geometry_file: str, engine_file: str) -> ShaftLayout:
    """The whole shaft of a load case: ``shaft_layout`` of the geometry with one throw per
    engine throw (``for_engine_throws``)."""
    return shaft_layout(for_engine_throws(g, engine), engine, geometry_file=geometry_file, engine_file=engine_file)
