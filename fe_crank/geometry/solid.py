"""The OpenCASCADE solid of one crank throw, before it is split into named parts.

Built in the THROW frame (``fe_crank.geometry.spec``): journal halves, two webs
(convex hull of two circles), the crankpin, annular-sector counterweights on ``-y``
(turned by their ``offset`` from ``-y`` towards ``+x``),
fused into one solid; real fillets (OCC rolling-ball) on the four circular edges
where pin and journals meet the webs (undercut fillets as ring-plus-torus booleans),
the counterweight transition fillets; an optional oil bore cut through the pin.
:func:`throw_solid` returns that one solid (``fe_crank.geometry.throw.add_throw``
splits and names it; a STEP export of it is what a CAD system would hold).

Call inside :func:`fe_crank.gmsh_io.gmsh_session`; gmsh tags do not leave this package.
"""

from __future__ import annotations

import math

from fe_crank.errors import GeometryError
from fe_crank.geometry.checks import check_geometry
from fe_crank.geometry.cw_fillet import junction_edges
from fe_crank.geometry.spec import CounterweightSpec, CrankGeometry, ThrowSpec

BIG = 10.0  # m: tools larger than any crank


def _arc_points(occ, cx, cy, z, r, a0, a1, max_step=math.pi / 2):
    """Points on a circle (centre cx, cy) from angle a0 to a1 (angles from +y towards +x).

    OpenCASCADE parametrises each circle (and the cylinder a web's arc is extruded to)
    from its +x direction (a = 90 deg here): a face whose arc runs across that direction
    straddles the periodic surface's seam, and gmsh then takes the edge at the arc's end
    for a seam and fails on an uncut throw ("the 1D mesh seems not to be forming a
    closed loop"; measured on the pear web of geometry/inline4.toml without a
    counterweight).  The arc is therefore broken at that direction, then into steps of
    at most ``max_step``.
    """
    lo, hi = min(a0, a1), max(a0, a1)
    seams = [
        a
        for k in range(
            math.floor((lo - math.pi / 2) / (2 * math.pi)), math.ceil((hi - math.pi / 2) / (2 * math.pi)) + 1
        )
        if lo + 1e-9 < (a := math.pi / 2 + 2 * math.pi * k) < hi - 1e-9
    ]
    breaks = [a0, *(seams if a1 > a0 else seams[::-1]), a1]
    angles = [a0]
    for b0, b1 in zip(breaks[:-1], breaks[1:], strict=True):
        n = max(1, math.ceil(abs(b1 - b0) / max_step - 1e-12))
        angles += [b0 + (b1 - b0) * k / n for k in range(1, n + 1)]
    return [occ.addPoint(cx + r * math.sin(a), cy + r * math.cos(a), z) for a in angles]


def _arc_curves(occ, pts, centre):
    return [occ.addCircleArc(pts[i], centre, pts[i + 1]) for i in range(len(pts) - 1)]


def web_prism(occ, g: CrankGeometry, z0: float) -> int:
    """Hull of circle (0,0,ra) and circle (0,R,rb) in the plane z0, extruded by the web thickness."""
    ra, rb, R = g.web.journal_end_radius, g.web.pin_end_radius, g.crank_radius
    t = g.web_thickness
    if abs(ra - rb) >= R:  # one circle contains the other: the web is a disc
        if ra >= rb:
            return occ.addCylinder(0, 0, z0, 0, 0, t, ra)
        return occ.addCylinder(0, R, z0, 0, 0, t, rb)
    phi = math.asin((ra - rb) / R)
    # tangent normal u = (cos phi, sin phi) on +x; angle of u from +y: 90 deg - phi
    a_u = math.pi / 2 - phi
    ca = occ.addPoint(0, 0, z0)
    cb = occ.addPoint(0, R, z0)
    # journal end: from +x tangent point round through -y to the -x tangent point
    pa = _arc_points(occ, 0, 0, z0, ra, a_u, 2 * math.pi - a_u)
    # pin end: from -x tangent point round through +y to the +x tangent point
    pb = _arc_points(occ, 0, R, z0, rb, -a_u, a_u)
    curves = _arc_curves(occ, pa, ca)
    curves.append(occ.addLine(pa[-1], pb[0]))
    curves += _arc_curves(occ, pb, cb)
    curves.append(occ.addLine(pb[-1], pa[0]))
    loop = occ.addCurveLoop(curves)
    face = occ.addPlaneSurface([loop])
    out = occ.extrude([(2, face)], 0, 0, t)
    return next(tag for dim, tag in out if dim == 3)


def sector_prism(occ, cw: CounterweightSpec, z0: float) -> int:
    """Annular sector r2..r1 within angle/2 of its mid-line (-y turned by its offset towards
    +x: at ``pi - offset`` from +y towards +x) in the plane z0, extruded by its thickness."""
    mid = math.pi - cw.offset
    a0, a1 = mid - cw.angle / 2, mid + cw.angle / 2
    c = occ.addPoint(0, 0, z0)
    po = _arc_points(occ, 0, 0, z0, cw.outer_radius, a0, a1)
    pi = _arc_points(occ, 0, 0, z0, cw.inner_radius, a1, a0)
    curves = _arc_curves(occ, po, c)
    curves.append(occ.addLine(po[-1], pi[0]))
    curves += _arc_curves(occ, pi, c)
    curves.append(occ.addLine(pi[-1], po[0]))
    face = occ.addPlaneSurface([occ.addCurveLoop(curves)])
    out = occ.extrude([(2, face)], 0, 0, cw.thickness)
    return next(tag for dim, tag in out if dim == 3)


def _edges_on_circle(gmsh, cx, cy, z, r, tol):
    out = []
    for _, c in gmsh.model.getEntities(1):
        lo, hi = gmsh.model.getParametrizationBounds(1, c)
        ok = True
        for s in (0.0, 0.3, 0.7, 1.0):
            x, y, zz = gmsh.model.getValue(1, c, [lo[0] + s * (hi[0] - lo[0])])
            if abs(zz - z) > tol or abs(math.hypot(x - cx, y - cy) - r) > tol:
                ok = False
                break
        if ok:
            out.append(c)
    return out


def _cut_to_fundamental(occ, solid: int, cut: tuple[int, ...], g: CrankGeometry) -> int:
    """Intersect the solid with ``x >= 0`` (axis 0 in ``cut``) and ``z <= 0`` (axis 2)."""
    if not cut:
        return solid
    if not set(cut) <= {0, 2}:
        raise ValueError(f"cut axes must be 0 (x = 0) and/or 2 (z = 0), got {cut}")
    x0 = 0.0 if 0 in cut else -BIG
    z1 = 0.0 if 2 in cut else BIG
    box = occ.addBox(x0, -BIG, -BIG, BIG - x0, 2 * BIG, z1 + BIG)
    out, _ = occ.intersect([(3, solid)], [(3, box)])
    occ.synchronize()
    if len(out) != 1:
        raise GeometryError(f"cutting the throw to its fundamental part gave {len(out)} solids", file=g.file or None)
    return out[0][1]


def throw_solid(
    g: CrankGeometry, throw: ThrowSpec | str | int | None = None, *, cut: tuple[int, ...] = ()
) -> tuple[int, dict[int, CounterweightSpec]]:
    """Build the one solid of a throw in the current gmsh model (OCC kernel).

    ``cut``: as in ``add_throw`` (the solid is cut to its fundamental part).  Returns the
    solid's volume tag and the throw's counterweights by web.  Raises ``GeometryError``
    for impossible input (checked before any OCC call) and when OpenCASCADE cannot build
    the fillets.
    """
    import gmsh

    check_geometry(g)
    spec = throw if isinstance(throw, ThrowSpec) else g.throw(throw)
    occ = gmsh.model.occ
    R = g.crank_radius
    rp, rj = g.crankpin_diameter / 2, g.journal_diameter / 2
    zp = g.crankpin_length / 2
    t = g.web_thickness
    L = g.journal_length
    zw = zp + t  # outer web faces at +-zw
    tol = 1e-6 * max(1.0, R)

    parts = []
    parts.append(occ.addCylinder(0, 0, -zw - L, 0, 0, L, rj))  # journal_1
    parts.append(occ.addCylinder(0, 0, zw, 0, 0, L, rj))  # journal_2
    parts.append(occ.addCylinder(0, R, -zp, 0, 0, 2 * zp, rp))  # crankpin
    parts.append(web_prism(occ, g, -zw))
    parts.append(web_prism(occ, g, zp))
    cws = {}
    for cw in spec.counterweights:
        z0 = -zw if cw.web == 1 else zw - cw.thickness
        tag = sector_prism(occ, cw, z0)
        parts.append(tag)
        cws[cw.web] = cw
    fused, _ = occ.fuse([(3, parts[0])], [(3, p) for p in parts[1:]])
    occ.synchronize()
    if len(fused) != 1:
        raise GeometryError(
            f"the throw's parts do not form one solid ({len(fused)} pieces)", file=g.file or None, key="throws"
        )
    solid = fused[0][1]

    fillets = []
    radii = []
    undercuts = []
    circles = set()
    # (radius, undercut, (cx, cy, z of the web face, cylinder radius), direction from the face into the pin/journal)
    for rf, u, (cx, cy, z, r), side in (
        (g.crankpin_fillet, g.crankpin_undercut, (0.0, R, -zp, rp), +1.0),
        (g.crankpin_fillet, g.crankpin_undercut, (0.0, R, zp, rp), -1.0),
        (g.journal_fillet, g.journal_undercut, (0.0, 0.0, -zw, rj), -1.0),
        (g.journal_fillet, g.journal_undercut, (0.0, 0.0, zw, rj), +1.0),
    ):
        if rf <= 0:
            continue
        if u > 0:
            undercuts.append((rf, u, cx, cy, z, r, side))
            continue
        edges = _edges_on_circle(gmsh, cx, cy, z, r, tol)
        circles.update(edges)
        if not edges:
            raise GeometryError(
                f"no edge found where the fillet of {rf * 1e3:g} mm should go (z = {z * 1e3:g} mm)", file=g.file or None
            )
        fillets += edges
        radii += [rf] * len(edges)
    # counterweight-to-web transition fillets (cw_fillet.py): every other concave edge
    for _, _, cx, cy, z, r, _ in undercuts:
        circles.update(_edges_on_circle(gmsh, cx, cy, z, r, tol))
    cw_edges = junction_edges(gmsh, solid, cws, circles, 1e-3 * min(g.web_thickness, R))
    fillets += [e for e, _ in cw_edges]
    radii += [rc for _, rc in cw_edges]
    if fillets:
        try:
            out = occ.fillet([solid], fillets, radii, removeVolume=True)
        except Exception as exc:  # gmsh raises a bare Exception from OpenCASCADE
            raise GeometryError(f"OpenCASCADE could not build the fillets: {exc}", file=g.file or None) from None
        occ.synchronize()
        if len(out) != 1:
            raise GeometryError(f"filleting gave {len(out)} solids instead of one", file=g.file or None)
        solid = out[0][1]
    for rf, u, cx, cy, z, r, side in undercuts:
        # undercut fillet: add the ring between the cylinder and the arc's centre plane, then
        # cut the torus of the arc (it removes the spandrel's outside and the groove in the web)
        zc = z + side * (rf - u)
        ring = occ.addCylinder(cx, cy, min(z, zc), 0, 0, abs(zc - z), r + rf)
        out, _ = occ.fuse([(3, solid)], [(3, ring)])
        torus = occ.addTorus(cx, cy, zc, r + rf, rf)
        out, _ = occ.cut(out, [(3, torus)])
        occ.synchronize()
        if len(out) != 1:
            raise GeometryError(f"the undercut fillet at z = {z * 1e3:g} mm split the solid", file=g.file or None)
        solid = out[0][1]

    if g.oil_bore is not None:
        a = g.oil_bore.angle
        dx, dy = math.sin(a), math.cos(a)
        if 0 in cut:  # a bore along x or y (the caller checked): exact direction, exactly symmetric
            dx, dy = float(round(dx)), float(round(dy))
        half = 2.0 * rp
        bore = occ.addCylinder(
            -half * dx, R - half * dy, 0.0, 2 * half * dx, 2 * half * dy, 0.0, g.oil_bore.diameter / 2
        )
        out, _ = occ.cut([(3, solid)], [(3, bore)])
        occ.synchronize()
        solid = out[0][1]

    solid = _cut_to_fundamental(occ, solid, cut, g)

    return solid, cws
