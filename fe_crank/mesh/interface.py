"""End faces of a throw meshed identically under rotation, so that throws join conformingly.

In the whole-shaft model (``fe_crank.fe.shaft``) every throw is the same mesh turned to its
angle; adjacent throws meet at the main-bearing centre plane, where the end face of one
(``end_2``) and the end face of the next (``end_1``) must carry the same nodes.  Throw k+1 is
turned by ``a_(k+1) - a_k`` against throw k, so the end face's mesh must map onto itself
under that rotation.  ``imprint_sectors`` splits each end face into ``n`` equal sectors
(radial edges from the centre to the rim, the first through the rim's existing vertex)
and makes every sector's surface mesh a rotated copy of the first one (gmsh periodic
meshes, an affine map per sector), and the rear face's sectors translated copies of the
front face's: the face's mesh is then invariant under rotations by multiples of
``2 pi / n`` bit for bit up to the round-off of the map (about 1e-12 m, snapped when the
throws are joined).  ``sectors_for(angles)`` is the smallest ``n`` whose multiples of
``2 pi / n`` hold every angle between adjacent throws.
"""

from __future__ import annotations

import math

from fe_crank.errors import MeshError

#: most sectors an end face is split into (15 deg): finer angles cannot be joined
MAX_SECTORS = 24


def sectors_for(angles, tol: float = 1e-9) -> int:
    """Smallest n (1 .. ``MAX_SECTORS``) with every angle a multiple of 2 pi / n, or 0."""
    for n in range(1, MAX_SECTORS + 1):
        if all(abs(math.remainder(a * n / (2 * math.pi), 1.0)) < tol * max(n, 1) for a in angles):
            return n
    return 0


def _rotation(a: float, dz: float = 0.0) -> list[float]:
    """4x4 affine map (row-major) turning by ``a`` from +y towards +x and shifting by dz."""
    c, s = math.cos(a), math.sin(a)
    return [c, s, 0.0, 0.0, -s, c, 0.0, 0.0, 0.0, 0.0, 1.0, dz, 0.0, 0.0, 0.0, 1.0]


def _angle(gmsh, dim: int, tag: int) -> float:
    x, y, _ = gmsh.model.occ.getCenterOfMass(dim, tag) if dim else gmsh.model.getValue(0, tag, [])
    return math.atan2(x, y) % (2 * math.pi)


def _groups(gmsh) -> list[tuple[int, str, list[int]]]:
    out = []
    for dim, ptag in gmsh.model.getPhysicalGroups():
        name = gmsh.model.getPhysicalName(dim, ptag)
        out.append((dim, name, [int(t) for t in gmsh.model.getEntitiesForPhysicalGroup(dim, ptag)]))
    return out


def _signature(gmsh, tag: int) -> tuple[float, ...]:
    """Area and area centroid of a face: what identifies it after OCC renumbered it."""
    return (gmsh.model.occ.getMass(2, tag), *gmsh.model.occ.getCenterOfMass(2, tag))


def _renumbered(gmsh, before: dict[int, tuple[float, ...]], sectors: set[int]) -> dict[int, int]:
    """Old tag -> new tag of the named faces the fragment renumbered (the lateral face of
    the journal, whose rim edge was split), found by area and centroid."""
    now = {t for _, t in gmsh.model.getEntities(2)}
    out = {}
    for old, sig in before.items():
        if old in now:
            continue
        scale = max(abs(v) for v in sig[1:]) + math.sqrt(sig[0])
        match = [
            t
            for t in now - sectors
            if max(abs(a - b) for a, b in zip(_signature(gmsh, t), sig)) < 1e-9 * max(scale, sig[0])
        ]
        if len(match) != 1:
            raise MeshError("splitting the end faces into sectors lost a named face")
        out[old] = match[0]
    return out


def _sector_edges(gmsh, faces: list[int], rim_angle: float, n: int) -> tuple[list[int], list[int]]:
    """The radial lines (line i at ``rim_angle + 2 pi i / n``) and the rim arcs (arc i
    bounding sector i) of one split end face, each list in angular order."""
    edges = sorted({abs(t) for f in faces for _, t in gmsh.model.getBoundary([(2, f)], oriented=False)})
    step = 2 * math.pi / n

    def slot(tag: int, offset: float) -> int:
        k = ((_angle(gmsh, 1, tag) - rim_angle) / step - offset) % n
        i = round(k) % n
        if abs(k - round(k)) > 1e-6:
            return -1
        return i

    lines, arcs = [-1] * n, [-1] * n
    for e in edges:
        if gmsh.model.getType(1, e) == "Line":
            i = slot(e, 0.0)
            lines[i] = e if i >= 0 else lines[i]
        else:
            i = slot(e, 0.5)
            arcs[i] = e if i >= 0 else arcs[i]
    if -1 in lines or -1 in arcs:
        raise MeshError("the sectors of a split end face do not have one radial line and one rim arc each")
    return lines, arcs


def _fix_edge_masters(gmsh, new_faces, present, z_of, rim_angle: float, n: int) -> None:
    """Give every sector edge one master: radial line 0 and rim arc 0 of the first face.

    Setting a face periodic makes gmsh pair its edges with the master face's edges itself;
    with two sectors each radial line is the image of the other under the half turn, and
    which of the two gmsh made the master depended on the order of objects in memory,
    which changed the surface mesh from run to run.  The masters stated explicitly here
    make the edge meshes, and so every mesh built on them, the same on every run."""
    z0 = z_of[present[0]]
    first_lines, first_arcs = _sector_edges(gmsh, new_faces[present[0]], rim_angle, n)
    for e in (first_lines[0], first_arcs[0]):  # a master of its own (no longer another's slave)
        gmsh.model.mesh.setPeriodic(1, [e], [e], _rotation(0.0))
    for name in present:
        lines, arcs = _sector_edges(gmsh, new_faces[name], rim_angle, n)
        for i in range(n):
            tfo = _rotation(2 * math.pi * i / n, z_of[name] - z0)
            if lines[i] != first_lines[0]:
                gmsh.model.mesh.setPeriodic(1, [lines[i]], [first_lines[0]], tfo)
            if arcs[i] != first_arcs[0]:
                gmsh.model.mesh.setPeriodic(1, [arcs[i]], [first_arcs[0]], tfo)


def imprint_sectors(gmsh, model, n: int, faces=("end_1", "end_2")):
    """Split the named end faces of the built throw ``model`` (``geometry.throw.ThrowModel``)
    into ``n`` sectors with rotated-copy meshes (module doc); returns the model with its
    ``surfaces`` updated (the physical groups are rebuilt with the new faces)."""
    occ = gmsh.model.occ
    present = [f for f in faces if f in model.surfaces]
    if n <= 1 or not present:
        return model
    groups = _groups(gmsh)
    other = {t for dim, name, tags in groups if dim == 2 and name not in present for t in tags}
    before = {t: _signature(gmsh, t) for t in other}
    rim_angle, new_faces, z_of = None, {}, {}
    for name in present:
        tags = model.surfaces[name]
        if len(tags) != 1:
            raise MeshError(f"the end face {name!r} is {len(tags)} faces; it must be one disc to be split")
        face = tags[0]
        z = occ.getCenterOfMass(2, face)[2]
        rim = [t for d, t in gmsh.model.getBoundary([(2, face)], combined=False, recursive=True) if d == 0]
        angles = sorted({round(_angle(gmsh, 0, t), 12) for t in rim})
        if len(angles) != 1 or (rim_angle is not None and abs(angles[0] - rim_angle) > 1e-9):
            raise MeshError(f"the end face {name!r} is not a disc with one rim vertex (vertices at {angles})")
        rim_angle = angles[0]
        radius = math.hypot(*gmsh.model.getValue(0, rim[0], [])[:2])
        volumes = [int(t) for t in gmsh.model.getAdjacencies(2, face)[0]]
        centre = occ.addPoint(0.0, 0.0, z)
        lines = []
        for i in range(n):
            a = rim_angle + 2 * math.pi * i / n
            p = occ.addPoint(radius * math.sin(a), radius * math.cos(a), z)
            lines.append(occ.addLine(centre, p))
        occ.fragment([(3, v) for v in volumes], [(1, line) for line in lines])
        occ.synchronize()
        found = []
        for _, s in gmsh.model.getEntities(2):
            if s in other or gmsh.model.getType(2, s) != "Plane":
                continue
            cx, cy, cz = occ.getCenterOfMass(2, s)
            if abs(cz - z) < 1e-9 * max(1.0, radius) and math.hypot(cx, cy) < radius:
                found.append(s)
        if len(found) != n:
            raise MeshError(f"splitting the end face {name!r} into {n} sectors gave {len(found)} faces")
        new_faces[name] = sorted(found, key=lambda s: (_angle(gmsh, 2, s) - rim_angle) % (2 * math.pi))
        z_of[name] = z
    renamed = _renumbered(gmsh, before, {s for f in new_faces.values() for s in f})
    groups = [(d, name, [renamed.get(t, t) for t in tags] if d == 2 else tags) for d, name, tags in groups]
    master = new_faces[present[0]][0]
    z0 = z_of[present[0]]
    for name in present:
        for i, s in enumerate(new_faces[name]):
            if s != master:
                gmsh.model.mesh.setPeriodic(2, [s], [master], _rotation(2 * math.pi * i / n, z_of[name] - z0))
    assert rim_angle is not None  # set by the first face (present is not empty)
    _fix_edge_masters(gmsh, new_faces, present, z_of, rim_angle, n)
    gmsh.model.removePhysicalGroups()
    for name in dict.fromkeys(name for _, name, _ in groups):  # first-seen order: the same tags on every run
        gmsh.model.removePhysicalName(name)
    for dim, name, tags in groups:
        ptag = gmsh.model.addPhysicalGroup(dim, new_faces.get(name, tags))
        gmsh.model.setPhysicalName(dim, ptag, name)
    surfaces = dict(model.surfaces)
    surfaces.update(new_faces)
    return type(model)(model.volumes, surfaces, model.fillet_radii)
