"""One crank throw as an OpenCASCADE solid in gmsh, with named physical groups.

The solid of the throw (``fe_crank.geometry.solid.throw_solid``: journal halves, webs,
crankpin, counterweights, fillets, oil bore, in the THROW frame of
``fe_crank.geometry.spec``) is split (boolean fragment with slab and sector tools) into
conformal volumes, so the mesh is one connected body whose subdomains are the
parts of the throw.  Fillet volumes belong to the pin / journal they round.

Call :func:`add_throw` inside :func:`fe_crank.gmsh_io.gmsh_session`; gmsh tags do
not leave this package.
"""

from __future__ import annotations

from dataclasses import dataclass

from fe_crank.errors import GeometryError
from fe_crank.geometry.cw_fillet import fill_tools, fillet_faces
from fe_crank.geometry.solid import BIG, sector_prism, throw_solid, web_prism
from fe_crank.geometry.spec import CrankGeometry, ThrowSpec
from fe_crank.geometry.surfaces import classify_surfaces


@dataclass(frozen=True)
class ThrowModel:
    """Internal: the gmsh entity tags of a built throw (used by ``fe_crank.mesh``)."""

    volumes: dict[str, list[int]]
    surfaces: dict[str, list[int]]
    fillet_radii: dict[str, float]


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

    occ = gmsh.model.occ
    solid, cws = throw_solid(g, throw, cut=cut)
    R = g.crank_radius
    zp = g.crankpin_length / 2
    t = g.web_thickness
    zw = zp + t  # outer web faces at +-zw
    tol = 1e-6 * max(1.0, R)

    # split into subdomains: slabs at the web faces, counterweight sectors
    tools = [
        occ.addBox(-BIG, -BIG, -BIG, 2 * BIG, 2 * BIG, BIG - zw),  # z < -zw
        occ.addBox(-BIG, -BIG, -zw, 2 * BIG, 2 * BIG, t),  # web 1 slab
        occ.addBox(-BIG, -BIG, -zp, 2 * BIG, 2 * BIG, 2 * zp),  # pin slab
        occ.addBox(-BIG, -BIG, zp, 2 * BIG, 2 * BIG, t),  # web 2 slab
    ]
    cw_tools = []  # (web, tag, is the sector itself)
    for web, cw in cws.items():
        z0 = -zw if web == 1 else zw - cw.thickness
        cw_tools.append((web, sector_prism(occ, cw, z0), True))
        if cw.fillet_radius:
            cw_tools += [(web, tag, False) for tag in fill_tools(occ, g, cw, web_prism, sector_prism, BIG)]
    _, out_map = occ.fragment([(3, solid)], [(3, x) for x in tools + [tag for _, tag, _ in cw_tools]])
    occ.synchronize()
    keep = {tag for dim, tag in out_map[0] if dim == 3}
    drop = [(3, tag) for dim, tag in gmsh.model.getEntities(3) if tag not in keep]
    occ.remove(drop, recursive=True)
    occ.synchronize()

    volumes: dict[str, list[int]] = {k: [] for k in ("journal_1", "web_1", "crankpin", "web_2", "journal_2")}
    for cwweb in sorted(cws):
        volumes[f"counterweight_{cwweb}"] = []
    cw_pieces: dict[int, set[int]] = {web: set() for web in cws}
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
    fillet_radii: dict[str, float] = {}
    if g.crankpin_fillet > 0:
        fillet_radii.update(crankpin_fillet_1=g.crankpin_fillet, crankpin_fillet_2=g.crankpin_fillet)
    if g.journal_fillet > 0:
        fillet_radii.update(journal_fillet_1=g.journal_fillet, journal_fillet_2=g.journal_fillet)
    return ThrowModel(volumes, surfaces, fillet_radii)
