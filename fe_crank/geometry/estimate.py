"""Element count of a throw mesh, estimated before gmsh runs (a resource bound).

A tetrahedral mesh with local edge length ``h`` holds about ``rho / h^3`` elements
per unit volume: ``6 sqrt(2) = 8.49`` for regular tetrahedra (volume
``h^3 / (6 sqrt 2)``); gmsh's Delaunay meshes hold 3-8 times more (measured on the
test geometries, gmsh 4.15: its edges scatter below the target), so ``rho = 4 x 8.49``.  The size field of ``fe_crank.mesh`` is ``size_max`` in the
bulk and ``h(s) = h_f + g s`` at a distance ``s`` from a fillet (``h_f`` the fillet
target edge, ``g`` the grading), up to ``size_max``.  Integrating ``rho / h^3`` over
the layers beside a fillet surface of area ``A`` (area taken constant, the solid on
one side):

    N_f = rho A / (2 g) (h_f^-2 - size_max^-2)

and the bulk adds ``rho V / size_max^3``.  ``A`` is the quarter torus
``(pi/2) r_f * 2 pi (r_0 + r_f)`` (an upper bound of the fillet area), ``V`` the
solid volume (journals, crankpin, web prisms, counterweight sectors).  Curved
cylinder faces are meshed with at most 12 edges per turn
(``Mesh.MeshSizeFromCurvature``), treated the same way with ``h = 2 pi r / 12``.

The estimate is for refusing a mesh that would not finish (a fillet radius of a few
micrometres, a ``size_max`` typed in the wrong unit), not for planning: it is
checked against real gmsh meshes in tests/test_io_geometry_limits.py (within a
factor 3).  ``MAX_ELEMENTS`` is the default limit (docs/limits.md).
"""

from __future__ import annotations

import math

import numpy as np

from fe_crank.geometry.spec import CrankGeometry, ThrowSpec

#: default limit on the estimated element count of one throw mesh.  The ``fine``
#: preset of the shipped throws is estimated at 1.2-1.7 M (the V4 throw: 1.34 M
#: estimated, 0.58 M real, docs/performance.md) and must pass; a mesh of 3 M
#: estimated elements could not be solved on the 24 GB reference machine anyway.
MAX_ELEMENTS = 3_000_000
#: tetrahedra per h^3: 4 x the regular packing 6 sqrt(2).  gmsh's Delaunay meshes of
#: this project's throws hold 3-8 x the regular-packing count (measured, tests and
#: docs/limits.md), the factor 4 keeps the estimate within a factor 3 of them
TETS_PER_H3 = 4 * 6.0 * math.sqrt(2.0)
_SAFETY = 0.65  # fe_crank.mesh: fillet target edge = SAFETY * r / fillet_divisions


def hull_area(a: float, b: float, d: float, n: int = 720) -> float:
    """Area of the convex hull of a circle of radius ``a`` at the origin and one of
    radius ``b`` at distance ``d`` (the web outline), from its support points."""
    th = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    u = np.stack([np.cos(th), np.sin(th)])
    p1 = a * u
    p2 = np.array([[0.0], [d]]) + b * u
    pick = (p2 * u).sum(0) > (p1 * u).sum(0)
    pts = np.where(pick, p2, p1)
    x, y = pts
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def graded_layer_elements(area: float, h0: float, size_max: float, grading: float) -> float:
    """Extra tetrahedra of a size field graded from ``h0`` on a surface of ``area`` to ``size_max``."""
    if h0 >= size_max:
        return 0.0
    return TETS_PER_H3 * area / (2.0 * grading) * (h0**-2 - size_max**-2)


def estimate_elements(g: CrankGeometry, spec: ThrowSpec, opt) -> int:
    """Estimated tetrahedra of ``fe_crank.mesh.mesh_throw(g, spec, size=opt)``.

    ``g`` a ``CrankGeometry``, ``spec`` its ``ThrowSpec``, ``opt`` a ``MeshOptions``.
    """
    size_max = opt.size_max if opt.size_max is not None else g.crankpin_diameter / opt.coarse_divisions
    rp, rj = g.crankpin_diameter / 2, g.journal_diameter / 2
    vol = 2 * math.pi * rj**2 * g.journal_length + math.pi * rp**2 * g.crankpin_length
    vol += 2 * g.web_thickness * hull_area(g.web.journal_end_radius, g.web.pin_end_radius, g.crank_radius)
    for cw in spec.counterweights:
        vol += 0.5 * cw.angle * (cw.outer_radius**2 - cw.inner_radius**2) * cw.thickness
    n = TETS_PER_H3 * vol / size_max**3
    for r0, rf in ((rp, g.crankpin_fillet), (rj, g.journal_fillet)):
        if rf > 0:
            area = 0.5 * math.pi * rf * 2 * math.pi * (r0 + rf)
            n += 2 * graded_layer_elements(area, _SAFETY * rf / opt.fillet_divisions, size_max, opt.grading)
    for r0, length in ((rp, g.crankpin_length), (rj, 2 * g.journal_length)):
        n += graded_layer_elements(2 * math.pi * r0 * length, 2 * math.pi * r0 / 12, size_max, opt.grading)
    if g.oil_bore is not None:
        db = g.oil_bore.diameter
        n += graded_layer_elements(
            math.pi * db * 2 * rp, math.pi * db / (2 * opt.bore_divisions), size_max, opt.grading
        )
    return int(math.ceil(n))


def check_element_budget(g: CrankGeometry, spec: ThrowSpec, opt, max_elements: int | None = None) -> int:
    """Refuse (``GeometryError`` naming the geometry file) a throw whose estimated
    element count exceeds ``max_elements`` (default ``MAX_ELEMENTS``); return the
    estimate.  The message names the smallest fillet, the usual cause."""
    from fe_crank.errors import GeometryError

    limit = MAX_ELEMENTS if max_elements is None else int(max_elements)
    n = estimate_elements(g, spec, opt)
    if n > limit:
        fillets = [
            (r, k)
            for k, r in (("crankpin.fillet_radius", g.crankpin_fillet), ("journal.fillet_radius", g.journal_fillet))
            if r > 0
        ]
        key = min(fillets)[1] if fillets else None
        raise GeometryError(
            f"the mesh would have about {n:.3g} elements, more than the limit {limit:.3g} "
            "(a fillet radius or mesh size far too small?); raise it with --max-elements or "
            "[mesh] max_elements in the load case (docs/limits.md)",
            file=g.file or None,
            key=key,
        )
    return n
