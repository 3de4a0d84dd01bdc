"""The throws recognised in a CAD file against the engine they are checked for.

``engine_keys`` gives the mesh plan's keys (``fe_crank.throw_scope``) after checking
that the file's shaft is the engine's:

* throws: a file with one throw stands for every throw of the engine (each assessed
  on it with its own loads, as a parametric geometry with one throw does); a file with
  several must hold the engine's throws by name (``[cad] throws``, from the front;
  ``"1"``, ``"2"``, ... by default), as many as the engine has;
* crank radius: each recognised throw's within ``CRANK_RADIUS_RTOL`` of the engine's
  throw it stands for (the kinematics run on the engine's, the FE on the drawing's);
  a ratio near that of two length units says the file's unit is wrong (a file in
  inches read as millimetres: 25.4), which ``[cad] length_unit`` settles;
* angles: the pins' angles from the front throw's, in the positive sense of
  ``fe_crank.model`` (``+y`` towards ``+x``), within ``ANGLE_TOL`` of the engine's,
  ``sense (angle_k - angle_front)`` of its shaft (a whole shaft is one shaft).

* spacing (a file of several throws): the pins' mid-planes along the crank axis as far
  apart as the engine's ``axial_position``s, within ``CRANK_RADIUS_RTOL`` of the engine's
  spacing; adjacent throws share one main journal (the drawing has one journal more than
  throws, as the engine has main bearings); the main-bearing plane between two throws,
  midway between their ``axial_position``s (``fe_crank.geometry.shaft``), at the drawn
  journal's middle, where the throw model ends (``CadFeatures`` bearing centres), within
  the same tolerance.

Each mismatch is one ``InputError`` naming the CAD file, the ``[cad]`` key that
settles it, both values and the engine file's key.
"""

from __future__ import annotations

import math

from fe_crank import model
from fe_crank.cad.config import CadInput
from fe_crank.cad.features import CadFeatures, ThrowFeatures
from fe_crank.cad.frame import turn_angle
from fe_crank.errors import InputError
from fe_crank.throw_scope import ALL_THROWS

CRANK_RADIUS_RTOL = 1e-3
ANGLE_TOL = 1e-3  # rad (0.06 deg)
#: ratios of length units (m per unit over m per unit): mm/in, mm/ft, mm/m, mm/cm, in/ft
UNIT_RATIOS = (25.4, 304.8, 1000.0, 10.0, 12.0, 100.0)


def _mm(v: float) -> str:
    return f"{v * 1e3:.6g} mm"


def _engine_key(engine: model.Engine, name: str, field: str, engine_file: str, loadcase: str) -> str:
    i = next(k for k, t in enumerate(engine.throws) if t.name == name)
    prefix = "engine." if engine_file == loadcase else ""
    return f"{prefix}throws[{i}].{field}"


def _unit_ratio(ratio: float) -> bool:
    return any(abs(math.log(ratio) - s * math.log(u)) < 0.02 for u in UNIT_RATIOS for s in (1, -1))


def _check_radius(t: ThrowFeatures, e: model.Throw, cad: CadInput, engine, engine_file, loadcase) -> None:
    if abs(t.crank_radius - e.crank_radius) <= CRANK_RADIUS_RTOL * e.crank_radius:
        return
    ratio = t.crank_radius / e.crank_radius
    unit = _unit_ratio(ratio)
    hint = (
        f"{ratio:.4g} times the engine's: the file's numbers are in another unit than taken; state it in "
        f"length_unit in {cad.where}"
        if unit
        else "the CAD file is not the shaft of this engine: correct the drawing or the engine"
    )
    raise InputError(
        f"throw {t.name} of the CAD file has a crank radius of {_mm(t.crank_radius)} (stroke "
        f"{_mm(2 * t.crank_radius)}), the engine's throw {e.name} in {engine_file} "
        f"({_engine_key(engine, e.name, 'crank_radius or stroke', engine_file, loadcase)}) one of "
        f"{_mm(e.crank_radius)}; {hint}",
        file=str(cad.file),
        key="cad.length_unit" if unit else cad.file_key,
    )


def _check_angles(f: CadFeatures, cad: CadInput, engine: model.Engine, engine_file: str, loadcase: str) -> None:
    first = f.throws[0]
    e0 = engine.throw(first.name)
    shafts = {engine.throw(t.name).shaft for t in f.throws}
    if len(shafts) > 1:
        raise InputError(
            f"the CAD file's throws are on one crank axis, the engine's {[t.name for t in f.throws]} on the shafts "
            f"{sorted(shafts)} ({engine_file}): give one file per shaft",
            file=str(cad.file),
            key="cad.throws",
        )
    sense = engine.shaft(e0.shaft).sense
    for t in f.throws[1:]:
        e = engine.throw(t.name)
        want = turn_angle(sense * (e.angle - e0.angle))
        off = abs((t.angle - want + math.pi) % (2 * math.pi) - math.pi)
        if off > ANGLE_TOL:
            raise InputError(
                f"throw {t.name} of the CAD file has its crankpin at {math.degrees(t.angle):.6g} deg from throw "
                f"{first.name}'s (turning from +y towards +x, the front the first throw), the engine's at "
                f"{math.degrees(want):.6g} deg ({engine_file}: "
                f"{_engine_key(engine, e.name, 'angle', engine_file, loadcase)} with the shaft's sense "
                f"{sense:+d}); name the file's throws from the front in throws = [...] in {cad.where}, or, when the "
                "file's front is its other end, state axis (front to flywheel)",
                file=str(cad.file),
                key="cad.throws",
            )


def _shaft_position(f: CadFeatures, t: ThrowFeatures) -> float:
    """The throw's crankpin mid-plane along the crank axis (file frame, from the axis point)."""
    return sum((o - p) * e for o, p, e in zip(t.origin, f.axis.point, f.axis.direction, strict=True))


def _check_spacing(f: CadFeatures, cad: CadInput, engine: model.Engine, engine_file: str, loadcase: str) -> None:
    throws = f.throws
    s = [_shaft_position(f, t) for t in throws]
    e = [engine.throw(t.name) for t in throws]
    pitch = [abs(b.axial_position - a.axial_position) for a, b in zip(e, e[1:])]
    scale = max(pitch + [e[0].crank_radius])
    tol = CRANK_RADIUS_RTOL * scale

    def key(name: str) -> str:
        return _engine_key(engine, name, "axial_position", engine_file, loadcase)

    for k in range(len(throws) - 1):
        a, b = throws[k], throws[k + 1]
        drawn, want = s[k + 1] - s[k], e[k + 1].axial_position - e[k].axial_position
        if abs(drawn - want) > tol:
            raise InputError(
                f"throws {a.name} and {b.name} of the CAD file are {_mm(drawn)} apart along the crank axis (front to "
                f"rear), the engine's {_mm(want)} ({engine_file}: {key(b.name)} less {key(a.name)}); the CAD file is "
                "not the shaft of this engine: correct the drawing or the engine",
                file=str(cad.file),
                key=cad.file_key,
            )
        rear, front = a.journals[1], b.journals[0]
        if set(rear.faces) != set(front.faces):
            raise InputError(
                f"the CAD file's throws {a.name} and {b.name} have no main journal between them (throw {a.name}'s "
                f"rear journal is faces {list(rear.faces)}, throw {b.name}'s front journal faces "
                f"{list(front.faces)}): {len(_journals(f))} main journals drawn for {len(throws)} throws, the "
                f"engine's shaft has a main bearing between adjacent throws ({len(throws) + 1} journals)",
                file=str(cad.file),
                key=cad.file_key,
            )
        centre = s[k] + a.bearings[1].z
        plane = s[k] + 0.5 * want
        if abs(centre - plane) > tol:
            raise InputError(
                f"the main bearing between throws {a.name} and {b.name} sits {_mm(0.5 * want)} behind throw "
                f"{a.name}'s crankpin in the engine ({engine_file}: midway between {key(a.name)} and "
                f"{key(b.name)}), the drawn journal's middle {_mm(centre - s[k])}: the CAD file is not the shaft of "
                "this engine",
                file=str(cad.file),
                key=cad.file_key,
            )


def _journals(f: CadFeatures) -> list[tuple[int, ...]]:
    """The distinct main journals of the drawing, front to rear (by their faces)."""
    out: list[tuple[int, ...]] = []
    for t in f.throws:
        for j in t.journals:
            if j.faces not in out:
                out.append(j.faces)
    return out


def engine_keys(
    features: CadFeatures, cad: CadInput, engine: model.Engine, *, engine_file: str, loadcase: str
) -> dict[str, str]:
    """The mesh plan's keys (key -> recognised throw name) after checking the file's
    throws against the engine's (module docstring); ``engine_file``: the file the
    engine was read from, ``loadcase``: the load case's (for the messages' keys)."""
    names = [t.name for t in features.throws]
    eng = [t.name for t in engine.throws]
    if len(names) == 1:
        for e in engine.throws:
            _check_radius(features.throws[0], e, cad, engine, engine_file, loadcase)
        return {names[0] if eng == names else ALL_THROWS: names[0]}
    if sorted(names) != sorted(eng):
        raise InputError(
            f"the CAD file holds {len(names)} throws, named {names} from the front, the engine {len(eng)}, "
            f"named {eng} ({engine_file}); name the file's throws after the engine's in throws = [...] in "
            f"{cad.where} (or give a file of one throw that stands for all)",
            file=str(cad.file),
            key="cad.throws",
        )
    for t in features.throws:
        _check_radius(t, engine.throw(t.name), cad, engine, engine_file, loadcase)
    _check_angles(features, cad, engine, engine_file, loadcase)
    _check_spacing(features, cad, engine, engine_file, loadcase)
    return {n: n for n in eng}
