"""One throw of the recognised shaft as a model of named parts (in the file's frame).

A copy of the shaft is cut at the main-bearing centre planes (not where a journal ends
in the shaft's free end face: that face is the centre) and split, as the parametric
throw is (``fe_crank.geometry.throw``), by planes at the webs' faces into
``journal_1``, ``web_1``, ``crankpin``, ``web_2``, ``journal_2`` (fillets go with the
pin or journal they round); the material on the far side of the axis (``y < 0`` in the
throw frame) farther than a web's counterweight radius, between its bearing centre and
``z = 0``, is ``counterweight_<web>`` (absent when there is none); where its transition
fillets rise over ``y = 0`` (a counterweight of 180 degrees), the region reaches over
them; a counterweight recognised by its own sector (``cad.throw``) has that outline
(``Plan.cw_outline``) in place of the half plane.  The tools are prisms normal to the crank axis (``Frame.prism``), whose faces lie
on the web faces to the last bit when the axis runs along a coordinate axis of the file
(OpenCASCADE does not split along a plane tangent to a fillet that is off by round-off).

Outer faces are named by the recognised feature of the file's face they lie on: their
sample points lie on that face (closest-point distance within ``tol``, inside its
trimmed boundary).  The cut faces at the bearing centres (or the free end faces there)
are ``end_1``/``end_2``.  Mass properties are integrated on the B-rep and expressed in
the throw frame.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.cad.frame import Frame
from fe_crank.cad.survey import face_samples
from fe_crank.errors import InputError

BIG = 10.0  # m: tools larger than any crank
_SQUARE = ((-BIG, -BIG), (BIG, -BIG), (BIG, BIG), (-BIG, BIG))


@dataclass(frozen=True, eq=False)
class Plan:
    """Internal: where to cut and split one throw (shaft positions s along the axis, m)."""

    name: str
    mid: float  # the throw frame's origin
    bearings: tuple[float, float]  # the bearing centres
    free: tuple[bool, bool]  # the end there is the shaft's free end face
    webs: tuple[float, float, float, float]  # web 1 outer, web 1 inner, web 2 inner, web 2 outer
    cw_radius: tuple[float, float]  # counterweight radius per web
    cw_top: tuple[float, float]  # the counterweight's region is y < cw_top (throw frame, >= 0)
    groups: dict[int, str]  # file face -> group name
    # per web: the counterweight region's outline (x, y of the throw frame) in place of the
    # half plane y < cw_top, for one recognised by its own sector (cad.throw); None: the half plane
    cw_outline: tuple[tuple[tuple[float, float], ...] | None, tuple[tuple[float, float], ...] | None] = (None, None)


@dataclass(frozen=True, eq=False)
class Built:
    """Internal: the gmsh tags of the built throw."""

    volumes: dict[str, list[int]]
    surfaces: dict[str, list[int]]


def _cw_tool(occ, frame: Frame, origin, web: int, r: float, top: float, span: tuple[float, float], outline=None) -> int:
    s0, s1 = span
    corners = outline if outline is not None else ((-BIG, -BIG), (BIG, -BIG), (BIG, top), (-BIG, top))
    half = frame.prism(occ, corners, s0, s1, origin)
    base = origin + s0 * frame.rotation[2]
    cyl = occ.addCylinder(*map(float, base), *map(float, (s1 - s0) * frame.rotation[2]), r)
    out, _ = occ.cut([(3, half)], [(3, cyl)])
    return out[0][1]


def _outer_faces(gmsh, volumes) -> list[int]:
    count: dict[int, int] = {}
    for v in volumes:
        for _, s in gmsh.model.getBoundary([(3, v)], oriented=False, combined=False):
            count[abs(s)] = count.get(abs(s), 0) + 1
    return sorted(s for s, n in count.items() if n == 1)


_SHIFTS = [(0.0, 0.0)] + [(a, b) for a in (0.0, 2 * np.pi, -2 * np.pi) for b in (0.0, 2 * np.pi, -2 * np.pi)][1:]


def _in_face(gmsh, face: int, uv) -> bool:
    """Is the parameter pair on the trimmed face?  A periodic surface's parameters come
    back from a projection in any period, the face's boundary lies in one: each is tried."""
    return any(gmsh.model.isInside(2, face, [float(uv[0] + a), float(uv[1] + b)], parametric=True) for a, b in _SHIFTS)


def _on_face(gmsh, face: int, pts: np.ndarray, tol: float) -> bool:
    closest, uv = gmsh.model.getClosestPoint(2, face, pts.ravel().tolist())
    d = np.linalg.norm(np.asarray(closest).reshape(-1, 3) - pts, axis=1)
    if np.max(d) > tol:
        return False
    uv = np.asarray(uv).reshape(-1, 2)
    return sum(_in_face(gmsh, face, q) for q in uv) >= 0.8 * len(uv)


@dataclass(frozen=True)
class EndSlab:
    """Internal: the round bar of the journal at an end of the throw model that is drawn
    anew (``build_throw``'s ``ends``): its radius and its length from the bearing centre."""

    radius: float
    length: float


def _seam_at_y(gmsh, occ, vol: int, frame: Frame, base: np.ndarray) -> None:
    """Turn the new cylinder ``vol`` about the crank axis so that its seam (the one vertex
    of each circle) lies on the throw frame's +y."""
    x, y, e = frame.rotation
    (vertex, *_) = [t for d, t in gmsh.model.getBoundary([(3, vol)], recursive=True) if d == 0]
    p = np.asarray(occ.getBoundingBox(0, vertex)[:3]) - base
    a = float(np.arctan2(p @ x, p @ y))  # from +y towards +x
    if a != 0.0:
        # a turn by -a about e, right-handed, takes the angle from +y towards +x back by a
        occ.rotate([(3, vol)], *map(float, base), *map(float, e), a)


def redraw_ends(gmsh, piece, frame: Frame, origin, plan: Plan, ends: tuple[EndSlab, EndSlab], file: str):
    """The piece with the journal at each end, from its bearing centre inwards over the
    slab's length, replaced by a new round bar of the same radius whose seam lies on the
    throw frame's +y, so that the end face is a disc with one rim vertex at the same place
    on every throw (``mesh.interface.imprint_sectors`` splits it into equal sectors; the
    file's own seams and edges there fall where they were drawn).  The slab must be the
    whole round bar in the drawing (its volume that of the cylinder, to 1e-9): a bore,
    flat or groove there is refused rather than drawn over."""
    occ = gmsh.model.occ
    out = piece
    for k, (s, sign) in enumerate(((plan.bearings[0], 1.0), (plan.bearings[1], -1.0))):
        slab = ends[k]
        s0, s1 = sorted((s, s + sign * slab.length))
        want = np.pi * slab.radius**2 * slab.length
        (probe,) = occ.copy(out)
        base = origin + s0 * frame.rotation[2]
        bar = occ.addCylinder(*map(float, base), *map(float, (s1 - s0) * frame.rotation[2]), slab.radius)
        inside, _ = occ.intersect([probe], [(3, bar)])
        occ.synchronize()
        have = sum(occ.getMass(d, t) for d, t in inside if d == 3)
        occ.remove(inside, recursive=True)
        (probe,) = occ.copy(out)
        box = frame.prism(occ, _SQUARE, s0, s1, origin)
        region, _ = occ.intersect([probe], [(3, box)])
        occ.synchronize()
        total = sum(occ.getMass(d, t) for d, t in region if d == 3)
        occ.remove(region, recursive=True)
        if abs(have - want) > 1e-9 * want or abs(total - want) > 1e-9 * want:
            raise InputError(
                f"throw {plan.name}: the main journal at its {'front' if k == 0 else 'rear'} bearing centre is not a "
                f"plain round bar of {2e3 * slab.radius:.6g} mm within {slab.length * 1e3:.4g} mm of that centre "
                f"(material there {total:.6g} m^3, of it within the journal's radius {have:.6g} m^3, the bar's "
                f"{want:.6g} m^3): the whole-shaft model joins its throws on round end faces at the bearing centres",
                file=file,
                key="cad.file",
            )
        cut, _ = occ.cut(out, [(3, frame.prism(occ, _SQUARE, s0, s1, origin))])
        new = occ.addCylinder(*map(float, base), *map(float, (s1 - s0) * frame.rotation[2]), slab.radius)
        occ.synchronize()
        _seam_at_y(gmsh, occ, new, frame, base)
        out, _ = occ.fuse(cut, [(3, new)])
        occ.synchronize()
        if len(out) != 1:
            raise InputError(
                f"throw {plan.name}: its journal redrawn at a bearing centre the piece is {len(out)} solids",
                file=file,
                key="cad.file",
            )
    return out


def build_throw(
    gmsh,
    shaft: int,
    frame: Frame,
    origin: np.ndarray,
    plan: Plan,
    tol: float,
    file: str,
    ends: tuple[EndSlab, EndSlab] | None = None,
    half: bool = False,
) -> Built:
    """Build the throw's named parts in the current model (the shaft stays as it is).
    ``origin``: the crank axis's point of shaft position 0; ``ends``: redraw the journal
    at both bearing centres (``redraw_ends``, for end faces that join the neighbours);
    ``half``: only the front half, ``z <= 0`` of the throw frame (a throw that is its own
    mirror image across ``z = 0``, meshed as its half and mirrored: ``cad.mesh``)."""
    occ = gmsh.model.occ
    (copy,) = occ.copy([(3, shaft)])
    b1 = -BIG if plan.free[0] else plan.bearings[0]
    b2 = BIG if plan.free[1] else plan.bearings[1]
    out, _ = occ.intersect([copy], [(3, frame.prism(occ, _SQUARE, b1, b2, origin))])
    occ.synchronize()
    if len(out) != 1:
        raise InputError(
            f"throw {plan.name}: cut at its main-bearing centres the shaft falls into {len(out)} pieces",
            file=file,
            key="cad.faces",
        )
    if ends is not None:
        out = redraw_ends(gmsh, out, frame, origin, plan, ends, file)
    if half:
        out, _ = occ.intersect(out, [(3, frame.prism(occ, _SQUARE, -BIG, plan.mid, origin))])
        occ.synchronize()
    so1, si1, si2, so2 = plan.webs
    slabs = [(-BIG, so1), (so1, si1), (si1, si2), (si2, so2)]
    tools = [frame.prism(occ, _SQUARE, a, b, origin) for a, b in slabs]
    spans = ((-BIG, plan.mid), (plan.mid, BIG))
    cw = [
        (
            web,
            _cw_tool(
                occ,
                frame,
                origin,
                web,
                plan.cw_radius[web - 1],
                plan.cw_top[web - 1],
                spans[web - 1],
                plan.cw_outline[web - 1],
            ),
        )
        for web in (1, 2)
    ]
    _, out_map = occ.fragment(out, [(3, t) for t in tools] + [(3, t) for _, t in cw])
    occ.synchronize()
    keep = {t for d, t in out_map[0] if d == 3}
    occ.remove([(3, t) for _, t in gmsh.model.getEntities(3) if t not in keep and t != shaft], recursive=True)
    occ.synchronize()

    volumes: dict[str, list[int]] = {k: [] for k in ("journal_1", "web_1", "crankpin", "web_2", "journal_2")}
    for i, (web, _) in enumerate(cw):
        pieces = sorted({t for d, t in out_map[1 + len(tools) + i] if d == 3} & keep)
        if pieces:
            volumes[f"counterweight_{web}"] = pieces
    in_cw = {t for k, v in volumes.items() if k.startswith("counterweight") for t in v}
    for t in sorted(keep - in_cw):
        s = float((np.asarray(occ.getCenterOfMass(3, t)) - origin) @ frame.rotation[2])
        name = "journal_1" if s < so1 else "web_1" if s < si1 else "crankpin" if s <= si2 else "web_2"
        volumes[name if s <= so2 else "journal_2"].append(t)
    for name, tags in volumes.items():
        if not tags and not (half and name.endswith("_2")):
            raise InputError(
                f"throw {plan.name}: splitting the throw at its web faces left no {name} (OpenCASCADE cuts "
                "exactly only along a crank axis that runs along a coordinate axis of the file: export it so)",
                file=file,
                key="cad.file",
            )
    surfaces = _name_faces(gmsh, keep, frame, origin, plan, tol)
    return Built({k: v for k, v in volumes.items() if v}, surfaces)


def _name_faces(gmsh, keep: set[int], frame: Frame, origin, plan: Plan, tol: float) -> dict[str, list[int]]:
    out: dict[str, list[int]] = {}
    for s in _outer_faces(gmsh, keep):
        _, pts = face_samples(gmsh, s)
        if len(pts) == 0:
            continue
        if gmsh.model.getType(2, s) == "Plane":
            pos = (pts - origin) @ frame.rotation[2]
            end = [k for k, b in enumerate(plan.bearings) if np.all(np.abs(pos - b) <= 2 * tol)]
            if end:
                out.setdefault(f"end_{end[0] + 1}", []).append(s)
                continue
        for face, group in plan.groups.items():
            if _on_face(gmsh, face, pts, tol):
                out.setdefault(group, []).append(s)
                break
    return out


def throw_mass(gmsh, volumes: dict[str, list[int]], density: float, frame: Frame, name: str):
    """``MassProperties`` of the named volumes in the throw frame (``fe_crank.geometry.mass``:
    exact B-rep integrals; centroid ``R (c - o)``, inertia ``R J R^T``)."""
    from fe_crank.geometry.mass import MassProperties, combine_volumes

    occ = gmsh.model.occ
    R = frame.rotation
    per = {}
    for tags in volumes.values():
        for v in tags:
            c = R @ (np.asarray(occ.getCenterOfMass(3, v)) - frame.origin)
            J = np.asarray(occ.getMatrixOfInertia(3, v)).reshape(3, 3)
            per[v] = (occ.getMass(3, v), c, R @ J @ R.T)
    parts = {k: combine_volumes([per[v] for v in tags], density) for k, tags in volumes.items()}
    return MassProperties(throw=name, density=density, total=combine_volumes(list(per.values()), density), parts=parts)
