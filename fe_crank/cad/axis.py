"""The crank axis of a B-rep: the common axis of the largest set of coaxial cylindrical
faces (main journals, the webs' rounded journal ends, counterweight arcs, shaft ends).

Two cylinders are coaxial when their axes are parallel to ``ANGLE_TOL`` and one axis
passes within ``tol`` of the other's points.  A tie between two sets of the same size is
ambiguous (``InputError`` naming both sets and the key ``cad.faces.axis`` that settles
it); ``[cad.faces] axis`` names the faces outright.

Direction (front, the free end, to the flywheel): ``[cad] axis`` when given (it must be
parallel to the recognised axis), else the positive sense of the file's coordinate axis
the crank axis lies along; a crank axis along none of them needs ``[cad] axis``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fe_crank.cad.config import CadInput
from fe_crank.cad.survey import Face, unit_vector
from fe_crank.errors import InputError

#: rad: axes this close to parallel are parallel
ANGLE_TOL = 1e-6


@dataclass(frozen=True, eq=False)
class Line:
    """A line through ``origin`` along the unit vector ``e`` (internal)."""

    origin: np.ndarray
    e: np.ndarray

    def distance(self, p: np.ndarray) -> np.ndarray:
        d = np.atleast_2d(p) - self.origin
        return np.linalg.norm(d - np.outer(d @ self.e, self.e), axis=1)

    def same(self, other: Line, tol: float) -> bool:
        """Coaxial with ``other``."""
        par = np.linalg.norm(np.cross(self.e, other.e)) <= ANGLE_TOL
        return bool(par and self.distance(other.origin)[0] <= tol and self.distance(other.origin + other.e)[0] <= tol)


def line_of(face: Face) -> Line:
    """The axis of a cylindrical face, its direction made a unit vector without a BLAS
    kernel (``cad.survey.unit_vector``: the same last bits on every processor)."""
    return Line(face.origin, unit_vector(face.direction))


def coaxial_sets(faces: list[Face], tol: float) -> list[list[Face]]:
    """Cylindrical faces grouped by common axis, largest set first (ties in file order)."""
    sets: list[tuple[Line, list[Face]]] = []
    for f in faces:
        line = line_of(f)
        for ln, members in sets:
            if ln.same(line, tol):
                members.append(f)
                break
        else:
            sets.append((line, [f]))
    return sorted((m for _, m in sets), key=lambda m: -len(m))


def _ids(faces: list[Face]) -> str:
    return "[" + ", ".join(str(f.tag) for f in faces) + "]"


def _direction(cad: CadInput, e: np.ndarray) -> np.ndarray:
    if cad.axis is not None:
        want = np.asarray(cad.axis, dtype=float)
        if np.linalg.norm(np.cross(want, e)) > 1e-3:
            raise InputError(
                f"the crank axis recognised runs along ({e[0]:.4g}, {e[1]:.4g}, {e[2]:.4g}), not along the axis "
                f"given in {cad.where}",
                file=str(cad.file),
                key="cad.axis",
            )
        return e if want @ e > 0 else -e
    k = int(np.argmax(np.abs(e)))
    if abs(abs(e[k]) - 1.0) > ANGLE_TOL:
        raise InputError(
            f"the crank axis runs along ({e[0]:.4g}, {e[1]:.4g}, {e[2]:.4g}), along none of the file's coordinate "
            f"axes: say which way is front to rear with axis = [x, y, z] in {cad.where}",
            file=str(cad.file),
            key="cad.axis",
        )
    out = np.zeros(3)
    out[k] = 1.0
    return out


def find_axis(faces: dict[int, Face], cad: CadInput, tol: float) -> tuple[Line, tuple[int, ...]]:
    """The crank axis (origin: the foot of the file's origin on it) and its faces."""
    given = cad.override("axis")
    if given is not None:
        chosen = [faces[t] for t in given.faces if t in faces]
        missing = [t for t in given.faces if t not in faces]
        bad = [f.tag for f in chosen if f.kind != "cylinder"]
        sets = coaxial_sets(chosen, tol)
        if missing or bad or len(sets) != 1:
            why = (
                f"faces {missing} are not in the model"
                if missing
                else (f"faces {bad} are not cylinders" if bad else "the faces have no common axis")
            )
            raise InputError(why, file=str(cad.file), key=given.key)
        best = sets[0]
    else:
        cylinders = [f for f in faces.values() if f.kind == "cylinder"]
        sets = coaxial_sets(cylinders, tol)
        if not sets:
            raise InputError(
                "no cylindrical face found, so no crank axis: is this a crankshaft?", file=str(cad.file), key="cad.file"
            )
        if len(sets) > 1 and len(sets[1]) == len(sets[0]):
            tied = [s for s in sets if len(s) == len(sets[0])]
            listing = " and ".join(_ids(s) for s in tied)
            raise InputError(
                f"the crank axis is ambiguous: the coaxial cylindrical faces {listing} are sets of equal size; "
                f"name the faces of the crank axis in {cad.where}",
                file=str(cad.file),
                key="cad.faces.axis",
            )
        best = sets[0]
    line = line_of(best[0])
    e = _direction(cad, line.e)
    along = math.fsum(float(a) * float(b) for a, b in zip(line.origin, e))  # scalar: no BLAS kernel
    origin = line.origin - along * e
    return Line(origin, e), tuple(sorted(f.tag for f in best))
