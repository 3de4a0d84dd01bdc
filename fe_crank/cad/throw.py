"""One recognised throw in its THROW frame: features, named parts and mass properties.

* webs: inner and outer faces from the pin's and journals' ends; the width B measured
  across the web's mid-plane at the middle of the pin/journal overlap (UR M53 3.1:
  ``y = ((R - D/2) + D_G/2) / 2``), from the outermost points of the solid on each side;
  the side radius at ``y = 0+``, where a counterweight (the material beyond it on the
  far side of the axis) begins (``[cad] counterweight_radius`` overrides it);
* counterweight fillets: the concave curved faces (centre of curvature outside the
  material) wholly in a counterweight's region, other than bores, holes and surfaces
  about the crank or pin axis;
* a counterweight's offset: the direction of its exact m r, turned from ``-y`` towards
  ``+x`` (``counterweight_offset``); one whose outer face reaches over ``y = 0`` towards
  its pin is recognised by its own sector (``_sector``: its flanks and their transition
  fillets bound its region in place of ``y = 0``);
* the named parts (``fe_crank.cad.model``) and their mass properties
  (``fe_crank.geometry.mass``: exact B-rep integrals).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Callable

import numpy as np

from fe_crank.cad.axis import Line, line_of
from fe_crank.cad.chains import End, extent
from fe_crank.cad.config import CadInput
from fe_crank.cad.features import Arc, Bearing, Counterweight, Cylinder, Fillet, OilBore, ThrowFeatures, Web
from fe_crank.cad.frame import Frame, chord, turn_angle
from fe_crank.cad.model import Built, EndSlab, Plan, build_throw, throw_mass
from fe_crank.cad.shaft import RawThrow
from fe_crank.cad.survey import Face, coverage
from fe_crank.errors import InputError


def _t(v) -> tuple[float, float, float]:
    x, y, z = (float(c) for c in np.ravel(v))
    return (x, y, z)


def _fillet(name: str, end: End, frame: Frame, mid: float, axis: Line, sign: float, tol: float) -> Fillet | None:
    if not end.fillet:
        return None
    arcs = tuple(
        Arc(f.tag, float(f.minor), float(f.radius), float(frame.to_throw(f.origin)[0][2]))
        for f in end.fillet
        if f.kind == "torus"
    )
    return Fillet(
        name,
        tuple(sorted(f.tag for f in end.fillet)),
        float(end.radius()),
        arcs,
        float(end.s_plane - mid),
        end.undercut(axis, sign, tol),
        float(sum(f.area for f in end.fillet)),
    )


def _side_radius(
    gmsh, shaft, frame, faces, axis, z_mid, s_web, reach, R, r_journal, z_range, lines, used, tol
) -> tuple[float, bool]:
    """Where a counterweight begins on a web, and whether its region reaches over its
    transition fillets above ``y = 0``.

    The radius of the web's rounded journal end: the smallest arc about the crank axis
    among the web's faces (beyond the journal) within the web's half width at ``y = 0+``.
    An arc wider than that bounds a counterweight (a half disc about the axis, whatever
    its radius against the web's), not the web; when the web shows no other, its own
    sides run down to the counterweight, which begins at the web's half width just
    above its transition fillets (the concave faces of the far side rising above
    ``y = 0``) and is bounded by ``y = 0`` (its fillets stay with the web: a region
    reaching over them would cut a sliver off the web's straight sides)."""
    lo, hi = s_web
    arcs = [
        f.radius
        for f in faces.values()
        if f.kind == "cylinder"
        and f.convex
        and f.radius > r_journal + tol
        and line_of(f).same(axis, tol)
        and lo - tol <= extent([f], axis)[0]
        and extent([f], axis)[1] <= hi + tol
        and coverage(f.edge_runs, f.origin, f.direction) < 0.99
    ]
    d = 1e-3 * R
    lo_x, hi_x, _ = chord(gmsh, shaft, frame, d, z_mid, reach)
    half = min(-lo_x, hi_x)
    within = [a for a in arcs if a <= half + tol]
    if within:
        return float(min(within)), True
    if not arcs:
        return float(math.hypot(half, d)), True
    # only counterweight outlines: the web's half width above the transition fillets
    rising = _cw_fillets(faces, frame, r_journal + tol, z_range, lines, used, tol)
    top = max([0.0] + [float(frame.to_throw(np.vstack([f.points, f.edge_points]))[:, 1].max()) for f in rising])
    if top > 0.0:
        lo_x, hi_x, _ = chord(gmsh, shaft, frame, top + d, z_mid, reach)
        half = min(-lo_x, hi_x)
    return float(half), False


def _over(gmsh, shaft, frame: Frame, cw: Counterweight, top: float, reach: float, R: float) -> tuple[float, float]:
    """How far the solid reaches along ``-x`` and ``+x`` (m) on the line ``1e-3 R`` above
    ``top`` (the counterweight region's boundary or its transition fillets, whichever is
    higher) through the counterweight's centroid's z (``counterweight_offset``)."""
    lo, hi, _ = chord(gmsh, shaft, frame, top + 1e-3 * R, cw.mass.centroid[2], reach)
    return float(-lo), float(hi)


def _top(frame: Frame, faces: list[Face], base: float) -> float:
    """The highest ``y`` (throw frame) of ``faces`` and ``base``."""
    return max([base] + [float(frame.to_throw(np.vstack([f.points, f.edge_points]))[:, 1].max()) for f in faces])


def _cw_fillets(faces, frame, radius, z_range, lines, used, tol) -> list[Face]:
    out = []
    for f in faces.values():
        if f.tag in used or f.kind == "plane" or f.convex:
            continue
        if f.kind in ("cylinder", "torus") and any(line_of(f).same(ln, tol) for ln in lines):
            continue
        if f.kind == "cylinder" and coverage(f.edge_runs, f.origin, f.direction) >= 0.99:
            continue  # a hole
        q = frame.to_throw(np.vstack([f.points, f.edge_points]))
        r = np.hypot(q[:, 0], q[:, 1])
        if (
            np.min(q[:, 1]) <= tol
            and np.all(r >= radius - tol)
            and np.all((q[:, 2] >= z_range[0] - tol) & (q[:, 2] <= z_range[1] + tol))
        ):
            out.append(f)
    return out


def _dir(phi: float) -> np.ndarray:
    """The unit vector at ``phi`` (rad) from ``-y`` towards ``+x`` (throw frame, x and y)."""
    return np.array([math.sin(phi), -math.cos(phi)])


def _flank_notch(faces, frame, phi, r, zs, pin_r, used, throw, web, side, file, tol):
    """The flank of a counterweight's sector at ``phi`` (beyond ``y = 0``) and the outline
    of its transition fillet there: ``(corners, fillet faces)``, the corners from the
    flank's corner with the web's side ``P``, the fillet's tangent point on the web's side
    ``B`` and on the flank ``A`` (an empty tuple for a sharp corner).  The fillet's material
    lies in the triangle ``P B A`` (a rolling-ball fillet of a re-entrant corner between
    two faces along the crank axis: a circular arc tangent to both, bulging towards ``P``;
    ``P`` the meeting point of its tangents at ``A`` and ``B``)."""
    d = _dir(phi)
    n2 = np.array([-d[1], d[0]])  # the flank line's normal

    def refuse(why: str) -> InputError:
        return InputError(
            f"throw {throw}: counterweight_{web} reaches over y = 0 towards its pin on its {side} side and {why}; "
            "a drawn counterweight turned over y = 0 is recognised by its own sector (a flank along a plane through "
            "the crank axis, leaving the web's straight side below the crankpin's centre, clear of the crankpin, "
            "through a sharp corner or a fillet along the crank axis); model it as a parametric geometry with "
            "counterweight.offset (docs/geometry.md)",
            file=file,
            key="cad.file",
        )

    def below_pin(corner: np.ndarray) -> None:
        if corner[1] >= pin_r:
            raise refuse(
                f"its flank meets the web's side {corner[1] * 1e3:.4g} mm from the crank axis towards the pin, "
                f"beyond the crankpin's centre ({pin_r * 1e3:.4g} mm: where the web's side turns round the pin)"
            )

    def inside(q: np.ndarray) -> bool:
        return bool(np.all((q[:, 2] >= zs[0] - tol) & (q[:, 2] <= zs[1] + tol)))

    def on_flank(q: np.ndarray) -> np.ndarray:
        return (np.abs(q[:, :2] @ n2) <= tol) & (q[:, :2] @ d > r)

    flank = [
        f
        for f in faces.values()
        if f.kind == "plane"
        and abs(frame.direction(f.direction)[2]) <= 1e-9
        and inside(q := frame.to_throw(np.vstack([f.points, f.edge_points])))
        and np.all(on_flank(q))
    ]
    if not flank:
        raise refuse(f"its outer face ends {math.degrees(abs(phi)):.4g} deg from -y on no plane through the crank axis")
    fil = []
    for f in faces.values():
        if f.tag in used or f.convex or f.kind == "plane":
            continue
        q = frame.to_throw(np.vstack([f.points, f.edge_points]))
        if not inside(q) or not np.any(on_flank(frame.to_throw(f.edge_points))):
            continue
        if f.kind != "cylinder" or abs(abs(frame.direction(f.direction)[2]) - 1.0) > 1e-9:
            raise refuse(f"its transition fillet there (face {f.tag}) is no cylinder along the crank axis")
        fil.append(f)
    if not fil:  # a sharp corner: the flank face begins where it leaves the web
        q = frame.to_throw(np.vstack([f.edge_points for f in flank]))
        below_pin(q[int(np.argmin(q[:, :2] @ d)), :2])
        return (), []
    c = frame.to_throw(fil[0].origin)[0][:2]
    rf = float(fil[0].radius)
    if any(np.linalg.norm(frame.to_throw(f.origin)[0][:2] - c) > tol or abs(f.radius - rf) > tol for f in fil):
        raise refuse(f"its transition fillet there (faces {sorted(f.tag for f in fil)}) is not one cylinder")
    a = (c @ d) * d  # the fillet's tangent point on the flank line
    ua = (a - c) / np.linalg.norm(a - c)
    u = frame.to_throw(np.vstack([f.edge_points for f in fil]))[:, :2] - c
    ub = u[int(np.argmin(u @ ua))]
    ub = ub / np.linalg.norm(ub)
    if 1.0 + ua @ ub <= 1e-6:
        raise refuse("its transition fillet there turns through half a turn")
    b = c + rf * ub
    corner = c + rf * (ua + ub) / (1.0 + ua @ ub)
    if np.linalg.norm(corner) <= r + tol or np.linalg.norm(b) <= r + tol:
        raise refuse("its transition fillet there meets the web on its rounded journal end, not on a straight side")
    below_pin(corner)
    pts = tuple((float(p[0]), float(p[1])) for p in (corner, b, c + rf * ua))
    return pts, fil


def _sector(faces, frame, axis, s_web, zs, r, r_side, t, used, throw, web, file, tol):
    """A counterweight recognised by its own sector, where its outer face (cylinders about
    the crank axis beyond ``r`` in the web's slab) reaches over ``y = 0`` towards its pin:
    ``(outline, fillet faces)``, the outline of its region in the throw frame's x, y (cut
    by the cylinder ``r`` in ``cad.model``): from its flank's angle ``phi_1`` (from ``-y``
    towards ``+x``; beyond 90 deg, with its transition fillet's outline) round the far
    side to ``phi_0`` (the same on the other side; where a flank stays on ``y <= 0`` the
    region is bounded by ``y = 0`` there, as the half plane of an unturned one is).  None:
    the outer face stays on the far side of ``y = 0`` (the half plane holds it whole).
    Outer faces are looked for beyond the web's side radius ``r_side`` too (a
    ``counterweight_radius`` inside it would take the web's rounded end for one)."""
    lo, hi = s_web
    outer = [
        f
        for f in faces.values()
        if f.kind == "cylinder"
        and f.convex
        and f.radius > max(r, r_side) + tol
        and line_of(f).same(axis, tol)
        and lo - tol <= extent([f], axis)[0]
        and extent([f], axis)[1] <= hi + tol
        and coverage(f.edge_runs, f.origin, f.direction) < 0.99
    ]
    if not outer:
        return None
    q = frame.to_throw(np.vstack([np.vstack([f.points, f.edge_points]) for f in outer]))
    if not np.any(q[:, 1] > tol):
        return None
    phi = np.arctan2(q[:, 0], -q[:, 1])
    p0, p1 = float(phi.min()), float(phi.max())
    # the crankpin and its fillets must stay clear of the region
    pin = list(t.pin) + [f for e in t.ends for f in e.fillet]
    pq = frame.to_throw(np.vstack([np.vstack([f.points, f.edge_points]) for f in pin]))
    pp = np.arctan2(pq[:, 0], -pq[:, 1])
    hit = (np.hypot(pq[:, 0], pq[:, 1]) > r + tol) & (pp >= min(p0, -math.pi / 2)) & (pp <= max(p1, math.pi / 2))
    if np.any(hit) or p1 - p0 >= 2 * math.pi - 1e-6:
        side = "+x" if p1 > -p0 else "-x"
        raise InputError(
            f"throw {throw}: counterweight_{web} reaches over y = 0 towards its pin on its {side} side (its outer "
            f"face from {math.degrees(p0):.4g} to {math.degrees(p1):.4g} deg from -y towards +x) and its sector "
            "beyond the web's side radius overlaps the crankpin or its fillets: no drawn counterweight is "
            "recognised there; model it as a parametric geometry with counterweight.offset (docs/geometry.md)",
            file=file,
            key="cad.file",
        )
    pin_r = float(t.crank_radius)
    fillets: list[Face] = []
    hi_pts: tuple = ()
    lo_pts: tuple = ()
    if p1 > math.pi / 2 and np.any(q[:, 0] > 0) and np.any(q[(q[:, 0] > 0), 1] > tol):
        hi_pts, f1 = _flank_notch(faces, frame, p1, r, zs, pin_r, used, throw, web, "+x", file, tol)
        fillets += f1
    else:
        p1 = math.pi / 2
    if p0 < -math.pi / 2 and np.any(q[(q[:, 0] < 0), 1] > tol):
        pts, f0 = _flank_notch(faces, frame, p0, r, zs, pin_r, used, throw, web, "-x", file, tol)
        lo_pts = tuple(reversed(pts))
        fillets += f0
    else:
        p0 = -math.pi / 2
    steps = max(2, math.ceil((p1 - p0) / (math.pi / 4)))
    far = [BIG_OUTLINE * _dir(p1 - k * (p1 - p0) / steps) for k in range(steps + 1)]
    outline = ((0.0, 0.0), *hi_pts, *((float(v[0]), float(v[1])) for v in far), *lo_pts)
    return outline, fillets


#: m: the far corners of a counterweight's sector outline (``_sector``), beyond any crank
BIG_OUTLINE = 10.0


#: deg: a recognised counterweight whose m r points farther than this from opposite its pin is
#: turned (``counterweight_offset``): it must then lie wholly on the far side of the boundary
#: of the region it is recognised in
CW_TURN_TOL_DEG = 1.0

#: rad: a recognised counterweight's offset below this is taken as round-off of the B-rep
#: integrals and of the recognised frame (a counterweight drawn symmetric about the crank
#: plane shows about 1e-12): recorded as 0
OFFSET_ROUNDOFF = 1e-6


def counterweight_offset(
    cw: Counterweight, throw: str, cad: CadInput, over: Callable[[], tuple[float, float]] | None
) -> float:
    """The angle (rad, from ``-y`` towards ``+x``) of a recognised counterweight's m r: the
    offset of the parametric ``counterweight.offset``, ``Counterweight.offset``.

    The recognition takes a counterweight as the material beyond its radius on the far
    side of ``y = 0`` (lifted over its transition fillets where they rise above it): a
    region centred opposite the pin, which holds a turned counterweight whole as long as
    it stays on that side (an annular sector of angle ``a`` turned by ``d`` with
    ``|d| + a/2`` up to 90 deg).  There the web has no material beyond the counterweight's
    radius, so the region is the one centred on the counterweight's own m r; its exact
    mass properties are the drawn counterweight's and their m r gives the offset.

    ``over()``: how far the solid reaches along ``-x`` and ``+x`` (m) on the line just above
    the region's boundary and the counterweight's transition fillets, through its centroid
    (``cad.frame.chord``).  A counterweight turned more than ``CW_TURN_TOL_DEG`` whose one
    side reaches farther there than the other (material of it beyond the web's side, above
    the boundary) would be taken in part and its rest left to the web: refused.
    ``over`` None: the region is the counterweight's own sector (``_sector``), which holds
    it whole by construction; the offset is the direction of its m r."""
    ux, uy = cw.mass.unbalance_vector
    if not cw.mass.mass > 0.0 or math.hypot(ux, uy) == 0.0:
        return 0.0
    turn = math.atan2(ux, -uy)
    if abs(turn) <= OFFSET_ROUNDOFF:
        return 0.0
    if abs(math.degrees(turn)) <= CW_TURN_TOL_DEG or over is None:
        return float(turn)
    left, right = over()
    if abs(right - left) > 1e-6 * max(left, right):
        side, far, near = ("+x", right, left) if right > left else ("-x", left, right)
        raise InputError(
            f"throw {throw}: counterweight_{cw.web} is turned from opposite its pin (the m r of its part on the far "
            f"side of y = 0 points {abs(math.degrees(turn)):.3g} deg from -y) and reaches over y = 0 towards its pin "
            f"on its {side} side (the solid reaches {far * 1e3:.4g} mm along {side} just above y = 0 and its "
            f"transition fillets, {near * 1e3:.4g} mm on the other side): a drawn counterweight is recognised as "
            "the material beyond its radius on the far side of y = 0 from its pin, and one turned over that line "
            "(or drawn asymmetric across it) would be taken in part; model it as a parametric geometry with "
            "counterweight.offset (docs/geometry.md)",
            file=str(cad.file),
            key="cad.file",
        )
    return float(turn)


#: the journal redrawn at a bearing centre (``cad.model.redraw_ends``) over this fraction
#: of its cylinder's length from the centre towards the web (``cad.whole.SLAB`` checks it)
SLAB_FRACTION = 0.25


def end_slabs(t: RawThrow) -> tuple[EndSlab, EndSlab]:
    """The round bars at the throw's bearing centres that ``cad.model.redraw_ends`` redraws."""
    j1, j2 = t.journals
    return (
        EndSlab(j1.radius, SLAB_FRACTION * (j1.hi - j1.centre)),
        EndSlab(j2.radius, SLAB_FRACTION * (j2.centre - j2.lo)),
    )


def throw_features(
    gmsh,
    shaft,
    faces,
    nbrs,
    axis: Line,
    raws: tuple[RawThrow, ...],
    index: int,
    cad: CadInput,
    tol,
    *,
    joinable: bool = False,
):
    """``(ThrowFeatures, Built, Plan, Frame)`` of throw ``index``; builds its parts in the
    current model (the caller removes the shaft before meshing them); ``joinable``: with
    its journal redrawn at both bearing centres (``end_slabs``), for the whole shaft."""
    t = raws[index]
    mid = t.mid
    frame = Frame.of(axis.origin, axis.e, t.u, mid)
    z = {
        k: v - mid
        for k, v in dict(
            zo1=t.journal_ends[0].s_plane,
            zi1=t.ends[0].s_plane,
            zi2=t.ends[1].s_plane,
            zo2=t.journal_ends[1].s_plane,
            b1=t.journals[0].centre,
            b2=t.journals[1].centre,
        ).items()
    }
    x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(3, shaft)
    reach = float(np.linalg.norm([x1 - x0, y1 - y0, z1 - z0]))
    groups: dict[int, str] = {}
    for f in t.pin:
        groups[f.tag] = "crankpin"
    for k in (0, 1):
        for f in t.journals[k].faces:
            groups[f.tag] = f"journal_{k + 1}"
        for f in t.ends[k].fillet:
            groups[f.tag] = f"crankpin_fillet_{k + 1}"
        for f in t.journal_ends[k].fillet:
            groups[f.tag] = f"journal_fillet_{k + 1}"
    for bore in t.bores:
        for f in bore:
            groups[f.tag] = "oil_bore"
    lines = [axis, t.pin_line]
    zranges = ((z["b1"], 0.0), (0.0, z["b2"]))
    webs, side_r, reach_over, slabs = [], [], [], []
    for k, (zo, zi) in enumerate(((z["zo1"], z["zi1"]), (z["zo2"], z["zi2"])), start=1):
        zm = 0.5 * (zo + zi)
        rj = t.journals[k - 1].radius
        y_mid = 0.5 * ((t.crank_radius - t.pin_radius) + rj)
        lo_x, hi_x, solid_width = chord(gmsh, shaft, frame, y_mid, zm, reach)
        width = hi_x - lo_x
        s_web = sorted((zo + mid, zi + mid))
        slabs.append(s_web)
        r_side, over = _side_radius(
            gmsh,
            shaft,
            frame,
            faces,
            axis,
            zm,
            s_web,
            reach,
            t.crank_radius,
            rj,
            zranges[k - 1],
            lines,
            set(groups),
            tol,
        )
        side_r.append(r_side)
        reach_over.append(over or cad.counterweight_radius is not None)
        webs.append(
            Web(
                k,
                tuple(sorted(f.tag for f in t.ends[k - 1].planes)),
                tuple(sorted(f.tag for f in t.journal_ends[k - 1].planes)),
                float(zi),
                float(zo),
                float(abs(zi - zo)),
                float(width),
                r_side,
                float(solid_width),
            )
        )
    cw_r = (cad.counterweight_radius,) * 2 if cad.counterweight_radius is not None else tuple(side_r)
    cw_faces, cw_top = {}, []
    outlines: list[tuple[tuple[float, float], ...] | None] = []
    for k, zr in ((1, zranges[0]), (2, zranges[1])):
        zs = (webs[k - 1].z_outer, webs[k - 1].z_inner)
        sector = _sector(
            faces,
            frame,
            axis,
            slabs[k - 1],
            sorted(zs),
            cw_r[k - 1],
            side_r[k - 1],
            t,
            set(groups),
            t.name,
            k,
            str(cad.file),
            tol,
        )
        cw_faces[k] = _cw_fillets(faces, frame, cw_r[k - 1], zr, lines, set(groups), tol)
        # the counterweight's region reaches over its fillets where they rise above y = 0
        ys = [float(frame.to_throw(np.vstack([f.points, f.edge_points]))[:, 1].max()) for f in cw_faces[k]]
        if sector is None:
            outlines.append(None)
            cw_top.append(max([0.0] + ys) if reach_over[k - 1] else 0.0)
        else:
            outline, notch = sector
            mine = {f.tag for f in notch}
            rising = [f.tag for f, y in zip(cw_faces[k], ys, strict=True) if y > tol and f.tag not in mine]
            if rising:
                raise InputError(
                    f"throw {t.name}: counterweight_{k} reaches over y = 0 towards its pin and its transition fillets "
                    f"{rising} on its other flank rise above y = 0: its region would cut them; model it as a "
                    "parametric geometry with counterweight.offset (docs/geometry.md)",
                    file=str(cad.file),
                    key="cad.file",
                )
            cw_faces[k] = sorted([f for f in cw_faces[k] if f.tag not in mine] + notch, key=lambda f: f.tag)
            outlines.append(outline)
            cw_top.append(0.0)
        for f in cw_faces[k]:
            groups[f.tag] = f"counterweight_fillet_{k}"
    plan = Plan(
        t.name,
        mid,
        (t.journals[0].centre, t.journals[1].centre),
        (t.journals[0].free_end, t.journals[1].free_end),
        (t.journal_ends[0].s_plane, t.ends[0].s_plane, t.ends[1].s_plane, t.journal_ends[1].s_plane),
        (cw_r[0], cw_r[1]),
        (cw_top[0], cw_top[1]),
        groups,
        (outlines[0], outlines[1]),
    )
    built = build_throw(gmsh, shaft, frame, axis.origin, plan, tol, str(cad.file), end_slabs(t) if joinable else None)
    _check_groups(built, groups, cad, t.name)
    mass = throw_mass(gmsh, built.volumes, cad.density, frame, t.name)
    cws = tuple(
        Counterweight(
            k,
            float(cw_r[k - 1]),
            tuple(sorted(f.tag for f in cw_faces[k])),
            float(min(f.min_radius for f in cw_faces[k])) if cw_faces[k] else None,
            mass.parts[f"counterweight_{k}"],
            float(sum(f.area for f in cw_faces[k])),
        )
        for k in (1, 2)
        if f"counterweight_{k}" in built.volumes
    )
    cws = tuple(
        dataclasses.replace(
            cw,
            offset=counterweight_offset(
                cw,
                t.name,
                cad,
                None
                if outlines[cw.web - 1] is not None
                else functools.partial(
                    _over,
                    gmsh,
                    shaft,
                    frame,
                    cw,
                    _top(frame, cw_faces[cw.web], cw_top[cw.web - 1]),
                    reach,
                    t.crank_radius,
                ),
            ),
        )
        for cw in cws
    )
    fillets = tuple(
        f
        for f in (
            _fillet("crankpin_fillet_1", t.ends[0], frame, mid, axis, -1.0, tol),
            _fillet("crankpin_fillet_2", t.ends[1], frame, mid, axis, 1.0, tol),
            _fillet("journal_fillet_1", t.journal_ends[0], frame, mid, axis, 1.0, tol),
            _fillet("journal_fillet_2", t.journal_ends[1], frame, mid, axis, -1.0, tol),
        )
        if f is not None
    )
    first = Frame.of(axis.origin, axis.e, raws[0].u, mid)
    angle = turn_angle(math.atan2(float(t.u @ first.rotation[0]), float(t.u @ first.rotation[1])))
    feats = ThrowFeatures(
        name=t.name,
        index=index,
        angle=float(angle),
        crank_radius=float(t.crank_radius),
        origin=_t(frame.origin),
        rotation=(_t(frame.rotation[0]), _t(frame.rotation[1]), _t(frame.rotation[2])),
        crankpin=_cylinder("crankpin", t.pin, t.pin_radius, axis, mid, t.axial_bores[1]),
        journals=(
            _cylinder("journal_1", t.journals[0].faces, t.journals[0].radius, axis, mid, t.axial_bores[0]),
            _cylinder("journal_2", t.journals[1].faces, t.journals[1].radius, axis, mid, t.axial_bores[2]),
        ),
        fillets=fillets,
        oil_bores=tuple(_bore(b, frame, t, nbrs) for b in t.bores),
        webs=(webs[0], webs[1]),
        bearings=(
            Bearing(1, float(z["b1"]), t.journals[0].free_end),
            Bearing(2, float(z["b2"]), t.journals[1].free_end),
        ),
        counterweights=cws,
        mass=mass,
    )
    return feats, built, plan, frame


def _cylinder(name, faces, radius, axis, mid, bore) -> Cylinder:
    lo, hi = extent(faces, axis)
    tags = tuple(sorted(f.tag for f in faces))
    return Cylinder(name, tags, float(2 * radius), float(lo - mid), float(hi - mid), float(bore))


def _bore(bore: tuple[Face, ...], frame: Frame, t: RawThrow, nbrs) -> OilBore:
    d = frame.direction(bore[0].direction)
    p = frame.to_throw(bore[0].origin)[0]
    # the point of the bore's axis nearest the crankpin's axis (x = 0, y = R, along z)
    a = np.array([0.0, t.crank_radius, 0.0])
    ez = np.array([0.0, 0.0, 1.0])
    n = np.cross(d, ez)
    if np.linalg.norm(n) > 1e-9:
        s = np.cross(a - p, ez) @ n / (n @ n)
        p = p + s * d
    near = {g for f in bore for g in nbrs[f.tag]}
    on = []
    for name, hosts in (("crankpin", t.pin), ("journal_1", t.journals[0].faces), ("journal_2", t.journals[1].faces)):
        if near & {f.tag for f in hosts}:
            on.append(name)
    angle = turn_angle(math.atan2(float(d[0]), float(d[1])), math.pi)
    return OilBore(tuple(f.tag for f in bore), float(2 * bore[0].radius), tuple(on), _t(p), _t(d), float(angle))


def _check_groups(built: Built, groups: dict[int, str], cad: CadInput, name: str) -> None:
    for group in sorted(set(groups.values())):
        if not built.surfaces.get(group):
            faces = sorted(t for t, g in groups.items() if g == group)
            raise InputError(
                f"throw {name}: the faces {faces} recognised as {group} were not found again in the throw model "
                "between its bearing centres",
                file=str(cad.file),
                key=f"cad.faces.{group}",
            )
