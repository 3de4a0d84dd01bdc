"""The mesh of a hot-spot zone: the throw's solid inside a ball round a hot spot, meshed
with the throw mesher's own size fields at a given fillet size (``mesh_zone``).

The solid comes from a ``ZoneSolid``: how to build the throw in the open gmsh session as
for its own mesh, and that mesher's size fields.  A parametric throw's
(``parametric_solid``) is ``geometry.throw.add_throw`` (the same solid, the same
subdomains) with ``mesh.sizing.set_size_fields``; a drawn throw's is the CAD mesher's
(``fe_crank.cad.zone.cad_zone_solid``).  The throw is fragmented with the ball, and
everything outside the ball removed.  The
zone's boundary faces are then named after the throw's: a face on the ball is the cut
(``CUT``); any other face takes the name of the nearest named boundary facet of the
assessed mesh (``names``: sample points on it and their boundary names, "" for an unnamed
face), so that the zone's fillets, oil bore, crankpin and journal surfaces are known
without tracking OpenCASCADE's face numbers through the boolean (the point a face is
named by: its surface's point closest to its centre of mass, or, where that falls off
the face, into a hole of it, the point of the face farthest from its edges).  The size fields are
the throw mesher's at the options given (fillets at ``r / fillet_divisions``, the oil
bore at ``bore_divisions``, the counterweights' transition fillets, the webs), so an element of the zone near a fillet is the size the
full refined mesh has there.  The tetrahedra are improved by gmsh's own optimiser, not by
Netgen's (``generate(..., netgen=False)``: four fifths of the zone's 3D meshing time), with
the throw mesher's checks, and its quadratic elements made straight-sided up to a scaled
Jacobian of ``ZONE_STRAIGHTEN_BELOW`` (the throw mesher's ``STRAIGHTEN_BELOW`` is 0.1): without
Netgen's pass more elements on a curved face keep a poorly curved shape, whose nodal stress
overshoots; the 1D meshes place their nodes at gmsh's integration accuracy
``LC_INTEGRATION_PRECISION``.  A set of balls gmsh cannot mesh raises ``ZoneMeshError``
naming the ball nearest the first surface left unmeshed.  ``mirror_zone`` reflects a
zone mesh across ``z = 0`` (the zone of the mirrored ball of a symmetric throw).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.spatial import cKDTree
from skfem import Mesh

from fe_crank.errors import MeshError
from fe_crank.geometry.spec import CrankGeometry, ThrowSpec
from fe_crank.mesh.generate import generate
from fe_crank.mesh.mirror import FLIP_TET10, swap_side
from fe_crank.mesh.options import MeshOptions
from fe_crank.mesh.quality import fillet_max_edge
from fe_crank.mesh.sizing import counterweight_fillet_radius, set_size_fields

#: the name of the zone's cut boundary (its faces on the ball)
CUT = "zone_cut"
#: gmsh's relative accuracy of the integral of 1 / size along a curve that places the nodes of
#: its 1D mesh (``Mesh.LcIntegrationPrecision``; gmsh's default 1e-9, kept by the throw
#: mesher): at 1e-6 the zones' 1D meshing is about a sixth of its time at 1e-9 (single-cylinder
#: throw, its zones at r/8: 2.2 s -> 0.35 s of CPU), the zones' node counts within 0.3 %
LC_INTEGRATION_PRECISION = 1e-6
#: a zone's quadratic elements of gmsh minSJ at or below this are made straight-sided.  Measured
#: on the drawn single-cylinder throw at ``test`` (benchmarks/verification/mesh_scatter.py): at
#: the throw mesher's 0.1, two of five round-off realisations of the drawing gave the shaft
#: fillets' r/2 peak 5.0 % and 5.7 % above the whole throw re-meshed (a poorly curved element
#: at the fillet), at 0.3 both within 0.5 %.  At ``coarse`` r/8 only the counterweight fillets'
#: peak moved (drawn throw 59.9 -> 58.7 MPa, its zones meshed with Netgen's optimiser 58.7; the
#: parametric throw under torque at r/6 13.03 -> 12.96 MPa, the full re-mesh 12.95), at no
#: meshing time (docs/performance.md)
ZONE_STRAIGHTEN_BELOW = 0.3
#: the balls' turn about an oblique axis (rad)
TILT, TILT_AXIS = 0.7, (0.6, 0.5, 0.2)


class ZoneMeshError(MeshError):
    """gmsh could not mesh a set of balls; ``ball``: the index of the ball nearest the first
    surface it left unmeshed (the likely cause: a ball grazing an edge of the solid),
    None when that is not known."""

    def __init__(self, message: str, ball: int | None = None):
        super().__init__(message)
        self.ball = ball


def _culprit(gmsh, cs: np.ndarray) -> int | None:
    """After a failed ``generate``: the ball whose centre is nearest the first surface (in
    gmsh's meshing order, by tag) left without elements (curves are not asked: a sphere's
    degenerate pole curves have none), else the first volume left without elements."""
    for dim in (2, 3):
        for _, tag in sorted(gmsh.model.getEntities(dim)):
            if not len(gmsh.model.mesh.getElementTypes(dim, tag)):
                box = np.asarray(gmsh.model.getBoundingBox(dim, tag))
                mid = 0.5 * (box[:3] + box[3:])
                return int(np.argmin(np.linalg.norm(cs - mid[None], axis=1)))
    return None


@dataclass(frozen=True)
class ZoneMesh:
    """A zone's quadratic mesh (scikit-fem ``MeshTet2``, boundaries named as the throw's and ``CUT``)."""

    mesh: Mesh
    centres: tuple[tuple[float, float, float], ...]  # m, the hot spots the balls are centred on
    radii: tuple[float, ...]  # m, the balls' radii
    options: MeshOptions
    fillet_max_edge: dict[str, float]  # m, longest edge on each fillet in the zone
    seconds: float
    #: its mirror image across z = 0 is a zone of the study too (``mirror_zone``): the balls
    #: of its pieces lie off the plane and the throw is its own mirror image
    mirrored: bool = False


@dataclass(frozen=True)
class SolidParts:
    """A throw's named gmsh entities: {subdomain: volume tags}, {boundary name: face tags},
    {fillet surface: radius (m)}."""

    volumes: dict[str, list[int]]
    surfaces: dict[str, list[int]]
    fillet_radii: dict[str, float]


@dataclass(frozen=True)
class ZoneSolid:
    """The solid the zones of a throw are cut from.

    ``build(gmsh)``: builds the whole throw in the open session's OpenCASCADE model, in the
    throw frame, with nothing else in the model, and returns its ``SolidParts``;
    ``size_fields(gmsh, parts, options)``: sets the throw mesher's size fields on the
    zone's ``parts`` at ``options``; ``lengths``: the length a zone radius is measured in
    on each hot-spot surface that is no shaft fillet (``counterweight_fillet_<web>``: its
    fillet radius; ``oil_bore``: the bore's diameter), m; ``throw`` and ``label``: the
    throw's and the model's names in messages."""

    throw: str
    label: str
    build: Callable[[Any], SolidParts]
    size_fields: Callable[[Any, SolidParts, MeshOptions], object]
    lengths: dict[str, float]


def parametric_solid(geometry: CrankGeometry, spec: ThrowSpec) -> ZoneSolid:
    """The ``ZoneSolid`` of the parametric throw ``spec`` of ``geometry``
    (``geometry.throw.add_throw``, ``mesh.sizing.set_size_fields``)."""

    def build(gmsh) -> SolidParts:
        from fe_crank.geometry.throw import add_throw

        model = add_throw(geometry, spec)
        for name in (*model.volumes, *model.surfaces):  # the throw's groups: the zone names its own
            gmsh.model.removePhysicalName(name)
        gmsh.model.removePhysicalGroups()
        return SolidParts(model.volumes, model.surfaces, model.fillet_radii)

    def size_fields(gmsh, parts: SolidParts, options: MeshOptions) -> float:
        return set_size_fields(gmsh, geometry, parts.surfaces, parts.fillet_radii, options, parts.volumes)

    lengths = {}
    for web in (1, 2):
        if any(cw.web == web and cw.fillet_radius for t in geometry.throws for cw in t.counterweights):
            lengths[f"counterweight_fillet_{web}"] = counterweight_fillet_radius(geometry, web)
    if geometry.oil_bore is not None:  # its outlet's stress field reaches further than a fillet's
        lengths["oil_bore"] = geometry.oil_bore.diameter
    return ZoneSolid(spec.name, geometry.name, build, size_fields, lengths)


#: parameter grid (per direction, the bounds left out) searched for a face's naming point
NAMING_GRID = 9


def _on_face(gmsh, s: int, p: np.ndarray) -> np.ndarray:
    """The point face ``s`` is named by: ``p``, the point of its surface closest to its
    centre of mass, where that lies on the face; else (a face round a hole, e.g. the pin's
    surface round the oil bore's outlet: the point falls in the hole, next to the hole's
    own faces) the point of a ``NAMING_GRID`` x ``NAMING_GRID`` grid of its parameters that
    lies on the face farthest from its edges."""
    if gmsh.model.isInside(2, s, p.tolist()):
        return p
    lo, hi = gmsh.model.getParametrizationBounds(2, s)
    curves = sorted({abs(c) for _, c in gmsh.model.getBoundary([(2, s)], oriented=False)})
    best, where = -1.0, p
    for u in np.linspace(lo[0], hi[0], NAMING_GRID + 2)[1:-1]:
        for v in np.linspace(lo[1], hi[1], NAMING_GRID + 2)[1:-1]:
            if not gmsh.model.isInside(2, s, [float(u), float(v)], parametric=True):
                continue
            x = np.asarray(gmsh.model.getValue(2, s, [float(u), float(v)]))
            d = min(
                (
                    float(np.linalg.norm(np.asarray(gmsh.model.getClosestPoint(1, c, x.tolist())[0]) - x))
                    for c in curves
                ),
                default=0.0,
            )
            if d > best:
                best, where = d, x
    return where


def _build(gmsh, solid: ZoneSolid, cs: np.ndarray, rs: np.ndarray, names) -> SolidParts:
    """The throw inside the balls in the open session, its volumes and faces named (module
    docstring)."""
    pts, labels = names
    tree = cKDTree(np.asarray(pts, float))
    model = solid.build(gmsh)
    occ = gmsh.model.occ
    vols = [(3, t) for _, t in gmsh.model.getEntities(3)]
    balls = []
    for c, r in zip(cs, rs):
        ball = occ.addSphere(float(c[0]), float(c[1]), float(c[2]), float(r))
        # the sphere's poles and seam turned off the throw's planes of symmetry and axes,
        # where they would cut its edges at a point (a degenerate loop for the mesher)
        occ.rotate([(3, ball)], float(c[0]), float(c[1]), float(c[2]), *TILT_AXIS, TILT)
        balls.append((3, ball))
    if len(balls) > 1:  # their union: no faces of one ball inside another
        balls, _ = occ.fuse(balls[:1], balls[1:])
    _, out_map = occ.fragment(vols, balls)
    occ.synchronize()
    in_ball = {t for m in out_map[len(vols) :] for d, t in m if d == 3}
    volumes: dict[str, list[int]] = {}
    keep: set[int] = set()
    for (_, old), pieces in zip(vols, out_map[: len(vols)]):
        name = next(n for n, tags in model.volumes.items() if old in tags)
        got = sorted(t for d, t in pieces if d == 3 and t in in_ball)
        volumes.setdefault(name, []).extend(got)
        keep |= set(got)
    if not keep:
        raise MeshError(f"the hot-spot zones hold no part of throw {solid.throw!r}")
    drop = [(3, t) for _, t in gmsh.model.getEntities(3) if t not in keep]
    occ.remove(drop, recursive=True)
    occ.synchronize()
    volumes = {k: v for k, v in volumes.items() if v}
    surfaces: dict[str, list[int]] = {}
    faces = gmsh.model.getBoundary([(3, t) for t in sorted(keep)], combined=True, oriented=False)
    for _, s in faces:
        s = abs(s)
        com = np.asarray(occ.getCenterOfMass(2, s))
        p = np.asarray(gmsh.model.getClosestPoint(2, s, com.tolist())[0])
        on_ball = np.abs(np.linalg.norm(p[None] - cs, axis=1) - rs) < 1e-6 * rs
        if gmsh.model.getType(2, s) == "Sphere" and on_ball.any():
            name = CUT
        else:
            name = labels[int(tree.query(_on_face(gmsh, s, p))[1])]
        surfaces.setdefault(name or "free", []).append(s)
    surfaces = {k: sorted(set(v)) for k, v in surfaces.items()}
    if CUT not in surfaces:
        raise MeshError(f"the hot-spot zones hold the whole throw {solid.throw!r}")
    return SolidParts(volumes, surfaces, model.fillet_radii)


def _pieces(gmsh, volumes: dict[str, list[int]]) -> list[list[int]]:
    """The zone's connected pieces (volume tags sharing a face), each sorted, in the order of
    their smallest tag."""
    tags = sorted(t for v in volumes.values() for t in v)
    parent = {t: t for t in tags}

    def root(t):
        while parent[t] != t:
            parent[t] = parent[parent[t]]
            t = parent[t]
        return t

    owner: dict[int, int] = {}
    for t in tags:
        for _, f in gmsh.model.getBoundary([(3, t)], oriented=False):
            f = abs(f)
            if f in owner:
                parent[root(t)] = root(owner[f])
            else:
                owner[f] = t
    out: dict[int, list[int]] = {}
    for t in tags:
        out.setdefault(root(t), []).append(t)
    return sorted(out.values(), key=lambda v: v[0])


def _node_count(gmsh, vols: list[int]) -> int:
    """The number of (quadratic) mesh nodes of the volumes ``vols``."""
    nodes = [np.asarray(gmsh.model.mesh.getElements(3, t)[2][0]) for t in vols]
    return int(np.unique(np.concatenate(nodes)).size) if nodes else 0


def _groups(counts: list[int], budget: float | None) -> list[list[int]]:
    """The pieces (their node counts ``counts``) packed into groups of at most ``budget``
    nodes (first fit, largest first; a larger piece alone), each group's pieces in order."""
    if budget is None:
        return [list(range(len(counts)))]
    order = sorted(range(len(counts)), key=lambda i: (-counts[i], i))
    groups: list[list[int]] = []
    load: list[int] = []
    for i in order:
        for g, n in enumerate(load):
            if n + counts[i] <= budget:
                groups[g].append(i)
                load[g] += counts[i]
                break
        else:
            groups.append([i])
            load.append(counts[i])
    return sorted((sorted(g) for g in groups), key=lambda g: g[0])


def _piece_kind(gmsh, piece: list[int], cs: np.ndarray, rs: np.ndarray, mirrored) -> bool:
    """The ``mirrored`` flag of the ball a piece lies in: the ball nearest (distance to its
    sphere, inside negative) the centre of mass of the piece's first volume (a ball of one
    kind overlaps none of the other, so any point of the piece names its kind)."""
    com = np.asarray(gmsh.model.occ.getCenterOfMass(3, piece[0]))
    return bool(mirrored[int(np.argmin(np.linalg.norm(cs - com[None], axis=1) - rs))])


def _convert(gmsh, parts: SolidParts, vols: list[int], cs, rs, options, t0, mirrored: bool = False) -> ZoneMesh:
    """The zone mesh of the volumes ``vols`` of the meshed model, its groups named as the zone's."""
    from fe_crank.gmsh_io import model_to_skfem

    chosen = set(vols)
    own = {abs(f) for _, f in gmsh.model.getBoundary([(3, t) for t in vols], combined=True, oriented=False)}
    for dim, tag in gmsh.model.getPhysicalGroups():  # the previous group's names, then its groups
        gmsh.model.removePhysicalName(gmsh.model.getPhysicalName(dim, tag))
    gmsh.model.removePhysicalGroups()
    for name, tags in parts.volumes.items():
        if got := [t for t in tags if t in chosen]:
            gmsh.model.addPhysicalGroup(3, got, name=name)
    for name, tags in parts.surfaces.items():
        if got := [t for t in tags if t in own]:
            gmsh.model.addPhysicalGroup(2, got, name=name)
    mesh = model_to_skfem(volumes=vols)
    fillets = [n for n in parts.fillet_radii if n in (mesh.boundaries or {})]
    return ZoneMesh(
        mesh=mesh,
        centres=tuple((float(c[0]), float(c[1]), float(c[2])) for c in cs),
        radii=tuple(float(r) for r in rs),
        options=options,
        fillet_max_edge=fillet_max_edge(mesh, fillets),
        seconds=time.perf_counter() - t0,
        mirrored=mirrored,
    )


def _facet_keys(mesh, tri: np.ndarray) -> np.ndarray:
    """One integer key per vertex triple (k, 3) of ``mesh`` (order-free)."""
    nv = np.int64(mesh.nvertices)
    t = np.sort(tri, axis=1).astype(np.int64)
    return (t[:, 0] * nv + t[:, 1]) * nv + t[:, 2]


def mirror_zone(zone: ZoneMesh) -> ZoneMesh:
    """The mirror image across ``z = 0`` of a zone mesh: node ``i`` of the image is node
    ``i`` of the zone with its ``z`` negated (exactly: the image of the image is the zone
    bit for bit), each element's nodes in the order that keeps its Jacobian positive
    (``mesh.mirror.FLIP_TET10``), the named boundaries and subdomains carried over with the
    front and rear names exchanged (``journal_1 <-> journal_2``, ...: ``mesh.mirror.swap_side``),
    the balls' centres mirrored.  It is the mesh the mirrored ball of a symmetric throw would
    have if its own mesh were made as the mirror image of the zone's (as the throw's own
    mesh is, ``mesh.mirror``)."""
    from skfem import MeshTet2

    mesh = zone.mesh
    P = np.array(mesh.doflocs, dtype=float)
    P[2] = -P[2]
    T = np.asarray(mesh.dofs.element_dofs, dtype=np.int64)[FLIP_TET10]
    image = MeshTet2(P, T.astype(np.int32))
    if image.nvertices != mesh.nvertices or not np.array_equal(image.t, mesh.t[FLIP_TET10[:4]]):
        raise MeshError("the mirror image of a hot-spot zone does not keep its node numbering")
    keys = _facet_keys(image, image.facets.T)
    order = np.argsort(keys)
    bnd = {}
    for name, idx in (mesh.boundaries or {}).items():
        want = _facet_keys(mesh, mesh.facets[:, np.asarray(idx, dtype=np.int64)].T)
        pos = np.minimum(np.searchsorted(keys[order], want), keys.size - 1)
        if np.any(keys[order][pos] != want):
            raise MeshError("the mirror image of a hot-spot zone lost a boundary facet")
        bnd[swap_side(name)] = np.sort(order[pos]).astype(np.int32)
    if bnd:
        image = image.with_boundaries(bnd)
    sub = {swap_side(name): np.asarray(idx) for name, idx in (mesh.subdomains or {}).items()}
    if sub:
        image = image.with_subdomains(sub)
    return ZoneMesh(
        mesh=image,
        centres=tuple((c[0], c[1], -c[2]) for c in zone.centres),
        radii=zone.radii,
        options=zone.options,
        fillet_max_edge={swap_side(k): v for k, v in zone.fillet_max_edge.items()},
        seconds=0.0,
        mirrored=False,
    )


def mesh_zone_levels(
    geometry: CrankGeometry,
    spec: ThrowSpec,
    levels: list[MeshOptions],
    centres,
    radii,
    names: tuple[np.ndarray, list[str]],
    *,
    group_nodes: float | None = None,
) -> list[list[ZoneMesh]]:
    """Every level of :func:`iter_solid_zone_levels` of the parametric throw ``spec`` of ``geometry``."""
    return list(
        iter_solid_zone_levels(parametric_solid(geometry, spec), levels, centres, radii, names, group_nodes=group_nodes)
    )


def iter_solid_zone_levels(
    solid: ZoneSolid,
    levels: list[MeshOptions],
    centres,
    radii,
    names: tuple[np.ndarray, list[str]],
    *,
    group_nodes: float | None = None,
    mirrored=None,
) -> Iterator[list[ZoneMesh]]:
    """Mesh the throw of ``solid`` inside the balls (``centres`` (k, 3),
    ``radii`` (k,), m; overlapping balls make one zone of their union) at each of the
    mesh options ``levels``: the solid is cut once, and only the size fields change from one
    level to the next.  ``names``: (points (n, 3) on the assessed mesh's boundary, the
    boundary name of each) to name the zone's faces (module docstring).

    Each level's mesh is returned in groups of its connected pieces (the union of a set of
    overlapping balls is a piece), each group of at most ``group_nodes`` mesh nodes (a
    larger piece alone; None: one group), so that each group can be solved as its own
    model: the pieces share no node, so their systems are independent and the groups'
    solutions are the whole mesh's.

    ``mirrored`` (k,) bool, default none: the balls whose zone's mirror image across
    ``z = 0`` is a zone too (``ZoneMesh.mirrored``, ``mirror_zone``); a ball so marked must
    overlap no ball that is not, and the groups hold pieces of one kind only.

    Each level is yielded as soon as it is meshed, the gmsh session held open (by the
    thread iterating) until the last."""
    from fe_crank.gmsh_io import gmsh_session

    cs = np.atleast_2d(np.asarray(centres, float))
    rs = np.asarray(radii, float)
    with gmsh_session() as gmsh:
        gmsh.option.setNumber("Mesh.LcIntegrationPrecision", LC_INTEGRATION_PRECISION)
        parts = _build(gmsh, solid, cs, rs, names)
        pieces = _pieces(gmsh, parts.volumes)
        kinds = [False] * len(pieces) if mirrored is None else [_piece_kind(gmsh, p, cs, rs, mirrored) for p in pieces]
        for options in levels:
            t0 = time.perf_counter()
            gmsh.model.mesh.clear()
            for tag in gmsh.model.mesh.field.list():
                gmsh.model.mesh.field.remove(tag)
            solid.size_fields(gmsh, parts, options)
            try:
                generate(gmsh, solid.throw, solid.label, options, netgen=False, straighten=ZONE_STRAIGHTEN_BELOW)
            except MeshError as exc:
                raise ZoneMeshError(str(exc), _culprit(gmsh, cs) if len(cs) > 1 else 0) from None
            counts = [_node_count(gmsh, p) for p in pieces]
            level = []
            for kind in sorted(set(kinds)):  # the pieces of one kind packed together
                of_kind = [i for i, k in enumerate(kinds) if k == kind]
                for g in _groups([counts[i] for i in of_kind], group_nodes):
                    vols = sorted(t for i in g for t in pieces[of_kind[i]])
                    level.append(_convert(gmsh, parts, vols, cs, rs, options, t0, kind))
            yield level


def mesh_zone(
    geometry: CrankGeometry,
    spec: ThrowSpec,
    options: MeshOptions,
    centres,
    radii,
    names: tuple[np.ndarray, list[str]],
) -> ZoneMesh:
    """Mesh the throw ``spec`` of ``geometry`` inside the balls (``centres`` (k, 3),
    ``radii`` (k,), m; overlapping balls make one zone of their union) at ``options``, in
    one model and one mesh; ``names`` as for :func:`mesh_zone_levels`."""
    return mesh_zone_levels(geometry, spec, [options], centres, radii, names)[0][0]


__all__ = [
    "CUT",
    "SolidParts",
    "ZoneMesh",
    "ZoneMeshError",
    "ZoneSolid",
    "iter_solid_zone_levels",
    "mesh_zone",
    "mesh_zone_levels",
    "mirror_zone",
    "parametric_solid",
]
