"""UR M53 Appendix III 2.2: at least 6 elements across the web thickness.

The appendix's element-mesh recommendations for the SCF models (IACS UR M53 Rev.2,
Appendix III, 2.2; KR Pt 5 Annex 5-3 reproduces them) ask, beside the fillet elements of
at most r/4, for "minimum 6 elements across web thickness": the web carries the bending
that the nominal stresses are defined on, and a web two or three elements thick is too
stiff in bending (quadratic elements included).

Measure: a straight line parallel to the crank axis through the web (at a few points of
its outline, ``sample_points``) crosses elements of the web subdomain; the number of
elements across is the web thickness over the mean axial extent (max z - min z of the
vertices) of the elements it crosses, n = W / mean(dz).  For a mesh in layers of height h
(every element spanning one layer) it is W/h, the number of layers, exactly; for an
unstructured mesh of element size h about W/h.  The smallest n over the sample lines is
reported, per web.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import Mesh

#: UR M53 App. III 2.2
MIN_ELEMENTS_ACROSS = 6


@dataclass(frozen=True)
class WebElements:
    """Elements across one web's thickness (the smallest over the sample lines)."""

    web: str
    across: float
    lines: int  # sample lines that crossed the web

    @property
    def ok(self) -> bool:
        return self.across >= MIN_ELEMENTS_ACROSS


def _crossed(p: np.ndarray, tets: np.ndarray, x0: float, y0: float) -> np.ndarray:
    """Indices (into ``tets``' columns) of the tetrahedra a line x = x0, y = y0 passes
    through: the point lies in the projection of the tet on the xy plane, the convex hull of
    its four projected vertices, i.e. in one of the four triangles of three of them."""
    xy = p[:2, tets]  # (2, 4, n)
    hit = np.zeros(tets.shape[1], bool)
    for a, b, c in ((0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)):
        A, B, C = xy[:, a], xy[:, b], xy[:, c]
        det = (B[0] - A[0]) * (C[1] - A[1]) - (C[0] - A[0]) * (B[1] - A[1])
        ok = np.abs(det) > 1e-30
        d = np.where(ok, det, 1.0)
        l1 = ((x0 - A[0]) * (C[1] - A[1]) - (C[0] - A[0]) * (y0 - A[1])) / d
        l2 = ((B[0] - A[0]) * (y0 - A[1]) - (x0 - A[0]) * (B[1] - A[1])) / d
        hit |= ok & (l1 >= 0) & (l2 >= 0) & (l1 + l2 <= 1)
    return np.flatnonzero(hit)


def sample_points(p: np.ndarray, tets: np.ndarray, n: int = 5) -> np.ndarray:
    """(2, n) points in the web's outline: the centroid of its elements and points along x
    through it at fractions of its half-extent (irrational offsets keep the lines off the
    mesh's faces and edges)."""
    cx, cy = p[:2, tets].mean(axis=(1, 2))
    x = p[0, tets]
    half = 0.5 * (x.max() - x.min())
    f = np.linspace(-0.6, 0.6, n) + 0.0123456789
    return np.vstack([cx + f * half, np.full(n, cy + 1e-3 * np.sqrt(2) * half)])


def web_elements_across(
    mesh: Mesh, webs: dict[str, np.ndarray], thickness: float, points: dict[str, np.ndarray] | None = None
) -> tuple[WebElements, ...]:
    """Elements across the thickness ``thickness`` (m) of each web: ``webs`` maps a web's
    name to its element indices (the mesh's ``web_i`` subdomains); ``points`` (name ->
    (2, k) xy of the sample lines; default ``sample_points``)."""
    if not thickness > 0:
        raise ValueError(f"web thickness must be positive, got {thickness!r}")
    p = np.asarray(mesh.p)
    out = []
    for name, elements in webs.items():
        tets = np.asarray(mesh.t)[:4, np.asarray(elements)]
        if tets.shape[1] == 0:
            raise ValueError(f"web {name!r} has no elements")
        pts = sample_points(p, tets) if points is None or name not in points else np.asarray(points[name])
        dz = p[2, tets].max(axis=0) - p[2, tets].min(axis=0)
        counts = []
        for x0, y0 in pts.T:
            hit = _crossed(p, tets, float(x0), float(y0))
            if hit.size:
                counts.append(thickness / float(dz[hit].mean()))
        if not counts:
            raise ValueError(f"no sample line crosses web {name!r}")
        out.append(WebElements(name, min(counts), len(counts)))
    return tuple(out)


def web_groups(mesh: Mesh) -> dict[str, np.ndarray]:
    """The mesh's web subdomains (``web_1``, ``web_2``) that are present."""
    subs = mesh.subdomains or {}
    return {k: np.asarray(subs[k]) for k in ("web_1", "web_2") if k in subs}


__all__ = ["MIN_ELEMENTS_ACROSS", "WebElements", "web_elements_across", "sample_points", "web_groups"]
