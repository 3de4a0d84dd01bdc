"""The THROW frame of a recognised throw in the file's frame, and chords of the solid.

``z`` along the crank axis (front to rear), ``y`` from the axis towards the crankpin's
centre, ``x = y x z`` (right-handed: the direction the pin moves in the positive
sense of rotation), origin on the axis midway between the webs' inner faces;
``p_throw = R (p_file - o)`` with the rows of ``R`` the frame's x, y, z axes.

The frame's products are written out term by term (``turn``), not left to a BLAS
kernel, whose order of summation, and so whose last bits, depends on the processor:
from the same fitted axes the same frame places the same cuts on every machine.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: an angle within this of 0 or of a full period is 0 (round-off of atan2 on fitted
#: directions: a pin at -1e-17 rad is at 0, not at 360 deg)
ANGLE_SNAP = 1e-9  # rad


def turn_angle(a: float, period: float = 2 * math.pi) -> float:
    """``a`` in ``[0, period)``; a value within ``ANGLE_SNAP`` of 0 or of ``period`` is 0."""
    a = float(a) % period
    return 0.0 if a <= ANGLE_SNAP or period - a <= ANGLE_SNAP else a


def turn(m: np.ndarray, p: np.ndarray) -> np.ndarray:
    """``p @ m.T`` for points ``p`` (n, 3) or (3,) and a 3 x 3 ``m``, summed in a fixed order."""
    p = np.asarray(p, dtype=float)
    return p[..., 0, None] * m[:, 0] + p[..., 1, None] * m[:, 1] + p[..., 2, None] * m[:, 2]


@dataclass(frozen=True, eq=False)
class Frame:
    origin: np.ndarray  # (3,) file frame
    rotation: np.ndarray  # (3, 3), rows x, y, z

    @classmethod
    def of(cls, axis_origin: np.ndarray, e: np.ndarray, u: np.ndarray, s_mid: float) -> Frame:
        y = u - float(turn(e[None, :], u)[0]) * e
        y = y / math.sqrt(math.fsum(float(c) * float(c) for c in y))
        x = np.cross(y, e)
        return cls(axis_origin + s_mid * e, np.vstack([x, y, e]))

    def to_throw(self, p: np.ndarray) -> np.ndarray:
        return turn(self.rotation, np.atleast_2d(p) - self.origin)

    def to_file(self, q: np.ndarray) -> np.ndarray:
        return turn(self.rotation.T, np.atleast_2d(q)) + self.origin

    def direction(self, d: np.ndarray) -> np.ndarray:
        return turn(self.rotation, d)

    def prism(self, occ, corners, s0: float, s1: float, axis_origin: np.ndarray) -> int:
        """A prism in the file frame: the polygon ``corners`` (x, y of this frame) in the
        plane normal to the axis at shaft position ``s0`` (``p = axis_origin + s e``),
        extruded to ``s1``.  When the axis runs along a coordinate axis of the file, the
        polygon lies exactly in the plane of that coordinate = s0 (x and y have no
        component along it) and the extrusion is exactly along it: the prism's end faces
        coincide with the file's faces at the same position to the last bit."""
        x, y, e = self.rotation
        base = axis_origin + s0 * e
        pts = [occ.addPoint(*map(float, base + a * x + b * y)) for a, b in corners]
        loop = occ.addCurveLoop([occ.addLine(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))])
        face = occ.addPlaneSurface([loop])
        out = occ.extrude([(2, face)], *map(float, (s1 - s0) * e))
        return next(t for d, t in out if d == 3)

    def move_into(self, gmsh, volumes: list[int]) -> dict[int, int]:
        """Move the volumes from the file frame into this frame (``p -> R (p - o)``: a
        translation by ``-o``, then the rotation ``R`` about the origin as one turn about
        its axis, both rigid, so OpenCASCADE keeps the surfaces analytic).  Volumes keep
        their tags, faces get new ones: returns old face tag -> new (each volume's faces
        are listed in the same order before and after; each pair is checked by its
        centre of mass)."""
        from scipy.spatial.transform import Rotation

        occ = gmsh.model.occ

        def faces() -> dict[int, list[int]]:
            return {
                v: [abs(t) for _, t in gmsh.model.getBoundary([(3, v)], combined=False, oriented=False)]
                for v in volumes
            }

        before = faces()
        centres = {f: np.asarray(occ.getCenterOfMass(2, f)) for fs in before.values() for f in fs}
        dim_tags = [(3, v) for v in volumes]
        if np.any(self.origin != 0.0):
            occ.translate(dim_tags, *map(float, -self.origin))
        turn = Rotation.from_matrix(self.rotation).as_rotvec()
        angle = float(np.linalg.norm(turn))
        if angle > 0.0:
            occ.rotate(dim_tags, 0.0, 0.0, 0.0, *map(float, turn / angle), angle)
        occ.synchronize()
        after = faces()
        out: dict[int, int] = {}
        scale = max((float(np.linalg.norm(c)) for c in centres.values()), default=1.0)
        for v in volumes:
            if len(before[v]) != len(after[v]):
                raise RuntimeError(f"volume {v} has other faces after the move")  # pragma: no cover
            for a, b in zip(before[v], after[v], strict=True):
                moved = self.to_throw(centres[a])[0]
                if out.setdefault(a, b) != b or np.linalg.norm(np.asarray(occ.getCenterOfMass(2, b)) - moved) > 1e-9 * (
                    1.0 + scale
                ):
                    raise RuntimeError(f"face {a} not found after the move into the throw frame")  # pragma: no cover
        return out


def chord(gmsh, volume: int, frame: Frame, y: float, z: float, reach: float) -> tuple[float, float, float]:
    """Where the line (y, z) of the throw frame runs in the solid (OpenCASCADE's common
    of the line and the solid: exact): its smallest and largest x, and the length of
    line inside the solid (less than their difference where the line crosses a hole);
    zeros when it misses.  The solid is left as it was."""
    occ = gmsh.model.occ
    p0, p1 = frame.to_file(np.array([[-reach, y, z], [reach, y, z]]))
    line = occ.addLine(occ.addPoint(*map(float, p0)), occ.addPoint(*map(float, p1)))
    out, _ = occ.intersect([(1, line)], [(3, volume)], removeObject=True, removeTool=False)
    occ.synchronize()
    xs, inside = [], 0.0
    for dim, c in out:
        ends = [
            float(frame.to_throw(np.asarray(gmsh.model.getValue(0, p, [])))[0][0])
            for _, p in gmsh.model.getBoundary([(dim, c)], combined=False)
        ]
        xs += ends
        inside += max(ends) - min(ends) if ends else 0.0
    occ.remove(out, recursive=True)
    occ.synchronize()
    return (min(xs), max(xs), inside) if xs else (0.0, 0.0, 0.0)
