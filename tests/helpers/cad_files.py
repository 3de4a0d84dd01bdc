"""CAD files for the tests, built with gmsh's OpenCASCADE API and written with its
STEP (or BREP) writer: the parametric throws exported as a CAD system would hold
them, a whole shaft, and shapes the parametric generator cannot make."""

from __future__ import annotations

import math
import re
from pathlib import Path

from fe_crank.geometry.solid import throw_solid
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.geometry.step import write_shaft_step
from fe_crank.gmsh_io import gmsh_session


def _write(gmsh, path: Path) -> Path:
    gmsh.model.occ.synchronize()
    gmsh.option.setString("Geometry.OCCTargetUnit", "M")  # the model is in m; STEP is written in mm
    gmsh.write(str(path))
    return path


def parametric_step(g: CrankGeometry, path: Path, throw: str | None = None) -> Path:
    """One throw of a parametric geometry, as the one solid ``throw_solid`` builds."""
    with gmsh_session() as gmsh:
        throw_solid(g, throw)
        return _write(gmsh, path)


def shaft_step(g: CrankGeometry, path: Path) -> Path:
    """All throws of ``g`` in a row along +z, throw k turned to its angle, fused: the
    journals of neighbouring throws join into one main journal of twice the length."""
    length = g.crankpin_length + 2 * g.web_thickness + 2 * g.journal_length
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        vols = []
        for k, spec in enumerate(g.throws):
            solid, _ = throw_solid(g, spec)
            # the throw frame's +y (the pin) turned by the throw angle, +y towards +x: about -z
            occ.rotate([(3, solid)], 0, 0, 0, 0, 0, 1, -spec.angle)
            occ.translate([(3, solid)], 0, 0, k * length)
            vols.append((3, solid))
        out, _ = occ.fuse(vols[:1], vols[1:])
        assert len(out) == 1
        return _write(gmsh, path)


def _sector(occ, r0: float, r1: float, angle: float, z0: float, t: float) -> int:
    """Annular sector r0..r1 within angle/2 of -y, z0..z0 + t (no fillets)."""
    ring = occ.addCylinder(0, 0, z0, 0, 0, t, r1)
    hole = occ.addCylinder(0, 0, z0, 0, 0, t, r0)
    out, _ = occ.cut([(3, ring)], [(3, hole)])
    a = angle / 2
    big = 2 * r1
    # keep the wedge within a of -y: the intersection of two half planes
    wedge = occ.addBox(-big, -big, z0, 2 * big, big, t)  # y < 0
    occ.rotate([(3, wedge)], 0, 0, 0, 0, 0, 1, a - math.pi / 2)
    other = occ.addBox(-big, -big, z0, 2 * big, big, t)
    occ.rotate([(3, other)], 0, 0, 0, 0, 0, 1, math.pi / 2 - a)
    both, _ = occ.intersect([(3, wedge)], [(3, other)])
    out, _ = occ.intersect(out, both)
    return out[0][1]


def plain_throw(gmsh, *, R=0.03, rj=0.022, rp=0.019, lj=0.015, lp=0.026, t=0.014, rw=0.03, rf=0.003) -> int:
    """A throw with a round web end (radius ``rw`` about the axis and the pin), fillets
    ``rf`` on the four pin/journal edges; returns the solid (z = 0 the pin's middle)."""
    occ = gmsh.model.occ
    zp, zw = lp / 2, lp / 2 + t
    parts = [
        occ.addCylinder(0, 0, -zw - lj, 0, 0, lj, rj),
        occ.addCylinder(0, 0, zw, 0, 0, lj, rj),
        occ.addCylinder(0, R, -zp, 0, 0, lp, rp),
    ]
    for z0 in (-zw, zp):  # web: a stadium of half width rw from the axis to the pin
        a = occ.addCylinder(0, 0, z0, 0, 0, t, rw)
        b = occ.addCylinder(0, R, z0, 0, 0, t, rw)
        box = occ.addBox(-rw, 0, z0, 2 * rw, R, t)
        web, _ = occ.fuse([(3, a)], [(3, b), (3, box)])
        parts.append(web[0][1])
    out, _ = occ.fuse([(3, parts[0])], [(3, p) for p in parts[1:]])
    occ.synchronize()
    solid = out[0][1]
    edges = _circles(gmsh, [(0, R, -zp, rp), (0, R, zp, rp), (0, 0, -zw, rj), (0, 0, zw, rj)])
    out = occ.fillet([solid], edges, [rf], removeVolume=True)
    occ.synchronize()
    return out[0][1]


def _circles(gmsh, circles) -> list[int]:
    found = []
    for _, c in gmsh.model.getEntities(1):
        lo, hi = gmsh.model.getParametrizationBounds(1, c)
        pts = [gmsh.model.getValue(1, c, [lo[0] + s * (hi[0] - lo[0])]) for s in (0.0, 0.4, 0.8)]
        for cx, cy, z, r in circles:
            if all(abs(p[2] - z) < 1e-9 and abs(math.hypot(p[0] - cx, p[1] - cy) - r) < 1e-9 for p in pts):
                found.append(c)
    return found


def sector_throw_step(path: Path, *, r1=0.06, angle=2.7925268031909276) -> Path:  # 160 deg
    """``plain_throw`` with an annular-sector counterweight on each web from the web's
    end radius to ``r1``, as thick as the web, without transition fillets: the far-side
    material beyond the web's end is exactly the sector (closed-form m r)."""
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        solid = plain_throw(gmsh)
        zp, zw = 0.013, 0.027
        sectors = [(3, _sector(occ, 0.03, r1, angle, z0, 0.014)) for z0 in (-zw, zp)]
        out, _ = occ.fuse([(3, solid)], sectors)
        assert len(out) == 1
        return _write(gmsh, path)


def _lines_along_z(gmsh, points, tol=1e-7) -> list[int]:
    """Straight edges parallel to z through the given (x, y) points."""
    found = []
    for _, c in gmsh.model.getEntities(1):
        lo, hi = gmsh.model.getParametrizationBounds(1, c)
        a = gmsh.model.getValue(1, c, [lo[0]])
        b = gmsh.model.getValue(1, c, [hi[0]])
        if abs(a[0] - b[0]) < tol and abs(a[1] - b[1]) < tol and abs(a[2] - b[2]) > tol:
            if any(math.hypot(a[0] - x, a[1] - y) < 1e-6 for x, y in points):
                found.append(c)
    return found


def lightened_throw_step(path: Path) -> Path:
    """``plain_throw`` whose webs each carry a trapezoidal counterweight (not an annular
    sector: its outline is four straight sides) with 4 mm transition fillets where it
    leaves the web's round end, and an 8 mm lightening hole through each web beside the
    pin.  The parametric generator makes neither."""
    rw, t, zp, zw = 0.036, 0.014, 0.013, 0.027
    # trapezoid: top corners inside the web's round end, bottom corners far out
    top, bottom, y_top, y_bot = 0.024, 0.05, -0.024, -0.07
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        solid = plain_throw(gmsh, rw=rw)
        cws = []
        for z0 in (-zw, zp):
            pts = [occ.addPoint(x, y, z0) for x, y in ((-top, y_top), (top, y_top), (bottom, y_bot), (-bottom, y_bot))]
            loop = occ.addCurveLoop([occ.addLine(pts[i], pts[(i + 1) % 4]) for i in range(4)])
            face = occ.addPlaneSurface([loop])
            cws.append(next(e for e in occ.extrude([(2, face)], 0, 0, t) if e[0] == 3))
        out, _ = occ.fuse([(3, solid)], cws)
        occ.synchronize()
        solid = out[0][1]
        # the exact junction points: intersections of the sides with the circle (refined)
        junction = []
        for s in (-1.0, 1.0):
            x0, y0, x1, y1 = s * top, y_top, s * bottom, y_bot
            lo, hi = 0.0, 1.0
            for _ in range(80):
                mid = 0.5 * (lo + hi)
                inside = math.hypot(x0 + mid * (x1 - x0), y0 + mid * (y1 - y0)) < rw
                lo, hi = (mid, hi) if inside else (lo, mid)
            junction.append((x0 + lo * (x1 - x0), y0 + lo * (y1 - y0)))
        edges = _lines_along_z(gmsh, junction)
        assert len(edges) == 4, edges
        out = occ.fillet([solid], edges, [0.004], removeVolume=True)
        occ.synchronize()
        solid = out[0][1]
        holes = [(3, occ.addCylinder(s * 0.029, 0.014, -0.05, 0, 0, 0.1, 0.004)) for s in (-1.0, 1.0)]
        out, _ = occ.cut([(3, solid)], holes)
        assert len(out) == 1
        return _write(gmsh, path)


def recessed_throw_step(g: CrankGeometry, path: Path, bore_radius: float = 0.002) -> Path:
    """A throw of ``g`` (whose fillets are recessed into the webs: ``undercut`` > 0) with
    an oblique oil drilling from the bottom of journal 1 through web 1 to the top of the
    crankpin (the parametric generator drills only straight through the pin)."""
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        solid, _ = throw_solid(g)
        zp = g.crankpin_length / 2
        zw = zp + g.web_thickness
        rj, rp, R = g.journal_diameter / 2, g.crankpin_diameter / 2, g.crank_radius
        a = (0.0, -rj, -zw - 0.5 * g.journal_length)  # on journal 1's surface, below the axis
        b = (0.0, R + rp, 0.0)  # the top of the pin at its middle
        d = [b[i] - a[i] for i in range(3)]
        n = math.sqrt(sum(c * c for c in d))
        e = [c / n for c in d]
        start = [a[i] - 0.01 * e[i] for i in range(3)]
        bore = occ.addCylinder(*start, *[(n + 0.02) * c for c in e], bore_radius)
        out, _ = occ.cut([(3, solid)], [(3, bore)])
        assert len(out) == 1
        return _write(gmsh, path)


def turned_step(src: Path, dst: Path, order: tuple[int, int, int]) -> Path:
    """``src`` with every 3D point and direction's coordinates taken in ``order`` (a cyclic
    order such as (2, 0, 1): x' = z, y' = x, z' = y, a rotation that takes the z axis to
    the x axis), written as text: exact to the last digit, as a CAD system that drew the
    shaft along another axis would write it."""
    assert order in ((0, 1, 2), (1, 2, 0), (2, 0, 1))

    def turn(m):
        vals = m.group(2).split(",")
        if len(vals) != 3:  # 2D points of the faces' parameter curves stay as they are
            return m.group(0)
        return f"{m.group(1)}({','.join(vals[i] for i in order)})"

    text = re.sub(r"((?:CARTESIAN_POINT|DIRECTION)\('[^']*',)\(([^()]*)\)", turn, src.read_text())
    dst.write_text(text)
    return dst


def pegged_step(g: CrankGeometry, path: Path, centre=(0.014, 0.025), radius=0.003, length=0.005) -> Path:
    """A throw of ``g`` with a peg (a whole-round cylinder parallel to the crank axis, off
    it, like a crankpin) standing on web 1's outer face: its free end has no web behind."""
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        solid, _ = throw_solid(g)
        zw = g.crankpin_length / 2 + g.web_thickness
        peg = occ.addCylinder(centre[0], centre[1], -zw - length, 0, 0, length, radius)
        out, _ = occ.fuse([(3, solid)], [(3, peg)])
        assert len(out) == 1
        return _write(gmsh, path)


def bolted_sector_step(path: Path, *, r1=0.06, angle=2.7925268031909276) -> Path:
    """``plain_throw`` and, as separate solids, an annular-sector counterweight (the web's
    end radius to ``r1``, 160 deg, as thick as the web) against each web's far side: a
    STEP of three solids, the counterweights touching the shaft."""
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        plain_throw(gmsh)
        for z0 in (-0.027, 0.013):
            _sector(occ, 0.03, r1, angle, z0, 0.014)
        return _write(gmsh, path)


SMALL_ENGINE = """
[engine]
name = "small single"
strokes = 4

[[engine.throws]]
name = "1"
crank_radius = "{radius}"

[[engine.cylinders]]
name = "1"
throw = "1"
bore = "50 mm"
rod_length = "80 mm"
rod_mass = "0.20 kg"
rod_cg_from_big_end = "22 mm"
piston_mass = "0.15 kg"
"""


def cad_loadcase(
    folder: Path,
    step: str,
    *,
    cad: str = 'density = "7850 kg/m^3"',
    radius: str = "20 mm",
    criteria: str = "min_static_safety = 1.5",
    extra: str = "",
    name: str = "case.toml",
) -> Path:
    """A load case in ``folder`` whose geometry is the CAD file ``step`` (relative to the
    folder) read as ``cad`` (the lines of its ``[cad]`` section) says, with the small
    single of ``tests/data/small_pass.toml`` of crank radius ``radius``."""
    text = (
        f'name = "{Path(step).stem} from CAD"\ngeometry = "{step}"\n\n[operating]\nspeed = "3000 rpm"\n'
        f'overspeed = "3600 rpm"\n{SMALL_ENGINE.format(radius=radius)}\n[cad]\n{cad}\n\n'
        f'[material]\nname = "42CrMo4"\n\n[criteria]\n{criteria}\n{extra}'
    )
    path = folder / name
    path.write_text(text)
    return path


def half_disc_throw_step(path: Path, *, rc=0.06, fillet: float | None = None, rw=0.03) -> Path:
    """``plain_throw`` (webs: stadiums of half width ``rw`` from the axis to the pin) with
    a half-disc counterweight of radius ``rc`` about the crank axis on the far side of
    each web, as thick as the web, fused: the forged shape whose counterweight outline is
    the web's outer radius (``rc = R + rw``, the default).  The web's rounded journal end
    lies inside the half disc, so the only arc about the axis the web shows is the
    counterweight's.  ``fillet``: a transition radius on the four re-entrant edges where
    the half disc's flat leaves the web's sides (None: sharp)."""
    t, zp, zw = 0.014, 0.013, 0.027
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        solid = plain_throw(gmsh, rw=rw)
        discs = []
        for z0 in (-zw, zp):
            disc = occ.addCylinder(0, 0, z0, 0, 0, t, rc)
            below = occ.addBox(-2 * rc, -2 * rc, z0, 4 * rc, 2 * rc, t)  # y < 0
            out, _ = occ.intersect([(3, disc)], [(3, below)])
            discs.append(out[0])
        out, _ = occ.fuse([(3, solid)], discs)
        assert len(out) == 1
        occ.synchronize()
        solid = out[0][1]
        if fillet is not None:
            edges = _lines_along_z(gmsh, [(-rw, 0.0), (rw, 0.0)])
            assert len(edges) == 4, edges
            out = occ.fillet([solid], edges, [fillet], removeVolume=True)
            occ.synchronize()
            assert len(out) == 1
        return _write(gmsh, path)


def layout_step(layout, path: Path, *, nose: tuple[float, float] | None = None, flange=None) -> Path:
    """The whole shaft as ``fe_crank.geometry.shaft`` places it, one STEP solid
    (``fe_crank.geometry.step.write_shaft_step``: the owner of the writing)."""
    return write_shaft_step(layout, path, nose=nose, flange=flange)


def bolted_shaft_step(
    layout, path: Path, where, *, r0: float, r1: float, angle: float, holes=(0.005, 0.028), nose=None, flange=None
) -> tuple:
    """The whole shaft of ``layout`` (``write_shaft_step``) and, as separate solids, an
    annular-sector counterweight (``r0`` .. ``r1``, included ``angle``, opposite the pin,
    as thick as the web, against the web's far side) on each (throw index, web) of
    ``where``, each with two axial bolt holes (``holes``: diameter, pitch radius; at
    +-angle/4 from its middle); ``nose``, ``flange`` as ``write_shaft_step``'s.  Returns the path and each body's exact OpenCASCADE mass
    properties (file frame: volume m^3, centroid (x, y, z) m)."""
    g = layout.geometry
    zp, t = g.crankpin_length / 2, g.web_thickness
    found = []

    def bodies(gmsh):
        occ = gmsh.model.occ
        for k, web in where:
            th = layout.throws[k]
            z0 = -zp - t if web == 1 else zp
            body = _sector(occ, r0, r1, angle, z0, t)
            for s in (-1.0, 1.0):
                a = s * angle / 4
                x, y = holes[1] * math.sin(a), -holes[1] * math.cos(a)
                hole = occ.addCylinder(x, y, z0 - 0.001, 0, 0, t + 0.002, holes[0] / 2)
                out, _ = occ.cut([(3, body)], [(3, hole)])
                body = out[0][1]
            occ.rotate([(3, body)], 0, 0, 0, 0, 0, 1, -layout.sense * th.angle)
            occ.translate([(3, body)], 0, 0, th.z)
            occ.synchronize()
            found.append((occ.getMass(3, body), tuple(occ.getCenterOfMass(3, body))))

    return write_shaft_step(layout, path, nose=nose, flange=flange, bodies=bodies), tuple(found)
