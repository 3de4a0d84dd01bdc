"""Recognise a crankshaft's features in a CAD file: :func:`recognise` -> ``CadFeatures``.

Steps (each in its module): read the file into gmsh in metres (``read``), fit every
face (``survey``), find the crank axis (``axis``) and the throws with their pins,
fillets, webs, journals and oil bores (``shaft``, ``chains``), then per throw
(``throw``): its frame, the webs' widths and counterweight radii, the counterweight
fillets, the model of named parts between the bearing centres and its mass properties.

Tolerance: ``TOL_REL`` times the diagonal of the shaft's bounding box, the largest
deviation of a face from its fitted surface, of two axes from being one, of two radii
from being equal (3e-7 m on a 0.3 m throw; CAD files are exact to ~1e-7 m).

A plausibility bound on size (``check_size``) refuses a shaft whose unit is off (a
shaft in millimetres read as inches is 25.4 times too large).
"""

from __future__ import annotations

import dataclasses
from collections import OrderedDict
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fe_crank.cad.axis import Line, find_axis, line_of
from fe_crank.cad.config import CadInput
from fe_crank.cad.ends import shaft_ends
from fe_crank.cad.features import BoltedBody, BoltHole, CadFeatures, CadSource, CrankAxis
from fe_crank.cad.frame import Frame
from fe_crank.cad.model import throw_mass
from fe_crank.cad.read import ReadResult, file_digest, read_cad
from fe_crank.cad.shaft import RawThrow, find_throws
from fe_crank.cad.survey import Face, coverage, neighbours, survey
from fe_crank.cad.throw import throw_features
from fe_crank.errors import InputError

TOL_REL = 1e-6
#: plausible sizes of a reciprocating engine's crankshaft (m), from model engines to the
#: largest two-stroke crosshead engines: journal and pin diameters, crank radius
DIAMETER_RANGE = (0.008, 1.3)
CRANK_RADIUS_RANGE = (0.005, 2.0)
_FORMATS = {"step": "STEP", "brep": "BREP", "iges": "IGES"}


def check_size(cad: CadInput, throws: tuple[RawThrow, ...], unit_text: str) -> None:
    """Refuse a shaft whose journals, pins or crank radius are out of any engine's range."""
    for t in throws:
        sizes = [
            ("main journal diameter", 2 * t.journals[0].radius, DIAMETER_RANGE),
            ("crankpin diameter", 2 * t.pin_radius, DIAMETER_RANGE),
            ("crank radius", t.crank_radius, CRANK_RADIUS_RANGE),
        ]
        for what, v, (lo, hi) in sizes:
            if not lo <= v <= hi:
                raise InputError(
                    f"throw {t.name}: the {what} comes out as {v * 1e3:.5g} mm, outside the range of crankshafts "
                    f"({lo * 1e3:g} to {hi * 1e3:g} mm), with the file's numbers taken in {unit_text}; if that unit "
                    f"is wrong, state the right one in length_unit in {cad.where}",
                    file=str(cad.file),
                    key="cad.length_unit",
                )


@dataclass(frozen=True, eq=False)
class Prepared:
    """Internal: the file read and its throws recognised, in the current gmsh model."""

    read: ReadResult
    tol: float
    faces: dict[int, Face]
    nbrs: dict[int, set[int]]
    axis: Line
    axis_faces: tuple[int, ...]
    raw: tuple[RawThrow, ...]

    def index(self, throw: str | int | None) -> int:
        """0-based index of a throw given by name, index or None (the first)."""
        if throw is None:
            return 0
        if isinstance(throw, int):
            if not 0 <= throw < len(self.raw):
                raise KeyError(f"throw index {throw} out of range (0..{len(self.raw) - 1})")
            return throw
        for i, t in enumerate(self.raw):
            if t.name == throw:
                return i
        raise KeyError(f"no throw named {throw!r}; throws are {[t.name for t in self.raw]}")


def prepare(gmsh, cad: CadInput) -> Prepared:
    """Read the file into the current model and recognise its axis and throws."""
    read = read_cad(gmsh, cad)
    x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(3, read.shaft)
    tol = TOL_REL * float(np.linalg.norm([x1 - x0, y1 - y0, z1 - z0]))
    tags = [abs(t) for _, t in gmsh.model.getBoundary([(3, read.shaft)], combined=False, oriented=False)]
    faces = survey(gmsh, sorted(set(tags)), tol)
    nbrs = neighbours(faces)
    axis, axis_faces = find_axis(faces, cad, tol)
    raw = find_throws(
        faces, nbrs, axis, cad, tol, lambda q: bool(gmsh.model.isInside(3, read.shaft, [float(c) for c in q]))
    )
    unit_text = f"{read.unit.name} (stated by {'the file' if read.unit.stated_by == 'file' else 'length_unit'})"
    check_size(cad, raw, unit_text)
    return Prepared(read, tol, faces, nbrs, axis, axis_faces, raw)


def _bolted(gmsh, body: int, p: Prepared, density: float) -> BoltedBody:
    """A bolted body's mass properties in the frame of the throw it sits on: the one whose
    bearing centres enclose its centroid, or the nearest."""
    s = float((np.asarray(gmsh.model.occ.getCenterOfMass(3, body)) - p.axis.origin) @ p.axis.e)

    def distance(t: RawThrow) -> float:
        lo, hi = sorted((t.journals[0].centre, t.journals[1].centre))
        return 0.0 if lo <= s <= hi else min(abs(s - lo), abs(s - hi))

    t = min(p.raw, key=distance)
    frame = Frame.of(p.axis.origin, p.axis.e, t.u, t.mid)
    props = throw_mass(gmsh, {"body": [body]}, density, frame, t.name).total
    return BoltedBody(t.name, 1 if props.centroid[2] < 0 else 2, props, _bolt_holes(gmsh, body, frame, p.tol))


def _bolt_holes(gmsh, body: int, frame: Frame, tol: float) -> tuple[BoltHole, ...]:
    """The whole-round holes through a bolted body (coaxial faces of one radius: one hole)."""
    tags = sorted({abs(t) for _, t in gmsh.model.getBoundary([(3, body)], combined=False, oriented=False)})
    faces = survey(gmsh, tags, tol)
    bores = [
        f
        for f in faces.values()
        if f.kind == "cylinder" and not f.convex and coverage(f.edge_runs, f.origin, f.direction) >= 0.99
    ]
    groups: list[list[Face]] = []
    for f in bores:
        for g in groups:
            if line_of(g[0]).same(line_of(f), tol) and abs(g[0].radius - f.radius) <= tol:
                g.append(f)
                break
        else:
            groups.append([f])
    out = []
    for g in groups:
        d = frame.direction(g[0].direction)
        d = d if d @ np.array([1.0, 1.0, 1.0]) >= 0 else -d
        q = frame.to_throw(g[0].origin)[0]
        ez = np.array([0.0, 0.0, 1.0])
        n = np.cross(d, ez)
        if np.linalg.norm(n) > 1e-9:  # the point of the hole's axis nearest the crank axis
            q = q + (np.cross(-q, ez) @ n / (n @ n)) * d
        else:  # parallel to the crank axis: its point in the web's plane
            q = q - q[2] * d
        point = (float(q[0]), float(q[1]), float(q[2]))
        direction = (float(d[0]), float(d[1]), float(d[2]))
        tags_g = tuple(sorted(f.tag for f in g))
        out.append(BoltHole(tags_g, float(2 * g[0].radius), point, direction, float(np.hypot(q[0], q[1]))))
    return tuple(sorted(out, key=lambda h: (h.point[0], h.point[1])))


#: the last features recognised in this process, by what they depend on (``_memo_key``):
#: the same file with the same keys is recognised once (``validate`` and then the check
#: of one load case; the load cases of a batch on one drawing)
_RECOGNISED: OrderedDict[tuple, CadFeatures] = OrderedDict()
MEMO_SIZE = 8


def _memo_key(cad: CadInput, sha256: str) -> tuple | None:
    """What recognition depends on: the file's bytes (their SHA-256), its name (the
    features' ``source.file``) and every ``[cad]`` key but those that only name places in
    messages (the file's folder, the TOML file, the key naming the file) or that the
    whole-shaft stage reads after recognition (``bearing_width``, ``[cad.shaft]``:
    ``whole.bearing_spec``).  None when a key's value is not hashable (no memo)."""
    plain = dataclasses.replace(cad, file=Path(cad.file.name), toml="", file_key="", bearing_width=None, shaft=None)
    try:
        hash(plain)
    except TypeError:
        return None
    return (sha256, plain)


def recognise(cad: CadInput) -> CadFeatures:
    """Read ``cad.file`` and recognise every throw (see the module docstring).  A file
    recognised before in this process with the same bytes and keys (``_memo_key``) gives
    the same features without being read again.

    Raises ``InputError`` naming the file, the key that settles it and the reason when
    the file cannot be read or a feature cannot be recognised."""
    key = _memo_key(cad, file_digest(cad))  # the checks read_cad makes first
    if key is not None and key in _RECOGNISED:
        _RECOGNISED.move_to_end(key)
        return _RECOGNISED[key]
    features = _recognise(cad)
    if key is not None:
        _RECOGNISED[key] = features
        while len(_RECOGNISED) > MEMO_SIZE:
            _RECOGNISED.popitem(last=False)
    return features


def _recognise(cad: CadInput) -> CadFeatures:
    from fe_crank.gmsh_io import gmsh_session

    with gmsh_session() as gmsh:
        p = prepare(gmsh, cad)
        bolted = tuple(_bolted(gmsh, b, p, cad.density) for b in p.read.bolted)  # before the throws drop them
        ends = shaft_ends(gmsh, p, cad.density)
        throws = tuple(
            throw_features(gmsh, p.read.shaft, p.faces, p.nbrs, p.axis, p.raw, i, cad, p.tol)[0]
            for i in range(len(p.raw))
        )
    source = CadSource(
        file=cad.file.name,
        sha256=p.read.sha256,
        format=_FORMATS[p.read.kind],
        unit=p.read.unit,
        solids=p.read.solids,
        bodies=cad.bodies,
        density=cad.density,
        material=cad.material,
    )
    ox, oy, oz = (float(v) for v in p.axis.origin)
    ex, ey, ez = (float(v) for v in p.axis.e)
    crank_axis = CrankAxis((ox, oy, oz), (ex, ey, ez), tuple(int(t) for t in p.axis_faces))
    return CadFeatures(source, crank_axis, throws, bolted, ends)
