"""The THROW frame of a recognised throw in the file's frame, and chords of the solid.

``z`` along the crank axis (front to rear), ``y`` from the axis towards the crankpin's
centre, ``x = y x z`` (right-handed: the direction the pin moves in the positive
sense of rotation), origin on the axis midway between the webs' inner faces;
``p_throw = R (p_file - o)`` with the rows of ``R`` the frame's x, y, z axes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True, eq=False)
class Frame:
    origin: np.ndarray  # (3,) file frame
    rotation: np.ndarray  # (3, 3), rows x, y, z

    @classmethod
    def of(cls, axis_origin: np.ndarray, e: np.ndarray, u: np.ndarray, s_mid: float) -> Frame:
        y = u - (u @ e) * e
        y /= np.linalg.norm(y)
        x = np.cross(y, e)
        return cls(axis_origin + s_mid * e, np.vstack([x, y, e]))

    def to_throw(self, p: np.ndarray) -> np.ndarray:
        return (np.atleast_2d(p) - self.origin) @ self.rotation.T

    def to_file(self, q: np.ndarray) -> np.ndarray:
        return np.atleast_2d(q) @ self.rotation + self.origin

    def direction(self, d: np.ndarray) -> np.ndarray:
        return self.rotation @ d

    def move(self, occ, dimtags) -> None:
        """Move shapes of the file frame into this frame: a translation by ``-origin`` and
        a rotation by ``R`` (rigid OpenCASCADE transformations, exact for every surface
        type; a general affine transformation would turn every surface into a B-spline
        approximation: measured, it changed a throw's volume by 0.2 %)."""
        from scipy.spatial.transform import Rotation

        o = [float(-c) for c in self.origin]
        occ.translate(dimtags, *o)
        v = Rotation.from_matrix(self.rotation).as_rotvec()
        angle = float(np.linalg.norm(v))
        if angle > 0:
            occ.rotate(dimtags, 0.0, 0.0, 0.0, *(float(c) for c in v / angle), angle)


def chord(gmsh, volume: int, frame: Frame, y: float, z: float, reach: float) -> tuple[float, float]:
    """Smallest and largest x at which the line (y, z) of the throw frame runs in the
    solid (OpenCASCADE's common of the line and the solid: exact); (0, 0) when it misses.
    The solid is left as it was."""
    occ = gmsh.model.occ
    p0, p1 = frame.to_file(np.array([[-reach, y, z], [reach, y, z]]))
    line = occ.addLine(occ.addPoint(*map(float, p0)), occ.addPoint(*map(float, p1)))
    out, _ = occ.intersect([(1, line)], [(3, volume)], removeObject=True, removeTool=False)
    occ.synchronize()
    xs = []
    for dim, c in out:
        for _, p in gmsh.model.getBoundary([(dim, c)], combined=False):
            xs.append(float(frame.to_throw(np.asarray(gmsh.model.getValue(0, p, [])))[0][0]))
    occ.remove(out, recursive=True)
    occ.synchronize()
    return (min(xs), max(xs)) if xs else (0.0, 0.0)
