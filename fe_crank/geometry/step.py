"""A parametric whole shaft written as a CAD file: ``write_shaft_step``.

The shaft as ``fe_crank.geometry.shaft`` places it (a ``ShaftLayout``): each throw's solid
(``fe_crank.geometry.solid.throw_solid``, its journal stubs to the bearing centres) turned
to its angle on the shaft (``sense x angle``, from ``+y`` towards ``+x``) and put at its
``axial_position``, the end journals to their length, optionally a plain nose and flange
beyond them (so that the end journals end in a shoulder, not a free face), fused into one
solid and written by gmsh's OpenCASCADE writer (STEP in millimetres, or BREP, by the
file's extension).  The CAD route reads such a file back as a drawn whole shaft
(``fe_crank.cad.whole``): the round trip of the whole path, and the benchmark of a drawn
shaft against the parametric one.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.geometry.solid import throw_solid
from fe_crank.gmsh_io import gmsh_session


def write_shaft_step(
    layout: ShaftLayout,
    path: str | Path,
    *,
    nose: tuple[float, float] | None = None,
    flange: tuple[float, float] | None = None,
    bodies: Callable[[Any], object] | None = None,
) -> Path:
    """Write the layout's shaft as one solid (module doc) to ``path`` and return it;
    ``nose``/``flange``: (diameter, length) in m of a plain cylinder beyond the front / rear
    end journal; ``bodies(gmsh)``: adds further solids (e.g. bolted counterweights) after
    the shaft is fused, written beside it as separate solids."""
    path = Path(path)
    g = layout.geometry
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        vols = []
        for t in layout.throws:
            solid, _ = throw_solid(g, t.spec)
            occ.rotate([(3, solid)], 0, 0, 0, 0, 0, 1, -layout.sense * t.angle)
            occ.translate([(3, solid)], 0, 0, t.z)
            vols.append((3, solid))
        rj = g.journal_diameter / 2
        first, last = layout.journals[0], layout.journals[-1]
        if first.centre - first.z0 > 0:
            vols.append((3, occ.addCylinder(0, 0, first.z0, 0, 0, first.centre - first.z0, rj)))
        if last.z1 - last.centre > 0:
            vols.append((3, occ.addCylinder(0, 0, last.centre, 0, 0, last.z1 - last.centre, rj)))
        if nose is not None:
            vols.append((3, occ.addCylinder(0, 0, first.z0 - nose[1], 0, 0, nose[1], nose[0] / 2)))
        if flange is not None:
            vols.append((3, occ.addCylinder(0, 0, last.z1, 0, 0, flange[1], flange[0] / 2)))
        out, _ = occ.fuse(vols[:1], vols[1:])
        if len(out) != 1:
            raise RuntimeError(f"the shaft's solids fused into {len(out)} solids, not one")
        occ.synchronize()
        if bodies is not None:
            bodies(gmsh)
            occ.synchronize()
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")  # the model is in m; STEP is written in mm
        gmsh.write(str(path))
    return path


__all__ = ["write_shaft_step"]
