"""The mesh of a hot-spot zone: the throw's solid inside a ball round a hot spot, meshed
with the throw mesher's own size fields at a given fillet size (``mesh_zone``).

The throw is built as for its own mesh (``geometry.throw.add_throw``: the same solid, the
same subdomains), fragmented with the ball, and everything outside the ball removed.  The
zone's boundary faces are then named after the throw's: a face on the ball is the cut
(``CUT``); any other face takes the name of the nearest named boundary facet of the
assessed mesh (``names``: sample points on it and their boundary names, "" for an unnamed
face), so that the zone's fillets, oil bore, crankpin and journal surfaces are known
without tracking OpenCASCADE's face numbers through the boolean.  The size fields are
``mesh.sizing.set_size_fields`` of the throw mesher at the options given (fillets at
``r / fillet_divisions``, the oil bore at ``bore_divisions``, the counterweights'
transition fillets, the webs), so an element of the zone near a fillet is the size the
full refined mesh has there.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree
from skfem import Mesh

from fe_crank.errors import MeshError
from fe_crank.geometry.spec import CrankGeometry, ThrowSpec
from fe_crank.mesh.generate import generate
from fe_crank.mesh.options import MeshOptions
from fe_crank.mesh.quality import fillet_max_edge
from fe_crank.mesh.sizing import set_size_fields

#: the name of the zone's cut boundary (its faces on the ball)
CUT = "zone_cut"
#: the balls' turn about an oblique axis (rad)
TILT, TILT_AXIS = 0.7, (0.6, 0.5, 0.2)


@dataclass(frozen=True)
class ZoneMesh:
    """A zone's quadratic mesh (scikit-fem ``MeshTet2``, boundaries named as the throw's and ``CUT``)."""

    mesh: Mesh
    centres: tuple[tuple[float, float, float], ...]  # m, the hot spots the balls are centred on
    radii: tuple[float, ...]  # m, the balls' radii
    options: MeshOptions
    fillet_max_edge: dict[str, float]  # m, longest edge on each fillet in the zone
    seconds: float


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
    one model; ``names``: (points (n, 3) on the assessed mesh's boundary, the boundary name
    of each) to name the zone's faces (module docstring)."""
    from fe_crank.geometry.throw import add_throw
    from fe_crank.gmsh_io import gmsh_session, model_to_skfem

    t0 = time.perf_counter()
    cs = np.atleast_2d(np.asarray(centres, float))
    rs = np.asarray(radii, float)
    pts, labels = names
    tree = cKDTree(np.asarray(pts, float))
    with gmsh_session() as gmsh:
        model = add_throw(geometry, spec)
        occ = gmsh.model.occ
        for name in (*model.volumes, *model.surfaces):  # the throw's groups: the zone names its own
            gmsh.model.removePhysicalName(name)
        gmsh.model.removePhysicalGroups()
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
            raise MeshError(f"the hot-spot zones hold no part of throw {spec.name!r}")
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
                name = labels[int(tree.query(p)[1])]
            surfaces.setdefault(name or "free", []).append(s)
        for name, tags in volumes.items():
            gmsh.model.addPhysicalGroup(3, tags, name=name)
        for name, tags in surfaces.items():
            gmsh.model.addPhysicalGroup(2, sorted(set(tags)), name=name)
        if CUT not in surfaces:
            raise MeshError(f"the hot-spot zones hold the whole throw {spec.name!r}")
        set_size_fields(gmsh, geometry, surfaces, model.fillet_radii, options, volumes)
        generate(gmsh, spec.name, geometry.name, options)
        mesh = model_to_skfem()
    fillets = [n for n in model.fillet_radii if n in (mesh.boundaries or {})]
    return ZoneMesh(
        mesh=mesh,
        centres=tuple((float(c[0]), float(c[1]), float(c[2])) for c in cs),
        radii=tuple(float(r) for r in rs),
        options=options,
        fillet_max_edge=fillet_max_edge(mesh, fillets),
        seconds=time.perf_counter() - t0,
    )


__all__ = ["CUT", "ZoneMesh", "mesh_zone"]
