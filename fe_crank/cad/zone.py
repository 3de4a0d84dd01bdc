"""The solid the hot-spot zones of a drawn throw are cut from: :func:`cad_zone_solid`.

The throw is built as for its own mesh (``fe_crank.cad.mesh``): the file read and its
throws recognised (``cad.recognise.prepare``), the throw's features and named parts
between its bearing centres (``cad.throw.throw_features``, ``cad.model.build_throw``; its
journals redrawn at the bearing centres where the mesh options join it to its
neighbours, as the assessed mesh's are), the rest of the shaft removed and the parts
moved into the throw frame (``Frame.move_into``), where the assessed mesh, its hot spots
and the size fields are.  The whole throw, never the mirrored half a symmetric throw's
own mesh may be built from: the zones sit round the hot spots on either side.  The size
fields are the CAD mesher's (``cad.mesh.size_fields``), so a zone's elements near a
fillet are the size the full re-mesh of the drawn throw has there.
"""

from __future__ import annotations

from fe_crank.cad.config import CadInput
from fe_crank.cad.features import ThrowFeatures
from fe_crank.cad.mesh import size_fields
from fe_crank.mesh.options import MeshOptions
from fe_crank.mesh.zone import SolidParts, ZoneSolid


def _features(gmsh, cad: CadInput, throw: str | int | None, joinable: bool):
    """(features, built parts, frame) of the throw, built in the open session's model."""
    from fe_crank.cad.recognise import prepare
    from fe_crank.cad.throw import throw_features

    prep = prepare(gmsh, cad)
    feats, built, _, frame = throw_features(
        gmsh,
        prep.read.shaft,
        prep.faces,
        prep.nbrs,
        prep.axis,
        prep.raw,
        prep.index(throw),
        cad,
        prep.tol,
        joinable=joinable,
    )
    return feats, built, frame


def _lengths(t: ThrowFeatures) -> dict[str, float]:
    """The zone radius's length on the counterweight fillets (their radius) and the oil
    bore (the smallest bore's diameter, as the size field's)."""
    out = {f"counterweight_fillet_{cw.web}": cw.fillet_radius for cw in t.counterweights if cw.fillet_radius}
    if t.oil_bores:
        out["oil_bore"] = min(b.diameter for b in t.oil_bores)
    return out


def cad_zone_solid(cad: CadInput, throw: str | int | None, options: MeshOptions) -> ZoneSolid:
    """The ``ZoneSolid`` of ``throw`` (name, 0-based index or None for the first) of the CAD
    file ``cad``, whose assessed mesh was made at ``options`` (module docstring).  Reads
    and recognises the file once here (the features' sizes), and again in each model the
    zones are cut in."""
    from fe_crank.gmsh_io import gmsh_session

    joinable = options.interface_sectors > 1
    with gmsh_session() as gmsh:
        feats = _features(gmsh, cad, throw, joinable)[0]
    radii = {f.name: f.radius for f in feats.fillets if f.radius > 0}

    def build(gmsh) -> SolidParts:
        _, built, frame = _features(gmsh, cad, throw, joinable)
        occ = gmsh.model.occ
        keep = {v for tags in built.volumes.values() for v in tags}
        occ.remove([(3, v) for _, v in gmsh.model.getEntities(3) if v not in keep], recursive=True)
        occ.synchronize()
        moved = frame.move_into(gmsh, sorted(keep))
        surfaces = {name: [moved[s] for s in tags] for name, tags in built.surfaces.items()}
        return SolidParts({k: list(v) for k, v in built.volumes.items()}, surfaces, dict(radii))

    def fields(gmsh, parts: SolidParts, opt: MeshOptions) -> dict[str, float]:
        return size_fields(gmsh, feats, parts.surfaces, parts.volumes, opt)

    return ZoneSolid(feats.name, cad.file.name, build, fields, _lengths(feats))


__all__ = ["cad_zone_solid"]
