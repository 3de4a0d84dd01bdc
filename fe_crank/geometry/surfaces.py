"""Names of the outer surfaces of a built throw (``fe_crank.geometry.throw.add_throw``).

A surface is outer when it bounds exactly one kept volume; it is named by its OCC type
(plane, torus of a rolling-ball fillet, cylinder) and where its bounding box lies in the
throw frame (``fe_crank.geometry.spec``): journal and pin ends, fillets, journals,
crankpin, oil bore.  Every expected group must get at least one surface.
"""

from __future__ import annotations

from fe_crank.errors import GeometryError
from fe_crank.geometry.spec import CrankGeometry


def _radii(gmsh, s: int, cx: float, cy: float) -> list[float]:
    """Distances from the axis (cx, cy) of points of surface ``s`` (a 3 x 3 grid of its parameters)."""
    lo, hi = gmsh.model.getParametrizationBounds(2, s)
    out = []
    for a in (0.1, 0.5, 0.9):
        for b in (0.1, 0.5, 0.9):
            x, y, _ = gmsh.model.getValue(2, s, [lo[0] + a * (hi[0] - lo[0]), lo[1] + b * (hi[1] - lo[1])])
            out.append(((x - cx) ** 2 + (y - cy) ** 2) ** 0.5)
    return out


def classify_surfaces(
    gmsh, g: CrankGeometry, volumes: set[int], tol: float, *, cut: tuple[int, ...] = ()
) -> dict[str, list[int]]:
    """Name the outer surfaces by where they lie (bounding boxes in the throw frame).

    ``cut``: the solid is the fundamental part ``x >= 0`` (0 in ``cut``) / ``z <= 0`` (2 in
    ``cut``) of a symmetric throw: a surface touching ``x = 0`` is judged by its mirrored
    bounding box (``x0 = -x1``), the ``_2`` groups are not expected, and the cut faces
    (planes through the origin) stay unnamed."""
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
    if 2 in cut:
        names = [n for n in names if not n.endswith("_2")]
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
        if 0 in cut and near(x0, 0.0):
            x0 = -x1
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
            elif cut and abs(zc) < zw - tl and rfp > 0 and max(_radii(gmsh, s, 0.0, R)) < rp + rfp + tl:
                out[f"crankpin_fillet_{side}"].append(s)
            elif abs(zc) > zp + tl and rfj > 0:
                out[f"journal_fillet_{side}"].append(s)
        elif kind == "Cylinder":
            if near(x0, -rj) and near(x1, rj) and near(y0, -rj) and near(y1, rj) and abs(zc) > zw:
                out[f"journal_{side}"].append(s)
            elif (
                near(x0, -rp)
                and near(x1, rp)
                and near(y0, R - rp)
                and near(y1, R + rp)
                and z1 <= zp + tl
                and z0 >= -zp - tl
            ):
                out["crankpin"].append(s)
            elif cut and abs(zc) > zw and all(near(r, rj) for r in _radii(gmsh, s, 0.0, 0.0)):
                out[f"journal_{side}"].append(s)  # a cut may split the journal into several faces
            elif cut and z1 <= zp + tl and z0 >= -zp - tl and all(near(r, rp) for r in _radii(gmsh, s, 0.0, R)):
                out["crankpin"].append(s)
            elif (
                g.oil_bore is not None
                and z1 <= zp + tl
                and z0 >= -zp - tl
                and abs(xc) < rp + tl
                and abs(yc - R) < rp + tl
            ):
                out["oil_bore"].append(s)
    out.pop("unnamed", None)
    for name, tags in out.items():
        if not tags:
            raise GeometryError(f"building the throw found no surface for {name!r}", file=g.file or None)
    return out
