"""gmsh size fields of the parametric throw: fillet elements of ``r / fillet_divisions``
(IACS UR M53 appendix, FE guidance: at most ``r/4``), growing with the distance from
the fillets.  The counterweight-to-web transition fillets (``counterweight_fillet_<web>``
surfaces, ``fe_crank.geometry.cw_fillet``) get the same ``r / fillet_divisions`` rule.
With ``web_divisions`` the web volumes get edges of at most ``W / web_divisions`` (UR M53
App. III 2.2's elements across the web thickness W, ``fe_crank.rules.m53.web_mesh``).
The fields themselves: ``fe_crank.mesh.fields`` (shared with the CAD route)."""

from __future__ import annotations

import numpy as np

from fe_crank.geometry.spec import CrankGeometry
from fe_crank.mesh.fields import apply_fields, bore_field, surface_field, torus_distance, torus_field, web_field
from fe_crank.mesh.options import FILLET_SAFETY, MeshOptions


def _fillet_distance(g: CrankGeometry, name: str) -> str:
    """gmsh MathEval expression: distance from (x, y, z) to the fillet's torus.

    The rolling-ball fillet of radius ``r_f`` between a cylinder of radius ``r`` and a
    web face is part of the torus whose spine circle (radius ``r + r_f``, about the
    cylinder's axis) lies ``r_f - u`` off the web face (``u`` the undercut)
    (``fe_crank.mesh.fields.torus_distance``).
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
    return torus_distance(cy, zc, a, rf)


#: target edge on the counterweight fillets = _CW_SAFETY r / fillet_divisions (the largest
#: edge on them is not enforced: about 1 mm on a 3 mm fillet at targets r/2 ... r/6)
_CW_SAFETY = FILLET_SAFETY


def counterweight_fillet_radius(g: CrankGeometry, web: int) -> float:
    """Smallest ``fillet_radius`` of the counterweights on ``web`` (1 or 2) over the throws
    (the mesh of any throw is then at least as fine as its own radius asks)."""
    radii = [cw.fillet_radius for t in g.throws for cw in t.counterweights if cw.web == web and cw.fillet_radius]
    return min(radii)


def set_size_fields(
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
        fields.append(web_field(gmsh, webs, geometry.web_thickness, opt.web_divisions, size_max))
    for name, r in fillet_radii.items():
        h = FILLET_SAFETY * r / opt.fillet_divisions
        fields.append(torus_field(gmsh, _fillet_distance(geometry, name), h, size_max, opt.grading))
    if "oil_bore" in surfaces and geometry.oil_bore is not None:
        h = np.pi * geometry.oil_bore.diameter / (2 * opt.bore_divisions)
        fields.append(bore_field(gmsh, surfaces["oil_bore"], h, size_max, opt.grading))
    for name, tags in surfaces.items():
        if name.startswith("counterweight_fillet_"):
            r = counterweight_fillet_radius(geometry, int(name.rsplit("_", 1)[1]))
            h = _CW_SAFETY * r / opt.fillet_divisions
            fields.append(surface_field(gmsh, tags, h, size_max, opt.grading))
    apply_fields(gmsh, fields, size_max)
    return size_max
