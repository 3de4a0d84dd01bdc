"""The transition fillet between a counterweight and its web (``counterweight.fillet_radius``).

Where an annular-sector counterweight leaves the web outline, the fused solid has
concave (re-entrant) edges: the sector's radial faces against the web's side face, and,
for a counterweight thinner or thicker than the web, the sector's axial face against the
web's side face or the web's inner face against the sector's sides.  An elastic body is
singular at such an edge: near a 270-degree corner the stresses grow like
``rho^(lambda - 1)`` with ``lambda = 0.5445`` (M. L. Williams, "Stress singularities
resulting from various boundary conditions in angular corners of plates in extension",
J. Appl. Mech. 19 (1952) 526-528), so each halving of the element size raises the
computed peak by ``2^0.4555 = 1.37`` and no mesh gives a finite answer.  A real
counterweight has a transition radius there; with ``fillet_radius`` the edges are
rounded (OpenCASCADE rolling-ball fillet) and the peak is a finite, mesh-convergent
concentration.

The rounded corner adds material outside both the sector and the web prism; it is
meshed as part of the counterweight subdomain (:func:`fill_tools`), so that the fillet
surface is assessed by the counterweight criteria, and its curved faces are the
boundary group ``counterweight_fillet_<web>`` that ``fe_crank.mesh.sizing`` refines to
``r/4`` like the shaft fillets.
"""

from __future__ import annotations

import math

import numpy as np

from fe_crank.geometry.spec import CounterweightSpec, CrankGeometry

#: points tested round an edge's midpoint; a concave (re-entrant) edge has material on
#: more than half of them (3/4 at a right-angled re-entrant corner)
_RING = 16
_CONCAVE = 0.6


#: the ring's points in the order they are tested: spread round the ring first (bit-reversed
#: indices), so that a few points already show which side of ``_CONCAVE`` the edge is on
_ORDER = (0, 8, 4, 12, 2, 10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15)


def _midpoint(gmsh, curve: int) -> tuple[np.ndarray, float]:
    """The edge's parametric midpoint and the curve's parameter there."""
    lo, hi = gmsh.model.getParametrizationBounds(1, curve)
    u = 0.5 * (lo[0] + hi[0])
    return np.array(gmsh.model.getValue(1, curve, [u])), u


def _concave(gmsh, solid: int, curve: int, eps: float) -> bool:
    """Is the edge concave (material on more than ``_CONCAVE`` of a small ring round its
    midpoint, in the plane normal to it)?  The ring's points are classified one by one
    (``gmsh.model.isInside``, the costly call) until the count decides: the answer is that
    of classifying all of them."""
    p, u = _midpoint(gmsh, curve)
    t = np.array(gmsh.model.getDerivative(1, curve, [u]))
    n = np.linalg.norm(t)
    if not n > 0:
        return False
    t /= n
    a = np.array([1.0, 0.0, 0.0]) if abs(t[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = np.cross(t, a)
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(t, e1)
    ang = 2 * math.pi * (np.arange(_RING) + 0.5) / _RING
    pts = p[None, :] + eps * (np.cos(ang)[:, None] * e1 + np.sin(ang)[:, None] * e2)
    need = math.floor(_CONCAVE * _RING) + 1  # points inside for "more than _CONCAVE"
    inside = 0
    for k, i in enumerate(_ORDER):
        inside += gmsh.model.isInside(3, solid, pts[i].tolist())
        if inside >= need:
            return True
        if inside + (_RING - k - 1) < need:
            return False
    return False


def junction_edges(
    gmsh, solid: int, cws: dict[int, CounterweightSpec], exclude: set[int], eps: float
) -> list[tuple[int, float]]:
    """(edge, radius) of every concave edge of the fused throw that is not in ``exclude``
    (the pin and journal circles), on the side (z < 0: web 1) of a counterweight with a
    ``fillet_radius``.  Before the shaft fillets the only other concave edges of the
    fused solid are those circles: webs are convex prisms, pin and journals cylinders.
    An edge on a side without such a counterweight is not tested."""
    out: list[tuple[int, float]] = []
    if not any(cw.fillet_radius for cw in cws.values()):
        return out
    edges = set()
    for _, face in gmsh.model.getBoundary([(3, solid)], combined=False, oriented=False):
        for _, e in gmsh.model.getBoundary([(2, face)], combined=False, oriented=False):
            edges.add(abs(e))
    for e in sorted(edges - set(exclude)):
        z = float(_midpoint(gmsh, e)[0][2])
        cw = cws.get(1 if z < 0 else 2)
        if cw is not None and cw.fillet_radius and _concave(gmsh, solid, e, eps):
            out.append((e, cw.fillet_radius))
    return out


def fill_tools(occ, g: CrankGeometry, cw: CounterweightSpec, web_prism, sector_prism, big: float) -> list[int]:
    """Fragment tools that put a counterweight's fillet material into its subdomain: the
    slab of the counterweight's thickness plus its fillet radius (towards the crankpin),
    less the web prism, the sector prism and a cylinder round the crankpin of radius
    ``d_p/2 + r_f``.  In the throw, that region holds only the material the fillets
    add.  ``web_prism(occ, g, z0)``, ``sector_prism(occ, cw, z0)``: the builders of
    ``throw.py``."""
    if cw.fillet_radius is None:
        raise ValueError("a counterweight without a fillet_radius has no fillet material")
    zp = g.crankpin_length / 2
    zw = zp + g.web_thickness
    h = cw.thickness + cw.fillet_radius
    z0 = -zw if cw.web == 1 else zw - h
    box = occ.addBox(-big, -big, z0, 2 * big, 2 * big, h)
    web = web_prism(occ, g, -zw if cw.web == 1 else zp)
    pin = occ.addCylinder(
        0.0, g.crank_radius, -big, 0.0, 0.0, 2 * big, g.crankpin_diameter / 2 + g.crankpin_fillet * (1 + 1e-6) + 1e-9
    )
    sector = sector_prism(occ, cw, -zw if cw.web == 1 else zw - cw.thickness)
    out, _ = occ.cut([(3, box)], [(3, web), (3, pin), (3, sector)])
    return [tag for dim, tag in out if dim == 3]


def fillet_faces(gmsh, fill_volumes: set[int], keep: set[int]) -> list[int]:
    """Curved outer faces of the fillet pieces (a face is outer when it bounds one kept
    volume; the planar caps on the web faces are left out)."""
    count: dict[int, int] = {}
    for v in keep:
        for _, s in gmsh.model.getBoundary([(3, v)], oriented=False, combined=False):
            count[abs(s)] = count.get(abs(s), 0) + 1
    out = set()
    for v in fill_volumes:
        for _, s in gmsh.model.getBoundary([(3, v)], oriented=False, combined=False):
            if count.get(abs(s)) == 1 and gmsh.model.getType(2, abs(s)) != "Plane":
                out.add(abs(s))
    return sorted(out)
