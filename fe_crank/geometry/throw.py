"""One crank throw as an OpenCASCADE solid in gmsh, with named physical groups.

Built in the THROW frame (``fe_crank.geometry.spec``): journal halves, two webs
(convex hull of two circles), the crankpin, annular-sector counterweights on ``-y``,
fused into one solid; real fillets (OCC rolling-ball) on the four circular edges
where pin and journals meet the webs; an optional oil bore cut through the pin.
The fused solid is then split (boolean fragment with slab and sector tools) into
conformal volumes, so the mesh is one connected body whose subdomains are the
parts of the throw.  Fillet volumes belong to the pin / journal they round.

Call :func:`add_throw` inside :func:`fe_crank.gmsh_io.gmsh_session`; gmsh tags do
not leave this package.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from fe_crank.errors import GeometryError
from fe_crank.geometry.checks import check_geometry
from fe_crank.geometry.cw_fillet import fill_tools, fillet_faces, junction_edges
from fe_crank.geometry.spec import CounterweightSpec, CrankGeometry, ThrowSpec
from fe_crank.geometry.surfaces import classify_surfaces

_BIG = 10.0  # m: tools larger than any crank


@dataclass(frozen=True)
class ThrowModel:
    """Internal: the gmsh entity tags of a built throw (used by ``fe_crank.mesh``)."""

    volumes: dict[str, list[int]]
    surfaces: dict[str, list[int]]
    fillet_radii: dict[str, float]


def _arc_points(occ, cx, cy, z, r, a0, a1, max_step=math.pi / 2):
    """Points on a circle (centre cx, cy) from angle a0 to a1 (angles from +y towards +x)."""
    n = max(1, math.ceil(abs(a1 - a0) / max_step - 1e-12))
    pts = []
    for k in range(n + 1):
        a = a0 + (a1 - a0) * k / n
        pts.append(occ.addPoint(cx + r * math.sin(a), cy + r * math.cos(a), z))
    return pts


def _arc_curves(occ, pts, centre):
    return [occ.addCircleArc(pts[i], centre, pts[i + 1]) for i in range(len(pts) - 1)]


def _web_prism(occ, g: CrankGeometry, z0: float) -> int:
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


def _sector_prism(occ, cw: CounterweightSpec, z0: float) -> int:
    """Annular sector r2..r1 within angle/2 of -y in the plane z0, extruded by its thickness."""
    a0, a1 = math.pi - cw.angle / 2, math.pi + cw.angle / 2
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
    x0 = 0.0 if 0 in cut else -_BIG
    z1 = 0.0 if 2 in cut else _BIG
    box = occ.addBox(x0, -_BIG, -_BIG, _BIG - x0, 2 * _BIG, z1 + _BIG)
    out, _ = occ.intersect([(3, solid)], [(3, box)])
    occ.synchronize()
    if len(out) != 1:
        raise GeometryError(f"cutting the throw to its fundamental part gave {len(out)} solids", file=g.file or None)
    return out[0][1]


def add_throw(g: CrankGeometry, throw: ThrowSpec | str | int | None = None, *, cut: tuple[int, ...] = ()) -> ThrowModel:
    """Build one throw in the current gmsh model (OCC kernel) and name its groups.

    ``cut``: axes of mirror planes (0: ``x = 0``, 2: ``z = 0``) across which the caller
    knows the throw to be symmetric (``fe_crank.mesh.planes``); the solid is then cut to
    its fundamental part ``x >= 0`` / ``z <= 0`` before it is split and named, so only the
    ``_1`` groups exist for a cut at ``z = 0``, and the cut faces are left unnamed.
    Returns the entity tags by group name (internal to fe-crank's meshing).
    Raises ``GeometryError`` for impossible input (checked before any OCC call) and
    when OpenCASCADE cannot build the fillets.
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
    parts.append(_web_prism(occ, g, -zw))
    parts.append(_web_prism(occ, g, zp))
    cws = {}
    for cw in spec.counterweights:
        z0 = -zw if cw.web == 1 else zw - cw.thickness
        tag = _sector_prism(occ, cw, z0)
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

    # split into subdomains: slabs at the web faces, counterweight sectors
    tools = [
        occ.addBox(-_BIG, -_BIG, -_BIG, 2 * _BIG, 2 * _BIG, _BIG - zw),  # z < -zw
        occ.addBox(-_BIG, -_BIG, -zw, 2 * _BIG, 2 * _BIG, t),  # web 1 slab
        occ.addBox(-_BIG, -_BIG, -zp, 2 * _BIG, 2 * _BIG, 2 * zp),  # pin slab
        occ.addBox(-_BIG, -_BIG, zp, 2 * _BIG, 2 * _BIG, t),  # web 2 slab
    ]
    cw_tools = []  # (web, tag, is the sector itself)
    for web, cw in cws.items():
        z0 = -zw if web == 1 else zw - cw.thickness
        cw_tools.append((web, _sector_prism(occ, cw, z0), True))
        if cw.fillet_radius:
            cw_tools += [(web, tag, False) for tag in fill_tools(occ, g, cw, _web_prism, _sector_prism, _BIG)]
    _, out_map = occ.fragment([(3, solid)], [(3, x) for x in tools + [tag for _, tag, _ in cw_tools]])
    occ.synchronize()
    keep = {tag for dim, tag in out_map[0] if dim == 3}
    drop = [(3, tag) for dim, tag in gmsh.model.getEntities(3) if tag not in keep]
    occ.remove(drop, recursive=True)
    occ.synchronize()

    volumes: dict[str, list[int]] = {k: [] for k in ("journal_1", "web_1", "crankpin", "web_2", "journal_2")}
    for cwweb in sorted(cws):
        volumes[f"counterweight_{cwweb}"] = []
    cw_pieces = {web: set() for web in cws}
    sector_pieces = set()
    for i, (web, _, sector) in enumerate(cw_tools):
        got = {tag for dim, tag in out_map[1 + len(tools) + i] if dim == 3} & keep
        cw_pieces[web] |= got
        sector_pieces |= got if sector else set()
    for tag in sorted(keep):
        in_cw = [web for web, s in cw_pieces.items() if tag in s]
        if in_cw:
            volumes[f"counterweight_{in_cw[0]}"].append(tag)
            continue
        z = occ.getCenterOfMass(3, tag)[2]
        if z < -zw:
            volumes["journal_1"].append(tag)
        elif z < -zp:
            volumes["web_1"].append(tag)
        elif z <= zp:
            volumes["crankpin"].append(tag)
        elif z <= zw:
            volumes["web_2"].append(tag)
        else:
            volumes["journal_2"].append(tag)

    if 2 in cut:  # only the front half (z <= 0) was built
        volumes = {k: v for k, v in volumes.items() if not (k.endswith("_2") and not v)}
    surfaces = classify_surfaces(gmsh, g, keep, tol, cut=cut)
    for web in sorted(cws):
        if cws[web].fillet_radius and not (2 in cut and web == 2):  # web 2 is the mirror image of web 1
            faces = fillet_faces(gmsh, cw_pieces[web] - sector_pieces, keep)
            if not faces:
                raise GeometryError(
                    f"the counterweight fillet on web {web} left no surface",
                    file=g.file or None,
                    key="counterweight.fillet_radius",
                )
            surfaces[f"counterweight_fillet_{web}"] = faces
    for name, tags in volumes.items():
        if not tags:
            raise GeometryError(f"building the throw left no volume for {name!r}", file=g.file or None)
        gmsh.model.addPhysicalGroup(3, tags, name=name)
    for name, tags in surfaces.items():
        gmsh.model.addPhysicalGroup(2, tags, name=name)
    fillet_radii = {}
    if g.crankpin_fillet > 0:
        fillet_radii.update(crankpin_fillet_1=g.crankpin_fillet, crankpin_fillet_2=g.crankpin_fillet)
    if g.journal_fillet > 0:
        fillet_radii.update(journal_fillet_1=g.journal_fillet, journal_fillet_2=g.journal_fillet)
    return ThrowModel(volumes, surfaces, fillet_radii)
