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
import math
from dataclasses import dataclass

from fe_crank.errors import InputError
from fe_crank.geometry.spec import BearingInput, BearingLaw, CrankGeometry, PlainCylinder, ShaftSpec, ThrowSpec

#: relative tolerance of the comparisons between geometry and engine (lengths, angles)
TOL = 1e-9


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
    power_takeoff: str  # "rear" | "front"
    geometry_file: str
    engine_file: str

    @property
    def thrust_bearing(self) -> MainBearing:
        return next(b for b in self.bearings if b.thrust)

    @property
    def half_length(self) -> float:
        """Axial distance of the outer web faces from the crankpin mid-plane, m."""
        return self.geometry.crankpin_length / 2 + self.geometry.web_thickness


def _deg(a: float) -> str:
    return f"{math.degrees(a):.6g} deg"


def _engine_throws(engine, shaft: str | None, gfile: str, efile: str):
    names = [s.name for s in engine.shafts]
    if shaft is None:
        if len(names) > 1:
            raise InputError(
                f"the engine {efile} has {len(names)} shafts; say which one the geometry describes",
                file=gfile,
                key="shaft",
            )
        shaft = names[0]
    if shaft not in names:
        raise InputError(f"the engine {efile} has no shaft {shaft!r}", file=gfile, key="shaft")
    throws = [t for t in engine.throws if t.shaft == shaft]
    return sorted(throws, key=lambda t: t.axial_position), engine.shaft(shaft).sense


def check_against_engine(g: CrankGeometry, engine, *, geometry_file: str, engine_file: str, shaft: str | None = None):
    """Refuse a geometry that describes another shaft than the engine's; return the
    engine's throws in axial order and the shaft's sense of rotation."""
    gf, ef = geometry_file, engine_file
    et, sense = _engine_throws(engine, shaft, gf, ef)
    if len(et) != len(g.throws):
        raise InputError(
            f"{len(g.throws)} throw(s) here, {len(et)} in the engine {ef} (throws): "
            "the geometry and the engine describe different crankshafts",
            file=gf,
            key="throws",
        )
    for i, (gt, t) in enumerate(zip(g.throws, et)):
        if gt.name != t.name:
            raise InputError(
                f"throw {i + 1} from the front is named {gt.name!r} here, {t.name!r} in the engine {ef} "
                f"(throws, in axial order)",
                file=gf,
                key=f"throws[{i}].name",
            )
        da = math.remainder(gt.angle - t.angle, 2 * math.pi)
        if abs(da) > TOL:
            raise InputError(
                f"throw {gt.name!r} at {_deg(gt.angle)} here, at {_deg(t.angle)} in the engine {ef} "
                f"(throws[{i}].angle)",
                file=gf,
                key=f"throws[{i}].angle",
            )
        if abs(t.crank_radius - g.crank_radius) > TOL * g.crank_radius:
            raise InputError(
                f"crank radius {g.crank_radius * 1e3:.6g} mm (stroke {2e3 * g.crank_radius:.6g} mm) here, "
                f"stroke {2e3 * t.crank_radius:.6g} mm (crank radius {t.crank_radius * 1e3:.6g} mm) for throw "
                f"{t.name!r} in the engine {ef} (throws[{i}].stroke)",
                file=gf,
                key="stroke",
            )
    return et, sense


def _pitch(g: CrankGeometry, et, gf: str, ef: str) -> float | None:
    if len(et) < 2:
        return None
    steps = [b.axial_position - a.axial_position for a, b in zip(et, et[1:])]
    pitch = steps[0]
    for i, s in enumerate(steps[1:], start=1):
        if abs(s - pitch) > TOL * pitch:
            raise InputError(
                f"the throws are not evenly spaced: {pitch * 1e3:.6g} mm between the first two, "
                f"{s * 1e3:.6g} mm between throws {et[i].name!r} and {et[i + 1].name!r} (axial_position); "
                "the whole-shaft model needs one pitch",
                file=ef,
                key=f"throws[{i + 1}].axial_position",
            )
    stated = g.shaft.pitch if g.shaft is not None else None
    if stated is not None and abs(stated - pitch) > TOL * pitch:
        raise InputError(
            f"pitch {stated * 1e3:.6g} mm here, {pitch * 1e3:.6g} mm between the throws' axial_position "
            f"in the engine {ef}",
            file=gf,
            key="shaft.pitch",
        )
    gap = pitch - g.crankpin_length - 2 * g.web_thickness
    if gap <= 2 * g.journal_fillet:
        raise InputError(
            f"the engine {ef} puts the throws {pitch * 1e3:.6g} mm apart, but a throw of this geometry is "
            f"{(g.crankpin_length + 2 * g.web_thickness) * 1e3:.6g} mm long between its outer web faces: "
            f"a gap of {gap * 1e3:.6g} mm leaves no room for two journal fillets of "
            f"{g.journal_fillet * 1e3:.6g} mm",
            file=gf,
            key="web.thickness",
        )
    return pitch


def bearing_stub(g: CrankGeometry, engine, *, geometry_file: str, engine_file: str, shaft: str | None = None) -> float:
    """Length of a journal stub from the outer web face to its main-bearing centre, m:
    half the gap between adjacent webs on a shaft of two or more throws, the geometry's
    ``journal.length`` on a single throw (module doc).  Checks the files agree."""
    et, _ = check_against_engine(g, engine, geometry_file=geometry_file, engine_file=engine_file, shaft=shaft)
    pitch = _pitch(g, et, geometry_file, engine_file)
    if pitch is None:
        return g.journal_length
    return 0.5 * (pitch - g.crankpin_length - 2 * g.web_thickness)


def throw_at_bearings(
    g: CrankGeometry, engine, *, geometry_file: str, engine_file: str, shaft: str | None = None
) -> CrankGeometry:
    """The geometry whose journal stubs end at the engine's bearing centres (module doc).

    A geometry of several throws must describe the engine's shaft (``check_against_engine``).
    A geometry of one throw may stand for every throw of the engine (the per-throw model's
    shortcut, ``mesh.plan``): its crank radius is checked against every throw's stroke and
    the stub follows from the pitch of the shafts whose throws the engine spreads along the
    axis (one pitch for all of them); on an engine that places none apart (one throw per
    shaft, or throws at one axial position) the geometry's ``journal.length`` stays."""
    if len(g.throws) == 1:
        stub = _one_for_all_stub(g, engine, geometry_file, engine_file)
    else:
        stub = bearing_stub(g, engine, geometry_file=geometry_file, engine_file=engine_file, shaft=shaft)
    return g if stub == g.journal_length else dataclasses.replace(g, journal_length=stub)


def _one_for_all_stub(g: CrankGeometry, engine, gf: str, ef: str) -> float:
    for i, t in enumerate(engine.throws):
        if abs(t.crank_radius - g.crank_radius) > TOL * g.crank_radius:
            raise InputError(
                f"crank radius {g.crank_radius * 1e3:.6g} mm (stroke {2e3 * g.crank_radius:.6g} mm) here, "
                f"stroke {2e3 * t.crank_radius:.6g} mm (crank radius {t.crank_radius * 1e3:.6g} mm) for throw "
                f"{t.name!r} in the engine {ef} (throws[{i}].stroke): the geometry's one throw stands for "
                "every throw of the engine",
                file=gf,
                key="stroke",
            )
    pitches: dict[str, float] = {}
    for s in engine.shafts:
        et = sorted((t for t in engine.throws if t.shaft == s.name), key=lambda t: t.axial_position)
        if len(et) > 1 and et[-1].axial_position - et[0].axial_position > TOL * g.crank_radius:
            p = _pitch(dataclasses.replace(g, shaft=None), et, gf, ef)
            if p is not None:  # two throws or more apart: always
                pitches[s.name] = p
    if not pitches:
        return g.journal_length
    values = sorted(pitches.values())
    if values[-1] - values[0] > TOL * values[-1]:
        raise InputError(
            f"the engine {ef} spaces the throws of its shafts differently "
            f"({', '.join(f'{k}: {v * 1e3:.6g} mm' for k, v in pitches.items())}); the geometry's one throw "
            "cannot stand for all of them: give a geometry per shaft",
            file=gf,
            key="throws",
        )
    stated = g.shaft.pitch if g.shaft is not None else None
    if stated is not None and abs(stated - values[0]) > TOL * values[0]:
        raise InputError(
            f"pitch {stated * 1e3:.6g} mm here, {values[0] * 1e3:.6g} mm between the throws' axial_position "
            f"in the engine {ef}",
            file=gf,
            key="shaft.pitch",
        )
    return 0.5 * (values[0] - g.crankpin_length - 2 * g.web_thickness)


def for_engine_throws(g: CrankGeometry, engine, shaft: str | None = None) -> CrankGeometry:
    """The geometry with one throw per throw of the engine's shaft: ``g`` itself, or, when
    ``g`` gives one throw standing for all (``throw_at_bearings``), that throw under each
    engine throw's name and angle (axial order), so that the whole shaft can be built."""
    names = [s.name for s in engine.shafts]
    shaft = shaft if shaft is not None else (names[0] if len(names) == 1 else None)
    et = sorted((t for t in engine.throws if t.shaft == shaft), key=lambda t: t.axial_position)
    if len(g.throws) != 1 or not et:
        return g
    one = g.throws[0]
    return dataclasses.replace(g, throws=tuple(dataclasses.replace(one, name=t.name, angle=t.angle) for t in et))


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
        width = (b.width if b is not None else None) or spec.bearing_width or flat
        law = (b.law if b is not None else None) or spec.bearing_law
        out.append(MainBearing(str(j + 1) if b is None else b.name, j, js.centre, width, law))
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
    pitch = _pitch(g, et, gf, ef)
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
    )


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
