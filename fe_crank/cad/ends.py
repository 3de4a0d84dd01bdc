"""The shaft's ends beyond its end journals: the nose at the front and the flange at the
rear (the power take-off end of most engines; the names follow the crank axis's sense,
front to flywheel).

An end is the material beyond the end journal's cylindrical face, away from the throws
(the journal's fillet or shoulder into the end goes with it); none where the end journal
ends in the shaft's free end face (fe-crank's throw files end so: half a bearing).  Its
extent and largest diameter (of the whole-round cylinders about the crank axis it shows)
are given in the frame of the throw it adjoins, with its mass properties (exact B-rep
integrals, as the throw's).  Neither is part of a throw model: they carry no load but
the torque to the bearings' side (docs/shaft.md)."""

from __future__ import annotations

import numpy as np

from fe_crank.cad.axis import line_of
from fe_crank.cad.chains import extent
from fe_crank.cad.features import ShaftEnd
from fe_crank.cad.frame import Frame
from fe_crank.cad.model import BIG, throw_mass
from fe_crank.cad.survey import coverage

_PLANE = ((-BIG, -BIG), (BIG, -BIG), (BIG, BIG), (-BIG, BIG))


def shaft_ends(gmsh, prepared, density: float) -> tuple[ShaftEnd, ...]:
    """The nose and flange of the prepared shaft (``recognise.Prepared``), where drawn."""
    p = prepared
    occ = gmsh.model.occ
    lo_shaft, hi_shaft = extent(list(p.faces.values()), p.axis)
    out = []
    for name, t, side in (("nose", p.raw[0], 0), ("flange", p.raw[-1], 1)):
        j = t.journals[side]
        cut = j.lo if side == 0 else j.hi
        far = lo_shaft if side == 0 else hi_shaft
        if j.free_end or abs(far - cut) <= p.tol:
            continue
        frame = Frame.of(p.axis.origin, p.axis.e, t.u, t.mid)
        s0, s1 = (far - 1.0, cut) if side == 0 else (cut, far + 1.0)
        (copy,) = occ.copy([(3, p.read.shaft)])
        tool = frame.prism(occ, _PLANE, s0, s1, p.axis.origin)
        pieces, _ = occ.intersect([copy], [(3, tool)])
        occ.synchronize()
        vols = [v for d, v in pieces if d == 3]
        if not vols:
            continue
        mass = throw_mass(gmsh, {name: vols}, density, frame, t.name).total
        occ.remove(pieces, recursive=True)
        occ.synchronize()
        lo, hi = sorted((cut, far))
        radii = [
            f.radius
            for f in p.faces.values()
            if f.kind == "cylinder"
            and f.convex
            and line_of(f).same(p.axis, p.tol)
            and extent([f], p.axis)[0] >= lo - p.tol
            and extent([f], p.axis)[1] <= hi + p.tol
            and coverage(f.edge_runs, f.origin, f.direction) >= 0.99
        ]
        tags = tuple(
            sorted(
                f.tag
                for f in p.faces.values()
                if extent([f], p.axis)[0] >= lo - p.tol and extent([f], p.axis)[1] <= hi + p.tol
            )
        )
        z = sorted(float(v - t.mid) for v in (cut, far))
        out.append(
            ShaftEnd(name, t.name, tags, float(2 * max(radii)) if radii else 0.0, z[0], z[1], float(np.ptp(z)), mass)
        )
    return tuple(out)
