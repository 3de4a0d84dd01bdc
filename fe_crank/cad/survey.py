"""What each face of the B-rep is: a plane, a cylinder, a torus or another surface,
fitted from points sampled on the face (gmsh's OpenCASCADE evaluators), whatever the
file calls it (a cylinder written as a B-spline is a cylinder here).

Sampling: a grid of the face's parameters, kept where the point lies on the trimmed
face (``gmsh.model.isInside`` with parametric coordinates); normals point out of the
solid (gmsh orients an OpenCASCADE face's normal by the face's orientation in the
solid).  Fits, each accepted when every sample lies within ``tol`` of the surface:

* plane: all normals parallel;
* cylinder: the axis is normal to every surface normal, i.e. the eigenvector of the
  smallest eigenvalue of ``sum n n^T``; centre and radius by the algebraic circle fit of
  the points projected on a plane normal to it (I. Kasa, IEEE Trans. Instrum. Meas. 25
  (1976) 8-14: exact for points on a circle);
* torus: the tube radius ``rho = 1 / max |kappa|`` (the meridian curvature of a torus
  whose spine is larger than twice its tube, as every fillet of a cylinder is) and the
  spine circle fitted to ``p - s rho n`` (``s = +1``: tube convex, ``-1``: concave);
* anything else: "other", with its smallest radius of curvature.

The fitted numbers (radii, axis points, axis directions) are rounded, lengths to 1 nm and
direction cosines to 1e-12 (``LENGTH_QUANTUM_DECIMALS``, ``DIRECTION_QUANTUM_DECIMALS``;
``snap_length``, ``snap_point``, ``snap_direction``): their last bits depend on
the kernels the linear-algebra library picks for the machine's processor (OpenBLAS's
Haswell and Sandybridge kernels give a fillet's spine radius and an oil bore's direction
that differ in the last bit), and gmsh turns a last-bit change of a size field or a cut
into another mesh.  Rounded, a drawing gives the same features, the same mesh and the
same verdict on every machine; a dimension drawn in millimetres or inches is a multiple
of the quantum, so it is recognised as its decimal value (a 56 mm journal as 0.056 m).
Measured positions (a plane's point, the sample points) are the file's own, unrounded.

Convexity (``convex``): the centre of curvature lies inside the material (a shaft's
outside, a web's rounded edge) rather than outside it (a bore, a fillet of a re-entrant
edge).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: fitted lengths are rounded to this (m): far below any drawing's resolution, far above
#: the round-off of a fit (1e-16 of the size)
LENGTH_QUANTUM_DECIMALS = 9  # 1 nm
#: fitted unit vectors: each direction cosine rounded to this many decimals, then renormalised
DIRECTION_QUANTUM_DECIMALS = 12
_GRID = (6, 16)  # parameter grids tried (n x n), the finer one for narrow faces
_MIN_POINTS = 6
_CURVE_SAMPLES = 9


@dataclass(frozen=True, eq=False)
class Face:
    """One face of the model: its fit and sample points (internal to the CAD route)."""

    tag: int
    gtype: str  # gmsh's name of the surface type
    kind: str  # "plane", "cylinder", "torus", "other"
    area: float
    points: np.ndarray  # (k, 3) points on the face
    normals: np.ndarray  # (k, 3) outward unit normals there
    edge_points: np.ndarray  # (m, 3) points on its boundary curves
    curves: tuple[int, ...]
    edge_runs: tuple[np.ndarray, ...]  # the boundary points curve by curve, in order along each
    origin: np.ndarray  # plane: a point; cylinder: a point of the axis; torus: the centre
    direction: np.ndarray  # plane: normal; cylinder, torus: axis (unit)
    radius: float = 0.0  # cylinder radius, torus spine radius
    minor: float = 0.0  # torus tube radius
    convex: bool = True
    min_radius: float = float("inf")  # smallest radius of curvature at the samples

    def axial(self, origin: np.ndarray, e: np.ndarray, edges: bool = True) -> np.ndarray:
        """Positions along the line (origin, e) of its boundary (or interior) points."""
        return ((self.edge_points if edges else self.points) - origin) @ e


def face_samples(gmsh, tag: int) -> tuple[np.ndarray, np.ndarray]:
    """Parameter pairs on the trimmed face and their points."""
    lo, hi = gmsh.model.getParametrizationBounds(2, tag)
    uv: list[float] = []
    for n in _GRID:
        uv = []
        for i in range(n):
            for j in range(n):
                u = lo[0] + (i + 0.5) / n * (hi[0] - lo[0])
                v = lo[1] + (j + 0.5) / n * (hi[1] - lo[1])
                if gmsh.model.isInside(2, tag, [u, v], parametric=True):
                    uv += [u, v]
        if len(uv) >= 2 * _MIN_POINTS:
            break
    if not uv:
        return np.zeros(0), np.zeros((0, 3))
    pts = np.asarray(gmsh.model.getValue(2, tag, uv)).reshape(-1, 3)
    return np.asarray(uv), pts


def _curve_points(gmsh, curve: int, cache: dict[int, np.ndarray]) -> np.ndarray:
    if curve not in cache:
        lo, hi = gmsh.model.getParametrizationBounds(1, curve)
        t = lo[0] + (hi[0] - lo[0]) * np.linspace(0.0, 1.0, _CURVE_SAMPLES)
        cache[curve] = np.asarray(gmsh.model.getValue(1, curve, t.tolist())).reshape(-1, 3)
    return cache[curve]


def circle_fit(q: np.ndarray) -> tuple[np.ndarray, float]:
    """Centre and radius of the circle through 2D points ``q`` (k, 2), Kasa's fit."""
    A = np.column_stack([2 * q, np.ones(len(q))])
    b = (q**2).sum(axis=1)
    sol, *_ = np.linalg.lstsq(A, b, rcond=None)
    c = sol[:2]
    return c, float(np.sqrt(max(sol[2] + c @ c, 0.0)))


def snap_length(x: float) -> float:
    """A fitted length (m) rounded to 1 nm (the module doc)."""
    return float(round(float(x), LENGTH_QUANTUM_DECIMALS))


def snap_point(p: np.ndarray) -> np.ndarray:
    """A fitted point (m), each coordinate rounded to 1 nm."""
    return np.array([snap_length(c) for c in p])


def snap_direction(e: np.ndarray) -> np.ndarray:
    """A fitted axis, its direction cosines rounded (the module doc) and the result
    renormalised in scalar arithmetic (correctly rounded sums, no BLAS): an axis along a
    coordinate axis becomes exactly that axis.  An axis has no sense of its own (an
    eigenvector's sign is the solver's choice, and differs between kernels): its first
    non-zero cosine is made positive."""
    c = [float(round(float(v), DIRECTION_QUANTUM_DECIMALS)) for v in e]
    if next(v for v in c if v != 0.0) < 0.0:
        c = [-v for v in c]
    return unit_vector(c)


def unit_vector(v) -> np.ndarray:
    """``v`` scaled to unit length in scalar arithmetic (a correctly rounded sum, no BLAS
    kernel): the same last bits on every processor."""
    c = [float(x) for x in v]
    n = math.sqrt(math.fsum(x * x for x in c))
    return np.array([x / n for x in c])


def _basis(e: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    a = np.array([1.0, 0.0, 0.0]) if abs(e[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    b1 = np.cross(e, a)
    b1 /= np.linalg.norm(b1)
    return b1, np.cross(e, b1)


def _circle3(s: np.ndarray, normal: np.ndarray) -> tuple[np.ndarray, float]:
    """Centre and radius of the circle through 3D points ``s`` lying in a plane of ``normal``."""
    b1, b2 = _basis(normal)
    c0 = s.mean(axis=0)
    q = np.column_stack([(s - c0) @ b1, (s - c0) @ b2])
    c, r = circle_fit(q)
    return c0 + c[0] * b1 + c[1] * b2, r


def _fit_cylinder(p, n, tol):
    w, V = np.linalg.eigh(n.T @ n)
    e = V[:, 0]
    if np.max(np.abs(n @ e)) > 1e-6 or w[1] < 1e-10 * len(n):
        return None
    centre, r = _circle3(p, e)
    d = p - centre
    radial = d - np.outer(d @ e, e)
    if np.max(np.abs(np.linalg.norm(radial, axis=1) - r)) > tol:
        return None
    convex = bool(np.mean(np.einsum("ij,ij->i", radial, n)) > 0)
    return centre - (centre @ e) * e, e, r, convex


def _fit_torus(p, n, kmax, tol):
    rho = float(np.median(1.0 / kmax))
    for sgn, convex in ((1.0, True), (-1.0, False)):
        s = p - sgn * rho * n
        _, _, Vt = np.linalg.svd(s - s.mean(axis=0))
        e = Vt[2]
        if np.max(np.abs((s - s.mean(axis=0)) @ e)) > tol:
            continue
        centre, a = _circle3(s, e)
        d = p - centre
        h = d @ e
        radial = np.linalg.norm(d - np.outer(h, e), axis=1)
        dist = np.hypot(radial - a, h)
        if a > 0 and np.max(np.abs(dist - rho)) <= tol:
            return centre, e, a, rho, convex
    return None


def survey(gmsh, tags: list[int], tol: float) -> dict[int, Face]:
    """Fit every face of ``tags``; ``tol`` (m) is the largest deviation of a sample."""
    out = {}
    cache: dict[int, np.ndarray] = {}
    occ = gmsh.model.occ
    for tag in tags:
        uv, p = face_samples(gmsh, tag)
        curves = tuple(abs(c) for _, c in gmsh.model.getBoundary([(2, tag)], combined=False, oriented=False))
        edge = [_curve_points(gmsh, c, cache) for c in curves]
        edge_points = np.vstack(edge) if edge else p
        gtype = gmsh.model.getType(2, tag)
        area = float(occ.getMass(2, tag))
        if len(p) == 0:  # no parameter sample on the face: its boundary stands for it
            p = edge_points
            uv = np.asarray(gmsh.model.getParametrization(2, tag, p.ravel().tolist()))
        n = np.asarray(gmsh.model.getNormal(tag, uv.tolist())).reshape(-1, 3)
        k1, k2, _, _ = gmsh.model.getPrincipalCurvatures(tag, uv.tolist())
        kmax = np.maximum(np.abs(np.asarray(k1)), np.abs(np.asarray(k2)))
        min_radius = float(1.0 / kmax.max()) if kmax.max() > 0 else float("inf")
        base = dict(
            tag=tag,
            gtype=gtype,
            area=area,
            points=p,
            normals=n,
            edge_points=edge_points,
            curves=curves,
            edge_runs=tuple(edge),
        )
        if np.all(np.abs(n @ n[0]) > 1 - 1e-9) and np.max(np.abs((p - p[0]) @ n[0])) <= tol:
            out[tag] = Face(kind="plane", origin=p[0], direction=n[0], **base)
            continue
        cyl = _fit_cylinder(p, n, tol) if len(p) >= 3 else None
        if cyl is not None:
            o, e, r, convex = cyl
            o, e, r = snap_point(o), snap_direction(e), snap_length(r)
            out[tag] = Face(kind="cylinder", origin=o, direction=e, radius=r, convex=convex, min_radius=r, **base)
            continue
        tor = _fit_torus(p, n, kmax, tol) if len(p) >= 4 and np.all(kmax > 0) else None
        if tor is not None:
            c, e, a, rho, convex = tor
            c, e, a, rho = snap_point(c), snap_direction(e), snap_length(a), snap_length(rho)
            out[tag] = Face(
                kind="torus", origin=c, direction=e, radius=a, minor=rho, convex=convex, min_radius=rho, **base
            )
            continue
        out[tag] = Face(kind="other", origin=p.mean(axis=0), direction=n[0], min_radius=min_radius, **base)
    return out


def neighbours(faces: dict[int, Face]) -> dict[int, set[int]]:
    """Faces sharing a boundary curve with each face."""
    by_curve: dict[int, set[int]] = {}
    for f in faces.values():
        for c in f.curves:
            by_curve.setdefault(c, set()).add(f.tag)
    out: dict[int, set[int]] = {t: set() for t in faces}
    for group in by_curve.values():
        for t in group:
            out[t] |= group - {t}
    return out


def coverage(runs, origin: np.ndarray, e: np.ndarray, bins: int = 72) -> float:
    """Fraction of the full turn about the line (origin, e) that the curves ``runs``
    (arrays of points in order along each curve) sweep: the angle between consecutive
    points is swept the short way round (bins of 5 deg)."""
    b1, b2 = _basis(e)
    hit = np.zeros(bins, dtype=bool)
    for pts in runs:
        d = pts - origin
        ang = np.arctan2(d @ b2, d @ b1)
        for a0, a1 in zip(ang[:-1], ang[1:]):
            da = (a1 - a0 + np.pi) % (2 * np.pi) - np.pi
            steps = max(1, int(np.ceil(abs(da) / (np.pi / bins))))
            t = a0 + da * np.linspace(0.0, 1.0, steps + 1)
            hit[np.floor((t + np.pi) / (2 * np.pi) * bins).astype(int) % bins] = True
    return float(hit.sum()) / bins
