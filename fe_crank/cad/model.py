"""One throw of the recognised shaft as a model of named parts, in its THROW frame.

A copy of the shaft is moved into the throw's frame (``fe_crank.cad.frame``), cut at
the main-bearing centre planes (not where a journal ends in the shaft's free end face:
that face is the centre) and split, as the parametric throw is
(``fe_crank.geometry.throw``), by planes at the webs' faces into ``journal_1``,
``web_1``, ``crankpin``, ``web_2``, ``journal_2`` (fillets go with the pin or journal
they round); the material on the far side of the axis (``y < 0``) farther than a web's
counterweight radius, between its bearing centre and ``z = 0``, is ``counterweight_<web>``
(absent when there is none); where its transition fillets rise over ``y = 0`` (a
counterweight of 180 degrees), the region reaches up over them.

Outer faces are named by the recognised feature of the file's face they lie on: their
sample points, taken back to the file's frame, lie on that face (closest-point distance
within ``tol``, inside its trimmed boundary).  The cut faces at the bearing centres (or
the free end faces there) are ``end_1``/``end_2``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.cad.frame import Frame
from fe_crank.cad.survey import _samples
from fe_crank.errors import InputError

BIG = 10.0  # m: tools larger than any crank


@dataclass(frozen=True, eq=False)
class Plan:
    """Internal: where to cut and split one throw (throw frame, m)."""

    name: str
    bearings: tuple[float, float]  # z of the bearing centres
    free: tuple[bool, bool]  # the end there is the shaft's free end face
    webs: tuple[float, float, float, float]  # z of web 1 outer, web 1 inner, web 2 inner, web 2 outer
    cw_radius: tuple[float, float]  # counterweight radius per web
    cw_top: tuple[float, float]  # the counterweight's region is y < cw_top (>= 0: over its fillets)
    groups: dict[int, str]  # file face -> group name


@dataclass(frozen=True, eq=False)
class Built:
    """Internal: the gmsh tags of the built throw."""

    volumes: dict[str, list[int]]
    surfaces: dict[str, list[int]]


def _slab(occ, z0: float, z1: float) -> int:
    return occ.addBox(-BIG, -BIG, z0, 2 * BIG, 2 * BIG, z1 - z0)


def _cw_tool(occ, web: int, r: float, top: float) -> int:
    z0, z1 = (-BIG, 0.0) if web == 1 else (0.0, BIG)
    box = occ.addBox(-BIG, -BIG, z0, 2 * BIG, BIG + top, z1 - z0)
    cyl = occ.addCylinder(0.0, 0.0, z0, 0.0, 0.0, z1 - z0, r)
    out, _ = occ.cut([(3, box)], [(3, cyl)])
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
    flat = pts.ravel().tolist()
    closest, uv = gmsh.model.getClosestPoint(2, face, flat)
    d = np.linalg.norm(np.asarray(closest).reshape(-1, 3) - pts, axis=1)
    if np.max(d) > tol:
        return False
    uv = np.asarray(uv).reshape(-1, 2)
    return sum(_in_face(gmsh, face, q) for q in uv) >= 0.8 * len(uv)


def build_throw(gmsh, shaft: int, frame: Frame, plan: Plan, tol: float, file: str) -> Built:
    """Build the throw's named parts in the current model (the shaft stays as it is)."""
    occ = gmsh.model.occ
    (copy,) = occ.copy([(3, shaft)])
    frame.move(occ, [copy])
    z1 = -BIG if plan.free[0] else plan.bearings[0]
    z2 = BIG if plan.free[1] else plan.bearings[1]
    out, _ = occ.intersect([copy], [(3, _slab(occ, z1, z2))])
    occ.synchronize()
    if len(out) != 1:
        raise InputError(
            f"throw {plan.name}: cut at its main-bearing centres the shaft falls into {len(out)} pieces",
            file=file,
            key="cad.faces",
        )
    solid = out[0][1]
    zo1, zi1, zi2, zo2 = plan.webs
    tools = [_slab(occ, -BIG, zo1), _slab(occ, zo1, zi1), _slab(occ, zi1, zi2), _slab(occ, zi2, zo2)]
    cw = [(web, _cw_tool(occ, web, plan.cw_radius[web - 1], plan.cw_top[web - 1])) for web in (1, 2)]
    _, out_map = occ.fragment([(3, solid)], [(3, t) for t in tools] + [(3, t) for _, t in cw])
    occ.synchronize()
    keep = {t for d, t in out_map[0] if d == 3}
    occ.remove([(3, t) for _, t in gmsh.model.getEntities(3) if t not in keep and t != shaft], recursive=True)
    occ.synchronize()

    volumes: dict[str, list[int]] = {k: [] for k in ("journal_1", "web_1", "crankpin", "web_2", "journal_2")}
    for i, (web, _) in enumerate(cw):
        pieces = sorted({t for d, t in out_map[1 + len(tools) + i] if d == 3} & keep)
        if pieces and sum(occ.getMass(3, t) for t in pieces) > 0:
            volumes[f"counterweight_{web}"] = pieces
    in_cw = {t for k, v in volumes.items() if k.startswith("counterweight") for t in v}
    for t in sorted(keep - in_cw):
        z = occ.getCenterOfMass(3, t)[2]
        name = "journal_1" if z < zo1 else "web_1" if z < zi1 else "crankpin" if z <= zi2 else "web_2"
        volumes[name if z <= zo2 else "journal_2"].append(t)
    for name, tags in volumes.items():
        if not tags:
            raise InputError(f"throw {plan.name}: splitting the throw left no {name}", file=file, key="cad.faces")
    surfaces = _name_faces(gmsh, keep, frame, plan, tol)
    return Built(volumes, surfaces)


def _name_faces(gmsh, keep: set[int], frame: Frame, plan: Plan, tol: float) -> dict[str, list[int]]:
    out: dict[str, list[int]] = {}
    for s in _outer_faces(gmsh, keep):
        if gmsh.model.getType(2, s) == "Plane":
            x0, y0, za, x1, y1, zb = gmsh.model.getBoundingBox(2, s)
            end = [k for k, zc in enumerate(plan.bearings) if abs(za - zc) <= 2 * tol and abs(zb - zc) <= 2 * tol]
            if end:
                out.setdefault(f"end_{end[0] + 1}", []).append(s)
                continue
        _, pts = _samples(gmsh, s)
        if len(pts) == 0:
            continue
        back = frame.to_file(pts)
        for face, group in plan.groups.items():
            if _on_face(gmsh, face, back, tol):
                out.setdefault(group, []).append(s)
                break
    return out
