"""The throws of a crankshaft B-rep, in shaft positions ``s`` along the crank axis.

* crankpins: convex cylinders parallel to the crank axis and off it, whole round (their
  boundary curves sweep the full turn about their axis), ending at both ends -- through
  their fillets -- on planes normal to the axis (the webs' inner faces).  The pin's
  distance from the axis is the crank radius; the pins, front to rear, are the throws;
* main journals: convex whole-round cylinders on the crank axis; a throw's journal on
  each side is the nearest one outside its web, ending through its fillet on the web's
  outer face.  The bearing centre is the journal's middle, between the faces that bound
  it; a journal ending in a free end face of the shaft is half a bearing (fe-crank's
  throw files end so, docs/geometry.md) and its end face is the bearing centre;
* bores (``fe_crank.cad.bores``): oil bores and axial bores.

``[cad.faces]`` entries name the faces of a feature outright; they are checked the
same way.  Where no rule decides, an ``InputError`` names the faces and the key.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.cad.axis import Line, line_of
from fe_crank.cad.bores import axial_bore, oil_bores
from fe_crank.cad.chains import End, contiguous, cylinder_groups, extent, normal_plane, walk
from fe_crank.cad.config import CadInput, FaceOverride
from fe_crank.cad.survey import Face, coverage
from fe_crank.errors import InputError

FULL_TURN = 0.99  # boundary curves sweeping this fraction of a turn: a whole-round cylinder


@dataclass(frozen=True, eq=False)
class Journal:
    faces: tuple[Face, ...]
    radius: float
    lo: float  # extent of its cylindrical faces along the axis
    hi: float
    centre: float  # bearing centre
    free_end: bool


@dataclass(frozen=True, eq=False)
class RawThrow:
    """Internal: one throw recognised in shaft positions."""

    name: str
    pin: tuple[Face, ...]
    pin_line: Line
    pin_radius: float
    crank_radius: float
    u: np.ndarray  # unit vector from the axis towards the pin centre
    ends: tuple[End, End]  # the pin's front and rear ends (fillets, webs' inner faces)
    journals: tuple[Journal, Journal]
    journal_ends: tuple[End, End]  # the journals' ends at the webs (web outer faces)
    bores: tuple[tuple[Face, ...], ...]
    axial_bores: tuple[float, float, float]  # m, diameter of a bore along the journal 1, pin, journal 2 axis (0: none)

    @property
    def mid(self) -> float:
        """Position of the throw frame's origin: midway between the webs' inner faces."""
        return 0.5 * (self.ends[0].s_plane + self.ends[1].s_plane)


def _ids(faces) -> str:
    return "[" + ", ".join(str(f.tag) for f in faces) + "]"


class _Ctx:
    def __init__(self, faces, nbrs, axis: Line, cad: CadInput, tol: float, inside):
        self.faces, self.nbrs, self.axis, self.cad, self.tol = faces, nbrs, axis, cad, tol
        self.inside = inside  # point (file frame) -> is it in the solid
        self.shaft = extent(list(faces.values()), axis)

    def fail(self, reason: str, key: str) -> InputError:
        return InputError(f"{reason} (set {key} in {self.cad.where})", file=str(self.cad.file), key=key)

    def key(self, group: str, throw: str) -> str:
        """The ``[cad.faces]`` key of a throw's group (no throw table in a single-throw file)."""
        many = self.cad.throws is not None and len(self.cad.throws) > 1
        return FaceOverride(group, (), throw if many else None).key

    def end(self, group: str, throw: str, cyl: list[Face], sign: float, line: Line) -> End:
        """The end of ``cyl`` towards ``sign``: the faces ``[cad.faces]`` names as its fillet
        (and the web face they meet), else what ``walk`` finds."""
        ov = self.cad.override(group, throw)
        if ov is None:
            return walk(cyl, sign, line, self.axis, self.faces, self.nbrs, self.tol)
        given = [self.faces[t] for t in ov.faces if t in self.faces]
        if len(given) != len(ov.faces):
            raise InputError("names faces that are not in the model", file=str(self.cad.file), key=ov.key)
        lo, hi = extent(cyl, self.axis)
        tip = lo if sign < 0 else hi
        near = {t for f in given for t in self.nbrs[f.tag]} - {f.tag for f in given + cyl}
        planes = [self.faces[t] for t in sorted(near) if normal_plane(self.faces[t], self.axis)]
        planes = [
            p for p in planes if sign * (float(np.median(p.axial(self.axis.origin, self.axis.e))) - tip) >= -self.tol
        ]
        if not planes:
            raise InputError(
                f"the faces {list(ov.faces)} meet no web face normal to the crank axis",
                file=str(self.cad.file),
                key=ov.key,
            )
        s = [float(np.median(p.axial(self.axis.origin, self.axis.e))) for p in planes]
        s0 = max(s) if sign < 0 else min(s)
        return End(tuple(given), tuple(p for p, v in zip(planes, s) if abs(v - s0) <= self.tol), s0)

    def given(self, group: str, throw: str | None, kind: str) -> list[Face] | None:
        ov = self.cad.override(group, throw)
        if ov is None:
            return None
        bad = [t for t in ov.faces if t not in self.faces or self.faces[t].kind not in (kind, "other")]
        if bad:
            raise InputError(f"faces {bad} are not {kind} faces of the model", file=str(self.cad.file), key=ov.key)
        return [self.faces[t] for t in ov.faces]


def _pins(ctx: _Ctx) -> list[list[Face]]:
    """The crankpins' faces, front to rear: those ``[cad.faces]`` names, else every
    whole-round convex cylinder parallel to the crank axis and off it."""
    ax, tol = ctx.axis, ctx.tol
    stated = [ov for ov in ctx.cad.faces if ov.group == "crankpin"]
    if stated:
        # every stated override names its faces, so ``given`` finds them
        groups = [g for g in (ctx.given("crankpin", ov.throw, "cylinder") for ov in stated) if g is not None]
    else:
        par = [
            f
            for f in ctx.faces.values()
            if f.kind == "cylinder"
            and f.convex
            and np.linalg.norm(np.cross(f.direction, ax.e)) <= 1e-6
            and ax.distance(f.origin)[0] > tol
        ]
        runs = [run for g in cylinder_groups(par, tol) for run in contiguous(g, ax, tol)]
        groups = [g for g in runs if coverage(_runs(g), g[0].origin, g[0].direction) >= FULL_TURN]
    if not groups:
        raise ctx.fail(
            "no crankpin found: no whole-round cylinder parallel to the crank axis and off it", "cad.faces.crankpin"
        )
    return sorted(groups, key=lambda g: extent(g, ax)[0])


def _web_behind(ctx: _Ctx, line: Line, radius: float, s: float) -> bool:
    """Most of 8 points on a circle of half the pin's radius about its axis, at shaft
    position ``s`` (just beyond a web face), lie in the solid (a bore may take some)."""
    foot = line.origin + (s - (line.origin - ctx.axis.origin) @ ctx.axis.e) * ctx.axis.e
    a = np.cross(ctx.axis.e, [1.0, 0.0, 0.0] if abs(ctx.axis.e[0]) < 0.9 else [0.0, 1.0, 0.0])
    a /= np.linalg.norm(a)
    b = np.cross(ctx.axis.e, a)
    ang = np.arange(8) * np.pi / 4
    pts = foot + 0.5 * radius * (np.outer(np.cos(ang), a) + np.outer(np.sin(ang), b))
    return sum(ctx.inside(p) for p in pts) >= 5


def _pin_ends(ctx: _Ctx, name: str, pin: list[Face]) -> tuple[End, End]:
    """The pin's fillets and web faces; a web face must have the web behind it."""
    line = line_of(pin[0])
    ends = []
    for side, sign in ((1, -1.0), (2, 1.0)):
        end = ctx.end(f"crankpin_fillet_{side}", name, pin, sign, line)
        if end.ok and not _web_behind(ctx, line, pin[0].radius, end.s_plane + sign * 1e3 * ctx.tol):
            raise ctx.fail(
                f"throw {name}: the cylinder {_ids(pin)} parallel to the crank axis ends at its "
                f"{'front' if side == 1 else 'rear'} in faces {sorted(p.tag for p in end.planes)} with no web "
                "behind them: it is no crankpin; name the crankpins' faces",
                ctx.key("crankpin", name),
            )
        if not end.ok:
            raise ctx.fail(
                f"throw {name}: the crankpin {_ids(pin)} does not end on a web face normal to the crank axis at its "
                f"{'front' if side == 1 else 'rear'} end (faces there that are neither fillet nor web face: "
                f"{sorted(end.stray) or 'none'}); name its fillet's faces, or name the crankpins' faces "
                f"({ctx.key('crankpin', name)}) if this cylinder is none",
                ctx.key(f"crankpin_fillet_{side}", name),
            )
        ends.append(end)
    return ends[0], ends[1]


def _runs(group):
    return [r for f in group for r in f.edge_runs]


def _journals(ctx: _Ctx) -> list[list[Face]]:
    ax, tol = ctx.axis, ctx.tol
    on = [f for f in ctx.faces.values() if f.kind == "cylinder" and f.convex and line_of(f).same(ax, tol)]
    out = []
    for g in cylinder_groups(on, tol):
        for run in contiguous(g, ax, tol):
            if coverage(_runs(run), ax.origin, ax.e) >= FULL_TURN:
                out.append(run)
    return out


def _journal(ctx: _Ctx, cands, side: int, web_s: float, name: str) -> tuple[Journal, End]:
    ax, tol = ctx.axis, ctx.tol
    key = ctx.key(f"journal_{side}", name)
    given = ctx.given(f"journal_{side}", name, "cylinder")
    if given is not None:
        cands = [given]
    if side == 1:
        pick = [c for c in cands if extent(c, ax)[1] <= web_s + tol]
        run = max(pick, key=lambda c: extent(c, ax)[1]) if pick else None
    else:
        pick = [c for c in cands if extent(c, ax)[0] >= web_s - tol]
        run = min(pick, key=lambda c: extent(c, ax)[0]) if pick else None
    where = "in front of" if side == 1 else "behind"
    if run is None:
        raise ctx.fail(f"throw {name}: no main journal {where} web {side}", key)
    toward = ctx.end(f"journal_fillet_{side}", name, run, 1.0 if side == 1 else -1.0, ax)
    if not toward.ok or (toward.s_plane - web_s) * (1 if side == 1 else -1) >= -tol:
        raise ctx.fail(
            f"throw {name}: the main journal {_ids(run)} {where} web {side} does not end on the web's outer face "
            f"(faces there that are neither fillet nor web face: {sorted(toward.stray) or 'none'}); name its "
            "fillet's faces, or the journal's",
            ctx.key(f"journal_fillet_{side}", name),
        )
    away = walk(run, -1.0 if side == 1 else 1.0, ax, ax, ctx.faces, ctx.nbrs, tol)
    lo, hi = extent(run, ax)
    far = away.s_plane if away.ok else (lo if side == 1 else hi)
    free = away.ok and abs(far - (ctx.shaft[0] if side == 1 else ctx.shaft[1])) <= tol
    centre = far if free else 0.5 * (far + toward.s_plane)
    return Journal(tuple(run), run[0].radius, lo, hi, centre, free), toward


def find_throws(faces: dict[int, Face], nbrs, axis: Line, cad: CadInput, tol: float, inside) -> tuple[RawThrow, ...]:
    """Every throw of the shaft, front to rear; ``inside(p)``: is the point in the solid."""
    ctx = _Ctx(faces, nbrs, axis, cad, tol, inside)
    pins = _pins(ctx)
    names = cad.throws if cad.throws is not None else tuple(str(i + 1) for i in range(len(pins)))
    if len(names) != len(pins):
        raise ctx.fail(
            f"{len(pins)} crankpins recognised (faces {', '.join(_ids(p) for p in pins)}), but {len(names)} "
            "throw names given",
            "cad.throws",
        )
    cands = _journals(ctx)
    out = []
    for name, pin in zip(names, pins):
        front, rear = _pin_ends(ctx, name, pin)
        line = line_of(pin[0])
        d = line.origin - axis.origin
        d = d - (d @ axis.e) * axis.e
        R = float(np.linalg.norm(d))
        j1, e1 = _journal(ctx, cands, 1, front.s_plane, name)
        j2, e2 = _journal(ctx, cands, 2, rear.s_plane, name)
        near = [(list(pin), pin[0].radius), (list(j1.faces), j1.radius), (list(j2.faces), j2.radius)]
        bores = oil_bores(ctx, name, near, (min(j1.centre, j2.centre), max(j1.centre, j2.centre)))
        hollow = (
            axial_bore(ctx, axis, j1.lo, j1.hi),
            axial_bore(ctx, line, *extent(pin, axis)),
            axial_bore(ctx, axis, j2.lo, j2.hi),
        )
        out.append(
            RawThrow(name, tuple(pin), line, pin[0].radius, R, d / R, (front, rear), (j1, j2), (e1, e2), bores, hollow)
        )
    return tuple(out)
