"""gmsh size fields: fillet elements of ``r / fillet_divisions`` (IACS UR M53 appendix,
FE guidance: at most ``r/4``), growing with the distance from the fillets.  The
counterweight-to-web transition fillets (``counterweight_fillet_<web>`` surfaces,
``fe_crank.geometry.cw_fillet``) get the same ``r / fillet_divisions`` rule.  With
``web_divisions`` the web volumes get edges of at most ``W / web_divisions`` (UR M53 App. III
2.2's elements across the web thickness W, ``fe_crank.fe.web_mesh``)."""

from __future__ import annotations

import numpy as np

from fe_crank.geometry.spec import CrankGeometry
from fe_crank.mesh.options import _SAFETY, MeshOptions


def _fillet_distance(g: CrankGeometry, name: str) -> str:
    """gmsh MathEval expression: distance from (x, y, z) to the fillet's torus.

    The rolling-ball fillet of radius ``r_f`` between a cylinder of radius ``r`` and a
    web face is part of the torus whose spine circle (radius ``r + r_f``, about the
    cylinder's axis) lies ``r_f - u`` off the web face (``u`` the undercut); distance to the torus =
    ``| dist(x, spine) - r_f |`` (exact, unlike sampled ``Distance`` fields).
    """
    zp = g.crankpin_length / 2
    zw = zp + g.web_thickness
    if name.startswith("crankpin_fillet"):
        rf, a, cy = g.crankpin_fillet, g.crankpin_diameter / 2 + g.crankpin_fillet, g.crank_radius
        off = rf - g.crankpin_undercut
        zc = -zp + off if name.endswith("1") else zp - off
    else:
        rf, a, cy = g.journal_fillet, g.journal_diameter / 2 + g.journal_fillet, 0.0
        off = rf - g.journal_undercut
        zc = -zw - off if name.endswith("1") else zw + off
    rho = f"Sqrt(x*x + (y - ({cy!r}))*(y - ({cy!r})))"
    spine = f"Sqrt(({rho} - {a!r})*({rho} - {a!r}) + (z - ({zc!r}))*(z - ({zc!r})))"
    return f"Fabs({spine} - {rf!r})"


#: target edge on the counterweight fillets = _CW_SAFETY r / fillet_divisions (the largest
#: edge on them is not enforced: about 1 mm on a 3 mm fillet at targets r/2 ... r/6)
_CW_SAFETY = _SAFETY
#: target edge in the webs = _WEB_SAFETY W / web_divisions: W/6 targets gave 6.75 elements
#: across (``fe.web_mesh``'s measure) on the small test throw with 3.8 mm fillets
_WEB_SAFETY = 0.7


def counterweight_fillet_radius(g: CrankGeometry, web: int) -> float:
    """Smallest ``fillet_radius`` of the counterweights on ``web`` (1 or 2) over the throws
    (the mesh of any throw is then at least as fine as its own radius asks)."""
    radii = [cw.fillet_radius for t in g.throws for cw in t.counterweights if cw.web == web and cw.fillet_radius]
    return min(radii)


def _surface_field(gmsh, tags: list[int], h: float, size_max: float, grading: float) -> int:
    """Threshold field: ``h`` within ``h`` of the surfaces (sampled 100 x 100 per face,
    so that the sampling gap stays below ``h``), growing by ``grading`` beyond."""
    d = gmsh.model.mesh.field.add("Distance")
    gmsh.model.mesh.field.setNumbers(d, "SurfacesList", tags)
    gmsh.model.mesh.field.setNumber(d, "Sampling", 100)
    th = gmsh.model.mesh.field.add("Threshold")
    gmsh.model.mesh.field.setNumber(th, "InField", d)
    gmsh.model.mesh.field.setNumber(th, "SizeMin", min(h, size_max))
    gmsh.model.mesh.field.setNumber(th, "SizeMax", size_max)
    gmsh.model.mesh.field.setNumber(th, "DistMin", h)
    gmsh.model.mesh.field.setNumber(th, "DistMax", h + max(size_max - h, 0.0) / grading)
    return th


def _set_size_fields(
    gmsh,
    geometry: CrankGeometry,
    surfaces: dict[str, list[int]],
    fillet_radii: dict[str, float],
    opt: MeshOptions,
    volumes: dict[str, list[int]] | None = None,
) -> float:
    size_max = opt.size_max if opt.size_max is not None else geometry.crankpin_diameter / opt.coarse_divisions
    fields = []
    webs = [t for name in ("web_1", "web_2") for t in (volumes or {}).get(name, ())]
    if opt.web_divisions is not None and webs:  # UR M53 App. III 2.2: elements across the web
        h = _WEB_SAFETY * geometry.web_thickness / opt.web_divisions
        c = gmsh.model.mesh.field.add("Constant")
        gmsh.model.mesh.field.setNumbers(c, "VolumesList", webs)
        gmsh.model.mesh.field.setNumber(c, "VIn", min(h, size_max))
        gmsh.model.mesh.field.setNumber(c, "VOut", size_max)
        fields.append(c)
    for name, r in fillet_radii.items():
        h = _SAFETY * r / opt.fillet_divisions
        d = gmsh.model.mesh.field.add("MathEval")
        gmsh.model.mesh.field.setString(d, "F", _fillet_distance(geometry, name))
        th = gmsh.model.mesh.field.add("Threshold")
        gmsh.model.mesh.field.setNumber(th, "InField", d)
        gmsh.model.mesh.field.setNumber(th, "SizeMin", h)
        gmsh.model.mesh.field.setNumber(th, "SizeMax", size_max)
        gmsh.model.mesh.field.setNumber(th, "DistMin", 0.0)
        gmsh.model.mesh.field.setNumber(th, "DistMax", max(size_max - h, 0.0) / opt.grading)
        fields.append(th)
    if "oil_bore" in surfaces and geometry.oil_bore is not None:
        h = np.pi * geometry.oil_bore.diameter / (2 * opt.bore_divisions)
        d = gmsh.model.mesh.field.add("Distance")
        gmsh.model.mesh.field.setNumbers(d, "SurfacesList", surfaces["oil_bore"])
        th = gmsh.model.mesh.field.add("Threshold")
        gmsh.model.mesh.field.setNumber(th, "InField", d)
        gmsh.model.mesh.field.setNumber(th, "SizeMin", min(h, size_max))
        gmsh.model.mesh.field.setNumber(th, "SizeMax", size_max)
        gmsh.model.mesh.field.setNumber(th, "DistMin", 0.0)
        gmsh.model.mesh.field.setNumber(th, "DistMax", max(size_max - h, 0.0) / opt.grading)
        fields.append(th)
    for name, tags in surfaces.items():
        if name.startswith("counterweight_fillet_"):
            r = counterweight_fillet_radius(geometry, int(name.rsplit("_", 1)[1]))
            h = _CW_SAFETY * r / opt.fillet_divisions
            fields.append(_surface_field(gmsh, tags, h, size_max, opt.grading))
    if fields:
        mn = gmsh.model.mesh.field.add("Min")
        gmsh.model.mesh.field.setNumbers(mn, "FieldsList", fields)
        gmsh.model.mesh.field.setAsBackgroundMesh(mn)
    gmsh.option.setNumber("Mesh.MeshSizeMax", size_max)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 12)  # 12 elements per 2 pi on curved faces
    return size_max
