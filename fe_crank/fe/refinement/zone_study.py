"""The hot-spot convergence study by zones: only the hot spots are refined.

``fe.refinement.convergence.fillet_convergence`` re-meshes and re-solves the whole throw at each
finer fillet size.  ``zone_convergence`` gives the same levels from submodels
(``fe.refinement.zone``): the first level is the assessed mesh's own solution, as there; for each
finer level, every hot spot is meshed again inside a ball of radius
``ZONE_RADIUS`` x its fillet radius (the oil bore: its diameter) round the assessed mesh's
peak (``mesh.zone``: cut from the throw's solid, parametric or drawn, ``zone_solid``; the
throw mesher's size fields at that level's fillet size), driven
on its cut by the assessed solution of every load set (the balls cut from the throw
once, every level meshed in that one model, its connected pieces solved in groups of at
most ``GROUP_FRACTION`` x the assessed model's nodes, one factorisation a group, each freed
before the next), and its peak read at the hot-spot surface's nodes within ``REACH`` x
the zone radius of the centre.  On a throw that is its own mirror image across ``z = 0``
(``mirror_symmetric``) the balls off the plane are folded onto ``z > 0`` (``fold_spots``):
a mirror pair of hot spots is one zone, meshed and factorised once and solved for itself
and for its mirror image (``mesh.zone.mirror_zone``, ``fe.refinement.zone.ZoneSystem``).

Hot spots: for each hot-spot family (shaft fillets; counterweight fillets; oil bore) and
each load set, the peak node of every surface of the family whose assessed peak is at
least ``CANDIDATE`` x the family's peak (so a surface that refinement could lift above the
governing one by up to 1/CANDIDATE - 1 = 18 % is followed too); centres closer than half
a zone radius to an earlier one are merged.  The level's value of a family and load set
is the largest over the zones, as the full study's is over the surfaces.
"""

from __future__ import annotations

import dataclasses
import logging
import queue
import threading
import time
from collections.abc import Iterator

import numpy as np

from fe_crank.cad.config import CadInput
from fe_crank.errors import MeshError
from fe_crank.fe.core.loads import PinPressure, pin_pressure_load, pin_surface
from fe_crank.fe.core.stress import stress_at_selected_nodes, von_mises
from fe_crank.fe.refinement.levels import (
    COUNTERWEIGHT_PREFIX,
    FACTORS,
    OIL_BORE_PREFIX,
    TOLERANCE,
    ConvergenceLevel,
    ConvergenceStudy,
    level_peaks,
)
from fe_crank.fe.refinement.zone import Interpolator, ZoneSystem, boundary_samples, zone_peaks
from fe_crank.fe.throw.options import Material
from fe_crank.fe.throw.pin_directions import pin_direction, unit_force
from fe_crank.fe.throw.surface_peaks import COUNTERWEIGHT_FILLETS, FILLETS, OIL_BORE
from fe_crank.fe.throw.unit_cases import UnitSolutions
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.mesh.mirror import swap_side
from fe_crank.mesh.options import MeshOptions
from fe_crank.mesh.planes import symmetry_planes
from fe_crank.mesh.types import ThrowMesh
from fe_crank.mesh.zone import (
    ZoneMesh,
    ZoneMeshError,
    ZoneSolid,
    iter_solid_zone_levels,
    mirror_zone,
    parametric_solid,
)

log = logging.getLogger(__name__)

#: zone radius / the hot spot's fillet radius (docs/fe.md: the cut-boundary error at 2 and 3 radii)
ZONE_RADIUS = 3.0
#: the zone's peak is read within REACH x its radius of the centre
REACH = 0.5
#: surfaces followed: assessed peak >= CANDIDATE x the family's assessed peak
CANDIDATE = 0.85
FAMILIES = (("", FILLETS), (COUNTERWEIGHT_PREFIX, COUNTERWEIGHT_FILLETS), (OIL_BORE_PREFIX, OIL_BORE))


@dataclasses.dataclass(frozen=True)
class HotSpot:
    """A zone's centre (m), radius (m) and the surface whose assessed peak it is."""

    centre: tuple[float, float, float]
    radius: float
    surface: str


def zone_solid(geometry: CrankGeometry | CadInput, throw_mesh: ThrowMesh) -> ZoneSolid:
    """The solid the zones of the assessed mesh ``throw_mesh`` are cut from: its parametric
    throw (``mesh.zone.parametric_solid``) or its drawn one (``cad.zone.cad_zone_solid``)."""
    if isinstance(geometry, CadInput):
        from fe_crank.cad.zone import cad_zone_solid

        return cad_zone_solid(geometry, throw_mesh.throw, throw_mesh.options)
    return parametric_solid(geometry, geometry.throw(throw_mesh.throw))


def hot_spot_radius(solid: ZoneSolid, throw_mesh: ThrowMesh, surface: str) -> float:
    """The length the zone radius is measured in: the fillet's radius, the oil bore's
    diameter (its outlet's stress field reaches further than a fillet's)."""
    if surface in throw_mesh.fillet_radii:
        return throw_mesh.fillet_radii[surface]
    return solid.lengths[surface]


def hot_spots(
    solid: ZoneSolid,
    throw_mesh: ThrowMesh,
    unit_solutions: UnitSolutions,
    fields: dict[str, np.ndarray],
    *,
    zone_radius: float = ZONE_RADIUS,
) -> list[HotSpot]:
    """The zones of the study (module docstring), largest assessed peak first."""
    mesh, basis = unit_solutions.mesh, unit_solutions.system.basis
    groups = {
        name: basis.get_dofs(mesh.boundaries[name]).all()
        for _, names in FAMILIES
        for name in names
        if name in (mesh.boundaries or {})
    }
    ids = np.unique(np.concatenate(list(groups.values())))
    mat = unit_solutions.material
    s = stress_at_selected_nodes(
        mesh, list(fields.values()), mat.youngs_modulus, mat.poisson_ratio, ids, dofs=basis.dofs
    )
    found: list[tuple[float, HotSpot]] = []
    for j in range(len(fields)):
        vm = von_mises(s[j])
        for _, names in FAMILIES:
            peaks = {}
            for name in names:
                if name in groups:
                    v = vm[np.searchsorted(ids, groups[name])]
                    peaks[name] = (float(v.max()), int(groups[name][int(np.argmax(v))]))
            if not peaks:
                continue
            top = max(v for v, _ in peaks.values())
            for name, (v, node) in peaks.items():
                if v >= CANDIDATE * top:
                    x = unit_solutions.points[:, node]
                    r = zone_radius * hot_spot_radius(solid, throw_mesh, name)
                    found.append((v, HotSpot((float(x[0]), float(x[1]), float(x[2])), r, name)))
    found.sort(key=lambda t: -t[0])
    out: list[HotSpot] = []
    for _, h in found:
        if all(np.linalg.norm(np.subtract(h.centre, o.centre)) > 0.5 * min(h.radius, o.radius) for o in out):
            out.append(h)
    return out


def mirror_symmetric(geometry: CrankGeometry | CadInput, throw_mesh: ThrowMesh) -> bool:
    """Is the throw's solid its own mirror image across its mid-plane ``z = 0``?  A
    parametric throw: when its specification makes it so (``mesh.planes.symmetry_planes``);
    a drawn one: when its own mesh was made as a mirrored half (``ThrowMesh.symmetry``: the
    CAD mesher mirrors only a throw whose B-rep it found symmetric)."""
    if isinstance(geometry, CadInput):
        return 2 in throw_mesh.symmetry
    return 2 in symmetry_planes(geometry, throw_mesh.throw)


#: folded balls (below) whose centres are closer than this x their radius are one ball,
#: grown to hold both
FOLD_MERGE = 0.05


def _distance(a: HotSpot, b: HotSpot) -> float:
    return float(np.linalg.norm(np.subtract(a.centre, b.centre)))


def _overlap(a: HotSpot, b: HotSpot) -> bool:
    return _distance(a, b) < a.radius + b.radius


def _mirror(h: HotSpot) -> HotSpot:
    return HotSpot((h.centre[0], h.centre[1], -h.centre[2]), h.radius, swap_side(h.surface))


def fold_spots(spots: list[HotSpot], symmetric: bool) -> tuple[list[HotSpot], list[bool], list[int]]:
    """The balls to cut for ``spots`` of a throw that is (``symmetric``) or is not its own
    mirror image across ``z = 0``: (balls, whether each ball's zone serves its mirror image
    too, the ball of each spot).

    Not symmetric: the spots' own balls.  Symmetric: every spot is folded onto ``z > 0`` (a
    spot below the plane replaced by its mirror image), and folded balls whose centres lie
    within ``FOLD_MERGE`` x the radius of each other are one ball, grown to hold both.  Each
    folded ball's zone is solved for itself and for its mirror image, whose mesh is the
    zone's mirrored (``mesh.zone.mirror_zone``).  A spot keeps its own ball, meshed and
    solved alone as without the fold (``central``), where its ball reaches the plane; where
    its folded ball would overlap another folded ball none of whose spots' balls its own
    overlaps (the fold would join into one zone two balls that were apart, a union the
    study without the fold never meshes: measured at ``test``, the union of two
    journal-fillet balls 0.47 radius apart gave a fillet peak 21 % above either ball's
    alone); and where its ball or mirrored ball overlaps the ball of a central spot;
    repeated until none is added.  So every spot lies in its own ball, in a zone or in its image, and no
    zone overlaps another of the other kind."""
    if not symmetric:
        return list(spots), [False] * len(spots), list(range(len(spots)))
    n = len(spots)
    central = [abs(h.centre[2]) <= h.radius for h in spots]
    while True:
        for i in range(n):  # a ball or mirrored ball overlapping a central one: central
            if not central[i] and any(
                central[j] and (_overlap(spots[i], spots[j]) or _overlap(_mirror(spots[i]), spots[j])) for j in range(n)
            ):
                central[i] = True
        balls, mirrored, owner = _folded(spots, central)
        members = [[i for i in range(n) if owner[i] == k] for k in range(len(balls))]
        joined = {
            i
            for a in range(len(balls))
            for b in range(a + 1, len(balls))
            if mirrored[a]
            and mirrored[b]
            and _overlap(balls[a], balls[b])
            # apart before the fold: no spot of the one overlaps a spot of the other
            and not any(_overlap(spots[i], spots[j]) for i in members[a] for j in members[b])
            for i in members[a] + members[b]
        }
        if not joined:
            break
        for i in joined:
            central[i] = True
    cut = [b for b, m in zip(balls, mirrored) if not m]
    if any(_overlap(b, c) or _overlap(_mirror(b), c) for b, m in zip(balls, mirrored) if m for c in cut):
        return list(spots), [False] * n, list(range(n))  # a grown ball reached a central one
    return balls, mirrored, owner


def _folded(spots: list[HotSpot], central: list[bool]) -> tuple[list[HotSpot], list[bool], list[int]]:
    """``fold_spots``'s balls for the ``central`` spots given: theirs, then the others'
    folded and merged."""
    n = len(spots)
    balls = [h for i, h in enumerate(spots) if central[i]]
    owner = [-1] * n
    for k, i in enumerate(i for i in range(n) if central[i]):
        owner[i] = k
    mirrored = [False] * len(balls)
    for i, h in enumerate(spots):
        if central[i]:
            continue
        f = h if h.centre[2] > 0 else _mirror(h)
        for k in range(len(balls)):
            b = balls[k]
            d = _distance(b, f)
            if mirrored[k] and d <= FOLD_MERGE * min(b.radius, f.radius):
                balls[k] = dataclasses.replace(b, radius=max(b.radius, f.radius + d))
                owner[i] = k
                break
        else:
            owner[i] = len(balls)
            balls.append(f)
            mirrored.append(True)
    return balls, mirrored, owner


#: a ball whose zone gmsh cannot mesh is tried again this much larger (a ball that grazes an
#: edge of the solid leaves sliver faces)
RETRY_GROWTH = 1.07
#: a level's zones are solved in groups of connected pieces of at most this fraction of the
#: assessed model's nodes each (a larger piece alone): the largest factorisation of the
#: study is a group's, not the level's (docs/fe.md, "Only the hot spots refined")
GROUP_FRACTION = 0.5


def level_meshes(
    solid: ZoneSolid, levels, spots: list[HotSpot], samples, group_nodes=None, grown=frozenset(), mirrored=None
) -> list[list[ZoneMesh]]:
    """The zones of every level (``levels``: their mesh options), in groups
    (``mesh.zone.iter_solid_zone_levels``): every ball cut from the throw in one gmsh model, once,
    and re-meshed per level.  Where gmsh cannot mesh that model at some level, the ball
    nearest the first curve or surface it left unmeshed (``ZoneMeshError.ball``) is made
    ``RETRY_GROWTH`` larger and the model cut and meshed again (once per ball: ``grown``,
    the indices already grown); failing that, the balls split into two halves, each done
    the same way.  ``mirrored``: per ball, its zone serves its mirror image too
    (``fold_spots``; default none)."""
    radii = [h.radius * (RETRY_GROWTH if i in grown else 1.0) for i, h in enumerate(spots)]
    try:
        return list(
            iter_solid_zone_levels(
                solid, levels, [h.centre for h in spots], radii, samples, group_nodes=group_nodes, mirrored=mirrored
            )
        )
    except ZoneMeshError as exc:
        log.info("the hot-spot zones on %s: %s", ", ".join(h.surface for h in spots), exc)
        if exc.ball is not None and exc.ball not in grown:
            log.info("the zone on %s tried %g x larger", spots[exc.ball].surface, RETRY_GROWTH)
            return level_meshes(solid, levels, spots, samples, group_nodes, grown | {exc.ball}, mirrored)
        if len(spots) == 1:
            raise
    half = len(spots) // 2
    m1, m2 = (None, None) if mirrored is None else (mirrored[:half], mirrored[half:])
    first = level_meshes(solid, levels, spots[:half], samples, group_nodes, frozenset(i for i in grown if i < half), m1)
    second = level_meshes(
        solid, levels, spots[half:], samples, group_nodes, frozenset(i - half for i in grown if i >= half), m2
    )
    return [a + b for a, b in zip(first, second)]


def holds(zones: list[ZoneMesh], spot: HotSpot) -> bool:
    """Whether a level's zones hold the hot spot ``spot``: a node of its surface within
    ``REACH`` x its radius of its centre."""
    for zm in zones:
        mesh = zm.mesh
        if spot.surface in (mesh.boundaries or {}):
            nodes = np.unique(mesh.facets[:, mesh.boundaries[spot.surface]])
            d = np.linalg.norm(mesh.p[:, nodes] - np.asarray(spot.centre)[:, None], axis=0)
            if d.size and d.min() <= REACH * spot.radius:
                return True
    return False


def held_level_meshes(
    solid: ZoneSolid, levels, spots: list[HotSpot], samples, group_nodes=None, mirrored=None
) -> list[list[ZoneMesh]]:
    """``level_meshes`` checked: the balls that the solid's cut left out without an error
    (OpenCASCADE's fragment of a ball in a degenerate position can give no volume) are made
    ``RETRY_GROWTH`` larger and cut and meshed again on their own, once, their zones added to
    each level's (a zone solved alone is exact where it overlaps another: each is a
    submodel of its own); a hot spot still not held is a ``MeshError`` (its peak would be
    missed, not refined)."""
    meshes = level_meshes(solid, levels, spots, samples, group_nodes, mirrored=mirrored)
    lost = [i for i, h in enumerate(spots) if not all(holds(zones, h) for zones in meshes)]
    if not lost:
        return meshes
    log.info("the zones on %s left out: tried %g x larger", ", ".join(spots[i].surface for i in lost), RETRY_GROWTH)
    grown = [dataclasses.replace(spots[i], radius=spots[i].radius * RETRY_GROWTH) for i in lost]
    again = level_meshes(
        solid, levels, grown, samples, group_nodes, mirrored=None if mirrored is None else [mirrored[i] for i in lost]
    )
    still = [h.surface for h in grown if not all(holds(zones, h) for zones in again)]
    if still:
        raise MeshError(f"the hot-spot zones on {', '.join(still)} could not be cut from the throw")
    return [a + b for a, b in zip(meshes, again)]


class Unpipelined(Exception):
    """``pipelined_levels`` could not give every level from its one cut (a ball gmsh could
    not mesh or that the cut left out): the levels are to be meshed by ``held_level_meshes``."""


def pipelined_levels(
    solid: ZoneSolid, levels, spots: list[HotSpot], samples, group_nodes=None, mirrored=None
) -> Iterator[list[ZoneMesh]]:
    """The zones of every level as ``held_level_meshes`` gives them where its first cut
    meshes every level and holds every spot -- the same gmsh calls in the same order, so
    the same meshes -- each level yielded as soon as gmsh has meshed it: gmsh runs in a
    thread of its own (its calls release the interpreter's lock), so that the caller
    solves a level while the next is meshed.  Raises ``Unpipelined`` where that cut does
    not do (the caller then meshes by ``held_level_meshes``, its retries included)."""
    out: queue.Queue = queue.Queue()

    def produce() -> None:
        try:
            for zones in iter_solid_zone_levels(
                solid,
                levels,
                [h.centre for h in spots],
                [h.radius for h in spots],
                samples,
                group_nodes=group_nodes,
                mirrored=mirrored,
            ):
                out.put(("level", zones))
        except ZoneMeshError as exc:
            out.put(("retry", exc))
        except BaseException as exc:  # raised again in the caller's thread
            out.put(("error", exc))
        else:
            out.put(("done", None))

    worker = threading.Thread(target=produce, name="fe-crank-zone-mesh", daemon=True)
    worker.start()
    try:
        while True:
            kind, value = out.get()
            if kind == "done":
                return
            if kind == "error":
                raise value
            if kind == "retry":  # logged where ``held_level_meshes`` meets it again
                raise Unpipelined from value
            if not all(holds(value, h) for h in spots):
                raise Unpipelined
            yield value
    finally:
        worker.join()


def pins_of(unit_solutions: UnitSolutions, loads: dict[str, dict[str, float]]) -> dict[str, PinPressure]:
    """The pin pressure of every pin unit case of ``loads``: the solved unit cases' own
    (``UnitSolutions.pin``), the others built alike on the same crankpin surface (a load set
    of another model, ``zone_convergence``'s ``driven``)."""
    pins = dict(unit_solutions.pin)
    missing = sorted({c for w in loads.values() for c in w if pin_direction(c) is not None} - set(pins))
    if missing:
        basis, opts = unit_solutions.system.basis, unit_solutions.options
        surface = pin_surface(basis, opts.pin_boundary)
        for name in missing:
            pins[name] = pin_pressure_load(
                basis, unit_force(name), boundary=opts.pin_boundary, half_angle=opts.pin_half_angle, surface=surface
            )[1]
    return pins


def zone_convergence(
    geometry: CrankGeometry | CadInput,
    material: Material,
    throw_mesh: ThrowMesh,
    unit_solutions: UnitSolutions,
    loads: dict[str, dict[str, float]],
    *,
    factors=FACTORS,
    tolerance: float = TOLERANCE,
    zone_radius: float = ZONE_RADIUS,
    driven: dict[str, tuple[np.ndarray, dict[str, float]]] | None = None,
) -> ConvergenceStudy:
    """The study's levels r/(n f), f in ``factors`` (the first 1: the assessed mesh
    ``throw_mesh`` and its solution ``unit_solutions``, which must hold every unit case of
    ``loads``), the finer ones from the hot-spot zones (module docstring) of the throw of
    ``geometry``, parametric or drawn (``zone_solid``).  ``driven``: further load sets
    {name: (displacement (3 N,) on ``unit_solutions``' dofs, the loads inside a zone as
    unit cases and weights)}, another model's states of the same throw mesh (the whole
    shaft's, ``fe.shaft.refinement``): their hot spots are found, cut and solved with the
    others', in the same zones and factorisations."""
    if len(factors) < 2 or factors[0] != 1.0:
        raise ValueError("a zone study starts from the assessed mesh (factor 1) and has at least two levels")
    loads = {k: dict(v) for k, v in loads.items()}
    t0 = time.perf_counter()
    fields = {name: unit_solutions.combine(w) for name, w in loads.items()}
    for name, (u, w) in (driven or {}).items():
        if np.shape(u) != (3 * unit_solutions.points.shape[1],):
            raise ValueError(f"the load set {name!r} is not a displacement of the assessed throw mesh")
        fields[name], loads[name] = np.asarray(u, float), dict(w)
    pins = pins_of(unit_solutions, loads)
    first = level_peaks(unit_solutions, fields)
    base = throw_mesh.options
    levels = [
        ConvergenceLevel(
            fillet_divisions=base.fillet_divisions,
            n_dof=unit_solutions.n_dof,
            fillet_max_edge=dict(throw_mesh.stats.fillet_max_edge),
            peaks={k: v[0] for k, v in first.items()},
            where={k: v[1] for k, v in first.items()},
            seconds=time.perf_counter() - t0,
            reused=True,
            bore_divisions=base.bore_divisions,
        )
    ]
    solid = zone_solid(geometry, throw_mesh)
    spots = hot_spots(solid, throw_mesh, unit_solutions, fields, zone_radius=zone_radius)
    balls, mirrored, owner = fold_spots(spots, mirror_symmetric(geometry, throw_mesh))
    log.info(
        "hot-spot zones: %d spots, %d balls cut (%d of them also solved mirrored)",
        len(spots),
        len(balls),
        sum(mirrored),
    )
    samples = boundary_samples(unit_solutions.mesh)
    interp = Interpolator(unit_solutions.mesh, unit_solutions.system.basis.dofs, unit_solutions.points)
    every = [n for _, names in FAMILIES for n in names]
    options = [
        dataclasses.replace(base, fillet_divisions=base.fillet_divisions * f, bore_divisions=base.bore_divisions * f)
        for f in factors[1:]
    ]
    group_nodes = GROUP_FRACTION * unit_solutions.n_dof / 3

    def solve_level(mopt: MeshOptions, zones: list[ZoneMesh], meshing: float) -> ConvergenceLevel:
        """One level's zones solved for every load set and their peaks read; ``meshing``: the
        seconds of its meshing, counted in its time."""
        t0 = time.perf_counter() - meshing
        best: dict[str, tuple[float, str]] = {}
        n_dof, images, edges = 0, 0, dict[str, float]()
        # each spot read round its own centre, as far as its ball grew (``level_meshes``)
        cut = {c: r for zm in zones for c, r in zip(zm.centres, zm.radii)}
        read = (
            [h.centre for h in spots],
            [h.radius * cut.get(balls[k].centre, balls[k].radius) / balls[k].radius for h, k in zip(spots, owner)],
        )
        for zm in zones:
            system = ZoneSystem(zm, material, unit_solutions.options)
            try:
                image = mirror_zone(zm) if zm.mirrored else None
                own, got = system.fields_and_mirror(image, pins, loads, fields, interp)
                solved = [(zm, own, system.basis)]
                if image is not None:
                    solved.append((image, *got) if got is not None else (image, None, None))
            finally:
                system.release()
            for z, U, basis in solved:
                if U is None:  # the image's nodes are not the zone's reflected: solved alone
                    system = ZoneSystem(z, material, unit_solutions.options)
                    try:
                        U, basis = system.fields(pins, loads, fields, interp), system.basis
                    finally:
                        system.release()
                n_dof += int(3 * basis.N)
                images += int(3 * basis.N) if z is not zm else 0
                for k, v in z.fillet_max_edge.items():
                    edges[k] = max(edges.get(k, 0.0), v)
                for name, per in zone_peaks(z, basis, material, U, every, REACH, read).items():
                    for prefix, names in FAMILIES:
                        for surface in names:
                            if surface in per and per[surface] > best.get(prefix + name, (-np.inf, ""))[0]:
                                best[prefix + name] = (per[surface], surface)
        missing = sorted(set(first) - set(best))
        if missing:
            raise RuntimeError(f"the hot-spot zones hold no node of the surfaces of {missing}")
        level = ConvergenceLevel(
            fillet_divisions=mopt.fillet_divisions,
            n_dof=n_dof,
            fillet_max_edge=edges,
            peaks={k: best[k][0] for k in first},
            where={k: best[k][1] for k in first},
            seconds=time.perf_counter() - t0,
            bore_divisions=mopt.bore_divisions,
            zones=len(spots),
        )
        log.info(
            "convergence level r/%g: %d zones, %d DOF (%d of them the mirror images'), %.1f s",
            mopt.fillet_divisions,
            len(spots),
            n_dof,
            images,
            level.seconds,
        )
        return level

    # each level solved while gmsh meshes the next (``pipelined_levels``), else all meshed first
    refined: list[ConvergenceLevel] = []
    try:
        for zones in pipelined_levels(solid, options, balls, samples, group_nodes, mirrored):
            refined.append(solve_level(options[len(refined)], zones, max(zm.seconds for zm in zones)))
    except Unpipelined:
        t0 = time.perf_counter()
        meshes = held_level_meshes(solid, options, balls, samples, group_nodes, mirrored=mirrored)
        meshing = (time.perf_counter() - t0) / len(options)  # the cut shared by the levels
        refined = [solve_level(mopt, zones, meshing) for mopt, zones in zip(options, meshes)]
    levels.extend(refined)
    changes = {
        name: [abs(b.peaks[name] - a.peaks[name]) / b.peaks[name] for a, b in zip(levels, levels[1:])]
        for name in levels[0].peaks
    }
    return ConvergenceStudy(
        levels=tuple(levels), loads=loads, tolerance=tolerance, changes=changes, method="zones", zone_radius=zone_radius
    )


__all__ = [
    "CANDIDATE",
    "REACH",
    "ZONE_RADIUS",
    "HotSpot",
    "fold_spots",
    "hot_spots",
    "mirror_symmetric",
    "zone_convergence",
    "zone_solid",
]
