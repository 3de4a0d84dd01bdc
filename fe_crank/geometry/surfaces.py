"""Names of the outer surfaces of a built throw (``fe_crank.geometry.throw.add_throw``).

A surface is outer when it bounds exactly one kept volume; it is named by its OCC type
(plane, torus of a rolling-ball fillet, cylinder) and where its bounding box lies in the
throw frame (``fe_crank.geometry.spec``): journal and pin ends, fillets, journals,
crankpin, oil bore.  Every expected group must get at least one surface.
"""

from __future__ import annotations

from fe_crank.errors import GeometryError
from fe_crank.geometry.spec import CrankGeometry


def classify_surfaces(gmsh, g: CrankGeometry, volumes: set[int], tol: float) -> dict[str, list[int]]:
    """Name the outer surfaces by where they lie (bounding boxes in the throw frame)."""
    R = g.crank_radius
    rp, rj = g.crankpin_diameter / 2, g.journal_diameter / 2
    zp = g.crankpin_length / 2
    zw = zp + g.web_thickness
    ze = zw + g.journal_length
    rfp, rfj = g.crankpin_fillet, g.journal_fillet
    names = ["journal_1", "journal_2", "crankpin", "end_1", "end_2"]
    if rfp > 0:
        names += ["crankpin_fillet_1", "crankpin_fillet_2"]
    if rfj > 0:
        names += ["journal_fillet_1", "journal_fillet_2"]
    if g.oil_bore is not None:
        names.append("oil_bore")
    out: dict[str, list[int]] = {n: [] for n in names}
    # outer surfaces: those bounding exactly one kept volume
    count: dict[int, int] = {}
    for v in volumes:
        for _, s in gmsh.model.getBoundary([(3, v)], oriented=False, combined=False):
            count[abs(s)] = count.get(abs(s), 0) + 1
    tl = 1e-6 + tol

    def near(a, b):
        return abs(a - b) < tl

    for s, n in count.items():
        if n != 1:
            continue
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, s)
        kind = gmsh.model.getType(2, s)
        xc, yc, zc = 0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (z0 + z1)
        side = 1 if zc < 0 else 2
        if kind == "Plane":
            if near(z0, -ze) and near(z1, -ze):
                out["end_1"].append(s)
            elif near(z0, ze) and near(z1, ze):
                out["end_2"].append(s)
        elif kind == "Torus":
            # OCC rolling-ball fillet of a circular edge: around the pin or a journal
            if abs(zc) < zw - tl and near(xc, 0.0) and abs(yc - R) < rp and (rfp > 0):
                out[f"crankpin_fillet_{side}"].append(s)
            elif abs(zc) > zp + tl and rfj > 0:
                out[f"journal_fillet_{side}"].append(s)
        elif kind == "Cylinder":
            if near(x0, -rj) and near(x1, rj) and near(y0, -rj) and near(y1, rj) and abs(zc) > zw:
                out[f"journal_{side}"].append(s)
            elif near(x0, -rp) and near(x1, rp) and near(y0, R - rp) and near(y1, R + rp) and z1 <= zp + tl and z0 >= -zp - tl:
                out["crankpin"].append(s)
            elif g.oil_bore is not None and z1 <= zp + tl and z0 >= -zp - tl and abs(xc) < rp + tl and abs(yc - R) < rp + tl:
                out["oil_bore"].append(s)
    out.pop("unnamed", None)
    for name, tags in out.items():
        if not tags:
            raise GeometryError(f"building the throw found no surface for {name!r}", file=g.file or None)
    return out
