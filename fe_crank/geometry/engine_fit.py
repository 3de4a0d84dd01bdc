"""Does a geometry file describe the engine's crankshaft, and where are its main-bearing
centres?  ``check_against_engine`` compares the two files (throw count, names in axial
order, angles, crank radius against stroke / 2, a uniform pitch, the geometry's stated
``[shaft] pitch``) and refuses a mismatch naming both files, the key and both values;
``bearing_stub`` is the length of a throw's journal stub from its outer web face to the
main-bearing centre (half the gap between adjacent webs, ``(pitch - L_pin - 2 t) / 2``,
on a shaft of two or more throws; the geometry's ``journal.length`` on a single throw),
and ``throw_at_bearings`` the geometry with that stub, so that the per-throw model's
supports and the UR M53 lever (UR M53 2.1: "supported in the centre of the adjacent main
journals") sit where the engine has its bearings (``fe_crank.geometry.shaft`` places the
whole shaft on the same centres).
"""

from __future__ import annotations

import dataclasses
import math

from fe_crank.errors import InputError
from fe_crank.geometry.spec import CrankGeometry

#: relative tolerance of the comparisons between geometry and engine (lengths, angles)
TOL = 1e-9


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


def pitch_of(g: CrankGeometry, et, gf: str, ef: str) -> float | None:
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
    pitch = pitch_of(g, et, geometry_file, engine_file)
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
            p = pitch_of(dataclasses.replace(g, shaft=None), et, gf, ef)
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
