"""What lies at the end of a crankpin or journal: the fillet and the web face.

From the cylinder's faces, :func:`walk` steps to the neighbouring faces that lie wholly
beyond the cylinder's end (along the crank axis, within ``tol``) and goes on through
fillet faces -- tori coaxial with the cylinder (rolling-ball fillets of the circular
edge, single or compound), or blends of another surface type -- until it reaches planes
normal to the crank axis: the web face.  The fillet's radius is the smallest radius of
curvature of its faces; its undercut the depth it reaches beyond the web face into the
web (0 for a fillet tangent to the face).  Anything else at the end (a cone, a
cylinder, a face that never leads to a web face) is reported with its face numbers.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.cad.axis import ANGLE_TOL, Line, line_of
from fe_crank.cad.survey import Face


@dataclass(frozen=True, eq=False)
class End:
    """Internal: the fillet and web face found at one end of a cylinder (shaft positions s)."""

    fillet: tuple[Face, ...]  # fillet faces, from the cylinder outwards
    planes: tuple[Face, ...]  # the web face(s) reached (normal to the axis)
    s_plane: float  # position of the web face along the crank axis
    stray: tuple[int, ...] = ()  # faces at the end that are neither fillet nor web face

    @property
    def ok(self) -> bool:
        return bool(self.planes) and not self.stray

    def radius(self) -> float:
        return min((f.min_radius for f in self.fillet), default=0.0)

    def undercut(self, axis: Line, sign: float, tol: float) -> float:
        """Depth of the fillet beyond the web face, into the web (``sign`` -1: the end
        looks towards smaller s); 0 within ``tol``.  A torus that dips below the face
        reaches its spine plane's distance less its tube radius (exact); other faces
        by their sample points."""
        if not self.fillet:
            return 0.0
        depth = 0.0
        for f in self.fillet:
            sampled = float(np.max(sign * (f.axial(axis.origin, axis.e) - self.s_plane)))
            if sampled > tol and f.kind == "torus":
                spine = float((f.origin - axis.origin) @ axis.e)
                sampled = max(sampled, sign * (spine - self.s_plane) + f.minor)
            depth = max(depth, sampled)
        return depth if depth > tol else 0.0


def normal_plane(f: Face, axis: Line) -> bool:
    return f.kind == "plane" and abs(abs(f.direction @ axis.e) - 1.0) <= ANGLE_TOL


def extent(faces, axis: Line) -> tuple[float, float]:
    s = np.concatenate([f.axial(axis.origin, axis.e) for f in faces])
    return float(s.min()), float(s.max())


def walk(
    start: list[Face],
    sign: float,
    line: Line,
    axis: Line,
    faces: dict[int, Face],
    nbrs: dict[int, set[int]],
    tol: float,
) -> End:
    """The end of the cylinder ``start`` (faces about ``line``) towards ``sign`` (-1:
    smaller s, the front; +1: the rear)."""
    lo, hi = extent(start, axis)
    end = lo if sign < 0 else hi
    seen = {f.tag for f in start}
    frontier = list(start)
    fillet: list[Face] = []
    planes: list[Face] = []
    stray: list[int] = []
    while frontier:
        nxt = []
        for f in frontier:
            for t in sorted(nbrs[f.tag] - seen):
                g = faces[t]
                a, b = extent([g], axis)
                beyond = (b <= end + tol) if sign < 0 else (a >= end - tol)
                if not beyond:
                    continue
                seen.add(t)
                if normal_plane(g, axis):
                    planes.append(g)
                elif (g.kind == "torus" and Line(g.origin, g.direction).same(line, tol)) or g.kind == "other":
                    fillet.append(g)
                    nxt.append(g)
                else:
                    stray.append(t)
        frontier = nxt
    if not planes:
        return End(tuple(fillet), (), float("nan"), tuple(stray))
    s_planes = [float(np.median(p.axial(axis.origin, axis.e))) for p in planes]  # exact on an axis-aligned plane
    # the web face is the nearest plane: farther ones reached through a blend are not it
    s0 = min(s_planes, key=lambda s: abs(s - end))
    web = tuple(p for p, s in zip(planes, s_planes) if abs(s - s0) <= tol)
    return End(tuple(fillet), web, s0, tuple(stray))


def cylinder_groups(cands: list[Face], tol: float) -> list[list[Face]]:
    """Cylinders grouped by common axis and equal radius."""
    groups: list[list[Face]] = []
    for f in cands:
        for g in groups:
            if abs(g[0].radius - f.radius) <= tol and line_of(g[0]).same(line_of(f), tol):
                g.append(f)
                break
        else:
            groups.append([f])
    return groups


def contiguous(group: list[Face], axis: Line, tol: float) -> list[list[Face]]:
    """A group of coaxial cylinders of one radius split where it is interrupted along the axis."""
    items = sorted(group, key=lambda f: extent([f], axis)[0])
    out: list[list[Face]] = []
    top = -np.inf
    for f in items:
        a, b = extent([f], axis)
        if out and a <= top + tol:
            out[-1].append(f)
        else:
            out.append([f])
        top = max(top, b)
    return out
