"""The smallest element the hot-spot convergence study may ask of the mesher, and the
refusal of a geometry whose fillet or oil bore would need a smaller one at the study's
finest level (docs/limits.md, "Physical range"; docs/fe.md, "Only the hot spots refined").

The study meshes the fillets at ``r / (n f)`` (``n`` the preset's fillet divisions, ``f``
the finest level's factor; the size field's target is ``FILLET_SAFETY`` x that, gmsh's
surface edges reaching up to about 1.4 x the target) and the oil bore at ``pi d / (2 m f)``
(``m`` its divisions).  ``MIN_EDGE`` = 10 um is the smallest target accepted:

* the solid is built and meshed in metres, where OpenCASCADE merges points closer than
  its confusion tolerance (``Precision::Confusion()`` = 1e-7) and gmsh heals with
  ``Geometry.Tolerance`` = 1e-8 (gmsh reference manual, "Geometry options"): at 10 um the
  booleans' tolerance that cuts the balls and the fillets' tangent edges is 1 % of an
  element edge, so the mesher's curve and surface points are not moved at the element's
  own scale; a hundred times smaller and the tolerance is an element;
* 10 um is the grain size of quenched and tempered or forged crankshaft steels (10-50
  um), below which the isotropic continuum the stresses are computed on does not hold.

A fillet of a few millimetres is far from the bound (a 3 mm fillet at ``fine``'s finest
level r/16: a 122 um target); the bound refuses a slip of the unit (``"0.3 um"`` for
``"0.3 mm"``) or a fillet too small for a level of the study, before anything is meshed.
"""

from __future__ import annotations

import math

from fe_crank.errors import InputError
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.mesh.options import FILLET_SAFETY, MeshOptions

#: m: the smallest element edge the study may ask for at a fillet or the oil bore
MIN_EDGE = 1e-5


def study_edges(geometry: CrankGeometry, options: MeshOptions, finest: float) -> list[tuple[str, float, float]]:
    """(key in the geometry file, radius or diameter m, the size field's target edge m)
    at the finest level ``finest`` (the factor of the fillet divisions) of each fillet and
    the oil bore of ``geometry``."""
    n = options.fillet_divisions * finest
    out = []
    for key, r in (
        ("crankpin.fillet_radius", geometry.crankpin_fillet),
        ("journal.fillet_radius", geometry.journal_fillet),
    ):
        if r > 0:
            out.append((key, r, FILLET_SAFETY * r / n))
    for i, t in enumerate(geometry.throws):
        for cw in t.counterweights:
            if cw.fillet_radius:
                key = (
                    f"throws[{i}].counterweight.fillet_radius"
                    if len(geometry.throws) > 1
                    else "counterweight.fillet_radius"
                )
                out.append((key, cw.fillet_radius, FILLET_SAFETY * cw.fillet_radius / n))
    if geometry.oil_bore is not None:
        d = geometry.oil_bore.diameter
        out.append(("oil_bore.diameter", d, math.pi * d / (2 * options.bore_divisions * finest)))
    return out


def check_study_edges(geometry: CrankGeometry, options: MeshOptions, finest: float, preset: str, file: str) -> None:
    """Refuse a fillet or oil bore whose element at the study's finest level (``finest`` x
    the fillet divisions of ``options``, the preset ``preset``) is below ``MIN_EDGE``;
    ``file``: the load case, named where the geometry has no file of its own."""
    for key, size, edge in study_edges(geometry, options, finest):
        if edge < MIN_EDGE:
            what = "diameter" if key.endswith("diameter") else "radius"
            smallest = size * MIN_EDGE / edge
            raise InputError(
                f"{what} {size * 1e3:g} mm is too small for the hot-spot convergence study at mesh size "
                f"{preset!r}: its finest level asks for elements of {edge * 1e6:.3g} um, below the "
                f"{MIN_EDGE * 1e6:g} um the mesher takes (docs/limits.md); give a {what} of at least "
                f"{smallest * 1e3:.3g} mm (check its unit), or a coarser mesh size, or run without the study "
                "([mesh] convergence = false)",
                file=geometry.file or file,
                key=key,
            )


__all__ = ["MIN_EDGE", "check_study_edges", "study_edges"]
