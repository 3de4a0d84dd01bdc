"""Quadratic tetrahedral mesh of one throw of a CAD file: the parametric route's rules.

:func:`mesh_cad_throw` recognises the file (``fe_crank.cad.recognise``), builds the
throw's named parts between its bearing centres (``fe_crank.cad.model``) and meshes
them with the steps and checks of ``fe_crank.mesh.generate`` into a ``ThrowMesh`` with
the parametric route's named groups (boundaries ``journal_1/2``, ``end_1/2``,
``crankpin``, ``crankpin_fillet_1/2``, ``journal_fillet_1/2``, ``oil_bore``,
``counterweight_fillet_1/2``; subdomains ``journal_1/2``, ``web_1/2``, ``crankpin``,
``counterweight_1/2``), as far as the throw has them.

Sizes (``fe_crank.mesh.fields``): every recognised fillet ``r / fillet_divisions``
(times the presets' safety factor), exact on its tori, sampled on other blends; the
largest fillet edge checked against ``r / fillet_divisions`` for presets with at least
4 (IACS UR M53 App. III: at most r/4); oil bores ``pi d / (2 bore_divisions)``;
counterweight fillets like the parametric ones; with ``web_divisions`` each web's
elements at most its thickness W / ``web_divisions`` (UR M53 App. III 2.2).  The mesh is of the whole throw (no
mirror planes: a drawn solid is not symmetric by construction), in the throw's THROW
frame (``ThrowFeatures.rotation``/``origin``: the parts are moved there before meshing),
as the FE stage and the assessment expect.  Cached like the
parametric meshes, keyed by the file's SHA-256 and everything of ``[cad]`` that changes
the solid.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import time
from pathlib import Path

import numpy as np

from fe_crank.cad.config import CadInput
from fe_crank.cad.features import ThrowFeatures
from fe_crank.cad.survey import DIRECTION_QUANTUM_DECIMALS, LENGTH_QUANTUM_DECIMALS
from fe_crank.errors import GeometryError
from fe_crank.mesh.cache import mesher_key
from fe_crank.mesh.fields import apply_fields, bore_field, surface_field, torus_distance, torus_field, web_field
from fe_crank.mesh.generate import finish, generate, through_cache
from fe_crank.mesh.interface import imprint_sectors
from fe_crank.mesh.mirror import mirror_all, swap_side
from fe_crank.mesh.msh import write_msh
from fe_crank.mesh.options import DEFAULT_CACHE_DIR, FILLET_SAFETY, MeshOptions, resolve_options
from fe_crank.mesh.types import ThrowMesh


@dataclasses.dataclass(frozen=True)
class _Parts:
    """The built throw's named gmsh entities, as ``mesh.interface.imprint_sectors`` reads them."""

    volumes: dict[str, list[int]]
    surfaces: dict[str, list[int]]
    fillet_radii: dict[str, float]


def cad_cache_key(cad: CadInput, sha256: str, throw: str, opt: MeshOptions) -> str:
    """SHA-256 (hex, 20 chars) of the file's bytes, the ``[cad]`` entries that change
    the solid, the throw, the mesh options and what every mesh depends on beside them
    (``mesh.cache.mesher_key``: the gmsh options, the versions, the cache format)."""
    opts = dataclasses.asdict(opt)
    if opts["web_divisions"] is None:  # the meshes made before the web control keep their keys
        del opts["web_divisions"]
    payload = {
        "route": "cad",
        "frame": "throw",
        "file": sha256,
        "cad": {
            "length_unit": cad.length_unit,
            "axis": cad.axis,
            "throws": cad.throws,
            "bodies": cad.bodies,
            "counterweight_radius": cad.counterweight_radius,
            "faces": [dataclasses.asdict(f) for f in cad.faces],
        },
        # the fitted radii and axes rounded (``survey.snap_length``, ``snap_direction``):
        # meshes made from the unrounded fits do not stand for these
        "fits": {"length_decimals": LENGTH_QUANTUM_DECIMALS, "direction_decimals": DIRECTION_QUANTUM_DECIMALS},
        "throw": throw,
        "options": opts,
        "mesher": mesher_key(),
        # a joinable mesh (end faces in sectors): mirrored across z = 0 where the throw is symmetric
        **(
            {"joinable": "mirrored where symmetric"} if opt.interface_sectors > 1 else {}
        ),  # the gmsh options, versions and cache format, as the parametric route's
    }
    return hashlib.sha256(json.dumps(payload, sort_keys=True, default=repr).encode()).hexdigest()[:20]


def size_fields(
    gmsh, t: ThrowFeatures, surfaces: dict[str, list[int]], volumes: dict[str, list[int]], opt: MeshOptions
) -> dict[str, float]:
    """Set the size fields of the drawn throw ``t`` (module docstring) on its named
    ``surfaces`` and ``volumes`` (gmsh tags, throw frame) at ``opt``; returns the fillet
    radii (m) by fillet surface."""
    size_max = opt.size_max if opt.size_max is not None else t.crankpin.diameter / opt.coarse_divisions
    fields, radii = [], {}
    if opt.web_divisions is not None:  # UR M53 App. III 2.2: elements across each web's thickness
        for web in t.webs:
            if volumes.get(f"web_{web.side}"):
                fields.append(web_field(gmsh, volumes[f"web_{web.side}"], web.thickness, opt.web_divisions, size_max))
    for f in t.fillets:
        if f.radius <= 0:
            continue
        radii[f.name] = f.radius
        h = FILLET_SAFETY * f.radius / opt.fillet_divisions
        cy = t.crank_radius if f.name.startswith("crankpin") else 0.0
        for arc in f.arcs:
            expr = torus_distance(cy, arc.spine_z, arc.spine_radius, arc.radius)
            fields.append(torus_field(gmsh, expr, h, size_max, opt.grading))
        if len(f.arcs) < len(f.faces) and f.name in surfaces:  # blends that are no torus: the sampled distance
            fields.append(surface_field(gmsh, surfaces[f.name], h, size_max, opt.grading))
    if t.oil_bores and "oil_bore" in surfaces:
        d = min(b.diameter for b in t.oil_bores)
        fields.append(
            bore_field(gmsh, surfaces["oil_bore"], np.pi * d / (2 * opt.bore_divisions), size_max, opt.grading)
        )
    for cw in t.counterweights:
        name = f"counterweight_fillet_{cw.web}"
        if cw.fillet_radius and name in surfaces:
            h = FILLET_SAFETY * cw.fillet_radius / opt.fillet_divisions
            fields.append(surface_field(gmsh, surfaces[name], h, size_max, opt.grading))
    apply_fields(gmsh, fields, size_max)
    return radii


def estimate_cad_elements(t: ThrowFeatures, opt: MeshOptions) -> int:
    """Tetrahedra the mesh of ``t`` will have, estimated as ``fe_crank.geometry.estimate``
    does for a parametric throw: ``rho V / size_max^3`` in the bulk plus the layers graded
    from each refined face (the recognised fillets' own areas, the journals', the pin's
    and the bores' surfaces)."""
    from fe_crank.geometry.estimate import TETS_PER_H3, graded_layer_elements

    size_max = opt.size_max if opt.size_max is not None else t.crankpin.diameter / opt.coarse_divisions
    n = TETS_PER_H3 * t.mass.total.volume / size_max**3
    for f in t.fillets:
        if f.radius > 0:
            n += graded_layer_elements(f.area, FILLET_SAFETY * f.radius / opt.fillet_divisions, size_max, opt.grading)
    for cw in t.counterweights:
        if cw.fillet_radius:
            n += graded_layer_elements(
                cw.fillet_area, FILLET_SAFETY * cw.fillet_radius / opt.fillet_divisions, size_max, opt.grading
            )
    for c in (t.crankpin, *t.journals):
        r = c.diameter / 2
        n += graded_layer_elements(2 * np.pi * r * (c.z_max - c.z_min), 2 * np.pi * r / 12, size_max, opt.grading)
    for b in t.oil_bores:
        n += graded_layer_elements(
            np.pi * b.diameter * t.crankpin.diameter,
            np.pi * b.diameter / (2 * opt.bore_divisions),
            size_max,
            opt.grading,
        )
    return int(np.ceil(n))


def mirror_symmetric(gmsh, t: ThrowFeatures, built, frame) -> bool:
    """Is the built throw its own mirror image across its frame's ``z = 0``?  The
    recognised features first (web faces, bearing centres, fillet radii and counterweights
    in pairs, within 1e-9 of the crank radius), then the B-rep: the mirror image of every
    face of the built parts is a face of them (area within 1e-7 of the largest face's,
    centroid within 1e-7 of the crank radius: faces are matched one to one), and each
    part of the front side has the mirror image's exact mass properties of its rear
    partner (volume, centroid, inertia tensor, to 1e-9).  Any doubt: no."""
    tol = 1e-9 * t.crank_radius
    w1, w2 = t.webs
    b1, b2 = t.bearings
    pairs = [(w1.z_inner, -w2.z_inner), (w1.z_outer, -w2.z_outer), (b1.z, -b2.z)]
    for name in ("crankpin_fillet", "journal_fillet"):
        f1, f2 = t.fillet(f"{name}_1"), t.fillet(f"{name}_2")
        if (f1 is None) != (f2 is None):
            return False
        if f1 is not None and f2 is not None:
            pairs.append((f1.radius, f2.radius))
    cws = {cw.web: cw for cw in t.counterweights}
    if set(cws) not in (set(), {1, 2}):
        return False
    if cws:  # (a turned counterweight's turn: in the parts' mass properties below)
        pairs.append((cws[1].radius, cws[2].radius))
    if any(abs(a - b) > tol for a, b in pairs) or any(abs(b.point[2]) > tol for b in t.oil_bores):
        return False
    occ = gmsh.model.occ
    R, o = frame.rotation, frame.origin
    faces = sorted({abs(f) for vs in built.volumes.values() for v in vs for _, f in gmsh.model.getBoundary([(3, v)])})
    sig = np.array([[occ.getMass(2, f), *(R @ (np.asarray(occ.getCenterOfMass(2, f)) - o))] for f in faces])
    image = sig * np.array([1.0, 1.0, 1.0, -1.0])
    # OpenCASCADE integrates a face's area and centroid to about 1e-8 (a face across the
    # plane, its own image, shows a centroid 4e-8 R off it): matched within 1e-7
    loose = 100 * tol
    scale = np.array([1e-7 * max(float(sig[:, 0].max()), 1e-300), loose, loose, loose])
    used = np.zeros(len(sig), bool)
    for row in image:  # every face's mirror image is a face of the throw (area and centroid)
        hit = np.flatnonzero(np.all(np.abs(sig - row) <= scale, axis=1) & ~used)
        if hit.size == 0:
            return False
        used[hit[0]] = True
    for a, b in (("journal_1", "journal_2"), ("web_1", "web_2"), ("counterweight_1", "counterweight_2")):
        pa, pb = t.mass.parts.get(a), t.mass.parts.get(b)
        if (pa is None) != (pb is None):
            return False
        if pa is not None and pb is not None:
            ca, cb = np.asarray(pa.centroid), np.asarray(pb.centroid) * np.array([1.0, 1.0, -1.0])
            Ja, Jb = np.asarray(pa.inertia), np.asarray(pb.inertia) * np.array([[1, 1, -1], [1, 1, -1], [-1, -1, 1]])
            if (
                abs(pa.volume - pb.volume) > 1e-9 * pa.volume
                or np.abs(ca - cb).max() > tol
                or np.abs(Ja - Jb).max() > 1e-9 * np.abs(Ja).max()
            ):
                return False
    return True


def _build(cad: CadInput, throw: str | int | None, opt: MeshOptions, folder: Path, max_elements: int | None = None):
    from fe_crank.cad.model import build_throw
    from fe_crank.cad.recognise import prepare
    from fe_crank.cad.throw import end_slabs, throw_features
    from fe_crank.gmsh_io import gmsh_session, model_to_skfem

    t0 = time.perf_counter()
    with gmsh_session() as gmsh:
        prep = prepare(gmsh, cad)
        index = prep.index(throw)
        feats, built, plan, frame = throw_features(
            gmsh,
            prep.read.shaft,
            prep.faces,
            prep.nbrs,
            prep.axis,
            prep.raw,
            index,
            cad,
            prep.tol,
            joinable=opt.interface_sectors > 1,
        )
        from fe_crank.geometry.estimate import MAX_ELEMENTS

        limit = MAX_ELEMENTS if max_elements is None else int(max_elements)
        n = estimate_cad_elements(feats, opt)
        if n > limit:
            raise GeometryError(
                f"the mesh of throw {feats.name} would have about {n:.3g} elements, more than the limit {limit:.3g} "
                f"(its smallest fillet radius is {min((f.radius for f in feats.fillets), default=0) * 1e3:.3g} mm); "
                "raise it with --max-elements or [mesh] max_elements (docs/limits.md)",
                file=str(cad.file),
            )
        occ = gmsh.model.occ
        planes: tuple[int, ...] = ()
        if opt.interface_sectors > 1 and opt.symmetric and mirror_symmetric(gmsh, feats, built, frame):
            # its own mirror image across z = 0: its front half meshed and mirrored, as a
            # symmetric parametric throw is (``mesh.mirror``; half the interface solves)
            occ.remove([(3, v) for tags in built.volumes.values() for v in tags], recursive=True)
            occ.synchronize()
            built = build_throw(
                gmsh,
                prep.read.shaft,
                frame,
                prep.axis.origin,
                plan,
                prep.tol,
                str(cad.file),
                end_slabs(prep.raw[index]),
                half=True,
            )
            planes = (2,)
        keep = {v for tags in built.volumes.values() for v in tags}
        occ.remove([(3, v) for _, v in gmsh.model.getEntities(3) if v not in keep], recursive=True)
        occ.synchronize()
        # the FE model and the size fields are in the throw frame (docs/contracts.md)
        moved = frame.move_into(gmsh, sorted(keep))
        surfaces = {name: [moved[s] for s in tags] for name, tags in built.surfaces.items()}
        for name, tags in built.volumes.items():
            gmsh.model.addPhysicalGroup(3, tags, name=name)
        for name, tags in surfaces.items():
            gmsh.model.addPhysicalGroup(2, tags, name=name)
        if opt.interface_sectors > 1:  # end faces that join the turned neighbours node to node
            surfaces = imprint_sectors(gmsh, _Parts(built.volumes, surfaces, {}), opt.interface_sectors).surfaces
        radii = size_fields(gmsh, feats, surfaces, built.volumes, opt)
        min_quality, straightened = generate(gmsh, feats.name, cad.file.name, opt)
        mesh = model_to_skfem()
        if not planes:
            gmsh.write(str(folder / "throw.msh"))
    surfaces_named, volumes_named = set(built.surfaces), set(built.volumes)
    if planes:
        mesh = mirror_all(mesh, planes)
        straightened *= 2  # each straightened element and its image
        surfaces_named |= {swap_side(n) for n in surfaces_named}
        volumes_named |= {swap_side(n) for n in volumes_named}
        write_msh(folder / "throw.msh", mesh)
    stats = finish(
        mesh,
        (surfaces_named, volumes_named),
        radii,
        opt,
        min_quality=min_quality,
        straightened=straightened,
        t0=t0,
        planes=planes,
    )
    return mesh, stats


def mesh_cad_throw(
    cad: CadInput,
    throw: str | int | None = None,
    *,
    size: str | MeshOptions = "coarse",
    cache_dir: str | Path | None = DEFAULT_CACHE_DIR,
    max_elements: int | None = None,
) -> ThrowMesh:
    """Mesh one throw (name, 0-based index or None for the first) of the CAD file
    ``cad`` with quadratic tetrahedra (cached); see the module docstring.

    ``max_elements``: limit on the element count estimated before meshing
    (``estimate_cad_elements``; default ``fe_crank.geometry.estimate.MAX_ELEMENTS``).
    Raises ``InputError`` when the file cannot be read or recognised (``GeometryError``
    when the mesh would be too large), ``MeshError`` when gmsh fails or a mesh check does."""
    from fe_crank.cad.read import file_digest

    opt = resolve_options(size)
    sha = file_digest(cad)
    # keyed by the throw's name however it was given (None, its index or its name: one mesh, one entry)
    label = throw if isinstance(throw, str) else (cad.throws[throw or 0] if cad.throws else str((throw or 0) + 1))
    key = cad_cache_key(cad, sha, label, opt)

    def build(folder: Path | None):
        assert folder is not None  # needs_folder: through_cache always gives one
        return _build(cad, throw, opt, folder, max_elements)

    return through_cache(key, cache_dir, build, label, opt, needs_folder=True)
