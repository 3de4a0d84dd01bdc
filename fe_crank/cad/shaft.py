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
* axial bores (a hollow pin or journal): the widest hole along the pin's (journal's) axis;
* oil bores: concave cylinders (holes) narrower than half the pin (journal) that meet the
  crankpin (a journal of the throw); every face on the same line with the same radius
  within the throw belongs to the bore.

``[cad.faces]`` entries name the faces of a feature outright; they are checked the
same way.  Where no rule decides, an ``InputError`` names the faces and the key.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.cad.axis import Line, line_of
from fe_crank.cad.chains import End, contiguous, cylinder_groups, extent, walk
from fe_crank.cad.config import CadInput
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
    def __init__(self, faces, nbrs, axis: Line, cad: CadInput, tol: float):
        self.faces, self.nbrs, self.axis, self.cad, self.tol = faces, nbrs, axis, cad, tol
        self.shaft = extent(list(faces.values()), axis)

    def fail(self, reason: str, key: str) -> InputError:
        return InputError(f"{reason} (set {key} in {self.cad.where})", file=str(self.cad.file), key=key)

    def given(self, group: str, throw: str | None, kind: str) -> list[Face] | None:
        ov = self.cad.override(group, throw)
        if ov is None:
            return None
        bad = [t for t in ov.faces if t not in self.faces or self.faces[t].kind not in (kind, "other")]
        if bad:
            raise InputError(f"faces {bad} are not {kind} faces of the model", file=str(self.cad.file), key=ov.key)
        return [self.faces[t] for t in ov.faces]


def _pins(ctx: _Ctx) -> list[tuple[list[Face], End, End]]:
    ax, tol = ctx.axis, ctx.tol
    stated = [ov for ov in ctx.cad.faces if ov.group == "crankpin"]
    given = [ctx.given("crankpin", ov.throw, "cylinder") for ov in stated] or None
    if given is not None:
        groups = given
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
    out = []
    for g in groups:
        line = line_of(g[0])
        front = walk(g, -1.0, line, ax, ctx.faces, ctx.nbrs, tol)
        rear = walk(g, +1.0, line, ax, ctx.faces, ctx.nbrs, tol)
        if front.ok and rear.ok:
            out.append((g, front, rear))
        elif given is not None:
            bad = front if not front.ok else rear
            raise ctx.fail(
                f"the crankpin {_ids(g)} does not end on a web face normal to the crank axis at its "
                f"{'front' if bad is front else 'rear'} end (faces there: {sorted(bad.stray) or 'none'})",
                "cad.faces.crankpin_fillet_1" if bad is front else "cad.faces.crankpin_fillet_2",
            )
    if not out:
        raise ctx.fail(
            "no crankpin found: no whole-round cylinder parallel to the crank axis, off it, that ends on web faces "
            "at both ends",
            "cad.faces.crankpin",
        )
    return sorted(out, key=lambda x: extent(x[0], ctx.axis)[0])


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


def _journal(ctx: _Ctx, cands, side: int, web_s: float, name: str, key: str) -> tuple[Journal, End]:
    ax, tol = ctx.axis, ctx.tol
    given = ctx.given(key.rsplit(".", 1)[-1], name, "cylinder") if ctx.cad.faces else None
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
    toward = walk(run, 1.0 if side == 1 else -1.0, ax, ax, ctx.faces, ctx.nbrs, tol)
    if not toward.ok or (toward.s_plane - web_s) * (1 if side == 1 else -1) >= -tol:
        raise ctx.fail(
            f"throw {name}: the main journal {_ids(run)} {where} web {side} does not end on the web's outer face "
            f"(faces there: {sorted(toward.stray) or 'none'})",
            key,
        )
    away = walk(run, -1.0 if side == 1 else 1.0, ax, ax, ctx.faces, ctx.nbrs, tol)
    lo, hi = extent(run, ax)
    far = away.s_plane if away.ok else (lo if side == 1 else hi)
    free = away.ok and abs(far - (ctx.shaft[0] if side == 1 else ctx.shaft[1])) <= tol
    centre = far if free else 0.5 * (far + toward.s_plane)
    return Journal(tuple(run), run[0].radius, lo, hi, centre, free), toward


def _bores(ctx: _Ctx, name: str, near: list[tuple[list[Face], float]], span: tuple[float, float]):
    given = ctx.cad.override("oil_bore", name)
    ax, tol = ctx.axis, ctx.tol
    holes = [f for f in ctx.faces.values() if f.kind == "cylinder" and not f.convex]
    if given is not None:
        groups = cylinder_groups([ctx.faces[t] for t in given.faces if t in ctx.faces], tol)
    else:
        starts = []
        for host, r in near:
            tags = {t for f in host for t in ctx.nbrs[f.tag]}
            starts += [f for f in holes if f.tag in tags and f.radius < r / 2]
        groups = cylinder_groups(starts, tol)
    out = []
    for g in groups:
        line = line_of(g[0])
        members = [
            f
            for f in holes
            if abs(f.radius - g[0].radius) <= tol
            and line_of(f).same(line, tol)
            and span[0] - tol <= extent([f], ax)[0]
            and extent([f], ax)[1] <= span[1] + tol
        ]
        out.append(tuple(sorted(members, key=lambda f: f.tag)))
    return tuple(out)


def _axial_bore(ctx: _Ctx, line: Line, lo: float, hi: float) -> float:
    """Diameter of the widest hole along ``line`` within [lo, hi] (a hollow pin or journal)."""
    ax, tol = ctx.axis, ctx.tol
    found = [
        f.radius
        for f in ctx.faces.values()
        if f.kind == "cylinder"
        and not f.convex
        and line_of(f).same(line, tol)
        and extent([f], ax)[0] < hi - tol
        and extent([f], ax)[1] > lo + tol
    ]
    return 2.0 * max(found, default=0.0)


def find_throws(faces: dict[int, Face], nbrs, axis: Line, cad: CadInput, tol: float) -> tuple[RawThrow, ...]:
    """Every throw of the shaft, front to rear."""
    ctx = _Ctx(faces, nbrs, axis, cad, tol)
    pins = _pins(ctx)
    names = cad.throws if cad.throws is not None else tuple(str(i + 1) for i in range(len(pins)))
    if len(names) != len(pins):
        raise ctx.fail(
            f"{len(pins)} crankpins recognised (faces {', '.join(_ids(p) for p, _, _ in pins)}), but {len(names)} "
            "throw names given",
            "cad.throws",
        )
    cands = _journals(ctx)
    out = []
    for name, (pin, front, rear) in zip(names, pins):
        line = line_of(pin[0])
        d = line.origin - axis.origin
        d = d - (d @ axis.e) * axis.e
        R = float(np.linalg.norm(d))
        j1, e1 = _journal(ctx, cands, 1, front.s_plane, name, "cad.faces.journal_1")
        j2, e2 = _journal(ctx, cands, 2, rear.s_plane, name, "cad.faces.journal_2")
        near = [(list(pin), pin[0].radius), (list(j1.faces), j1.radius), (list(j2.faces), j2.radius)]
        bores = _bores(ctx, name, near, (min(j1.centre, j2.centre), max(j1.centre, j2.centre)))
        hollow = (
            _axial_bore(ctx, axis, j1.lo, j1.hi),
            _axial_bore(ctx, line, *extent(pin, axis)),
            _axial_bore(ctx, axis, j2.lo, j2.hi),
        )
        out.append(
            RawThrow(name, tuple(pin), line, pin[0].radius, R, d / R, (front, rear), (j1, j2), (e1, e2), bores, hollow)
        )
    return tuple(out)
